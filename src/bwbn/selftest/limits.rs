//! Closed forms the model must reproduce, in every arithmetic.
//!
//! * With `alpha = 1` the hysteretic spring vanishes: `R = k0 u` exactly
//!   (eq. 3.2), tangent `k0`.
//! * Under monotonic loading z tends to `Zu = (1/(beta+gamma))^(1/n)`
//!   (eq. 3.12), and the tangent to `alpha k0`.
//! * With `n = 1` the rate (eq. 3.4) is linear in z on each side of z = 0, so
//!   z(u) along a monotonic segment is a sum of exponentials:
//!   with `w = z sgn(du)` and `s = |u - u0|`,
//!   `dw/ds = 1 - (beta+gamma) w` for w > 0 and `1 - (gamma-beta) w` for w < 0.

use super::history::{base, displacement, POINTS};
use crate::bwbn::{BoucWen, Bwbn, BwbnParams};
use crate::element::Element;
use crate::scalar::{Fixed, Scalar};
use crate::selftest::report;

fn commit<S: Scalar>(el: &mut Bwbn<S>, u: S) -> crate::element::Response<S> {
    match el.set_trial(u) {
        Ok(r) => {
            el.commit();
            r
        }
        Err(e) => panic!("{}: step to {} refused: {}", S::NAME, u.to_f32(), e),
    }
}

fn linear_elastic<S: Scalar>() {
    let b = BoucWen::new(S::from_i32(6), S::ONE, S::lit(1.2), S::from_i32(2), -S::ONE)
        .expect("alpha = 1 is valid");
    let mut el = Bwbn::new(BwbnParams::plain(b));
    for i in 1..POINTS {
        let u = displacement::<S>(i);
        let r = commit(&mut el, u);
        assert!(
            r.force == b.k0 * u,
            "{}: alpha = 1: force at point {} is not k0 u",
            S::NAME,
            i
        );
        assert!(
            r.tangent == b.k0,
            "{}: alpha = 1: tangent at point {} is not k0",
            S::NAME,
            i
        );
    }
}

/// Pushes the plain model to 20 mm in 0.05 mm steps: z rises monotonically
/// to Zu without overshooting, the tangent falls to alpha k0.
fn monotonic<S: Scalar>(z_tol: f64) {
    let b = base::<S>();
    let zu = b.zu().expect("beta + gamma > 0").to_f64();
    let mut el = Bwbn::new(BwbnParams::plain(b));
    let mut last_z = 0.0;
    let mut r = el.response();
    for i in 1..=400 {
        r = commit(&mut el, S::ratio(i, 20));
        let z = el.committed().z.to_f64();
        assert!(
            z >= last_z,
            "{}: z decreased under monotonic loading at step {}",
            S::NAME,
            i
        );
        assert!(
            z <= zu * (1.0 + z_tol),
            "{}: z overshot Zu at step {}",
            S::NAME,
            i
        );
        last_z = z;
    }
    let gap = Scalar::abs(last_z - zu) / zu;
    let k_end = Scalar::abs(r.tangent.to_f64() - (b.alpha * b.k0).to_f64()) / b.k0.to_f64();
    report!(
        "  {}: at 20 mm |z - Zu|/Zu = {}, |tangent - alpha k0|/k0 = {}",
        S::NAME,
        gap as f32,
        k_end as f32
    );
    assert!(gap <= z_tol, "{}: z did not reach Zu", S::NAME);
    assert!(
        k_end <= z_tol * 10.0,
        "{}: the tangent did not reach alpha k0",
        S::NAME
    );
}

