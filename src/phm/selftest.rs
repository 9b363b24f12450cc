//! Test bodies shared by the host unit tests and the on-target (QEMU) test
//! package: each rule on a constructed twist path with expected points
//! computed by hand from the thesis' equations, the inner-cycle memory and
//! its full-memory policy, input checks and symmetry.
//!
//! Every body is generic over the arithmetic; [`CASES`] lists them in `f32`
//! and [`Fixed`] (the target arithmetics), the host test runs them in `f64`
//! too. A body panics (through `assert!`) on failure.
//!
//! The primary curve of all cases, the same in both directions:
//!
//! ```text
//! cracking (1, 10)  yield (5, 20)  plateau end (10, 20)  (15, 16)
//! slopes     10          2.5              0               -0.8
//! ```

use super::{Coefficients, Element, Kind, Phm, PhmParams};
use crate::scalar::{Fixed, Scalar};

/// The shared cases, named `phm::<case>::<arithmetic>`.
pub const CASES: &[(&str, fn())] = &[
    ("phm::elastic_rule_1::f32", elastic_rule_1::<f32>),
    ("phm::elastic_rule_1::q16", elastic_rule_1::<Fixed>),
    ("phm::pre_yield_rule_2::f32", pre_yield_rule_2::<f32>),
    ("phm::pre_yield_rule_2::q16", pre_yield_rule_2::<Fixed>),
    ("phm::post_yield_rule_3::f32", post_yield_rule_3::<f32>),
    ("phm::post_yield_rule_3::q16", post_yield_rule_3::<Fixed>),
    ("phm::pinched_rules_4_6::f32", pinched_rules_4_6::<f32>),
    ("phm::pinched_rules_4_6::q16", pinched_rules_4_6::<Fixed>),
    ("phm::inner_cycle_returns::f32", inner_cycle_returns::<f32>),
    (
        "phm::inner_cycle_returns::q16",
        inner_cycle_returns::<Fixed>,
    ),
    ("phm::memory_full_policy::f32", memory_full_policy::<f32>),
    ("phm::memory_full_policy::q16", memory_full_policy::<Fixed>),
    ("phm::bad_input_refused::f32", bad_input_refused::<f32>),
    ("phm::bad_input_refused::q16", bad_input_refused::<Fixed>),
    ("phm::symmetric_response::f32", symmetric_response::<f32>),
    ("phm::symmetric_response::q16", symmetric_response::<Fixed>),
];

/// Absolute torque tolerance of the hand-computed points (torques up to 20):
/// rounding of f64; of f32 (about 20 * 2^-24 per operation); of Q15.16 (2^-16
/// per operation, and the thesis' four-digit coefficients rounded to 2^-16,
/// e.g. 0.0004 -> 0.000397).
pub(crate) fn tol<S: Scalar>() -> f64 {
    match S::NAME {
        "f64" => 1e-9,
        "f32" => 2e-4,
        _ => 4e-3,
    }
}

fn close<S: Scalar>(got: S, want: f64, what: &str) {
    let g = got.to_f64();
    assert!(
        (g - want).abs() <= tol::<S>() * (1.0 + want.abs() / 20.0),
        "{what}: got {g}, want {want}"
    );
}

/// The test curve of the module docs, in both directions.
pub(crate) fn params<S: Scalar>() -> PhmParams<S, 4> {
    let p = |x: i32, y: i32| [S::from_i32(x), S::from_i32(y)];
    PhmParams::symmetric(
        &[p(1, 10), p(5, 20), p(10, 20), p(15, 16)],
        Coefficients::thesis(),
    )
    .expect("the test curve is valid")
}

/// Twist `num/den` in the element's arithmetic.
fn tw<S: Scalar>(num: i32, den: i32) -> S {
    S::from_i32(num) / S::from_i32(den)
}

/// Drives `el` in `steps` equal committed steps from its twist to `to`.
pub(crate) fn drive<S: Scalar, const N: usize, const M: usize>(
    el: &mut Phm<S, N, M>,
    to: S,
    steps: i32,
) {
    let from = el.displacement();
    for i in 1..=steps {
        let t = if i == steps {
            to
        } else {
            from + (to - from) * S::from_i32(i) / S::from_i32(steps)
        };
        el.set_trial(t).expect("finite twist");
        el.commit();
    }
}

