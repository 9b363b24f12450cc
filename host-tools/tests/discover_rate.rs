//! Rate dependence, the effect the library does not model: the diagnosis must
//! name it on a record that has it, with its coefficient, and stay silent
//! where it is absent or an effect of the library explains the record better.
//!
//! Records: the synthetic base of `hyst::discover::synthetic` along its
//! earthquake-like path (sampled every 0.02 s, so the speed of loading varies
//! from sample to sample) or its step-wise path (triangular cycles of 60
//! samples at a constant period, so the speed is `sgn(v)` times a multiple of
//! the amplitude), with a dashpot `c v` added to the force or not, and noise.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, write};
use hyst::discover::rate;
use hyst::discover::synthetic::{path, record, Noise, Path, BASE};
use hyst::discover::{discover, weigh, Diagnosis, WeighOptions};
use hyst::fit::experiment::{Drive, Experiment};
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::ModelSpec;
use hysteresis::bwbn::{Bwbn, EffectKind, ENERGY_LIMIT};
use hysteresis::Element;

const DT: f64 = 0.02;

/// The base model along `which`, with a dashpot `c` (kN s/mm) and noise.
fn record_with_dashpot(which: Path, c: f64, seed: u64) -> (Experiment, Vec<f64>) {
    let (params, _) = ModelSpec::BW
        .build(|n| {
            if n == ENERGY_LIMIT {
                return Some(5000.0);
            }
            BASE.iter().find(|(k, _)| *k == n).map(|(_, v)| *v)
        })
        .unwrap();
    let u = path(which);
    let t: Vec<f64> = (0..u.len()).map(|i| i as f64 * DT).collect();
    let mut el = Bwbn::new(params);
    let last = u.len() - 1;
    let f: Vec<f64> = (0..u.len())
        .map(|i| {
            let r = el.set_trial(u[i]).unwrap().force;
            el.commit();
            let (a, b) = (i.saturating_sub(1), (i + 1).min(last));
            r + c * (u[b] - u[a]) / (t[b] - t[a])
        })
        .collect();
    // Noise at the levels of `Noise::HIGH`.
    let peak = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut gauss = hyst::data::Normal::new(seed);
    let exp = Experiment {
        input: u
            .iter()
            .map(|v| v + Noise::HIGH.displacement * gauss.sample())
            .collect(),
        output: f
            .iter()
            .map(|v| v + Noise::HIGH.force * peak * gauss.sample())
            .collect(),
        drive: Drive::Displacement,
    };
    (exp, t)
}

/// The check on `bw` fitted to `exp`, its candidates weighed.
fn check(exp: Experiment, t: &[f64]) -> rate::RateCheck {
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    let suspects = weigh(&problem, &outcome, &d, &WeighOptions::default());
    rate::of_fit(&problem, &outcome, &d, &suspects, t).expect("a time base")
}

#[test]
fn a_dashpot_is_named_and_its_coefficient_found() {
    // Peak speed about 20 mm/s: c = 0.1 kN s/mm is a viscous force of up to
    // 2 kN against a hysteretic strength of about 19 kN.
    let c = 0.1;
    for seed in [1, 2] {
        let (exp, t) = record_with_dashpot(Path::Irregular(seed), c, seed);
        let r = check(exp, &t);
        assert!(r.significant, "seed {seed}: {}", r.evidence);
        assert!(
            (r.viscous - c).abs() < 0.2 * c,
            "seed {seed}: c = {} against {c}: {}",
            r.viscous,
            r.evidence
        );
        covers(&r, c);
    }
}

/// The interval given for `c` holds the best `c` and the true one.
fn covers(r: &rate::RateCheck, c: f64) {
    let [lo, hi] = r.viscous_interval.expect("an interval where named");
    assert!(
        lo < r.viscous && r.viscous < hi && lo <= c && c <= hi,
        "[{lo}, {hi}] for c = {} against {c}: {}",
        r.viscous,
        r.evidence
    );
}

#[test]
fn nothing_is_named_without_a_dashpot() {
    for seed in [1, 2, 3] {
        let (exp, t) = record_with_dashpot(Path::Irregular(seed), 0.0, seed);
        let r = check(exp, &t);
        assert!(!r.significant, "seed {seed}: {}", r.evidence);
    }
}

#[test]
fn a_library_effect_is_not_mistaken_for_rate_dependence() {
    // Pinching, strength and stiffness degradation hidden, no dashpot: the
    // misfit of plain Bouc-Wen is large, but an effect refitted explains it
    // better than a dashpot, on either path.
    for (hidden, which, seed) in [
        (EffectKind::Pinching, Path::Irregular(4), 4),
        (EffectKind::StrengthDegradation, Path::Irregular(5), 5),
        (EffectKind::StiffnessDegradation, Path::Irregular(7), 7),
        (EffectKind::Pinching, Path::StepWise, 8),
        (EffectKind::StrengthDegradation, Path::StepWise, 9),
    ] {
        let exp = record(&[hidden], which, Noise::HIGH, seed).unwrap();
        let t: Vec<f64> = (0..exp.input.len()).map(|i| i as f64 * DT).collect();
        let r = check(exp, &t);
        assert!(!r.significant, "{}: {}", hidden.name(), r.evidence);
    }
}

#[test]
fn a_test_at_constant_period_shows_it_at_the_reversals() {
    let (exp, t) = record_with_dashpot(Path::StepWise, 0.1, 6);
    let r = check(exp, &t);
    assert!(r.significant, "{}", r.evidence);
    covers(&r, 0.1);
}

