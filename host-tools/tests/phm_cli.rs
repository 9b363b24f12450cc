//! `hyst simulate` and `hyst fit` with `--model phm-torsion` as a user runs
//! them: a twist history through a PHM file and back, a fit that recovers the
//! PHM that made a noisy record, and the errors on bad input.

#[path = "support/cli.rs"]
mod cli;

use cli::{err, hyst, ok, tmp, write};
use hyst::data::{read, ReadOptions, Record};
use hyst::fit::phm::{first_excursions, fit_envelope, idealise, valid_start, PhmProblem};
use hyst::model::{simulate_phm, PhmFile};
use hysteresis::phm::{Coefficients, Direction, PhmParams};
use serde_json::Value;
use std::process::Output;

/// An asymmetric column; yield twists between the amplitudes of
/// [`history`], so no fitted yield twist sits on the switch of eqs 1-3.
const TRUTH: &str = r#"{"model": "phm-torsion", "units": {"twist": "deg", "torque": "kN m"},
 "primary": {"positive": [[0.2, 100.0], [1.2, 160.0], [4.2, 172.0], [7.5, 150.0]],
             "negative": [[0.25, 110.0], [1.3, 158.0], [4.3, 166.0], [7.5, 140.0]]},
 "coefficients": {"eq2b_b": 0.38, "eq3b_b": 0.12, "eq4_a": 0.65, "eq5b_b": 0.85, "eq6_c": 0.95}}"#;

/// Two cycles at each of 10 amplitudes up to 8 deg, 40 samples a leg.
fn history() -> Vec<f64> {
    let mut x = vec![0.0f64];
    for a in [0.1, 0.3, 0.6, 1.0, 1.5, 2.5, 3.5, 5.0, 6.5, 8.0] {
        for _ in 0..2 {
            for target in [a, -a, 0.0] {
                let x0 = *x.last().unwrap();
                x.extend((1..=40).map(|i| x0 + (target - x0) * i as f64 / 40.0));
            }
        }
    }
    x
}

fn csv(header: &str, rows: impl Iterator<Item = String>) -> String {
    let mut s = format!("{header}\n");
    for r in rows {
        s.push_str(&r);
        s.push('\n');
    }
    s
}

/// The CSV `hyst simulate` wrote to stdout, read as a record.
fn stdout_record(o: Output) -> Record {
    let text = String::from_utf8(o.stdout).unwrap();
    hyst::data::read_str(
        "stdout",
        &text,
        hyst::data::Format::Csv,
        &ReadOptions::default(),
    )
    .unwrap()
}

