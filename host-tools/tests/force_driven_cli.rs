//! A force-driven record through the CLI as a user runs it: `hyst fit --mass`
//! identifies the oscillator of thesis eq. 3.3 from the Bouc-Wen example of
//! section 4.4 (`benches/baselines/bw_synthetic.csv`: RK4 at 2 ms from the
//! true parameters, no noise), and `hyst simulate` with the fit file predicts
//! the displacement again, to the error the fit reported.

#[path = "support/cli.rs"]
mod cli;

use cli::{err, hyst, ok, stderr, tmp};
use serde_json::Value;

const RECORD: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../benches/baselines/bw_synthetic.csv"
);
const TRUTH: [(&str, f64); 5] = [
    ("alpha", 0.2),
    ("beta", 2.0),
    ("gamma", -1.0),
    ("xi", 0.05),
    ("n", 1.2),
];

#[test]
fn fit_with_mass_then_simulate_the_fit() {
    let fit = tmp("fit.json").display().to_string();
    let out = ok(hyst(&[
        "fit", RECORD, "--model", "bw", "--mass", "500", "--fix", "k0=6", "--out", &fit, "--json",
    ]));
    let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&fit).unwrap()).unwrap();
    // The record is RK4 at 2 ms, within 1.95e-4 mm of the converged motion
    // (its README): the fit must land on the truth to well within that.
    for (name, truth) in TRUTH {
        let got = file[name].as_f64().unwrap();
        assert!(
            ((got - truth) / truth).abs() < 1e-3,
            "{name}: {got} vs {truth}"
        );
    }
    assert_eq!(file["m"].as_f64(), Some(500.0));
    let nrmse = summary["nrmse"].as_f64().unwrap();
    assert!(nrmse < 1e-3, "nrmse {nrmse}");

    // The fit file selects the force drive and the mass by itself.
    let csv = tmp("sim.csv").display().to_string();
    let sim = ok(hyst(&["simulate", RECORD, "--params", &fit, "--out", &csv]));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("time,force,displacement"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let measured: Vec<f64> = std::fs::read_to_string(RECORD)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    assert_eq!(rows.len(), measured.len());
    let n = rows.len() as f64;
    let err = (rows
        .iter()
        .zip(&measured)
        .map(|(r, u)| (r[2] - u).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    let rms = (measured.iter().map(|u| u * u).sum::<f64>() / n).sqrt();
    // Simulating the fit reproduces the error the fit reported (NRMSE of the
    // displacement), so the file carries everything the prediction needs.
    assert!(
        (err / rms - nrmse).abs() <= 0.01 * nrmse,
        "simulated NRMSE {} vs fitted {nrmse}",
        err / rms
    );
    let note = stderr(&sim);
    assert!(note.contains("displacement RMS error"), "{note}");
}

#[test]
fn a_force_record_without_a_mass_is_refused_with_the_remedy() {
    let params = tmp("plain.json");
    std::fs::write(
        &params,
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "xi": 0.05}"#,
    )
    .unwrap();
    let params = params.display().to_string();
    let msg = err(hyst(&[
        "simulate", RECORD, "--params", &params, "--mass", "0",
    ]));
    assert!(msg.contains("positive number of kg"), "{msg}");
}
