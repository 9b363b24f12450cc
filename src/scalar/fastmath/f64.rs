//! `f64` `x^y` and `e^x` with two 256-byte tables.
//!
//! * `exp(x)`: `x = (32 k + j) ln2/32 + r` with `|r| <= ln2/64`, so
//!   `e^x = 2^k 2^(j/32) e^r`; `2^(j/32)` from [`EXP2_TABLE`], `e^r = 1 + r Q(r)`
//!   with `Q` of degree 4 (minimax, relative error 8.7e-17 on the interval).
//! * `pow(x, y)`: `x = 2^e m` with `m` in [0.703125, 1.40625), cut into 16 intervals
//!   with centres `c` ([`LOG_TABLE`]: `c` and `log2 c`), `log2 m = log2 c + s P(s^2)`
//!   with `s = (m - c)/(m + c)`, `|s| <= 0.0154` (`m - c` is exact), `P` of degree 3
//!   (relative error 1.4e-17). Then `y log2 x = y e + y log2 m` where `y e` is
//!   kept exact by splitting `y` into a 26-bit head and its tail (no FMA on the
//!   default x86-64 target), so the only roundings that grow with the result's
//!   size are those of `y log2 m` (`|log2 m| < 0.51`); `2^(y log2 x)` then goes
//!   through the same kernel as `exp`.
//!
//! Measured relative errors are in the tests at the end of this file.

/// 1.5 * 2^52: adding it rounds a value below 2^51 in magnitude to an integer that
/// sits in the low bits of the sum.
const SHIFT: f64 = 6_755_399_441_055_744.0;
/// 32 / ln 2
const INV_LN2_32: f64 = 46.166_241_308_446_83;
/// ln2/32 in two parts (fdlibm's split of ln2, divided by 32 exactly): the head
/// has 32 significant bits, so `k * LN2_32_HI` is exact for `|k| < 2^21`.
const LN2_32_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000) / 32.0;
const LN2_32_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76) / 32.0;
/// ln2/32 rounded once (for `pow`, whose reduced argument is already in units of ln2/32).
const LN2_32: f64 = core::f64::consts::LN_2 / 32.0;

/// `2^(j/32)`, `j = 0..32`, rounded to nearest (`remez.py`).
const EXP2_TABLE: [f64; 32] = [
    1.0,
    1.021_897_148_654_116_6,
    1.044_273_782_427_413_8,
    1.067_140_400_676_823_7,
    1.090_507_732_665_257_7,
    1.114_386_742_595_892_4,
    1.138_788_634_756_691_6,
    1.163_724_858_777_577_5,
    1.189_207_115_002_721,
    1.215_247_359_980_469,
    1.241_857_812_073_484,
    1.269_050_957_191_733_2,
    1.296_839_554_651_009_6,
    1.325_236_643_159_741_3,
    1.354_255_546_936_892_7,
    1.383_909_881_963_832,
    core::f64::consts::SQRT_2,
    1.445_180_806_977_046_7,
    1.476_826_145_939_499_3,
    1.509_164_427_593_422_8,
    1.542_210_825_407_940_7,
    1.575_980_845_107_886_5,
    1.610_490_331_949_254_3,
    1.645_755_478_153_965,
    1.681_792_830_507_429,
    1.718_619_298_122_478,
    1.756_252_160_373_299_5,
    1.794_709_075_003_107_2,
    1.834_008_086_409_342_4,
    1.874_167_634_110_3,
    1.915_206_561_397_147_4,
    1.957_144_124_175_400_2,
];

/// `e^r = 1 + r Q(r)` on `|r| <= ln2/64`, minimax for relative error (`remez.py`).
const Q: [f64; 5] = [
    0.999_999_999_999_999_8,
    0.499_999_999_991_724_84,
    0.166_666_666_672_987_82,
    0.041_666_894_086_727_05,
    0.008_333_318_656_745_49,
];

