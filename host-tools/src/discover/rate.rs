//! Rate dependence: an effect the library does not model, looked for so that
//! the diagnosis can name it instead of pinning the error on an effect it does
//! model.
//!
//! A viscous force grows with the speed of loading (a dashpot, the fluid of a
//! damper, strain-rate effects); the Bouc-Wen models are rate independent, so
//! a fit to a record with one bends its loop towards the dashpot's: wider,
//! and, where effects are on offer, pinched or degraded to follow the speed.
//! The check therefore refits the model with a dashpot `c v` in parallel
//! (`v = du/dt` by central differences): for each trial `c` the force
//! `F - c v` is refitted by least squares from the fitted parameters, and
//! `c` is searched (doubled from a first guess while the fit improves, then
//! narrowed by golden sections) for the best fit. Only a dissipating `c > 0`
//! is tried: `c < 0` would feed energy in, which no material does.
//!
//! The gain is weighed like an offset's (see [`offset`](super::offset): one
//! added number, significant below a BIC change of -10 and at least
//! [`MIN_SHARE`](super::offset::MIN_SHARE) of the squared error), and, as a
//! lag is (see [`lag`](super::lag)), named only where the model with the
//! dashpot fits at least as well as the best candidate effect refitted on the
//! same model: an effect the dashpot resembles must then explain the record
//! no better than one number that is not a parameter of the model.
//!
//! Measured on the review's records (a base `bw` model, 1.5% force noise,
//! noise floor NRMSE 0.022-0.027; scratch): a dashpot whose force reaches a
//! fifth of the peak, on a sine history, was taken as pinching and asymmetry
//! by the ladder (NRMSE 0.0406 to 0.0305) while the regression of the
//! residual on the speed that this check replaced found 0.4% of the squared
//! error; a dashpot of four times that was not named at all (`bw` left at
//! 0.113). That regression stood beside terms a rate-independent misfit
//! leaves (`sgn(v)`, `sgn(v)` times the amplitude), which on a sine take up
//! most of `c v`, and the fit had already absorbed part of the dashpot. The
//! refit names both: c = 0.48 for 0.5 (`bw` with the dashpot alone at
//! 0.0230) and c = 2.000 for 2.0 (0.1132 to 0.0262), and 0.73 for 0.7 on
//! triangular cycles; on twelve records without a dashpot (nothing,
//! pinching, strength or stiffness degradation, asymmetry or a gap hidden)
//! it names none.

use super::diagnosis::Diagnosis;
use super::ladder::{Discovery, Step};
use super::lag::best_effect;
use super::offset::{refit_residual, scale_of, Gain};
use super::suspects::Suspect;
use crate::data::speed;
use crate::fit::experiment::Drive;
use crate::fit::objectives::{Target, ENVELOPE_FLOOR};
use crate::fit::problem::Problem;
use crate::fit::run::Outcome;
use serde::Serialize;

/// Golden sections after the bracket: it narrows to 2.1% of its width.
const SECTIONS: usize = 8;

/// Most doublings (or halvings) of the first guess while bracketing the best
/// `c`: a factor of 4096 either way.
const DOUBLINGS: usize = 12;

/// The likelihood ratio at the ends of the interval given for `c`: chi-squared
/// with one degree of freedom at 95% (its square root, 1.96, is what the
/// search for the ends solves for).
const CHI2_95: f64 = 3.841_458_820_694_124;

/// Refits spent on each end of the interval for `c`.
const END_REFITS: usize = 8;

/// What the record says about rate dependence.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct RateCheck {
    /// The model whose fit was checked.
    pub model: String,
    /// Named: see the module docs for the rule.
    pub significant: bool,
    /// The viscous coefficient `c` of the best refit, force per
    /// (displacement/s) (kN s/mm for kN and mm): the model lacks `c v`.
    pub viscous: f64,
    /// Where the record places `c`: the coefficients whose refit fits no
    /// worse than the best by a likelihood ratio of 3.84 (`n_eff ln(S(c) /
    /// S(best)) <= 3.84`, chi-squared with one degree of freedom at 95%,
    /// the model refitted at every `c`). Given where the dashpot is named.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub viscous_interval: Option<[f64; 2]>,
    /// Share of the squared error the dashpot removes.
    pub share: f64,
    /// NRMSE of the model refitted with `c v`.
    pub nrmse_with: f64,
    /// BIC change from adding `c v` (one added number).
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

/// `problem` with the dashpot's force `c v` taken off the measured force.
fn without_dashpot(problem: &Problem, v: &[f64], c: f64) -> Problem {
    let mut p = problem.clone();
    for (f, v) in p.exp.output.iter_mut().zip(v) {
        *f -= c * v;
    }
    p.target = Target::new(&p.exp, ENVELOPE_FLOOR);
    p
}

