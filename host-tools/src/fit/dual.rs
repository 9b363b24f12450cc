//! Forward-mode derivatives: a dual number the core's models run in.
//!
//! [`Dual<N>`] carries a value and its derivatives with respect to `N`
//! variables, and implements the core's [`Scalar`], so the very code that
//! simulates a parameter set in `f64` ([`Bwbn`](hysteresis::bwbn::Bwbn),
//! [`Sdof`](hysteresis::bwbn::Sdof), the integrators, every built-in effect)
//! also returns the exact derivatives of its output with respect to the
//! parameters: the Jacobian of a least-squares fit in one simulation instead of
//! one simulation per parameter, and without the truncation and round-off of
//! finite differences.
//!
//! The value part is computed with the same `f64` operations in the same order
//! as an `f64` simulation, and every comparison (`<`, `==`, `is_finite`) looks
//! at the value only, so a dual simulation takes the same sub-steps and returns
//! bit-identical values; the derivatives are those of that computation with
//! the sub-steps where they fell: the integrators take every sub-step size
//! through [`Scalar::value`], which drops the derivatives (where the error
//! control puts a sub-step is not a function of the parameters to
//! differentiate).

use hysteresis::Scalar;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A value and its derivatives with respect to `N` variables.
#[derive(Clone, Copy, Debug)]
pub struct Dual<const N: usize> {
    /// The value.
    pub v: f64,
    /// Its derivatives.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (zero derivatives).
    pub const fn cst(v: f64) -> Self {
        Dual { v, d: [0.0; N] }
    }

    /// Variable number `i`: derivative 1 with respect to itself.
    pub fn var(v: f64, i: usize) -> Self {
        let mut d = [0.0; N];
        if let Some(di) = d.get_mut(i) {
            *di = 1.0;
        }
        Dual { v, d }
    }

    /// The value `v` whose derivatives are `k` times those of `self`
    /// (the chain rule for a function with derivative `k` at `self`).
    #[inline(always)]
    fn chain(self, v: f64, k: f64) -> Self {
        let mut d = self.d;
        for di in &mut d {
            *di *= k;
        }
        Dual { v, d }
    }
}

impl<const N: usize> Default for Dual<N> {
    fn default() -> Self {
        Self::cst(0.0)
    }
}

/// Equality of values (derivatives are not compared), so that branches in the
/// models go the way they go in `f64`.
impl<const N: usize> PartialEq for Dual<N> {
    fn eq(&self, other: &Self) -> bool {
        self.v == other.v
    }
}

/// Order of values, as [`PartialEq`].
impl<const N: usize> PartialOrd for Dual<N> {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        self.v.partial_cmp(&other.v)
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for (a, b) in self.d.iter_mut().zip(&o.d) {
            *a += b;
        }
        self
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for (a, b) in self.d.iter_mut().zip(&o.d) {
            *a -= b;
        }
        self
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for ((r, a), b) in d.iter_mut().zip(&self.d).zip(&o.d) {
            *r = a * o.v + self.v * b;
        }
        Dual { v: self.v * o.v, d }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        let inv = 1.0 / o.v;
        let mut d = [0.0; N];
        for ((r, a), b) in d.iter_mut().zip(&self.d).zip(&o.d) {
            *r = (a - v * b) * inv;
        }
        Dual { v, d }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.chain(-self.v, -1.0)
    }
}

impl<const N: usize> AddAssign for Dual<N> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const N: usize> SubAssign for Dual<N> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<const N: usize> MulAssign for Dual<N> {
    #[inline(always)]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

impl<const N: usize> Scalar for Dual<N> {
    const ZERO: Self = Self::cst(0.0);
    const ONE: Self = Self::cst(1.0);
    const MAX: Self = Self::cst(f64::MAX);
    const EPSILON: Self = Self::cst(f64::EPSILON);
    const MIN_POSITIVE: Self = Self::cst(f64::MIN_POSITIVE);
    const NAME: &'static str = "dual";
    const CARRIES_DERIVATIVES: bool = true;

