//! A drifting displacement zero: a transducer whose zero moves along the test
//! (a displacement transducer creeping, a reference frame settling), which no
//! effect of the library models, told apart from a drifting load cell (see
//! [`offset::drift`](super::offset::drift)), whose straight line in the force
//! it otherwise resembles (found by review: a displacement drift of 1.5 mm
//! over a test whose yield displacement is 3 mm was named a force drift, and
//! the printed option left NRMSE 0.0178 where taking the line off the
//! displacement gave the clean 0.0166).
//!
//! The two leave different residuals. A load cell's drift adds the same force
//! at every point of a loop. A displacement drift `d` shifts the loop along
//! the displacement: the model fed the measured displacement is off by about
//! its tangent stiffness times `d`, most on the elastic branches and hardly
//! at all where the force yields, and its first step carries the line's
//! start. So the check estimates the line in the sample number that, taken
//! off the displacement, fits best (Gauss-Newton on the line's two ends with
//! the model's parameters held, from finite differences of the model's force,
//! then the model refitted by least squares; two rounds), and weighs it
//! against the force line refitted the same way.
//!
//! It runs where a line in the force explains enough of the residual to be
//! weighed as the force drift is (a BIC change below -10 and
//! [`MIN_SHARE`](super::offset::MIN_SHARE) of the squared error): a drift in
//! either channel leaves one. It is named where the displacement line is
//! significant against the fit as it was (two numbers), fits decisively
//! better than the force line refitted (a BIC change below -10 at equal
//! count), adds a BIC change below -10 to a constant force alone, fits at
//! least as well as the best candidate effect refitted (asymmetry among them,
//! which must have been weighed or be in the model, as for the force drift),
//! neither end of the line is beyond [`RUNS_OFF`] of the peak displacement,
//! and the start away from rest is not named or the line's BIC change is
//! more than 10 below the start's (the line's first end holds a start; the
//! start is then not named and says why).

use super::diagnosis::Diagnosis;
use super::offset::{
    asymmetry_known, decimals, peak, refit_residual, scale_of, Gain, Offset, OffsetCheck,
    ResidualLine,
};
use super::signature::mean;
use super::suspects::{residual, Suspect, SIGNIFICANT_BIC};
use crate::data::Baseline;
use crate::fit::experiment::Drive;
use crate::fit::problem::Problem;
use crate::fit::run::{self, Method, Outcome, Quiet};

/// Largest end of a line, as a fraction of the peak displacement, taken for
/// a drifting zero: a line found running further stands in for another
/// misfit (on the step before asymmetry was added, lines of 40% of the peak
/// displacement were printed as drifts; on real columns, 113%: found by
/// review), and no transducer's zero drifts that far unnoticed.
pub const RUNS_OFF: f64 = 0.25;

/// Gauss-Newton rounds (each followed by a refit of the model's parameters).
const ROUNDS: usize = 2;

/// The finite-difference step of the line's ends, as a fraction of the peak
/// displacement.
const STEP: f64 = 1e-3;

/// `problem` with `line` taken off its displacement, as `--subtract
/// displacement=FIRST..LAST` takes it off the record.
fn without(problem: &Problem, line: Baseline) -> Problem {
    let mut p = problem.clone();
    let n = p.exp.input.len();
    p.exp
        .input
        .iter_mut()
        .enumerate()
        .for_each(|(k, u)| *u -= line.at(k, n));
    p
}

/// The line that, taken off the displacement of `problem`, fits best, with
/// the residual of the model refitted to the record without it; from the
/// fitted parameters `x0`. `None` where a simulation or a refit fails or the
/// step is singular (a model with no stiffness to feel a displacement).
fn estimate(problem: &Problem, x0: &[f64]) -> Option<(Baseline, Vec<f64>)> {
    let n = problem.exp.input.len();
    let h = STEP * peak(&problem.exp.input);
    if n < 3 || h.is_nan() || h <= 0.0 {
        return None;
    }
    let mut line = Baseline::line(0.0, 0.0);
    let mut x = x0.to_vec();
    let mut r = residual(problem, &x)?;
    for _ in 0..ROUNDS {
        // Columns of the residual's derivative with respect to the line's
        // two ends, by forward differences.
        let column = |moved: Baseline| -> Option<Vec<f64>> {
            let moved = residual(&without(problem, moved), &x)?;
            Some(moved.iter().zip(&r).map(|(m, r)| (m - r) / h).collect())
        };
        let a = column(Baseline {
            first: line.first + h,
            ..line
        })?;
        let b = column(Baseline {
            last: line.last + h,
            ..line
        })?;
        let dot = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(p, q)| p * q).sum::<f64>();
        let (aa, ab, bb) = (dot(&a, &a), dot(&a, &b), dot(&b, &b));
        let (ar, br) = (dot(&a, &r), dot(&b, &r));
        let det = aa * bb - ab * ab;
        if det.is_nan() || det <= 1e-12 * aa * bb {
            return None;
        }
        line.first -= (bb * ar - ab * br) / det;
        line.last -= (aa * br - ab * ar) / det;
        let moved = without(problem, line);
        x = run::fit(&moved, Method::Lsq, &x, &Quiet).ok()?.x;
        r = residual(&moved, &x)?;
    }
    Some((line, r))
}