/// The bits of 0.703125: `x - 2^e * 0.703125` has `e` in its exponent field and the
/// interval index in the next four bits.
const LOG_OFFSET: u64 = 0x3fe6_8000_0000_0000;

/// Centre `c` of each of the 16 intervals of `m`, and `log2 c` rounded to nearest
/// (`remez.py`): 9 intervals of width 1/32 from 0.703125, then [1 - 1/64, 1 + 1/32)
/// with centre 1 (so that `1^y` and `(2^k)^y` are exact), then 6 of width 1/16.
const LOG_TABLE: [(f64, f64); 16] = [
    (0.71875, -0.476_438_043_942_987_1),
    (0.75, -0.415_037_499_278_843_8),
    (0.78125, -0.356_143_810_225_275_3),
    (0.8125, -0.299_560_281_858_907_8),
    (0.84375, -0.245_112_497_836_531_47),
    (0.875, -0.192_645_077_942_395_88),
    (0.90625, -0.142_019_004_872_427_88),
    (0.9375, -0.093_109_404_391_481_47),
    (0.96875, -0.045_803_689_613_124_79),
    (1.0, 0.0),
    (1.0625, 0.087_462_841_250_339_4),
    (1.125, 0.169_925_001_442_312_37),
    (1.1875, 0.247_927_513_443_585_5),
    (1.25, 0.321_928_094_887_362_35),
    (1.3125, 0.392_317_422_778_760_3),
    (1.375, 0.459_431_618_637_297_26),
];

/// `log2(c (1+s)/(1-s)) - log2 c = s P(s^2)` for `|s| <= 0.0154`, minimax for
/// relative error (`remez.py`).
const P: [f64; 4] = [
    2.885_390_081_777_926_8,
    0.961_796_693_929_776_1,
    0.577_077_961_396_711_1,
    0.412_444_980_633_958_9,
];

const EXP_MASK: u64 = 0x7ff0_0000_0000_0000;
const MIN_NORMAL_BITS: u64 = 0x0010_0000_0000_0000;

/// `2^n` for `n` in the normal exponent range `[-1022, 1023]`.
#[inline(always)]
fn pow2i(n: i64) -> f64 {
    f64::from_bits(((n + 1023) as u64) << 52)
}

/// `2^k/32 * e^r` for `|r| <= ln2/64` (the shared kernel of `exp` and `pow`).
#[inline(always)]
fn exp_kernel(k: i64, r: f64) -> f64 {
    let t = EXP2_TABLE[(k & 31) as usize];
    let n = k >> 5;
    let r2 = r * r;
    // r Q(r) - r, evaluated in two halves for a shorter dependency chain.
    let poly = r * (Q[0] - 1.0) + r2 * (Q[1] + r * Q[2] + r2 * (Q[3] + r * Q[4]));
    let er_m1 = r + poly;
    if (n + 1021) as u64 <= 2043 {
        // 2^n * t is a normal number: put n into the exponent of t exactly.
        let scaled = f64::from_bits(t.to_bits().wrapping_add((n as u64) << 52));
        scaled + scaled * er_m1
    } else {
        scale_wide(t + t * er_m1, n)
    }
}

/// `v 2^n` for `v` in [0.7, 2) and any `n` (overflow to infinity, gradual
/// underflow with a single rounding).
#[cold]
#[inline(never)]
fn scale_wide(v: f64, n: i64) -> f64 {
    if n > 0 {
        let n = n.min(2046);
        v * pow2i(n - n / 2) * pow2i(n / 2)
    } else {
        // Exact while the intermediate stays normal; the last product rounds once.
        let n = n.max(-1100);
        (v * pow2i(n + 1000)) * pow2i(-1000)
    }
}

