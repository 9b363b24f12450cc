//! Rate dependence, the effect the library does not model: the diagnosis must
//! name it on a record that has it, and stay silent where it is absent or
//! where the test cannot tell it from a rate-independent misfit.
//!
//! Records: the synthetic base of `hyst::discover::synthetic` along its
//! earthquake-like path (sampled every 0.02 s, so the speed of loading varies
//! from sample to sample) or its step-wise path (triangular cycles of 60
//! samples at a constant period, so the speed is `sgn(v)` times a multiple of
//! the amplitude), with a dashpot `c v` added to the force or not, and noise.

use hyst::discover::rate;
use hyst::discover::synthetic::{path, record, Noise, Path, BASE};
use hyst::discover::Diagnosis;
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

fn check(exp: Experiment, t: &[f64]) -> rate::RateCheck {
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    rate::check(&d, t, outcome.scores.nrmse).expect("a time base and varying speed")
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
        // Fitted to the residual of the rate-independent fit, which has
        // absorbed part of the dashpot into a wider loop: a lower bound.
        assert!(
            r.viscous > 0.0 && r.viscous <= 1.1 * c,
            "seed {seed}: c = {} against {c}: {}",
            r.viscous,
            r.evidence
        );
    }
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
    // Pinching and strength degradation hidden, no dashpot: the misfit of
    // plain Bouc-Wen is large, but it does not grow with speed.
    for (hidden, seed) in [
        (EffectKind::Pinching, 4),
        (EffectKind::StrengthDegradation, 5),
    ] {
        let exp = record(&[hidden], Path::Irregular(seed), Noise::HIGH, seed).unwrap();
        let t: Vec<f64> = (0..exp.input.len()).map(|i| i as f64 * DT).collect();
        let r = check(exp, &t);
        assert!(!r.significant, "{}: {}", hidden.name(), r.evidence);
    }
}

#[test]
fn a_test_at_constant_period_cannot_show_it() {
    // Triangular cycles at a constant period: the speed is sgn(v) times a
    // multiple of the amplitude, which a rate-independent misfit can mimic,
    // so even a real dashpot is not named.
    let (exp, t) = record_with_dashpot(Path::StepWise, 0.1, 6);
    let r = check(exp, &t);
    assert!(!r.significant, "{}", r.evidence);
    assert!(r.share < 0.01, "{}", r.evidence);
}
