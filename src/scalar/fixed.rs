//! [`Fixed`]: saturating Q15.16 fixed point for FPU-less microcontrollers.
//!
//! A value is an `i32` holding `value * 2^16`: range about ±32767.99998,
//! resolution 2^-16 = 1.53e-5. Choose the units of a model so that its
//! displacements, forces and energies stay inside that range with room for the
//! resolution (for example mm and kN for a bridge column); the models detect
//! overflow and refuse the step instead of wrapping.
//!
//! Arithmetic saturates: a result outside the range becomes one of the two
//! saturated values, `i32::MAX` or `i32::MIN`, which play the part of ±infinity:
//! [`Scalar::is_finite`] is false for them and every operation with a saturated
//! operand returns a saturated value again (also `inf * 0` and `inf - inf`, which
//! would be NaN in floating point), with one exception: a finite value divided by a
//! saturated one is 0, as `x / inf` is in floating point. So a saturation anywhere in
//! a computation is visible in its result unless it only ever divides.
//!
//! `x^y`, `e^x` and `sqrt` use only integer instructions: `x^y = 2^(y log2 x)`,
//! with `log2` of the mantissa from a degree-7 polynomial on [1/sqrt 2, sqrt 2)
//! (max error 3.0e-7) and `2^f` from a degree-5 polynomial on [0, 1) (max
//! relative error 1.2e-7), both evaluated in Q2.30; `sqrt` is a bitwise integer
//! square root. Their error against `f64` is dominated by the final rounding to
//! 2^-16 (see the tests at the end of this file).

use super::Scalar;
use core::fmt;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

const FRAC: u32 = 16;
const ONE_RAW: i32 = 1 << FRAC;
const POS_INF: i32 = i32::MAX;
const NEG_INF: i32 = i32::MIN;

/// Saturating Q15.16 fixed-point number (see the documentation of `src/scalar/fixed.rs`).
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Fixed(i32);

impl Fixed {
    /// The value whose raw representation is `raw` (`value = raw / 2^16`).
    #[inline(always)]
    pub const fn from_raw(raw: i32) -> Self {
        Fixed(raw)
    }
    /// The raw representation (`value * 2^16`).
    #[inline(always)]
    pub const fn to_raw(self) -> i32 {
        self.0
    }
    #[inline(always)]
    const fn saturated(self) -> bool {
        self.0 == POS_INF || self.0 == NEG_INF
    }
    /// Clamps a wide intermediate result into the type, saturating out-of-range values.
    #[inline(always)]
    fn from_wide(v: i64) -> Self {
        if v >= POS_INF as i64 {
            Fixed(POS_INF)
        } else if v <= NEG_INF as i64 {
            Fixed(NEG_INF)
        } else {
            Fixed(v as i32)
        }
    }
}

impl fmt::Debug for Fixed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Integer-only formatting: no float code reaches fixed-point firmware.
        match self.0 {
            POS_INF => f.write_str("+sat"),
            NEG_INF => f.write_str("-sat"),
            raw => {
                let sign = if raw < 0 { "-" } else { "" };
                let mag = (raw as i64).unsigned_abs();
                let int = mag >> FRAC;
                let frac = ((mag & (ONE_RAW as u64 - 1)) * 100_000 + (1 << (FRAC - 1))) >> FRAC;
                write!(f, "{sign}{int}.{frac:05}")
            }
        }
    }
}

impl Add for Fixed {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        if self.saturated() {
            return self;
        }
        if rhs.saturated() {
            return rhs;
        }
        Fixed::from_wide(self.0 as i64 + rhs.0 as i64)
    }
}

impl Sub for Fixed {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self + (-rhs)
    }
}

impl Neg for Fixed {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        match self.0 {
            POS_INF => Fixed(NEG_INF),
            NEG_INF => Fixed(POS_INF),
            raw => Fixed(-raw),
        }
    }
}

