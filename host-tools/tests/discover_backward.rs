//! The ladder's backward step (`hyst::discover::ladder::redundant`): an
//! effect the final model does not need is found and taken away; one the
//! record holds is kept. And the effects a user gives with the model, which
//! the loop keeps (`unneeded`): named when the record does not need them.
//! The records come from the project's simulator with a known hidden model,
//! which is the expectation.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, write, write_record};
use hyst::discover::ladder::{redundant, unneeded, Step};
use hyst::discover::synthetic::{hidden_values, record, Noise, Path, BASE};
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec};
use hysteresis::bwbn::EffectKind;

const STRENGTH: EffectRef = EffectRef::Builtin(EffectKind::StrengthDegradation);
const STIFFNESS: EffectRef = EffectRef::Builtin(EffectKind::StiffnessDegradation);
const PINCHING: EffectRef = EffectRef::Builtin(EffectKind::Pinching);

/// `bw+strength-degradation+stiffness-degradation` fitted to a record that
/// hides `hidden`, as the final step of a ladder.
fn final_step(hidden: &[EffectKind], seed: u64) -> Step {
    let exp = record(hidden, Path::StepWise, Noise::LOW, seed).unwrap();
    let spec = ModelSpec::BW.with(STRENGTH).with(STIFFNESS);
    // The initial values the ladder holds at 1 when it adds these effects.
    let fixed = [("nu0".to_string(), 1.0), ("eta0".to_string(), 1.0)];
    let problem = Problem::new(spec, exp, &fixed).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    Step::diagnosed(problem, outcome).unwrap()
}

#[test]
fn an_effect_the_record_lacks_is_taken_away_and_one_it_holds_is_kept() {
    for seed in [1, 2] {
        // Strength degradation hidden: stiffness degradation is not needed.
        let step = final_step(&[EffectKind::StrengthDegradation], seed);
        let r = redundant(&step, &[], &[]).expect("stiffness degradation is redundant");
        assert_eq!(r.effect, STIFFNESS, "seed {seed}");
        assert!(r.delta_bic < 2.0, "seed {seed}: {}", r.delta_bic);
        assert_eq!(r.problem.par.spec, ModelSpec::BW.with(STRENGTH));
        // The refit without it is as good as the fit with it, to the noise.
        let (with, without) = (step.outcome.scores.nrmse, r.outcome.scores.nrmse);
        assert!(
            without < with * 1.02,
            "seed {seed}: {without} against {with}"
        );
        // Kept (an effect of the first model): nothing else to take away.
        assert!(redundant(&step, &[STIFFNESS], &[]).is_none(), "seed {seed}");
        // ...but named as one the record does not need, and only it.
        let given = [STRENGTH, STIFFNESS];
        let named = unneeded(&step.problem, &step.outcome, &step.diagnosis, &given, &[]);
        let names: Vec<&str> = named.iter().map(|u| u.effect).collect();
        assert_eq!(names, ["stiffness-degradation"], "seed {seed}");
        assert_eq!(named[0].nrmse_with, with);
        assert!(named[0].nrmse_without < with * 1.02, "seed {seed}");

        // Both hidden: both stay.
        let step = final_step(
            &[
                EffectKind::StrengthDegradation,
                EffectKind::StiffnessDegradation,
            ],
            seed,
        );
        if let Some(r) = redundant(&step, &[], &[]) {
            panic!(
                "seed {seed}: {} taken away at {:+.1}",
                r.effect.name(),
                r.delta_bic
            );
        }
        let given = [STRENGTH, STIFFNESS];
        let named = unneeded(&step.problem, &step.outcome, &step.diagnosis, &given, &[]);
        assert!(named.is_empty(), "seed {seed}: {named:?}");
    }
}

/// `hyst diagnose` on a record with nothing hidden, given `bw+pinching`,
/// says that the record does not need pinching (text and JSON); on a record
/// with pinching hidden it says nothing of the kind.
#[test]
fn diagnose_names_a_given_effect_the_record_does_not_need() {
    for (hidden, name) in [(vec![], "plain"), (vec![EffectKind::Pinching], "pinched")] {
        let exp = record(&hidden, Path::StepWise, Noise::LOW, 3).unwrap();
        let csv = write_record(&format!("{name}.csv"), &exp);
        let spec = ModelSpec::BW.with(PINCHING).to_string();
        // Weighing no candidate keeps the test to the one removal.
        let args = [
            "diagnose",
            &csv,
            "--model",
            &spec,
            "--candidates",
            "asymmetry",
        ];
        let json = ok(hyst(&[&args[..], &["--json"]].concat())).stdout;
        let v: serde_json::Value = serde_json::from_slice(&json).unwrap();
        let named = v["not_needed"].as_array().expect("a list");
        if hidden.is_empty() {
            assert_eq!(named.len(), 1, "{name}: {v}");
            assert_eq!(named[0]["effect"], "pinching", "{name}: {v}");
            let delta = named[0]["delta_bic"].as_f64().unwrap();
            assert!(delta < 2.0, "{name}: {delta}");
            // Without pinching's six parameters the fit is as good, to the noise.
            let (with, without) = (
                named[0]["nrmse_with"].as_f64().unwrap(),
                named[0]["nrmse_without"].as_f64().unwrap(),
            );
            assert!(without < 1.02 * with, "{name}: {without} against {with}");
            let text = String::from_utf8(ok(hyst(&args)).stdout).unwrap();
            assert!(
                text.contains("effects of the model the record does not need:\n  pinching: "),
                "{text}"
            );
        } else {
            assert!(named.is_empty(), "{name}: {v}");
            // Given parameters are not fitted, and each removal is: a poor given set (k0 at
            // 80% of the truth) made a decisive pinching "not needed" (found by review), so
            // `--params` weighs no removal.
            let mut given: Vec<String> = BASE
                .iter()
                .chain(hidden_values(EffectKind::Pinching))
                .map(|(k, v)| match *k {
                    "k0" => format!("\"k0\": {}", 0.8 * v),
                    _ => format!("\"{k}\": {v}"),
                })
                .collect();
            given.push(format!("\"model\": \"{spec}\""));
            let params = write("poor.json", &format!("{{{}}}", given.join(", ")));
            let json = ok(hyst(
                &[&args[..], &["--params", &params, "--json"]].concat(),
            ))
            .stdout;
            let v: serde_json::Value = serde_json::from_slice(&json).unwrap();
            assert_eq!(v["not_needed"], serde_json::json!([]), "{name}: {v}");
        }
    }
}
