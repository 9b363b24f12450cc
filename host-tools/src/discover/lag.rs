//! A lag between the channels: the force and the displacement read at
//! different instants (two acquisition systems not in step, a filter on one
//! channel), which no effect of the library models, looked for so that the
//! diagnosis can name it instead of pinning the misfit on an effect (found by
//! review: a force channel one sample late, at 100 samples a cycle, was added
//! to `bw` as stiffness degradation at a BIC change of -37 and flagged as rate
//! dependence; three samples late, as pinching).
//!
//! A force read `s` samples late pairs each displacement with the force of `s`
//! samples before: the loop's branches move along the displacement in the
//! direction of travel, most where the force changes fastest (the elastic
//! unloading and reloading branches), and the loop looks thinner there. A
//! fit absorbs part of it into its parameters, so the residual alone
//! underestimates it (one sample late: the residual's regression on the
//! model force's rate of change reads 0.12 samples).
//!
//! The check refits the model, from its fitted parameters, to the record
//! realigned by one sample each way, and walks on in the better direction
//! while the fit improves, up to [`MAX_LAG`] samples; each realignment drops
//! the `|s|` samples that lose their partner. Its gain is weighed on the
//! samples both fits share, like an offset (see [`offset`](super::offset):
//! one added number, significant below a BIC change of -10, and at least
//! [`MIN_SHARE`](super::offset::MIN_SHARE) of the squared error), and it is
//! named only where the realigned model fits at least as well as the best
//! candidate effect refitted on the same model: an effect that a lag
//! resembles must then explain the record no better than one number that is
//! not a parameter of the model.
//!
//! Measured on the review's records (100 samples a cycle, 1% force noise;
//! `bw` refitted to each record realigned, scratch): a force 1, 2 or 3
//! samples late took `bw` from NRMSE 0.034, 0.055, 0.074 back to 0.016-0.017
//! at the right lag (0.017 without a lag); on 20 records without a lag
//! (nothing, strength or stiffness degradation, pinching, asymmetry hidden,
//! coloured noise, 20 to 400 samples a cycle) every realignment fitted worse
//! but one (stiffness degradation with holds at the peaks: 4% of the squared
//! error, and one with noise in the displacement at 400 samples a cycle:
//! 15%, where stiffness degradation refitted does better).

use super::diagnosis::Diagnosis;
use super::ladder::{Discovery, Step};
use super::offset::{refit_residual, scale_of, Gain};
use super::suspects::Suspect;
use crate::fit::experiment::Drive;
use crate::fit::objectives::{Target, ENVELOPE_FLOOR};
use crate::fit::problem::Problem;
use crate::fit::run::Outcome;
use serde::Serialize;

/// Largest lag (samples) the check tries each way.
pub const MAX_LAG: usize = 8;

/// What the record says about a lag between its channels.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct LagCheck {
    /// The model whose fit was checked.
    pub model: String,
    /// Named: see the module docs for the rule.
    pub significant: bool,
    /// Samples the force reads behind the displacement (negative: ahead of
    /// it), the realignment that fitted best.
    pub samples: i64,
    /// Share of the squared error the realignment removes, on the samples
    /// both fits share.
    pub share: f64,
    /// NRMSE of the realigned refit.
    pub nrmse_with: f64,
    /// BIC change of the realignment (one added number).
    pub delta_bic: f64,
    /// Effective sample size used (as for the offsets).
    pub n_eff: f64,
    /// The candidate effect that, refitted on the same model, fitted best,
    /// and its NRMSE, where any was weighed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub best_effect: Option<(String, f64)>,
    /// The evidence in words.
    pub evidence: String,
}

