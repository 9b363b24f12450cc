//! Zero offsets: a record whose instruments do not read zero at zero, which
//! no effect of the library models, looked for so that the diagnosis can name
//! it instead of pinning the misfit on an effect (found by review: a force
//! offset of 3% of the peak was added to `bw` as asymmetry at a BIC change of
//! -386, and a displacement offset left pinching named on an irregular path).
//!
//! Checks on displacement-driven fits, each weighed like a suspect (see
//! [`suspects`]): BIC at the larger of the suspects'
//! effective sample size (that of the best model they found, so that offsets
//! and effects are on one scale) and that of the residual with the offset
//! removed, significant below -10, and only when the offset removes at least
//! [`MIN_SHARE`] of the squared error.
//!
//! * **A force offset.** The load cell reads `F0` where the force is zero, so
//!   the measured force is the specimen's plus a constant. A symmetric model
//!   cannot follow it; strength asymmetry (`Zu± = Zu (1 ± a)`) follows it at
//!   the peaks but not where the force crosses zero. The check fits the
//!   constant to the residual (its mean: the fits weigh every sample alike).
//!   The constant and asymmetry explain the same lopsided residual, so where
//!   the suspects weighed asymmetry the offset is named only when the
//!   constant alone, one number that is not a parameter of the model, fits at
//!   least as well as the model refitted with asymmetry. And an instrument's
//!   zero is off from the first sample: over the record's elastic start
//!   (until the displacement reaches [`EARLY`] of its peak) the residual at
//!   zero displacement must show at least [`START_SHARE`] of the constant, and
//!   the window must reach zero (within a tenth of its reach)
//!   (Kunnath's A7-A10, SPD 351-354, read zero force at rest and have loops
//!   that a constant fits as well as asymmetry does).
//! * **A start away from rest.** The models start at rest at zero
//!   displacement (z = 0), so when the record's first displacement `u0` is
//!   not zero their first step is a jump to `u0` that loads them before the
//!   test begins. The transducer's zero is off, or the record starts after
//!   the loading did. The check refits the model from rest at the first
//!   sample (the displacement minus `u0`), starting from the fitted
//!   parameters, with `u0` as the one added number. The jump can take up a
//!   force offset (a model near its elastic limit turns it into a constant
//!   z), so the start is also named where it adds significantly to a constant
//!   force alone, and a named start keeps the refit's own constant force
//!   where the force offset's rule holds against the start alone (it is
//!   significant, and the refit's residual at rest over its elastic start
//!   shows at least [`START_SHARE`] of it); or, where
//!   the load cell drifts beside the start, a line in the sample number
//!   fitted to what the refit leaves, kept where the force drift's rule
//!   holds against the start alone (significant, and a BIC change below -10
//!   beyond a constant). A constant or a line kept
//!   beside the start must fit at least as well as asymmetry refitted from
//!   rest there, which explains the same lopsided residual; where asymmetry
//!   fits better the force is left as measured, and the start is named only
//!   where it is significant alone or beside asymmetry. First displacements below
//!   [`START_FLOOR`] of the peak are left out. In a Bouc-Wen model a
//!   displacement offset acts only through this start and the elastic spring
//!   `alpha k0 u0`, a constant force. Where the start is named the force
//!   check is not named on its own: the jump leaves a constant of its own.
//!
//! * **A drifting force zero.** A load cell warming up or creeping reads a
//!   zero that moves along the test. The check fits a straight line in the
//!   sample number to the residual (two numbers) and names it where it is
//!   significant, adds a BIC change below -10 to a constant alone, fits at
//!   least as well as asymmetry refitted, the start is not named, and a line
//!   in the displacement does not fit decisively better ([`drift`]; a
//!   drifting displacement zero leaves a like residual:
//!   [`displacement_drift`]).
//!
//! The force checks do not refit the model with the offset removed, so their
//! gains are lower bounds of what a refit finds; `--subtract` (see the
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
use super::displacement_drift;
use super::ladder::{Discovery, Step};
use super::signature::mean;
use super::suspects::{self, effective_n, residual, Suspect, WeighOptions, SIGNIFICANT_BIC};
use crate::fit::experiment::Drive;
use crate::fit::problem::Problem;
use crate::fit::run::{self, Method, Outcome, Quiet};
use crate::model::{EffectRef, ModelSpec};
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
    /// The force's zero drifts along the record.
    Drift,
    /// The displacement's zero drifts along the record
    /// ([`displacement_drift`]).
    DisplacementDrift,
}

/// What the record says about one zero offset.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct OffsetCheck {
    /// Which offset.
    pub offset: Offset,
    /// The model whose fit was checked (in `discover`, the rung from which
    /// asymmetry was added, or the first or final model).
    pub model: String,
    /// Named: see the module docs for the rule.
    pub significant: bool,
    /// The offset: the constant the measured force reads above the model's
    /// (force units, kN), the first displacement (mm), or for a drift how
    /// far the channel's zero moves from the first sample to the last (kN
    /// for the force, mm for the displacement).
    pub value: f64,
    /// The offset as a fraction of the record's peak force or displacement.
    pub relative: f64,
    /// For a named start away from rest: the constant force that, taken off
    /// as well, adds a BIC change below -10 to the start alone (a force offset
    /// the model had absorbed into its first jump), if any and no line is
    /// kept (`force_line`). For a drifting
    /// displacement zero: the constant force fitted together with its line
    /// ([`displacement_drift`]), if it adds a BIC change below -10.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub with_force: Option<f64>,
    /// For a drift: the channel's zero the line puts at the first and at
    /// the last sample (kN or mm), which `--subtract CHANNEL=FIRST..LAST`
    /// takes off.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<[f64; 2]>,
    /// For a drifting displacement zero: the line in the force (kN at the
    /// first and at the last sample) fitted together with its own, where it
    /// adds a BIC change below -10 ([`displacement_drift`]); for a named
    /// start, the line in the force its refit leaves, where it is significant
    /// against the start alone and beyond a constant ([`start`]). The option
    /// takes both off.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_line: Option<[f64; 2]>,
    /// Share of the squared error that removing the offset removes.
    pub share: f64,
    /// NRMSE with the offset removed: the parameters as fitted for the force
    /// offset, refitted from rest at the first sample for the start.
    pub nrmse_with: f64,
    /// BIC change from removing the offset (one added number, two with
    /// `with_force`, three with a start's `force_line`).
    pub delta_bic: f64,
    /// Effective sample size used: the larger of the suspects' (that of the
    /// best model they found, so that the offset and the effects are weighed
    /// on one scale) and that of the residual with the offset removed.
    pub n_eff: f64,
    /// For the force offset: the NRMSE of the model refitted with
    /// asymmetry, where the suspects weighed it. For the start: that of the
    /// model refitted from rest at the first sample with asymmetry, where a
    /// force's part beside the start was weighed against it.
    pub asymmetry_nrmse: Option<f64>,
    /// The evidence in words.
    pub evidence: String,
}

