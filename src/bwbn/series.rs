//! Plain Bouc-Wen along the displacement by series ([`Method::Series`](super::Method::Series)).
//!
//! With every effect off (A = nu = eta = h = 1), eq. 3.4 along an increment
//! of direction `d = sgn(du)` is autonomous in the distance `s = |u - u0|`.
//! While z keeps its sign `sigma`, `x = |z|` obeys
//!
//! ```text
//! dx/ds = d sigma (1 - c x^n),   c = beta d sigma + gamma
//! ```
//!
//! **Away from z = 0** the solution is analytic in s and is summed as its
//! Taylor series at x0. The coefficients of `p = x^n` follow from those of x
//! by the recurrence of a power (`x p' = n x' p`), so a sub-step evaluates
//! one `pow` however high its order:
//!
//! ```text
//! x_1 = d sigma (1 - c p_0),   k x_0 p_k = sum_{j=1..k} (n j - (k - j)) x_j p_(k-j),
//! x_(k+1) = -d sigma c p_k / (k + 1)
//! ```
//!
//! The order grows until the last two terms at the sub-step's length are
//! within the tolerance; when [`MAX_ORDER`] is reached first, the sub-step is
//! halved until they are (the coefficients do not depend on the length, so
//! only the sum is redone).
//!
//! **Near z = 0** (`|c| x^n <= NEAR`) `x^n` is not analytic and the sign of z,
//! hence c, may change within the sub-step. There s is summed as a function of
//! x instead, `ds/dx = 1 / (1 - c x^n)` in closed form:
//!
//! ```text
//! G_c(x) = integral_0^x dxi / (1 - c xi^n) = x sum_m (c x^n)^m / (n m + 1)
//! ```
//!
//! a geometric series of ratio at most `EDGE` (0.2). The distance to z = 0 is
//! `G_c(x0)`; the x reached after a distance is found by Newton's method on
//! `G`. The energy of eq. 3.8, `de/du = k_hys z`, is summed alike: the series
//! of z integrated term by term, and near zero
//! `integral x ds = H_c(x) = x^2 sum_m (c x^n)^m / (n m + 2)`.

use super::base::BoucWen;
use super::effects::Stiffness;
use super::integrate::Control;
use crate::element::StepError;
use crate::scalar::Scalar;

/// Highest order of a Taylor sub-step.
pub const MAX_ORDER: usize = 12;

/// Coefficient arrays hold 16 entries and every runtime index is masked with
/// `LEN - 1`: the mask never changes an index (all are at most `MAX_ORDER`),
/// but it lets the compiler see that none can be out of bounds, so no panic
/// path reaches the firmware, at one instruction an index (iterators did the
/// same at 33% more instructions a step on the Cortex-M4F: 1,072 against 805).
const LEN: usize = 16;
const MASK: usize = LEN - 1;

/// Where the sums in x take over from the Taylor series: `|c| x^n` at most
/// this. Near z = 0 the Taylor series' radius shrinks with x, so it would
/// need ever shorter sub-steps.
const NEAR: f32 = 0.1;

/// How far the sums in x carry a sub-step moving away from z = 0: to
/// `|c| x^n = EDGE`, beyond `NEAR` so that the Taylor series takes the next
/// sub-step whatever the rounding at the edge (their ratio is then 0.2:
/// 24 terms reach `0.2^24 = 2e-17`).
const EDGE: f32 = 0.2;

/// Most terms of the sums in x and Newton iterations (Newton converges
/// quadratically from `G(x) ~ x`).
const MAX_TERMS: usize = 24;
/// The weights of the sums' terms, masked like the coefficients (`LEN`).
const TERMS_LEN: usize = 32;
const TERMS_MASK: usize = TERMS_LEN - 1;
const MAX_NEWTON: usize = 16;

/// The end of an increment.
#[derive(Clone, Copy, Debug)]
pub(crate) struct End<S> {
    /// Hysteretic displacement.
    pub z: S,
    /// Hysteretic energy.
    pub energy: S,
    /// dz/du at the end, along the increment.
    pub dz_du: S,
    /// d(energy)/du at the end, `k_hys z`.
    pub de_du: S,
}

/// The terms of the sums in x for one sub-step: how many, and the weights
/// `1 / (n m + 1)` of `G_c` and `1 / (n m + 2)` of `H_c` for term m.
struct Terms<S> {
    count: usize,
    g: [S; TERMS_LEN],
    h: [S; TERMS_LEN],
}

