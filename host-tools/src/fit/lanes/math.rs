//! `|z|^n = exp(n ln|z|)` on [`LANES`] values at once, branch-free so that the compiler keeps
//! every lane in one vector register (AVX2 with the repository's `x86-64-v3` build).
//!
//! The table-driven scalar `pow` of the core cannot be vectorised (its table lookups and special
//! cases branch per value); these polynomials can:
//!
//! * `ln x`: `x = 2^e m` with `m` in [sqrt(1/2), sqrt(2)), `ln m = 2 atanh s` with
//!   `s = (m - 1)/(m + 1)`, `|s| <= 0.1716`, as the odd series `2 s (1 + s^2/3 + ... + s^18/19)`
//!   (truncation below 3e-17 relative).
//! * `exp y`: `y = k ln2 + r`, `|r| <= ln2/2` (ln2 in two parts), `e^r` as its Taylor polynomial
//!   of degree 13 (truncation below 4e-17 relative), `2^k` put into the exponent field.
//!
//! The relative error of `|z|^n` against `f64::powf` is below `(4 + |n ln|z||) 2^-52` on the
//! models' domain (tested below): the rounding of `n ln|z|` is amplified by `exp`, as in any
//! `exp(n ln z)` without extra precision (at most 3.7e-14 for `|z|` in [1e-12, 1e3], `n` up to 6).

use super::{Lanes, LANES};

/// The bits of sqrt(1/2): subtracting them leaves the power of two of `x / sqrt(1/2)` in the
/// exponent field.
const SQRT_HALF_BITS: u64 = 0x3fe6_a09e_667f_3bcd;
/// 2^52 + 2^51: adding it rounds a value below 2^51 to an integer held in the low bits.
const SHIFT: f64 = 6_755_399_441_055_744.0;
/// ln 2 in two parts: the head has 32 significant bits, so `k * LN2_HI` is exact for `|k| < 2^21`.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// Below this `exp` underflows (`e^-708` is the smallest normal magnitude's order).
const EXP_MIN: f64 = -708.0;
/// Above this `exp` overflows.
const EXP_MAX: f64 = 709.78;
/// `|z|` is raised to at least this before its logarithm, so that `0^n` is
/// `e^(n ln 1e-300)`: zero to within 1e-300 for `n >= 1`, and below 1e-60 for the smallest
/// exponent the models accept that matters (`n >= 0.2`).
const TINY: f64 = 1e-300;

/// `2 atanh(s) / s = 2 (1 + s^2/3 + s^4/5 + ...)`, coefficients of `s^2k`.
const ATANH: [f64; 10] = [
    2.0,
    2.0 / 3.0,
    2.0 / 5.0,
    2.0 / 7.0,
    2.0 / 9.0,
    2.0 / 11.0,
    2.0 / 13.0,
    2.0 / 15.0,
    2.0 / 17.0,
    2.0 / 19.0,
];

/// `1/k!`, `k = 0..=13`.
const INV_FACTORIAL: [f64; 14] = [
    1.0,
    1.0,
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
    1.0 / 40_320.0,
    1.0 / 362_880.0,
    1.0 / 3_628_800.0,
    1.0 / 39_916_800.0,
    1.0 / 479_001_600.0,
    1.0 / 6_227_020_800.0,
];

/// `ln x` for a positive normal `x`.
#[inline(always)]
fn ln(x: f64) -> f64 {
    let bits = x.to_bits();
    let e = (bits.wrapping_sub(SQRT_HALF_BITS) as i64) >> 52;
    let m = f64::from_bits(bits.wrapping_sub((e as u64) << 52));
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let s4 = s2 * s2;
    let s8 = s4 * s4;
    // Estrin's scheme: four independent chains instead of one of nine steps.
    let a = ATANH[1].mul_add(s2, ATANH[0]) + ATANH[3].mul_add(s2, ATANH[2]) * s4;
    let b = ATANH[5].mul_add(s2, ATANH[4]) + ATANH[7].mul_add(s2, ATANH[6]) * s4;
    let c = ATANH[9].mul_add(s2, ATANH[8]);
    let series = c.mul_add(s8, b).mul_add(s8, a);
    // `e as f64` without the integer conversion AVX2 lacks: e sits in the low bits of 2^52 + 2^51.
    let ef = f64::from_bits(SHIFT.to_bits().wrapping_add(e as u64)) - SHIFT;
    ef.mul_add(LN2_HI, ef.mul_add(LN2_LO, s * series))
}

