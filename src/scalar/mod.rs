//! The arithmetic the models are written in.
//!
//! Every model in this crate is generic over [`Scalar`], implemented for
//!
//! * `f64`: the host (fitting, reference simulations),
//! * `f32`: microcontrollers with a single-precision FPU (Cortex-M4F, M7),
//! * [`Fixed`]: a saturating Q15.16 fixed-point number for parts without an FPU
//!   (Cortex-M0/M3).
//!
//! The transcendental functions a hysteresis model needs (`|z|^n`, `exp`, `sqrt`)
//! are part of the trait so that each arithmetic uses the implementation that is
//! right for it: table-driven `pow`/`exp` for `f64`, table-free ones counted in
//! instructions for `f32` (both in `fastmath`), integer ones for the fixed-point
//! type (see `docs/benchmarks.md` and the accuracy tests in each module).
//!
//! Non-finite values have one meaning in every arithmetic: [`Scalar::is_finite`]
//! is false for NaN and infinities, and for a fixed-point value that has
//! saturated. Models check their results with it and refuse to commit a state
//! that is not finite.

mod fastmath;
mod fixed;
mod float32;
mod float64;

pub use fixed::Fixed;

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// `[0, 1/1, 1/2, ..., 1/16]` in the float type `$t`, each quotient rounded
/// once at compile time: the table of [`Scalar::recip_int`] for `f32` and
/// `f64`.
macro_rules! recip_table {
    ($t:ty) => {
        [
            0.0 as $t,
            1.0,
            1.0 / 2.0,
            1.0 / 3.0,
            1.0 / 4.0,
            1.0 / 5.0,
            1.0 / 6.0,
            1.0 / 7.0,
            1.0 / 8.0,
            1.0 / 9.0,
            1.0 / 10.0,
            1.0 / 11.0,
            1.0 / 12.0,
            1.0 / 13.0,
            1.0 / 14.0,
            1.0 / 15.0,
            1.0 / 16.0,
        ]
    };
}
pub(crate) use recip_table;