/// Plain Bouc-Wen on one increment.
struct Branch<'a, S: Scalar> {
    base: &'a BoucWen<S>,
    /// Direction of the increment, +1 or -1.
    d: S,
    /// Absolute tolerance of z.
    atol: S,
}

impl<'a, S: Scalar> Branch<'a, S> {
    /// The coefficient c for z of sign `sigma`.
    fn c(&self, sigma: S) -> S {
        self.base.beta * self.d * sigma + self.base.gamma
    }

    /// `x^n` for the branch of coefficient c: zero when c is, since `x^n`
    /// only ever enters multiplied by c (`dx/ds = d sigma (1 - c x^n)`). In
    /// fixed point `x^n` saturates for large x (`100^8`) and `0 * saturated`
    /// stays saturated, which gave z = 32768 for `beta = gamma = 0` (found by
    /// review).
    fn pow_n(&self, c: S, x: S) -> S {
        if c == S::ZERO {
            S::ZERO
        } else {
            x.powf(self.base.n)
        }
    }

    /// Whether `|c| x^n` puts x in the region of the sum in x.
    fn near(&self, c: S, xn: S) -> bool {
        (c * xn).abs() <= S::lit(NEAR)
    }

    /// How many terms of the sums reach the tolerance wherever x is at most
    /// `x_hi` (with `q_hi = |c| x_hi^n`), and their weights: the first term
    /// at `x_hi` that moves `G_c` (a distance) by less than a tenth of z's
    /// tolerance, or by less than the arithmetic's resolution. The ratio is
    /// at most `EDGE`, so what is left after it is below a quarter of it. One
    /// count serves every sum of a sub-step, so that `G_c` is one smooth
    /// function of x for Newton's method (a count chosen at each x made
    /// `G_c` jump by about a term, more than Newton's stopping rule, which
    /// then cycled between two iterates), and the weights' divisions are
    /// done once, not at every iteration.
    fn terms(&self, q_hi: S, x_hi: S) -> Terms<S> {
        let n = self.base.n;
        let cut = S::lit(0.1) * self.atol;
        let mut t = Terms {
            count: MAX_TERMS,
            g: [S::ZERO; TERMS_LEN],
            h: [S::ZERO; TERMS_LEN],
        };
        let (mut term, mut nm) = (x_hi, S::ZERO);
        for m in 1..MAX_TERMS + 1 {
            nm += n;
            let rg = S::ONE / (nm + S::ONE);
            t.g[m & TERMS_MASK] = rg;
            t.h[m & TERMS_MASK] = S::ONE / (nm + S::from_i32(2));
            term *= q_hi.abs();
            let dg = term * rg;
            if dg <= cut || dg <= S::EPSILON * x_hi {
                t.count = m;
                break;
            }
        }
        t
    }

    /// `(G_c(x), H_c(x))` for `x^n = xn`, summed to `t.count` terms.
    fn sums(&self, c: S, x: S, xn: S, t: &Terms<S>) -> (S, S) {
        if x == S::ZERO {
            return (S::ZERO, S::ZERO);
        }
        let q = c * xn;
        let (mut g, mut h, mut qm) = (S::ONE, S::ONE / S::from_i32(2), S::ONE);
        for m in 1..t.count + 1 {
            qm *= q;
            g += qm * t.g[m & TERMS_MASK];
            h += qm * t.h[m & TERMS_MASK];
        }
        (x * g, x * x * h)
    }

    /// The x in `[0, hi]` with `G_c(x) = target`, its `H_c` and `x^n`, by
    /// Newton's method. It stops when a correction is below a thousandth of
    /// z's tolerance or at the arithmetic's resolution, and returns the
    /// corrected x with `H_c` and `x^n` carried to it to first order from
    /// the iterate's (`H' = x G'`, `(x^n)' = n x^n / x`), so that no further
    /// power is taken; a correction clamped at `hi` returns `hi` itself, which
    /// the caller recognises as the edge.
    fn solve(&self, c: S, target: S, hi: S, terms: &Terms<S>) -> Result<(S, S, S), StepError> {
        let n = self.base.n;
        let stop = S::lit(1e-3) * self.atol;
        let mut x = target.min(hi);
        for _ in 0..MAX_NEWTON {
            let xn = self.pow_n(c, x);
            let (g, h) = self.sums(c, x, xn, terms);
            // G' = 1 / (1 - c x^n).
            let slope = S::ONE - c * xn;
            let next = (x - (g - target) * slope).max(S::ZERO).min(hi);
            let dx = next - x;
            if dx.abs() <= stop
                || dx.abs() <= S::from_i32(4) * (S::EPSILON * next + S::MIN_POSITIVE)
            {
                if x == S::ZERO {
                    let xn = self.pow_n(c, next);
                    let (_, h) = self.sums(c, next, xn, terms);
                    return Ok((next, h, xn));
                }
                return Ok((next, h + dx * x / slope, xn + n * xn * dx / x));
            }
            x = next;
        }
        Err(StepError::ToleranceNotMet)
    }