fn nrmse(y: &[f64], yhat: &[f64]) -> f64 {
    let n = y.len() as f64;
    let rms = (y.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
    let e = y
        .iter()
        .zip(yhat)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        / n;
    e.sqrt() / rms
}

#[test]
fn simulate_writes_what_the_element_computes() {
    let p = write("truth.json", TRUTH);
    let x = history();
    let h = write(
        "hist.csv",
        &csv("twist (deg)", x.iter().map(|v| v.to_string())),
    );
    let out = tmp("sim.csv");
    let svg = tmp("sim.svg");
    let o = tmp("sim.txt");
    // The PHM file selects the model; --model phm-torsion says the same.
    ok(hyst(&[
        "simulate",
        &h,
        "--params",
        &p,
        "--out",
        out.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]));
    let same = ok(hyst(&[
        "simulate",
        &h,
        "--model",
        "phm-torsion",
        "--params",
        &p,
    ]));
    assert_eq!(std::fs::read(&out).unwrap(), same.stdout);
    std::fs::write(&o, &same.stdout).unwrap();
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));

    // The CSV reads back as a twist/torque record equal to the element's run.
    let r = read(&out, &ReadOptions::default()).unwrap();
    assert!(r.is_torsion());
    let direct = simulate_phm(&PhmFile::read(&p).unwrap().params, &x).unwrap();
    assert_eq!(r.displacement().unwrap(), &x[..]);
    assert_eq!(r.force().unwrap(), &direct.torque[..]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("twist (deg),torque (kN m),tangent,n_positive,n_negative\n"));
    // Two cycles at 8 deg: the counter of each direction ends at 2.
    assert!(
        text.trim_end().ends_with(",2,2"),
        "{}",
        &text[text.len() - 80..]
    );

    let j = ok(hyst(&["simulate", &h, "--params", &p, "--json"]));
    let v: Value = serde_json::from_slice(&j.stdout).unwrap();
    assert_eq!(v["model"], "phm-torsion");
    assert_eq!(v["samples"], x.len());
    assert_eq!(v["columns"]["torque (kN m)"][100], direct.torque[100]);

    // A history in rad is converted to the file's deg.
    let rad = write(
        "hist_rad.csv",
        &csv("twist (rad)", x.iter().map(|v| v.to_radians().to_string())),
    );
    let o2 = ok(hyst(&["simulate", &rad, "--params", &p]));
    let r2 = stdout_record(o2);
    for (a, b) in r2.force().unwrap().iter().zip(&direct.torque) {
        assert!((a - b).abs() < 1e-9);
    }

    // The read options hold here too (they were ignored for the PHM: found by review): a
    // history 1 deg off, taken back by `--subtract` (canonical deg), is the history.
    let shifted = write(
        "hist_shifted.csv",
        &csv("twist (deg)", x.iter().map(|v| (v + 1.0).to_string())),
    );
    let o3 = ok(hyst(&[
        "simulate",
        &shifted,
        "--params",
        &p,
        "--subtract",
        "displacement=1",
    ]));
    let r3 = stdout_record(o3);
    for (a, b) in r3.force().unwrap().iter().zip(&direct.torque) {
        assert!((a - b).abs() < 1e-9);
    }
    // `twist` names the same channel; a torque the history lacks is called so.
    let o4 = ok(hyst(&[
        "simulate",
        &shifted,
        "--params",
        &p,
        "--subtract",
        "twist=1",
    ]));
    assert_eq!(stdout_record(o4).force(), r3.force());
    let e = err(hyst(&[
        "simulate",
        &shifted,
        "--params",
        &p,
        "--subtract",
        "torque=5",
    ]));
    assert!(
        e.contains("cannot subtract 5 from the torque: the record has no torque"),
        "{e}"
    );
}

/// `clean` with deterministic noise of standard deviation 1: sums of 12
/// uniforms of an LCG started at `seed`.
fn with_noise(clean: &[f64], seed: u64) -> Vec<f64> {
    let mut state = seed;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    clean
        .iter()
        .map(|t| t + (0..12).map(|_| uniform()).sum::<f64>() - 6.0)
        .collect()
}

/// [`TRUTH`] over [`history`]: the parameters, the twist, the clean torque
/// and the torque with the noise of [`with_noise`] from `seed`.
fn noisy_truth(seed: u64) -> (PhmParams<f64, 8>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let p = write(&format!("truth_{seed}.json"), TRUTH);
    let truth = PhmFile::read(&p).unwrap().params;
    let x = history();
    let clean = simulate_phm(&truth, &x).unwrap().torque;
    let noisy = with_noise(&clean, seed);
    (truth, x, clean, noisy)
}

/// A twist-torque record file (deg, kN m) named `name`.
fn record_file(name: &str, twist: &[f64], torque: &[f64]) -> String {
    write(
        name,
        &csv(
            "twist (deg),torque (kN m)",
            twist.iter().zip(torque).map(|(a, b)| format!("{a},{b}")),
        ),
    )
}

