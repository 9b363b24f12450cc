//! Cross-checks against OpenSees (`../shared/data/opensees-reference/`).
//!
//! With OpenSees' conventions switched on (one backward-Euler step per
//! increment, energy in kN*mm with the end-of-step z, OpenSees' Zu), our model
//! reproduces its `BoucWen` and `BWBN` outputs to 1e-9 kN. With our own
//! error-controlled integrator we measure how far OpenSees is from the
//! converged solution.

mod common;

use hysteresis::bwbn::{Bwbn, BwbnParams, Control, EffectKind, EffectSet, Method, ZuRule};
use hysteresis::Element;

/// The parameter sets of the reference cases (`cases.json`), translated to
/// our names in [`common::reference_params`]: the case picks the effects.
fn case_params(case: &str) -> BwbnParams<f64> {
    let set = match case {
        "BoucWen_plain" | "BWBN_plain" | "BoucWenOriginal_plain" => EffectSet::NONE,
        "BoucWen_degrade" => EffectSet::NONE
            .with(EffectKind::ADegradation)
            .with(EffectKind::StrengthDegradation)
            .with(EffectKind::StiffnessDegradation),
        "BWBN_pinch" => EffectSet::NONE.with(EffectKind::Pinching),
        other => panic!("no such case {other}"),
    };
    common::reference_params(set).with_zu_rule(ZuRule::OpenSees)
}

fn run(params: BwbnParams<f64>, control: Control<f64>, history: &[f64]) -> Vec<(f64, f64)> {
    let mut el = Bwbn::with_extra(params, (), control).unwrap();
    history
        .iter()
        .map(|&u| {
            let r = el
                .set_trial(u)
                .unwrap_or_else(|e| panic!("step to {u}: {e}"));
            el.commit();
            (r.force, el.committed().energy)
        })
        .collect()
}

const CASES: [&str; 5] = [
    "BoucWen_plain",
    "BWBN_plain",
    "BoucWenOriginal_plain",
    "BoucWen_degrade",
    "BWBN_pinch",
];

#[test]
fn opensees_scheme_reproduces_opensees_to_1e_9_kn() {
    let history = common::reference_history();
    for case in CASES {
        let reference = common::reference_case(case);
        let ours = run(case_params(case), Control::opensees(1e-12, 100), &history);
        let worst = ours
            .iter()
            .zip(&reference)
            .map(|((f, _), (_, g))| (f - g).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 1e-9, "{case}: worst difference {worst:e} kN");
    }
}

/// The converged solution, computed two independent ways (Dormand-Prince 5(4)
/// and Bogacki-Shampine 3(2) at tight tolerances) that must agree.
fn converged(params: BwbnParams<f64>, history: &[f64]) -> Vec<f64> {
    let dp = run(
        params,
        Control {
            method: Method::Dp54,
            tol: 1e-12,
            max_substeps: 60_000,
        },
        history,
    );
    let bs = run(
        params,
        Control {
            method: Method::Bs32,
            tol: 1e-11,
            max_substeps: 60_000,
        },
        history,
    );
    let peak = dp.iter().fold(0.0f64, |a, (f, _)| a.max(f.abs()));
    let gap = dp
        .iter()
        .zip(&bs)
        .map(|(a, b)| (a.0 - b.0).abs())
        .fold(0.0, f64::max);
    assert!(gap <= 1e-9 * peak, "references disagree by {gap:e} kN");
    dp.into_iter().map(|(f, _)| f).collect()
}

#[test]
fn default_integration_is_within_1e_6_of_peak_force() {
    let history = common::reference_history();
    for case in ["BoucWen_plain", "BoucWen_degrade", "BWBN_pinch"] {
        let params = case_params(case).with_zu_rule(ZuRule::Thesis);
        let exact = converged(params, &history);
        let peak = exact.iter().fold(0.0f64, |a, f| a.max(f.abs()));
        let ours = run(params, Control::default_for(), &history);
        let worst = ours
            .iter()
            .zip(&exact)
            .map(|((f, _), g)| (f - g).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 1e-6 * peak, "{case}: {:e} of peak", worst / peak);
    }
}

/// OpenSees' one-step backward Euler is first order: on the reference history
/// it is 0.47 kN (3.3% of the 14.4 kN peak) off the converged solution right
/// after reversals (README of the reference data). Our converged solution
/// confirms it.
#[test]
fn opensees_is_off_the_converged_answer_after_reversals() {
    let history = common::reference_history();
    let exact = converged(
        case_params("BoucWen_plain").with_zu_rule(ZuRule::Thesis),
        &history,
    );
    let reference = common::reference_case("BoucWen_plain");
    let errors: Vec<f64> = reference
        .iter()
        .zip(&exact)
        .map(|((_, g), f)| (g - f).abs())
        .collect();
    let (worst_i, worst) =
        errors
            .iter()
            .enumerate()
            .fold((0, 0.0), |a, (i, &e)| if e > a.1 { (i, e) } else { a });
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    assert!(
        (0.46..0.48).contains(&worst),
        "worst OpenSees error {worst} kN"
    );
    assert!((0.09..0.10).contains(&rms), "RMS OpenSees error {rms} kN");
    // The worst point lies within a few steps after a reversal: the
    // displacement increment changes sign just before it.
    let du = |i: usize| history[i] - history[i - 1];
    assert!(
        (1..=6).any(|back| du(worst_i - back + 1) * du(worst_i - back) < 0.0),
        "worst at step {worst_i}"
    );
}