/// The weighing the checks share (the offsets here, the lag of
/// [`lag`](super::lag)): the residual of `d` (NRMSE `nrmse`) against the
/// residual `after` removing `k` numbers.
#[derive(Clone, Copy)]
pub(super) struct Gain {
    pub(super) share: f64,
    pub(super) nrmse_with: f64,
    pub(super) delta_bic: f64,
    pub(super) n_eff: f64,
}

impl Gain {
    /// The gain of going from the residual `before` (NRMSE `nrmse`) to
    /// `after` with `k` more numbers, on the record diagnosed as `d`. The
    /// effective sample size is the larger of the suspects' (`scale`) and
    /// that of `after`: like the suspects' own, that of the best model in the
    /// comparison, which the offset model may be (a start 5 mm off on s1:
    /// refitted from rest it is back at the clean NRMSE, whose residual is
    /// white, while every effect left it correlated: found by review).
    pub(super) fn of(
        d: &Diagnosis,
        nrmse: f64,
        before: &[f64],
        after: &[f64],
        k: usize,
        scale: Scale,
    ) -> Option<Gain> {
        let sq = |r: &[f64]| r.iter().map(|r| r * r).sum::<f64>();
        let (b, rest) = (sq(before), sq(after));
        if !(b > 0.0 && rest > 0.0 && b.is_finite() && rest.is_finite()) {
            return None;
        }
        let floor = d.segmentation.cycles().half_cycles().len();
        let own = effective_n(after, k, floor);
        let n_eff = scale.map_or(own, |s| s.max(own));
        Some(Gain {
            share: 1.0 - rest / b,
            nrmse_with: nrmse * (rest / b).sqrt(),
            delta_bic: n_eff * (rest / b).ln() + k as f64 * n_eff.ln(),
            n_eff,
        })
    }

    pub(super) fn significant(&self) -> bool {
        self.delta_bic < SIGNIFICANT_BIC && self.share >= MIN_SHARE
    }