/// `e^x`. Relative error at most `tests::EXP_BOUND` (1.6 ulp) for `|x| <= 708`;
/// overflows to infinity above 709.78, underflows gradually to 0 below -708.4.
#[inline]
pub fn exp(x: f64) -> f64 {
    if !(x.abs() <= 746.0) {
        return exp_special(x);
    }
    let kt = x * INV_LN2_32 + SHIFT;
    let k = kt.to_bits() as i64 - SHIFT.to_bits() as i64;
    let kf = kt - SHIFT;
    let r = (x - kf * LN2_32_HI) - kf * LN2_32_LO;
    exp_kernel(k, r)
}

#[cold]
#[inline(never)]
fn exp_special(x: f64) -> f64 {
    if x.is_nan() {
        x
    } else if x > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// `x^y` for `x >= 0`: relative error at most `tests::POW_BOUND` (1e-15) on the domain
/// of the hysteresis models (`x` in [1e-12, 1e6], `y` in [0.2, 6]); in general the
/// absolute error of `y log2 x` is about `(0.3 |y| + 2) 2^-53`.
///
/// Special values follow C99 for `x >= 0`: `x^0 = 1` and `1^y = 1` for any `x`,
/// `y` (even NaN); `0^y` is 0 for `y > 0` and infinity for `y < 0`;
/// `inf^y` is infinity for `y > 0` and 0 for `y < 0`; `x^inf` is infinity for
/// `x > 1` and 0 for `x < 1`. Negative `x` (outside the domain) gives NaN, as
/// does NaN in either argument otherwise; `-0` counts as `+0`.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    let xb = x.to_bits();
    // One test for positive, normal and finite x and finite y.
    if xb.wrapping_sub(MIN_NORMAL_BITS) >= EXP_MASK - MIN_NORMAL_BITS
        || (y.to_bits() & EXP_MASK) == EXP_MASK
    {
        return pow_special(x, y);
    }
    pow_core(xb, 0, y)
}

/// `x^y` for `x = bits(xb) * 2^eoff`, `xb` positive normal, `y` finite.
#[inline(always)]
fn pow_core(xb: u64, eoff: i64, y: f64) -> f64 {
    let off = xb.wrapping_sub(LOG_OFFSET);
    let e_field = off & 0xfff0_0000_0000_0000;
    let e = ((off as i64) >> 52) + eoff;
    let (c, log2c) = LOG_TABLE[((off >> 48) & 15) as usize];
    let m = f64::from_bits(xb.wrapping_sub(e_field));
    // log2 m = log2 c + s P(s^2): m - c is exact (Sterbenz).
    let s = (m - c) / (m + c);
    let z = s * s;
    let log2m = log2c + s * (P[0] + z * P[1] + z * z * (P[2] + z * P[3]));

    // y log2 x = y e + y log2 m, with y e = yh e + yl e exactly: yh has 26
    // significant bits, e at most 11.
    let ef = e as f64;
    let yh = f64::from_bits(y.to_bits() & 0xffff_ffff_f800_0000);
    let t1 = yh * ef;
    let t2 = (y - yh) * ef;
    let p = y * log2m;
    // k = round(32 y log2 x); the rest g = 32 y log2 x - k is gathered so that only
    // additions of size |g| <= 1/2 round.
    let kt = (t1 + (p + t2)) * 32.0 + SHIFT;
    // Wrapping: for |y log2 x| far beyond the range (kt negative, infinite
    // or NaN) the difference of the bit patterns overflows, and the wrapped
    // value lands outside the window the next line accepts.
    let k = (kt.to_bits() as i64).wrapping_sub(SHIFT.to_bits() as i64);
    let kf = kt - SHIFT;
    if (k.wrapping_add(35_000)) as u64 > 70_000 {
        return pow_out_of_range(t1 + (p + t2));
    }
    let g = ((t1 * 32.0 - kf) + p * 32.0) + t2 * 32.0;
    exp_kernel(k, g * LN2_32)
}

