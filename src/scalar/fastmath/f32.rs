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
//! * `powf(x, y)`: `x = 2^e m` with `m` in [1/sqrt2, sqrt2), `log2 m = s P(s^2)`
//!   with `s = (m-1)/(m+1)`, `|s| <= 0.172`, and `P` of degree 3 (relative error
//!   1.3e-8); `y e` is kept exact by splitting `y` into a 12-bit head and its tail,
//!   so only `y log2 m` (`|log2 m| <= 1/2`) is rounded at the size of the
//!   result's logarithm; `2^g` for the remaining `|g| <= 1/2` is `1 + g R(g)` with
//!   `R` of degree 4 (relative error 9.7e-8). The error that is left comes mostly
//!   from the three roundings in `s` and `log2 m`, multiplied by `y`: a few ulp
//!   for `y` up to 6 (see the tests).
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

/// The bits of 1/sqrt2 (rounded up): `x - 2^e / sqrt2` has `e` in its exponent field.
const LOG_OFFSET: u32 = 0x3f35_04f3;
/// `log2((1+s)/(1-s)) = s P(s^2)` on `|s| <= 1/5` (used on `|s| <= 0.172`), minimax
/// for relative error.
const P: [f32; 4] = [2.885_39, 0.961_817_74, 0.575_305_4, 0.457_829_98];
/// `2^g = 1 + g R(g)` on `|g| <= 1/2`, minimax for relative error (`R[0]` is
/// 0.693147, fitted: three ulp below ln 2).
const R: [f32; 5] = [
    f32::from_bits(0x3f31_7215),
    0.240_222_25,
    0.055_506_51,
    0.009_672_604,
    0.001_330_262_6,
];

