//! Axis ticks: "nice" 1-2-5 steps on linear axes, decades on log axes, and
//! labels in engineering form (a power of ten that is a multiple of 3 is
//! factored out of the labels and shown once, beside the unit).
//!
//! Labels are built from integers (tick index times step mantissa), so they
//! never show floating-point noise such as `0.30000000000000004`.

/// The ticks of one axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// Tick positions in data units, ascending.
    pub values: Vec<f64>,
    /// One label per tick.
    pub labels: Vec<String>,
    /// Power of ten factored out of the labels (a multiple of 3; 0 for none).
    pub exponent: i32,
}

/// Step mantissas tried, smallest first.
const MANTISSAS: [i64; 3] = [1, 2, 5];

/// Ticks at 1, 2 or 5 times a power of ten inside `[lo, hi]`, the step
/// nearest (by ratio) to the one giving `target` intervals, and at least two
/// ticks whenever the range allows.
///
/// `lo < hi` and both finite are expected; other input gives no ticks.
pub fn linear(lo: f64, hi: f64, target: usize) -> Ticks {
    let empty = Ticks {
        values: Vec::new(),
        labels: Vec::new(),
        exponent: 0,
    };
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return empty;
    }
    // Work on half-values so that `hi - lo` cannot overflow near f64::MAX.
    let half_span = hi / 2.0 - lo / 2.0;
    let target = target.max(2) as f64;
    let raw = half_span / target * 2.0;
    // The 1-2-5 step nearest the raw step by ratio.
    let e0 = raw.log10().floor() as i32;
    let off_by = |&(m, e): &(usize, i32)| (MANTISSAS[m] as f64 * pow10(e) / raw).ln().abs();
    let (mut m_idx, mut e) = [(0, e0), (1, e0), (2, e0), (0, e0 + 1)]
        .into_iter()
        .min_by(|a, b| off_by(a).total_cmp(&off_by(b)))
        .unwrap_or((0, e0));
    // Shrink the step until at least two ticks fall in the range.
    for _ in 0..8 {
        let step = MANTISSAS[m_idx] as f64 * pow10(e);
        let (k0, k1) = index_range(lo, hi, step);
        if k1 - k0 >= 1.0 || !step.is_normal() {
            break;
        }
        if m_idx == 0 {
            m_idx = MANTISSAS.len() - 1;
            e -= 1;
        } else {
            m_idx -= 1;
        }
    }
    let m = MANTISSAS[m_idx];
    let step = m as f64 * pow10(e);
    if !step.is_normal() {
        return empty;
    }
    let (k0, k1) = index_range(lo, hi, step);
    if !(k0.is_finite() && k1.is_finite()) || k1 < k0 || k1 - k0 > 1000.0 {
        return empty;
    }
    let ks: Vec<i64> = (k0 as i64..=k1 as i64).collect();
    let values: Vec<f64> = ks.iter().map(|&k| times_pow10((k * m) as f64, e)).collect();
    let largest = values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let exponent = engineering_exponent(largest);
    // Each label is (k * m) * 10^(e - exponent): an integer shifted by a
    // decimal point, the same number of decimals for every tick.
    let shift = e - exponent;
    let labels = ks.iter().map(|&k| shifted_integer(k * m, shift)).collect();
    Ticks {
        values,
        labels,
        exponent,
    }
}

/// First and last tick index `k` with `k * step` inside `[lo, hi]`, forgiving
/// the last-bit rounding of `lo / step` so a range ending on a tick keeps it.
fn index_range(lo: f64, hi: f64, step: f64) -> (f64, f64) {
    ((lo / step - 1e-9).ceil(), (hi / step + 1e-9).floor())
}

/// `x × 10^e`, dividing by an exact power of ten for negative `e` so that
/// 7 × 10⁻¹ is the double nearest 0.7.
fn times_pow10(x: f64, e: i32) -> f64 {
    if e < 0 {
        x / pow10(-e)
    } else {
        x * pow10(e)
    }
}

