//! `f32`: the arithmetic of single-precision FPUs (Cortex-M4F, M7).
//!
//! Only `f32` operations appear here: no `f64` literal or call may reach firmware
//! built for an FPU that cannot do double precision (a soft-float `f64` operation
//! costs about 40 times its `f32` counterpart on the M4F).

use super::{fastmath, Scalar};

impl Scalar for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const MAX: Self = f32::MAX;
    const EPSILON: Self = f32::EPSILON;
    const MIN_POSITIVE: Self = f32::MIN_POSITIVE;
    const NAME: &'static str = "f32";

    #[inline(always)]
    fn lit(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn to_f32(self) -> f32 {
        self
    }
    #[inline(always)]
    fn from_i32(x: i32) -> Self {
        x as f32
    }
    #[inline(always)]
    fn recip_int(k: usize) -> Self {
        const RECIP: [f32; 17] = super::recip_table!(f32);
        match RECIP.get(k) {
            Some(&r) if k > 0 => r,
            _ => 1.0 / k as f32,
        }
    }
    #[inline(always)]
    fn ratio(num: i32, den: i32) -> Self {
        // Both are exact in f32 for the small integers of tableaus: one rounding.
        num as f32 / den as f32
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        libm::fabsf(self)
    }
    #[inline]
    fn powf(self, y: Self) -> Self {
        fastmath::f32::powf(self, y)
    }
    #[inline]
    fn exp(self) -> Self {
        fastmath::f32::expf(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrtf(self)
    }
}
