//! The parametric trends of thesis 2.7.3 and 2.7.4, run as a user runs them
//! (`hyst fe --set`): on the 400 mm square column TP-92 at 50 mm elements,
//! low axial compression raises the cracking torque much and the peak torque
//! a little (Fig. 2.3; the tests TP-91 and TP-92 of Table 2.1, 0 and 1 MPa:
//! cracking +26%, ultimate +10%), and more transverse steel raises the peak
//! torque (Figs 2.4, 2.5).

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok};
use serde_json::Value;
use std::path::Path;

/// Cracking and peak torque (kN m) of TP-92 at 50 mm elements with the
/// file's values `sets` replaced.
fn run(sets: &[&str]) -> (f64, f64) {
    let specimen = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-92.toml");
    let mut args = vec![
        "fe",
        specimen.to_str().unwrap(),
        "--element-size",
        "50",
        "--threads",
        "1",
        "--json",
    ];
    for s in sets {
        args.extend(["--set", s]);
    }
    let o = ok(hyst(&args));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    for (s, (key, value)) in sets.iter().zip(v["overrides"].as_object().unwrap()) {
        assert_eq!(*s, format!("{key}={}", value.as_str().unwrap()));
    }
    let field = |k: &str| v[k].as_f64().unwrap_or_else(|| panic!("no {k} in {v}"));
    (field("cracking_torque"), field("max_torque"))
}

#[test]
fn low_axial_compression_raises_cracking_torque_much_and_peak_a_little() {
    let runs: Vec<(f64, (f64, f64))> = [0.0, 160.0, 320.0]
        .into_iter()
        .map(|n| (n, run(&[&format!("loading.axial_force_kn={n}")])))
        .collect();
    for w in runs.windows(2) {
        let ((n0, (cr0, pk0)), (n1, (cr1, pk1))) = (w[0], w[1]);
        let (rise_cr, rise_pk) = (cr1 / cr0 - 1.0, pk1 / pk0 - 1.0);
        eprintln!(
            "axial {n0} -> {n1} kN: cracking {cr0:.1} -> {cr1:.1} kN m ({:+.1}%), peak {pk0:.1} -> {pk1:.1} ({:+.1}%)",
            100.0 * rise_cr,
            100.0 * rise_pk
        );
        assert!(
            rise_cr > 0.0 && rise_pk > 0.0,
            "compression must raise both"
        );
        assert!(
            rise_cr > rise_pk,
            "the cracking torque must rise more than the peak"
        );
    }
}

#[test]
fn more_transverse_steel_raises_the_peak_torque() {
    // Hoop spacing 94, 47 (Table 1.1's 0.79%) and 31.3 mm: 0.40%, 0.79%, 1.19%.
    let peaks: Vec<(f64, f64)> = [94.0, 47.0, 31.3]
        .into_iter()
        .map(|s| (s, run(&[&format!("transverse.spacing_mm={s}")]).1))
        .collect();
    eprintln!("hoop spacing (mm), peak torque (kN m): {peaks:?}");
    for w in peaks.windows(2) {
        assert!(
            w[1].1 > w[0].1,
            "peak torque must rise with the transverse steel: {peaks:?}"
        );
    }
}
