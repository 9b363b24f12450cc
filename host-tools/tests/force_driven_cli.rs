//! A force-driven record through the CLI as a user runs it: `hyst fit --mass`
//! identifies the oscillator of thesis eq. 3.3 from the Bouc-Wen example of
//! section 4.4 (`benches/baselines/bw_synthetic.csv`: RK4 at 2 ms from the
//! true parameters, no noise), and `hyst simulate` with the fit file predicts
//! the displacement again, to the error the fit reported.

#[path = "support/cli.rs"]
mod cli;
#[path = "support/thesis_bw.rs"]
#[allow(dead_code)]
mod thesis_bw;

use cli::{err, hyst, ok, stderr, tmp, write};
use serde_json::Value;
use thesis_bw::TRUTH;

const RECORD: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../benches/baselines/bw_synthetic.csv"
);

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
    // The default method, auto, screened its starts with the fixed-step model and says so (the
    // best screened end was refined, the first start fitted directly).
    assert_eq!(summary["method"], "auto");
    let screening = &summary["screening"];
    assert_eq!(screening["method"], "rk4", "{summary}");
    assert_eq!(screening["starts"].as_u64(), Some(8));
    assert_eq!(screening["refined"].as_u64(), Some(1));
    assert!(screening["lane_runs"].as_u64().unwrap() > 0);

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

/// `hyst fit` by NSGA-II on the benchmark record with the options `extra`.
fn nsga2_fit(extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "fit", RECORD, "--model", "bw", "--mass", "500", "--fix", "k0=6", "--method", "nsga2",
    ];
    args.extend_from_slice(extra);
    hyst(&args)
}

/// NSGA-II on a force-driven plain Bouc-Wen record searches with the lane-batched RK4 model
/// (`hyst::fit::lanes`), says so, and reports what the error-controlled model scores: the
/// front's file and `hyst simulate` of the fit agree with the reported NRMSE.
#[test]
fn nsga2_searches_with_the_fixed_step_model_and_reports_the_core() {
    let fit = tmp("nsga2.json").display().to_string();
    let front = tmp("front.csv").display().to_string();
    let out = ok(nsga2_fit(&[
        "--population",
        "40",
        "--generations",
        "20",
        "--pareto",
        &front,
        "--out",
        &fit,
        "--json",
    ]));
    let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
    let search = &summary["search_model"];
    assert_eq!(search["method"], "rk4", "{summary}");
    assert_eq!(
        search["lanes"].as_u64(),
        Some(hyst::fit::lanes::LANES as u64)
    );
    let steps = search["steps_per_sample"].as_u64().unwrap();
    let most = hyst::fit::lanes::MAX_SUBSTEPS as u64;
    assert!((1..=most).contains(&steps), "{search}");
    assert!(
        search["checked_error"].as_f64().unwrap() <= 2.5e-4,
        "{search}"
    );
    let retried = search["retried"].as_u64().unwrap();
    assert!(search["by_core"].as_u64().unwrap() <= retried, "{search}");
    let nrmse = summary["nrmse"].as_f64().unwrap();
    assert!(nrmse.is_finite() && nrmse < 0.5, "{nrmse}");

    let sim = ok(hyst(&[
        "simulate",
        RECORD,
        "--params",
        &fit,
        "--out",
        &tmp("p.csv").display().to_string(),
    ]));
    let note = stderr(&sim);
    let number_after = |key: &str| -> f64 {
        note.split(key)
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("no `{key}` in {note}"))
    };
    let simulated = number_after("displacement RMS error ") / number_after("the measured RMS ");
    assert!(
        (simulated - nrmse).abs() <= 0.01 * nrmse,
        "{simulated} vs {nrmse}"
    );

    // The front file scores with the core too: the chosen member's row carries the fit's
    // NRMSE and four objectives.
    let text = std::fs::read_to_string(&front).unwrap();
    let ortiz: Vec<f64> = summary["ortiz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(
        rows.iter().any(|r| {
            let tail = &r[r.len() - 5..];
            close(tail[4], nrmse) && tail[..4].iter().zip(&ortiz).all(|(a, b)| close(*a, *b))
        }),
        "no row of the front scores as the fit ({nrmse}, {ortiz:?}):\n{text}"
    );

    let text =
        String::from_utf8(ok(nsga2_fit(&["--population", "16", "--generations", "2"])).stdout)
            .unwrap();
    assert!(
        text.contains(&format!(
            "Note: the search simulated {} candidates at a time by RK4",
            hyst::fit::lanes::LANES
        )),
        "{text}"
    );
}

