//! One-at-a-time sensitivity analysis (thesis section 3.5.3): each parameter
//! is varied from -50% to +50% of its value with the others held, the output
//! `Y'` is compared with the output `Y` at the nominal set by
//! `e = sqrt(sum (Y - Y')^2)` (eq. 3.24), and parameters are ranked by the
//! largest `|e|` over the sweep (eq. 3.25, Table 3.5).

use super::problem::Problem;
use anyhow::{bail, Result};
use rayon::prelude::*;
use serde::Serialize;

/// The sweep of one parameter.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Parameter name.
    pub name: String,
    /// Nominal physical value.
    pub nominal: f64,
    /// Relative changes (-0.5 ... 0.5): of the value, or of the fitting
    /// range where the value is zero (`of_range`).
    pub changes: Vec<f64>,
    /// Whether the value is zero and the changes are fractions of the
    /// parameter's fitting range instead.
    pub of_range: bool,
    /// `e` of eq. 3.24 at each change (NaN, `null` in JSON, where the model
    /// could not be simulated, e.g. the change made the set invalid).
    pub errors: Vec<f64>,
    /// How many changes could not be simulated.
    pub not_simulated: usize,
    /// `max |e|` (eq. 3.25) over the simulated changes; NaN if none was.
    pub max_error: f64,
    /// Rank by `max_error`, 1 = most sensitive; sweeps with no simulated
    /// change rank last.
    pub rank: usize,
}

/// The most levels a sweep takes: steps of 0.1% from -50% to +50%. Each
/// level is one simulation a parameter (17,017 for the 17 of `bwbn`), and
/// the levels are allocated before the first (2^61 of them overflowed).
pub const MAX_LEVELS: usize = 1001;

/// Sweeps every free parameter of `problem` around the normalised point `x`,
/// whose predicted output is `nominal` (`Problem::try_predict`), over
/// `levels` (3 to [`MAX_LEVELS`]) equally spaced changes from -50% to +50%. A
/// parameter whose value is zero is swept over +-50% of its fitting range
/// instead (a relative change of zero is no change).
pub fn analyse(problem: &Problem, x: &[f64], nominal: &[f64], levels: usize) -> Result<Vec<Sweep>> {
    if levels < 3 {
        bail!("the sweep needs at least 3 levels (-50%, 0, +50%), got {levels}");
    }
    if levels > MAX_LEVELS {
        bail!("the sweep takes at most {MAX_LEVELS} levels (steps of 0.1%), got {levels}");
    }
    let changes: Vec<f64> = (0..levels)
        .map(|i| -0.5 + i as f64 / (levels - 1) as f64)
        .collect();
    let phys = problem.par.physical(x);
    let mut sweeps: Vec<Sweep> = (0..problem.dim())
        .into_par_iter()
        .map(|j| {
            let free = &problem.par.free[j];
            let of_range = x[j] == 0.0;
            let errors = changes
                .iter()
                .map(|c| {
                    let mut xv = x.to_vec();
                    xv[j] = if of_range {
                        c * (free.hi - free.lo)
                    } else {
                        x[j] * (1.0 + c)
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
            let simulated = errors.iter().filter(|e| e.is_finite());
            let not_simulated = levels - simulated.clone().count();
            let max_error = simulated.fold(f64::NAN, |a: f64, b| a.max(*b));
            Sweep {
                name: free.spec.name.to_string(),
                nominal: phys[free.spec.name],
                changes: changes.clone(),
                of_range,
                errors,
                not_simulated,
                max_error,
                rank: 0,
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..sweeps.len()).collect();
    // Descending, NaN (nothing simulated) last.
    let key = |s: &Sweep| {
        if s.max_error.is_nan() {
            f64::NEG_INFINITY
        } else {
            s.max_error
        }
    };
    order.sort_by(|&a, &b| key(&sweeps[b]).total_cmp(&key(&sweeps[a])));
    for (r, i) in order.into_iter().enumerate() {
        sweeps[i].rank = r + 1;
    }
    Ok(sweeps)
}
