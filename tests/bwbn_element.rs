//! Analytic limits and element-API properties of the BWBN element.

mod common;

use hysteresis::bwbn::{
    BoucWen, Bwbn, BwbnParams, Control, EffectKind, EffectSet, Method, ParamError, Rule, Sdof,
};
use hysteresis::{Element, StepError};

fn named(set: EffectSet, extra: &[(&str, f64)]) -> BwbnParams<f64> {
    BwbnParams::from_named(set, |n| {
        extra
            .iter()
            .find(|(k, _)| *k == n)
            .map(|(_, v)| *v)
            .or(match n {
                "k0" => Some(6.0),
                "alpha" => Some(0.2),
                "n" => Some(1.2),
                "beta" => Some(2.0),
                "gamma" => Some(-1.0),
                _ => None,
            })
    })
    .unwrap()
}

/// All four thesis effects at the strength of the OpenSees reference cases.
fn full() -> BwbnParams<f64> {
    common::reference_params(EffectSet::BWBN)
}

fn drive(el: &mut Bwbn<f64>, history: &[f64]) -> Vec<f64> {
    history
        .iter()
        .map(|&u| {
            let r = el.set_trial(u).unwrap();
            el.commit();
            r.force
        })
        .collect()
}

#[test]
fn alpha_one_is_linear_elastic() {
    let p = BwbnParams::plain(BoucWen::new(6.0, 1.0, 1.2, 2.0, -1.0).unwrap());
    let mut el = Bwbn::new(p);
    for u in common::reference_history() {
        let r = el.set_trial(u).unwrap();
        el.commit();
        assert!(
            (r.force - 6.0 * u).abs() <= 1e-12 * (1.0 + u.abs()),
            "R({u}) = {}",
            r.force
        );
        assert_eq!(r.tangent, 6.0);
    }
}

#[test]
fn z_tends_to_zu_under_monotonic_loading() {
    // Zu = (A0 / (nu0 (beta + gamma)))^(1/n) (eq. 3.12), also with A0 and nu0 != 1.
    for (a0, nu0) in [(1.0, 1.0), (1.5, 1.0), (1.0, 0.7), (2.0, 1.3)] {
        let set = EffectSet::NONE
            .with(EffectKind::ADegradation)
            .with(EffectKind::StrengthDegradation);
        let p = named(set, &[("A0", a0), ("nu0", nu0)]);
        let zu = (a0 / (nu0 * 1.0f64)).powf(1.0 / 1.2);
        let mut el = Bwbn::new(p);
        let mut last = 0.0;
        for i in 1..=400 {
            el.set_trial(i as f64 * 0.05).unwrap();
            el.commit();
            let z = el.committed().z;
            assert!(
                z >= last && z < zu * (1.0 + 1e-12),
                "z must rise monotonically towards Zu"
            );
            last = z;
        }
        assert!(
            (last - zu).abs() < 1e-6 * zu,
            "A0 {a0}, nu0 {nu0}: z = {last}, Zu = {zu}"
        );
        // and the tangent has fallen to the post-yield stiffness alpha k0
        assert!((el.response().tangent - 1.2).abs() < 1e-5);
    }
}

/// The tangent is the derivative of the force with respect to the trial
/// displacement. The finite differences are taken on a tightly converged
/// element (tolerance 1e-12), because an adaptive integrator's force is smooth
/// in the trial displacement only to within its tolerance: at the default
/// 1e-9, differences over 1e-6 mm would measure that tolerance, not the
/// tangent.
#[test]
fn tangent_matches_finite_differences() {
    let history = common::reference_history();
    let tight = Control {
        method: Method::Dp54,
        tol: 1e-12,
        max_substeps: 60_000,
    };
    for params in [named(EffectSet::NONE, &[]), full()] {
        let mut el = Bwbn::new(params);
        let mut reference = Bwbn::new(params).with_control(tight).unwrap();
        let mut checked = 0;
        for (i, &u) in history.iter().enumerate() {
            let r = el.set_trial(u).unwrap();
            reference.set_trial(u).unwrap();
            if i % 7 == 5 && u != history[i - 1] {
                let d = 1e-6;
                let fp = reference.set_trial(u + d).unwrap().force;
                let fm = reference.set_trial(u - d).unwrap().force;
                let fd = (fp - fm) / (2.0 * d);
                assert!(
                    (fd - r.tangent).abs() <= 1e-6 * r.tangent.abs().max(1.2),
                    "step {i}: tangent {} vs finite difference {fd}",
                    r.tangent
                );
                reference.set_trial(u).unwrap();
                checked += 1;
            }
            el.commit();
            reference.commit();
        }
        assert!(checked > 500);
    }
}

