//! Error-controlled integration of the model's ODEs over one increment, with a
//! bounded work budget.
//!
//! The increment (of displacement for the quasi-static element, of time for
//! the dynamic driver) is split into sub-steps of an embedded explicit
//! Runge-Kutta pair. Each sub-step's local error estimate `err_i` is compared
//! with `atol_i + tol * max(|y_i|, |y_i'|)`; a sub-step is accepted when every
//! ratio is at most 1, and the next size follows from the largest ratio `r` as
//! `h * 0.9 r^(-1/q)` (`q` = order of the estimate + 1), limited to [0.1, 5].
//! The size proposed at the end of one increment is kept in the state and
//! tried first on the next one. Both pairs are "first same as last": the last
//! stage is the derivative at the new point, which is reused as the first stage
//! of the next sub-step and gives the consistent tangent for free.
//!
//! * [`Method::Dp54`]: Dormand-Prince 5(4), 6 derivative evaluations a sub-step;
//!   the host default.
//! * [`Method::Bs32`]: Bogacki-Shampine 3(2), 3 evaluations a sub-step; the
//!   default for `f32` and fixed point, where the tolerance is looser.
//! * [`Method::BackwardEuler`]: one implicit Euler step per increment, solved
//!   by Newton's method: the scheme of OpenSees' `BoucWen` and `BWBN`
//!   materials, kept to reproduce their results. Not error-controlled.
//!
//! When a sub-step fails `max_substeps` times in one increment, or its size
//! falls below the arithmetic's resolution, the increment fails with
//! [`StepError::ToleranceNotMet`] and the caller keeps its old state.

use crate::element::StepError;
use crate::scalar::Scalar;

/// The integration scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Method {
    /// Dormand-Prince 5(4), adaptive.
    Dp54,
    /// Bogacki-Shampine 3(2), adaptive.
    Bs32,
    /// One backward-Euler step per increment (OpenSees' scheme), Newton-solved.
    BackwardEuler,
}

impl Method {
    /// The order of the solution the method advances with (5, 3 or 1), which
    /// tests compare with the observed convergence order.
    pub const fn order(self) -> u32 {
        match self {
            Method::Dp54 => 5,
            Method::Bs32 => 3,
            Method::BackwardEuler => 1,
        }
    }
}

/// How an increment is integrated.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Control<S> {
    /// The scheme.
    pub method: Method,
    /// Local error tolerance, relative to the state's scale (z relative to
    /// Zu). For `BackwardEuler`: the Newton tolerance.
    pub tol: S,
    /// Work budget: the most sub-steps (accepted or rejected) one increment
    /// may take, or Newton iterations for `BackwardEuler`.
    pub max_substeps: u16,
}

impl<S: Scalar> Control<S> {
    /// The default for the arithmetic `S`: `Dp54` at 1e-9 for `f64`
    /// (force error below 1e-6 of peak on the reference histories), `Bs32` at
    /// 1e-5 for `f32` and 2e-3 for fixed point (the bounds the on-target tests
    /// prove), 64 sub-steps.
    pub fn default_for() -> Self {
        let (method, tol) = match S::NAME {
            "f64" => (Method::Dp54, S::lit(1e-9)),
            "f32" => (Method::Bs32, S::lit(1e-5)),
            _ => (Method::Bs32, S::lit(2e-3)),
        };
        Control {
            method,
            tol,
            max_substeps: 64,
        }
    }

    /// OpenSees' scheme: one backward-Euler step per increment, Newton to
    /// `tol` (absolute, on z) in at most `max_iter` iterations.
    pub fn opensees(tol: S, max_iter: u16) -> Self {
        Control {
            method: Method::BackwardEuler,
            tol,
            max_substeps: max_iter,
        }
    }
}

/// A rational tableau coefficient.
type Q = (i32, i32);

/// An explicit, first-same-as-last Runge-Kutta pair with `M` stages.
struct Tableau<const M: usize> {
    c: [Q; M],
    /// Stage coefficients; the last row holds the weights of the propagated
    /// solution (first same as last).
    a: [[Q; M]; M],
    /// Weights of the error estimate (b - b*).
    e: [Q; M],
    /// Accept-and-grow thresholds: the largest factor `f` in [`FACTORS`] with
    /// `r <= (0.9/f)^q`.
    thresholds: [f32; FACTORS.len()],
}

const FACTORS: [f32; 12] = [5.0, 4.0, 3.0, 2.0, 1.5, 1.2, 1.0, 0.8, 0.6, 0.4, 0.25, 0.1];

