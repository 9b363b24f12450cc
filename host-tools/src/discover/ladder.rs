//! The discovery loop: fit, diagnose, add the strongest significant effect,
//! refit from the previous fit, repeat until nothing significant is left;
//! then take away any effect the final model no longer needs.
//!
//! The backward step: an effect is judged when it is added, against the
//! fit of the model before it. Where that fit had stalled short of its
//! minimum, the effect was credited with what a better fit of the same model
//! reaches without it (Saatcioglu and Baingo RC9, SPD 387: pinching fitted
//! to NRMSE 0.145 on its rung, strength degradation then added at delta-BIC
//! -11.4; refitted from the final model with strength degradation switched
//! off, pinching alone reaches 0.123, and strength degradation changes the
//! BIC by -1.4). So once nothing more is significant, each effect the ladder
//! added is switched off in turn and the model refitted from the final fit;
//! the one whose removal raises the BIC least is taken away when that rise
//! is below [`REMOVAL_BIC`], and the loop goes on from the smaller model,
//! that effect no longer a candidate.
//!
//! An effect enters at very strong evidence (a BIC change of 10) and leaves
//! only when what is left of it is not worth more than a bare mention (2,
//! on the same scale of Kass and Raftery), as stepwise regression enters a
//! term at a stricter level than it removes one. A removal threshold of 10
//! took effects away one at a time that were significant together: on
//! Watson and Park's No. 10 (SPD 294) pinching went at +1.8 and then strength
//! degradation at +9.6, back to `bw`, where the two together halve the
//! NRMSE (0.317 to 0.153). With 2, pinching still goes there (its removal is
//! weighed at the final model's sample size, 23 half-cycles, where its
//! addition was weighed at 36, that of a richer model's residual) and
//! strength degradation stays.

use super::diagnosis::Diagnosis;
use super::suspects::{self, bic, effective_n, Suspect, WeighOptions};
use crate::fit::problem::Problem;
use crate::fit::run::{self, Outcome};
use crate::model::{EffectRef, ModelSpec};
use anyhow::Result;
use rayon::prelude::*;
use serde::Serialize;

/// BIC rise below which the backward step takes an effect away: "not
/// worth more than a bare mention" (Kass and Raftery).
pub const REMOVAL_BIC: f64 = 2.0;

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
    /// The effect this rung took away from the previous one (the backward
    /// step), if it is not an addition.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub removed: Option<&'static str>,
}

impl Rung {
    /// The model, and what the backward step took away to reach it.
    pub fn label(&self) -> String {
        match self.removed {
            Some(e) => format!("{} (-{e})", self.model),
            None => self.model.clone(),
        }
    }
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

impl Step {
    /// A model fitted elsewhere as a step, diagnosed, with no candidate
    /// weighed (for [`redundant`] or [`crate::discover::slip::of_ladder`]).
    pub fn diagnosed(problem: Problem, outcome: Outcome) -> Result<Self> {
        let diagnosis = Diagnosis::new(&problem, &outcome)?;
        Ok(Step {
            spec: problem.par.spec,
            problem,
            outcome,
            diagnosis,
            suspects: vec![],
        })
    }
}

/// The result of a discovery run.
pub struct Discovery {
    /// The ladder, first model first.
    pub rungs: Vec<Rung>,
    /// Every step, the last one being the final model.
    pub steps: Vec<Step>,
    /// Effects of the first model that the final one does not need: the
    /// backward step keeps the effects the loop starts from, and says so.
    pub unneeded: Vec<Unneeded>,
}

impl Discovery {
    /// The final step.
    pub fn last(&self) -> &Step {
        self.steps
            .last()
            .expect("a discovery has at least one step")
    }
}

/// An effect taken out of a model, and the model refitted without it.
pub struct Removal {
    /// The effect.
    pub effect: EffectRef,
    /// BIC change of removing it: below [`REMOVAL_BIC`], the model does not
    /// need it.
    pub delta_bic: f64,
    /// The model without it, refitted.
    pub problem: Problem,
    /// Its fit.
    pub outcome: Outcome,
}

/// Each effect of `effects` taken out of the model of `problem`, fitted as
/// `outcome` and lined up with its record as `diagnosis`, with the BIC change
/// of its removal. Each removal is refitted from `outcome` with the effect
/// switched off, and the better of that and an `earlier` fit of the same
/// model counts. The effective sample size is that of the model's residual,
/// with the half-cycles as floor (as in [`suspects::weigh`]).
pub fn removals(
    problem: &Problem,
    outcome: &Outcome,
    diagnosis: &Diagnosis,
    effects: &[EffectRef],
    earlier: &[Step],
) -> Vec<Removal> {
    let spec = problem.par.spec;
    let Some(residual) = suspects::residual(problem, &outcome.x) else {
        return vec![];
    };
    let floor = diagnosis.segmentation.cycles().half_cycles().len();
    let n_eff = effective_n(&residual, problem.dim(), floor);
    let full = bic(outcome.scores.nrmse.powi(2), problem.dim(), n_eff);
    effects
        .par_iter()
        .filter(|e| spec.contains(**e))
        .filter_map(|&e| {
            let smaller = spec.without(e);
            let fixed: Vec<(String, f64)> = problem
                .par
                .fixed
                .iter()
                .filter(|(k, _)| !e.owns(k))
                .map(|(k, v)| (k.to_string(), *v))
                .collect();
            let p = Problem::new(smaller, problem.exp.clone(), &fixed).ok()?;
            let refit = run::refit_from(&p, outcome, "from the model with one more effect").ok();
            let before = earlier
                .iter()
                .filter(|s| s.spec == smaller)
                .map(|s| s.outcome.clone());
            let outcome = refit
                .into_iter()
                .chain(before)
                .min_by(|a, b| a.scores.nrmse.total_cmp(&b.scores.nrmse))?;
            let delta = bic(outcome.scores.nrmse.powi(2), p.dim(), n_eff) - full;
            Some(Removal {
                effect: e,
                delta_bic: delta,
                problem: p,
                outcome,
            })
        })
        .collect()
}

/// An effect of a model that its record does not need: taken out and the
/// model refitted, the BIC rises by less than [`REMOVAL_BIC`].
#[derive(Clone, Debug, Serialize)]
pub struct Unneeded {
    /// The effect.
    pub effect: &'static str,
    /// BIC change of removing it.
    pub delta_bic: f64,
    /// NRMSE of the model with it.
    pub nrmse_with: f64,
    /// NRMSE of the model refitted without it.
    pub nrmse_without: f64,
}

impl Unneeded {
    /// One sentence.
    pub fn words(&self) -> String {
        let verdict = if self.delta_bic <= 0.0 {
            "the model is better without it".to_string()
        } else {
            format!("below {REMOVAL_BIC}, not worth more than a bare mention")
        };
        format!(
            "{}: the model refitted without it reaches NRMSE {:.4} ({:.4} with it), a BIC change \
             of {:+.1}: {verdict}, so the record does not need it",
            self.effect, self.nrmse_without, self.nrmse_with, self.delta_bic
        )
    }
}

/// The effects of `effects` that the model of `problem`, fitted as
/// `outcome`, does not need (the [`removals`] below [`REMOVAL_BIC`]), the
/// least needed first: what a diagnosis says of the effects a user gave.
pub fn unneeded(
    problem: &Problem,
    outcome: &Outcome,
    diagnosis: &Diagnosis,
    effects: &[EffectRef],
    earlier: &[Step],
) -> Vec<Unneeded> {
    let mut found: Vec<Unneeded> = removals(problem, outcome, diagnosis, effects, earlier)
        .into_iter()
        .filter(|r| r.delta_bic < REMOVAL_BIC)
        .map(|r| Unneeded {
            effect: r.effect.name(),
            delta_bic: r.delta_bic,
            nrmse_with: outcome.scores.nrmse,
            nrmse_without: r.outcome.scores.nrmse,
        })
        .collect();
    found.sort_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic));
    found
}

