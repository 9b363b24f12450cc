//! A model with effects fitted directly can stall with an effect's parameters
//! at the ends of their ranges; `diagnose` then grows it from its base as the
//! ladder does and diagnoses the better fit.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, stderr};
use serde_json::Value;

fn data(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// `hyst diagnose` of `bw+pinching` on a record made by that model (pinching hidden on an
/// irregular path, `tests/data/PROVENANCE.md`), weighing the effect the stalled fit named
/// (found by review: fitted directly from eight starts, the model stopped at NRMSE 0.0438 with
/// `p`, `q` and `lambda` at the ends of their ranges, and stiffness degradation was named for
/// what was left, "BIC rises by 3308 without it"). Diagnosed, the fit must reach the true
/// parameters' NRMSE (the noise) within 2%, and name nothing.
#[test]
fn a_stalled_fit_of_the_right_model_is_grown_and_names_nothing() {
    let record = data("pinching_irregular.csv");
    let diagnose = |extra: &[&str]| -> (Value, String) {
        let args = [
            &[
                "diagnose",
                record.as_str(),
                "--model",
                "bw+pinching",
                "--candidates",
                "stiffness-degradation",
                "--json",
            ],
            extra,
        ]
        .concat();
        let out = ok(hyst(&args));
        let v = serde_json::from_slice(&out.stdout).expect("diagnose --json prints JSON");
        (v, stderr(&out))
    };
    let truth = data("pinching_irregular.truth.json");
    let (at_truth, _) = diagnose(&["--params", &truth]);
    let floor = at_truth["nrmse"].as_f64().unwrap();
    let (fitted, notes) = diagnose(&[]);
    let nrmse = fitted["nrmse"].as_f64().unwrap();
    println!("{notes}\nNRMSE {nrmse} against {floor} at the truth");
    assert!(nrmse < 1.02 * floor, "{nrmse} against {floor}: {notes}");
    let suspect = &fitted["suspects"][0];
    assert_eq!(suspect["effect"], "stiffness-degradation", "{fitted}");
    assert_eq!(suspect["significant"], false, "{suspect}");
    // Where the direct fit stopped in a corner, the note says what was done, and `fit`, which
    // keeps its direct fit, says that it can stall there.
    if notes.contains("fitted directly") {
        assert!(notes.contains("grown from its base"), "{notes}");
        let fit = ok(hyst(&["fit", &record, "--model", "bw+pinching"]));
        let said = String::from_utf8_lossy(&fit.stdout);
        assert!(said.contains("a fit can stall"), "{said}");
    }
}