fn torque<S: Scalar, const N: usize, const M: usize>(el: &Phm<S, N, M>) -> S {
    el.response().force
}

/// Unloading rule 1 and loading rule 1: uncracked, the element follows the
/// initial stiffness 10 both ways.
pub fn elastic_rule_1<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    drive(&mut el, tw(1, 2), 5);
    close(torque(&el), 5.0, "0.5");
    drive(&mut el, tw(-8, 10), 13);
    close(torque(&el), -8.0, "-0.8");
    close(el.response().tangent, 10.0, "tangent");
    drive(&mut el, S::ZERO, 8);
    close(torque(&el), 0.0, "back to 0");
    assert_eq!(el.committed().kind(), Kind::Elastic);
    assert_eq!(el.memory_depth(), 0);
}

/// Unloading before yield (eqs 1a, 1c, 3a) and loading rule 2 (towards the
/// other direction's cracking point), then rule 6 (primary curve).
pub fn pre_yield_rule_2<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    drive(&mut el, S::from_i32(3), 30);
    // Primary curve: 10 + 2.5 * (3 - 1) = 15, tangent 2.5.
    close(torque(&el), 15.0, "primary at 3");
    close(el.response().tangent, 2.5, "primary tangent");
    // mu_c = 3. Eq. 1a: theta_ur1 = 3 (1.0498 - 0.0028*3) = 3.1242 > 3, so the
    // cap puts it where slope 10 from (3, 15) reaches T_ur1 (gap G2);
    // eq. 1c: T_ur1 = 15 (0.8527 - 0.0009*3) = 12.75 -> theta = 3 - 2.25/10.
    let t_ur1 = 15.0 * (0.8527 - 0.0009 * 3.0);
    let x_ur1 = 3.0 - (15.0 - t_ur1) / 10.0;
    // Eq. 3a: theta_su = 3 (0.2358 - 0.0015*3) = 0.6939.
    let x_su = 3.0 * (0.2358 - 0.0015 * 3.0);
    drive(&mut el, tw(29, 10), 1);
    close(torque(&el), 15.0 - 10.0 * 0.1, "first unloading segment");
    close(el.response().tangent, 10.0, "capped unloading stiffness");
    drive(&mut el, tw(3, 2), 7);
    close(
        torque(&el),
        t_ur1 * (1.5 - x_su) / (x_ur1 - x_su),
        "towards theta_su",
    );
    // Rule 2: from (0.6939, 0) straight to (-1, -10).
    drive(&mut el, S::ZERO, 5);
    close(
        torque(&el),
        -10.0 * x_su / (1.0 + x_su),
        "towards -cracking",
    );
    // Rule 6: on the negative primary curve past cracking.
    drive(&mut el, S::from_i32(-2), 10);
    close(torque(&el), -12.5, "negative primary");
    assert_eq!(el.committed().kind(), Kind::Envelope);
    let pos = el.levels()[0];
    assert_eq!(pos.cycles, 1);
    close(pos.twist, 3.0, "theta_m");
}

/// Unloading past yield (eqs 1b, 1d, 2a, 2b, 3b) and loading rule 3 (eq. 4)
/// towards a direction that cracked but did not yield.
pub fn post_yield_rule_3<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    // Negative level theta_m = 3 (cracked, not yielded), then up to +8.
    drive(&mut el, S::from_i32(-3), 30);
    drive(&mut el, S::from_i32(8), 110);
    close(torque(&el), 20.0, "plateau at 8");
    close(el.response().tangent, 0.0, "plateau tangent");
    let mu: f64 = 8.0 / 5.0;
    // Eq. 1b gives theta_ur1 = 8 (1.0047 - 0.0004 mu) > 8: capped (gap G2).
    let t_ur1 = 20.0 * (0.8623 - 0.0006 * mu);
    let x_ur1 = 8.0 - (20.0 - t_ur1) / 10.0;
    // Eqs 2a, 2b (with mu_y, gap G1) and 3b.
    let x_ur2 = 8.0 * (0.7101 + 0.0363 * mu);
    let t_ur2 = 20.0 * (0.3243 - 0.0126 * mu);
    let x_su = 8.0 * (0.0848 + 0.1012 * mu);
    drive(&mut el, tw(79, 10), 1);
    close(torque(&el), 19.0, "capped first segment");
    drive(&mut el, S::from_i32(7), 9);
    close(
        torque(&el),
        t_ur2 + (t_ur1 - t_ur2) * (7.0 - x_ur2) / (x_ur1 - x_ur2),
        "ur1 -> ur2",
    );
    drive(&mut el, S::from_i32(3), 40);
    close(
        torque(&el),
        t_ur2 * (3.0 - x_su) / (x_ur2 - x_su),
        "ur2 -> su",
    );
    // Eq. 4 with theta_m/theta_c = 3 of the negative direction.
    let k = 10.0 * 0.7513 * libm::pow(3.0, -0.786);
    drive(&mut el, S::ZERO, 30);
    close(torque(&el), -k * x_su, "eq. 4 line at 0");
    close(el.response().tangent, k, "eq. 4 slope");
    drive(&mut el, tw(-3, 2), 15);
    close(torque(&el), -k * (1.5 + x_su), "eq. 4 line at -1.5");
    // The line k (x + x_su) meets the primary curve 10 + 2.5 (x - 1) at
    // x = (7.5 - k x_su) / (k - 2.5) = 1.87: at -3 the path is on it.
    drive(&mut el, S::from_i32(-3), 15);
    close(torque(&el), -15.0, "rule 6");
}