/// Along a discovery the dashpot is weighed on the first model, before an
/// effect could stand in for it, and on the final one.
#[test]
fn a_discovery_names_the_dashpot_beside_the_effects_it_adds() {
    let c = 0.1;
    for (which, seed) in [(Path::StepWise, 10), (Path::Irregular(11), 11)] {
        let (exp, t) = record_with_dashpot(which, c, seed);
        let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
        let outcome =
            run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
        let discovery = discover(problem, outcome, &WeighOptions::default(), |_| {}).unwrap();
        let check = rate::of_ladder(&discovery, &t).expect("a time base");
        let ladder: Vec<String> = discovery.steps.iter().map(|s| s.spec.to_string()).collect();
        assert!(check.significant, "{ladder:?}: {}", check.evidence);
        // On the step-wise path the ladder takes pinching for the dashpot
        // (bw+pinching reaches 0.0355, bw with the dashpot alone 0.0298): the
        // evidence says so.
        if which == Path::StepWise {
            assert_eq!(ladder, ["bw", "bw+pinching"]);
            assert!(
                check
                    .evidence
                    .contains("the effects the loop added (pinching) may stand in for the dashpot"),
                "{}",
                check.evidence
            );
        }
        // The refitted loop takes up part of the dashpot: on the irregular
        // path of seed 11 the best fit of `bw` with a dashpot is at c = 0.074
        // (refits at c from 0.05 to 0.13 measured: NRMSE 0.03907 at 0.07 and
        // 0.08, 0.03942 at the true 0.1; the same from the fit of `bw`, from
        // the default starts and from the true parameters), at 0.094 and 0.092
        // for seeds 1 and 2. The interval given, 0.059 to 0.088, holds the
        // record's noise only and misses the truth there; on the step-wise
        // path it holds it.
        assert!(
            check.viscous > 0.5 * c && check.viscous < 1.2 * c,
            "c = {} against {c}: {}",
            check.viscous,
            check.evidence
        );
        if which == Path::StepWise {
            covers(&check, c);
        } else {
            let [lo, hi] = check.viscous_interval.expect("an interval where named");
            assert!(
                lo < check.viscous && check.viscous < hi,
                "{}",
                check.evidence
            );
        }
    }
}

/// The loop the diagnosis asks for: a dashpot named with its coefficient, taken off with
/// `--dashpot` as the record is read, and the effect the ladder had taken for it gone; the
/// option refused where it cannot mean anything, and recorded in a fit file.
#[test]
fn the_dashpot_named_is_taken_off_and_the_effect_it_stood_for_goes() {
    let (exp, t) = record_with_dashpot(Path::StepWise, 0.1, 10);
    let rows: String = (0..t.len())
        .map(|i| format!("{},{},{}\n", t[i], exp.input[i], exp.output[i]))
        .collect();
    let path = write(
        "damped.csv",
        &format!("time (s),displacement (mm),force (kN)\n{rows}"),
    );
    let out = String::from_utf8(ok(hyst(&["discover", &path, "--model", "bw"])).stdout).unwrap();
    assert!(out.contains("bw+pinching"), "{out}");
    let option = out
        .split("`--dashpot ")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .unwrap_or_else(|| panic!("no --dashpot in {out}"));
    let c: f64 = option.parse().unwrap();
    assert!((c - 0.1).abs() < 0.2 * 0.1, "{c}");
    let again = ok(hyst(&[
        "discover",
        &path,
        "--model",
        "bw",
        "--dashpot",
        option,
    ]));
    let note = cli::stderr(&again);
    let out = String::from_utf8(again.stdout).unwrap();
    assert!(
        note.contains("column 'force (kN)': a dashpot's force, ")
            && note.contains(" kN s/mm times the speed of 'displacement (mm)'"),
        "{note}"
    );
    assert!(out.contains("nothing added"), "{out}");
    assert!(!out.contains("bw+pinching"), "{out}");
    let rate = out.split("rate dependence").nth(1).unwrap_or_default();
    assert!(rate.trim_start().starts_with("not significant"), "{out}");

    for (args, expected) in [
        (
            vec!["--dashpot", "-0.1"],
            "expected a positive viscous coefficient for the dashpot",
        ),
        (vec!["--dashpot", "abc"], "invalid value 'abc'"),
    ] {
        let e = cli::err(hyst(
            &[&["fit", &path, "--model", "bw"], &args[..]].concat(),
        ));
        // The option is at fault, not the record.
        assert!(
            e.contains(expected) && !e.contains("damped.csv"),
            "{args:?}: {e}"
        );
    }
    let untimed: String = (0..t.len())
        .map(|i| format!("{},{}\n", exp.input[i], exp.output[i]))
        .collect();
    let untimed = write(
        "untimed.csv",
        &format!("displacement (mm),force (kN)\n{untimed}"),
    );
    let e = cli::err(hyst(&[
        "fit",
        &untimed,
        "--model",
        "bw",
        "--dashpot",
        "0.1",
    ]));
    assert!(
        e.contains("cannot take a dashpot off the force: the record has no sample times"),
        "{e}"
    );

    let file = cli::tmp("damped-fit.json");
    let file = file.to_str().unwrap();
    ok(hyst(&[
        "fit",
        &path,
        "--model",
        "bw",
        "--method",
        "lsq",
        "--dashpot",
        option,
        "--out",
        file,
    ]));
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    assert_eq!(fit["fit"]["dashpot"].as_f64(), Some(c), "{fit}");
    let note = cli::stderr(&ok(hyst(&["simulate", &path, "--params", file])));
    assert!(
        note.contains(&format!(
            "read with `--dashpot {c}`, which is not given here"
        )),
        "{note}"
    );
}
