//! A fit that stops at the end of a search range says so. The record is a
//! plain Bouc-Wen loop with alpha = 0.7, beyond the range the fits search for
//! alpha (0 to 0.5, chosen for RC columns, whose post-yield ratio is a few
//! percent), though the model allows alpha up to 1.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, tmp};
use hysteresis::bwbn::{BoucWen, Bwbn, BwbnParams};
use hysteresis::Element;
use serde_json::Value;

/// Cycles of growing amplitude up to 6 mm, 100 steps a cycle; returns the path.
fn record(alpha: f64) -> String {
    let base = BoucWen::new(6.0, alpha, 1.2, 2.0, -1.0).unwrap();
    let mut el = Bwbn::new(BwbnParams::plain(base));
    let mut text = String::from("displacement (mm),force (kN)\n");
    for k in 0..=600 {
        let cycle = k as f64 / 100.0;
        let u = (cycle + 1.0) * (2.0 * std::f64::consts::PI * cycle).sin();
        let f = el.set_trial(u).unwrap().force;
        el.commit();
        text.push_str(&format!("{u},{f}\n"));
    }
    let path = tmp(&format!("alpha-{alpha}.csv"));
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn a_parameter_stopped_by_its_search_range_is_reported() {
    let rec = record(0.7);
    let o = ok(hyst(&["fit", &rec, "--method", "lsq", "--json"]));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    let at = summary["at_bounds"].as_array().unwrap();
    let alpha = at.iter().find(|a| a["name"] == "alpha").expect("alpha");
    assert_eq!(alpha["end"], "upper");
    assert_eq!(alpha["value"].as_f64(), Some(0.5));
    assert_eq!(alpha["beyond_is_valid"], true);
    let stuck = summary["nrmse"].as_f64().unwrap();

    // The text says it, and fixing alpha at the truth fits the record.
    let text = String::from_utf8(ok(hyst(&["fit", &rec, "--method", "lsq"])).stdout).unwrap();
    assert!(
        text.contains("alpha stopped at the upper end of its search range"),
        "{text}"
    );
    let o = ok(hyst(&[
        "fit",
        &rec,
        "--method",
        "lsq",
        "--fix",
        "alpha=0.7",
        "--json",
    ]));
    let fixed: Value = serde_json::from_slice(&o.stdout).unwrap();
    let nrmse = fixed["nrmse"].as_f64().unwrap();
    assert!(
        nrmse < 1e-6 && stuck > 100.0 * nrmse,
        "{stuck} then {nrmse}"
    );
    assert_eq!(fixed["at_bounds"], serde_json::json!([]));

    // The diagnosis says it too: the misfit it leaves is what its suspects are asked to explain.
    let d: Value = serde_json::from_slice(&ok(hyst(&["diagnose", &rec, "--json"])).stdout).unwrap();
    let alpha = d["at_bounds"]
        .as_array()
        .unwrap()
        .iter()
        .find(|a| a["name"] == "alpha");
    assert_eq!(alpha.expect("alpha")["end"], "upper", "{d}");
    let text = String::from_utf8(ok(hyst(&["diagnose", &rec])).stdout).unwrap();
    assert!(
        text.contains("note: alpha stopped at the upper end of its search range"),
        "{text}"
    );
    // Given parameters were not searched: alpha = 0.7 beyond the range is no stop.
    let truth = tmp("alpha-0.7.json");
    std::fs::write(
        &truth,
        r#"{"model": "bw", "k0": 6, "alpha": 0.7, "n": 1.2, "beta": 2, "gamma": -1}"#,
    )
    .unwrap();
    let truth = truth.display().to_string();
    let args = ["diagnose", &rec, "--params", &truth, "--json"];
    let d: Value = serde_json::from_slice(&ok(hyst(&args)).stdout).unwrap();
    assert_eq!(d["at_bounds"], serde_json::json!([]), "{d}");
    assert!(d["nrmse"].as_f64().unwrap() < 1e-6, "{d}");
    let text = String::from_utf8(ok(hyst(&args[..4])).stdout).unwrap();
    assert!(!text.contains("stopped at"), "{text}");
}

/// Inside the ranges nothing is reported.
#[test]
fn a_fit_inside_its_ranges_reports_no_bounds() {
    let rec = record(0.2);
    let o = ok(hyst(&["fit", &rec, "--method", "lsq", "--json"]));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["at_bounds"], serde_json::json!([]));
    assert!(summary["nrmse"].as_f64().unwrap() < 1e-6);
}

/// `auto` screens its starts with the fixed-step lane model only for force-driven plain Bouc-Wen
/// records; a displacement-driven loop is fitted from every start with the core, and the summary
/// has no screening.
#[test]
fn auto_on_a_displacement_record_fits_every_start_with_the_core() {
    let rec = record(0.2);
    let o = ok(hyst(&["fit", &rec, "--method", "auto", "--json"]));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["method"], "auto");
    assert!(summary["screening"].is_null(), "{summary}");
    assert!(summary["nrmse"].as_f64().unwrap() < 1e-6);
}