/// Ticks on a log axis over `[lo, hi]` (`0 < lo < hi`): every decade (or every
/// few decades on wide ranges), with 2 and 5 between decades on narrow ones,
/// and 1-2-5 linear ticks when the range is less than a decade wide.
pub fn log(lo: f64, hi: f64, target: usize) -> Ticks {
    let empty = Ticks {
        values: Vec::new(),
        labels: Vec::new(),
        exponent: 0,
    };
    if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi) {
        return empty;
    }
    let (d0, d1) = (lo.log10(), hi.log10());
    let decades = d1 - d0;
    let target = target.max(2);
    let mantissas: &[i64] = if decades < 2.5 { &[1, 2, 5] } else { &[1] };
    let every = ((decades / target as f64).ceil() as i32).max(1);
    let mut ticks = Vec::new();
    for e in (d0.floor() as i32 - 1)..=(d1.ceil() as i32) {
        if mantissas.len() == 1 && e.rem_euclid(every) != 0 {
            continue;
        }
        for &m in mantissas {
            let v = times_pow10(m as f64, e);
            if v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12) {
                ticks.push((v, m, e));
            }
        }
    }
    // One style per axis: plain decimals when every tick reads well that way.
    let plain_style = ticks.iter().all(|&(_, _, e)| (-3..=4).contains(&e));
    let values: Vec<f64> = ticks.iter().map(|t| t.0).collect();
    let labels: Vec<String> = ticks
        .iter()
        .map(|&(_, m, e)| log_label(m, e, plain_style))
        .collect();
    if values.len() < 2 {
        // Less than a decade: plain linear ticks read better than one label.
        let mut t = linear(lo, hi, target);
        if t.exponent != 0 {
            // Log labels stand alone; undo the shared factor.
            t.labels = t.values.iter().map(|&v| plain(v)).collect();
            t.exponent = 0;
        }
        return t;
    }
    Ticks {
        values,
        labels,
        exponent: 0,
    }
}

/// The multiple of 3 to factor out of labels whose largest magnitude is
/// `largest`: none for 0.01 ≤ |v| < 10 000 (and for 0).
pub fn engineering_exponent(largest: f64) -> i32 {
    if largest == 0.0 || !largest.is_finite() || (1e-2..1e4).contains(&largest) {
        0
    } else {
        3 * (largest.log10().floor() as i32).div_euclid(3)
    }
}

/// `10^e` without the rounding drift of repeated multiplication.
pub fn pow10(e: i32) -> f64 {
    // `powi` is exact for |e| <= 22 and within an ulp or two elsewhere.
    10f64.powi(e)
}

/// The integer `n` times `10^shift`, written out in decimal (shift < 0 puts a
/// decimal point `-shift` places from the right). Uses U+2212 for minus.
fn shifted_integer(n: i64, shift: i32) -> String {
    let neg = n < 0;
    let mut digits = n.unsigned_abs().to_string();
    if shift >= 0 {
        if n != 0 {
            digits.extend(std::iter::repeat_n('0', shift as usize));
        }
    } else {
        let places = (-shift) as usize;
        if digits.len() <= places {
            let pad = places + 1 - digits.len();
            digits.insert_str(0, &"0".repeat(pad));
        }
        digits.insert(digits.len() - places, '.');
    }
    if neg {
        format!("\u{2212}{digits}")
    } else {
        digits
    }
}

/// Label of the log tick `m × 10^e`: plain decimals, or a power of ten.
fn log_label(m: i64, e: i32, plain_style: bool) -> String {
    if plain_style {
        shifted_integer(m, e)
    } else if m == 1 {
        format!("10{}", superscript(e))
    } else {
        format!("{m}\u{00d7}10{}", superscript(e))
    }
}

