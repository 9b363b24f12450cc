//! The lane-batched oscillator as a least-squares residual function, for screening the starts of
//! a multi-start fit ([`Method::Auto`](crate::fit::run::Method::Auto)) before the core refines
//! the best of them.
//!
//! A bounded Levenberg-Marquardt fit asks for residuals at one trial point at a time and for a
//! Jacobian at each accepted point. Here a Jacobian is one batch of lanes: the point and a step of
//! [`STEP`] of each variable's range to either side of it (central differences; a variable whose
//! step would leave its bounds is differenced to one side), so that a plain Bouc-Wen model with
//! its six free parameters takes 13 of the [`LANES`]. The residuals are those of
//! [`Problem::residuals`] with the fixed-step model in place of the core's error-controlled one;
//! its error is that of the [`SearchModel`] (checked against the core for NRMSE, not for
//! parameters), so the minimum found here is near the core's, not on it, and the result of a
//! screening is always refined and scored with the core.

use super::{SearchModel, LANES};
use crate::fit::lsq::Residuals;
use crate::fit::problem::Problem;
use nalgebra::DMatrix;

/// The difference step, a fraction of each variable's bound range: small enough for the
/// truncation error of central differences (at 1e-2 up to 18% of a column on the thesis'
/// example), large enough for the lanes' `f32` rounding. From 3e-4 to 1e-3 the columns are
/// within 3.3e-2 of the core's exact ones, the fixed-step model's own error (test below).
pub const STEP: f64 = 1e-3;

/// The fixed-step model's residuals on a problem.
pub struct LaneResiduals<'a> {
    problem: &'a Problem,
    model: &'a SearchModel,
}

impl<'a> LaneResiduals<'a> {
    /// The residuals of `problem` simulated by `model` (its search model).
    pub fn new(problem: &'a Problem, model: &'a SearchModel) -> Self {
        LaneResiduals { problem, model }
    }
}

impl Residuals for LaneResiduals<'_> {
    fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.model.residuals(self.problem, &[x]).pop().flatten()
    }

    fn residuals_jacobian(&self, x: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>)> {
        let (lo, hi) = self.problem.par.bounds();
        // Each column's two points and the distance between them, as lane indices (lane 0 is x).
        let mut points = vec![x.to_vec()];
        let mut columns = Vec::with_capacity(x.len());
        for j in 0..x.len() {
            let h = STEP * (hi[j] - lo[j]);
            let mut lane = |v: f64| {
                let mut p = x.to_vec();
                p[j] = v;
                points.push(p);
                points.len() - 1
            };
            columns.push(match (x[j] + h <= hi[j], x[j] - h >= lo[j]) {
                (true, true) => (lane(x[j] + h), lane(x[j] - h), 2.0 * h),
                (true, false) => (lane(x[j] + h), 0, h),
                (false, true) => (0, lane(x[j] - h), h),
                // A range narrower than two steps: no difference to take.
                (false, false) => (0, 0, 0.0),
            });
        }
        if points.len() > LANES {
            return None;
        }
        let refs: Vec<&[f64]> = points.iter().map(Vec::as_slice).collect();
        let runs = self.model.residuals(self.problem, &refs);
        let r0 = runs.first()?.clone()?;
        let mut jac = DMatrix::zeros(r0.len(), x.len());
        for (j, &(plus, minus, width)) in columns.iter().enumerate() {
            if width == 0.0 {
                continue;
            }
            let (Some(a), Some(b)) = (&runs[plus], &runs[minus]) else {
                // A neighbour that cannot be simulated: no slope along this variable, which
                // least squares then leaves where it is (as with differenced core runs).
                continue;
            };
            for (k, (a, b)) in a.iter().zip(b).enumerate() {
                jac[(k, j)] = (a - b) / width;
            }
        }
        Some((r0, jac))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::lanes::search::tests::{problem as thesis, TRUTH};
    use crate::fit::lanes::search::{MARGIN, SEARCH_TOLERANCE};
    use crate::fit::problem::LeastSquares;
    use crate::model::ModelSpec;
    use std::collections::BTreeMap;

    /// The thesis' example (sec. 4.4) at its 100 Hz: F = t sin(2 pi t) kN on 500 kg, k = 6 kN/mm
    /// (fixed), the displacement of the true oscillator.
    fn problem() -> Problem {
        thesis(ModelSpec::BW, 100.0)
    }

    fn at(p: &Problem, scale: f64) -> Vec<f64> {
        let values: BTreeMap<&str, f64> = TRUTH.iter().map(|(k, v)| (*k, v * scale)).collect();
        p.par.normalise(&values)
    }

    /// Against the exact Jacobian of the core (one simulation in dual numbers) at the truth and
    /// 20% off it, at the 8 steps a sample the search model chooses here: every column within
    /// 5e-2 of its largest entry (measured 1.3e-3 to 3.3e-2, the largest for `xi`; the same for
    /// steps of 3e-4 to 1e-3 of the range, so this is the fixed-step model's own error, not the
    /// differences'; at 1e-2 of the range the differences add up to 18%), and the residuals, in
    /// NRMSE, within the tolerance the search model was accepted with (measured 5.5e-6 and
    /// 4.0e-6).
    #[test]
    fn the_lane_jacobian_is_the_cores() {
        let p = problem();
        let model = SearchModel::for_problem(&p).unwrap();
        let lanes = LaneResiduals::new(&p, &model);
        let core = LeastSquares::new(&p);
        for scale in [1.0, 1.2] {
            let x = at(&p, scale);
            let (r_lane, j_lane) = lanes.residuals_jacobian(&x).unwrap();
            let (r_core, j_core) = core.residuals_jacobian(&x).unwrap();
            for j in 0..x.len() {
                let col = j_core.column(j);
                let peak = col.amax();
                let off = (j_lane.column(j) - col).amax();
                assert!(
                    off < 5e-2 * peak,
                    "column {j} at {scale}: {off:e} of {peak:e}"
                );
            }
            let diff: f64 = r_lane
                .iter()
                .zip(&r_core)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(diff < MARGIN * SEARCH_TOLERANCE, "{diff:e}");
        }
    }

    /// The single-point residuals are the Jacobian batch's lane 0: the lanes are independent.
    #[test]
    fn residuals_alone_are_those_of_the_batch() {
        let p = problem();
        let model = SearchModel::for_problem(&p).unwrap();
        let lanes = LaneResiduals::new(&p, &model);
        let x = at(&p, 0.9);
        let alone = lanes.residuals(&x).unwrap();
        let (batch, _) = lanes.residuals_jacobian(&x).unwrap();
        assert_eq!(alone, batch);
    }
}
