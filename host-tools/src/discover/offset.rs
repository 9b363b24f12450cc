//! Zero offsets: a record whose instruments do not read zero at zero, which
//! no effect of the library models, looked for so that the diagnosis can name
//! it instead of pinning the misfit on an effect (found by review: a force
//! offset of 3% of the peak was added to `bw` as asymmetry at a BIC change of
//! -386, and a displacement offset left pinching named on an irregular path).
//!
//! Two checks on displacement-driven fits:
//!
//! * **A force offset.** The load cell reads `F0` where the force is zero, so
//!   the measured force is the specimen's plus a constant. A symmetric model
//!   cannot follow it; strength asymmetry (`Zu± = Zu (1 ± a)`) follows it at
//!   the peaks but not where the force crosses zero. The check fits the
//!   constant to the residual (its mean: the fits weigh every sample alike)
//!   and weighs it like a suspect (see [`suspects`](super::suspects)): BIC
//!   with the effective sample size of what is left, significant below -10,
//!   and only when it removes at least [`MIN_SHARE`] of the squared error.
//!   Where asymmetry is a significant suspect as well, the offset is named
//!   only when the constant alone, one number that is not a parameter of the
//!   model, fits at least as well as the model refitted with asymmetry: then
//!   the asymmetry may be the instrument's zero.
//! * **A start away from rest.** The models start at rest at zero
//!   displacement (z = 0), so when the record's first displacement `u0` is
//!   not zero their first step is a jump to `u0` that loads them before the
//!   test begins. The transducer's zero is off, or the record starts after
//!   the loading did. The check refits the model from rest at the first
//!   sample (the displacement minus `u0`), starting from the fitted
//!   parameters, and weighs the change of the error the same way, with `u0`
//!   as the one added number. In a
//!   Bouc-Wen model a displacement offset acts only through this start and
//!   the elastic spring `alpha k0 u0`, a constant force that the force
//!   check sees.
//!
//! The force check does not refit the model with the offset removed, so its
//! gain is a lower bound of what a refit finds; `--subtract` (see the
//! README) removes a known offset from the record before fitting.
//!
//! Measured on the synthetic base (`tests/discover_offset.rs`): a force
//! offset of 3% of the peak removes 50-75% of a `bw` fit's squared error and
//! the constant alone reaches the noise-only NRMSE (0.028 against 0.033 with
//! asymmetry refitted, step-wise path); hidden asymmetry of 0.3 leaves a
//! constant that removes 79-85% of the error but reaches only NRMSE 0.11-0.14
//! against 0.03-0.04 with asymmetry; records with nothing hidden leave at
//! most 3.7%.

use super::diagnosis::Diagnosis;
use super::ladder::Discovery;
use super::suspects::{effective_n, Suspect, SIGNIFICANT_BIC};
use crate::fit::experiment::Drive;
use crate::fit::problem::Problem;
use crate::fit::run::{self, Method, Outcome, Quiet};
use crate::model::EffectRef;
use hysteresis::bwbn::EffectKind;
use serde::Serialize;

/// Smallest share of the squared error an offset must remove to be named:
/// records with nothing hidden leave a residual whose mean removes up to
/// 3.7% (an irregular path, whose misfit is not symmetric), a force offset of
/// 1% of the peak about a third (measured, see the module docs).
pub const MIN_SHARE: f64 = 0.1;

/// Which instrument's zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Offset {
    /// The force reads a constant too much everywhere.
    Force,
    /// The record starts at a displacement other than zero.
    Start,
}