/// `e^y` for a finite `y`, with `y` clamped to [-708, 709.78] first (no comparisons, so that the
/// lanes stay in vector registers): below, the result is about 3e-308 instead of a subnormal or
/// 0; above, about 1.8e308 instead of infinity, which makes the state infinite a stage later.
#[inline(always)]
fn exp(y: f64) -> f64 {
    let y = y.clamp(EXP_MIN, EXP_MAX);
    let kt = y.mul_add(core::f64::consts::LOG2_E, SHIFT);
    let kf = kt - SHIFT;
    let r = kf.mul_add(-LN2_LO, kf.mul_add(-LN2_HI, y));
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let f = &INV_FACTORIAL;
    let p0 = f[1].mul_add(r, f[0]) + f[3].mul_add(r, f[2]) * r2;
    let p1 = f[5].mul_add(r, f[4]) + f[7].mul_add(r, f[6]) * r2;
    let p2 = f[9].mul_add(r, f[8]) + f[11].mul_add(r, f[10]) * r2;
    let p3 = f[13].mul_add(r, f[12]);
    let poly = (p3.mul_add(r4, p2)).mul_add(r8, p1.mul_add(r4, p0));
    // k (at most 1024 in magnitude) is in the low bits of kt; shift it into the exponent.
    let k = kt.to_bits().wrapping_sub(SHIFT.to_bits());
    f64::from_bits(poly.to_bits().wrapping_add(k << 52))
}

/// `|z|^n` lane by lane (`n > 0`). A NaN `z` gives a finite value here, but the state it came
/// from stays NaN in the integration (`z` itself is carried), so non-finite simulations are
/// still seen at the end.
#[inline(always)]
pub fn pow_abs(z: &Lanes, n: &Lanes) -> Lanes {
    let mut out = [0.0; LANES];
    for i in 0..LANES {
        out[i] = exp(n[i] * ln(z[i].abs().max(TINY)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error of `pow_abs` against `powf` over the models' domain, `|z|` from 1e-12 to
    /// 1e3 and `n` from 0.2 to 6, in units of `(4 + |n ln|z||) 2^-52`.
    #[test]
    fn pow_abs_agrees_with_powf() {
        let mut worst: f64 = 0.0;
        for i in 0..20_000 {
            let z: Lanes = core::array::from_fn(|l| {
                let t = (i * LANES + l) as f64 / (20_000 * LANES) as f64;
                let z = 10f64.powf(-12.0 + 15.0 * t);
                if l % 2 == 0 {
                    z
                } else {
                    -z
                }
            });
            let n: Lanes =
                core::array::from_fn(|l| 0.2 + 5.8 * ((i * 7 + l * 13) % 997) as f64 / 996.0);
            let got = pow_abs(&z, &n);
            for l in 0..LANES {
                let want = z[l].abs().powf(n[l]);
                let y = n[l] * z[l].abs().ln();
                let err = ((got[l] - want) / want).abs() / ((4.0 + y.abs()) * f64::EPSILON);
                worst = worst.max(err);
            }
        }
        assert!(worst <= 1.0, "worst relative error {worst} x (4 + |y|) eps");
    }

    #[test]
    fn zero_and_overflow_saturate() {
        let n = [1.2; LANES];
        let mut z = [0.0; LANES];
        z[1] = -0.0;
        z[2] = f64::INFINITY;
        z[3] = 1e300;
        z[4] = 1.0;
        z[5] = 2.0;
        let p = pow_abs(&z, &n);
        assert!(p[0] < 1e-300 && p[1] < 1e-300, "0^n = {} {}", p[0], p[1]);
        assert!(
            p[2] > 1e308 && p[3] > 1e308,
            "{p:?}: saturated, not infinite"
        );
        assert_eq!(p[4], 1.0);
        assert!((p[5] - 2f64.powf(1.2)).abs() < 1e-15);
    }
}