impl Mul for Fixed {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        if self.saturated() || rhs.saturated() {
            return if (self.0 < 0) != (rhs.0 < 0) {
                Fixed(NEG_INF)
            } else {
                Fixed(POS_INF)
            };
        }
        let p = self.0 as i64 * rhs.0 as i64;
        Fixed::from_wide((p + (1 << (FRAC - 1))) >> FRAC)
    }
}

impl Div for Fixed {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Self) -> Self {
        let neg = (self.0 < 0) != (rhs.0 < 0);
        if self.saturated() || rhs.0 == 0 {
            return if neg { Fixed(NEG_INF) } else { Fixed(POS_INF) };
        }
        if rhs.saturated() {
            return Fixed(0);
        }
        let num = (self.0 as i64).unsigned_abs() << FRAC;
        let den = (rhs.0 as i64).unsigned_abs();
        let q = ((num + den / 2) / den) as i64;
        Fixed::from_wide(if neg { -q } else { q })
    }
}

impl AddAssign for Fixed {
    #[inline]
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}
impl SubAssign for Fixed {
    #[inline]
    fn sub_assign(&mut self, rhs: Self) {
        *self = *self - rhs;
    }
}
impl MulAssign for Fixed {
    #[inline]
    fn mul_assign(&mut self, rhs: Self) {
        *self = *self * rhs;
    }
}

/// One in Q2.30, the format of the polynomial evaluations.
const Q30: i64 = 1 << 30;

/// Coefficients of log2(1 + t) for t in [1/sqrt 2 - 1, sqrt 2 - 1], Q2.30,
/// highest degree first (max abs error 3.0e-7).
const LOG2_POLY: [i64; 8] = [
    183_322_876,   // 0.17073273259129793
    -292_866_645,  // -0.27275331739725206
    319_177_225,   // 0.2972569545760298
    -385_425_291,  // -0.35895527450387865
    515_894_955,   // 0.4804646177124709
    -774_571_623,  // -0.7213760384682857
    1_549_087_058, // 1.4426997469832723
    0,
];

/// Coefficients of 2^f for f in [0, 1), Q2.30, highest degree first
/// (max abs error 1.2e-7).
const EXP2_POLY: [i64; 6] = [
    2_024_339,     // 0.0018853123157910414
    9_635_082,     // 0.008973369430480159
    59_953_343,    // 0.05583590159235725
    257_862_141,   // 0.2401528332785046
    744_266_793,   // 0.6931524655711588
    1_073_741_824, // 1.0
];

/// log2(e) in Q2.30.
const LOG2_E_Q30: i64 = 1_549_082_005;
/// sqrt(2) in Q2.30.
const SQRT2_Q30: i64 = 1_518_500_250;

#[inline]
fn horner_q30(coeffs: &[i64], t: i64) -> i64 {
    let mut acc = 0i64;
    for &c in coeffs {
        acc = ((acc * t) >> 30) + c;
    }
    acc
}

/// log2 of a positive raw Q15.16 value, in Q2.30 (|result| < 2^35).
fn log2_q30(raw: i32) -> i64 {
    // raw = 2^p * m0 with m0 in [1, 2), p in 0..=30.
    let p = 31 - raw.leading_zeros() as i64;
    let mut m = ((raw as i64) << 30) >> p; // Q30 in [1, 2)
    let mut e = p - FRAC as i64;
    if m >= SQRT2_Q30 {
        m >>= 1;
        e += 1;
    }
    (e << 30) + horner_q30(&LOG2_POLY, m - Q30)
}

/// 2^w for w in Q2.30 (i64), rounded to Q15.16 and saturated.
fn exp2_q30(w: i64) -> Fixed {
    let k = w >> 30; // floor
    let f = w & (Q30 - 1);
    let p = horner_q30(&EXP2_POLY, f); // Q30 in [1, 2)
                                       // value = p * 2^k / 2^30; raw = value * 2^16 = p * 2^(k - 14)
    let shift = k - 14;
    if shift >= 17 {
        return Fixed(POS_INF);
    }
    if shift >= 0 {
        return Fixed::from_wide(p << shift);
    }
    if shift <= -32 {
        return Fixed(0);
    }
    let s = (-shift) as u32;
    Fixed::from_wide((p + (1 << (s - 1))) >> s)
}

