//! The parametric trends of thesis 2.7.3 and 2.7.4, run as a user runs them
//! (`hyst fe --set`) on the 400 mm square column TP-92 at 50 mm elements:
//! low axial compression raises both the cracking and the peak torque
//! (Fig. 2.3), and more transverse steel raises the peak torque (Figs 2.4,
//! 2.5). The same directions hold at the 25 mm of the specimen files
//! (docs/fe.md, "Parametric runs"). The thesis's contrast, cracking raised
//! much and the peak a little (tests TP-91 and TP-92, 0 and 1 MPa: +26% and
//! +10%), is not asserted: the model does not reproduce it (25 mm: +10% and
//! +12.5%), and is documented as such.

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
fn low_axial_compression_raises_cracking_and_peak_torque() {
    let runs: Vec<(f64, (f64, f64))> = [0.0, 160.0, 320.0]
        .into_iter()
        .map(|n| (n, run(&[&format!("loading.axial_force_kn={n}")])))
        .collect();
    for w in runs.windows(2) {
        let ((n0, (cr0, pk0)), (n1, (cr1, pk1))) = (w[0], w[1]);
        eprintln!(
            "axial {n0} -> {n1} kN: cracking {cr0:.1} -> {cr1:.1} kN m ({:+.1}%), peak {pk0:.1} -> {pk1:.1} ({:+.1}%)",
            100.0 * (cr1 / cr0 - 1.0),
            100.0 * (pk1 / pk0 - 1.0)
        );
        assert!(cr1 > cr0, "compression must raise the cracking torque");
        assert!(pk1 > pk0, "compression must raise the peak torque");
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