/// A value in the shortest plain decimal form with up to 6 significant digits.
pub fn plain(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let digits = (5 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    s.replace('-', "\u{2212}")
}

/// An integer in Unicode superscript digits (for `×10³` and `10⁻⁶`).
pub fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for c in n.unsigned_abs().to_string().chars() {
        s.push(DIGITS[c as usize - '0' as usize]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_one_two_five(t: &Ticks) {
        assert!(t.values.len() >= 2, "too few ticks: {t:?}");
        let step = t.values[1] - t.values[0];
        for w in t.values.windows(2) {
            assert!(
                ((w[1] - w[0]) / step - 1.0).abs() < 1e-9,
                "uneven steps {t:?}"
            );
        }
        let mantissa = step / pow10(step.log10().floor() as i32);
        assert!(
            [1.0, 2.0, 5.0, 10.0]
                .iter()
                .any(|m| (mantissa - m).abs() < 1e-6),
            "step {step} is not 1-2-5"
        );
    }

    #[test]
    fn unit_range() {
        let t = linear(0.0, 1.0, 5);
        assert_eq!(t.labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        assert_eq!(t.exponent, 0);
    }

    #[test]
    fn negative_range_uses_true_minus() {
        let t = linear(-47.0, 52.0, 5);
        assert_eq!(t.labels, ["\u{2212}40", "\u{2212}20", "0", "20", "40"]);
        assert_one_two_five(&t);
    }

    #[test]
    fn labels_have_no_float_noise() {
        let t = linear(0.1, 0.7, 6);
        assert_eq!(t.labels, ["0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"]);
    }

    #[test]
    fn tiny_range_factors_out_engineering_exponent() {
        let t = linear(1.2e-9, 7.9e-9, 5);
        assert_eq!(t.exponent, -9);
        assert_eq!(t.labels, ["2", "3", "4", "5", "6", "7"]);
        assert_one_two_five(&t);
    }

    #[test]
    fn huge_range_factors_out_engineering_exponent() {
        let t = linear(0.0, 3.3e7, 4);
        assert_eq!(t.exponent, 6);
        assert_eq!(t.labels, ["0", "10", "20", "30"]);
    }

    #[test]
    fn near_f64_limits_do_not_overflow() {
        let t = linear(-f64::MAX, f64::MAX, 5);
        assert!(t.values.iter().all(|v| v.is_finite()));
        assert_one_two_five(&t);
        assert_eq!(t.exponent, 306);
        let t = linear(1e-300, 9e-300, 4);
        assert_eq!(t.exponent, -300);
        assert_one_two_five(&t);
    }

    #[test]
    fn narrow_offset_range_keeps_decimals() {
        let t = linear(100.001, 100.004, 4);
        assert_eq!(t.labels, ["100.001", "100.002", "100.003", "100.004"]);
    }

    #[test]
    fn degenerate_and_non_finite_ranges_give_no_ticks() {
        for (lo, hi) in [
            (1.0, 1.0),
            (2.0, 1.0),
            (f64::NAN, 1.0),
            (0.0, f64::INFINITY),
        ] {
            let t = linear(lo, hi, 5);
            assert!(t.values.is_empty(), "{lo}..{hi} gave {t:?}");
            assert!(log(lo, hi, 5).values.is_empty());
        }
        assert!(log(-1.0, 10.0, 5).values.is_empty());
    }

    #[test]
    fn every_target_gives_at_least_two_ticks() {
        for target in 1..12 {
            for (lo, hi) in [(0.0, 1.0), (0.95, 1.05), (-3.0, 1e5), (12.0, 13.0)] {
                let t = linear(lo, hi, target);
                assert_one_two_five(&t);
                assert!(t.values.len() <= 2 * target + 3, "{lo}..{hi}: {t:?}");
                assert!(t.values.iter().all(|&v| v >= lo && v <= hi));
            }
        }
    }

    #[test]
    fn log_decades_and_intermediates() {
        let t = log(0.01, 0.5, 6);
        assert_eq!(t.labels, ["0.01", "0.02", "0.05", "0.1", "0.2", "0.5"]);
        let t = log(1e-9, 1e3, 6);
        assert_eq!(t.labels, ["10⁻⁸", "10⁻⁶", "10⁻⁴", "10⁻²", "10⁰", "10²"]);
    }

    #[test]
    fn log_below_one_decade_falls_back_to_linear() {
        let t = log(0.031, 0.048, 4);
        assert!(t.values.len() >= 2);
        assert!(t.labels.iter().all(|l| l.starts_with("0.0")), "{t:?}");
    }

    #[test]
    fn superscripts() {
        assert_eq!(superscript(-12), "⁻¹²");
        assert_eq!(superscript(3), "³");
        assert_eq!(plain(-0.00125), "\u{2212}0.00125");
        assert_eq!(plain(1500.0), "1500");
    }
}