const DP54: Tableau<7> = Tableau {
    c: [(0, 1), (1, 5), (3, 10), (4, 5), (8, 9), (1, 1), (1, 1)],
    a: [
        [(0, 1); 7],
        [(1, 5), (0, 1), (0, 1), (0, 1), (0, 1), (0, 1), (0, 1)],
        [(3, 40), (9, 40), (0, 1), (0, 1), (0, 1), (0, 1), (0, 1)],
        [(44, 45), (-56, 15), (32, 9), (0, 1), (0, 1), (0, 1), (0, 1)],
        [
            (19372, 6561),
            (-25360, 2187),
            (64448, 6561),
            (-212, 729),
            (0, 1),
            (0, 1),
            (0, 1),
        ],
        [
            (9017, 3168),
            (-355, 33),
            (46732, 5247),
            (49, 176),
            (-5103, 18656),
            (0, 1),
            (0, 1),
        ],
        [
            (35, 384),
            (0, 1),
            (500, 1113),
            (125, 192),
            (-2187, 6784),
            (11, 84),
            (0, 1),
        ],
    ],
    e: [
        (71, 57600),
        (0, 1),
        (-71, 16695),
        (71, 1920),
        (-17253, 339200),
        (22, 525),
        (-1, 40),
    ],
    // (0.9/f)^5
    thresholds: [
        1.889_568e-4,
        5.766_504e-4,
        2.43e-3,
        1.845_281e-2,
        7.776e-2,
        0.237_305,
        0.590_49,
        1.801_964,
        7.593_75,
        57.665_04,
        604.661_76,
        59_049.0,
    ],
};

const BS32: Tableau<4> = Tableau {
    c: [(0, 1), (1, 2), (3, 4), (1, 1)],
    a: [
        [(0, 1); 4],
        [(1, 2), (0, 1), (0, 1), (0, 1)],
        [(0, 1), (3, 4), (0, 1), (0, 1)],
        [(2, 9), (1, 3), (4, 9), (0, 1)],
    ],
    e: [(-5, 72), (1, 12), (1, 9), (-1, 8)],
    // (0.9/f)^3
    thresholds: [
        5.832e-3,
        1.139_062_5e-2,
        2.7e-2,
        9.112_5e-2,
        0.216,
        0.421_875,
        0.729,
        1.423_828_1,
        3.375,
        11.390_625,
        46.656,
        729.0,
    ],
};

#[inline(always)]
fn q<S: Scalar>(c: Q) -> S {
    S::ratio(c.0, c.1)
}

/// The factor by which to change the sub-step size after an error ratio `r`.
#[inline]
fn factor<S: Scalar>(thresholds: &[f32; FACTORS.len()], r: S) -> S {
    let mut i = 0;
    while i < FACTORS.len() - 1 && r > S::lit(thresholds[i]) {
        i += 1;
    }
    S::lit(FACTORS[i])
}

/// The result of integrating over one increment.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Advanced<S, const N: usize> {
    /// The state at the end.
    pub y: [S; N],
    /// The derivative at the end (last stage).
    pub dy: [S; N],
    /// The sub-step size to try first next time.
    pub h_next: S,
}

/// Integrates `dy/dx = f(x, y)` from `x = 0` to `x = len > 0`.
///
/// `dy0` is the derivative at the start; `atol` the absolute tolerances;
/// `h_try` the first sub-step size to try.
pub(crate) fn advance<S: Scalar, const N: usize>(
    ctl: &Control<S>,
    f: &mut impl FnMut(S, &[S; N]) -> Result<[S; N], StepError>,
    y0: [S; N],
    dy0: [S; N],
    len: S,
    atol: &[S; N],
    h_try: S,
) -> Result<Advanced<S, N>, StepError> {
    match ctl.method {
        Method::Dp54 => adaptive(&DP54, ctl, f, y0, dy0, len, atol, h_try),
        Method::Bs32 => adaptive(&BS32, ctl, f, y0, dy0, len, atol, h_try),
        Method::BackwardEuler => backward_euler(ctl, f, y0, len, atol),
    }
}

#[allow(clippy::too_many_arguments)]
#[inline]
fn adaptive<S: Scalar, const N: usize, const M: usize>(
    t: &Tableau<M>,
    ctl: &Control<S>,
    f: &mut impl FnMut(S, &[S; N]) -> Result<[S; N], StepError>,
    y0: [S; N],
    dy0: [S; N],
    len: S,
    atol: &[S; N],
    h_try: S,
) -> Result<Advanced<S, N>, StepError> {
    let mut x = S::ZERO;
    let mut y = y0;
    let mut dy = dy0;
    let mut h = if h_try > S::ZERO { h_try } else { len };
    let h_min = S::EPSILON * S::lit(16.0) * len;
    let mut attempts = 0u16;
    // Why the last attempt failed, returned if the budget runs out.
    let mut failure = StepError::ToleranceNotMet;
    loop {
        let remaining = len - x;
        // Take the rest in one go when it is not much longer than h (less than
        // the 0.8 shrink of a rejection undoes, so a rejection always shrinks).
        let last = remaining <= h * S::lit(1.1);
        if last {
            h = remaining;
        }
        attempts += 1;
        if attempts > ctl.max_substeps || !(h > h_min) {
            return Err(failure);
        }
        match try_substep(t, ctl, f, x, &y, &dy, h, atol) {
            Ok((y_new, dy_new, ratio)) if ratio <= S::ONE => {
                x += h;
                y = y_new;
                dy = dy_new;
                h *= factor::<S>(&t.thresholds, ratio);
                if last {
                    return Ok(Advanced { y, dy, h_next: h });
                }
            }
            Ok((y_new, _, ratio)) => {
                failure = if y_new.iter().all(|v| v.is_finite()) {
                    StepError::ToleranceNotMet
                } else {
                    StepError::NonFiniteState
                };
                h *= factor::<S>(&t.thresholds, ratio).min(S::lit(0.8));
            }
            Err(e) => {
                // A stage left the model's domain (an overshooting trial
                // sub-step can): retry smaller, report it if that never helps.
                failure = e;
                h *= S::lit(0.25);
            }
        }
    }
}