/// What the record says about one zero offset.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct OffsetCheck {
    /// Which offset.
    pub offset: Offset,
    /// Named: see the module docs for the rule.
    pub significant: bool,
    /// The offset: the constant the measured force reads above the model's
    /// (force units, kN), or the first displacement (mm).
    pub value: f64,
    /// The offset as a fraction of the record's peak force or displacement.
    pub relative: f64,
    /// Share of the squared error that removing the offset removes.
    pub share: f64,
    /// NRMSE with the offset removed, the parameters as fitted.
    pub nrmse_with: f64,
    /// BIC change from removing the offset (one added number).
    pub delta_bic: f64,
    /// Effective sample size used.
    pub n_eff: f64,
    /// For the force offset: the NRMSE of the model refitted with
    /// asymmetry, where that is a significant suspect.
    pub asymmetry_nrmse: Option<f64>,
    /// The evidence in words.
    pub evidence: String,
}

/// The weighing both checks share: the residual `r` before and `after`
/// removing the offset, of a fit with NRMSE `nrmse`.
struct Gain {
    share: f64,
    nrmse_with: f64,
    delta_bic: f64,
    n_eff: f64,
}

impl Gain {
    fn of(d: &Diagnosis, nrmse: f64, after: &[f64]) -> Option<Gain> {
        let before: f64 = d.residual.iter().map(|r| r * r).sum();
        let rest: f64 = after.iter().map(|r| r * r).sum();
        if !(before > 0.0 && rest > 0.0 && before.is_finite() && rest.is_finite()) {
            return None;
        }
        let floor = d.segmentation.cycles().half_cycles().len();
        let n_eff = effective_n(after, 1, floor);
        Some(Gain {
            share: 1.0 - rest / before,
            nrmse_with: nrmse * (rest / before).sqrt(),
            delta_bic: n_eff * (rest / before).ln() + n_eff.ln(),
            n_eff,
        })
    }

    fn significant(&self) -> bool {
        self.delta_bic < SIGNIFICANT_BIC && self.share >= MIN_SHARE
    }

    /// Why a gain is not named.
    fn not_significant(&self) -> String {
        if self.delta_bic < SIGNIFICANT_BIC {
            format!(
                "Not significant: it removes less than {:.0}% of the squared error.",
                100.0 * MIN_SHARE
            )
        } else if self.share < 0.0 {
            "Not significant: the model fits worse without it.".into()
        } else {
            "Not significant.".into()
        }
    }

    fn words(&self, nrmse: f64) -> String {
        format!(
            "the NRMSE from {nrmse:.4} to {:.4} ({:.1}% of the squared error; delta-BIC {:+.0})",
            self.nrmse_with,
            100.0 * self.share,
            self.delta_bic
        )
    }
}

fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Looks for a force offset in the residual of `d`, a displacement-driven fit
/// with NRMSE `nrmse` whose candidate effects were weighed as `suspects`.
pub fn force(d: &Diagnosis, nrmse: f64, suspects: &[Suspect]) -> Option<OffsetCheck> {
    let n = d.residual.len() as f64;
    let mean = d.residual.iter().sum::<f64>() / n;
    let after: Vec<f64> = d.residual.iter().map(|r| r - mean).collect();
    let gain = Gain::of(d, nrmse, &after)?;
    // The model's force is the measured force plus the residual: a load cell
    // reading `F0` too much leaves a residual of `-F0`.
    let value = -mean;
    let relative = value / peak(&d.force);
    let asymmetry = suspects
        .iter()
        .find(|s| is_asymmetry(s) && s.significant)
        .map(|s| s.nrmse_with);
    let at_least_as_good = asymmetry.is_none_or(|a| gain.nrmse_with <= a);
    let significant = gain.significant() && at_least_as_good;
    let mut evidence = format!(
        "The measured force reads {value:+.4} kN ({:+.1}% of its peak) above the model's on \
         average; a constant force taken off it takes {}.",
        100.0 * relative,
        gain.words(nrmse)
    );
    evidence.push(' ');
    evidence.push_str(&match (significant, asymmetry) {
        (true, Some(a)) => format!(
            "Asymmetry, refitted, reaches {a:.4}: no better than this one number, which is not a \
             parameter of the model. A load cell that does not read zero at zero force looks like \
             unequal strength in the two directions: check the instrument's zero before trusting \
             the asymmetry, and run again with `--subtract force={value:.4}` to take it off."
        ),
        (true, None) => format!(
            "No effect of the library adds a constant force: check the load cell's zero, and run \
             again with `--subtract force={value:.4}` to take it off."
        ),
        (false, Some(a)) if !at_least_as_good => format!(
            "Not named: asymmetry, refitted, reaches {a:.4}, better than a constant offset does."
        ),
        (false, _) => gain.not_significant(),
    });
    Some(OffsetCheck {
        offset: Offset::Force,
        significant,
        value,
        relative,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: asymmetry,
        evidence,
    })
}