/// Where the fixed-step model cannot search (here: an effect the lanes do not hold), NSGA-II
/// searches with the core and says why, in the text and in `--json`.
#[test]
fn nsga2_says_why_it_searches_with_the_core() {
    let budget = ["--population", "16", "--generations", "2"];
    let model = ["--model", "bw+strength-degradation"];
    let with = |extra: &[&str]| {
        let mut args = vec!["fit", RECORD, "--mass", "500", "--fix", "k0=6"];
        args.extend_from_slice(&["--method", "nsga2"]);
        args.extend_from_slice(&budget);
        args.extend_from_slice(&model);
        args.extend_from_slice(extra);
        ok(hyst(&args))
    };
    let summary: Value = serde_json::from_slice(&with(&["--json"]).stdout).unwrap();
    let search = &summary["search_model"];
    assert_eq!(search["method"], "core", "{summary}");
    let reason = search["reason"].as_str().unwrap();
    assert!(reason.contains("only plain Bouc-Wen"), "{reason}");
    let text = String::from_utf8(with(&[]).stdout).unwrap();
    assert!(
        text.contains("Note: the search simulated every candidate with the error-controlled model"),
        "{text}"
    );
}

/// `--polish` refines NSGA-II's choice by least squares: the JSON keeps the chosen set's
/// scores, the fit reaches the record's parameters, the text gives both errors, and the flag
/// is refused with a method that has no evolutionary search.
#[test]
fn polish_refines_the_nsga2_choice_and_reports_both_errors() {
    let budget = ["--population", "16", "--generations", "10"];
    let file = tmp("polished.json").display().to_string();
    let out = ok(nsga2_fit(
        &[&budget[..], &["--polish", "--json", "--out", &file]].concat(),
    ));
    let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["method"], "nsga2+lsq", "{summary}");
    let chosen = summary["polished_from"]["nrmse"].as_f64().unwrap();
    // The parameter file keeps where the polish started, for whoever reads the fit later.
    let saved: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    assert_eq!(saved["fit"]["method"], "nsga2+lsq");
    assert_eq!(
        saved["fit"]["polished_from"]["nrmse"].as_f64(),
        Some(chosen)
    );
    let nrmse = summary["nrmse"].as_f64().unwrap();
    // The record is RK4 at 2 ms (no noise): what is left is that integrator's error, 1.9e-5.
    assert!(
        nrmse < 1e-4 && nrmse < 1e-2 * chosen,
        "{nrmse} from {chosen}"
    );
    for (name, truth) in TRUTH {
        let v = summary["params"][name].as_f64().unwrap();
        assert!((v - truth).abs() <= 1e-3 * truth.abs(), "{name} {v}");
    }

    let text =
        String::from_utf8(ok(nsga2_fit(&[&budget[..], &["--polish"]].concat())).stdout).unwrap();
    assert!(
        text.contains("method nsga2+lsq") && text.contains("NSGA-II chose a set with NRMSE"),
        "{text}"
    );

    let msg = err(hyst(&[
        "fit", RECORD, "--model", "bw", "--mass", "500", "--method", "lsq", "--polish",
    ]));
    assert!(msg.contains("use it with --method nsga2"), "{msg}");
}

/// Forgione's noisy estimation record of the Bouc-Wen benchmark, fitted as the docs run it
/// (`auto`, force linear between samples). Least squares reaches the truth from the default
/// start only: seven random starts end in minima at NRMSE 0.29-0.64, and so did every end
/// screened with the fixed-step model, the default start's included, so `auto` once returned
/// NRMSE 0.316 with `n` and `alpha` at the ends of their ranges. The true parameters (the
/// benchmark's PROVENANCE, in this crate's units) must come back to 3%; the damping is left
/// out, 13% low with linear forcing (README, "cubic").
#[test]
fn auto_finds_the_benchmark_oscillator() {
    let record = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/boucwen-benchmark/csv/train_multisine_forgione.csv"
    );
    let out = ok(hyst(&[
        "fit",
        record,
        "--model",
        "bw",
        "--mass",
        "2",
        "--sample-rate",
        "750",
        "--json",
    ]));
    let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
    // The added output noise alone is 1.2% of rms(y).
    let nrmse = summary["nrmse"].as_f64().unwrap();
    assert!(nrmse < 0.015, "nrmse {nrmse}");
    let params = &summary["params"];
    for (name, truth) in [
        ("k0", 0.1),
        ("alpha", 0.5),
        ("n", 1.0),
        ("beta", 0.8),
        ("gamma", -1.1),
    ] {
        let got = params[name].as_f64().unwrap();
        assert!(
            ((got - truth) / truth).abs() < 0.03,
            "{name}: {got} vs {truth}"
        );
    }
}