    /// The x at which `|c| x^n = EDGE` (no limit when c = 0), and that
    /// `x^n`.
    fn edge(&self, c: S) -> (S, S) {
        if c == S::ZERO {
            (S::MAX, S::MAX)
        } else {
            let xn = S::lit(EDGE) / c.abs();
            let edge = xn.powf(S::ONE / self.base.n);
            if edge.is_finite() {
                (edge, xn)
            } else {
                (S::MAX, S::MAX)
            }
        }
    }

    /// A sub-step by the sums in x from `z` (in their region, `x0n` =
    /// `|z|^n`) over at most `len`: the new z, the distance covered,
    /// `∫ z ds` and dz/du at the end.
    fn near_zero(&self, z: S, x0n: S, len: S) -> Result<(S, S, S, S), StepError> {
        let x0 = z.abs();
        let mut sigma = if z == S::ZERO { self.d } else { z.signum0() };
        let (mut used, mut area, mut start) = (S::ZERO, S::ZERO, (x0, x0n));
        if z != S::ZERO && self.d * sigma < S::ZERO {
            // Towards zero: G_c(x0) to reach it.
            let c = self.c(sigma);
            let terms = self.terms(c * x0n, x0);
            let (to_zero, h0) = self.sums(c, x0, x0n, &terms);
            if len <= to_zero {
                let (x, h, xn) = self.solve(c, to_zero - len, x0, &terms)?;
                return Ok((sigma * x, len, sigma * (h0 - h), S::ONE - c * xn));
            }
            used = to_zero;
            area = sigma * h0;
            sigma = -sigma;
            start = (S::ZERO, S::ZERO);
        }
        // Away from zero (from x0, or from 0 after crossing it), up to the
        // edge of the region.
        let c = self.c(sigma);
        let (edge, edge_n) = self.edge(c);
        let terms = self.terms(c * edge_n, edge);
        let (g_start, h_start) = self.sums(c, start.0, start.1, &terms);
        let (x, h, xn) = self.solve(c, g_start + (len - used), edge, &terms)?;
        if x < edge {
            return Ok((
                sigma * x,
                len,
                area + sigma * (h - h_start),
                S::ONE - c * xn,
            ));
        }
        let (g_edge, h_edge) = self.sums(c, edge, edge_n, &terms);
        Ok((
            sigma * edge,
            used + (g_edge - g_start),
            area + sigma * (h_edge - h_start),
            S::ONE - c * edge_n,
        ))
    }