/// One dashpot refitted: its coefficient, the refit's residual and squared
/// error (infinite where the refit fails).
struct Trial {
    c: f64,
    after: Vec<f64>,
    squared: f64,
}

impl Trial {
    fn run(problem: &Problem, x0: &[f64], v: &[f64], c: f64) -> Trial {
        let after = refit_residual(&without_dashpot(problem, v, c), x0).unwrap_or_default();
        let squared = after.iter().map(|r| r * r).sum::<f64>();
        Trial {
            c,
            squared: if after.is_empty() || !squared.is_finite() {
                f64::INFINITY
            } else {
                squared
            },
            after,
        }
    }
}

/// The best dashpot for the fit `x0` of `problem`, diagnosed as `d`: from
/// the first guess, the residual's own regression on `v`
/// (where that dissipates) or a viscous force of 1% of the record's, doubled
/// while the fit improves (halved while it does not improve on `c = 0`),
/// then narrowed by [`SECTIONS`] golden sections. `None` where no `c > 0`
/// improves on the fit.
fn search(problem: &Problem, x0: &[f64], d: &Diagnosis, v: &[f64]) -> Option<Trial> {
    let rv = (v.iter().map(|v| v * v).sum::<f64>() / v.len() as f64).sqrt();
    // The force's RMS, as the fit's target already holds it.
    let rf = problem.target.rms;
    if !(rv > 0.0 && rf > 0.0) {
        return None;
    }
    let zero = d.total_sq;
    // The model's force is measured + r, so the missing force is -r ≈ c v.
    let regressed =
        -d.residual.iter().zip(v).map(|(r, v)| r * v).sum::<f64>() / (rv * rv * v.len() as f64);
    let guess = regressed.max(0.01 * rf / rv);
    let run = |c: f64| Trial::run(problem, x0, v, c);
    let mut best = run(guess);
    let mut halvings = 0;
    while best.squared >= zero {
        if halvings == DOUBLINGS {
            return None;
        }
        halvings += 1;
        best = run(best.c / 2.0);
    }
    // Bracket `[lo, hi]` around `best`, both ends fitting worse (`c = 0` is
    // the fit itself).
    let (mut lo, mut hi) = (0.0, 2.0 * best.c);
    if halvings == 0 {
        for _ in 0..DOUBLINGS {
            let next = run(2.0 * best.c);
            hi = next.c;
            if next.squared >= best.squared {
                break;
            }
            lo = best.c;
            best = next;
        }
    }
    let phi = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (run(hi - phi * (hi - lo)), run(lo + phi * (hi - lo)));
    for _ in 0..SECTIONS {
        if a.squared <= b.squared {
            hi = b.c;
            b = a;
            a = run(hi - phi * (hi - lo));
        } else {
            lo = a.c;
            a = b;
            b = run(lo + phi * (hi - lo));
        }
    }
    [a, b]
        .into_iter()
        .fold(best, |m, t| if t.squared < m.squared { t } else { m })
        .into()
}

/// The profile interval of `c` around the best refit `best` (see
/// [`RateCheck::viscous_interval`]), `zero` the fit's squared error without a
/// dashpot and `n_eff` the effective sample size the gain was weighed with.
/// On either side the root of `h(c) = sqrt(n_eff ln(S(c) / S(best))) - 1.96`
/// is found by regula falsi (the Illinois variant; `h` is near linear in `c`
/// where `S` is near quadratic), bracketed below by `c = 0` and above by
/// stepping out from `best` in steps that double; at most [`END_REFITS`]
/// refits an end. `None` where an end cannot be bracketed or a refit fails.
fn interval(
    problem: &Problem,
    x0: &[f64],
    v: &[f64],
    best: &Trial,
    zero: f64,
    n_eff: f64,
) -> Option<[f64; 2]> {
    let target = CHI2_95.sqrt();
    let h = |squared: f64| (n_eff * (squared / best.squared).ln()).max(0.0).sqrt() - target;
    let at = |c: f64| h(Trial::run(problem, x0, v, c).squared);
    let h_zero = h(zero);
    if h_zero <= 0.0 {
        return None;
    }
    let lower = root(&at, (0.0, h_zero), (best.c, -target))?;
    let mut step = best.c - lower;
    let mut out = (best.c + step, at(best.c + step));
    let mut inside = (best.c, -target);
    let mut steps = 1;
    while out.1 <= 0.0 {
        if steps == END_REFITS {
            return None;
        }
        inside = out;
        step *= 2.0;
        out = (best.c + step, at(best.c + step));
        steps += 1;
    }
    let upper = root(&at, out, inside)?;
    Some([lower, upper])
}