/// `2^t` for `|t| > 1093`: beyond the range of `f64` either way.
#[cold]
#[inline(never)]
fn pow_out_of_range(t: f64) -> f64 {
    if t > 0.0 {
        f64::INFINITY
    } else if t < 0.0 {
        0.0
    } else {
        f64::NAN
    }
}

#[cold]
#[inline(never)]
fn pow_special(x: f64, y: f64) -> f64 {
    if y == 0.0 || x == 1.0 {
        return 1.0;
    }
    if x.is_nan() || y.is_nan() || x < 0.0 {
        return f64::NAN;
    }
    if y.is_infinite() {
        return match (x > 1.0, y > 0.0) {
            (true, true) | (false, false) => f64::INFINITY,
            _ => 0.0,
        };
    }
    if x == 0.0 {
        return if y > 0.0 { 0.0 } else { f64::INFINITY };
    }
    if x.is_infinite() {
        return if y > 0.0 { f64::INFINITY } else { 0.0 };
    }
    // Subnormal x: scale it into the normal range first.
    pow_core((x * pow2i(54)).to_bits(), -54, y)
}

#[cfg(test)]
mod tests {
    //! Against the standard library's (glibc's) `f64` functions, which are within
    //! one ulp of the exact values: `|got - std| / |std|`.
    use super::*;

    /// Largest relative error of [`exp`] for `|x| <= 708` (normal results).
    pub(super) const EXP_BOUND: f64 = 3.5e-16;
    /// Largest relative error of [`pow`] for `x` in [1e-12, 1e6], `y` in [0.2, 6].
    pub(super) const POW_BOUND: f64 = 1.0e-15;

    /// SplitMix64: a fixed, reproducible stream of draws.
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

    fn rel(got: f64, exact: f64) -> f64 {
        ((got - exact) / exact).abs()
    }

    /// The largest relative error over `cases` and where it occurs; NaN counts as infinite.
    fn worst(cases: impl Iterator<Item = (f64, f64, f64)>) -> (f64, f64, f64) {
        cases.fold((0.0, 0.0, 0.0), |w, (a, got, exact)| {
            let e = rel(got, exact);
            let e = if e.is_nan() { f64::INFINITY } else { e };
            if e > w.0 {
                (e, a, got)
            } else {
                w
            }
        })
    }

    /// `x^y` on the models' domain: a dense geometric grid (ratio not a root of 10,
    /// so the points do not repeat per decade) and uniform draws in log x and y.
    fn pow_domain() -> impl Iterator<Item = (f64, f64)> {
        let grid = (0..3001).flat_map(|i| {
            let x =
                1e-12 * (1e18f64).powf(i as f64 / 3000.0) * (1.0 + 1e-3 * ((i * 7) % 11) as f64);
            (0..200).map(move |j| (x.min(1e6), 0.2 + 5.8 * j as f64 / 199.0))
        });
        let mut d = Draws(1);
        let random = (0..500_000).map(move |_| {
            let x = 10f64.powf(-12.0 + 18.0 * d.next());
            (x, 0.2 + 5.8 * d.next())
        });
        // Near 1, where log2 m is small and the table intervals meet.
        let near_one = (0..20_001).flat_map(|i| {
            let x = 1.0 + (i as f64 - 10_000.0) * 3.7e-5;
            [(x, 0.5), (x, 1.7), (x, 5.9)]
        });
        grid.chain(random).chain(near_one)
    }

    #[test]
    fn pow_meets_its_bound_on_the_model_domain() {
        let (err, x, got) = worst(pow_domain().map(|(x, y)| (x, pow(x, y), x.powf(y))));
        println!("pow: max relative error {err:.3e} (x = {x:e}, got {got:e})");
        assert!(
            err <= POW_BOUND,
            "pow error {err:e} > {POW_BOUND:e} at x = {x:e}"
        );
        assert!(
            err > POW_BOUND / 2.0,
            "bound {POW_BOUND:e} is loose: max {err:e}"
        );
    }