    fn lit(x: f32) -> Self {
        Self::cst(<f64 as Scalar>::lit(x))
    }
    fn from_f64(x: f64) -> Self {
        Self::cst(x)
    }
    fn to_f64(self) -> f64 {
        self.v
    }
    fn to_f32(self) -> f32 {
        self.v as f32
    }
    /// The value as a constant: a sub-step size chosen by the error control
    /// carries no derivatives (see [`Scalar::value`]).
    fn value(self) -> Self {
        Self::cst(self.v)
    }
    fn from_i32(x: i32) -> Self {
        Self::cst(<f64 as Scalar>::from_i32(x))
    }
    fn ratio(num: i32, den: i32) -> Self {
        Self::cst(<f64 as Scalar>::ratio(num, den))
    }
    /// Whether the value is finite (the derivatives are checked where the
    /// Jacobian is assembled).
    fn is_finite(self) -> bool {
        self.v.is_finite()
    }
    fn abs(self) -> Self {
        if self.v < 0.0 {
            -self
        } else {
            self
        }
    }
    /// `x^y`: `d(x^y) = y x^(y-1) dx + x^y ln(x) dy`. At `x = 0` the value is
    /// `0^y` and the derivatives are taken as zero (the one-sided derivative
    /// of `|z|^n` at `z = 0` for `n > 1`; the models meet `x = 0` only there).
    fn powf(self, y: Self) -> Self {
        let v = Scalar::powf(self.v, y.v);
        if self.v == 0.0 {
            return Self::cst(v);
        }
        let mut r = self.chain(v, y.v * v / self.v);
        if y.d.iter().any(|&dy| dy != 0.0) {
            let k = v * self.v.ln();
            for (r, dy) in r.d.iter_mut().zip(&y.d) {
                *r += k * dy;
            }
        }
        r
    }
    fn exp(self) -> Self {
        let v = Scalar::exp(self.v);
        self.chain(v, v)
    }
    /// `sqrt(x)`; at `x = 0` the derivatives are taken as zero.
    fn sqrt(self) -> Self {
        let v = Scalar::sqrt(self.v);
        if v == 0.0 {
            return Self::cst(v);
        }
        self.chain(v, 0.5 / v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type D2 = Dual<2>;

    /// Central difference of `f` along variable `i` at `(a, b)`.
    fn central(f: impl Fn(f64, f64) -> f64, a: f64, b: f64, i: usize) -> f64 {
        let h = 1e-6;
        let (da, db) = if i == 0 { (h, 0.0) } else { (0.0, h) };
        (f(a + da, b + db) - f(a - da, b - db)) / (2.0 * h)
    }

    fn check(fd: impl Fn(D2, D2) -> D2, ff: impl Fn(f64, f64) -> f64, a: f64, b: f64) {
        let r = fd(D2::var(a, 0), D2::var(b, 1));
        assert_eq!(r.v, ff(a, b), "values equal the f64 computation exactly");
        for i in 0..2 {
            let want = central(&ff, a, b, i);
            assert!(
                (r.d[i] - want).abs() <= 1e-7 * want.abs().max(1.0),
                "d/dx{i} at ({a}, {b}): {} against central difference {want}",
                r.d[i]
            );
        }
    }

    #[test]
    fn arithmetic_derivatives_match_central_differences() {
        check(
            |x, y| x * y + x / y - y,
            |x, y| x * y + x / y - y,
            1.3,
            -0.7,
        );
        check(
            |x, y| -(x - y) * (x + y),
            |x, y| -(x - y) * (x + y),
            0.4,
            2.5,
        );
        check(|x, y| (x * y).abs(), |x, y| (x * y).abs(), 0.4, -2.5);
        let mut acc = D2::var(0.9, 0);
        acc += D2::var(0.3, 1);
        acc *= D2::var(0.9, 0);
        acc -= D2::var(0.3, 1);
        assert_eq!(acc.v, (0.9 + 0.3) * 0.9 - 0.3);
        assert_eq!(acc.d, [2.0 * 0.9 + 0.3, 0.9 - 1.0]);
    }

    #[test]
    fn transcendental_derivatives_match_central_differences() {
        // |z|^n with both the base and the exponent variable, as in the model
        check(
            |z, n| z.abs().powf(n),
            |z, n| Scalar::powf(z.abs(), n),
            -0.37,
            1.2,
        );
        check(|z, n| z.powf(n), <f64 as Scalar>::powf, 2.6, 0.45);
        check(|x, y| (x * y).exp(), |x, y| Scalar::exp(x * y), -0.8, 1.9);
        check(
            |x, y| (x * x + y).sqrt(),
            |x, y| Scalar::sqrt(x * x + y),
            1.7,
            0.2,
        );
    }

    #[test]
    fn comparisons_and_zero_bases_follow_the_value() {
        let a = D2::var(1.0, 0);
        let b = D2::cst(1.0);
        assert_eq!(a, b, "equal values compare equal whatever the derivatives");
        assert!(D2::var(-1.0, 1) < b);
        assert!(!D2::cst(f64::NAN).is_finite());
        let zero = D2::ZERO.powf(D2::var(1.2, 1));
        assert_eq!((zero.v, zero.d), (0.0, [0.0, 0.0]));
        assert_eq!(D2::ZERO.sqrt().d, [0.0, 0.0]);
        assert_eq!(
            D2::var(1.0, 5).d,
            [0.0, 0.0],
            "an index past N seeds nothing"
        );
    }
}
