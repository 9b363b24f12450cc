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
    /// When the measured force's sample-to-sample changes line up best with
    /// the model's, in samples (positive: later), within [`MAX_LAG`]; a lag
    /// is named only where this has the realignment's sign, or is 0 and the
    /// force is read late.
    pub changes_shift: Option<i64>,
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

/// When the measured force `force` changes against the model's (`force +
/// residual`), in samples: the shift `tau` (within [`MAX_LAG`] each way) that
/// maximises the correlation of their sample-to-sample changes,
/// `sum_k dm[k] df[k + tau]`. The model is driven by the displacement as
/// sampled, so it changes in step with it; the largest changes are the
/// elastic unloadings after each reversal, which a force read late starts
/// late. A residual that a realignment removes for another reason leaves the
/// changes in step: a coarse record whose samples miss the reversal peaks
/// (in step, yet a sample's realignment removed 29-54% of its squared error:
/// found by review). The fit bends its loop towards a lag, so the shift
/// reads less than the lag (1 for a force five samples late at 100 samples
/// a cycle) and can read 0 (one or two samples late at 20 samples a
/// cycle). Measured on the realigned record refitted instead, it read 0 on
/// every realignment, right or wrong (the refit bends too), and with the
/// refit's model driven by the record as read, the realignment's own lag.
fn in_step_shift(force: &[f64], residual: &[f64]) -> Option<i64> {
    let model: Vec<f64> = force.iter().zip(residual).map(|(f, r)| f + r).collect();
    let steps = |x: &[f64]| x.windows(2).map(|w| w[1] - w[0]).collect::<Vec<f64>>();
    let (dm, df) = (steps(&model), steps(force));
    let n = dm.len() as i64;
    let w = MAX_LAG as i64;
    let correlation = |tau: i64| -> f64 {
        (0..n)
            .filter(|k| (0..n).contains(&(k + tau)))
            .map(|k| dm[k as usize] * df[(k + tau) as usize])
            .sum()
    };
    (-w..=w)
        .map(|tau| (tau, correlation(tau)))
        .filter(|(_, c)| c.is_finite())
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(tau, _)| tau)
}

/// The candidate effect that fitted best, refitted on the model the suspects
/// were weighed on.
pub(super) fn best_effect(suspects: &[Suspect]) -> Option<(String, f64)> {
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
    let lag = trial.lag;
    // The force's changes must come late (or early) as the realignment says;
    // in step, they allow only a late force. The misfits of other kinds a
    // realignment was found to remove (a coarse record whose samples miss
    // the reversal peaks, a dashpot) make the force look early, and the fit
    // bends its loop towards a lag so that on a coarse record a force read
    // late reads in step (one or two samples late at 20 samples a cycle,
    // found by review).
    let timing = in_step_shift(&d.force, &d.residual);
    let timed = match timing {
        Some(0) => lag > 0,
        Some(t) => t.signum() == lag.signum(),
        None => false,
    };
    let significant = gain.significant() && at_least_as_good && timed;
    let (late, before, k) = if lag > 0 {
        ("late", "before", lag)
    } else {
        ("early", "after", -lag)
    };
    let plural = |k: i64| if k == 1 { "sample" } else { "samples" };
    let change = gain.words(nrmse);
    let changes = match timing {
        Some(0) if lag > 0 => "The measured force's changes run in step with the model's, as a \
                               fit bent towards a late force can make them on a coarse record."
            .to_string(),
        Some(0) => "The measured force's changes run in step with the model's.".to_string(),
        Some(t) => format!(
            "The measured force's changes line up best with the model's {} {} {}.",
            t.abs(),
            plural(t.abs()),
            if t > 0 { "later" } else { "earlier" }
        ),
        None => String::new(),
    };
    let mut evidence = format!(
        "With the force read {k} {} {late} (each force sample paired with the displacement {k} \
         {before} it, {k} {} lost at the ends) and {model} refitted, the fit takes {change} on \
         the samples both share. {changes}",
        plural(k),
        if k == 1 { "pair" } else { "pairs" },
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
        // A dashpot's force turns with the velocity at a reversal, ahead of
        // the elastic unloading (found by review: a viscous force of 5% of
        // the peak at 400 samples a cycle was named a force a sample early).
        let dashpot = if lag < 0 {
            " A viscous force (a dashpot, a rate-dependent material) also makes the force lead \
             at the reversals: if the instruments are known to be in step, look at rate \
             dependence instead."
        } else {
            ""
        };
        format!(
            "{effect}{LAG_REMEDY} a loop's steep branches lean along the displacement, which \
             effects can stand in for: check how the two channels were sampled, and run again \
             with `--lag force={lag}` to realign them.{dashpot}"
        )
    } else if gain.share < 0.0 {
        format!("Not significant: realigned by a sample either way, {model} fits worse.")
    } else if !gain.significant() {
        gain.not_significant()
    } else if !at_least_as_good {
        let (name, e) = best_effect.clone().unwrap_or_default();
        format!("Not named: {name}, refitted instead, reaches {e:.4}, better than a lag does.")
    } else {
        "Not named: the force's changes do not come when such a lag would make them, so the \
         realignment removes a misfit of another kind (a coarse record whose samples miss the \
         reversal peaks, a viscous force, a lag in part of the record or of a fraction of a \
         sample)."
            .into()
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
        changes_shift: timing,
        evidence,
    })
}