    /// Why a gain is not named.
    pub(super) fn not_significant(&self) -> String {
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

    /// The change in words; one that fits worse is said so, not as a
    /// negative share (found by review: "-9175681130736232.0%").
    pub(super) fn words(&self, nrmse: f64) -> String {
        if self.share < 0.0 {
            return format!(
                "the NRMSE from {nrmse:.4} to {:.4}, worse (delta-BIC {:+.0})",
                self.nrmse_with, self.delta_bic
            );
        }
        format!(
            "the NRMSE from {nrmse:.4} to {:.4} ({:.1}% of the squared error; delta-BIC {:+.0})",
            self.nrmse_with,
            100.0 * self.share,
            self.delta_bic
        )
    }
}

/// The effective sample size the suspects were weighed at (they share one),
/// `None` where none were weighed.
pub(super) type Scale = Option<f64>;

pub(super) fn scale_of(suspects: &[Suspect]) -> Scale {
    suspects.first().map(|s| s.n_eff)
}

/// The elastic start of a record: the samples before the displacement first
/// reaches this fraction of its peak.
pub const EARLY: f64 = 0.05;

/// Smallest part of the constant the residual must show over the elastic
/// start for a force offset to be named.
pub const START_SHARE: f64 = 0.5;

/// What the residual `r` reads at zero displacement over the elastic start
/// of `u` (at least its first three samples): the intercept of a straight
/// line fitted to `r` against `u` there, so that an elastic stiffness the
/// model has wrong (a residual growing with `u`) is not taken for an offset;
/// the mean where the displacement hardly moves. With how many samples.
/// `None` where the window's displacements stay further from zero than a
/// tenth of its reach (a record starting 1 mm off on a slope of 360 kN/mm read -384 kN
/// by extrapolation: found by review).
fn early_reading(r: &[f64], u: &[f64]) -> Option<(f64, usize)> {
    let limit = EARLY * peak(u);
    let n = u
        .iter()
        .position(|u| u.abs() > limit)
        .unwrap_or(u.len())
        .max(3)
        .min(u.len());
    let (r, u) = (&r[..n], &u[..n]);
    let (lo, hi) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    // Zero within the window, or within a tenth of the window's reach of it
    // (the shared s2 starts at 0.18 mm, 0.18% of its peak).
    if !(lo <= 0.0 && hi >= 0.0) && lo.abs().min(hi.abs()) > 0.1 * limit {
        return None;
    }
    let (mr, mu, slope) = line(u, r);
    if n < 3 || hi - lo <= 1e-9 * limit {
        return Some((mr, n));
    }
    Some((mr - slope * mu, n))
}

/// Decimals that print a value to 1e-5 of `peak` (at least 4): an offset of
/// a record whose forces are a few 1e-4 printed as `0.0000` at 4 decimals,
/// and the option that gave back took nothing off (found by review).
pub(super) fn decimals(peak: f64) -> usize {
    let d = (-(1e-5 * peak).log10()).ceil();
    if d.is_finite() {
        d.clamp(4.0, 15.0) as usize
    } else {
        4
    }
}

/// The least-squares line of `y` against `x`: the means of `y` and `x` and
/// the slope (not finite where `x` does not vary).
fn line(x: &[f64], y: &[f64]) -> (f64, f64, f64) {
    let (my, mx) = (mean(y), mean(x));
    let sxx: f64 = x.iter().map(|x| (x - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(x, y)| (x - mx) * (y - my)).sum();
    (my, mx, sxy / sxx)
}

/// Whether asymmetry, which can stand in for a drift on a test of growing
/// amplitude, was weighed among `suspects` or is in the model `spec`: a line
/// is named only where something held it against asymmetry (with
/// `--candidates` leaving it out, a hidden asymmetry was named a drift of 11%
/// of the peak: found by review).
pub(super) fn asymmetry_known(spec: ModelSpec, suspects: &[Suspect]) -> bool {
    asymmetry_refit(suspects).is_some() || spec.contains(EffectRef::Builtin(EffectKind::Asymmetry))
}

/// A straight line in the sample number fitted to a residual by least
/// squares: what a drifting zero leaves.
pub(super) struct ResidualLine {
    /// The sample number scaled to [0, 1]: `k / (n - 1)`.
    pub(super) s: Vec<f64>,
    mean: f64,
    mean_s: f64,
    slope: f64,
    /// The residual with the line taken off.
    pub(super) after: Vec<f64>,
}

impl ResidualLine {
    /// The line of `r`, which has at least two samples.
    pub(super) fn of(r: &[f64]) -> Self {
        let n = r.len();
        let s: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
        let (mean, mean_s, slope) = line(&s, r);
        let after = s
            .iter()
            .zip(r)
            .map(|(s, r)| r - mean - slope * (s - mean_s))
            .collect();
        ResidualLine {
            s,
            mean,
            mean_s,
            slope,
            after,
        }
    }

    /// The line at `s` (a residual, model less measured).
    pub(super) fn at(&self, s: f64) -> f64 {
        self.mean + self.slope * (s - self.mean_s)
    }
}

/// The asymmetry suspect, where the suspects weighed and fitted it.
fn asymmetry_refit(suspects: &[Suspect]) -> Option<&Suspect> {
    suspects
        .iter()
        .find(|s| is_asymmetry(s) && s.nrmse_with.is_finite())
}

pub(super) fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Looks for a force offset in the residual of the displacement-driven fit
/// of `model`, diagnosed as `d` with NRMSE `nrmse`, whose candidate effects
/// were weighed as `suspects`. Where the record's start away from rest is
/// named (`start_named`) the model's first jump leaves a constant of its own
/// (a start 5 mm off named a force offset of -28 kN on the shared record s1,
/// which has none: found by review), so the offset is then weighed within the
/// start's refit ([`OffsetCheck::with_force`]), not alone. Where the force
/// drift is named (`drift_named` is [`Offset::Drift`], [`drift`]) its line
/// holds the constant, so the offset is not named beside it: offsets for one
/// channel add up, and a user giving both options took the constant off
/// twice (found by review). Where the displacement's drift is named
/// ([`Offset::DisplacementDrift`]) the constant is part of what it leaves, or
/// of what its estimate took off the force beside its line.
pub fn force(
    model: &str,
    d: &Diagnosis,
    nrmse: f64,
    suspects: &[Suspect],
    start_named: bool,
    drift_named: Option<&OffsetCheck>,
) -> Option<OffsetCheck> {
    let m = mean(&d.residual);
    let after: Vec<f64> = d.residual.iter().map(|r| r - m).collect();
    let gain = Gain::of(d, nrmse, &d.residual, &after, 1, scale_of(suspects))?;
    // The model's force is the measured force plus the residual: a load cell
    // reading `F0` too much leaves a residual of `-F0`.
    let value = -m;
    let relative = value / peak(&d.force);
    // The constant and asymmetry explain the same lopsided residual: the
    // offset is named only where it explains it at least as well.
    let asymmetry = asymmetry_refit(suspects).map(|s| (s.nrmse_with, s.significant));
    let at_least_as_good = asymmetry.is_none_or(|(a, _)| gain.nrmse_with <= a);
    // An instrument's zero is off from the first sample on: before the
    // loading leaves the elastic start the residual shows the constant too. A
    // record that reads zero force at rest is not offset, whatever its loops
    // (Kunnath's A7-A10, SPD 351-354: zero at the start, and a constant that
    // fits their lopsided loops as well as asymmetry does).
    let early = early_reading(&d.residual, &d.displacement);
    let at_start = early.is_some_and(|(e, _)| e * m > 0.0 && e.abs() >= START_SHARE * m.abs());
    let significant =
        gain.significant() && at_least_as_good && at_start && !start_named && drift_named.is_none();
    let dp = decimals(peak(&d.force));
    let reading = match early {
        Some((e, n)) => format!(
            "At zero displacement over the first {n} samples (until the displacement reaches \
             {:.0}% of its peak) it reads {:+.dp$} kN above.",
            100.0 * EARLY,
            -e
        ),
        None => format!(
            "The record does not pass through zero displacement before the displacement reaches \
             {:.0}% of its peak, so its force at rest cannot be read.",
            100.0 * EARLY
        ),
    };
    let mut evidence = format!(
        "The measured force reads {value:+.dp$} kN ({:+.1}% of its peak) above the model's on \
         average (the model's own lopsided misfit included); a constant force taken off it takes \
         {}. {reading}",
        100.0 * relative,
        gain.words(nrmse),
    );
    evidence.push(' ');
    evidence.push_str(&if significant {
        match asymmetry {
            Some((a, true)) => format!(
                "Asymmetry, refitted, reaches {a:.4}: no better than this one number, which is \
                 not a parameter of the model. A load cell that does not read zero at zero force \
                 looks like unequal strength in the two directions: check the instrument's zero \
                 before trusting the asymmetry, and run again with `--subtract \
                 force={value:.dp$}` to take it off."
            ),
            _ => format!(
                "No effect of the library adds a constant force: check the load cell's zero, and \
                 run again with `--subtract force={value:.dp$}` to take it off."
            ),
        }
    } else if !gain.significant() {
        gain.not_significant()
    } else if start_named {
        "Not named on its own: the record starts away from rest (below), and the model's first \
         jump leaves a constant of its own; the start's refit weighs the load cell's zero as well \
         (a constant, or a line where it drifts)."
            .into()
    } else if let (Some(c), true) = (
        drift_named.filter(|c| c.offset == Offset::DisplacementDrift),
        at_least_as_good && at_start,
    ) {
        if c.with_force.is_some() || c.force_line.is_some() {
            "Not named on its own: the displacement drift (below) was estimated together with \
             what the force needs beside its line, and its option takes both off."
                .into()
        } else {
            "Not named on its own: the displacement drift (below) leaves a constant force of \
             its own (the elastic spring times the line); take its line off and look again."
                .into()
        }
    } else if drift_named.is_some() && at_least_as_good && at_start {
        "Not named on its own: the force drift (below) takes off a line that holds this \
         constant; its option alone takes off both (giving both would take the constant off \
         twice, since offsets for one channel add up)."
            .into()
    } else if let Some((a, _)) = asymmetry.filter(|_| !at_least_as_good) {
        format!("Not named: asymmetry, refitted, reaches {a:.4}, better than a constant does.")
    } else if early.is_none() {
        "Not named: an instrument's offset shows at rest, which this record does not reach.".into()
    } else {
        format!(
            "Not named: an instrument's offset would show from the start, and there the record \
             reads less than {:.0}% of the constant, so the constant is a lopsided misfit, not \
             the load cell's zero.",
            100.0 * START_SHARE
        )
    });
    Some(OffsetCheck {
        offset: Offset::Force,
        model: model.to_string(),
        significant,
        value,
        relative,
        with_force: None,
        line: None,
        force_line: None,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: asymmetry.map(|(a, _)| a),
        evidence,
    })
}

/// Looks for a drifting force zero (a load cell warming up or creeping) in
/// the residual of the displacement-driven fit of `model`, diagnosed as `d`
/// with NRMSE `nrmse`, whose candidates were weighed as `suspects`: a
/// straight line in the sample number fitted to the residual. Named when it
/// is significant as the offsets are, adds a BIC change below -10 to a
/// constant alone (a constant offset is [`force`]'s), fits at least as well
/// as the model refitted with asymmetry (which otherwise stands in for it:
/// a drift of 1% of the peak force over a test was added as asymmetry at a
/// BIC change of -485, found by review), the start is not named, and a
/// line in the displacement does not fit decisively better (`displacement`,
/// [`displacement_drift::check`]).
pub fn drift(
    spec: ModelSpec,
    d: &Diagnosis,
    nrmse: f64,
    suspects: &[Suspect],
    start_named: Option<&OffsetCheck>,
    displacement: Option<&OffsetCheck>,
) -> Option<OffsetCheck> {
    let model = spec.to_string();
    let r = &d.residual;
    let n = r.len();
    if n < 3 {
        return None;
    }
    let fitted = ResidualLine::of(r);
    let after = &fitted.after;
    let constant: Vec<f64> = r.iter().map(|r| r - fitted.mean).collect();
    let scale = scale_of(suspects);
    let gain = Gain::of(d, nrmse, r, after, 2, scale)?;
    let beyond_constant = Gain::of(d, nrmse, &constant, after, 1, scale)?;
    // The measured force is the model's less the residual: its zero moves by
    // -slope over the record.
    let value = -fitted.slope;
    let relative = value / peak(&d.force);
    let asymmetry = asymmetry_refit(suspects).map(|s| s.nrmse_with);
    // Real asymmetry leaves a residual a line can follow on paths of growing
    // amplitude: without asymmetry weighed, or in the model, there is nothing
    // to hold the line against.
    let asymmetry_known = asymmetry_known(spec, suspects);
    let at_least_as_good = asymmetry.is_none_or(|a| gain.nrmse_with <= a);
    let displaced = displacement.filter(|c| c.significant);
    let significant = gain.significant()
        && beyond_constant.delta_bic < SIGNIFICANT_BIC
        && asymmetry_known
        && at_least_as_good
        && start_named.is_none()
        && displaced.is_none();
    // Where the line puts the zero at the first and the last sample (a
    // constant offset beside the drift shows in the first: found by review).
    let (first, last) = (-fitted.at(0.0), -fitted.at(1.0));
    let dp = decimals(peak(&d.force));
    let mut evidence = format!(
        "The measured force's zero moves by {value:+.dp$} kN ({:+.1}% of its peak) from the \
         first sample to the last, against the model's (a straight line in the sample number \
         fitted to the residual: {:+.dp$} kN at the first sample, {:+.dp$} kN at the last); \
         taking the line off takes {}, a BIC change of {:+.0} beyond a constant alone.",
        100.0 * relative,
        first,
        last,
        gain.words(nrmse),
        beyond_constant.delta_bic
    );
    evidence.push(' ');
    let remedy = format!(
        "run again with `--subtract force={first:.dp$}..{last:.dp$}` to take it off{}",
        if displacement.is_some() {
            " (a line in the displacement, weighed below, fits no decisively better)"
        } else {
            ""
        }
    );
    evidence.push_str(&if significant {
        match asymmetry {
            Some(a) => format!(
                "Asymmetry, refitted, reaches {a:.4}: no better than these two numbers, which are \
                 not parameters of the model. A load cell whose zero drifts (warming up, creep) \
                 looks like unequal strength in the two directions: check the instrument before \
                 trusting an effect named for it, and {remedy}."
            ),
            None => format!(
                "No effect of the library drifts with time: check the load cell's zero (warming \
                 up, creep) before trusting an effect named for it, and {remedy}."
            ),
        }
    } else if !gain.significant() {
        gain.not_significant()
    } else if let Some([a, b]) = displaced.and_then(|c| c.force_line) {
        format!(
            "Not named on its own: fitted together with a line in the displacement (below), the \
             load cell's zero drifts from {a:+.dp$} kN to {b:+.dp$} kN, and the displacement \
             drift's option takes both off (this line, estimated alone, holds part of the \
             displacement's)."
        )
    } else if let Some(c) = displaced {
        format!(
            "Not named: a line in the displacement (below) fits decisively better, {:.4}; the \
             displacement's zero drifts, not the load cell's{}.",
            c.nrmse_with,
            c.with_force.map_or(String::new(), |f| format!(
                ", which reads a constant {f:+.dp$} kN off beside it (fitted together with the \
                 displacement's line; its option takes both off)"
            ))
        )
    } else if beyond_constant.delta_bic >= SIGNIFICANT_BIC {
        "Not named: a constant explains it as well (weighed as the force offset).".into()
    } else if let Some([a, b]) = start_named.and_then(|c| c.force_line) {
        format!(
            "Not named on its own: refitted from rest at the record's first sample (below), the \
             load cell's zero drifts from {a:+.dp$} kN to {b:+.dp$} kN, and the start's option \
             takes both off."
        )
    } else if start_named.is_some() {
        "Not named: the record starts away from rest (below), whose refit it would meet.".into()
    } else if !asymmetry_known {
        "Not named: asymmetry, which can stand in for a drift on a test of growing amplitude, \
         was not weighed (add it to --candidates to compare)."
            .into()
    } else {
        format!(
            "Not named: asymmetry, refitted, reaches {:.4}, better than a drift does.",
            asymmetry.unwrap_or(f64::NAN)
        )
    });
    Some(OffsetCheck {
        offset: Offset::Drift,
        model,
        significant,
        value,
        relative,
        with_force: None,
        line: Some([first, last]),
        force_line: None,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: asymmetry,
        evidence,
    })
}

/// The residual (model less measured) of `problem` refitted by least squares
/// from `x0`, the parameters of a fit to the record before it was changed;
/// `None` where the refit fails.
pub(super) fn refit_residual(problem: &Problem, x0: &[f64]) -> Option<Vec<f64>> {
    let refit = run::fit(problem, Method::Lsq, x0, &Quiet).ok()?;
    residual(problem, &refit.x)
}

/// First displacements below this fraction of the peak are not checked: a
/// jump that small cannot matter, and a record taken off by `--subtract`
/// keeps a rounding residue (found by review: 4.5e-5 mm refitted in full).
pub const START_FLOOR: f64 = 1e-3;

/// Looks for a start away from rest: `outcome`, a displacement-driven fit of
/// `problem` diagnosed as `d` with candidate effects weighed as `suspects`,
/// refitted by least squares (from its own parameters) to the record moved to
/// rest at its first displacement; and, since a jump at the start can take up
/// a constant force (a model near its elastic limit turns the jump into a
/// constant z), with the refit's own constant force taken off as well, which
/// is kept where [`force`] would name it on the refit: significant against
/// the start alone and read at rest over the refit's elastic start (or a
/// line, weighed as [`drift`] weighs one). `None` for other drives, a first
/// displacement below [`START_FLOOR`] of the peak or a model that cannot be
/// simulated from there.
pub fn start(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
) -> Option<OffsetCheck> {
    if problem.exp.drive != Drive::Displacement {
        return None;
    }
    let u0 = *problem.exp.input.first()?;
    let relative = u0 / peak(&problem.exp.input);
    if relative.is_nan() || relative.abs() < START_FLOOR {
        return None;
    }
    let mut shifted = problem.clone();
    shifted.exp.input.iter_mut().for_each(|u| *u -= u0);
    // The misfit a wrong start leaves is spread over the whole record by the
    // fit's compromise, so the same parameters alone recover little of it
    // (a 10 mm offset on the shared record s1: 25% of the squared error at
    // delta-BIC -6 with the same parameters).
    let from_rest = run::fit(&shifted, Method::Lsq, &outcome.x, &Quiet).ok()?;
    let after = residual(&shifted, &from_rest.x)?;
    let nrmse = outcome.scores.nrmse;
    let scale = scale_of(suspects);
    let alone = Gain::of(d, nrmse, &d.residual, &after, 1, scale)?;
    // With a constant force taken off as well, the start is weighed against
    // the constant alone: it must add to what the constant explains (a pure
    // force offset on s2, whose first displacement is 0.18 mm, was named as a
    // start with a force: found by review).
    let m = mean(&after);
    let both: Vec<f64> = after.iter().map(|r| r - m).collect();
    let m0 = mean(&d.residual);
    let constant: Vec<f64> = d.residual.iter().map(|r| r - m0).collect();
    let beyond = Gain::of(d, nrmse, &constant, &both, 1, scale);
    let total = Gain::of(d, nrmse, &d.residual, &both, 2, scale);
    // A load cell drifting beside the start leaves the refit a line in the
    // sample number, which the force drift's check does not name beside a
    // named start (the jump leaves a constant of its own): a start of 1.5 mm
    // beside a drift of 2% of the peak force was refitted to 0.0193 with a
    // constant (clean 0.0166), and the drift was named only on the next run
    // (found by review). The line is weighed as the force drift's check
    // weighs one against the fit: significant against the start alone (two
    // numbers), and a BIC change below -10 beyond a constant (asking 10% of
    // what the start and a constant leave, a drift of 1% of the peak force
    // was left to the second run, which added asymmetry for it: found by
    // review).
    let line = ResidualLine::of(&after);
    let line_gain = Gain::of(d, nrmse, &after, &line.after, 2, scale);
    let slope = Gain::of(d, nrmse, &both, &line.after, 1, scale);
    let with_line = Gain::of(d, nrmse, &d.residual, &line.after, 3, scale);
    // The start is named where it is significant alone or beyond the
    // constant. With a named start the line is kept as above, else the
    // constant where it adds decisively (a BIC change below -10) to the
    // start alone; either must fit at least as well as asymmetry refitted
    // from rest there, which explains the same lopsided residual (a start
    // on a record with asymmetry of 4% hidden kept a line of 2.6% of the
    // peak force, which hid the asymmetry from the next run: found by
    // review). The evidence then gives the gain of
    // all against the fit as it was. An unnamed start is reported alone: the
    // force's parts are the force checks'.
    let named = alone.significant() || beyond.as_ref().is_some_and(Gain::significant);
    let line_weighed = line_gain.as_ref().is_some_and(Gain::significant)
        && slope
            .as_ref()
            .is_some_and(|g| g.delta_bic < SIGNIFICANT_BIC);
    let line_part = with_line
        .filter(|_| named && line_weighed)
        .map(|l| (l, ForcePart::Line([-line.at(0.0), -line.at(1.0)])));
    // A constant is weighed as the force offset's check weighs one, against
    // the start alone: significant, and read at rest over the refit's elastic
    // start, where a load cell's zero shows and a lopsided misfit does not
    // (with asymmetry of 4% hidden and left out of the candidates, a
    // constant of 9.9% of the peak force was kept beside a start at a BIC
    // change below -10, and the next run was left a worse fit: found by
    // review).
    let constant_gain = Gain::of(d, nrmse, &after, &both, 1, scale);
    let early = early_reading(&after, &shifted.exp.input);
    let at_rest = early.is_some_and(|(e, _)| e * m > 0.0 && e.abs() >= START_SHARE * m.abs());
    let constant_weighed = constant_gain.as_ref().is_some_and(Gain::significant);
    let constant_part = total
        .filter(|_| named && constant_weighed && at_rest)
        .map(|t| (t, ForcePart::Constant(-m)));
    // Asymmetry is refitted beside the start where a force part would be
    // kept, or where the start is named only beyond a constant.
    let asymmetry =
        if line_part.is_some() || constant_part.is_some() || (named && !alone.significant()) {
            Asymmetry::beside_start(&shifted, &from_rest, suspects)
        } else {
            Asymmetry::Absent
        };
    let candidates = [line_part, constant_part];
    let admitted = candidates
        .iter()
        .flatten()
        .find(|(g, f)| asymmetry.admits(g.nrmse_with, matches!(f, ForcePart::Line(_))));
    // What asymmetry holds instead, if anything.
    let refused = candidates
        .iter()
        .flatten()
        .next()
        .filter(|_| admitted.is_none() && matches!(asymmetry, Asymmetry::Refitted(_)));
    let (gain, force) = match admitted {
        Some((g, f)) => (*g, Some(*f)),
        None => (alone, None),
    };
    // Where no force part is kept (asymmetry holds what it would take, or
    // it is refused on its own), the start beyond a constant means nothing:
    // it must then be significant alone or beside asymmetry, each refitted,
    // since its option takes the start alone off (a record with asymmetry of
    // 0.3 hidden starting 0.5 mm off: the start alone fits worse, the start
    // beyond a constant was named; with asymmetry left out of the
    // candidates, the constant, not read at rest, was kept beside it).
    let beside_asymmetry = match &asymmetry {
        Asymmetry::Refitted(a) if force.is_none() => a.start_gain(d, scale),
        _ => None,
    };
    let significant = if force.is_none() {
        alone.significant() || beside_asymmetry.as_ref().is_some_and(Gain::significant)
    } else {
        named
    };
    // Named beside asymmetry only: the check's numbers are the start's there.
    let reported = match beside_asymmetry {
        Some(b) if significant && !alone.significant() => b,
        _ => gain,
    };
    let f0 = problem.exp.output[0];
    let peak_f = peak(&d.force);
    let (du, df) = (decimals(peak(&problem.exp.input)), decimals(peak_f));
    let taken = match force {
        None => String::new(),
        Some(ForcePart::Constant(f)) => format!(
            " with a constant force of {f:+.df$} kN ({:+.1}% of the peak) taken off as well",
            100.0 * f / peak_f
        ),
        Some(ForcePart::Line([a, b])) => format!(
            " with a line taken off the force as well ({a:+.df$} kN at the first sample, \
             {b:+.df$} kN at the last: the load cell's zero moves by {:+.1}% of the peak force; \
             the line removes {:.1}% of the squared error the start alone leaves, delta-BIC \
             {:+.0}, a BIC change of {:+.0} beyond a constant)",
            100.0 * (b - a) / peak_f,
            line_gain.as_ref().map_or(f64::NAN, |g| 100.0 * g.share),
            line_gain.as_ref().map_or(f64::NAN, |g| g.delta_bic),
            slope.as_ref().map_or(f64::NAN, |g| g.delta_bic)
        ),
    };
    let with_asymmetry = match (&asymmetry, &beside_asymmetry) {
        (Asymmetry::Refitted(a), Some(b)) => a.alone_nrmse.map_or(String::new(), |alone| {
            format!(
                " Beside asymmetry, the start takes the NRMSE from {alone:.4} to {:.4} ({:.1}% \
                 of the squared error; delta-BIC {:+.0}).",
                a.nrmse,
                100.0 * b.share,
                b.delta_bic
            )
        }),
        _ => String::new(),
    };
    let beside = match (&asymmetry, refused) {
        (Asymmetry::Refitted(a), Some((g, f))) => format!(
            " {} beside it would reach {:.4}, but asymmetry, refitted from rest there, reaches \
             {:.4}: a load cell whose zero is off looks like unequal strength in the two \
             directions, and the force is left as measured.",
            f.capitalised(),
            g.nrmse_with,
            a.nrmse,
        ),
        (Asymmetry::Refitted(a), None) => force.map_or(String::new(), |f| {
            format!(
                " Asymmetry, refitted from rest there, reaches {:.4}: no better than {}, which \
                 is not a parameter of the model.",
                a.nrmse,
                f.name()
            )
        }),
        (Asymmetry::NotWeighed, _) if line_part.is_some() => " A line in the force beside it is \
             not kept: asymmetry, which can stand in for a load cell's drift, was not weighed \
             (add it to --candidates to compare)."
            .into(),
        (Asymmetry::InModel, _) if line_part.is_some() => " A line in the force beside it is \
             not kept: the model's asymmetry, fitted with the start, follows a load cell's drift \
             in part and took up part of the line (weigh it on a model without asymmetry)."
            .into(),
        _ => String::new(),
    };
    // A constant refused for what the refit reads at rest, said beside
    // whatever was said of the line.
    let not_at_rest = if force.is_none() && named && constant_weighed && !at_rest {
        format!(
            " A constant force of {:+.df$} kN beside it is not taken off{}: {}",
            -m,
            if beside.is_empty() { "" } else { " either" },
            match early {
                Some((e, n)) => format!(
                    "at rest, over the first {n} samples of the refit, the record reads \
                     {:+.df$} kN off, less than {:.0}% of it, so the constant is a lopsided \
                     misfit, not the load cell's zero.",
                    -e,
                    100.0 * START_SHARE
                ),
                None => "the refit does not pass through rest early enough to read the load \
                         cell's zero."
                    .into(),
            }
        )
    } else {
        String::new()
    };
    let verdict = if !significant {
        match &beside_asymmetry {
            Some(b) => b.not_significant(),
            None => gain.not_significant(),
        }
    } else {
        let also = match force {
            None => String::new(),
            Some(ForcePart::Constant(f)) => format!(" --subtract force={f:.df$}"),
            Some(ForcePart::Line([a, b])) => format!(" --subtract force={a:.df$}..{b:.df$}"),
        };
        format!(
            "{START_REMEDY}, run again with `--subtract displacement={u0:.du$}{also}` (effects \
             named for this record may stand in for the offset); if the specimen was loaded \
             before the record starts, the model cannot know its state and the first cycles will \
             fit less well."
        )
    };
    let evidence = format!(
        "The record starts at displacement {u0:+.du$} mm ({:+.1}% of its peak) and force \
         {f0:+.df$} kN; the models start at rest at zero, so their first step is a jump of \
         {u0:+.du$} mm. Refitted from rest at the first sample{taken}, the model takes {}.\
         {beside}{not_at_rest}{with_asymmetry} {verdict}",
        100.0 * relative,
        gain.words(nrmse)
    );
    Some(OffsetCheck {
        offset: Offset::Start,
        model: problem.par.spec.to_string(),
        significant,
        value: u0,
        relative,
        with_force: match force {
            Some(ForcePart::Constant(f)) => Some(f),
            _ => None,
        },
        line: None,
        force_line: match force {
            Some(ForcePart::Line(l)) => Some(l),
            _ => None,
        },
        share: reported.share,
        nrmse_with: reported.nrmse_with,
        delta_bic: reported.delta_bic,
        n_eff: reported.n_eff,
        asymmetry_nrmse: match &asymmetry {
            Asymmetry::Refitted(a) => Some(a.nrmse),
            _ => None,
        },
        evidence,
    })
}

/// Asymmetry weighed against the force a named start's refit takes off
/// beside it ([`start`]).
enum Asymmetry {
    /// Not weighed against the force, or it cannot be fitted: nothing to
    /// hold the force against.
    Absent,
    /// In the model already, fitted with the start's jump: it took up part
    /// of what a line would take (a 3% force offset beside a start on a
    /// record with asymmetry hidden was printed as a drift of 2.9% of the
    /// peak force, running against the offset: found by review), so a
    /// constant is kept, a line not.
    InModel,
    /// Not among the candidates weighed.
    NotWeighed,
    /// Refitted from rest at the first sample.
    Refitted(AsymmetryFromRest),
}

/// Asymmetry refitted from rest at a record's first sample.
struct AsymmetryFromRest {
    /// Its NRMSE.
    nrmse: f64,
    /// Its residual.
    residual: Vec<f64>,
    /// The NRMSE and residual of asymmetry refitted from the jump, as the
    /// suspects weighed it.
    alone_nrmse: Option<f64>,
    alone: Option<Vec<f64>>,
}

impl AsymmetryFromRest {
    /// What the start adds to asymmetry, on the record diagnosed as `d`.
    fn start_gain(&self, d: &Diagnosis, scale: Scale) -> Option<Gain> {
        let alone = self.alone.as_deref()?;
        Gain::of(d, self.alone_nrmse?, alone, &self.residual, 1, scale)
    }
}

impl Asymmetry {
    /// Asymmetry added to the start's refit `from_rest` of `shifted` (the
    /// record moved to rest at its first sample), where `suspects` weighed
    /// it.
    fn beside_start(shifted: &Problem, from_rest: &Outcome, suspects: &[Suspect]) -> Self {
        let effect = EffectRef::Builtin(EffectKind::Asymmetry);
        if shifted.par.spec.contains(effect) {
            return Asymmetry::InModel;
        }
        let Some(weighed) = asymmetry_refit(suspects) else {
            return Asymmetry::NotWeighed;
        };
        let starts = WeighOptions::default().starts;
        let refit = suspects::refit(shifted, from_rest, effect, starts, &[], false).ok();
        let fitted = refit.and_then(|(p, o)| Some((o.scores.nrmse, residual(&p, &o.x)?)));
        let Some((nrmse, residual_from_rest)) = fitted else {
            return Asymmetry::Absent;
        };
        let alone = weighed.refit.as_ref().and_then(|(p, o)| residual(p, &o.x));
        Asymmetry::Refitted(AsymmetryFromRest {
            nrmse,
            residual: residual_from_rest,
            alone_nrmse: alone.as_ref().map(|_| weighed.nrmse_with),
            alone,
        })
    }

    /// Whether a force part reaching `nrmse` may be kept beside the start:
    /// where asymmetry, refitted, fits no better, and, for a `line`, where
    /// something held it against asymmetry (as the force drift's check asks).
    fn admits(&self, nrmse: f64, line: bool) -> bool {
        match self {
            Asymmetry::Absent => true,
            Asymmetry::InModel | Asymmetry::NotWeighed => !line,
            Asymmetry::Refitted(a) => nrmse <= a.nrmse,
        }
    }
}

/// What a named start's refit takes off the force beside it ([`start`]).
#[derive(Clone, Copy)]
enum ForcePart {
    /// A constant (kN).
    Constant(f64),
    /// A line: the load cell's zero at the first and at the last sample (kN).
    Line([f64; 2]),
}

impl ForcePart {
    /// What is taken off, in words.
    fn name(self) -> &'static str {
        match self {
            ForcePart::Constant(_) => "a constant force",
            ForcePart::Line(_) => "a line in the force",
        }
    }

    /// [`ForcePart::name`] opening a sentence.
    fn capitalised(self) -> &'static str {
        match self {
            ForcePart::Constant(_) => "A constant force",
            ForcePart::Line(_) => "A line in the force",
        }
    }
}

