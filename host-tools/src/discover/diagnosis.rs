//! Comparing a fitted model with its record: errors per cycle, half-cycle
//! and branch class, energy and peak force per cycle, and the places where
//! the model fails, ranked by their share of the squared error and described
//! in an engineer's words.

use crate::data::{Branch, SegmentOptions, Segmentation};
use crate::fit::experiment::{Drive, Prediction};
use crate::fit::objectives::energy_input;
use crate::fit::problem::Problem;
use crate::fit::run::Outcome;
use anyhow::{anyhow, Result};
use serde::Serialize;

/// Measured against model for one cycle.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct CycleStats {
    /// Cycle number (1-based, as engineers count).
    pub cycle: usize,
    /// Whether the cycle closes (returns to its start).
    pub complete: bool,
    /// RMS of the residual over the cycle.
    pub rms_error: f64,
    /// Energy `∮ F du` measured over the cycle.
    pub energy_measured: f64,
    /// The same with the model's force.
    pub energy_model: f64,
    /// Largest positive force, measured and model.
    pub peak_positive: (f64, f64),
    /// Largest negative force (as a negative number), measured and model.
    pub peak_negative: (f64, f64),
    /// Largest |input| (displacement amplitude for quasi-static records).
    pub amplitude: f64,
}

/// A place where the model fails.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Place {
    /// Share of the total squared error that lies here (0-1).
    pub share: f64,
    /// Share of the samples that lie here.
    pub sample_share: f64,
    /// The branch class.
    pub branch: String,
    /// Within the near-zero-force band (20% of the cycle's peak force).
    pub near_zero_force: bool,
    /// First and last cycle (1-based).
    pub cycles: (usize, usize),
    /// Model secant stiffness over measured along the branch runs here.
    pub stiffness_ratio: Option<f64>,
    /// The place in words.
    pub words: String,
}

/// A model lined up with its record.
#[derive(Clone, Debug)]
pub struct Diagnosis {
    /// Measured displacement.
    pub displacement: Vec<f64>,
    /// Measured force.
    pub force: Vec<f64>,
    /// The model's prediction.
    pub prediction: Prediction,
    /// Residual of the output, model minus measured.
    pub residual: Vec<f64>,
    /// The record's cycles and branch classes.
    pub segmentation: Segmentation,
    /// Per-cycle comparison.
    pub cycles: Vec<CycleStats>,
    /// Places where the model fails, largest share first.
    pub places: Vec<Place>,
    /// Total squared residual.
    pub total_sq: f64,
    /// Relative error of the total energy input `∫ F du` at the end.
    pub energy_error: f64,
}

impl Diagnosis {
    /// Lines up the fit `outcome` of `problem` with its record.
    pub fn new(problem: &Problem, outcome: &Outcome) -> Result<Self> {
        let prediction = problem
            .predict(&outcome.x)
            .ok_or_else(|| anyhow!("the fitted model cannot be simulated on its record"))?;
        let exp = &problem.exp;
        let (u, f) = (exp.displacement().to_vec(), exp.force().to_vec());
        let residual: Vec<f64> = prediction
            .output
            .iter()
            .zip(&exp.output)
            .map(|(m, y)| m - y)
            .collect();
        let segmentation = Segmentation::new(&u, &f, &exp.input, &SegmentOptions::default())
            .map_err(|e| anyhow!("cannot cut the record into cycles: {e}"))?;
        let model_force = match exp.drive {
            Drive::Displacement => prediction.force.clone(),
            Drive::Force { .. } => f.clone(),
        };
        let model_u = match exp.drive {
            Drive::Displacement => u.clone(),
            Drive::Force { .. } => prediction.displacement.clone(),
        };
        let cycles = cycle_stats(
            &segmentation,
            &u,
            &f,
            &model_u,
            &model_force,
            &residual,
            &exp.input,
        );
        let total_sq: f64 = residual.iter().map(|r| r * r).sum();
        let places = places(&segmentation, &u, &f, &model_force, &residual, total_sq);
        let e_meas = energy_input(&u, &f);
        let e_model = energy_input(&model_u, &model_force);
        let last = |e: &[f64]| e.last().copied().unwrap_or(0.0);
        let energy_error =
            (last(&e_model) - last(&e_meas)).abs() / last(&e_meas).abs().max(f64::MIN_POSITIVE);
        Ok(Diagnosis {
            displacement: u,
            force: f,
            prediction,
            residual,
            segmentation,
            cycles,
            places,
            total_sq,
            energy_error,
        })
    }

    /// The model's force at each sample (the predicted force for quasi-static
    /// records, the restoring force for dynamic ones).
    pub fn model_force(&self) -> &[f64] {
        &self.prediction.force
    }
}