    /// A Taylor sub-step from `z != 0` over at most `len`, or
    /// `Err(|z|^n)` when z is in the region of the sums in x.
    ///
    /// The coefficients are kept relative to `x0` and the length in units of
    /// `x0`: `X_k = x_k x0^(k-1)`, `P_k = p_k x0^k / p0`, `r = s / x0`, which
    /// turns the recurrence into `k P_k = sum (n j - (k - j)) X_j P_(k-j)`,
    /// `X_(k+1) = -d sigma c p0 P_k / (k + 1)` (no division by x0). Unscaled,
    /// `x_k` grows like `x0^-k` near the region of the sums, which
    /// overflowed `f32` at order 12 once x0 was below about 1e-3 (lengths in
    /// metres) and saturated Q15.16 (found by review).
    #[allow(clippy::type_complexity)]
    fn taylor(&self, z: S, len: S) -> Result<Result<(S, S, S, S), S>, StepError> {
        let sigma = z.signum0();
        let x0 = z.abs();
        let c = self.c(sigma);
        let n = self.base.n;
        let mut p = [S::ZERO; LEN];
        let mut x = [S::ZERO; LEN];
        let p0 = self.pow_n(c, x0);
        if self.near(c, p0) {
            return Ok(Err(p0));
        }
        let ds = self.d * sigma;
        let x1 = ds * (S::ONE - c * p0);
        // The length unit: x0, or shorter where x changes faster (rate |x1|)
        // or the series' radius is shorter (about x0 / (n |c| p0)).
        let g = x1.abs().max(S::ONE + n * (c * p0).abs());
        p[0] = S::ONE;
        x[0] = S::ONE;
        x[1] = x1 / g;
        // The tolerance in units of x0.
        let atol = self.atol / x0;
        let (mut s, mut r) = (len, len / x0 * g);
        // Far beyond the radius (an increment of tens of thousands of lengths
        // x0 / g) r is beyond fixed point's range: halve the length until it
        // is not, so that s and r stay one length.
        for _ in 0..32 {
            if r.is_finite() {
                break;
            }
            s = s / S::from_i32(2);
            r = s / x0 * g;
        }
        let mut top = MAX_ORDER;
        let mut prev = x[1].abs() * r;
        let mut r_k = r;
        let (n1, minus_dscp) = (n + S::ONE, -(ds * c * p0) / g);
        // The weight of X_1 P_(k-1), n - (k - 1), falls by one an order.
        let mut w1 = n;
        for k in 1..MAX_ORDER {
            let (mut acc, mut w) = (S::ZERO, w1);
            // (An exclusive range: `1..=k` kept an extra exit test in the loop.)
            for j in 1..k + 1 {
                // n j - (k - j), rising by n + 1 with j.
                acc += w * x[j & MASK] * p[(k - j) & MASK];
                w += n1;
            }
            w1 -= S::ONE;
            let pk = acc * S::recip_int(k);
            let xk1 = pk * (minus_dscp * S::recip_int(k + 1));
            p[k & MASK] = pk;
            x[(k + 1) & MASK] = xk1;
            r_k *= r;
            let t = xk1.abs() * r_k;
            if k >= 2 && t + prev <= atol {
                top = k + 1;
                break;
            }
            prev = t;
        }
        // In fixed point each coefficient is off by about a unit in its last
        // place, which the sum multiplies by up to `r^top` (`r_k` here): the
        // length is also halved until that stays within the tolerance. (Found
        // on random parameter sets in Q15.16: coefficients below the last
        // place read as zero, so the terms looked converged at r = 2.3 while
        // the sum was 2% of Zu off.) Not where `x1` is zero: then every
        // coefficient is exactly zero and z stays (at Zu to the last place).
        // The resolution is relative in floating point, where this is
        // compiled out.
        let absolute = S::MIN_POSITIVE > S::lit(1e-30);
        let lsb = S::MIN_POSITIVE * S::from_i32(4);
        // After a halving fixed point chooses the order again at the shorter
        // length: kept at the first length's, the bound above held Q15.16 to
        // 0.4 Zu a sub-step along saturation (found by review). Floating
        // point keeps the full order, whose derivative (the tangent)
        // converges more slowly than the value.
        let mut halvings = 0;
        let rounded = absolute && x[1] != S::ZERO;
        let last = top;
        while (top == MAX_ORDER && !Self::small(&x, r, atol)) || (rounded && lsb * r_k > atol) {
            s = s / S::from_i32(2);
            r = r / S::from_i32(2);
            if absolute {
                (top, r_k) = Self::order_at(&x, last, r, atol);
            }
            halvings += 1;
            if halvings > 64 || !(r > S::ZERO) {
                return Err(StepError::ToleranceNotMet);
            }
        }
        // A sum that overshoots z = 0 (possible only at the edge of the
        // series' radius) is summed again over half the length.
        for _ in 0..64 {
            let (v, dv, iv) = Self::sum(&x, top, r);
            // (The energy's integral may pass fixed point's range where z
            // does not, |z| above 181: it is then reported as non-finite.)
            let (v, iv) = (x0 * v, x0 * (x0 * iv / g));
            if v > S::ZERO && v.is_finite() {
                return Ok(Ok((sigma * v, s, sigma * iv, ds * dv * g)));
            }
            s = s / S::from_i32(2);
            r = r / S::from_i32(2);
        }
        Err(StepError::NonFiniteState)
    }

    /// The order at which the series `x[..=last]` at length r is truncated
    /// (the first k from 3 whose last two terms are within `atol`, as the
    /// recurrence chooses it, or `last`), and `r^k`.
    fn order_at(x: &[S; LEN], last: usize, r: S, atol: S) -> (usize, S) {
        let mut r_k = r;
        let mut prev = x[1].abs() * r;
        for k in 2..last + 1 {
            r_k *= r;
            let t = x[k & MASK].abs() * r_k;
            if k >= 3 && t + prev <= atol {
                return (k, r_k);
            }
            prev = t;
        }
        (last, r_k)
    }

