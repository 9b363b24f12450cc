//! The discovery loop: fit, diagnose, add the strongest significant effect,
//! refit from the previous fit, repeat until nothing significant is left.

use super::diagnosis::Diagnosis;
use super::suspects::{self, Suspect, WeighOptions};
use crate::fit::problem::Problem;
use crate::fit::run::Outcome;
use crate::model::ModelSpec;
use anyhow::Result;
use serde::Serialize;

/// One model of the ladder.
#[derive(Clone, Debug, Serialize)]
pub struct Rung {
    /// The model.
    pub model: String,
    /// Fitted parameters.
    pub params: usize,
    /// Relative RMS error.
    pub nrmse: f64,
    /// Relative error of the total energy `∫ F du`.
    pub energy_error: f64,
    /// BIC change from the previous rung (None for the first).
    pub delta_bic: Option<f64>,
}

/// What one step of the loop found.
pub struct Step {
    /// The model.
    pub spec: ModelSpec,
    /// Its fitting problem and fit.
    pub problem: Problem,
    /// Its fit.
    pub outcome: Outcome,
    /// The comparison with the record.
    pub diagnosis: Diagnosis,
    /// The candidates, most likely first.
    pub suspects: Vec<Suspect>,
}

/// The result of a discovery run.
pub struct Discovery {
    /// The ladder, first model first.
    pub rungs: Vec<Rung>,
    /// Every step, the last one being the final model.
    pub steps: Vec<Step>,
}

impl Discovery {
    /// The final step.
    pub fn last(&self) -> &Step {
        self.steps
            .last()
            .expect("a discovery has at least one step")
    }
}

/// Runs the loop from the fit `outcome` of `problem`; `on_step` is told
/// about each diagnosed model (for live progress).
pub fn discover(
    problem: Problem,
    outcome: Outcome,
    options: &WeighOptions,
    mut on_step: impl FnMut(&Step),
) -> Result<Discovery> {
    let mut rungs = vec![];
    let mut steps: Vec<Step> = vec![];
    let (mut problem, mut outcome) = (problem, outcome);
    let mut delta = None;
    loop {
        let diagnosis = Diagnosis::new(&problem, &outcome)?;
        let suspects = suspects::weigh(&problem, &outcome, &diagnosis, options);
        rungs.push(Rung {
            model: problem.par.spec.to_string(),
            params: problem.dim(),
            nrmse: outcome.scores.nrmse,
            energy_error: diagnosis.energy_error,
            delta_bic: delta,
        });
        let next = suspects
            .iter()
            .find(|s| s.significant)
            .and_then(|s| Some((s.delta_bic, s.refit.clone()?)));
        let step = Step {
            spec: problem.par.spec,
            problem,
            outcome,
            diagnosis,
            suspects,
        };
        on_step(&step);
        steps.push(step);
        match next {
            Some((d, (p, o))) => {
                delta = Some(d);
                problem = p;
                outcome = o;
            }
            None => break,
        }
    }
    Ok(Discovery { rungs, steps })
}