/// A record made by the PHM itself with noise of 1 kN m (about 1.5 % of the
/// RMS torque): the fit from the idealised envelope and the thesis'
/// coefficients finds a set that explains it as well as the truth does;
/// the cracking and yield points and the five coefficients changed from the
/// thesis' values are within 3 standard errors of the truth. (The points
/// past the peak are not checked: the record never returns to the primary
/// curve there, a pinched reloading meets it only past the previous extreme,
/// and the last point lies beyond the largest twist; the fit reports them
/// with infinite standard errors.)
#[test]
fn fit_recovers_the_model_that_made_the_record() {
    let (truth, x, clean, noisy) = noisy_truth(12345);
    let data = record_file("record.csv", &x, &noisy);
    let fit = tmp("fit.json");
    let o = ok(hyst(&[
        "fit",
        &data,
        "--model",
        "phm-torsion",
        "--out",
        fit.to_str().unwrap(),
        "--json",
    ]));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["model"], "phm-torsion");
    let fitted_nrmse = v["nrmse"].as_f64().unwrap();
    let truth_nrmse = nrmse(&noisy, &clean);
    eprintln!("NRMSE fit {fitted_nrmse:.5}, truth {truth_nrmse:.5}");
    // As good as the truth to 10 %: the rest is the noise.
    assert!(
        fitted_nrmse < 1.1 * truth_nrmse,
        "{fitted_nrmse} vs {truth_nrmse}"
    );
    // The fitted set is searched for closed cycles that return energy
    // (model::phm_passivity): near the thesis' coefficients, none.
    let passivity = &v["passivity"];
    eprintln!("passivity: {passivity}");
    assert!(passivity["cycles"].as_u64().unwrap() > 50);
    assert_eq!(passivity["returning_energy"], 0);

    // A fit file records what the record's reading took off, for the PHM too (it did not:
    // found by review).
    let shifted = tmp("fit_shifted.json");
    ok(hyst(&[
        "fit",
        &data,
        "--model",
        "phm-torsion",
        "--subtract",
        "torque=0.5..-0.5",
        "--out",
        shifted.to_str().unwrap(),
    ]));
    let recorded: Value =
        serde_json::from_str(&std::fs::read_to_string(&shifted).unwrap()).unwrap();
    assert_eq!(
        recorded["fit"]["subtract"]["force"],
        serde_json::json!([0.5, -0.5]),
        "{recorded}"
    );

    // Round trip: the written file simulates the record to the same NRMSE.
    let refit = ok(hyst(&[
        "simulate",
        &data,
        "--params",
        fit.to_str().unwrap(),
    ]));
    let r = stdout_record(refit);
    assert!((nrmse(&noisy, r.force().unwrap()) - fitted_nrmse).abs() < 1e-9);

    let got = PhmFile::read(&fit).unwrap().params;
    let std = &v["std"];
    for (d, dir) in [
        hysteresis::phm::Direction::Positive,
        hysteresis::phm::Direction::Negative,
    ]
    .into_iter()
    .enumerate()
    {
        let (g, t) = (got.primary(dir).points(), truth.primary(dir).points());
        let pstd = &v["primary_std"][["positive", "negative"][d]];
        for i in 0..2 {
            for k in 0..2 {
                let s = pstd[i][k].as_f64().unwrap();
                eprintln!(
                    "{dir:?} point {i}.{k}: fit {:.4} +- {s:.4}, truth {:.4}",
                    g[i][k], t[i][k]
                );
                assert!(
                    (g[i][k] - t[i][k]).abs() < 3.0 * s,
                    "{dir:?} point {i}: {:?} vs {:?}",
                    g[i],
                    t[i]
                );
            }
        }
    }
    for name in ["eq2b_b", "eq3b_b", "eq4_a", "eq5b_b", "eq6_c"] {
        let (g, t) = (
            got.coefficients().get(name).unwrap(),
            truth.coefficients().get(name).unwrap(),
        );
        let s = std[name].as_f64().unwrap();
        eprintln!("{name}: fit {g:.4} +- {s:.4}, truth {t:.4}");
        assert!((g - t).abs() < 3.0 * s, "{name}: {g} +- {s} vs {t}");
    }
    // What was recovered within a few standard errors is not called undetermined (until
    // 2026-11-30 the cracking torques were, next to standard errors of 0.2 on 100), and
    // what has no finite standard error is.
    let id = &v["identifiability"];
    let undetermined: Vec<&str> = id["undetermined"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    eprintln!("undetermined: {undetermined:?}");
    for name in [
        "positive.T_c",
        "negative.T_c",
        "eq2b_b",
        "eq3b_b",
        "eq4_a",
        "eq5b_b",
        "eq6_c",
    ] {
        assert!(!undetermined.contains(&name), "{name} named undetermined");
    }
    for (name, rel) in id["relative_std"].as_array().unwrap().iter().map(|p| {
        (
            p[0].as_str().unwrap(),
            p[1].as_f64().unwrap_or(f64::INFINITY),
        )
    }) {
        assert_eq!(undetermined.contains(&name), rel > 0.5, "{name}: {rel}");
    }
}

