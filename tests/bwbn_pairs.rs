//! The Runge-Kutta pairs (the integrators wherever an effect is on) on random
//! parameter sets and random histories, in `f64`, `f32` and Q15.16, against
//! the same model in `f64` by Dormand-Prince at 1e-13.
//!
//! On the reference history of `../shared/data/opensees-reference/` the
//! pairs meet the bounds of the README (`tests/bwbn_opensees.rs`). On random
//! sets they did not: a sub-step across z = 0, where `|z|^n` and
//! `sgn(z du)` change form, or the first sub-step after a reversal, taken
//! with the size carried over from the other direction while z now moves up
//! to `2 beta / (beta + gamma)` times faster, could come out far off with an
//! error estimate that was small by chance (before the kink landing and the
//! reversal start of `src/bwbn/integrate.rs`, in the families below: `f64`
//! up to 3.3e-6 of peak force, `f32` 6.0e-3, Q15.16 with Zu >= 1 0.10, all
//! accepted as `Ok`).

use hysteresis::bwbn::Bwbn;
use hysteresis::bwbn::{BwbnParams, Control, EffectSet, Method};
use hysteresis::{Element, Fixed, Scalar};

/// Uniform in [0, 1) from a 64-bit linear congruential generator (Knuth's
/// MMIX constants).
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

/// A random history: `len` increments, each uniform in `+-reach` z-scales.
struct Family {
    effects: bool,
    len: usize,
    reach: f64,
}