/// A real number type the models can be computed in.
///
/// Implementations must make `+ - * /` total (no panics): floats follow IEEE 754,
/// [`Fixed`] saturates (and then reports itself as not finite).
pub trait Scalar:
    Copy
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + Send
    + Sync
    + 'static
{
    /// 0
    const ZERO: Self;
    /// 1
    const ONE: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The spacing of representable values near 1 (machine epsilon, or one
    /// least-significant bit for fixed point).
    const EPSILON: Self;
    /// The smallest positive value: one least-significant bit in fixed point,
    /// where the resolution is absolute, the smallest normal number in floating
    /// point.
    const MIN_POSITIVE: Self;
    /// Short name used in table headers and error messages (`"f64"`, `"f32"`, `"q16"`).
    const NAME: &'static str;
    /// Whether a number carries more than its value (the host's dual numbers
    /// carry derivatives with respect to parameters): the integrators then
    /// keep those derivatives well-defined where the model is not smooth
    /// (see `integrate::advance`). False for plain numbers, whose code paths
    /// this compiles out of.
    const CARRIES_DERIVATIVES: bool = false;

    /// Converts a literal. Models only call it with constants, which the
    /// compiler folds, so no float arithmetic reaches fixed-point code paths.
    fn lit(x: f32) -> Self;
    /// Converts an `f64` (host side: loading parameters, tests). Values out of
    /// range become non-finite (float) or saturate (fixed point).
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64` (host side and tests).
    fn to_f64(self) -> f64;
    /// Converts to `f32` (logging on the device).
    fn to_f32(self) -> f32;
    /// Converts a small integer exactly.
    fn from_i32(x: i32) -> Self;
    /// `num / den`, rounded once. Used for exact rational constants (Runge-Kutta
    /// tableaus); constant-folded like [`lit`](Scalar::lit).
    fn ratio(num: i32, den: i32) -> Self;

    /// False for NaN, infinities and saturated fixed-point values.
    fn is_finite(self) -> bool;
    /// |x|
    fn abs(self) -> Self;
    /// `x^y` for `x >= 0`. Returns 0 for `x == 0` and `y > 0`. (The float
    /// implementations follow C99 elsewhere: `x^0 = 1`, `0^y = inf` for `y < 0`.)
    fn powf(self, y: Self) -> Self;
    /// e^x
    fn exp(self) -> Self;
    /// Square root of a non-negative number.
    fn sqrt(self) -> Self;

    /// The larger of two values (`self` if they are unordered).
    #[inline]
    fn max(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }
    /// The smaller of two values (`self` if they are unordered).
    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }
    /// `y0 + k (x - x0)`: the value at `x` of the line of slope `k` through
    /// `(x0, y0)`, the interpolation of every polygonal model. Fixed point
    /// evaluates it in one wide expression with one saturation check.
    #[inline]
    fn line(y0: Self, k: Self, x: Self, x0: Self) -> Self {
        y0 + k * (x - x0)
    }
    /// `1/k`, rounded once. The float types read `k <= 16` from a table: series
    /// coefficients divide by their index, and a division in every term would
    /// cost more than the term.
    #[inline]
    fn recip_int(k: usize) -> Self {
        Self::ratio(1, k as i32)
    }
    /// The value alone, as a constant. The identity for plain numbers; a
    /// number that carries more than its value (the host's dual numbers carry
    /// derivatives with respect to parameters) drops the rest. The
    /// integrators pass their sub-step sizes through it: where a sub-step
    /// ends is a decision of the error control, and derivatives of the state
    /// must be those of the sub-steps taken. (A sub-step size that carried
    /// derivatives fed them back through every later increment's carried size
    /// and grew them geometrically: to 1e5 in 90 increments, measured.)
    #[inline(always)]
    fn value(self) -> Self {
        self
    }
    /// +1 for positive, -1 for negative values, 0 for zero.
    #[inline]
    fn signum0(self) -> Self {
        if self > Self::ZERO {
            Self::ONE
        } else if self < Self::ZERO {
            -Self::ONE
        } else {
            Self::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn generic_identities<S: Scalar>(tol: f64) {
        let two = S::from_i32(2);
        assert_eq!((S::ONE + S::ONE), two);
        assert!((two.sqrt().to_f64() - core::f64::consts::SQRT_2).abs() < tol);
        assert!((S::ONE.exp().to_f64() - core::f64::consts::E).abs() < tol * 3.0);
        assert_eq!(S::ZERO.powf(S::lit(1.2)), S::ZERO);
        assert!((two.powf(S::lit(0.5)).to_f64() - core::f64::consts::SQRT_2).abs() < tol);
        assert_eq!(S::lit(-3.0).abs(), S::lit(3.0));
        assert_eq!(S::lit(-3.0).signum0(), -S::ONE);
        assert_eq!(S::ZERO.signum0(), S::ZERO);
        assert_eq!(S::ONE.max(two), two);
        assert_eq!(S::ONE.min(two), S::ONE);
        assert!(S::MAX.is_finite());
    }

    #[test]
    fn identities_hold_in_every_arithmetic() {
        generic_identities::<f64>(1e-15);
        generic_identities::<f32>(1e-6);
        generic_identities::<Fixed>(1e-4);
    }

    /// The tables of `recip_int` hold 1/k rounded once, as the division does,
    /// and the division takes over past them.
    #[test]
    fn recip_int_is_one_over_k() {
        for k in 1..40usize {
            assert_eq!(f64::recip_int(k).to_bits(), (1.0 / k as f64).to_bits());
            assert_eq!(f32::recip_int(k).to_bits(), (1.0 / k as f32).to_bits());
            assert_eq!(Fixed::recip_int(k), Fixed::ratio(1, k as i32));
        }
    }
}