/// Past yield in both directions: loading rules 4 and 5 (eqs 5a, 5b, 6), rule
/// 6, and the cycle counter n = 2 on the repeated cycle.
pub fn pinched_rules_4_6<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    drive(&mut el, S::from_i32(8), 80);
    drive(&mut el, S::from_i32(-8), 160);
    close(torque(&el), -20.0, "negative plateau");
    let mu: f64 = 1.6;
    let x_su = 8.0 * (0.0848 + 0.1012 * mu);
    // Reloading towards +8 with n = 1, T_m = 20:
    let n = 1.0;
    let tp = 20.0 * ((0.9425 - 0.0783 * n) * libm::pow(mu, 0.1155 * n - 1.3943)).min(1.0);
    let x_cr = 8.0 * ((0.0766 - 0.0067 * n) * mu + 0.0782 * n + 0.0037);
    let tm2 = 20.0 * (0.9842 + 0.0177 * n - 0.05557 * mu).min(1.0);
    // The pinched line from (-x_su, 0) through (8, T_p), up to theta_cr.
    let t_cr = tp * (x_cr + x_su) / (8.0 + x_su);
    drive(&mut el, S::ZERO, 80);
    close(torque(&el), tp * x_su / (8.0 + x_su), "pinched line at 0");
    drive(&mut el, S::from_i32(5), 50);
    let k = (tm2 - t_cr) / (8.0 - x_cr);
    close(
        torque(&el),
        t_cr + k * (5.0 - x_cr),
        "towards (theta_m, T'_m)",
    );
    drive(&mut el, S::from_i32(8), 30);
    close(torque(&el), tm2, "T'_m at theta_m");
    // The second cycle: n = 2 in both directions, T_m = T'_m of the first.
    drive(&mut el, S::from_i32(-8), 160);
    close(torque(&el), -tm2, "T'_m at -theta_m");
    assert_eq!(el.levels()[0].cycles, 2);
    drive(&mut el, S::from_i32(8), 160);
    let tm3 = tm2 * (0.9842 + 0.0177 * 2.0 - 0.05557 * mu).min(1.0);
    close(torque(&el), tm3, "T'_m with n = 2");
    assert_eq!(el.levels()[1].cycles, 2);
    // Rule 6: beyond theta_m the branch runs on (slope about 2.3 from
    // (8, 17.0)) and meets the plateau (20) near 9.3.
    drive(&mut el, tw(19, 2), 15);
    close(torque(&el), 20.0, "back on the primary curve");
}