/// Looks for a start away from rest: `outcome`, a displacement-driven fit of
/// `problem` diagnosed as `d`, refitted by least squares (from its own
/// parameters) to the record moved to rest at its first displacement. `None`
/// for other drives, a first displacement of zero or a model that cannot be
/// simulated from there.
pub fn start(problem: &Problem, outcome: &Outcome, d: &Diagnosis) -> Option<OffsetCheck> {
    if problem.exp.drive != Drive::Displacement {
        return None;
    }
    let u0 = *problem.exp.input.first()?;
    if u0 == 0.0 {
        return None;
    }
    let mut shifted = problem.clone();
    shifted.exp.input.iter_mut().for_each(|u| *u -= u0);
    // The misfit a wrong start leaves is spread over the whole record by the
    // fit's compromise, so the same parameters alone recover little of it
    // (a 10 mm offset on the shared record s1: 25% of the squared error at
    // delta-BIC -6 with the same parameters).
    let refit = run::fit(&shifted, Method::Lsq, &outcome.x, &Quiet).ok()?;
    let predicted = shifted.predict(&refit.x)?;
    let after: Vec<f64> = predicted
        .output
        .iter()
        .zip(&problem.exp.output)
        .map(|(m, f)| m - f)
        .collect();
    let nrmse = outcome.scores.nrmse;
    let gain = Gain::of(d, nrmse, &after)?;
    let relative = u0 / peak(&problem.exp.input);
    let significant = gain.significant();
    let f0 = problem.exp.output[0];
    let verdict = if !significant {
        gain.not_significant()
    } else {
        format!(
            "If the displacement transducer's zero is off, run again with `--subtract \
             displacement={u0:.4}` (effects named for this record may stand in for the offset); \
             if the specimen was loaded before the record starts, the model cannot know its state \
             and the first cycles will fit less well."
        )
    };
    let evidence = format!(
        "The record starts at displacement {u0:+.4} mm ({:+.1}% of its peak) and force \
         {f0:+.4} kN; the models start at rest at zero, so their first step is a jump of \
         {u0:+.4} mm. Refitted from rest at the first sample, the model takes {}. \
         {verdict}",
        100.0 * relative,
        gain.words(nrmse)
    );
    Some(OffsetCheck {
        offset: Offset::Start,
        significant,
        value: u0,
        relative,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: None,
        evidence,
    })
}

/// Both checks along a discovery: the force offset on the step from which
/// the ladder added asymmetry (where it was the strongest significant
/// suspect), else on the final model; the start on the first model, before
/// any effect could stand in for it.
pub fn of_ladder(discovery: &Discovery) -> (Option<OffsetCheck>, Option<OffsetCheck>) {
    let first = &discovery.steps[0];
    if first.problem.exp.drive != Drive::Displacement {
        return (None, None);
    }
    let asymmetric = discovery.steps.iter().find(|s| {
        s.suspects
            .iter()
            .find(|x| x.significant)
            .is_some_and(is_asymmetry)
    });
    let on = asymmetric.unwrap_or_else(|| discovery.last());
    (
        force(&on.diagnosis, on.outcome.scores.nrmse, &on.suspects),
        start(&first.problem, &first.outcome, &first.diagnosis),
    )
}

fn is_asymmetry(s: &Suspect) -> bool {
    s.effect == EffectRef::Builtin(EffectKind::Asymmetry)
}
