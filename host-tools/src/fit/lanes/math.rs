//! `|z|^n = exp(n ln|z|)` on [`LANES`](super::LANES) `f32` values at once, branch-free so that
//! the compiler keeps every lane in vector registers (AVX2 with the repository's `x86-64-v3`
//! build: eight lanes a register).
//!
//! The table-driven scalar `pow` of the core cannot be vectorised (its table lookups and special
//! cases branch per value); these polynomials can:
//!
//! * `ln x`: `x = 2^e m` with `m` in [sqrt(1/2), sqrt(2)), `ln m = 2 atanh s` with
//!   `s = (m - 1)/(m + 1)`, `|s| <= 0.1716`, as the odd series `2 s (1 + s^2/3 + ... + s^8/9)`
//!   (truncation below 2e-9 relative, under a thirtieth of `f32`'s rounding).
//! * `exp y`: `y = k ln2 + r`, `|r| <= ln2/2` (ln2 in two parts), `e^r` as its Taylor polynomial
//!   of degree 7 (truncation below 8e-9 relative), `2^k` put into the exponent field.
//!
//! The relative error of `|z|^n` against `f64::powf` is below `(4 + |n ln|z||) 2^-23` on the
//! models' domain (tested below): the rounding of `n ln|z|` is amplified by `exp`, as in any
//! `exp(n ln z)` without extra precision (at most 3.5e-6 for `|z|` in [1e-12, 1e3], `n` up to 6).

use super::Lanes;

/// The bits of sqrt(1/2): subtracting them leaves the power of two of `x / sqrt(1/2)` in the
/// exponent field.
const SQRT_HALF_BITS: u32 = 0x3f35_04f3;
/// 2^23 + 2^22: adding it rounds a value below 2^22 to an integer held in the low bits.
const SHIFT: f32 = 12_582_912.0;
/// ln 2 in two parts: the head has 15 significant bits, so `k * LN2_HI` is exact for `|k| < 2^9`.
const LN2_HI: f32 = f32::from_bits(0x3f31_7200);
const LN2_LO: f32 = f32::from_bits(0x35bf_be8e);
/// Below this `exp` underflows (`e^-87` is the order of the smallest normal `f32`).
const EXP_MIN: f32 = -87.0;
/// Above this `exp` overflows.
const EXP_MAX: f32 = 88.7;
/// `|z|` is raised to at least this before its logarithm, so that `0^n` is `e^(n ln 1e-37)`:
/// below 1e-37 for `n >= 1`, and below 5e-8 (a rounding of the `1` it is subtracted from) for
/// the smallest exponent the models accept that matters (`n >= 0.2`).
const TINY: f32 = 1e-37;

/// `2 atanh(s) / s = 2 (1 + s^2/3 + s^4/5 + ...)`, coefficients of `s^2k`.
const ATANH: [f32; 5] = [2.0, 2.0 / 3.0, 2.0 / 5.0, 2.0 / 7.0, 2.0 / 9.0];

/// `1/k!`, `k = 0..=7`.
const INV_FACTORIAL: [f32; 8] = [
    1.0,
    1.0,
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
];

/// `ln x` for a positive normal `x`.
#[inline(always)]
fn ln(x: f32) -> f32 {
    let bits = x.to_bits();
    let e = (bits.wrapping_sub(SQRT_HALF_BITS) as i32) >> 23;
    let m = f32::from_bits(bits.wrapping_sub((e as u32) << 23));
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let s4 = s2 * s2;
    // Estrin's scheme: independent chains instead of one of five steps.
    let a = ATANH[1].mul_add(s2, ATANH[0]);
    let b = ATANH[4].mul_add(s4, ATANH[3].mul_add(s2, ATANH[2]));
    let series = b.mul_add(s4, a);
    let ef = e as f32;
    ef.mul_add(LN2_HI, ef.mul_add(LN2_LO, s * series))
}