fn cycle_stats(
    seg: &Segmentation,
    u: &[f64],
    f: &[f64],
    mu: &[f64],
    mf: &[f64],
    residual: &[f64],
    input: &[f64],
) -> Vec<CycleStats> {
    seg.cycles()
        .cycles()
        .iter()
        .map(|c| {
            let path: Vec<usize> = c.path().collect();
            let area = |uu: &[f64], ff: &[f64]| {
                path.windows(2)
                    .map(|w| 0.5 * (ff[w[0]] + ff[w[1]]) * (uu[w[1]] - uu[w[0]]))
                    .sum::<f64>()
            };
            let samples = c.samples();
            let n = samples.len().max(1) as f64;
            let rms = (samples
                .clone()
                .map(|i| residual[i] * residual[i])
                .sum::<f64>()
                / n)
                .sqrt();
            let max_of = |v: &[f64]| {
                samples
                    .clone()
                    .map(|i| v[i])
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            let min_of = |v: &[f64]| samples.clone().map(|i| v[i]).fold(f64::INFINITY, f64::min);
            CycleStats {
                cycle: c.index + 1,
                complete: c.complete,
                rms_error: rms,
                energy_measured: area(u, f),
                energy_model: area(mu, mf),
                peak_positive: (max_of(f), max_of(mf)),
                peak_negative: (min_of(f), min_of(mf)),
                amplitude: samples.clone().map(|i| input[i].abs()).fold(0.0, f64::max),
            }
        })
        .collect()
}

/// Sum of |ΔF| of the model over the measured, over the contiguous runs of
/// `in_place` samples: the ratio of secant stiffnesses along those branches
/// (both forces at the same measured displacements).
pub(crate) fn stiffness_ratio(in_place: &[bool], f: &[f64], mf: &[f64]) -> Option<f64> {
    let (mut dm, mut dp) = (0.0, 0.0);
    let mut i = 0;
    while i < in_place.len() {
        if !in_place[i] {
            i += 1;
            continue;
        }
        let start = i;
        while i + 1 < in_place.len() && in_place[i + 1] {
            i += 1;
        }
        if i > start + 1 {
            dm += (f[i] - f[start]).abs();
            dp += (mf[i] - mf[start]).abs();
        }
        i += 1;
    }
    (dm > 0.0).then(|| dp / dm)
}

fn places(
    seg: &Segmentation,
    _u: &[f64],
    f: &[f64],
    mf: &[f64],
    residual: &[f64],
    total_sq: f64,
) -> Vec<Place> {
    let labels = seg.labels();
    let n_cycles = seg.cycles().cycles().len();
    let mut out = vec![];
    for branch in Branch::ALL {
        for near in [true, false] {
            let member = |i: usize| labels[i].branch == branch && labels[i].near_zero_force == near;
            let mut per_cycle = vec![0.0; n_cycles.max(1)];
            let mut count = 0usize;
            for (i, r) in residual.iter().enumerate() {
                if member(i) {
                    per_cycle[labels[i].cycle.min(n_cycles.saturating_sub(1))] += r * r;
                    count += 1;
                }
            }
            let group: f64 = per_cycle.iter().sum();
            if total_sq <= 0.0 || group <= 0.0 {
                continue;
            }
            // The shortest run of cycles holding 70% of this group's error.
            let (a, b) = shortest_window(&per_cycle, 0.7 * group);
            let window_sq: f64 = per_cycle[a..=b].iter().sum();
            let in_place: Vec<bool> = (0..residual.len())
                .map(|i| member(i) && (a..=b).contains(&labels[i].cycle))
                .collect();
            let ratio = stiffness_ratio(&in_place, f, mf);
            let zone = if near {
                "within 20% of zero force"
            } else {
                "away from zero force"
            };
            let share = window_sq / total_sq;
            let cycles = if a == b {
                format!("cycle {}", a + 1)
            } else {
                format!("cycles {}-{}", a + 1, b + 1)
            };
            let mut words = format!(
                "{:.0}% of the error lies on {} branches {}, {}",
                100.0 * share,
                branch,
                zone,
                cycles
            );
            if let Some(r) = ratio.filter(|r| !(0.87..=1.15).contains(r)) {
                words.push_str(&format!(
                    "; the model's {branch} stiffness there is {r:.1}x the measured"
                ));
            }
            out.push(Place {
                share,
                sample_share: count as f64 / residual.len().max(1) as f64,
                branch: branch.name().to_string(),
                near_zero_force: near,
                cycles: (a + 1, b + 1),
                stiffness_ratio: ratio,
                words,
            });
        }
    }
    out.sort_by(|x, y| y.share.total_cmp(&x.share));
    out
}

/// The shortest contiguous window of `v` whose sum reaches `target`
/// (earliest among equals).
fn shortest_window(v: &[f64], target: f64) -> (usize, usize) {
    let mut best = (0, v.len().saturating_sub(1));
    for a in 0..v.len() {
        let mut s = 0.0;
        for (b, x) in v.iter().enumerate().skip(a) {
            s += x;
            if s >= target {
                if b - a < best.1 - best.0 {
                    best = (a, b);
                }
                break;
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shortest_window_holds_the_target() {
        assert_eq!(shortest_window(&[1.0, 0.0, 5.0, 4.0, 0.5], 8.0), (2, 3));
        assert_eq!(shortest_window(&[3.0], 2.0), (0, 0));
        assert_eq!(shortest_window(&[1.0, 1.0, 1.0], 2.5), (0, 2));
    }

    #[test]
    fn stiffness_ratio_compares_force_changes_along_runs() {
        let place = [false, true, true, true, false, true, true, true];
        let f = [0.0, 0.0, 1.0, 2.0, 9.0, 0.0, -1.0, -2.0];
        let model = [0.0, 0.0, 3.0, 6.0, 9.0, 0.0, -3.0, -6.0];
        assert_eq!(stiffness_ratio(&place, &f, &model), Some(3.0));
    }
}
