//! Random and adversarial histories through every combination of effects, with
//! parameters at the edges of their valid ranges: no panic, no non-finite
//! output, and trial/commit/revert stay consistent whatever happens.

use hysteresis::bwbn::{Bwbn, BwbnParams, Control, EffectSet, Method};
use hysteresis::{Element, Fixed, Scalar, StepError};
use proptest::prelude::*;

/// A parameter set from the strategy's raw draws; edges come from picking the
/// ends of each range with high probability.
fn params(bits: u8, v: &[f64; 14]) -> Option<BwbnParams<f64>> {
    let set = EffectSet::from_bits(bits)?;
    let names = [
        "k0",
        "alpha",
        "n",
        "beta",
        "gamma",
        "A0",
        "delta_A",
        "nu0",
        "delta_nu",
        "eta0",
        "delta_eta",
        "zeta0",
        "p",
        "lambda",
    ];
    BwbnParams::from_named(set, |name| {
        if name == "energy_limit" {
            return Some(1e4);
        }
        names.iter().position(|n| *n == name).map(|i| v[i])
    })
    .ok()
}

fn edge(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![Just(lo), Just(hi), lo..hi]
}

fn param_values() -> impl Strategy<Value = [f64; 14]> {
    (
        (
            edge(1e-3, 1e4),
            edge(0.0, 1.0),
            edge(0.3, 6.0),
            edge(0.0, 20.0),
            edge(-20.0, 20.0),
        ),
        (
            edge(0.1, 3.0),
            edge(-0.05, 0.05),
            edge(0.1, 3.0),
            edge(0.0, 0.05),
        ),
        (
            edge(0.1, 3.0),
            edge(0.0, 0.05),
            edge(-1.0, 0.99),
            edge(0.0, 5.0),
            edge(0.05, 3.0),
        ),
    )
        .prop_map(|((a, b, c, d, e), (f, g, h, i), (j, k, l, m, n))| {
            [a, b, c, d, e, f, g, h, i, j, k, l, m, n]
        })
}

/// Increments: ordinary, tiny, zero, huge, and reversal-every-step runs.
fn history() -> impl Strategy<Value = Vec<f64>> {
    let step = prop_oneof![
        4 => -2.0..2.0f64,
        1 => -1e-9..1e-9f64,
        1 => Just(0.0),
        1 => prop_oneof![Just(1e6), Just(-1e6), Just(1e3), Just(-1e3)],
    ];
    let zigzag = (0.0..3.0f64, 2..40usize).prop_map(|(a, n)| {
        (0..n)
            .map(|i| if i % 2 == 0 { a } else { -a })
            .collect::<Vec<_>>()
    });
    let bad = prop::collection::vec(
        (
            0..80usize,
            prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)],
        ),
        0..3,
    );
    (
        prop::collection::vec(prop_oneof![step.prop_map(|s| vec![s]), zigzag], 1..60),
        bad,
    )
        .prop_map(|(chunks, bad)| {
            let mut u = 0.0;
            let mut h: Vec<f64> = chunks
                .into_iter()
                .flatten()
                .map(|du| {
                    u += du;
                    u
                })
                .collect();
            for (i, v) in bad {
                let i = i.min(h.len());
                h.insert(i, v);
            }
            h
        })
}

fn check<S: Scalar>(mut el: Bwbn<S>, history: &[f64]) -> Result<(), TestCaseError> {
    for &u in history {
        if !u.is_finite() || !S::from_f64(u).is_finite() {
            let before = (*el.committed(), *el.trial(), el.response());
            prop_assert_eq!(el.set_trial(S::from_f64(u)), Err(StepError::NonFiniteInput));
            prop_assert_eq!((*el.committed(), *el.trial(), el.response()), before);
            continue;
        }
        let before = (*el.committed(), el.response());
        let u = S::from_f64(u);
        match el.set_trial(u) {
            Ok(r) => {
                prop_assert!(r.force.is_finite() && r.tangent.is_finite());
                prop_assert_eq!(
                    *el.committed(),
                    before.0,
                    "a trial changed the committed state"
                );
                // The same trial again is bit-identical.
                prop_assert_eq!(el.set_trial(u), Ok(r));
                if u.to_f64() as i64 % 3 == 0 {
                    el.revert();
                    prop_assert_eq!(*el.trial(), *el.committed());
                    prop_assert_eq!(el.response(), before.1);
                } else {
                    el.commit();
                    prop_assert_eq!(*el.committed(), *el.trial());
                }
            }
            Err(e) => {
                prop_assert!(e != StepError::NonFiniteInput, "finite input refused");
                prop_assert_eq!(*el.committed(), before.0);
                prop_assert_eq!(el.response(), before.1);
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn adversarial_histories_f64(bits in 0u8..32, v in param_values(), h in history()) {
        if let Some(p) = params(bits, &v) {
            check(Bwbn::new(p), &h)?;
            check(Bwbn::new(p).with_control(Control::opensees(1e-10, 50)).unwrap(), &h)?;
            check(Bwbn::new(p).with_control(Control { method: Method::Bs32, tol: 1e-5, max_substeps: 64 }).unwrap(), &h)?;
            check(Bwbn::new(p).with_control(Control { method: Method::Series, tol: 1e-9, max_substeps: 1000 }).unwrap(), &h)?;
        }
    }

    #[test]
    fn adversarial_histories_f32_and_fixed(bits in 0u8..32, v in param_values(), h in history()) {
        if let Some(p) = params(bits, &v) {
            if let Ok(p32) = BwbnParams::<f32>::from_named(p.effect_set(), |n| p.get(n).map(|x| x as f32)) {
                check(Bwbn::new(p32), &h)?;
                check(Bwbn::new(p32).with_control(Control { method: Method::Series, tol: 1e-5, max_substeps: 64 }).unwrap(), &h)?;
            }
            let fixed = BwbnParams::<Fixed>::from_named(p.effect_set(), |n| p.get(n).map(Fixed::from_f64));
            if let Ok(pq) = fixed {
                check(Bwbn::new(pq), &h)?;
                check(Bwbn::new(pq).with_control(Control { method: Method::Series, tol: Fixed::from_f64(2e-4), max_substeps: 64 }).unwrap(), &h)?;
            }
        }
    }
}