/// The root of `h` between `(a, h(a))` and `(b, h(b))` of opposite signs by
/// the Illinois variant of regula falsi: [`END_REFITS`] evaluations, or
/// fewer where `|h|` falls below 0.01 (the likelihood ratio within 0.04 of
/// its target). `None` where an end or a value between is not finite (a
/// refit that failed: no line to interpolate on).
fn root(h: &impl Fn(f64) -> f64, a: (f64, f64), b: (f64, f64)) -> Option<f64> {
    if !(a.1.is_finite() && b.1.is_finite()) {
        return None;
    }
    let (mut a, mut b) = (a, b);
    let mut side = 0i8;
    for _ in 0..END_REFITS {
        let c = (a.0 * b.1 - b.0 * a.1) / (b.1 - a.1);
        let hc = h(c);
        if !hc.is_finite() {
            return None;
        }
        if hc.abs() < 0.01 {
            return Some(c);
        }
        if (hc > 0.0) == (a.1 > 0.0) {
            a = (c, hc);
            if side == -1 {
                b.1 /= 2.0;
            }
            side = -1;
        } else {
            b = (c, hc);
            if side == 1 {
                a.1 /= 2.0;
            }
            side = 1;
        }
    }
    Some((a.0 * b.1 - b.0 * a.1) / (b.1 - a.1))
}

/// The check on one fit (`hyst diagnose`): `outcome` of `problem`,
/// diagnosed as `d`, its candidates weighed as `suspects`, the record sampled
/// at `time`. Displacement-driven records with a time base only. A named
/// dashpot's evidence ends with the option that takes it off the record.
pub fn of_fit(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
    time: &[f64],
) -> Option<RateCheck> {
    let mut check = weighed(problem, outcome, d, suspects, time)?;
    if check.significant {
        check.evidence.push_str(&remedy(check.viscous));
    }
    Some(check)
}

/// What takes a dashpot of `c` off the record, as a sentence.
fn remedy(c: f64) -> String {
    format!(" `--dashpot {c:.4e}` takes it off the force as the record is read.")
}

/// The check on one fit, as [`of_fit`] says, without the remedy.
fn weighed(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
    time: &[f64],
) -> Option<RateCheck> {
    if problem.exp.drive != Drive::Displacement {
        return None;
    }
    let v = speed::of(&problem.exp.input, time)?;
    let nrmse = outcome.scores.nrmse;
    let model = problem.par.spec.to_string();
    let speeds: Vec<f64> = v.iter().map(|v| v.abs()).filter(|v| *v > 0.0).collect();
    let (slow, fast) = quantiles(&speeds);
    let speed = format!(
        "The speed of loading ranges from {slow:.3e} to {fast:.3e} (10th to 90th percentile)."
    );
    let best_effect = best_effect(suspects);
    let Some(trial) = search(problem, &outcome.x, d, &v) else {
        return Some(RateCheck {
            model: model.clone(),
            significant: false,
            viscous: 0.0,
            viscous_interval: None,
            share: 0.0,
            nrmse_with: nrmse,
            delta_bic: 0.0,
            n_eff: scale_of(suspects).unwrap_or(0.0),
            best_effect,
            evidence: format!(
                "With a dashpot c v in parallel and {model} refitted, every c > 0 tried fits \
                 worse than {model} alone. {speed} Not significant: the record does not ask for \
                 a viscous force."
            ),
        });
    };
    let gain = Gain::of(d, nrmse, &d.residual, &trial.after, 1, scale_of(suspects))?;
    let at_least_as_good = best_effect
        .as_ref()
        .is_none_or(|(_, e)| gain.nrmse_with <= *e);
    let significant = gain.significant() && at_least_as_good;
    let c = trial.c;
    let viscous_interval = significant
        .then(|| interval(problem, &outcome.x, &v, &trial, d.total_sq, gain.n_eff))
        .flatten();
    let placed = match viscous_interval {
        Some([lo, hi]) => format!(
            "; the record places it between {lo:.4e} and {hi:.4e}, where the refit's likelihood \
             ratio to the best stays below 3.84 (95%)"
        ),
        None => String::new(),
    };
    let verdict = if significant {
        let effect = match &best_effect {
            Some((name, e)) => format!(
                "The best effect refitted instead, {name}, reaches {e:.4}: no better than this \
                 one number, which is not a parameter of the model. "
            ),
            None => String::new(),
        };
        format!(
            "{effect}No effect in the library grows with speed: the models here are rate \
             independent, so model it outside them (a dashpot in parallel, a rate-dependent \
             law)."
        )
    } else if !gain.significant() {
        gain.not_significant()
    } else {
        let (name, e) = best_effect.clone().unwrap_or_default();
        format!("Not named: {name}, refitted instead, reaches {e:.4}, better than a dashpot does.")
    };
    Some(RateCheck {
        model: model.clone(),
        significant,
        viscous: c,
        viscous_interval,
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        best_effect,
        evidence: format!(
            "With a dashpot c v in parallel (c = {c:.4e} force per displacement/s, the best \
             found{placed}; v the speed by central differences) and {model} refitted, the fit \
             takes {}. {speed} {verdict}",
            gain.words(nrmse)
        ),
    })
}