/// Over every closed cycle of the reference history the work done on the
/// element, the loop area, is positive, and the model's hysteretic energy
/// never ends a cycle lower than it started.
#[test]
fn dissipated_energy_is_never_negative_over_a_closed_cycle() {
    let history = common::reference_history();
    for params in [named(EffectSet::NONE, &[]), full()] {
        let mut el = Bwbn::new(params);
        let forces = drive(&mut el, &history);
        let mut el2 = Bwbn::new(params);
        let energy: Vec<f64> = history
            .iter()
            .map(|&u| {
                el2.set_trial(u).unwrap();
                el2.commit();
                el2.committed().energy
            })
            .collect();
        // cycles: 200 steps each, starting at u = 0
        for c in 0..18 {
            let (a, b) = (c * 200, (c + 1) * 200);
            let work: f64 = (a..b)
                .map(|i| 0.5 * (forces[i] + forces[i + 1]) * (history[i + 1] - history[i]))
                .sum();
            assert!(work > 0.0, "cycle {c}: loop area {work}");
            assert!(energy[b] >= energy[a], "cycle {c}: energy fell");
        }
    }
}

#[test]
fn a_trial_never_changes_the_committed_state() {
    let mut el = Bwbn::new(full());
    drive(&mut el, &[0.5, 1.0, 2.0, 1.5]);
    let committed = *el.committed();
    let before = el.response();
    let a = el.set_trial(3.0).unwrap();
    assert_eq!(*el.committed(), committed);
    let b = el.set_trial(-2.0).unwrap();
    assert_eq!(*el.committed(), committed);
    el.revert();
    assert_eq!(el.response(), before);
    assert_eq!(*el.trial(), committed);
    // the same trial from the same committed state is bit-identical
    assert_eq!(el.set_trial(3.0).unwrap(), a);
    assert_eq!(el.set_trial(-2.0).unwrap(), b);
    el.commit();
    assert_eq!(el.displacement(), -2.0);
    el.reset();
    assert_eq!(el.displacement(), 0.0);
    assert_eq!(el.response().force, 0.0);
    assert!((el.response().tangent - 6.0).abs() < 1e-14);
}

#[test]
fn non_finite_input_is_refused_and_leaves_the_state_unchanged() {
    let mut el = Bwbn::new(full());
    drive(&mut el, &[0.5, 1.0]);
    el.set_trial(1.5).unwrap();
    let (committed, trial, response) = (*el.committed(), *el.trial(), el.response());
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(el.set_trial(bad), Err(StepError::NonFiniteInput));
        assert_eq!(
            (*el.committed(), *el.trial(), el.response()),
            (committed, trial, response)
        );
    }
}

#[test]
fn a_step_over_budget_fails_without_touching_the_state() {
    let starved = Control {
        method: Method::Dp54,
        tol: 1e-14,
        max_substeps: 2,
    };
    let mut el = Bwbn::new(named(EffectSet::NONE, &[]))
        .with_control(starved)
        .unwrap();
    let (committed, response) = (*el.committed(), el.response());
    assert_eq!(el.set_trial(4.0), Err(StepError::ToleranceNotMet));
    assert_eq!(
        (*el.committed(), *el.trial(), el.response()),
        (committed, committed, response)
    );
}

/// A control an element cannot integrate with is refused when the element takes it, by field.
/// With `tol = -1` every sub-step passed its error test and one Dormand-Prince step across
/// 10 mm (Zu = 1) returned z = -685356 with `Ok`.
#[test]
fn a_control_that_cannot_bound_the_error_is_refused_by_name() {
    let bad = [
        (-1.0, 1000, "tol", Rule::NotPositive),
        (0.0, 1000, "tol", Rule::NotPositive),
        (f64::NAN, 1000, "tol", Rule::NotFinite),
        (f64::INFINITY, 1000, "tol", Rule::NotFinite),
        (1e-9, 0, "max_substeps", Rule::NotPositive),
    ];
    let plain = BwbnParams::plain(BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).unwrap());
    for (tol, max_substeps, field, rule) in bad {
        let control = Control {
            method: Method::Dp54,
            tol,
            max_substeps,
        };
        let expected = Err(ParamError { field, rule });
        assert_eq!(Bwbn::new(plain).with_control(control).map(|_| ()), expected);
        assert_eq!(Bwbn::with_extra(plain, (), control).map(|_| ()), expected);
        let osc = Sdof::new(plain, 0.05).unwrap().with_control(control);
        assert_eq!(osc.map(|_| ()), expected);
        assert_eq!(
            Sdof::with_extra(plain, 0.05, (), control).map(|_| ()),
            expected
        );
    }
    // The same step with a valid control ends just below the asymptote: z tends to Zu = 1, so
    // the force to alpha k0 u + (1 - alpha) k0 Zu.
    let mut el = Bwbn::new(plain)
        .with_control(Control {
            method: Method::Dp54,
            tol: 1e-9,
            max_substeps: 1000,
        })
        .unwrap();
    let f = el.set_trial(10.0).unwrap().force;
    let asymptote = 0.2 * 6.0 * 10.0 + 0.8 * 6.0;
    assert!(f < asymptote && asymptote - f < 1e-4, "{f}");
}