/// With another noise draw the fit from the idealised start stops 3.8 %
/// above the truth's NRMSE: it put the positive peak at a twist of 5.42,
/// past the amplitude 5.0, where the truth has it at 4.2, and a local fit
/// cannot move a breakpoint across an amplitude (the unloading from 5.0
/// changes segment there). `hyst fit` also starts from each breakpoint moved
/// to the neighbouring gaps between amplitudes, and the best of those
/// explains the record as well as the truth does. (Of twelve noise draws,
/// four stopped 3.5-4.6 % above the truth from the idealised start alone,
/// all with that peak past 5.0; with the starts all twelve reach 0.990-0.994
/// of the truth's NRMSE.)
#[test]
fn another_start_moves_a_breakpoint_across_an_amplitude() {
    let (_, x, clean, noisy) = noisy_truth(3 * 7919);
    let truth_nrmse = nrmse(&noisy, &clean);
    // The idealised start alone, as the fit was before the other starts.
    let curves: Vec<_> = [1.0, -1.0]
        .map(|sign| {
            let env = first_excursions(&x, &noisy, sign);
            fit_envelope(&env, &valid_start(&idealise(&env).unwrap()))
        })
        .into();
    let start = PhmParams::new(&curves[0], &curves[1], Coefficients::thesis()).unwrap();
    let alone = PhmProblem::new(&x, &noisy, ["deg", "kN m"], &start, &[])
        .unwrap()
        .solve(|_, _| {})
        .unwrap();
    let peak = alone.params.primary(Direction::Positive).points()[2][0];
    eprintln!(
        "idealised start alone: NRMSE {:.5} ({:.3} of the truth's), positive peak at {peak:.3}",
        alone.nrmse,
        alone.nrmse / truth_nrmse
    );
    assert!(alone.nrmse > 1.03 * truth_nrmse && peak > 5.0);

    let data = record_file("record_amplitude.csv", &x, &noisy);
    let o = ok(hyst(&["fit", &data, "--model", "phm-torsion", "--json"]));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let fitted = v["nrmse"].as_f64().unwrap();
    eprintln!("hyst fit: NRMSE {fitted:.5}, start: {}", v["start"]);
    assert!(
        fitted < truth_nrmse,
        "{fitted} against the truth's {truth_nrmse}"
    );
    assert!(v["starts"].as_u64().unwrap() > 1);
    assert!(v["start"].as_str().unwrap().contains("positive point 2"));
}

