//! The ladder's backward step (`hyst::discover::ladder::redundant`): an
//! effect the final model does not need is found and taken away; one the
//! record holds is kept. The records come from the project's simulator with
//! a known hidden model, which is the expectation.

use hyst::discover::ladder::{redundant, Step};
use hyst::discover::synthetic::{record, Noise, Path};
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec};
use hysteresis::bwbn::EffectKind;

const STRENGTH: EffectRef = EffectRef::Builtin(EffectKind::StrengthDegradation);
const STIFFNESS: EffectRef = EffectRef::Builtin(EffectKind::StiffnessDegradation);

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
    }
}