    /// Horner: `X(r)`, `dX/dr` and `∫_0^r X` of the series `x[..=top]`.
    fn sum(x: &[S; LEN], top: usize, r: S) -> (S, S, S) {
        let xt = x[top & MASK];
        let (mut v, mut dv) = (xt, S::from_i32(top as i32) * xt);
        let mut iv = xt * S::recip_int(top + 1);
        for k in (1..top).rev() {
            let xk = x[k & MASK];
            v = v * r + xk;
            dv = dv * r + S::from_i32(k as i32) * xk;
            iv = iv * r + xk * S::recip_int(k + 1);
        }
        let x0 = x[0];
        (v * r + x0, dv, (iv * r + x0) * r)
    }

    /// Whether the last two terms of a full-order series are within the
    /// tolerance `atol` at length `r` (both in units of x0).
    fn small(x: &[S; LEN], r: S, atol: S) -> bool {
        let mut r_k = S::ONE;
        for _ in 0..MAX_ORDER - 1 {
            r_k *= r;
        }
        (x[MAX_ORDER - 1].abs() + x[MAX_ORDER].abs() * r) * r_k <= atol
    }
}

/// Whether the arithmetic resolves the regions of the sums near z = 0: the
/// one where z approaches zero (`c = gamma - beta`; the Taylor series hands
/// over at `|c| x^n = NEAR`) and, in fixed point, the one where it leaves
/// zero (`c = beta + gamma`; the sums carry it to `|c| x^n = EDGE`). Each
/// must reach beyond one unit of fixed point's last place (its resolution is
/// absolute) or, in floating point, of the last place at the z-scale (where
/// z leaves zero from exactly zero floating point resolves any region). Where
/// they do not the element integrates by the arithmetic's pair instead:
/// - approaching, n = 0.3, `beta = 2`, `gamma = -1`: the region ends at
///   1.2e-5, 0.8 units of Q15.16, and 390 of 400 unloadings across z = 0 were
///   refused (found by review); n = 0.3, `beta = 20`, `gamma = -19`: 2.3e-9,
///   0.02 units of `f32` at Zu = 1, and 269 were refused;
/// - leaving, the hardening set n = 0.1, `beta = gamma = -1` in Q15.16: the
///   sums' region ends at 1e-10, and zigzags were refused or returned z = 0
///   (a second review).
///
/// Where a region ends at 1.2 units or more (n = 0.15, `beta = 0.635`,
/// `gamma = 0.126`) `Series` was sound and more accurate than the pair (4e-4
/// against 8.9e-3 of Zu); a first criterion that took `|beta| + |gamma|` for
/// both branches moved such sets, and every hardening set with n below 0.145
/// in `f32`, to the pair, which refused them or was up to 50x less accurate.
pub(crate) fn resolves<S: Scalar>(base: &BoucWen<S>) -> bool {
    let absolute = S::MIN_POSITIVE > S::lit(1e-30);
    let unit = if absolute {
        S::MIN_POSITIVE
    } else {
        S::EPSILON * base.z_scale()
    };
    // `(end / |c|)^(1/n) >= unit`, compared as `end / |c| >= unit^n`: the
    // region's end itself is a unit or two of Q15.16 and would round there.
    let floor = unit.powf(base.n);
    let resolved = |end: f32, c: S| c == S::ZERO || S::lit(end) / c.abs() >= floor;
    resolved(NEAR, base.gamma - base.beta) && (!absolute || resolved(EDGE, base.beta + base.gamma))
}

/// Integrates plain Bouc-Wen from `(z0, energy0)` over `len > 0` in direction
/// `d`, in at most `ctl.max_substeps` sub-steps; `atol` is z's absolute
/// tolerance.
pub(crate) fn advance<S: Scalar>(
    base: &BoucWen<S>,
    ctl: &Control<S>,
    atol: S,
    (z0, energy0): (S, S),
    d: S,
    len: S,
) -> Result<End<S>, StepError> {
    let k_hys = Stiffness::plain(base).hys;
    let b = Branch { base, d, atol };
    let (mut z, mut area, mut left) = (z0, S::ZERO, len);
    for _ in 0..ctl.max_substeps {
        let step = if z == S::ZERO {
            Err(S::ZERO)
        } else {
            b.taylor(z, left)?
        };
        let (z1, used, a, dz) = match step {
            Ok(s) => s,
            Err(zn) => b.near_zero(z, zn, left)?,
        };
        if !used.is_finite() {
            return Err(StepError::NonFiniteState);
        }
        z = z1;
        area += a;
        if used >= left {
            let energy = energy0 + d * k_hys * area;
            return Ok(End {
                z,
                energy,
                dz_du: dz,
                de_du: k_hys * z,
            });
        }
        left -= used;
    }
    Err(StepError::ToleranceNotMet)
}
