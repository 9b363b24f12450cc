//! Slip or a gap: an effect the library does not model, looked for so that
//! the diagnosis can name it instead of blaming pinching, which it resembles
//! (`../shared/notes/architecture.md`: "a flat plateau of near-zero force on
//! reversal, over a displacement band; often mistaken for pinching").
//!
//! Bars slipping in their anchorage, a bolt bearing in an oversized hole or
//! backlash in a linkage let the displacement run on at zero force after each
//! reversal until the parts bear again. The Bouc-Wen models cannot hold the
//! force at zero over a band of displacement: pinching (thesis eqs
//! 3.9-3.11) narrows the loop around zero force by lowering the rate of z,
//! but the force still changes with the elastic part `alpha k u`, and the
//! narrowing grows with the dissipated energy, so it is weakest in the first
//! cycles, where a gap is already as wide as it will be.
//!
//! The check looks at each half-cycle of a displacement-driven record (larger
//! than a tenth of the displacement range) where the force changes sign, and
//! measures the band of displacement around the sign change over which
//! `|F|` stays within [`TAU`] and [`TAU`]/2 of the record's peak force,
//! in the measurement and in the model:
//!
//! * **flatness**: the band at `TAU/2` over the band at `TAU`. A force that
//!   crosses zero with a slope gives about 0.5 (the band halves with the
//!   threshold); a plateau at zero gives about 1.
//! * **excess**: how much wider the measured band at `TAU/2` is than the
//!   model's, as a fraction of the half-cycle's displacement.
//!
//! Named (significant) when at least [`MIN_REVERSALS`] half-cycles are
//! measured, the median flatness is at least [`MIN_FLATNESS`] and the median
//! excess at least [`MIN_EXCESS`]. Measured under `bw` fits
//! (`tests/discover_slip.rs`): gaps of 0.5 and 1 mm (plateaus of 1 and 2 mm
//! against a yield displacement of 1 mm) give flatness 0.92-1.00 and excess
//! 0.12-0.40, and plateaus of 0.93-0.99 and 1.82-1.93 mm; no gap, and hidden
//! pinching, strength or stiffness degradation or asymmetry, give flatness at
//! most 0.45 and excess at most 0.037, as do the shared records s1 and s2;
//! with pinching added to the fit of s1 the excess is 0.

use super::diagnosis::Diagnosis;
use super::ladder::Discovery;
use crate::fit::experiment::Drive;
use serde::Serialize;
use std::ops::RangeInclusive;

/// The wider force band, as a fraction of the record's peak force.
pub const TAU: f64 = 0.1;
/// Fewest half-cycles with a measured band for the check to name slip.
pub const MIN_REVERSALS: usize = 4;
/// Smallest median flatness (band at `TAU/2` over band at `TAU`) of a
/// plateau: a straight crossing gives 0.5.
pub const MIN_FLATNESS: f64 = 0.75;
/// Smallest median excess of the measured band over the model's, as a
/// fraction of the half-cycle's displacement.
pub const MIN_EXCESS: f64 = 0.07;

/// What the record says about slip.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SlipCheck {
    /// A plateau the model lacks (see the module docs for the rule).
    pub significant: bool,
    /// Half-cycles measured (large enough, with a sign change of the force).
    pub reversals: usize,
    /// Median width of the measured band where `|F| <= TAU/2` of the peak
    /// force, in displacement units: the plateau's length, twice the gap.
    pub plateau: f64,
    /// The same for the model.
    pub model_plateau: f64,
    /// Median flatness of the measured bands (about 0.5 for a force crossing
    /// zero with a slope, 1 for a plateau).
    pub flatness: f64,
    /// Median excess of the measured band over the model's, as a fraction of
    /// the half-cycle's displacement.
    pub excess: f64,
    /// Share of the squared error inside the measured bands at `TAU`.
    pub share: f64,
    /// The evidence in words.
    pub evidence: String,
}

/// The samples of `path` around the first sign change of `f` along it over
/// which `|f| <= limit`, or `None` if `f` keeps its sign.
fn band(f: &[f64], path: &RangeInclusive<usize>, limit: f64) -> Option<RangeInclusive<usize>> {
    let (start, end) = (*path.start(), *path.end());
    let cross = (start + 1..=end).find(|&i| f[i - 1] * f[i] < 0.0 || f[i] == 0.0)?;
    let within = |i: usize| f[i].abs() <= limit;
    // The sample on the crossing's far side may exceed the limit in one
    // step; the band then is the crossing's near side alone, or empty.
    let seed = [cross, cross - 1].into_iter().find(|&i| within(i))?;
    let (mut lo, mut hi) = (seed, seed);
    while lo > start && within(lo - 1) {
        lo -= 1;
    }
    while hi < end && within(hi + 1) {
        hi += 1;
    }
    Some(lo..=hi)
}