    #[test]
    fn exp_meets_its_bound() {
        let n = 2_000_001;
        let sweep = (0..n).map(|i| -708.0 + 1416.0 * i as f64 / (n - 1) as f64);
        let mut d = Draws(2);
        let random = (0..500_000).map(move |_| -708.0 + 1416.0 * d.next());
        let small = (0..100_001).map(|i| (i as f64 - 50_000.0) * 1e-5);
        let (err, x, got) = worst(
            sweep
                .chain(random)
                .chain(small)
                .map(|x| (x, exp(x), x.exp())),
        );
        println!("exp: max relative error {err:.3e} (x = {x:e}, got {got:e})");
        assert!(
            err <= EXP_BOUND,
            "exp error {err:e} > {EXP_BOUND:e} at x = {x:e}"
        );
        assert!(
            err > EXP_BOUND / 2.0,
            "bound {EXP_BOUND:e} is loose: max {err:e}"
        );
    }

    #[test]
    fn tables_are_rounded_to_nearest() {
        for (j, t) in EXP2_TABLE.iter().enumerate() {
            assert_eq!(*t, (j as f64 / 32.0).exp2(), "2^({j}/32)");
        }
        for (j, &(c, l)) in LOG_TABLE.iter().enumerate() {
            let want = match j {
                0..=8 => 0.703125 + (j as f64 + 0.5) / 32.0,
                9 => 1.0,
                _ => 1.03125 + (j as f64 - 9.5) / 16.0,
            };
            assert_eq!(c, want, "centre {j}");
            assert_eq!(l, c.log2(), "log2 of centre {j}");
            // The interval of index j, as pow_core reads it from the bits of m.
            let lo = f64::from_bits(LOG_OFFSET + ((j as u64) << 48));
            let hi = f64::from_bits(LOG_OFFSET + ((j as u64 + 1) << 48));
            assert!(lo <= c && c < hi, "centre {j} outside [{lo}, {hi})");
            let s = ((lo - c) / (lo + c)).abs().max(((hi - c) / (hi + c)).abs());
            assert!(
                s <= 0.015_384_7,
                "interval {j}: |s| up to {s}, beyond the fit of P"
            );
        }
        assert!(((LN2_32_HI + LN2_32_LO) * 32.0 - core::f64::consts::LN_2).abs() < 1e-17);
        assert_eq!(
            (LN2_32_HI.to_bits() & 0x1f_ffff),
            0,
            "k * LN2_32_HI must be exact"
        );
    }

    fn same_class(a: f64, b: f64) -> bool {
        (a.is_nan() && b.is_nan()) || (a.is_infinite() && a == b) || (a == 0.0 && b == 0.0)
    }