/// A partial unloading and reloading (inner cycle) returns to the point
/// where it began and resumes the branch it left; nested cycles too.
pub fn inner_cycle_returns<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    drive(&mut el, S::from_i32(8), 80);
    drive(&mut el, S::from_i32(7), 10);
    let t7 = torque(&el).to_f64();
    // Reloading before zero torque: the chord back to (8, 20).
    drive(&mut el, tw(72, 10), 2);
    let t72 = t7 + (20.0 - t7) * 0.2;
    close(torque(&el), t72, "on the chord");
    close(el.response().tangent, 20.0 - t7, "chord slope");
    // Unloading from the chord (7.2 < 0.95 * 8: not counted): back along it
    // towards where it began (gap G3).
    drive(&mut el, tw(71, 10), 1);
    close(torque(&el), t72 - (20.0 - t7) * 0.1, "inner unloading");
    assert_eq!(el.memory_depth(), 3);
    // Reloading: the chord back to (7.2, t72), then the outer chord resumes.
    drive(&mut el, tw(72, 10), 1);
    close(torque(&el), t72, "inner loop closes");
    drive(&mut el, tw(76, 10), 4);
    close(torque(&el), t7 + (20.0 - t7) * 0.6, "outer chord resumed");
    assert_eq!(el.memory_depth(), 2);
    drive(&mut el, tw(85, 10), 9);
    close(torque(&el), 20.0, "primary curve resumed");
    assert_eq!(el.memory_depth(), 0);
    assert_eq!(el.levels()[0].cycles, 1);
    assert_eq!(el.forgotten(), 0);
}

/// With memory for two branches, a second nested inner cycle drops the
/// oldest entries (counted in `forgotten`); the outer chord then runs on past
/// its target as a straight line (gap G8) instead of resuming the branch.
pub fn memory_full_policy<S: Scalar>() {
    fn run<S: Scalar, const M: usize>() -> (Phm<S, 4, M>, S, S, S) {
        let mut el: Phm<S, 4, M> = Phm::new(params());
        drive(&mut el, S::from_i32(8), 80);
        drive(&mut el, S::from_i32(-8), 160);
        drive(&mut el, S::from_i32(4), 120);
        let t4 = torque(&el);
        drive(&mut el, tw(7, 2), 5);
        let t35 = torque(&el);
        drive(&mut el, tw(38, 10), 3);
        drive(&mut el, tw(36, 10), 2);
        drive(&mut el, tw(39, 10), 3);
        drive(&mut el, tw(9, 2), 6);
        let t45 = torque(&el);
        (el, t4, t35, t45)
    }
    let (full, t4, t35, t45) = run::<S, 2>();
    assert_eq!(full.forgotten(), 2);
    assert_eq!(full.committed().kind(), Kind::Ray);
    let (t4, t35) = (t4.to_f64(), t35.to_f64());
    close(t45, t4 + (t4 - t35), "chord continued past 4");
    let (roomy, _, _, t45) = run::<S, 16>();
    assert_eq!(roomy.forgotten(), 0);
    // With room, the pinched reloading branch of the last case resumes at 4.
    let mu: f64 = 1.6;
    let x_cr = 8.0 * ((0.0766 - 0.0067) * mu + 0.0782 + 0.0037);
    let tm2 = 20.0 * (0.9842 + 0.0177 - 0.05557 * mu);
    let k = (tm2 - t4) / (8.0 - 4.0);
    close(t45, t4 + k * 0.5, "reloading branch resumed");
    assert!(x_cr < 4.0);
}

/// Non-finite input is refused and changes nothing.
pub fn bad_input_refused<S: Scalar>() {
    let mut el: Phm<S, 4, 16> = Phm::new(params());
    drive(&mut el, S::from_i32(3), 10);
    el.set_trial(S::from_i32(2)).unwrap();
    let before = *el.trial();
    let bad = S::MAX + S::MAX; // inf, or saturated fixed point
    assert_eq!(el.set_trial(bad), Err(crate::StepError::NonFiniteInput));
    assert_eq!(*el.trial(), before);
    assert_eq!(el.displacement(), S::from_i32(3));
    el.revert();
    assert_eq!(el.response().force, el.committed().torque);
}

/// A symmetric curve and a mirrored twist history give mirrored torques.
pub fn symmetric_response<S: Scalar>() {
    let mut a: Phm<S, 4, 16> = Phm::new(params());
    let mut b: Phm<S, 4, 16> = Phm::new(params());
    let path = [6, -2, 3, 1, 2, -7, 8, 5, 6, -3, 12];
    for &x in path.iter() {
        drive(&mut a, S::from_i32(x), 20);
        drive(&mut b, S::from_i32(-x), 20);
        assert_eq!(a.response().force, -b.response().force, "at {x}");
        assert_eq!(a.response().tangent, b.response().tangent, "at {x}");
    }
}