/// Width in displacement of the samples `r` (0 for none).
fn width(u: &[f64], r: Option<&RangeInclusive<usize>>) -> f64 {
    r.map_or(0.0, |r| (u[*r.end()] - u[*r.start()]).abs())
}

fn median(mut x: Vec<f64>) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    x.sort_by(f64::total_cmp);
    let m = x.len() / 2;
    if x.len() % 2 == 1 {
        x[m]
    } else {
        0.5 * (x[m - 1] + x[m])
    }
}

/// Looks for a plateau of zero force on reversal in the record of `d` that
/// its model lacks. `None` for force-driven records (whose model output is a
/// displacement) and records without a half-cycle where the force changes
/// sign.
pub fn check(d: &Diagnosis, drive: &Drive) -> Option<SlipCheck> {
    if !matches!(drive, Drive::Displacement) {
        return None;
    }
    let (u, f, model) = (&d.displacement, &d.force, &d.prediction.force);
    let peak = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (lo, hi) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let range = hi - lo;
    if !(peak > 0.0 && range > 0.0) {
        return None;
    }
    let (wide, narrow) = (TAU * peak, 0.5 * TAU * peak);
    let (mut flat, mut excess, mut measured, mut modelled) = (vec![], vec![], vec![], vec![]);
    // Half-cycles whose wide band holds fewer than three samples: sampled too
    // coarsely around zero force to tell a slope from a plateau.
    let mut coarse = 0;
    let mut in_band = vec![false; u.len()];
    for h in d.segmentation.cycles().half_cycles() {
        let path = h.path();
        let amplitude = (u[*path.end()] - u[*path.start()]).abs();
        if !h.complete || amplitude < 0.1 * range {
            continue;
        }
        let Some(m_wide) = band(f, &path, wide) else {
            continue;
        };
        let m_narrow = band(f, &path, narrow);
        let f_narrow = band(model, &path, narrow);
        coarse += usize::from(m_wide.clone().count() < 3);
        let w_wide = width(u, Some(&m_wide));
        let (w_m, w_f) = (width(u, m_narrow.as_ref()), width(u, f_narrow.as_ref()));
        flat.push(if w_wide > 0.0 { w_m / w_wide } else { 0.0 });
        excess.push((w_m - w_f) / amplitude);
        measured.push(w_m);
        modelled.push(w_f);
        for i in m_wide {
            in_band[i] = true;
        }
    }
    let reversals = flat.len();
    if reversals == 0 {
        return None;
    }
    let (flatness, excess) = (median(flat), median(excess));
    let (plateau, model_plateau) = (median(measured), median(modelled));
    let in_sq: f64 = d
        .residual
        .iter()
        .zip(&in_band)
        .filter(|(_, b)| **b)
        .map(|(r, _)| r * r)
        .sum();
    let share = if d.total_sq > 0.0 {
        in_sq / d.total_sq
    } else {
        0.0
    };
    let significant =
        reversals >= MIN_REVERSALS && flatness >= MIN_FLATNESS && excess >= MIN_EXCESS;
    let verdict = if significant {
        "A plateau of zero force over a band of displacement is slip or a gap (bars slipping in \
         their anchorage, bolts in oversized holes, backlash), and no effect of the library holds \
         the force at zero over a band: pinching narrows the loop around zero force by slowing z, \
         but the elastic part alpha k u keeps a slope there, and it grows with the dissipated \
         energy. Model it outside them (a gap element in series with this model); the \
         plateau's length is about twice the gap."
            .to_string()
    } else if reversals < MIN_REVERSALS {
        format!("Not significant: {reversals} half-cycles are too few to tell (at least {MIN_REVERSALS}).")
    } else if flatness < MIN_FLATNESS {
        "Not significant: the measured force crosses zero with a slope, not along a plateau."
            .to_string()
    } else {
        "Not significant: the model's band around zero force is about as wide as the measured."
            .to_string()
    };
    let evidence = if !significant && 2 * coarse > reversals {
        format!(
            "In {coarse} of {reversals} half-cycles the measured force passes from -{:.0}% to \
             +{:.0}% of its peak in fewer than three samples, too few to tell a slope from a \
             plateau; a plateau as long as a gap would hold many. {:.0}% of the squared error \
             lies around these crossings. Not significant: no sign of a plateau.",
            100.0 * TAU,
            100.0 * TAU,
            100.0 * share,
        )
    } else {
        let band = 50.0 * TAU;
        let measured = band_words(plateau, band);
        format!(
            "In {reversals} half-cycles the measured force {measured}, the model's stays in it \
             over {model_plateau:.4} mm; the measured band at {band:.0}% is {:.0}% as wide as at \
             {:.0}% (flatness {flatness:.2}: about 0.5 where the force crosses zero with a slope, \
             1 on a plateau), and it is wider than the model's by {:.1}% of the half-cycle's \
             displacement. {:.0}% of the squared error lies in these bands. {verdict}",
            100.0 * flatness,
            100.0 * TAU,
            100.0 * excess,
            100.0 * share,
        )
    };
    Some(SlipCheck {
        significant,
        reversals,
        plateau,
        model_plateau,
        flatness,
        excess,
        share,
        evidence,
    })
}