/// `--params` starts a fit from a parameter file. At a least-squares fit's own end the gradient
/// is zero, so least squares from there stops at once on the same NRMSE; the file of a smaller
/// model starts a larger one, whose added effect starts switched off, so its fit can only lower
/// the error; and what cannot be a start is refused by name, not clamped into the range.
#[test]
fn a_fit_starts_from_a_parameter_file() {
    let fit = tmp("start.json").display().to_string();
    let first: Value = serde_json::from_slice(
        &ok(hyst(&[
            "fit", RECORD, "--model", "bw", "--mass", "500", "--method", "lsq", "--out", &fit,
            "--json",
        ]))
        .stdout,
    )
    .unwrap();
    let again = hyst(&[
        "fit", RECORD, "--model", "bw", "--method", "lsq", "--params", &fit, "--json",
    ]);
    let again: Value = serde_json::from_slice(&ok(again).stdout).unwrap();
    let (a, b) = (
        first["nrmse"].as_f64().unwrap(),
        again["nrmse"].as_f64().unwrap(),
    );
    assert!((a - b).abs() <= 1e-9 * a, "{a} then {b}");
    assert!(again["simulations"].as_u64().unwrap() <= 3, "{again}");
    // The mass came from the file.
    assert_eq!(again["params"]["m"].as_f64(), Some(500.0));

    let out = tmp("pinching.json").display().to_string();
    let larger = ok(hyst(&[
        "fit",
        RECORD,
        "--model",
        "bw+pinching",
        "--method",
        "lsq",
        "--params",
        &fit,
        "--out",
        &out,
        "--json",
    ]));
    assert!(
        stderr(&larger).contains("has no zeta0, p, q, psi0, delta_psi, lambda"),
        "{}",
        stderr(&larger)
    );
    let larger: Value = serde_json::from_slice(&larger.stdout).unwrap();
    assert!(larger["nrmse"].as_f64().unwrap() <= a, "{larger}");
    let written: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(written["fit"]["start"].as_str(), Some(fit.as_str()));

    let e = err(hyst(&[
        "fit", RECORD, "--model", "bw", "--method", "nsga2", "--params", &fit,
    ]));
    assert!(e.contains("NSGA-II draws its population"), "{e}");
    // The fit of bw+pinching does not start plain bw (its pinching would be dropped): the
    // model to give is named, also when --model is left at its default.
    for args in [vec!["--model", "bw"], vec![]] {
        let e = err(hyst(
            &[&["fit", RECORD, "--params", &out][..], &args].concat(),
        ));
        assert!(
            e.contains("which --model bw lacks: give --model bw+pinching"),
            "{e}"
        );
    }
    let mut far: Value = serde_json::from_str(&std::fs::read_to_string(&fit).unwrap()).unwrap();
    far["k0"] = 600.0.into();
    let far_path = write("far.json", &serde_json::to_string_pretty(&far).unwrap());
    let e = err(hyst(&[
        "fit", RECORD, "--model", "bw", "--params", &far_path,
    ]));
    assert!(
        e.contains("k0 = 600 lies outside the search range") && e.contains("--fix k0=600"),
        "{e}"
    );
    assert!(
        e.contains(&format!("{far_path}:")),
        "names the place in the file: {e}"
    );
    // No damping is made up for a force-driven start.
    let mut no_xi: Value = serde_json::from_str(&std::fs::read_to_string(&fit).unwrap()).unwrap();
    no_xi.as_object_mut().unwrap().remove("xi");
    let no_xi = write("no-xi.json", &serde_json::to_string_pretty(&no_xi).unwrap());
    let e = err(hyst(&["fit", RECORD, "--params", &no_xi]));
    assert!(e.contains("no `xi`") && e.contains("--fix xi="), "{e}");
    // A --fix that breaks the file's set is named as the cause: the fit has gamma < 0, and
    // beta + gamma < 0 leaves pinching without its Zu (legal plain Bouc-Wen).
    let gamma = first["params"]["gamma"].as_f64().unwrap();
    assert!(gamma < 0.0, "{first}");
    let fix = format!("beta={}", -gamma / 2.0);
    let e = err(hyst(&[
        "fit",
        RECORD,
        "--model",
        "bw+pinching",
        "--params",
        &fit,
        "--fix",
        &fix,
    ]));
    assert!(
        e.contains(&format!("with --fix {fix}: not a valid set")) && e.contains("Zu"),
        "{e}"
    );
}