#[test]
fn errors_name_the_file_and_what_was_expected() {
    let p = write("truth_err.json", TRUTH);
    let disp = write("disp.csv", "displacement (mm)\n0\n1\n");
    let e = err(hyst(&["simulate", &disp, "--params", &p]));
    assert!(
        e.contains("disp.csv: the PHM needs a twist column")
            && e.contains("found 'displacement (mm)' in mm"),
        "{e}"
    );

    let twist_mm = write("twist_mm.csv", "twist (mm)\n0\n1\n");
    let e = err(hyst(&["simulate", &twist_mm, "--params", &p]));
    assert!(
        e.contains("twist_mm.csv:1:1: column 'twist (mm)' is named like angle but its unit mm is a length unit"),
        "{e}"
    );

    let bad_row = write("bad_row.csv", "twist (deg)\n0\nabc\n");
    let e = err(hyst(&["simulate", &bad_row, "--params", &p]));
    assert!(e.contains("bad_row.csv:3:1"), "{e}");

    let bad_coef = write(
        "bad_coef.json",
        r#"{"model": "phm-torsion", "primary": {"positive": [[1, 5], [4, 6.5]]}, "coefficients": {"eq7": 1}}"#,
    );
    let h = write("h.csv", "twist (deg)\n0\n1\n");
    let e = err(hyst(&["simulate", &h, "--params", &bad_coef]));
    assert!(
        // Placed at the value: column 95 of the one line.
        e.contains("bad_coef.json:1:95: \"eq7\" is not a PHM coefficient"),
        "{e}"
    );

    let bad_json = write(
        "bad_json.json",
        "{\"model\": \"phm-torsion\",\n  \"primary\": }",
    );
    let e = err(hyst(&[
        "simulate",
        &h,
        "--model",
        "phm-torsion",
        "--params",
        &bad_json,
    ]));
    assert!(e.contains("bad_json.json:2:"), "{e}");

    let e = err(hyst(&["simulate", &h, "--model", "bw", "--params", &p]));
    assert!(
        e.contains("a PHM parameter file (model phm-torsion), but --model bw"),
        "{e}"
    );

    let bw = write(
        "bw.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1}"#,
    );
    let e = err(hyst(&[
        "simulate",
        &h,
        "--model",
        "phm-torsion",
        "--params",
        &bw,
    ]));
    assert!(
        e.contains("bw.json:1:11: \"model\" is \"bw\": expected \"phm-torsion\""),
        "{e}"
    );

    let e = err(hyst(&["fit", &h, "--model", "phm-torsion"]));
    assert!(e.contains("h.csv: expected a torque column"), "{e}");

    let rec = write(
        "rec.csv",
        "twist (deg),torque (kN m)\n0,0\n0.1,10\n0.2,20\n-0.1,-10\n",
    );
    let e = err(hyst(&["fit", &rec, "--model", "phm-torsion"]));
    assert!(
        e.contains("rec.csv: the positive direction has 2 samples"),
        "{e}"
    );
    let fit_fixing = |fixes: &[&str]| {
        let mut args = vec![
            "fit",
            rec.as_str(),
            "--model",
            "phm-torsion",
            "--params",
            &p,
        ];
        for f in fixes {
            args.extend(["--fix", f]);
        }
        err(hyst(&args))
    };
    let e = fit_fixing(&["eq9=1"]);
    assert!(
        e.contains("--fix eq9: not a variable of this fit") && e.contains("positive.theta_c"),
        "{e}"
    );
    let e = fit_fixing(&["eq4_a=0.5", "eq4_a=0.6"]);
    assert!(e.contains("`eq4_a` is fixed twice"), "{e}");
    let e = err(hyst(&["fit", &rec, "--model", "bw"]));
    assert!(e.contains("a twist/torque record"), "{e}");

    // Units hold twist and torque only; a curve holds at most PHM_POINTS (8) points here.
    let extra = write(
        "units_extra.json",
        &TRUTH.replace(r#""torque": "kN m""#, r#""torque": "kN m", "force": "kN""#),
    );
    let e = err(hyst(&["simulate", &h, "--params", &extra]));
    assert!(e.contains(r#""units" has a key "force""#), "{e}");
    let nine: Vec<String> = (1..=9).map(|i| format!("[{}, {}]", i, 100 + i)).collect();
    let nine = write(
        "nine.json",
        &format!(
            r#"{{"model": "phm-torsion", "primary": {{"positive": [{}]}}}}"#,
            nine.join(", ")
        ),
    );
    let e = err(hyst(&["simulate", &h, "--params", &nine]));
    assert!(
        e.contains("primary.positive has 9 points; a curve here has at most 8"),
        "{e}"
    );
}

/// Found by review: with a start file, a record whose torque is zero throughout hung the fit
/// (its NaN Jacobian never left nalgebra's SVD), and a one-sample record "fitted" to NRMSE 0
/// with every standard error 0. Both are refused, as the Bouc-Wen fits refuse them.
#[test]
fn records_without_anything_to_fit_are_refused() {
    let start = write("nothing_start.json", TRUTH);
    let zero = write(
        "zero_torque.csv",
        "twist (deg),torque (kN m)\n0,0\n1,0\n2,0\n1,0\n",
    );
    let e = err(hyst(&[
        "fit",
        &zero,
        "--model",
        "phm-torsion",
        "--params",
        &start,
    ]));
    assert!(
        e.contains("expected the torque to vary, found 0 kN m in every sample: nothing to fit"),
        "{e}"
    );
    let one = write(
        "one_sample.csv",
        "twist (deg),torque (kN m)\n0.5,10\n0.7,12\n",
    );
    let e = err(hyst(&[
        "fit",
        &one,
        "--model",
        "phm-torsion",
        "--params",
        &start,
    ]));
    assert!(
        e.contains("the record has 2 samples, too few to fit the"),
        "{e}"
    );
}