/// With beta < 0 unloading is softer than loading and the energy `∫ z du` falls below zero,
/// where no degradation or pinching function was validated: such a set is refused once an
/// effect reads the energy, and stays legal plain Bouc-Wen, whose energy then does go negative.
#[test]
fn a_negative_beta_is_refused_where_the_energy_is_read() {
    let values = |n: &str| match n {
        "k0" => Some(1.0),
        "alpha" => Some(0.0),
        "n" => Some(1.0),
        "beta" => Some(-0.25),
        "gamma" => Some(0.75),
        "nu0" => Some(1.0),
        "delta_nu" => Some(0.01),
        _ => None,
    };
    let refused = BwbnParams::from_named(
        EffectSet::NONE.with(EffectKind::StrengthDegradation),
        values,
    );
    assert_eq!(
        refused.map(|_| ()),
        Err(ParamError {
            field: "beta",
            rule: Rule::EnergyCanFallBelowZero
        })
    );
    let plain = BwbnParams::from_named(EffectSet::NONE, values).unwrap();
    let mut el = Bwbn::new(plain);
    for u in [1.0, 2.0, 3.0, 2.0, 1.0, 0.0] {
        el.set_trial(u).unwrap();
        el.commit();
    }
    assert!(el.committed().energy < 0.0, "{:?}", el.committed());
}

#[test]
fn energy_beyond_the_validated_range_is_refused() {
    let set = EffectSet::NONE.with(EffectKind::StrengthDegradation);
    let p = named(set, &[("delta_nu", -1e-3), ("energy_limit", 50.0)]);
    let mut el = Bwbn::new(p);
    let mut failed = None;
    for u in common::reference_history() {
        match el.set_trial(u) {
            Ok(_) => el.commit(),
            Err(e) => {
                failed = Some(e);
                break;
            }
        }
    }
    assert_eq!(failed, Some(StepError::EnergyOutOfRange));
    assert!(el.committed().energy <= 50.0);
}

#[test]
fn hardening_sets_are_legal_and_diverge_with_an_error_not_a_nan() {
    // beta + gamma < 0: the Bouc-Wen benchmark's hysteretic spring (per metre).
    let p = BwbnParams::plain(BoucWen::new(1e5, 0.5, 1.0, 800.0, -1100.0).unwrap());
    assert_eq!(p.zu(), None);
    let mut el = Bwbn::new(p);
    for u in [1e-4, 5e-4, 1e-3, -1e-3] {
        el.set_trial(u).unwrap();
        el.commit();
    }
    // Loading on: dz/du = 1 + 300 |z|, so z grows like e^(300 u) / 300,
    // beyond f64's range before u = 3 m. Within the default budget the step
    // gives up; with a budget large enough to follow it, the state overflows.
    let committed = *el.committed();
    assert_eq!(el.set_trial(3.0), Err(StepError::ToleranceNotMet));
    let patient = Control {
        method: Method::Dp54,
        tol: 1e-9,
        max_substeps: u16::MAX,
    };
    let mut el = el.with_control(patient).unwrap();
    assert_eq!(el.set_trial(3.0), Err(StepError::NonFiniteState));
    assert_eq!(*el.committed(), committed);
}