/// How a named start's advice begins: [`yield_start`] replaces it.
const START_REMEDY: &str = "If the displacement transducer's zero is off";

/// Unnames the start away from rest `start` for the drifting displacement
/// zero `drift`, which fits decisively better and whose first end holds the
/// start (a drift of 0.5 mm over an irregular record starting 0.016 mm off,
/// the noise: the start, refitted with a constant force, was named for it).
pub(super) fn yield_start(start: &mut OffsetCheck, drift: &OffsetCheck) {
    if let Some(at) = start.evidence.find(START_REMEDY) {
        start.evidence.truncate(at);
    }
    start.evidence.push_str(&format!(
        "Not named: a line in the displacement (above) fits decisively better (delta-BIC {:+.0} \
         against {:+.0}), and its first end holds the start.",
        drift.delta_bic, start.delta_bic
    ));
    start.significant = false;
}

/// The checks of one record: a force offset, a start away from rest, a
/// drifting force zero.
#[derive(Clone, Debug, Default)]
pub struct Offsets {
    /// [`force`].
    pub force: Option<OffsetCheck>,
    /// [`start`].
    pub start: Option<OffsetCheck>,
    /// [`drift`].
    pub drift: Option<OffsetCheck>,
    /// [`displacement_drift::check`].
    pub displacement_drift: Option<OffsetCheck>,
}

