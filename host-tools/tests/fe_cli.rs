//! `hyst fe` as a user runs it: a coarse, short damaged-plasticity run of
//! TP-91 whose `--backbone` file `hyst simulate --model phm-torsion` reads,
//! the section, rebar and VTK outputs of that run, and the refusal of an
//! elastic run's curve as a primary curve.

#[path = "support/cli.rs"]
mod cli;

use cli::{err, hyst, ok, tmp};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A fresh folder `name` in the scratch folder.
fn dir(name: &str) -> PathBuf {
    let d = tmp(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn specimen(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../specimens")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

/// The numeric rows of a CSV (after `#` lines and the header) and its
/// header.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn fe_backbone_feeds_the_phm_and_the_run_writes_section_rebar_and_damage() {
    // TP-91 at 50 mm (1,728 hexahedra, about 5 s): cracks, peaks and
    // softens before the end of its twist.
    let out = dir("tp91");
    let phm = out.join("tp91-phm.json");
    let o = ok(hyst(&[
        "fe",
        &specimen("tp-91.toml"),
        "--element-size",
        "50",
        "--threads",
        "1",
        "--out",
        out.to_str().unwrap(),
        "--backbone",
        phm.to_str().unwrap(),
        "--json",
    ]));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    let curve = &summary["primary_curve"];
    let point = |k: &str| [curve[k][0].as_f64().unwrap(), curve[k][1].as_f64().unwrap()];
    let (c, y, p, d) = (
        point("cracking"),
        point("yield_point"),
        point("peak"),
        point("deterioration"),
    );
    assert!(c[0] < y[0] && y[0] < p[0] && p[0] < d[0], "{curve}");
    assert!(c[1] < y[1] && y[1] < p[1] && d[1] < p[1], "{curve}");
    // The specimen file ends the run below half its peak, so the last
    // point of the curve, deterioration, is the first sample below it.
    assert_eq!(summary["stop_below_peak"].as_f64(), Some(0.5));
    assert_eq!(summary["stopped_after_peak"].as_bool(), Some(true));
    assert!(d[1] < 0.5 * p[1], "{curve}");
    // The peak is the summary's (kN m), the initial stiffness its
    // initial stiffness (kN m/rad there, per degree here).
    let peak = summary["peak_torque"].as_f64().unwrap();
    assert!((p[1] - peak).abs() < 1e-9 * peak, "{} vs {peak}", p[1]);
    let k0 = summary["initial_stiffness"].as_f64().unwrap();
    assert!((c[1] / c[0] - k0.to_radians()).abs() < 1e-6 * k0);

    // Against thesis Table 2.1 (TP-91: test cracking 60.7, ultimate 76.6
    // kN m), in the summary and in the torque-twist figure.
    let table = &summary["table_2_1"];
    let cracking = summary["cracking_torque"].as_f64().unwrap();
    let error = |k: &str| table[k].as_f64().unwrap();
    assert!((error("cracking_error") - (cracking / 60.7 - 1.0)).abs() < 1e-12);
    assert!((error("peak_error") - (peak / 76.6 - 1.0)).abs() < 1e-12);
    let svg = std::fs::read_to_string(out.join("torque_twist.svg")).unwrap();
    for text in [
        "test cracking 60.7",
        "test ultimate 76.6",
        &format!("peak {peak:.1}"),
        &format!("cracking {cracking:.1}"),
    ] {
        assert!(svg.contains(text), "no '{text}' in torque_twist.svg");
    }

    // The quasi-static checks up to the peak judge the steps up to the
    // peak's row of torque_twist.csv as if the run had ended there: the
    // hourglass share of every sampled row there (past the window's start,
    // 1% of the largest internal energy up to the peak) is within the
    // largest share reported (up to the CSV's ten significant digits), and
    // here within the whole run's, since the share grows after the peak.
    let to_peak = &summary["checks_to_peak"];
    let (h, rows) = csv(&out.join("torque_twist.csv"));
    let (time, tq) = (column(&h, "time_s"), column(&h, "torque_kNm"));
    let (ie, hg) = (column(&h, "internal_J"), column(&h, "hourglass_J"));
    let peak_row = rows
        .iter()
        .position(|r| (r[tq] - peak).abs() < 1e-6 * peak)
        .expect("the peak row");
    let t_peak = to_peak["t_peak"].as_f64().unwrap();
    assert!((t_peak - rows[peak_row][time]).abs() < 1e-9 * t_peak);
    let share = to_peak["max_hourglass_share"].as_f64().unwrap();
    let ie_max = rows[..=peak_row].iter().fold(0.0f64, |m, r| m.max(r[ie]));
    let sampled = rows[..=peak_row]
        .iter()
        .filter(|r| r[ie] >= 0.01 * ie_max)
        .fold(0.0f64, |m, r| m.max(r[hg] / r[ie]));
    assert!(
        sampled > 0.0 && sampled <= share * (1.0 + 1e-9),
        "{sampled} vs {share}"
    );
    assert!(share <= summary["max_hourglass_share"].as_f64().unwrap());
    // After the peak the crushed elements deform in hourglass modes: the
    // share of the sampled rows grows past the largest one before it
    // (TP-91 at 50 mm: 14.0% up to the peak, 18.6% at the end).
    let after = rows[peak_row..]
        .iter()
        .fold(0.0f64, |m, r| m.max(r[hg] / r[ie]));
    assert!(after > share, "{after} vs {share}");
    assert_eq!(
        to_peak["quasi_static"].as_bool().unwrap(),
        to_peak["failures"].as_array().unwrap().is_empty()
    );

    // The file is a PHM file: a twist history to past the peak and back
    // runs through `hyst simulate`, and on its first excursion the element
    // follows its primary curve, so at the peak twist it gives the peak
    // torque.
    let mut twist: Vec<f64> = (0..=100).map(|i| p[0] * i as f64 / 100.0).collect();
    twist.extend((1..=100).map(|i| p[0] * (1.0 - 2.0 * i as f64 / 100.0)));
    let hist = out.join("history.csv");
    let mut text = String::from("twist (deg)\n");
    for x in &twist {
        text.push_str(&format!("{x}\n"));
    }
    std::fs::write(&hist, text).unwrap();
    let sim = out.join("sim.csv");
    ok(hyst(&[
        "simulate",
        hist.to_str().unwrap(),
        "--model",
        "phm-torsion",
        "--params",
        phm.to_str().unwrap(),
        "--out",
        sim.to_str().unwrap(),
    ]));
    let (h, rows) = csv(&sim);
    let tq = column(&h, "torque (kN m)");
    assert_eq!(rows.len(), twist.len());
    assert!(
        (rows[100][tq] - p[1]).abs() < 1e-6 * p[1],
        "{}",
        rows[100][tq]
    );
    assert!(rows.iter().all(|r| r[tq].is_finite()));

    // Rebar strains against torque (Fig. 2.2): the largest strain of each
    // bar set, finite, and growing up to the peak (within 1% of its value
    // there: the explicit run's inertia leaves a ripple).
    let (h, rows) = csv(&out.join("rebar_strains.csv"));
    let t = column(&h, "torque_kNm");
    let at_peak = rows
        .iter()
        .position(|r| (r[t] - peak).abs() < 1e-6 * peak)
        .expect("the peak row");
    // The first yield of the hoops (328 MPa / 200 GPa, Table 1.1 and thesis
    // 2.2.2) is the first row whose largest hoop strain reaches it, and the
    // summary's peak twist is the peak row's.
    let (tw, hoop) = (column(&h, "twist_rad"), column(&h, "max_transverse_strain"));
    let first = rows
        .iter()
        .find(|r| r[hoop] >= 328.0 / 200_000.0)
        .expect("the hoops yield at 50 mm");
    let yield_twist = summary["transverse_yield_twist"].as_f64().unwrap();
    assert!((yield_twist - first[tw]).abs() < 1e-9 * yield_twist);
    let peak_twist = summary["peak_twist"].as_f64().unwrap();
    assert!((peak_twist - rows[at_peak][tw]).abs() < 1e-9 * peak_twist);
    // And as a plot, with each set's yield strain (Table 1.1: 328 and 354 MPa).
    let svg = std::fs::read_to_string(out.join("rebar_strains.svg")).unwrap();
    for text in [
        "hoops",
        "longitudinal bars",
        "hoop yield 0.00164",
        "longitudinal yield 0.00177",
    ] {
        assert!(svg.contains(text), "no '{text}' in rebar_strains.svg");
    }
    for name in ["max_longitudinal_strain", "max_transverse_strain"] {
        let j = column(&h, name);
        assert!(rows.iter().all(|r| r[j].is_finite()), "{name}");
        let top = rows[at_peak][j];
        assert!(top > 1e-4, "{name}: {top}");
        for w in rows[..=at_peak].windows(2) {
            assert!(w[1][j] >= w[0][j] - 0.01 * top, "{name}: {w:?}");
        }
    }

    // The section at cracking and at the peak (Figs 2.9, 2.10): columns
    // per stage and a plot with a panel per line of the square.
    let (h, rows) = csv(&out.join("section_shear.csv"));
    for name in ["tau_cracking_MPa", "tau_peak_MPa", "tau_end_MPa"] {
        let j = column(&h, name);
        assert!(rows.iter().all(|r| r[j].is_finite()), "{name}");
    }
    assert_eq!(rows.len(), 64, "an 8 x 8 grid at 50 mm");
    let svg = std::fs::read_to_string(out.join("section_shear.svg")).unwrap();
    assert!(svg.contains("towards the middle of a face") && svg.contains("along the diagonal"));
    let stages: Vec<&str> = summary["section"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["stage"].as_str().unwrap())
        .collect();
    assert_eq!(stages, ["cracking", "peak", "end"]);

    // Tension damage in the VTK files (Fig. 2.13): none at the start,
    // some by the end, within [0, 0.99] (the damage cap).
    let damage = |f: &str| -> Vec<f64> {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        let at = text
            .find("SCALARS tension_damage double 1\nLOOKUP_TABLE default\n")
            .expect("a tension_damage cell scalar");
        text[at..]
            .lines()
            .skip(2)
            .take(1728)
            .map(|v| v.parse().unwrap())
            .collect()
    };
    let first = damage("concrete_0000.vtk");
    assert!(first.iter().all(|&d| d == 0.0));
    let last_vtk = (0..)
        .take_while(|i| out.join(format!("concrete_{i:04}.vtk")).exists())
        .last()
        .unwrap();
    let last = damage(&format!("concrete_{last_vtk:04}.vtk"));
    assert_eq!(last.len(), 1728);
    assert!(last.iter().all(|&d| (0.0..=0.99 + 1e-12).contains(&d)));
    assert!(last.iter().any(|&d| d > 0.5));
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn an_elastic_run_has_no_primary_curve_and_says_why() {
    let out = dir("elastic");
    let phm = out.join("phm.json");
    let o = hyst(&[
        "fe",
        &specimen("tp-92.toml"),
        "--elastic",
        "--element-size",
        "100",
        "--threads",
        "1",
        "--out",
        out.to_str().unwrap(),
        "--backbone",
        phm.to_str().unwrap(),
    ]);
    // The summary and the other outputs are still there.
    assert!(String::from_utf8_lossy(&o.stdout).contains("max torque"));
    let e = err(o);
    assert!(e.contains("--backbone"), "{e}");
    assert!(e.contains("never cracks before its peak"), "{e}");
    assert!(e.contains("expected a fall below 95%"), "{e}");
    assert!(!phm.exists());
    assert!(out.join("torque_twist.csv").exists());
    assert!(out.join("section_shear.csv").exists());
    std::fs::remove_dir_all(&out).ok();
}

/// A run that becomes unstable (here an hourglass stiffness 1000 times the default, which the
/// elements' own time steps do not follow) ends with an error naming the time it diverged, not
/// with a panic in the material or NaN results reported as a run. The global estimate
/// (`time_step = "global"`) follows that stiffness: the same run is stable with it.
#[test]
fn a_diverging_run_is_an_error() {
    let stiff = [
        "fe",
        "../specimens/tp-91.toml",
        "--element-size",
        "100",
        "--set",
        "loading.twist=[[0.0, 0.0], [0.002, 0.001]]",
        "--set",
        "analysis.hourglass_scale=1000",
    ];
    let e = err(hyst(
        &[&stiff[..], &["--set", "analysis.time_step=\"element\""]].concat(),
    ));
    assert!(!e.contains("panicked"), "{e}");
    assert!(e.contains("TP-91: the run diverged at t = "), "{e}");
    ok(hyst(&stiff));
}

/// A run of more steps than any specimen needs is refused before it starts: a twist history
/// ending at 1e300 s, or a density of 1e-300, made the step count saturate `u64`, and the run
/// never ended (found by review).
#[test]
fn a_run_of_absurdly_many_steps_is_refused() {
    for set in [
        "loading.twist=[[0.0, 0.0], [1e300, 0.001]]",
        "concrete.density_kg_m3=1e-300",
    ] {
        let e = err(hyst(&[
            "fe",
            "../specimens/tp-91.toml",
            "--elastic",
            "--element-size",
            "100",
            "--set",
            set,
        ]));
        assert!(
            e.contains("TP-91: the run would take") && e.contains("more than the 1e8"),
            "{set}: {e}"
        );
    }
}

/// A mesh or thread count the run could not use is refused before any work: one element
/// across used to run as a 1-element mesh, and 3,000 threads took 34 s for a run two threads
/// do in 0.01 s, all of them waiting at each step's barrier.
#[test]
fn unusable_mesh_sizes_and_thread_counts_are_refused() {
    let tp91 = specimen("tp-91.toml");
    let e = err(hyst(&["fe", &tp91, "--element-size", "1e9"]));
    assert!(
        e.contains("--element-size 1000000000: `analysis.element_size_mm`: expected at most a quarter of the section's 400 mm"),
        "{e}"
    );
    let e = err(hyst(&["fe", &tp91, "--threads", "100000"]));
    assert!(
        e.contains("--threads 100000: `analysis.threads`: expected 1 to "),
        "{e}"
    );
    assert!(e.contains("found 100000"), "{e}");
    let e = err(hyst(&["fe", &tp91, "--set", "analysis.threads=100000"]));
    assert!(
        e.contains("--set analysis.threads=100000: `analysis.threads`: expected 1 to "),
        "{e}"
    );
    // The options are checked with the file's values, not after them: a file whose own
    // element size is too fine for the limit runs with a coarser --element-size.
    let fine = tmp("fine.toml");
    let text = std::fs::read_to_string(&tp91).unwrap();
    std::fs::write(
        &fine,
        text.replacen("element_size_mm = 25.0", "element_size_mm = 2.0", 1),
    )
    .unwrap();
    let fine = fine.to_str().unwrap();
    let e = err(hyst(&["fe", fine]));
    assert!(e.contains("a mesh of at most 5000000 elements"), "{e}");
    let e = err(hyst(&[
        "fe",
        fine,
        "--element-size",
        "25",
        "--threads",
        "0",
    ]));
    assert!(
        e.contains("--threads 0: `analysis.threads`: expected 1 to "),
        "the element size passed: {e}"
    );
}

/// Found by review: a value set twice (or by `--set` and its own option) silently took the
/// last, and the summary listed a `--set` that was not applied; `--backbone` could replace a
/// file the run wrote into `--out`; `--out a/b/c` made every missing folder, where every other
/// output refuses a folder that does not exist. All are refused before the run.
#[test]
fn contradicting_settings_and_outputs_are_refused_before_the_run() {
    let tp91 = specimen("tp-91.toml");
    let e = err(hyst(&[
        "fe",
        &tp91,
        "--set",
        "concrete.fc_mpa=30",
        "--set",
        "concrete.fc_mpa=45",
    ]));
    assert!(
        e.contains("--set concrete.fc_mpa=30 and --set concrete.fc_mpa=45 both set `concrete.fc_mpa`: give it once"),
        "{e}"
    );
    let e = err(hyst(&[
        "fe",
        &tp91,
        "--set",
        "analysis.element_size_mm=50",
        "--element-size",
        "100",
    ]));
    assert!(
        e.contains("--set analysis.element_size_mm=50 and --element-size 100 both set"),
        "{e}"
    );
    let out = dir("contradictions");
    for name in ["torque_twist.csv", "rebar_strains.csv", "concrete_0003.vtk"] {
        let backbone = out.join(name);
        let e = err(hyst(&[
            "fe",
            &tp91,
            "--out",
            out.to_str().unwrap(),
            "--backbone",
            backbone.to_str().unwrap(),
        ]));
        assert!(
            e.contains("the run writes that file into --out"),
            "{name}: {e}"
        );
    }
    let deep = out.join("missing").join("run");
    let e = err(hyst(&["fe", &tp91, "--out", deep.to_str().unwrap()]));
    let missing = format!(
        "the folder {} does not exist",
        out.join("missing").display()
    );
    assert!(e.contains(&missing), "{e}");
    assert!(!out.join("missing").exists());
}