/// Exact z after a monotonic segment from `(u0, z0)` to `u1` for n = 1,
/// beta = 2, gamma = -1.
fn z_n1(u0: f64, z0: f64, u1: f64) -> f64 {
    let d = if u1 >= u0 { 1.0 } else { -1.0 };
    let mut s = (u1 - u0) * d;
    let mut w = z0 * d;
    if w < 0.0 {
        // dw/ds = 1 + 3|w| = 1 - 3w until w reaches 0.
        let s0 = libm::log(1.0 - 3.0 * w) / 3.0;
        if s < s0 {
            return d * (1.0 / 3.0 + (w - 1.0 / 3.0) * libm::exp(-3.0 * s));
        }
        s -= s0;
        w = 0.0;
    }
    // dw/ds = 1 - w.
    d * (1.0 - (1.0 - w) * libm::exp(-s))
}

/// Six cycles at 1 and 2 mm with n = 1 against the closed form (Zu = 1).
fn n_one<S: Scalar>(z_tol: f64) {
    let b = BoucWen::new(S::from_i32(6), S::lit(0.2), S::ONE, S::from_i32(2), -S::ONE)
        .expect("n = 1 is valid");
    let mut el = Bwbn::new(BwbnParams::plain(b));
    let (mut u0, mut z0, mut err) = (0.0f64, 0.0f64, 0.0f64);
    // Points 1..=1200 of the history are the 0.5 and 1 mm blocks: doubled,
    // three cycles at 1 mm and three at 2 mm.
    for i in 1..=1200 {
        let u = displacement::<S>(i) * S::from_i32(2);
        commit(&mut el, u);
        let u = u.to_f64();
        let exact = z_n1(u0, z0, u);
        err = err.max(Scalar::abs(el.committed().z.to_f64() - exact));
        // Continue the exact solution from the exact state.
        (u0, z0) = (u, exact);
    }
    report!("  {}: n = 1, max |z - z_exact| = {}", S::NAME, err as f32);
    assert!(
        err <= z_tol,
        "{}: n = 1 closed form not reproduced",
        S::NAME
    );
}

/// alpha = 1 gives R = k0 u and tangent k0 exactly.
pub fn alpha_one_is_linear_elastic() {
    linear_elastic::<f64>();
    linear_elastic::<f32>();
    linear_elastic::<Fixed>();
}

/// z tends to Zu under monotonic loading.
pub fn z_tends_to_zu() {
    monotonic::<f64>(1e-9);
    monotonic::<f32>(1e-5);
    monotonic::<Fixed>(1e-3);
}

/// A Zu of 0.05 (a small unit of displacement): every step of cycles to
/// +-5 Zu is taken, and z reaches Zu from below. In Q15.16 the tolerances of
/// such a model would be below one least-significant bit without the floor of
/// `integrate::resolvable`, and steps failed.
fn small_zu<S: Scalar>() {
    let (n, zu) = (1.2f64, 0.05f64);
    let beta_gamma = (1.0 / zu).powf(n);
    let b = BoucWen::new(
        S::from_i32(6),
        S::lit(0.1),
        S::lit(1.2),
        S::from_f64(0.75 * beta_gamma),
        S::from_f64(0.25 * beta_gamma),
    )
    .expect("a valid set");
    let mut el = Bwbn::new(BwbnParams::plain(b));
    let mut peak = 0.0f64;
    for i in 1..=300 {
        let u = 5.0 * zu * libm::sin(2.0 * core::f64::consts::PI * i as f64 / 100.0);
        commit(&mut el, S::from_f64(u));
        peak = peak.max(Scalar::abs(el.committed().z.to_f64()));
    }
    report!(
        "  {}: Zu = 0.05, largest |z| / Zu = {}",
        S::NAME,
        (peak / zu) as f32
    );
    assert!(
        peak > 0.9 * zu && peak < 1.01 * zu,
        "{}: largest |z| {} for Zu 0.05",
        S::NAME,
        peak as f32
    );
}

/// A small Zu is integrated in every arithmetic.
pub fn small_zu_every_arithmetic() {
    small_zu::<f64>();
    small_zu::<f32>();
    small_zu::<Fixed>();
}

/// n = 1 reproduces the exponential closed form.
pub fn n_one_closed_form() {
    n_one::<f64>(1e-7);
    n_one::<f32>(1e-4);
    n_one::<Fixed>(3e-4);
}