/// The checks on one diagnosed fit (`hyst diagnose`).
pub fn of_fit(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
) -> Offsets {
    if problem.exp.drive != Drive::Displacement {
        return Offsets::default();
    }
    let model = problem.par.spec.to_string();
    let mut start = start(problem, outcome, d, suspects);
    let displaced = displacement_drift::check(problem, outcome, d, suspects, start.as_ref());
    let named = settle_start(&mut start, displaced.as_ref());
    let nrmse = outcome.scores.nrmse;
    let drift = drift(
        problem.par.spec,
        d,
        nrmse,
        suspects,
        start.as_ref().filter(|_| named),
        displaced.as_ref(),
    );
    let drifts = named_drift(&drift, &displaced);
    Offsets {
        force: force(&model, d, nrmse, suspects, named, drifts),
        drift,
        displacement_drift: displaced,
        start,
    }
}

/// The checks along a discovery: the force offset and drift on the step from which
/// the ladder added asymmetry (where it was the strongest significant
/// suspect), else on the final model; the start on the first model, before
/// any effect could stand in for it, and on the final one, whose whiter
/// residual weighs it more surely, keeping the stronger evidence (a record
/// with a force and a displacement offset and degradation hidden: delta-BIC
/// -9 on `bw`, found by review).
pub fn of_ladder(discovery: &Discovery) -> Offsets {
    let first = &discovery.steps[0];
    if first.problem.exp.drive != Drive::Displacement {
        return Offsets::default();
    }
    let asymmetric = discovery.steps.iter().find(|s| {
        s.suspects
            .iter()
            .find(|x| x.significant)
            .is_some_and(is_asymmetry)
    });
    let last = discovery.last();
    let on = asymmetric.unwrap_or(last);
    let start_on = |s: &Step| start(&s.problem, &s.outcome, &s.diagnosis, &s.suspects);
    let mut starts = vec![start_on(first)];
    if discovery.steps.len() > 1 {
        starts.push(start_on(last));
    }
    let mut start = starts
        .into_iter()
        .flatten()
        .min_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic));
    let (model, nrmse) = (on.spec.to_string(), on.outcome.scores.nrmse);
    let displaced = displacement_drift::check(
        &on.problem,
        &on.outcome,
        &on.diagnosis,
        &on.suspects,
        start.as_ref(),
    );
    let named = settle_start(&mut start, displaced.as_ref());
    let drift = drift(
        on.spec,
        &on.diagnosis,
        nrmse,
        &on.suspects,
        start.as_ref().filter(|_| named),
        displaced.as_ref(),
    );
    let drifts = named_drift(&drift, &displaced);
    Offsets {
        force: force(&model, &on.diagnosis, nrmse, &on.suspects, named, drifts),
        drift,
        displacement_drift: displaced,
        start,
    }
}

/// Which drift is named, if any.
fn named_drift<'a>(
    force: &'a Option<OffsetCheck>,
    displacement: &'a Option<OffsetCheck>,
) -> Option<&'a OffsetCheck> {
    [force, displacement]
        .into_iter()
        .flatten()
        .find(|c| c.significant)
}

/// Whether the start away from rest stays named beside the drifting
/// displacement zero `displaced`, which was weighed against it (a named drift
/// fitted decisively better: the start yields).
fn settle_start(start: &mut Option<OffsetCheck>, displaced: Option<&OffsetCheck>) -> bool {
    match (start.as_mut(), displaced) {
        (Some(s), Some(d)) if s.significant && d.significant => {
            yield_start(s, d);
            false
        }
        (s, _) => s.is_some_and(|s| s.significant),
    }
}

fn is_asymmetry(s: &Suspect) -> bool {
    s.effect == EffectRef::Builtin(EffectKind::Asymmetry)
}
