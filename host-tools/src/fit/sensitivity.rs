//! One-at-a-time sensitivity analysis (thesis section 3.5.3): each parameter
//! is varied from -50% to +50% of its value with the others held, the output
//! `Y'` is compared with the output `Y` at the nominal set by
//! `e = sqrt(sum (Y - Y')^2)` (eq. 3.24), and parameters are ranked by the
//! largest `|e|` over the sweep (eq. 3.25, Table 3.5).

use super::problem::Problem;
use rayon::prelude::*;
use serde::Serialize;

/// The sweep of one parameter.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Parameter name.
    pub name: String,
    /// Nominal physical value.
    pub nominal: f64,
    /// Relative changes (-0.5 ... 0.5).
    pub changes: Vec<f64>,
    /// `e` of eq. 3.24 at each change (NaN where the model could not be
    /// simulated, e.g. the change made the set invalid).
    pub errors: Vec<f64>,
    /// `max |e|` (eq. 3.25) over the finite ones.
    pub max_error: f64,
    /// Rank by `max_error`, 1 = most sensitive.
    pub rank: usize,
}

/// Sweeps every free parameter of `problem` around the normalised point `x`
/// over `levels` equally spaced changes from -50% to +50%. A parameter whose
/// value is zero is swept over +-50% of its fitting range instead (a relative
/// change of zero is no change).
pub fn analyse(problem: &Problem, x: &[f64], levels: usize) -> Vec<Sweep> {
    let nominal = problem.predict(x).map(|p| p.output).unwrap_or_default();
    let changes: Vec<f64> = (0..levels)
        .map(|i| -0.5 + i as f64 / (levels - 1).max(1) as f64)
        .collect();
    let phys = problem.par.physical(x);
    let mut sweeps: Vec<Sweep> = (0..problem.dim())
        .into_par_iter()
        .map(|j| {
            let free = &problem.par.free[j];
            let errors = changes
                .iter()
                .map(|c| {
                    let mut xv = x.to_vec();
                    xv[j] = if x[j] != 0.0 {
                        x[j] * (1.0 + c)
                    } else {
                        c * (free.hi - free.lo)
                    };
                    match problem.predict(&xv) {
                        Some(p) => nominal
                            .iter()
                            .zip(&p.output)
                            .map(|(a, b)| (a - b).powi(2))
                            .sum::<f64>()
                            .sqrt(),
                        None => f64::NAN,
                    }
                })
                .collect::<Vec<f64>>();
            let max_error = errors
                .iter()
                .filter(|e| e.is_finite())
                .fold(0.0, |a: f64, b| a.max(*b));
            Sweep {
                name: free.spec.name.to_string(),
                nominal: phys[free.spec.name],
                changes: changes.clone(),
                errors,
                max_error,
                rank: 0,
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..sweeps.len()).collect();
    order.sort_by(|&a, &b| sweeps[b].max_error.total_cmp(&sweeps[a].max_error));
    for (r, i) in order.into_iter().enumerate() {
        sweeps[i].rank = r + 1;
    }
    sweeps
}
