//! `f64`: the host arithmetic.
//!
//! `x^y` and `e^x` come from `fastmath` (within 1e-15 and 3.5e-16 relative, about
//! 3.3 and 1.8 times faster than `libm`), or, with the `std` feature, from the
//! standard library, which on x86-64 Linux (glibc, with FMA when the CPU has it)
//! is as fast in throughput and about 25-40 % shorter in latency (see
//! `benches/math.rs`).

#[cfg(not(feature = "std"))]
use super::fastmath;
use super::Scalar;

impl Scalar for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const MAX: Self = f64::MAX;
    const EPSILON: Self = f64::EPSILON;
    const MIN_POSITIVE: Self = f64::MIN_POSITIVE;
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
    fn recip_int(k: usize) -> Self {
        const RECIP: [f64; 17] = super::recip_table!(f64);
        match RECIP.get(k) {
            Some(&r) if k > 0 => r,
            _ => 1.0 / k as f64,
        }
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
    #[cfg(not(feature = "std"))]
    #[inline]
    fn powf(self, y: Self) -> Self {
        fastmath::f64::pow(self, y)
    }
    #[cfg(feature = "std")]
    #[inline]
    fn powf(self, y: Self) -> Self {
        std::primitive::f64::powf(self, y)
    }
    #[cfg(not(feature = "std"))]
    #[inline]
    fn exp(self) -> Self {
        fastmath::f64::exp(self)
    }
    #[cfg(feature = "std")]
    #[inline]
    fn exp(self) -> Self {
        std::primitive::f64::exp(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
}