/// Asymmetry (not in the thesis): z tends to Zu (1 + a) on the positive side
/// and -Zu (1 - a) on the negative; the springs are (1 + b) k0 and (1 - b) k0,
/// and the force stays continuous through u = 0 and z = 0.
#[test]
fn asymmetry_gives_unequal_strength_and_stiffness() {
    let (a, b) = (0.25, 0.1);
    let p = named(
        EffectSet::NONE.with(EffectKind::Asymmetry),
        &[("asym_strength", a), ("asym_stiffness", b)],
    );
    let mut el = Bwbn::new(p);
    let ups: Vec<f64> = (1..=400).map(|i| i as f64 * 0.05).collect();
    let downs: Vec<f64> = (1..=800).map(|i| 20.0 - i as f64 * 0.05).collect();
    drive(&mut el, &ups);
    assert!(
        (el.committed().z - (1.0 + a)).abs() < 1e-6,
        "z+ = {}",
        el.committed().z
    );
    // post-yield tangent on the positive side: alpha k0 (1 + b)
    assert!((el.response().tangent - 1.2 * (1.0 + b)).abs() < 1e-5);
    let forces = drive(&mut el, &downs);
    assert!(
        (el.committed().z + (1.0 - a)).abs() < 1e-6,
        "z- = {}",
        el.committed().z
    );
    assert!((el.response().tangent - 1.2 * (1.0 - b)).abs() < 1e-5);
    // continuity: no jump between consecutive 0.05 mm steps larger than the
    // stiffest spring allows
    let kmax = 6.0 * (1.0 + b) * 4.0;
    for w in forces.windows(2) {
        assert!(
            (w[1] - w[0]).abs() < kmax * 0.05,
            "force jumped from {} to {}",
            w[0],
            w[1]
        );
    }
    // with a = b = 0 the response is the plain one, bit for bit, under the
    // same integrator (the host default sums plain Bouc-Wen as series)
    let off = named(EffectSet::NONE.with(EffectKind::Asymmetry), &[]);
    let dp54 = Control {
        method: Method::Dp54,
        ..Control::default_for()
    };
    let mut plain = Bwbn::new(named(EffectSet::NONE, &[]))
        .with_control(dp54)
        .unwrap();
    let mut zero = Bwbn::new(off).with_control(dp54).unwrap();
    assert_eq!(drive(&mut plain, &ups), drive(&mut zero, &ups));
}

/// In Q15.16 the hysteretic energy of a plain element passes 32767 kN mm after about 400 cycles
/// of +-5 mm. No effect of plain Bouc-Wen reads it, so the element goes on (it refused every
/// dissipating step from cycle 405 on), the energy reads as non-finite (saturated), and the force
/// stays where `f32` has it; a degrading element, which reads the energy, still refuses.
#[test]
fn fixed_point_energy_overflow_stops_only_models_that_read_it() {
    use hysteresis::{Fixed, Scalar};
    fn params<S: Scalar>(set: EffectSet) -> BwbnParams<S> {
        BwbnParams::from_named(set, |n| {
            let v = match n {
                "k0" => 6.0,
                "alpha" => 0.2,
                "n" => 1.2,
                "beta" => 2.0,
                "gamma" => -1.0,
                "delta_nu" => 1e-6,
                _ => return None,
            };
            Some(S::from_f64(v))
        })
        .unwrap()
    }
    let u = |i: usize| 5.0 * (2.0 * std::f64::consts::PI * i as f64 / 40.0).sin();
    let plain = EffectSet::NONE;
    let mut fixed = Bwbn::new(params::<Fixed>(plain));
    let mut float = Bwbn::new(params::<f32>(plain));
    for i in 1..=500 * 40 {
        let r = fixed.set_trial(Fixed::from_f64(u(i)));
        assert!(r.is_ok(), "step {i} (cycle {}): {r:?}", i / 40);
        fixed.commit();
        float.set_trial(u(i) as f32).unwrap();
        float.commit();
    }
    assert!(!fixed.committed().energy.is_finite());
    assert!(float.committed().energy > 32767.0);
    // Within the fixed-point bound, 1e-3 of the peak force (0.2*6*5 + 0.8*6*1 = 10.8 kN).
    let (a, b) = (
        fixed.response().force.to_f64(),
        f64::from(float.response().force),
    );
    assert!((a - b).abs() < 1e-3 * 10.8, "force {a} against f32 {b}");
    // Strength degradation reads the energy: past the arithmetic's range it refuses.
    let mut degrading = Bwbn::new(params::<Fixed>(
        EffectSet::NONE.with(EffectKind::StrengthDegradation),
    ));
    let refused = (1..=500 * 40).find_map(|i| {
        let r = degrading.set_trial(Fixed::from_f64(u(i)));
        degrading.commit();
        r.err()
    });
    assert!(refused.is_some(), "the degrading element never refused");
}
