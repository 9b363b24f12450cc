//! Four lanes of `f64` for element batches.
//!
//! The hexahedron kernel works on [`LANES`] elements at once, each quantity
//! stored as one [`F4`] (structure of arrays). Every operator is a plain loop
//! over the four lanes, which the compiler turns into packed instructions:
//! two SSE2 operations per `F4` on a baseline x86-64 build, one AVX operation
//! when the build targets a CPU that has it. The code stays safe and portable.

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// Arithmetic shared by one `f64` and a batch of four ([`F4`]), so that a
/// formula of a material is written once and serves both the scalar
/// return mapping and the four-lane elastic trial. Every operation is the
/// lane-wise `f64` one, so a formula gives each lane of an [`F4`] exactly
/// the bits it gives that lane's value as an `f64`.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// One truth value per lane.
    type Mask: Copy;
    /// The same value in every lane.
    fn splat(v: f64) -> Self;
    /// Lane-wise square root.
    fn sqrt(self) -> Self;
    /// Lane-wise absolute value.
    fn abs(self) -> Self;
    /// Lane-wise `f64::max` (a NaN lane takes the other value).
    fn max(self, other: Self) -> Self;
    /// Lane-wise `f64::min`.
    fn min(self, other: Self) -> Self;
    /// Lane-wise `f64::clamp` (a NaN lane stays NaN).
    fn clamp(self, lo: f64, hi: f64) -> Self;
    /// Lane-wise `self > other` (false for NaN).
    fn gt(self, other: Self) -> Self::Mask;
    /// Lane-wise `self >= other` (false for NaN).
    fn ge(self, other: Self) -> Self::Mask;
    /// `a` where `mask` holds, `b` elsewhere.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn max(self, other: f64) -> f64 {
        f64::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: f64) -> f64 {
        f64::min(self, other)
    }
    #[inline(always)]
    fn clamp(self, lo: f64, hi: f64) -> f64 {
        f64::clamp(self, lo, hi)
    }
    #[inline(always)]
    fn gt(self, other: f64) -> bool {
        self > other
    }
    #[inline(always)]
    fn ge(self, other: f64) -> bool {
        self >= other
    }
    #[inline(always)]
    fn select(mask: bool, a: f64, b: f64) -> f64 {
        if mask {
            a
        } else {
            b
        }
    }
}

impl Real for F4 {
    type Mask = [bool; LANES];
    #[inline(always)]
    fn splat(v: f64) -> F4 {
        F4::splat(v)
    }
    #[inline(always)]
    fn sqrt(self) -> F4 {
        F4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F4 {
        F4(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn max(self, other: F4) -> F4 {
        F4(std::array::from_fn(|l| self.0[l].max(other.0[l])))
    }
    #[inline(always)]
    fn min(self, other: F4) -> F4 {
        F4::min(self, other)
    }
    #[inline(always)]
    fn clamp(self, lo: f64, hi: f64) -> F4 {
        F4(self.0.map(|v| v.clamp(lo, hi)))
    }
    #[inline(always)]
    fn gt(self, other: F4) -> [bool; LANES] {
        std::array::from_fn(|l| self.0[l] > other.0[l])
    }
    #[inline(always)]
    fn ge(self, other: F4) -> [bool; LANES] {
        std::array::from_fn(|l| self.0[l] >= other.0[l])
    }
    #[inline(always)]
    fn select(mask: [bool; LANES], a: F4, b: F4) -> F4 {
        F4(std::array::from_fn(
            |l| if mask[l] { a.0[l] } else { b.0[l] },
        ))
    }
}

/// Elements per batch.
pub const LANES: usize = 4;

/// One `f64` per element of a batch.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub struct F4(pub [f64; LANES]);

impl F4 {
    /// All lanes zero.
    pub const ZERO: F4 = F4([0.0; LANES]);

    /// The same value in every lane.
    #[inline(always)]
    pub fn splat(v: f64) -> F4 {
        F4([v; LANES])
    }

    /// Lane-wise `self * a + b`: one fused multiply-add (one rounding)
    /// where the build targets FMA (x86-64-v3, see `.cargo/config.toml`),
    /// a multiply and an add otherwise (a library call for the fused form
    /// would be slower than both).
    #[inline(always)]
    pub fn mul_add(self, a: F4, b: F4) -> F4 {
        let mut r = [0.0; LANES];
        for (l, r) in r.iter_mut().enumerate() {
            #[cfg(target_feature = "fma")]
            {
                *r = self.0[l].mul_add(a.0[l], b.0[l]);
            }
            #[cfg(not(target_feature = "fma"))]
            {
                *r = self.0[l] * a.0[l] + b.0[l];
            }
        }
        F4(r)
    }

    /// Lane-wise minimum.
    #[inline(always)]
    pub fn min(self, other: F4) -> F4 {
        F4(std::array::from_fn(|l| self.0[l].min(other.0[l])))
    }

    /// Lane-wise minimum with zero.
    #[inline(always)]
    pub fn min0(self) -> F4 {
        let mut r = [0.0; LANES];
        for (l, r) in r.iter_mut().enumerate() {
            *r = self.0[l].min(0.0);
        }
        F4(r)
    }

    /// Sum of the lanes, in lane order.
    #[inline(always)]
    pub fn sum(self) -> f64 {
        self.0.iter().sum()
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt, $tra:ident, $fa:ident) => {
        impl $tr for F4 {
            type Output = F4;
            #[inline(always)]
            fn $f(self, o: F4) -> F4 {
                let mut r = [0.0; LANES];
                for (l, r) in r.iter_mut().enumerate() {
                    *r = self.0[l] $op o.0[l];
                }
                F4(r)
            }
        }
        impl $tr<f64> for F4 {
            type Output = F4;
            #[inline(always)]
            fn $f(self, o: f64) -> F4 {
                let mut r = [0.0; LANES];
                for (l, r) in r.iter_mut().enumerate() {
                    *r = self.0[l] $op o;
                }
                F4(r)
            }
        }
        impl $tra for F4 {
            #[inline(always)]
            fn $fa(&mut self, o: F4) {
                *self = *self $op o;
            }
        }
    };
}

lane_op!(Add, add, +, AddAssign, add_assign);
lane_op!(Sub, sub, -, SubAssign, sub_assign);
lane_op!(Mul, mul, *, MulAssign, mul_assign);
lane_op!(Div, div, /, DivAssign, div_assign);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        let mut r = [0.0; LANES];
        for (l, r) in r.iter_mut().enumerate() {
            *r = -self.0[l];
        }
        F4(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_are_independent() {
        let a = F4([1.0, 2.0, 3.0, 4.0]);
        let b = F4([0.5, -1.0, 2.0, 0.0]);
        assert_eq!((a + b).0, [1.5, 1.0, 5.0, 4.0]);
        assert_eq!((a - b).0, [0.5, 3.0, 1.0, 4.0]);
        assert_eq!((a * b).0, [0.5, -2.0, 6.0, 0.0]);
        assert_eq!((a / F4::splat(2.0)).0, [0.5, 1.0, 1.5, 2.0]);
        assert_eq!(a.mul_add(b, a).0, [1.5, 0.0, 9.0, 4.0]);
        assert_eq!((-b).min0().0, [-0.5, 0.0, -2.0, 0.0]);
        assert_eq!(a.sum(), 10.0);
    }
}