/// `problem` with its force paired with the displacement `lag` samples
/// before it (a force read `lag` samples late; negative: early), the
/// unpaired samples dropped; `None` if too few samples would be left.
fn realigned(problem: &Problem, lag: i64) -> Option<Problem> {
    let n = problem.exp.len();
    let s = usize::try_from(lag.unsigned_abs()).ok()?;
    if s == 0 || n < s + problem.dim() + 2 {
        return None;
    }
    let mut p = problem.clone();
    if lag > 0 {
        p.exp.input.truncate(n - s);
        p.exp.output.drain(..s);
    } else {
        p.exp.input.drain(..s);
        p.exp.output.truncate(n - s);
    }
    p.target = Target::new(&p.exp, ENVELOPE_FLOOR);
    Some(p)
}

/// One realignment refitted: the residual of the fit as it was on the force
/// samples the realigned record keeps, and the refit's.
struct Trial {
    lag: i64,
    before: Vec<f64>,
    after: Vec<f64>,
}

impl Trial {
    /// The refit of `outcome` (a fit of `problem`, diagnosed as `d`) to the
    /// record realigned by `lag`, from the fitted parameters.
    fn run(problem: &Problem, outcome: &Outcome, d: &Diagnosis, lag: i64) -> Option<Trial> {
        let after = refit_residual(&realigned(problem, lag)?, &outcome.x)?;
        let (n, s) = (d.residual.len(), after.len());
        let before = if lag > 0 {
            d.residual[n - s..].to_vec()
        } else {
            d.residual[..s].to_vec()
        };
        Some(Trial { lag, before, after })
    }

    /// The refit's squared error over the fit's on the same samples.
    fn ratio(&self) -> f64 {
        let sq = |r: &[f64]| r.iter().map(|r| r * r).sum::<f64>();
        let r = sq(&self.after) / sq(&self.before);
        if r.is_nan() {
            f64::INFINITY
        } else {
            r
        }
    }
}

/// The realignment that fits best: one sample each way, then on in the
/// better direction while the fit improves, up to [`MAX_LAG`].
fn search(problem: &Problem, outcome: &Outcome, d: &Diagnosis) -> Option<Trial> {
    let better = |a: Trial, b: Trial| if b.ratio() < a.ratio() { b } else { a };
    let mut best = match (
        Trial::run(problem, outcome, d, 1),
        Trial::run(problem, outcome, d, -1),
    ) {
        (Some(a), Some(b)) => better(a, b),
        (a, b) => a.or(b)?,
    };
    let step = best.lag.signum();
    while best.ratio() < 1.0 && best.lag.unsigned_abs() < MAX_LAG as u64 {
        match Trial::run(problem, outcome, d, best.lag + step) {
            Some(t) if t.ratio() < best.ratio() => best = t,
            _ => break,
        }
    }
    Some(best)
}

/// The candidate effect that fitted best, refitted on the model the suspects
/// were weighed on.
fn best_effect(suspects: &[Suspect]) -> Option<(String, f64)> {
    suspects
        .iter()
        .filter(|s| s.nrmse_with.is_finite())
        .min_by(|a, b| a.nrmse_with.total_cmp(&b.nrmse_with))
        .map(|s| (s.effect.name().to_string(), s.nrmse_with))
}