    /// ulps between two non-negative finite doubles.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn exp_special_values_and_range_ends() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        assert!(exp(f64::NAN).is_nan());
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert_eq!(exp(1e300), f64::INFINITY);
        assert_eq!(exp(-1e300), 0.0);
        // Overflow threshold ln(MAX) = 709.782712893384, underflow below -745.13.
        assert!(exp(709.78).is_finite());
        assert_eq!(exp(709.79), f64::INFINITY);
        assert_eq!(exp(-745.2), 0.0);
        // The wide-range path: results near MAX and subnormal results, one rounding
        // (one ulp) against std.
        let mut x = 700.0;
        while x < 709.78 {
            assert!(rel(exp(x), x.exp()) <= EXP_BOUND, "exp({x})");
            x += 0.0137;
        }
        let mut x = -745.13;
        while x < -700.0 {
            let (got, want) = (exp(x), x.exp());
            let ok = if want < f64::MIN_POSITIVE {
                ulps(got, want) <= 1
            } else {
                rel(got, want) <= EXP_BOUND
            };
            assert!(ok, "exp({x}) = {got:e} vs {want:e}");
            x += 0.0137;
        }
    }

    /// `y log2 x` of about -3e14 puts the rounding constant's sum just below
    /// zero, where the bit-pattern difference overflowed `i64` (found by
    /// fuzzing the table loader: a panic in debug builds).
    #[test]
    fn pow_far_below_the_range_underflows_without_overflowing_the_exponent() {
        for y in [2.2e14, 3e14, 3.4e14] {
            assert_eq!(pow(0.5, y), 0.0, "0.5^{y}");
            assert_eq!(pow(2.0, -y), 0.0, "2^-{y}");
            assert_eq!(pow(2.0, y), f64::INFINITY, "2^{y}");
        }
    }

    #[test]
    fn pow_special_values_follow_c99_for_non_negative_x() {
        let xs = [
            0.0,
            -0.0,
            5e-324,
            1e-310,
            f64::MIN_POSITIVE,
            0.5,
            1.0,
            2.0,
            1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        let ys = [
            0.0,
            -0.0,
            1e-300,
            0.5,
            1.0,
            2.0,
            -1.0,
            -0.5,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for x in xs {
            for y in ys {
                if x == 0.0 && x.is_sign_negative() && y < 0.0 {
                    // C99 gives -inf for -0 and odd integer y; -0 is +0 here.
                    assert_eq!(pow(x, y), f64::INFINITY);
                    continue;
                }
                let (got, want) = (pow(x, y), x.powf(y));
                let ok = if want.is_finite() && want != 0.0 {
                    rel(got, want) <= POW_BOUND || ulps(got, want) <= 1
                } else {
                    same_class(got, want)
                };
                assert!(ok, "pow({x:e}, {y:e}) = {got:e}, std {want:e}");
            }
        }
        // Outside the domain: negative x.
        assert!(pow(-2.0, 0.5).is_nan());
        assert!(pow(-2.0, 2.0).is_nan());
        assert_eq!(pow(-2.0, 0.0), 1.0);
        assert_eq!(pow(0.0, 1.7), 0.0);
        assert_eq!(pow(1.0, 123.456), 1.0);
    }

    #[test]
    fn pow_overflow_underflow_and_subnormal_results() {
        assert!(pow(2.0, 1023.999).is_finite());
        assert_eq!(pow(2.0, 1024.0), f64::INFINITY);
        assert!(pow(10.0, 308.25).is_finite());
        assert_eq!(pow(10.0, 308.26), f64::INFINITY);
        assert_eq!(pow(1e-12, 6.0e3), 0.0);
        assert_eq!(pow(1e6, 6.0e3), f64::INFINITY);
        assert_eq!(pow(2.0, -1074.0), 5e-324);
        assert_eq!(pow(2.0, -1076.0), 0.0);
        // Results in the subnormal range and near MAX, against std.
        let mut y = 1.0;
        while y < 1.1 {
            for x in [1e-300, 3e-290, 1.7e-305] {
                let (got, want) = (pow(x, y), x.powf(y));
                let ok = if want < f64::MIN_POSITIVE {
                    ulps(got, want) <= 1
                } else {
                    rel(got, want) <= POW_BOUND
                };
                assert!(ok, "pow({x:e}, {y}) = {got:e}, std {want:e}");
            }
            y += 0.0011;
        }
        let mut y = 1.0;
        while y < 1.03 {
            let x = 1e300;
            let (got, want) = (pow(x, y), x.powf(y));
            assert!(
                same_class(got, want) || rel(got, want) <= POW_BOUND,
                "pow({x:e}, {y})"
            );
            y += 0.00011;
        }
    }

    #[test]
    fn pow_of_subnormal_x() {
        for x in [5e-324, 1e-320, 2.5e-310] {
            for y in [0.01, 0.2, 0.5, 0.9] {
                let (got, want) = (pow(x, y), x.powf(y));
                assert!(
                    rel(got, want) <= POW_BOUND,
                    "pow({x:e}, {y}) = {got:e}, std {want:e}"
                );
            }
        }
    }
}
