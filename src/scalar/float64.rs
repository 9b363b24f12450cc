//! `f64`: the host arithmetic, with `libm`'s correctly rounded-or-nearly functions.

use super::{fastmath, Scalar};

impl Scalar for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const MAX: Self = f64::MAX;
    const EPSILON: Self = f64::EPSILON;
    const NAME: &'static str = "f64";

    #[inline(always)]
    fn lit(x: f32) -> Self {
        x as f64
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self as f32
    }
    #[inline(always)]
    fn from_i32(x: i32) -> Self {
        x as f64
    }
    #[inline(always)]
    fn ratio(num: i32, den: i32) -> Self {
        num as f64 / den as f64
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        libm::fabs(self)
    }
    #[inline]
    fn powf(self, y: Self) -> Self {
        fastmath::f64::pow(self, y)
    }
    #[inline]
    fn exp(self) -> Self {
        fastmath::f64::exp(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
}