/// One sub-step of size `h` from `(x, y)` with derivative `dy`: the new state,
/// its derivative (the last stage) and the largest error ratio.
#[allow(clippy::too_many_arguments)]
#[inline]
fn try_substep<S: Scalar, const N: usize, const M: usize>(
    t: &Tableau<M>,
    ctl: &Control<S>,
    f: &mut impl FnMut(S, &[S; N]) -> Result<[S; N], StepError>,
    x: S,
    y: &[S; N],
    dy: &[S; N],
    h: S,
    atol: &[S; N],
) -> Result<([S; N], [S; N], S), StepError> {
    let mut k = [[S::ZERO; N]; M];
    k[0] = *dy;
    let mut y_stage = *y;
    for s in 1..M {
        y_stage = *y;
        for (j, kj) in k.iter().enumerate().take(s) {
            if t.a[s][j].0 != 0 {
                let ha = h * q::<S>(t.a[s][j]);
                for i in 0..N {
                    y_stage[i] += ha * kj[i];
                }
            }
        }
        k[s] = f(x + h * q::<S>(t.c[s]), &y_stage)?;
    }
    // First same as last: the last stage was evaluated at the new solution.
    let mut ratio = S::ZERO;
    for i in 0..N {
        let mut err = S::ZERO;
        for (s, ks) in k.iter().enumerate() {
            if t.e[s].0 != 0 {
                err += q::<S>(t.e[s]) * ks[i];
            }
        }
        let err = (h * err).abs();
        if err == S::ZERO {
            continue;
        }
        let r = err / (atol[i] + ctl.tol * y[i].abs().max(y_stage[i].abs()));
        // NaN compares false: a non-finite estimate counts as a failure.
        if !(r <= ratio) {
            ratio = if r.is_finite() { r } else { S::MAX };
        }
    }
    Ok((y_stage, k[M - 1], ratio))
}
/// One backward-Euler step `y1 = y0 + len f(len, y1)` for the first component,
/// with the others (energy-like integrals) following `y1_i = y0_i + len
/// f_i(len, y1)`, solved by Newton's method on the first component with a
/// finite-difference derivative.
fn backward_euler<S: Scalar, const N: usize>(
    ctl: &Control<S>,
    f: &mut impl FnMut(S, &[S; N]) -> Result<[S; N], StepError>,
    y0: [S; N],
    len: S,
    atol: &[S; N],
) -> Result<Advanced<S, N>, StepError> {
    // The implicit equations, reduced to the first component z:
    // g(z) = z - y0[0] - len * f0(len, Y(z)), where Y(z) also updates the
    // other components with the end-of-step z (as OpenSees does for energy).
    let mut eval = |z: S| -> Result<(S, [S; N], [S; N]), StepError> {
        let mut y = y0;
        y[0] = z;
        // Components 1.. depend on z through f_i = f_i(z) (energy rate is
        // proportional to z), so evaluate them at the end state iteratively:
        // for the BWBN energy this is exact after one pass because f_1 does not
        // depend on y[1].
        let d = f(len, &y)?;
        for i in 1..N {
            y[i] = y0[i] + len * d[i];
        }
        let d = f(len, &y)?;
        Ok((z - y0[0] - len * d[0], y, d))
    };
    let scale = atol[0] + ctl.tol;
    let dz = scale * S::lit(1e-3) + S::EPSILON * S::lit(64.0);
    let mut z = y0[0];
    for _ in 0..ctl.max_substeps {
        let (g, y, d) = eval(z)?;
        let (gp, _, _) = eval(z + dz)?;
        let (gm, _, _) = eval(z - dz)?;
        let slope = (gp - gm) / (dz + dz);
        let step = g / slope;
        if !step.is_finite() {
            return Err(StepError::NotConverged);
        }
        z -= step;
        if step.abs() <= ctl.tol {
            let (_, y, d) = if step == S::ZERO { (g, y, d) } else { eval(z)? };
            return Ok(Advanced {
                y,
                dy: d,
                h_next: len,
            });
        }
    }
    Err(StepError::NotConverged)
}