/// Integer square root of a u64 (floor).
fn isqrt_u64(v: u64) -> u64 {
    let mut op = v;
    let mut res = 0u64;
    let mut one = 1u64 << 62;
    while one > op {
        one >>= 2;
    }
    while one != 0 {
        if op >= res + one {
            op -= res + one;
            res = (res >> 1) + one;
        } else {
            res >>= 1;
        }
        one >>= 2;
    }
    res
}

impl Scalar for Fixed {
    const ZERO: Self = Fixed(0);
    const ONE: Self = Fixed(ONE_RAW);
    const MAX: Self = Fixed(POS_INF - 1);
    const EPSILON: Self = Fixed(1);
    const MIN_POSITIVE: Self = Fixed(1);
    const NAME: &'static str = "q16";

    /// Rounds to nearest (ties away from zero), saturating; NaN becomes the
    /// positive saturated value, as in [`from_f64`](Scalar::from_f64).
    ///
    /// Integer operations on the bits of `x` only: constant arguments fold
    /// at compile time, and a call with a run-time argument (a table
    /// indexed in a loop, such as the integrator's step-size thresholds)
    /// pulls no soft-float routine into FPU-less firmware.
    #[inline(always)]
    fn lit(x: f32) -> Self {
        let bits = x.to_bits();
        let negative = bits >> 31 != 0;
        let biased = ((bits >> 23) & 0xff) as i32;
        let fraction = (bits & 0x7f_ffff) as u64;
        if biased == 0xff {
            return if fraction != 0 || !negative {
                Fixed(POS_INF)
            } else {
                Fixed(NEG_INF)
            };
        }
        // |x| = mantissa * 2^(exponent), so |x| * 2^16 = mantissa * 2^shift.
        let (mantissa, exponent) = if biased == 0 {
            (fraction, -149)
        } else {
            (fraction | 1 << 23, biased - 150)
        };
        let shift = exponent + FRAC as i32;
        let magnitude = if shift >= 0 {
            if shift > 16 {
                // At least 2^(23 + 17) > i32::MAX: saturate.
                return if negative {
                    Fixed(NEG_INF)
                } else {
                    Fixed(POS_INF)
                };
            }
            (mantissa << shift) as i64
        } else if shift < -40 {
            0
        } else {
            let s = (-shift) as u32;
            ((mantissa + (1 << (s - 1))) >> s) as i64
        };
        Fixed::from_wide(if negative { -magnitude } else { magnitude })
    }
    #[inline]
    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            return Fixed(POS_INF);
        }
        let v = x * ONE_RAW as f64;
        Fixed::from_wide(if v >= 0.0 { v + 0.5 } else { v - 0.5 } as i64)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        match self.0 {
            POS_INF => f64::INFINITY,
            NEG_INF => f64::NEG_INFINITY,
            raw => raw as f64 / ONE_RAW as f64,
        }
    }
    #[inline]
    fn to_f32(self) -> f32 {
        match self.0 {
            POS_INF => f32::INFINITY,
            NEG_INF => f32::NEG_INFINITY,
            raw => raw as f32 / ONE_RAW as f32,
        }
    }
    #[inline]
    fn line(y0: Self, k: Self, x: Self, x0: Self) -> Self {
        let d = x.0 as i64 - x0.0 as i64;
        let d32 = d as i32;
        if y0.saturated() || k.saturated() || x.saturated() || x0.saturated() || d32 as i64 != d {
            return y0 + k * (x - x0);
        }
        // The product rounded as `Mul` rounds it, then the sum: the same result
        // as the three operations wherever none of them saturates, and no
        // spurious saturation where only an intermediate would.
        let p = k.0 as i64 * d32 as i64;
        Fixed::from_wide(((p + (1 << (FRAC - 1))) >> FRAC) + y0.0 as i64)
    }
    #[inline(always)]
    fn from_i32(x: i32) -> Self {
        Fixed::from_wide((x as i64) << FRAC)
    }
    #[inline(always)]
    fn ratio(num: i32, den: i32) -> Self {
        Fixed::from_raw(num) / Fixed::from_raw(den)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        !self.saturated()
    }
    #[inline]
    fn abs(self) -> Self {
        if self.0 < 0 {
            -self
        } else {
            self
        }
    }
    fn powf(self, y: Self) -> Self {
        if self.saturated() || y.saturated() || self.0 < 0 {
            return Fixed(POS_INF);
        }
        if self.0 == 0 {
            return Fixed(0);
        }
        let l24 = log2_q30(self.0) >> 6; // Q24, |l24| < 2^29
        let w = (y.0 as i64 * l24) >> 10; // Q16 * Q24 = Q40 -> Q30
        exp2_q30(w)
    }
    fn exp(self) -> Self {
        if self.saturated() {
            return if self.0 > 0 { self } else { Fixed(0) };
        }
        exp2_q30((self.0 as i64 * LOG2_E_Q30) >> FRAC)
    }
    fn sqrt(self) -> Self {
        if self.saturated() || self.0 < 0 {
            return Fixed(POS_INF);
        }
        Fixed(isqrt_u64((self.0 as u64) << FRAC) as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LSB: f64 = 1.0 / 65536.0;

    fn fx(x: f64) -> Fixed {
        Fixed::from_f64(x)
    }

    #[test]
    fn fused_line_equals_the_three_operations_unless_they_saturate() {
        let mut seed = 7u64;
        let mut raw = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            // Values up to about +-2^8, so that some products saturate.
            Fixed::from_raw(((seed >> 32) as i32) >> 7)
        };
        let (mut same, mut rescued) = (0, 0);
        for _ in 0..200_000 {
            let (y0, k, x, x0) = (raw(), raw(), raw(), raw());
            let fused = Fixed::line(y0, k, x, x0);
            let plain = y0 + k * (x - x0);
            if plain.is_finite() {
                assert_eq!(fused, plain, "{y0:?} + {k:?} ({x:?} - {x0:?})");
                same += 1;
            } else {
                // Saturated somewhere: the fused value is the exact one, clamped.
                let exact = y0.to_f64() + k.to_f64() * (x.to_f64() - x0.to_f64());
                if exact.abs() < 32767.0 {
                    assert!(
                        (fused.to_f64() - exact).abs() <= LSB,
                        "{exact} vs {fused:?}"
                    );
                    rescued += 1;
                } else {
                    assert!(!fused.is_finite());
                }
            }
        }
        assert!(same > 100_000 && rescued > 0, "{same} {rescued}");
        // A saturated input stays saturated.
        let inf = Fixed::from_raw(i32::MAX);
        assert_eq!(Fixed::line(inf, fx(1.0), fx(2.0), fx(1.0)), inf);
    }

    #[test]
    fn lit_equals_from_f64_on_a_sweep_of_f32_bit_patterns() {
        // Every 251st bit pattern (17 million values): normals, subnormals,
        // zeros, infinities, NaNs, ties and saturation on both sides.
        let mut bits = 0u32;
        loop {
            let x = f32::from_bits(bits);
            assert_eq!(
                Fixed::lit(x),
                Fixed::from_f64(x as f64),
                "{x:e} ({bits:#010x})"
            );
            match bits.checked_add(251) {
                Some(b) => bits = b,
                None => break,
            }
        }
        for x in [
            0.5 / 65536.0,
            -0.5 / 65536.0,
            1.5 / 65536.0,
            32767.99,
            -32768.0,
            32768.0,
        ] {
            assert_eq!(Fixed::lit(x), Fixed::from_f64(x as f64), "{x:e}");
        }
    }

    #[test]
    fn arithmetic_rounds_to_nearest() {
        assert_eq!((fx(1.5) * fx(2.25)).to_f64(), 3.375);
        assert_eq!((fx(1.0) / fx(3.0)).to_raw(), 21845); // 65536/3 = 21845.33
        assert_eq!((fx(-1.0) / fx(3.0)).to_raw(), -21845);
        assert_eq!((fx(2.0) / fx(-3.0)).to_raw(), -43691); // 43690.67
        assert_eq!(Fixed::lit(0.1).to_raw(), 6554);
        assert_eq!(Fixed::lit(-0.1).to_raw(), -6554);
    }

    #[test]
    fn overflow_saturates_and_sticks() {
        let big = fx(30000.0);
        let inf = big + big;
        assert!(!inf.is_finite());
        assert!(!(inf - big).is_finite(), "saturation must not be undone");
        assert!(!(inf * Fixed::ZERO).is_finite());
        assert!(!(fx(1.0) / Fixed::ZERO).is_finite());
        assert!(!(big * big).is_finite());
        assert!(!(-inf).is_finite());
        assert!((-inf) < Fixed::ZERO);
        assert!(Fixed::MAX.is_finite());
        assert!(!fx(f64::NAN).is_finite());
        assert!(!fx(1e9).is_finite());
    }

    #[test]
    fn debug_prints_decimal_without_floats() {
        extern crate std;
        use std::format;
        assert_eq!(format!("{:?}", fx(-2.5)), "-2.50000");
        assert_eq!(format!("{:?}", fx(1.0) + fx(1.0) / fx(3.0)), "1.33333");
        assert_eq!(format!("{:?}", Fixed::from_raw(i32::MAX)), "+sat");
    }

    /// `x^y` over the domain of `|z|^n` in Bouc-Wen models: bases from 1e-3 to
    /// 100, exponents 0.5 to 4. The error bound is the output rounding (half an
    /// LSB) plus 2e-6 relative (polynomials and the Q24 product).
    #[test]
    fn powf_against_f64() {
        let mut worst = 0.0f64;
        for i in 0..400 {
            let x = 1e-3 * libm::pow(1e5, i as f64 / 399.0);
            for j in 0..36 {
                let y = 0.5 + 3.5 * j as f64 / 35.0;
                let (xf, yf) = (fx(x), fx(y));
                let exact = libm::pow(xf.to_f64(), yf.to_f64());
                if exact >= 32768.0 {
                    assert!(!xf.powf(yf).is_finite());
                    continue;
                }
                let got = xf.powf(yf).to_f64();
                let err = (got - exact).abs();
                let bound = 0.5 * LSB + 2e-6 * exact;
                worst = worst.max(err / bound);
                assert!(err <= bound, "{x}^{y}: {got} vs {exact}");
            }
        }
        assert!(
            worst > 0.05,
            "bound should be reasonably tight, worst {worst}"
        );
    }

    #[test]
    fn exp_against_f64() {
        for i in 0..2000 {
            let x = -12.0 + 22.0 * i as f64 / 1999.0;
            let xf = fx(x);
            let exact = libm::exp(xf.to_f64());
            let got = xf.exp().to_f64();
            assert!(
                (got - exact).abs() <= 0.5 * LSB + 2e-6 * exact,
                "exp({x}): {got} vs {exact}"
            );
        }
        assert!(!fx(11.0).exp().is_finite());
        assert_eq!(fx(-20.0).exp(), Fixed::ZERO);
    }

    #[test]
    fn sqrt_is_floor_of_exact() {
        for i in 0..5000 {
            let x = i as f64 * 6.1;
            let got = fx(x).sqrt().to_f64();
            let exact = libm::sqrt(fx(x).to_f64());
            assert!(got <= exact && exact - got < LSB, "sqrt({x})");
        }
    }
}