/// Looks for a drifting displacement zero in the displacement-driven fit
/// `outcome` of `problem`, diagnosed as `d`, whose candidate effects were
/// weighed as `suspects`; see the module docs for the rule. `None` where no
/// line in the force explains enough to weigh, for other drives, or where
/// the estimate fails.
pub fn check(
    problem: &Problem,
    outcome: &Outcome,
    d: &Diagnosis,
    suspects: &[Suspect],
    start: Option<&OffsetCheck>,
) -> Option<OffsetCheck> {
    if problem.exp.drive != Drive::Displacement {
        return None;
    }
    let r = &d.residual;
    let n = r.len();
    if n < 3 {
        return None;
    }
    let nrmse = outcome.scores.nrmse;
    let scale = scale_of(suspects);
    // The force line, as the force drift fits it.
    let fitted = ResidualLine::of(r);
    if !Gain::of(d, nrmse, r, &fitted.after, 2, scale)?.significant() {
        return None;
    }
    // The force line refitted: the model's parameters move with the line,
    // as they do with the displacement's (the force's zero at s is -at(s),
    // taken off the measured force).
    let mut forced = problem.clone();
    forced
        .exp
        .output
        .iter_mut()
        .zip(&fitted.s)
        .for_each(|(f, s)| *f += fitted.at(*s));
    let force_line = refit_residual(&forced, &outcome.x)?;
    let (found, after) = estimate(problem, &outcome.x)?;
    let m = mean(r);
    let constant: Vec<f64> = r.iter().map(|r| r - m).collect();
    let gain = Gain::of(d, nrmse, r, &after, 2, scale)?;
    let beyond_force = Gain::of(d, nrmse, &force_line, &after, 0, scale)?;
    let beyond_constant = Gain::of(d, nrmse, &constant, &after, 1, scale)?;
    let best = suspects
        .iter()
        .filter(|s| s.nrmse_with.is_finite())
        .min_by(|a, b| a.nrmse_with.total_cmp(&b.nrmse_with));
    let at_least_as_good = best.is_none_or(|b| gain.nrmse_with <= b.nrmse_with);
    let known = asymmetry_known(problem.par.spec, suspects);
    // A named start holds unless the line beats it decisively: the line's
    // first end can hold a start, and a start refitted with a constant force
    // can take up part of a drift.
    let start_named = start.filter(|s| s.significant);
    let start_holds = start_named.is_some_and(|s| gain.delta_bic >= s.delta_bic + SIGNIFICANT_BIC);
    let peak_u = peak(&problem.exp.input);
    let (first, last) = (found.first, found.last);
    let reach = first.abs().max(last.abs()) / peak_u;
    let runs_off = reach.is_nan() || reach > RUNS_OFF;
    let significant = !runs_off
        && gain.significant()
        && beyond_force.delta_bic < SIGNIFICANT_BIC
        && beyond_constant.delta_bic < SIGNIFICANT_BIC
        && known
        && at_least_as_good
        && !start_holds;
    let value = last - first;
    let relative = value / peak_u;
    let du = decimals(peak_u);
    let force_nrmse = Gain::of(d, nrmse, r, &force_line, 2, scale)?.nrmse_with;
    let mut evidence = format!(
        "A straight line in the sample number taken off the displacement ({first:+.du$} mm at \
         the first sample, {last:+.du$} mm at the last: the zero moves by {value:+.du$} mm, \
         {:+.1}% of the peak displacement) with the model refitted takes {}; the line in the \
         force, refitted the same way, reaches {force_nrmse:.4}, a BIC change of {:+.0} for \
         the displacement's at equal count.",
        100.0 * relative,
        gain.words(nrmse),
        beyond_force.delta_bic
    );
    evidence.push(' ');
    evidence.push_str(&if runs_off {
        format!(
            "Not named: the line reaches {:.0}% of the peak displacement, further than a \
             transducer's zero drifts unnoticed (at most {:.0}% is taken for a drift), so it \
             stands in for another misfit and its size means nothing.",
            100.0 * reach,
            100.0 * RUNS_OFF
        )
    } else if significant {
        let over_start = start_named.map_or(String::new(), |s| {
            format!(
                " It fits decisively better than the start away from rest (below; delta-BIC \
                 {:+.0}), which its first end holds.",
                s.delta_bic
            )
        });
        format!(
            "A load cell's drift adds the same force all round a loop; this one shifts the loop \
             along the displacement, as a displacement transducer whose zero drifts (creep, a \
             reference frame settling) does. No effect of the library drifts with time: check \
             the transducer before trusting an effect named for it, and run again with \
             `--subtract displacement={first:.du$}..{last:.du$}` to take it off.{over_start}"
        )
    } else if !gain.significant() {
        gain.not_significant()
    } else if beyond_force.delta_bic >= SIGNIFICANT_BIC {
        "Not named: the line in the force fits as well (weighed as the force drift).".into()
    } else if beyond_constant.delta_bic >= SIGNIFICANT_BIC {
        "Not named: a constant force explains it as well (weighed as the force offset).".into()
    } else if start_holds {
        "Not named: the record starts away from rest (below), and the line fits it no \
         decisively better."
            .into()
    } else if let Some(b) = best.filter(|_| !at_least_as_good) {
        format!(
            "Not named: {}, refitted, reaches {:.4}, better than the line does.",
            b.effect.name(),
            b.nrmse_with
        )
    } else {
        "Not named: asymmetry, which can stand in for a drift on a test of growing amplitude, \
         was not weighed (add it to --candidates to compare)."
            .into()
    });
    Some(OffsetCheck {
        offset: Offset::DisplacementDrift,
        model: problem.par.spec.to_string(),
        significant,
        value,
        relative,
        with_force: None,
        line: Some([first, last]),
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: None,
        evidence,
    })
}