/// Weighs the realignment `trial` of the fit of `model` (NRMSE `nrmse`,
/// diagnosed as `d`, its candidates weighed as `suspects`).
fn weigh(
    model: &str,
    d: &Diagnosis,
    nrmse: f64,
    suspects: &[Suspect],
    trial: &Trial,
) -> Option<LagCheck> {
    let gain = Gain::of(d, nrmse, &trial.before, &trial.after, 1, scale_of(suspects))?;
    let best_effect = best_effect(suspects);
    let at_least_as_good = best_effect
        .as_ref()
        .is_none_or(|(_, e)| gain.nrmse_with <= *e);
    let significant = gain.significant() && at_least_as_good;
    let lag = trial.lag;
    let (late, before, k) = if lag > 0 {
        ("late", "before", lag)
    } else {
        ("early", "after", -lag)
    };
    let samples = if k == 1 { "sample" } else { "samples" };
    let mut evidence = format!(
        "With the force read {k} {samples} {late} (each force sample paired with the \
         displacement {k} {before} it, {k} dropped at each end) and the model refitted, the fit \
         takes {} on the samples both share.",
        gain.words(nrmse)
    );
    evidence.push(' ');
    evidence.push_str(&if significant {
        let effect = match &best_effect {
            Some((name, e)) => format!(
                "The best effect refitted instead, {name}, reaches {e:.4}: no better than this \
                 one number, which is not a parameter of the model. "
            ),
            None => String::new(),
        };
        format!(
            "{effect}Channels out of step make a loop's steep branches lean along the \
             displacement, which effects can stand in for: check how the two channels were \
             sampled, and run again with `--lag force={lag}` to realign them."
        )
    } else if gain.share < 0.0 {
        "Not significant: realigned by a sample either way, the model fits worse, so the \
         channels are in step to within a sample."
            .into()
    } else if !gain.significant() {
        gain.not_significant()
    } else {
        let (name, e) = best_effect.clone().unwrap_or_default();
        format!("Not named: {name}, refitted instead, reaches {e:.4}, better than a lag does.")
    });
    Some(LagCheck {
        model: model.to_string(),
        significant,
        samples: lag,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        best_effect,
        evidence,
    })
}

/// The check on one diagnosed fit (`hyst diagnose`): displacement-driven
/// records only.
pub fn of_fit(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
) -> Option<LagCheck> {
    if problem.exp.drive != Drive::Displacement {
        return None;
    }
    let trial = search(problem, outcome, d)?;
    weigh(
        &problem.par.spec.to_string(),
        d,
        outcome.scores.nrmse,
        suspects,
        &trial,
    )
}

/// The check along a discovery: searched on the first model, before any
/// effect could stand in for a lag, and the lag found there refitted on the
/// final model too, whose effects it must beat as well; the named check is
/// kept over one not named, else the stronger evidence.
pub fn of_ladder(discovery: &Discovery) -> Option<LagCheck> {
    let first = &discovery.steps[0];
    let on_first = of_fit(
        &first.problem,
        &first.outcome,
        &first.diagnosis,
        &first.suspects,
    )?;
    let last = discovery.last();
    if discovery.steps.len() == 1 || on_first.share <= 0.0 {
        return Some(on_first);
    }
    let stronger =
        |a: &LagCheck, b: &LagCheck| (!a.significant, a.delta_bic) < (!b.significant, b.delta_bic);
    Some(match on_step(last, on_first.samples) {
        Some(l) if stronger(&l, &on_first) => l,
        _ => on_first,
    })
}

/// The realignment by `lag` weighed on the discovery step `step`.
fn on_step(step: &Step, lag: i64) -> Option<LagCheck> {
    let trial = Trial::run(&step.problem, &step.outcome, &step.diagnosis, lag)?;
    weigh(
        &step.spec.to_string(),
        &step.diagnosis,
        step.outcome.scores.nrmse,
        &step.suspects,
        &trial,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::experiment::Experiment;
    use crate::model::ModelSpec;

    #[test]
    fn a_realignment_pairs_each_force_with_the_displacement_before_or_after_it() {
        let u: Vec<f64> = (0..12).map(|k| k as f64).collect();
        let f: Vec<f64> = (0..12).map(|k| 100.0 + k as f64).collect();
        let exp = Experiment {
            input: u,
            output: f,
            drive: Drive::Displacement,
        };
        let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
        let late = realigned(&problem, 2).unwrap();
        assert_eq!(late.exp.input, (0..10).map(f64::from).collect::<Vec<_>>());
        assert_eq!(late.exp.output[0], 102.0);
        assert_eq!(late.target.output, late.exp.output);
        let early = realigned(&problem, -1).unwrap();
        assert_eq!(early.exp.input[0], 1.0);
        assert_eq!(early.exp.output[0], 100.0);
        assert_eq!(early.exp.output.len(), 11);
        // Too few samples left for the five parameters.
        assert!(realigned(&problem, 6).is_none());
        assert!(realigned(&problem, 0).is_none());
    }
}
