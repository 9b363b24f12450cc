//! Noise in an imposed displacement: reversals that never happened.
//!
//! A displacement-driven model takes every sample of the measured
//! displacement as where the specimen went. Where the noise is as large as
//! the motion from one sample to the next, the measured path turns back and
//! forth all along its branches, and each turn unloads the model along its
//! elastic slope and reloads it: the loop ratchets. A fit then bends its
//! parameters to follow, and an effect that helps it do so looks significant.
//! On records of an independent simulator with strong stiffness degradation
//! and 0.2 mm of displacement noise on a path up to 100 mm (the noise of
//! `../shared/data/synthetic/`), `hyst discover` added strength degradation
//! after stiffness degradation (delta-BIC -28) on five records of five.
//!
//! The remedy keeps what the record resolves and drops what it cannot
//! ([`monotone`]):
//! * the noise is estimated from the third differences ([`noise`]);
//! * the turning points that rise above it, [`THRESHOLD`] deviations, are
//!   the reversals of the test (found as the diagnosis finds its cycles:
//!   [`Cycles`] with that absolute threshold);
//! * between two of them the path is replaced by its least-squares monotone
//!   fit ([`isotonic`], the pool-adjacent-violators algorithm), which keeps
//!   the turning points exactly and moves no sample further than the noise
//!   made it wander.
//!
//! This is done only when at least half of the measured reversals are such
//! noise: a record whose reversals are the test's is left as it is.

use crate::data::{Cycles, Threshold};
use serde::Serialize;

/// Turning points must rise this many noise deviations above the path on
/// both sides to count as reversals. The difference of two noisy samples has
/// a deviation of sqrt(2), so this is 4.2 of those: a sample-to-sample
/// wander that large is rarer than one in 30,000.
pub const THRESHOLD: f64 = 6.0;

/// The noise of `u` as a standard deviation, from the median absolute third
/// difference: white noise of deviation `s` gives third differences of
/// deviation `s sqrt(20)`, while a path sampled densely enough to be resolved
/// has third differences near zero away from its reversals, so the median
/// sees the noise. (On a coarsely sampled path it sees the path too and
/// overestimates.) `None` for fewer than eight samples.
pub fn noise(u: &[f64]) -> Option<f64> {
    if u.len() < 8 {
        return None;
    }
    let mut d3: Vec<f64> = u
        .windows(4)
        .map(|w| (w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0]).abs())
        .collect();
    let mid = d3.len() / 2;
    let (_, median, _) = d3.select_nth_unstable_by(mid, f64::total_cmp);
    // 0.6745: the median of |x| for a standard normal x.
    Some(*median / 0.6745 / 20f64.sqrt())
}

/// How often `u` turns back: sign changes between its non-zero increments.
pub fn reversals(u: &[f64]) -> usize {
    let mut last = 0.0f64;
    let mut count = 0;
    for w in u.windows(2) {
        let d = w[1] - w[0];
        if d != 0.0 {
            if last != 0.0 && d.signum() != last.signum() {
                count += 1;
            }
            last = d;
        }
    }
    count
}

/// The least-squares fit to `y` that never falls (`increasing`) or never
/// rises: the pool-adjacent-violators algorithm, O(n).
pub fn isotonic(y: &[f64], increasing: bool) -> Vec<f64> {
    let sign = if increasing { 1.0 } else { -1.0 };
    // Blocks of pooled samples: (sum, count), in the increasing frame.
    let mut blocks: Vec<(f64, usize)> = Vec::with_capacity(y.len());
    for &v in y {
        blocks.push((sign * v, 1));
        while let [.., (s0, c0), (s1, c1)] = blocks[..] {
            if s0 / c0 as f64 <= s1 / c1 as f64 {
                break;
            }
            blocks.pop();
            if let Some(last) = blocks.last_mut() {
                *last = (s0 + s1, c0 + c1);
            }
        }
    }
    blocks
        .iter()
        .flat_map(|&(s, c)| std::iter::repeat_n(sign * s / c as f64, c))
        .collect()
}

/// What [`monotone`] did to a record's displacement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Monotone {
    /// The estimated noise of the measured displacement ([`noise`]).
    pub noise: f64,
    /// The height a turning point needs to count as a reversal.
    pub threshold: f64,
    /// Reversals of the measured displacement ([`reversals`]).
    pub measured_reversals: usize,
    /// Reversals kept: the turning points above the threshold ([`Cycles`]).
    pub kept_reversals: usize,
    /// The largest change made to a sample.
    pub largest_change: f64,
}