/// `q 2^n` for a normal `q` in [0.7, 1.5) and `n` in [-125, 127], or `None`. `n` is a
/// wrapped bit difference and can be anything for huge arguments, so the test wraps too (with
/// `n + 125`, `expf(-17443600.0)` overflowed `i32`: a panic in debug builds, found by review).
#[inline(always)]
fn scale(q: f32, n: i32) -> Option<f32> {
    if (n as u32).wrapping_add(125) <= 252 {
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

/// `e^x`. Error at most `tests::EXPF_BOUND_ULP` (2.5 ulp) where the result is normal;
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

/// `x^y` for `x >= 0`. Error at most `tests::POWF_BOUND_ULP` (7 ulp, relative
/// error 4.7e-7) on the domain of the hysteresis models (`x` in [1e-12, 1e6], `y`
/// in [0.2, 6]) where the result is a normal `f32`.
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
    let t1 = yh * e;
    let t2 = (y - yh) * e;
    let p = y * log2m;
    let kt = (t1 + (p + t2)) + SHIFT;
    let n = (kt.to_bits() as i32).wrapping_sub(SHIFT.to_bits() as i32);
    let nf = kt - SHIFT;
    // g = y log2 x - n in [-1/2, 1/2]: t1 - nf is exact, and so is adding p (both
    // on the grid of p, sum below 1/2), so only the last addition rounds.
    let g = ((t1 - nf) + p) + t2;
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

#[cfg(test)]
mod tests {
    //! Against the standard library's `f64` functions on the same (exactly
    //! widened) inputs: the error of the `f64` reference (< 2^-52) is far below
    //! the `f32` errors measured here. Errors are in ulps of the exact value
    //! (`|got - exact| / ulp(exact)`, ulp = 2^-23 of the exact value's binade), so
    //! 0.5 is a correctly rounded result.
    use super::*;

    /// Where `x log2 e` or `y log2 x` lies just beyond the rounding constant, the exponent's
    /// bit difference wraps to near `i32::MAX`; the range test must not overflow on it.
    #[test]
    fn arguments_whose_exponent_wraps_underflow_without_overflowing() {
        for x in [-17_443_600.0f32, -17_443_618.0, -17_443_534.0, -2.0e7] {
            assert_eq!(expf(x), 0.0, "e^{x}");
        }
        for y in [25_165_800.0f32, 25_165_824.0, 3.0e7] {
            assert_eq!(powf(0.5, y), 0.0, "0.5^{y}");
            assert_eq!(powf(2.0, -y), 0.0, "2^-{y}");
            assert_eq!(powf(2.0, y), f32::INFINITY, "2^{y}");
        }
    }

    /// Largest error of [`expf`] in ulps where the result is normal (measured 2.19).
    const EXPF_BOUND_ULP: f64 = 2.5;
    /// Largest error of [`powf`] in ulps for `x` in [1e-12, 1e6], `y` in [0.2, 6],
    /// where the result is a normal `f32` (measured 6.41, relative error 4.7e-7).
    const POWF_BOUND_ULP: f64 = 7.0;

    struct Draws(u64);
    impl Draws {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Error of `got` in ulps of `exact` (normal range).
    fn ulp_err(got: f32, exact: f64) -> f64 {
        let ulp = (2f64).powi(exact.abs().log2().floor() as i32 - 23);
        let e = (got as f64 - exact).abs() / ulp;
        if e.is_nan() {
            f64::INFINITY
        } else {
            e
        }
    }

    /// Worst ulp error, worst relative error, and the argument of the worst ulp error.
    fn worst(cases: impl Iterator<Item = (f32, f32, f64)>) -> (f64, f64, f32) {
        cases.fold((0.0, 0.0, 0.0), |(wu, wr, wa), (a, got, exact)| {
            let u = ulp_err(got, exact);
            let r = ((got as f64 - exact) / exact).abs();
            (
                if u > wu { u } else { wu },
                wr.max(r),
                if u > wu { a } else { wa },
            )
        })
    }

    #[test]
    fn powf_meets_its_bound_on_the_model_domain() {
        let grid = (0..3001).flat_map(|i| {
            let x =
                (1e-12 * (1e18f64).powf(i as f64 / 3000.0) * (1.0 + 1e-3 * ((i * 7) % 11) as f64))
                    .min(1e6) as f32;
            (0..200).map(move |j| (x, (0.2 + 5.8 * j as f64 / 199.0) as f32))
        });
        let mut d = Draws(3);
        let random = (0..1_000_000).map(move |_| {
            let x = 10f64.powf(-12.0 + 18.0 * d.next()) as f32;
            (x, (0.2 + 5.8 * d.next()) as f32)
        });
        let near_one = (0..20_001).flat_map(|i| {
            let x = (1.0 + (i as f64 - 10_000.0) * 3.7e-5) as f32;
            [(x, 0.5), (x, 1.7), (x, 5.9)]
        });
        // Where the exact result is a normal f32 (1e-12^6 is not).
        let normal = |&(_, _, exact): &(f32, f32, f64)| {
            (f32::MIN_POSITIVE as f64..=f32::MAX as f64).contains(&exact)
        };
        let (u, r, x) = worst(
            grid.chain(random)
                .chain(near_one)
                .map(|(x, y)| (x, powf(x, y), (x as f64).powf(y as f64)))
                .filter(normal),
        );
        println!("powf: max error {u:.3} ulp, max relative error {r:.3e} (x = {x:e})");
        assert!(
            u <= POWF_BOUND_ULP,
            "powf error {u} ulp > {POWF_BOUND_ULP} at x = {x:e}"
        );
        assert!(
            u > POWF_BOUND_ULP * 0.75,
            "bound {POWF_BOUND_ULP} ulp is loose: max {u}"
        );
    }

    #[test]
    fn expf_meets_its_bound_on_every_1009th_float() {
        // Every 1009th bit pattern whose result is normal: about 2.2 million inputs.
        let pos = (0..0x42b1_0000u32).step_by(1009).map(f32::from_bits);
        let neg = (0..0x42ae_0000u32)
            .step_by(1009)
            .map(|b| -f32::from_bits(b));
        let (u, r, x) = worst(pos.chain(neg).map(|x| (x, expf(x), (x as f64).exp())));
        println!("expf: max error {u:.3} ulp, max relative error {r:.3e} (x = {x:e})");
        assert!(
            u <= EXPF_BOUND_ULP,
            "expf error {u} ulp > {EXPF_BOUND_ULP} at x = {x:e}"
        );
        assert!(
            u > EXPF_BOUND_ULP * 0.75,
            "bound {EXPF_BOUND_ULP} ulp is loose: max {u}"
        );
    }

    /// The `f64` reference rounded to `f32`.
    fn rounded(exact: f64) -> f32 {
        exact as f32
    }

    fn same_class(a: f32, b: f32) -> bool {
        (a.is_nan() && b.is_nan()) || (a.is_infinite() && a == b) || (a == 0.0 && b == 0.0)
    }

    /// `got` against the exact value: within `bound` ulp where the rounded value is
    /// normal, within one step of it where it is subnormal (one rounding there),
    /// the same zero, infinity or NaN otherwise.
    fn acceptable(got: f32, exact: f64, bound: f64) -> bool {
        let want = rounded(exact);
        if want.is_normal() {
            ulp_err(got, exact) <= bound
        } else if want != 0.0 && want.is_finite() {
            got.to_bits().abs_diff(want.to_bits()) <= 1
        } else {
            same_class(got, want)
        }
    }

    #[test]
    fn expf_special_values_and_range_ends() {
        assert_eq!(expf(0.0), 1.0);
        assert_eq!(expf(-0.0), 1.0);
        assert!(expf(f32::NAN).is_nan());
        assert_eq!(expf(f32::INFINITY), f32::INFINITY);
        assert_eq!(expf(f32::NEG_INFINITY), 0.0);
        assert_eq!(expf(1e30), f32::INFINITY);
        assert_eq!(expf(-1e30), 0.0);
        assert!(expf(88.72).is_finite());
        assert_eq!(expf(88.73), f32::INFINITY);
        assert_eq!(expf(-104.0), 0.0);
        // The wide-range path: subnormal results within one ulp of the rounded
        // reference, large ones within the bound.
        for b in (0x42ae_0000u32..0x42d0_0000).step_by(97) {
            let x = -f32::from_bits(b);
            let (got, exact) = (expf(x), (x as f64).exp());
            assert!(
                acceptable(got, exact, EXPF_BOUND_ULP),
                "expf({x}) = {got:e}, exact {exact:e}"
            );
        }
        for b in (0x42b0_0000u32..0x42b1_7218).step_by(7) {
            let x = f32::from_bits(b);
            assert!(
                ulp_err(expf(x), (x as f64).exp()) <= EXPF_BOUND_ULP,
                "expf({x})"
            );
        }
    }

    #[test]
    fn powf_special_values_follow_c99_for_non_negative_x() {
        let xs = [
            0.0,
            1e-45,
            1e-40,
            f32::MIN_POSITIVE,
            0.5,
            1.0,
            2.0,
            1e30,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        let ys = [
            0.0,
            -0.0,
            1e-30,
            0.5,
            1.0,
            2.0,
            -1.0,
            -0.5,
            1e30,
            -1e30,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for x in xs {
            for y in ys {
                let (got, exact) = (powf(x, y), (x as f64).powf(y as f64));
                assert!(
                    acceptable(got, exact, POWF_BOUND_ULP),
                    "powf({x:e}, {y:e}) = {got:e}, exact {exact:e}"
                );
            }
        }
        assert_eq!(powf(-0.0, 1.5), 0.0);
        assert_eq!(powf(-0.0, -1.0), f32::INFINITY);
        assert!(powf(-2.0, 0.5).is_nan());
        assert!(powf(-2.0, 2.0).is_nan());
        assert_eq!(powf(-2.0, 0.0), 1.0);
        assert_eq!(powf(1.0, 123.456), 1.0);
        assert_eq!(powf(2.0, 10.0), 1024.0);
    }

    #[test]
    fn powf_overflow_underflow_and_subnormal_arguments_and_results() {
        assert!(powf(2.0, 127.99).is_finite());
        assert_eq!(powf(2.0, 128.0), f32::INFINITY);
        assert_eq!(powf(1e-12, 6.0e3), 0.0);
        assert_eq!(powf(1e6, 6.0e3), f32::INFINITY);
        assert_eq!(powf(2.0, -149.0), 1e-45);
        assert_eq!(powf(2.0, -151.0), 0.0);
        let mut y = 1.0f32;
        while y < 1.3 {
            for x in [1e-30f32, 3e-33, 1.7e-36, 1e-40, 1e-44] {
                let (got, exact) = (powf(x, y), (x as f64).powf(y as f64));
                assert!(
                    acceptable(got, exact, POWF_BOUND_ULP),
                    "powf({x:e}, {y}) = {got:e}, exact {exact:e}"
                );
            }
            y += 0.0011;
        }
        for x in [1e-30f32, 3e25] {
            let mut y = 1.0f32;
            while y < 1.6 {
                let (got, exact) = (powf(x, y), (x as f64).powf(y as f64));
                assert!(
                    acceptable(got, exact, POWF_BOUND_ULP),
                    "powf({x:e}, {y}) = {got:e}, exact {exact:e}"
                );
                y += 0.00037;
            }
        }
    }
}