/// The slip check of a ladder: the final model's, unless the first model's
/// found a plateau the final one no longer shows. Then the effects added
/// since stand in for the gap (pinching narrows the loop around zero force
/// and takes the plateau's error, but holds the force at zero over no band),
/// and the first check stands, saying so. Found on the fastener record
/// `cfs-fastener-peterman2014` c54o6: a plateau of 12 mm against the model's
/// 0.5, significant on `bw`, and not on the ladder's final model with four
/// effects added, which `discover` reported as no slip.
pub fn of_ladder(discovery: &Discovery, last: Option<SlipCheck>) -> Option<SlipCheck> {
    let [first, .., final_step] = discovery.steps.as_slice() else {
        return last;
    };
    if last.as_ref().is_some_and(|s| s.significant) {
        return last;
    }
    match check(&first.diagnosis, &first.problem.exp.drive) {
        Some(s) if s.significant => Some(SlipCheck {
            evidence: format!(
                "On the first model, {}: {} The effects added since ({}) narrow the loop around \
                 zero force and take the plateau's error, so on the final model the check no \
                 longer shows it, but none of them holds the force at zero over a band: they \
                 stand in for the gap.",
                first.spec,
                s.evidence,
                final_step
                    .spec
                    .effects()
                    .iter()
                    .filter(|e| !first.spec.contains(**e))
                    .map(|e| e.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            ..s
        }),
        _ => last,
    }
}

/// What the measured force does in the band within `band` percent of its
/// peak around zero, whose median width is `plateau` (mm). A band of no
/// width is a force that passes it between two samples: "over 0.0000 mm"
/// read as a glitch (found by review).
fn band_words(plateau: f64, band: f64) -> String {
    if plateau > 0.0 {
        format!(
            "stays within {band:.0}% of its peak around zero over {plateau:.4} mm of \
             displacement (median)"
        )
    } else {
        format!(
            "passes the band within {band:.0}% of its peak around zero between two samples \
             (median: no sample inside it)"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_passed_between_two_samples_is_said_so() {
        assert_eq!(
            band_words(0.0556, 5.0),
            "stays within 5% of its peak around zero over 0.0556 mm of displacement (median)"
        );
        assert_eq!(
            band_words(0.0, 5.0),
            "passes the band within 5% of its peak around zero between two samples (median: no \
             sample inside it)"
        );
    }

    #[test]
    fn band_around_a_plateau_and_a_slope() {
        // Along u = 0..10, a force with a plateau of zero on 3..=6 and one
        // crossing zero with slope 1 at 5.
        let plateau: Vec<f64> = (0..=10)
            .map(|i| match i {
                0..=2 => (i as f64 - 3.0) * 2.0,
                3..=6 => 0.0,
                _ => (i as f64 - 6.0) * 2.0,
            })
            .collect();
        let slope: Vec<f64> = (0..=10).map(|i| i as f64 - 5.0).collect();
        let u: Vec<f64> = (0..=10).map(f64::from).collect();
        let path = 0..=10;
        let b = band(&plateau, &path, 0.5).unwrap();
        assert_eq!(b, 3..=6);
        assert_eq!(width(&u, Some(&b)), 3.0);
        // Twice the threshold: the plateau's band stays, the slope's widens.
        assert_eq!(band(&plateau, &path, 1.0).unwrap(), 3..=6);
        assert_eq!(band(&slope, &path, 1.0).unwrap(), 4..=6);
        assert_eq!(band(&slope, &path, 2.0).unwrap(), 3..=7);
        // No sign change, no band.
        let positive: Vec<f64> = (0..=10).map(|i| 1.0 + i as f64).collect();
        assert!(band(&positive, &path, 100.0).is_none());
    }

    #[test]
    fn median_of_odd_even_and_empty() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(vec![]).is_nan());
    }
}