/// The effect of `step`'s model, other than those in `keep`, whose removal
/// raises the BIC least, when that rise is below [`REMOVAL_BIC`] (the
/// removals of [`removals`]; `earlier` steps' fits count as theirs do).
pub fn redundant(step: &Step, keep: &[EffectRef], earlier: &[Step]) -> Option<Removal> {
    let candidates: Vec<EffectRef> = step
        .spec
        .effects()
        .into_iter()
        .filter(|e| !keep.contains(e))
        .collect();
    removals(
        &step.problem,
        &step.outcome,
        &step.diagnosis,
        &candidates,
        earlier,
    )
    .into_iter()
    .filter(|r| r.delta_bic < REMOVAL_BIC)
    .min_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic))
}

/// Runs the loop from the fit `outcome` of `problem`; `on_step` is told
/// about each diagnosed model (for live progress).
pub fn discover(
    problem: Problem,
    outcome: Outcome,
    options: &WeighOptions,
    mut on_step: impl FnMut(&Step),
) -> Result<Discovery> {
    let first = problem.par.spec.effects();
    let mut rungs = vec![];
    let mut steps: Vec<Step> = vec![];
    let mut taken_away: Vec<EffectRef> = vec![];
    let (mut problem, mut outcome) = (problem, outcome);
    let mut delta = None;
    let mut removed = None;
    loop {
        let diagnosis = Diagnosis::new(&problem, &outcome)?;
        // An effect taken away is not offered again.
        let options = WeighOptions {
            candidates: Some(
                options
                    .candidates
                    .clone()
                    .unwrap_or_else(|| suspects::default_candidates(problem.par.spec))
                    .into_iter()
                    .filter(|e| !taken_away.contains(e) && !problem.par.spec.contains(*e))
                    .collect(),
            ),
            ..options.clone()
        };
        let suspects = suspects::weigh(&problem, &outcome, &diagnosis, &options);
        rungs.push(Rung {
            model: problem.par.spec.to_string(),
            params: problem.dim(),
            nrmse: outcome.scores.nrmse,
            energy_error: diagnosis.energy_error,
            delta_bic: delta,
            removed: removed.take(),
        });
        // The rung's BIC change is that of adding the effect to this model. The suspect's own
        // `delta_bic` can be another comparison (the cost of removing it from the best model
        // found, when that holds two effects): the ladder showed -3987 for a step whose change
        // was -1368 (found by review).
        let next = suspects
            .iter()
            .find(|s| s.significant)
            .and_then(|s| Some((s.bic_of_adding(), s.refit.clone()?)));
        let step = Step {
            spec: problem.par.spec,
            problem,
            outcome,
            diagnosis,
            suspects,
        };
        on_step(&step);
        steps.push(step);
        if let Some((d, (p, o))) = next {
            delta = Some(d);
            problem = p;
            outcome = o;
            continue;
        }
        let (last, earlier) = steps.split_last().expect("a step was just pushed");
        match redundant(last, &first, earlier) {
            Some(r) => {
                taken_away.push(r.effect);
                delta = Some(r.delta_bic);
                removed = Some(r.effect.name());
                problem = r.problem;
                outcome = r.outcome;
            }
            None => break,
        }
    }
    let (last, earlier) = steps.split_last().expect("the loop pushes a step");
    let unneeded = unneeded(
        &last.problem,
        &last.outcome,
        &last.diagnosis,
        &first,
        earlier,
    );
    Ok(Discovery {
        rungs,
        steps,
        unneeded,
    })
}