/// The check along a discovery: on the first model, before any effect could
/// stand in for a dashpot (pinching and asymmetry took a sine record's
/// dashpot on `bw`, found by review), and on the final one, whose effects it
/// must beat as well. A check named on the final model is kept; else one
/// named on the first where the dashpot alone fits it no worse than the
/// effects the loop added fit the final model; else the final model's. Where
/// the dashpot alone does that, the evidence says the effects may stand in
/// for it.
pub fn of_ladder(discovery: &Discovery, time: &[f64]) -> Option<RateCheck> {
    let on = |s: &Step| weighed(&s.problem, &s.outcome, &s.diagnosis, &s.suspects, time);
    let first_step = &discovery.steps[0];
    let first = on(first_step);
    let last_step = discovery.last();
    let nrmse = last_step.outcome.scores.nrmse;
    let stands_in = first
        .clone()
        .filter(|f| discovery.steps.len() > 1 && f.significant && f.nrmse_with <= nrmse);
    let mut kept = if discovery.steps.len() == 1 {
        first
    } else {
        match (first, on(last_step)) {
            (_, Some(l)) if l.significant => Some(l),
            (Some(f), _) if stands_in.is_some() => Some(f),
            (Some(f), Some(l)) if !f.significant && f.delta_bic < l.delta_bic => Some(f),
            (f, l) => l.or(f.filter(|f| !f.significant)),
        }
    };
    if let Some(k) = kept.as_mut().filter(|k| k.significant) {
        let Some(f) = stands_in else {
            k.evidence.push_str(&remedy(k.viscous));
            return kept;
        };
        let added: Vec<&str> = last_step
            .spec
            .effects()
            .iter()
            .filter(|e| !first_step.spec.effects().contains(e))
            .map(|e| e.name())
            .collect();
        k.evidence.push_str(&format!(
            " On {}, the model the loop started from, the dashpot alone (c = {:.4e}) takes the \
             NRMSE to {:.4}, no worse than {} reaches without it ({nrmse:.4}): the effects the \
             loop added ({}) may stand in for the dashpot.{} Run again with it to see which of \
             them the record needs beside it.",
            f.model,
            f.viscous,
            f.nrmse_with,
            last_step.spec,
            added.join(", "),
            remedy(f.viscous),
        ));
    }
    kept
}

/// The 10th and 90th percentiles (0 for an empty slice).
fn quantiles(x: &[f64]) -> (f64, f64) {
    if x.is_empty() {
        return (0.0, 0.0);
    }
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let at = |q: f64| s[((s.len() - 1) as f64 * q).round() as usize];
    (at(0.1), at(0.9))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// The Illinois variant finds a root that plain regula falsi approaches
    /// from one side only (a convex function), within the tolerance on `h`
    /// and the budget of evaluations.
    #[test]
    fn the_ends_of_the_interval_are_roots_of_the_likelihood_ratio() {
        let calls = Cell::new(0);
        let h = |c: f64| {
            calls.set(calls.get() + 1);
            c * c * c - 0.125
        };
        let c = root(&h, (0.0, h(0.0)), (1.0, h(1.0))).unwrap();
        // |h| < 0.01 puts c within 0.01 / h'(0.5) = 0.0133 of 0.5.
        assert!((c - 0.5).abs() < 0.0134, "{c}");
        assert!(calls.get() <= 2 + END_REFITS, "{} calls", calls.get());
        // Either order of the bracket.
        let d = root(&h, (1.0, h(1.0)), (0.0, h(0.0))).unwrap();
        assert!((d - 0.5).abs() < 0.0134, "{d}");
        // A refit that fails is no root, between the ends or at one (the
        // upper end stepped out to a failed refit is not interpolated on).
        assert_eq!(root(&|_| f64::INFINITY, (0.0, -1.0), (1.0, 1.0)), None);
        calls.set(0);
        assert_eq!(root(&h, (0.0, -0.125), (1.0, f64::INFINITY)), None);
        assert_eq!(
            calls.get(),
            0,
            "no refit at a point interpolated on infinity"
        );
    }
}