/// One random parameter set of the family, every value rounded to Q15.16 so
/// that the three arithmetics step the same model, and its history; `None`
/// where the set is invalid (degradation that the energy limit forbids) or
/// outside what Q15.16 holds (as in `tests/bwbn_series.rs`: Zu from 0.1 to
/// 100, peak force below 8,000, `k0 Zu |u|` below 30,000).
///
/// Base: k0 0.3-300, alpha 0-0.5, n 0.6-4, beta 0.05-20, `|gamma| <= beta`.
/// With effects (all four of the thesis), in units of the energy
/// `e1 = (1 - alpha) k0 Zu^2` (a quarter of one cycle's dissipation at Zu)
/// and an energy limit of `200 e1`: A falls by up to half, nu and eta grow
/// by up to twice their start over that limit; pinching severity up to 0.95,
/// reached after about `1/p` of up to `e1 / 2`, centred at -0.2 to 0.3 Zu,
/// 0.05 to 1.05 Zu wide.
#[allow(clippy::type_complexity)]
fn draw(
    state: &mut u64,
    family: &Family,
) -> Option<(Vec<(&'static str, f64)>, EffectSet, Vec<f64>)> {
    let mut r = || uniform(state);
    let q = |v: f64| Fixed::from_f64(v).to_f64();
    let k0 = q(0.3 + r() * 299.7);
    let alpha = q(r() * 0.5);
    let n = q(0.6 + r() * 3.4);
    let beta = q(0.05 + r() * 19.95);
    let gamma = q((2.0 * r() - 1.0) * beta);
    let mut vals = vec![
        ("k0", k0),
        ("alpha", alpha),
        ("n", n),
        ("beta", beta),
        ("gamma", gamma),
    ];
    let zu = (1.0 / (beta + gamma)).powf(1.0 / n);
    let e1 = (1.0 - alpha) * k0 * zu * zu;
    let set = if family.effects {
        let limit = 200.0 * e1;
        vals.extend([
            ("delta_A", q(r() * 0.5 / limit)),
            ("delta_nu", q(r() / limit)),
            ("delta_eta", q(r() / limit)),
            ("zeta0", q(r() * 0.95)),
            ("p", q(r() * 2.0 / e1)),
            ("q", q(-0.2 + r() * 0.5)),
            ("psi0", q((0.05 + r()) * zu)),
            ("delta_psi", q(r() * 0.05 * zu / e1)),
            ("lambda", q(0.1 + r())),
            ("energy_limit", limit),
        ]);
        EffectSet::BWBN
    } else {
        EffectSet::NONE
    };
    let p = params::<f64>(set, &vals)?;
    let scale = p.z_scale();
    let mut u = 0.0;
    let history: Vec<f64> = (0..family.len)
        .map(|_| {
            u += (2.0 * r() - 1.0) * family.reach * scale;
            u
        })
        .collect();
    let reach = history.iter().fold(0.0f64, |m, u| m.max(u.abs()));
    ((0.1..=100.0).contains(&scale) && k0 * scale * reach < 30_000.0)
        .then_some((vals, set, history))
}

fn params<S: Scalar>(set: EffectSet, vals: &[(&str, f64)]) -> Option<BwbnParams<S>> {
    BwbnParams::from_named(set, |name| {
        vals.iter()
            .find(|(k, _)| *k == name)
            .map(|(_, v)| S::from_f64(*v))
    })
    .ok()
}

/// See [`family`].
const STEEP: f64 = 100.0;

/// The arithmetic's pair at its default tolerance and budget.
fn pair<S: Scalar>() -> Control<S> {
    Control {
        method: Control::<S>::pair_for(),
        ..Control::default_for()
    }
}

/// The largest force error over peak force up to the first refused
/// increment, and whether one was refused.
fn worst<S: Scalar>(p: BwbnParams<S>, history: &[f64], reference: &[f64]) -> (f64, bool) {
    let mut el = Bwbn::with_extra(p, (), pair::<S>()).unwrap();
    let peak = reference.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let mut worst = 0.0f64;
    for (&u, r) in history.iter().zip(reference) {
        let Ok(out) = el.set_trial(S::from_f64(u)) else {
            return (worst, true);
        };
        el.commit();
        worst = worst.max((out.force.to_f64() - r).abs() / peak);
    }
    (worst, false)
}

/// Runs `sets` random sets of a family; returns, per arithmetic (`f64`,
/// `f32`, Q15.16 with Zu >= 1), the worst error and the number of sets with
/// a refused increment, not counting sets near the hardening limit where z
/// leaves Zu on unloading more than [`STEEP`] times faster than elastically
/// (`2 beta / (beta + gamma)`): there `f32` and Q15.16 may run out of their
/// 64 sub-steps (measured: one set of 120 in `f32` with short increments,
/// 2 beta / (beta + gamma) = 781; the element refuses, unchanged).
fn family(family: Family, sets: usize, seed: u64) -> [(f64, usize); 3] {
    let mut state = seed;
    let mut out = [(0.0f64, 0usize); 3];
    let mut used = 0;
    while used < sets {
        let Some((vals, set, history)) = draw(&mut state, &family) else {
            continue;
        };
        let p = params::<f64>(set, &vals).expect("drawn valid");
        let tight = Control {
            method: Method::Dp54,
            tol: 1e-13,
            max_substeps: 60_000,
        };
        let mut el = Bwbn::with_extra(p, (), tight).unwrap();
        let reference: Option<Vec<f64>> = history
            .iter()
            .map(|&u| {
                let r = el.set_trial(u).ok()?;
                el.commit();
                Some(r.force)
            })
            .collect();
        // Past the energy limit the model is undefined in every arithmetic.
        let Some(reference) = reference else { continue };
        if reference.iter().any(|f| f.abs() >= 8000.0) {
            continue;
        }
        used += 1;
        let runs = [
            Some(worst(p, &history, &reference)),
            params::<f32>(set, &vals).map(|p| worst(p, &history, &reference)),
            params::<Fixed>(set, &vals)
                .filter(|p| p.z_scale() >= Fixed::ONE)
                .map(|p| worst(p, &history, &reference)),
        ];
        let (beta, gamma) = (p.base().beta, p.base().gamma);
        let steep = 2.0 * beta / (beta + gamma) > STEEP;
        for (tally, run) in out.iter_mut().zip(runs) {
            if let Some((w, refused)) = run {
                tally.0 = tally.0.max(w);
                tally.1 += usize::from(refused && !steep);
            }
        }
    }
    out
}

/// The bounds on random sets: `f64` within the README's 1e-6 of peak force
/// and nothing refused; `f32` within 2e-4 (the README's 1e-4 holds on the
/// reference history; here measured up to 1.03e-4); Q15.16 within 5e-3 where
/// Zu >= 1 (measured up to 2.5e-3; below Zu = 1 the tolerance of the pair
/// meets Q15.16's last place, see the README). Refusals in `f32` and Q15.16
/// only where `refusals_allowed`.
fn check(name: &str, [f64s, f32s, fixed]: [(f64, usize); 3], refusals_allowed: bool) {
    eprintln!("{name}: f64 {f64s:?}, f32 {f32s:?}, Q15.16 (Zu >= 1) {fixed:?}");
    assert!(f64s.0 <= 1e-6 && f64s.1 == 0, "{name}: f64 {f64s:?}");
    assert!(f32s.0 <= 2e-4, "{name}: f32 {f32s:?}");
    assert!(fixed.0 <= 5e-3, "{name}: Q15.16 {fixed:?}");
    assert!(
        refusals_allowed || (f32s.1 == 0 && fixed.1 == 0),
        "{name}: {f32s:?} {fixed:?}"
    );
}

/// Plain Bouc-Wen integrated by the pair (what every element with an effect
/// runs on), 120 sets of 1,500 increments of up to 0.3 Zu. Worst error over
/// peak force, before the kink landing and the reversal start / now: `f64`
/// 3.3e-6 / 2.2e-8, `f32` 6.0e-3 / 1.03e-4, Q15.16 (Zu >= 1) 0.10 / 5.4e-4.
#[test]
fn plain_sets_short_increments() {
    let tallies = family(
        Family {
            effects: false,
            len: 1500,
            reach: 0.3,
        },
        120,
        1,
    );
    check("plain, short", tallies, false);
}

/// The same, 150 sets of 150 increments of up to 3 Zu: `f64` 2.4e-7 /
/// 4.1e-9, `f32` 4.5e-4 / 7.0e-5, Q15.16 4.0e-3 / 2.5e-3. `f32` and Q15.16
/// may refuse an increment their budget of 64 sub-steps cannot cover (a
/// refusal leaves the element unchanged; the errors are those before it).
#[test]
fn plain_sets_long_increments() {
    let tallies = family(
        Family {
            effects: false,
            len: 150,
            reach: 3.0,
        },
        150,
        2,
    );
    check("plain, long", tallies, true);
}

/// All four thesis effects, 80 sets of 1,500 increments of up to 0.3 Zu:
/// `f64` 1.2e-6 / 1.7e-8, `f32` 3.3e-3 / 9.2e-5, Q15.16 3.4e-2 / 1.0e-3.
#[test]
fn bwbn_sets_short_increments() {
    let tallies = family(
        Family {
            effects: true,
            len: 1500,
            reach: 0.3,
        },
        80,
        3,
    );
    check("BWBN, short", tallies, false);
}

/// All four thesis effects, 100 sets of 150 increments of up to 3 Zu: `f64`
/// 2.0e-7 / 6.8e-9, `f32` 2.4e-4 / 8.9e-5, Q15.16 8.4e-4 / 8.8e-4.
#[test]
fn bwbn_sets_long_increments() {
    let tallies = family(
        Family {
            effects: true,
            len: 150,
            reach: 3.0,
        },
        100,
        4,
    );
    check("BWBN, long", tallies, true);
}