/// `e^y` for a finite `y`, with `y` clamped to [-87, 88.7] first (no comparisons, so that the
/// lanes stay in vector registers): below, the result is about 1.6e-38 instead of a subnormal or
/// 0; above, about 3.3e38 instead of infinity, which makes the state infinite a stage later.
#[inline(always)]
fn exp(y: f32) -> f32 {
    let y = y.clamp(EXP_MIN, EXP_MAX);
    let kt = y.mul_add(core::f32::consts::LOG2_E, SHIFT);
    let kf = kt - SHIFT;
    let r = kf.mul_add(-LN2_LO, kf.mul_add(-LN2_HI, y));
    let r2 = r * r;
    let r4 = r2 * r2;
    let f = &INV_FACTORIAL;
    let p0 = f[1].mul_add(r, f[0]) + f[3].mul_add(r, f[2]) * r2;
    let p1 = f[5].mul_add(r, f[4]) + f[7].mul_add(r, f[6]) * r2;
    let poly = p1.mul_add(r4, p0);
    // k (at most 128 in magnitude) is in the low bits of kt; shift it into the exponent.
    let k = kt.to_bits().wrapping_sub(SHIFT.to_bits());
    f32::from_bits(poly.to_bits().wrapping_add(k << 23))
}

/// `|z|^n` lane by lane (`n > 0`). A NaN `z` gives a finite value here, but the state it came
/// from stays NaN in the integration (`z` itself is carried), so non-finite simulations are
/// still seen at the end.
#[inline(always)]
pub fn pow_abs(z: &Lanes, n: &Lanes) -> Lanes {
    core::array::from_fn(|i| exp(n[i] * ln(z[i].abs().max(TINY))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::lanes::LANES;

    /// Relative error of `pow_abs` against `f64::powf` over the models' domain, `|z|` from 1e-12
    /// to 1e3 and `n` from 0.2 to 6, in units of `(4 + |n ln|z||) 2^-23`, where the power is in
    /// `f32`'s normal range (below it, the clamp's e^-87).
    #[test]
    fn pow_abs_agrees_with_powf() {
        let mut worst: f64 = 0.0;
        for i in 0..20_000 {
            let z: Lanes = core::array::from_fn(|l| {
                let t = (i * LANES + l) as f64 / (20_000 * LANES) as f64;
                let z = 10f64.powf(-12.0 + 15.0 * t) as f32;
                if l % 2 == 0 {
                    z
                } else {
                    -z
                }
            });
            let n: Lanes = core::array::from_fn(|l| {
                (0.2 + 5.8 * ((i * 7 + l * 13) % 997) as f64 / 996.0) as f32
            });
            let got = pow_abs(&z, &n);
            for l in 0..LANES {
                let (z, n) = (f64::from(z[l].abs()), f64::from(n[l]));
                let want = z.powf(n);
                let y = n * z.ln();
                let got = f64::from(got[l]);
                if y < f64::from(EXP_MIN) {
                    // Below f32's normal range: the clamped e^-87, as documented.
                    assert!(
                        got <= f64::from(EXP_MIN).exp() * 1.000_001,
                        "{z}^{n} = {got}"
                    );
                    continue;
                }
                let err = ((got - want) / want).abs() / ((4.0 + y.abs()) * f64::from(f32::EPSILON));
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
        z[2] = f32::INFINITY;
        z[3] = 1e38;
        z[4] = 1.0;
        z[5] = 2.0;
        let p = pow_abs(&z, &n);
        assert!(p[0] < 1e-37 && p[1] < 1e-37, "0^n = {} {}", p[0], p[1]);
        assert!(
            p[2] > 3e38 && p[3] > 3e38 && p[2].is_finite() && p[3].is_finite(),
            "{p:?}: saturated, not infinite"
        );
        assert_eq!(p[4], 1.0);
        assert!((f64::from(p[5]) - 2f64.powf(1.2)).abs() < 2.0 * 2.3 * f64::from(f32::EPSILON));
    }
}