impl Monotone {
    /// One sentence for the user about the `quantity` (displacement, twist)
    /// in `unit`.
    pub fn describe(&self, quantity: &str, unit: &str) -> String {
        let noise_reversals = self.measured_reversals - self.kept_reversals;
        format!(
            "the {quantity} reverses {} times, but only {} of the turns rise more than {:.3} \
             {unit} ({THRESHOLD} times its noise of {:.3} {unit}, from third differences) above \
             the path around them; the other {noise_reversals} are noise, which a model would \
             take for unloading and reloading. The model is driven by the {quantity} made \
             monotone between the {} reversals (least squares, every sample within {:.3} {unit} \
             of the measured one); --raw-displacement keeps it as measured",
            self.measured_reversals,
            self.kept_reversals,
            self.threshold,
            self.noise,
            self.kept_reversals,
            self.largest_change,
        )
    }
}

/// `u` made monotone between its reversals, when at least half of its
/// measured reversals are noise; `None` otherwise (also when the noise
/// cannot be estimated or is zero).
pub fn monotone(u: &[f64]) -> Option<(Vec<f64>, Monotone)> {
    let sd = noise(u).filter(|s| *s > 0.0 && s.is_finite())?;
    let threshold = THRESHOLD * sd;
    // Each turning point is the extreme of the path between its neighbours,
    // so the monotone fits below keep it exactly.
    let cycles = Cycles::find(u, Threshold::Absolute(threshold)).ok()?;
    let turns = cycles.reversals();
    let measured = reversals(u);
    if measured.saturating_sub(turns.len()) < turns.len().max(1) {
        return None;
    }
    let mut out = Vec::with_capacity(u.len());
    let mut start = 0;
    for end in turns.iter().copied().chain([u.len() - 1]) {
        let fit = isotonic(&u[start..=end], u[end] >= u[start]);
        // The turning point opening this segment closed the previous one.
        let skip = usize::from(start > 0);
        out.extend_from_slice(&fit[skip..]);
        start = end;
    }
    let largest_change = u
        .iter()
        .zip(&out)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    Some((
        out,
        Monotone {
            noise: sd,
            threshold,
            measured_reversals: measured,
            kept_reversals: turns.len(),
            largest_change,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::Normal;

    /// `n` standard normal deviates from `seed`.
    fn gauss(seed: u64, n: usize) -> Vec<f64> {
        let mut g = Normal::new(seed);
        (0..n).map(|_| g.sample()).collect()
    }

    /// Triangular cycles of growing amplitude, `per_cycle` samples each, two
    /// at each amplitude: the path of the shared synthetic records.
    fn triangles(amplitudes: &[f64], per_cycle: usize) -> Vec<f64> {
        let mut u = vec![0.0];
        for &a in amplitudes {
            for _ in 0..2 {
                for k in 1..=per_cycle {
                    let t = k as f64 / per_cycle as f64;
                    let v = if t <= 0.25 {
                        4.0 * t
                    } else if t <= 0.75 {
                        2.0 - 4.0 * t
                    } else {
                        4.0 * t - 4.0
                    };
                    u.push(a * v);
                }
            }
        }
        u
    }

    fn noisy(u: &[f64], sd: f64, seed: u64) -> Vec<f64> {
        u.iter()
            .zip(gauss(seed, u.len()))
            .map(|(v, g)| v + sd * g)
            .collect()
    }

    #[test]
    fn the_noise_of_a_resolved_path_is_read_from_its_third_differences() {
        let path = triangles(&[5.0, 10.0, 20.0, 40.0], 100);
        for sd in [0.02, 0.2, 1.0] {
            let est = noise(&noisy(&path, sd, 7)).unwrap();
            // The median of 800 dependent differences: within a few percent.
            assert!((est / sd - 1.0).abs() < 0.1, "sd {sd}: estimated {est}");
        }
        // A clean triangle has third differences only at its corners (and
        // rounding elsewhere).
        assert!(noise(&path).unwrap() < 1e-12);
        assert_eq!(noise(&[1.0; 7]), None);
    }

    #[test]
    fn reversals_count_the_turns_of_the_increments() {
        assert_eq!(reversals(&[0.0, 1.0, 2.0, 1.0, 1.0, 0.0, 3.0]), 2);
        assert_eq!(reversals(&[0.0, 0.0, 0.0]), 0);
        assert_eq!(reversals(&triangles(&[1.0, 2.0], 8)), 8);
    }

    /// The reversals [`monotone`] keeps are those of [`Cycles`] at an
    /// absolute threshold: the extremes that stand out by more than it.
    #[test]
    fn turning_points_are_the_extremes_that_stand_out() {
        let turns = |u: &[f64], h: f64| {
            Cycles::find(u, Threshold::Absolute(h))
                .unwrap()
                .reversals()
                .to_vec()
        };
        // A peak of 2 and a trough of -1, with wiggles of 0.3 on the way.
        let u = [0.0, 1.0, 0.7, 2.0, 1.0, 1.3, -1.0, 0.0];
        assert_eq!(turns(&u, 0.5), vec![3, 6]);
        // Every wiggle counts at a lower threshold.
        assert_eq!(turns(&u, 0.2), vec![1, 2, 3, 4, 5, 6]);
        // A first move down, then up.
        assert_eq!(turns(&[0.0, -0.4, -2.0, 1.0], 1.0), vec![2]);
        assert!(turns(&[], 1.0).is_empty());
        // Swings larger than the threshold that stay within it of the first
        // sample are reversals too (all but the first extreme, which no
        // earlier move confirms).
        let opening = [0.0, 0.6, -0.6, 0.6, -0.6, 3.0, -3.0, 0.0];
        assert_eq!(turns(&opening, 1.0), vec![2, 3, 4, 5, 6]);
    }

    #[test]
    fn isotonic_regression_pools_the_violators() {
        // Worked by hand: (3, 1) pool to 2, then (2, 2, 2) stays.
        assert_eq!(
            isotonic(&[1.0, 3.0, 1.0, 2.0], true),
            vec![1.0, 2.0, 2.0, 2.0]
        );
        assert_eq!(
            isotonic(&[3.0, 1.0, 2.0, 0.0], false),
            vec![3.0, 1.5, 1.5, 0.0]
        );
        // Already monotone: unchanged.
        let m = [0.0, 0.5, 0.5, 2.0];
        assert_eq!(isotonic(&m, true), m.to_vec());
        // Least squares keeps the mean.
        let g = gauss(3, 500);
        let fit = isotonic(&g, true);
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert!((mean(&fit) - mean(&g)).abs() < 1e-12);
        assert!(fit.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn a_noisy_path_keeps_its_reversals_and_loses_the_others() {
        let amplitudes = [5.0, 10.0, 20.0, 30.0, 40.0, 60.0, 80.0, 100.0];
        let path = triangles(&amplitudes, 100);
        let measured = noisy(&path, 0.2, 11);
        let (out, m) = monotone(&measured).expect("a noisy record");
        // The test's reversals: a peak and a trough a cycle.
        assert_eq!(m.kept_reversals, 2 * 2 * amplitudes.len());
        assert!(m.measured_reversals > 2 * m.kept_reversals, "{m:?}");
        assert_eq!(reversals(&out), m.kept_reversals);
        // Closer to the path than the measurement is.
        let rms = |a: &[f64]| {
            (a.iter()
                .zip(&path)
                .map(|(x, p)| (x - p).powi(2))
                .sum::<f64>()
                / a.len() as f64)
                .sqrt()
        };
        assert!(
            rms(&out) < rms(&measured),
            "{} {}",
            rms(&out),
            rms(&measured)
        );
        // The turning points stay as measured.
        let cycles = Cycles::find(&measured, Threshold::Absolute(m.threshold)).unwrap();
        assert!(cycles.reversals().iter().all(|&i| out[i] == measured[i]));
        assert!(m.largest_change < 5.0 * 0.2, "{m:?}");
    }

    #[test]
    fn a_record_whose_reversals_are_the_tests_is_left_alone() {
        // Clean, and coarsely sampled with little noise.
        let path = triangles(&[5.0, 10.0, 20.0], 100);
        assert_eq!(monotone(&path), None);
        let coarse = noisy(&triangles(&[5.0, 10.0, 20.0], 16), 0.01, 5);
        assert_eq!(monotone(&coarse), None);
    }
}