/// How a named lag's advice begins: [`yield_to`] replaces it.
const LAG_REMEDY: &str = "Channels out of step make";

/// Unnames the lag `lag` for another number that is not the model's, a zero
/// offset, a drift or a dashpot (called `name`), named at an NRMSE of
/// `other` (`None`: not named), where that fits better: the one that
/// explains more is taken off first (a zero drifting from -3 mm back to 0
/// beside a force offset, on `bw+pinching`: the drift took the NRMSE to
/// 0.0173, a force one sample late to 0.0965, and both were named; with the
/// drift taken off, no lag was left: found by review; a dashpot makes the
/// force lead at the reversals, and a sine record's was named a force a
/// sample early beside it, 0.0284 against the dashpot's 0.0234).
pub fn yield_to(lag: &mut LagCheck, name: &str, other: Option<f64>) {
    let Some(other) = other.filter(|o| lag.significant && *o < lag.nrmse_with) else {
        return;
    };
    if let Some(at) = lag.evidence.find(LAG_REMEDY) {
        lag.evidence.truncate(at);
    }
    lag.evidence.push_str(&format!(
        "Not named: the {name} (above), whose numbers are not the model's either, fits better \
         ({other:.4} against {:.4}): take it off the record and run again, and a lag that is \
         there is named then.",
        lag.nrmse_with
    ));
    lag.significant = false;
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

/// The check along a discovery: on the first model, before any effect could
/// stand in for a lag, and on the final one, whose effects it must beat as
/// well and whose residual, free of the effects the first model lacked,
/// shows the lag's size (force four samples late with pinching hidden: two
/// on `bw`, four on `bw+pinching`, found by review). A check named on the
/// final model is kept, else one named on the first, else the stronger
/// evidence.
pub fn of_ladder(discovery: &Discovery) -> Option<LagCheck> {
    let on = |s: &Step| of_fit(&s.problem, &s.outcome, &s.diagnosis, &s.suspects);
    let first = on(&discovery.steps[0]);
    if discovery.steps.len() == 1 {
        return first;
    }
    let last = on(discovery.last());
    match (first, last) {
        (_, Some(l)) if l.significant => Some(l),
        (Some(f), _) if f.significant => Some(f),
        (Some(f), Some(l)) => Some(if l.delta_bic < f.delta_bic { l } else { f }),
        (f, l) => f.or(l),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discover::offset::{Offset, OffsetCheck};
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

    /// The numbers of the review's record (a zero drifting from -3 mm back to 0 beside a force
    /// offset of -3%, on `bw+pinching`): the drift reached 0.0173, the realignment 0.0965.
    #[test]
    fn a_lag_yields_to_a_named_offset_that_fits_better() {
        let lag = LagCheck {
            model: "bw+pinching".into(),
            significant: true,
            samples: 1,
            share: 0.106,
            nrmse_with: 0.0965,
            delta_bic: -22.0,
            n_eff: 240.0,
            best_effect: None,
            changes_shift: Some(0),
            evidence: format!(
                "With the force read 1 sample late, the fit takes the NRMSE from 0.1021 to \
                 0.0965. {LAG_REMEDY} a loop's steep branches lean, and run again with \
                 `--lag force=1` to realign them."
            ),
        };
        let drift = |nrmse_with: f64, significant: bool| OffsetCheck {
            offset: Offset::DisplacementDrift,
            model: "bw+pinching".into(),
            significant,
            value: 3.16,
            relative: 0.2,
            with_force: Some(-1.05),
            line: Some([-3.02, 0.14]),
            force_line: None,
            share: 0.97,
            nrmse_with,
            delta_bic: -5628.0,
            n_eff: 240.0,
            asymmetry_nrmse: None,
            evidence: String::new(),
        };
        let mut yielded = lag.clone();
        let named = |o: &OffsetCheck| o.significant.then_some(o.nrmse_with);
        yield_to(
            &mut yielded,
            "displacement drift",
            named(&drift(0.0173, true)),
        );
        assert!(!yielded.significant);
        assert!(!yielded.evidence.contains("--lag"), "{}", yielded.evidence);
        assert!(
            yielded.evidence.contains(
                "Not named: the displacement drift (above), whose numbers are not the model's \
                 either, fits better (0.0173 against 0.0965)"
            ),
            "{}",
            yielded.evidence
        );
        // An offset that fits worse, or is not named, leaves the lag as it was.
        for offset in [drift(0.0990, true), drift(0.0173, false)] {
            let mut kept = lag.clone();
            yield_to(&mut kept, "displacement drift", named(&offset));
            assert_eq!(kept, lag);
        }
    }
}
