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
//! A load cell's zero can be off beside it. Each line estimated alone, a
//! force offset of 3% of the peak beside a displacement drift of 1.5 mm was
//! named a force drift, and the displacement's line came out at -1.31 mm
//! (found by review). So the line is estimated together with a constant
//! force, and with a line in the force, in the same Gauss-Newton steps (the
//! force's numbers enter them one for one); the force's part is kept where
//! it adds a BIC change below -10 to the simpler estimate, and the
//! displacement's line is then weighed against the force's part alone (the
//! force line or the constant, each refitted), at the numbers the estimate
//! adds beyond it, and must remove [`MIN_SHARE`] of what that leaves: the
//! load cell's error opened the check, and a small line in the displacement
//! can take up the model's own misfit (a force offset alone on a pinched
//! record was named a displacement drift of 0.23-0.33 mm beside it: found by
//! review).
//!
//! It runs where a line in the force explains enough of the residual to be
//! weighed as the force drift is (a BIC change below -10 and
//! [`MIN_SHARE`] of the squared error): a drift in
//! either channel leaves one. It is named where the estimate is significant
//! against the fit as it was (two numbers, three or four with the force's
//! part), fits decisively better than the force line refitted (a BIC change
//! below -10), adds a BIC change below -10 to a constant force refitted, fits at
//! least as well as the best candidate effect refitted (asymmetry among them,
//! which must have been weighed or be in the model, as for the force drift),
//! neither end of the line is beyond [`RUNS_OFF`] of the peak displacement,
//! and the start away from rest is not named or the line's BIC change is
//! more than 10 below the start's (the line's first end holds a start; the
//! start is then not named and says why).
//!
//! A named start opens the check too: a zero that drifts from 1.5 mm back
//! to zero beside a load cell's drift leaves a residual the start dominates,
//! where the force line explains too little, and was named a start with the
//! line not weighed (found by review). Beside a named start the line is
//! estimated from it (both ends at the first displacement, the model refitted
//! there), and its slope must be significant against the line's ends held
//! together at one value with the same part of the force (a BIC change below
//! -10 and [`MIN_SHARE`] of what that leaves).

use super::diagnosis::Diagnosis;
use super::offset::{
    asymmetry_known, decimals, peak, refit_residual, scale_of, Gain, Offset, OffsetCheck,
    ResidualLine, MIN_SHARE,
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

/// What a joint estimate takes off the force beside the displacement's line
/// (found by review: a displacement drift of 1.5 mm beside a force offset of
/// 3% of the peak, each line estimated alone, was named a force drift, and
/// the displacement's line alone came out at -1.31 mm).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ForcePart {
    /// Nothing.
    None,
    /// A constant force (a load cell's offset).
    Constant,
    /// A line in the sample number (a load cell's drift).
    Line,
}

impl ForcePart {
    /// The numbers it adds.
    fn count(self) -> usize {
        match self {
            ForcePart::None => 0,
            ForcePart::Constant => 1,
            ForcePart::Line => 2,
        }
    }
}

/// A line in the displacement estimated with what is taken off the force
/// beside it, and the residual of the model refitted to the record without
/// both.
struct Estimate {
    shape: Shape,
    part: ForcePart,
    displacement: Baseline,
    /// Taken off the measured force, as `--subtract force=` takes it off.
    force: Baseline,
    residual: Vec<f64>,
}

impl Estimate {
    /// The numbers estimated beside the model's parameters.
    fn count(&self) -> usize {
        self.shape.count() + self.part.count()
    }
}

/// `problem` with `displacement` taken off its displacement and `force` off
/// its force, as `--subtract` takes them off the record.
fn without(problem: &Problem, displacement: Baseline, force: Baseline) -> Problem {
    let mut p = problem.clone();
    let n = p.exp.input.len();
    p.exp
        .input
        .iter_mut()
        .enumerate()
        .for_each(|(k, u)| *u -= displacement.at(k, n));
    p.exp
        .output
        .iter_mut()
        .enumerate()
        .for_each(|(k, f)| *f -= force.at(k, n));
    p
}

/// Solves the normal equations `m x = b` (symmetric, at most a few
/// unknowns) by Cholesky's method; `None` where `m` is singular to within
/// 1e-12 of its diagonal.
fn solve_normal(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let k = b.len();
    for j in 0..k {
        let scale = m[j][j];
        for i in 0..j {
            m[j][j] -= m[j][i] * m[j][i];
        }
        if m[j][j].is_nan() || m[j][j] <= 1e-12 * scale {
            return None;
        }
        m[j][j] = m[j][j].sqrt();
        for i in j + 1..k {
            for l in 0..j {
                m[i][j] -= m[i][l] * m[j][l];
            }
            m[i][j] /= m[j][j];
        }
    }
    for i in 0..k {
        for l in 0..i {
            b[i] -= m[i][l] * b[l];
        }
        b[i] /= m[i][i];
    }
    for i in (0..k).rev() {
        for l in i + 1..k {
            b[i] -= m[l][i] * b[l];
        }
        b[i] /= m[i][i];
    }
    Some(b)
}

/// The residual's derivatives with respect to the line's two ends, by
/// forward differences of step `h`, at `displacement` and `force` taken off
/// `problem` with the parameters `x`, where the residual is `r`.
fn line_columns(
    problem: &Problem,
    x: &[f64],
    displacement: Baseline,
    force: Baseline,
    r: &[f64],
    h: f64,
) -> Option<[Vec<f64>; 2]> {
    let column = |moved: Baseline| -> Option<Vec<f64>> {
        let moved = residual(&without(problem, moved, force), x)?;
        Some(moved.iter().zip(r).map(|(m, r)| (m - r) / h).collect())
    };
    Some([
        column(Baseline {
            first: displacement.first + h,
            ..displacement
        })?,
        column(Baseline {
            last: displacement.last + h,
            ..displacement
        })?,
    ])
}

/// Where every estimate starts: the line taken off the displacement (none,
/// or a named start's constant), the parameters fitted there, their residual
/// and its derivatives with respect to the line's two ends, which the first
/// Gauss-Newton round of every force's part shares; with the difference step.
struct Origin {
    displacement: Baseline,
    x: Vec<f64>,
    residual: Vec<f64>,
    columns: [Vec<f64>; 2],
    h: f64,
}

impl Origin {
    /// At nothing taken off: the fit `x` as it was, whose residual is
    /// `residual`. `None` where the record is too short, has no displacement
    /// to step or cannot be simulated.
    fn of(problem: &Problem, x: &[f64], residual: &[f64]) -> Option<Self> {
        let zero = Baseline::line(0.0, 0.0);
        Self::with(problem, zero, x.to_vec(), residual.to_vec())
    }

    /// At a start away from rest `u0` taken off the displacement, with the
    /// model refitted there from `x`: a drift that starts away from zero is
    /// a start whose zero then moves, and a line estimated from nothing
    /// taken off must first climb to it through the model's jump at the
    /// first sample.
    fn at_start(problem: &Problem, x: &[f64], u0: f64) -> Option<Self> {
        let start = Baseline::line(u0, u0);
        let moved = without(problem, start, Baseline::line(0.0, 0.0));
        let x = run::fit(&moved, Method::Lsq, x, &Quiet).ok()?.x;
        let residual = residual(&moved, &x)?;
        Self::with(problem, start, x, residual)
    }

    fn with(
        problem: &Problem,
        displacement: Baseline,
        x: Vec<f64>,
        residual: Vec<f64>,
    ) -> Option<Self> {
        let h = STEP * peak(&problem.exp.input);
        if problem.exp.input.len() < 3 || h.is_nan() || h <= 0.0 {
            return None;
        }
        let zero = Baseline::line(0.0, 0.0);
        let columns = line_columns(problem, &x, displacement, zero, &residual, h)?;
        Some(Origin {
            displacement,
            x,
            residual,
            columns,
            h,
        })
    }
}

/// What is taken off the displacement: a line, or one constant (a start away
/// from rest, the line's ends held together).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    Line,
    Held,
}

impl Shape {
    /// The numbers it adds.
    fn count(self) -> usize {
        match self {
            Shape::Line => 2,
            Shape::Held => 1,
        }
    }
}

/// The line (or, `Held`, the constant) that, taken off the displacement of
/// `problem` with `part` taken off the force, fits best, from `origin`:
/// Gauss-Newton on the line's two ends (forward differences of the model's
/// force) and the force's numbers (the residual moves with them one for
/// one), each round followed by a refit of the model. `None` where a
/// simulation or a refit fails or the step is singular (a model with no
/// stiffness to feel a displacement).
fn estimate(problem: &Problem, origin: &Origin, shape: Shape, part: ForcePart) -> Option<Estimate> {
    let n = problem.exp.input.len();
    let s: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    let mut displacement = origin.displacement;
    let mut force = Baseline::line(0.0, 0.0);
    let mut x = origin.x.clone();
    let mut r = origin.residual.clone();
    for round in 0..ROUNDS {
        // The residual's derivatives with respect to the line's two ends (or
        // to both moved together) and to the force's numbers: taking `F` off
        // the measured force adds `F` to the residual (model less measured).
        let [at_first, at_last] = match round {
            0 => origin.columns.clone(),
            _ => line_columns(problem, &x, displacement, force, &r, origin.h)?,
        };
        let mut columns = match shape {
            Shape::Line => vec![at_first, at_last],
            Shape::Held => vec![at_first.iter().zip(&at_last).map(|(a, b)| a + b).collect()],
        };
        match part {
            ForcePart::None => {}
            ForcePart::Constant => columns.push(vec![1.0; n]),
            ForcePart::Line => {
                columns.push(s.iter().map(|s| 1.0 - s).collect());
                columns.push(s.clone());
            }
        }
        let dot = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(p, q)| p * q).sum::<f64>();
        let normal = columns
            .iter()
            .map(|a| columns.iter().map(|b| dot(a, b)).collect())
            .collect();
        let rhs = columns.iter().map(|a| -dot(a, &r)).collect();
        let step = solve_normal(normal, rhs)?;
        let (first, last) = match shape {
            Shape::Line => (step[0], step[1]),
            Shape::Held => (step[0], step[0]),
        };
        displacement.first += first;
        displacement.last += last;
        let f = shape.count();
        match part {
            ForcePart::None => {}
            ForcePart::Constant => {
                force.first += step[f];
                force.last = force.first;
            }
            ForcePart::Line => {
                force.first += step[f];
                force.last += step[f + 1];
            }
        }
        let moved = without(problem, displacement, force);
        x = run::fit(&moved, Method::Lsq, &x, &Quiet).ok()?.x;
        r = residual(&moved, &x)?;
    }
    Some(Estimate {
        shape,
        part,
        displacement,
        force,
        residual: r,
    })
}

/// The line estimated alone, and with what the force needs beside it where
/// that is worth keeping: a constant where it adds a BIC change below -10
/// (by `weigh`, the residual before, after and the numbers added) to the
/// line alone, a line in the force where that adds one below -10 to the
/// better of those two (the way a start keeps its constant force,
/// [`offset::start`](super::offset::start)).
fn joint(
    problem: &Problem,
    origin: &Origin,
    weigh: impl Fn(&[f64], &[f64], usize) -> Option<f64>,
) -> Option<(Estimate, Option<Estimate>)> {
    let alone = estimate(problem, origin, Shape::Line, ForcePart::None)?;
    let mut best: Option<Estimate> = None;
    for part in [ForcePart::Constant, ForcePart::Line] {
        let Some(e) = estimate(problem, origin, Shape::Line, part) else {
            continue;
        };
        let before = best.as_ref().unwrap_or(&alone);
        let change = weigh(&before.residual, &e.residual, e.count() - before.count());
        if change.is_some_and(|c| c < SIGNIFICANT_BIC) {
            best = Some(e);
        }
    }
    Some((alone, best))
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
    let start_named = start.filter(|s| s.significant);
    // The force line, as the force drift fits it. A named start opens the
    // check as well: a drift from 1.5 mm back to zero beside a load cell's
    // drift, where the start dominates the residual, was named a start, and
    // the line was not weighed (found by review).
    let fitted = ResidualLine::of(r);
    let opened = Gain::of(d, nrmse, r, &fitted.after, 2, scale)?.significant();
    if !opened && start_named.is_none() {
        return None;
    }
    // The force line and the constant refitted: the model's parameters move
    // with them, as they do with the displacement's line (the force's zero
    // at s is -at(s), taken off the measured force).
    let refit_with = |zero: &dyn Fn(f64) -> f64| {
        let mut forced = problem.clone();
        forced
            .exp
            .output
            .iter_mut()
            .zip(&fitted.s)
            .for_each(|(f, s)| *f += zero(*s));
        refit_residual(&forced, &outcome.x)
    };
    let force_line = refit_with(&|s| fitted.at(s))?;
    let m = mean(r);
    let constant = refit_with(&|_| m)?;
    let weigh = |before: &[f64], after: &[f64], k: usize| {
        Gain::of(d, nrmse, before, after, k, scale).map(|g| g.delta_bic)
    };
    let origin = match start_named {
        Some(s) => Origin::at_start(problem, &outcome.x, s.value)?,
        None => Origin::of(problem, &outcome.x, r)?,
    };
    let (alone, beside) = joint(problem, &origin, weigh)?;
    let found = beside.as_ref().unwrap_or(&alone);
    let k = found.count();
    let after = &found.residual;
    let gain = Gain::of(d, nrmse, r, after, k, scale)?;
    let beyond_force = Gain::of(d, nrmse, &force_line, after, k - 2, scale)?;
    let beyond_constant = Gain::of(d, nrmse, &constant, after, k - 1, scale)?;
    let part_bic = Gain::of(d, nrmse, &alone.residual, after, k - 2, scale)?.delta_bic;
    // Beside a force's part, the load cell's error is what opened the check,
    // and a small line in the displacement can take up the model's own misfit
    // (a force offset alone on a pinched record: a line of 0.23-0.33 mm named
    // at delta-BIC -15 to -210, found by review). So the displacement's line
    // must remove MIN_SHARE of what the force's part alone, refitted, leaves,
    // as every offset must of the fit as it was.
    let beyond_part = match found.part {
        ForcePart::None => None,
        ForcePart::Constant => Some(&beyond_constant),
        ForcePart::Line => Some(&beyond_force),
    };
    let own_share = beyond_part.is_none_or(|g| g.share >= MIN_SHARE);
    let best = suspects
        .iter()
        .filter(|s| s.nrmse_with.is_finite())
        .min_by(|a, b| a.nrmse_with.total_cmp(&b.nrmse_with));
    let at_least_as_good = best.is_none_or(|b| gain.nrmse_with <= b.nrmse_with);
    let known = asymmetry_known(problem.par.spec, suspects);
    // Beside a named start the line must earn its slope: held at one value
    // with the same force's part, the start and what the force needs leave a
    // residual whose share the slope must remove as an offset must (a BIC
    // change below -10 and MIN_SHARE). Against the start check's own refit,
    // which keeps no more than a constant force, lines of 0.01-0.16 mm were
    // named beside starts of 0.3-1.5 mm with a force offset or drift (found
    // by review), and lines of 0.1 mm beside starts alone.
    let held = match start_named {
        Some(_) => Some(estimate(problem, &origin, Shape::Held, found.part)?),
        None => None,
    };
    let slope = match &held {
        Some(h) => Some(Gain::of(d, nrmse, &h.residual, after, 1, scale)?),
        None => None,
    };
    let slope_short = slope.as_ref().is_some_and(|g| !g.significant());
    // And the start holds unless the line beats it decisively: the line's
    // first end can hold a start, and a start refitted with a constant force
    // can take up part of a drift.
    let start_holds =
        slope_short || start_named.is_some_and(|s| gain.delta_bic >= s.delta_bic + SIGNIFICANT_BIC);
    let peak_u = peak(&problem.exp.input);
    let (first, last) = (found.displacement.first, found.displacement.last);
    let reach = first.abs().max(last.abs()) / peak_u;
    let runs_off = reach.is_nan() || reach > RUNS_OFF;
    let significant = !runs_off
        && gain.significant()
        && beyond_force.delta_bic < SIGNIFICANT_BIC
        && beyond_constant.delta_bic < SIGNIFICANT_BIC
        && own_share
        && known
        && at_least_as_good
        && !start_holds;
    let value = last - first;
    let relative = value / peak_u;
    let du = decimals(peak_u);
    // What the slope adds to the line's ends held together, in words.
    let held_words = held.as_ref().zip(slope.as_ref()).map(|(h, g)| {
        let part = if h.part == ForcePart::None {
            ""
        } else {
            ", with the same part of the force"
        };
        let removes = if g.share > 0.0 {
            format!(
                "removes {:.1}% of the squared error that leaves",
                100.0 * g.share
            )
        } else {
            "removes none of the squared error that leaves".to_string()
        };
        format!(
            "held at one value there ({:+.du$} mm){part}, the line's slope {removes} \
             (delta-BIC {:+.0})",
            h.displacement.first, g.delta_bic
        )
    });
    let force_nrmse = Gain::of(d, nrmse, r, &force_line, 2, scale)?.nrmse_with;
    let peak_f = peak(&d.force);
    let df = decimals(peak_f);
    let (fa, fb) = (found.force.first, found.force.last);
    let (beside, also) = match found.part {
        ForcePart::None => (String::new(), String::new()),
        ForcePart::Constant => (
            format!(
                ", fitted together with a constant force taken off the force ({fa:+.df$} kN, \
                 {:+.1}% of its peak",
                100.0 * fa / peak_f
            ),
            format!(" --subtract force={fa:.df$}"),
        ),
        ForcePart::Line => (
            format!(
                ", fitted together with a line taken off the force ({fa:+.df$} kN at the first \
                 sample, {fb:+.df$} kN at the last, {:+.1}% of its peak",
                100.0 * (fb - fa) / peak_f
            ),
            format!(" --subtract force={fa:.df$}..{fb:.df$}"),
        ),
    };
    let beside = if beside.is_empty() {
        beside
    } else {
        format!(
            "{beside}: it adds a BIC change of {part_bic:+.0} to the displacement's line alone, \
             which alone would run from {:+.du$} to {:+.du$} mm)",
            alone.displacement.first, alone.displacement.last
        )
    };
    let mut evidence = format!(
        "A straight line in the sample number taken off the displacement ({first:+.du$} mm at \
         the first sample, {last:+.du$} mm at the last: the zero moves by {value:+.du$} mm, \
         {:+.1}% of the peak displacement){beside} with the model refitted takes {}; the line \
         in the force alone, refitted the same way, reaches {force_nrmse:.4}, a BIC change of \
         {:+.0} for this estimate.",
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
                 {:+.0} against {:+.0}), which its first end holds{}.",
                gain.delta_bic,
                s.delta_bic,
                held_words
                    .as_deref()
                    .map_or(String::new(), |w| format!(": {w}"))
            )
        });
        format!(
            "A load cell's drift adds the same force all round a loop; this one shifts the loop \
             along the displacement, as a displacement transducer whose zero drifts (creep, a \
             reference frame settling) does. No effect of the library drifts with time: check \
             the transducer before trusting an effect named for it, and run again with \
             `--subtract displacement={first:.du$}..{last:.du$}{also}` to take {}.\
             {over_start}",
            if also.is_empty() {
                "it off"
            } else {
                "both off (the load cell's zero is off as well: check it too)"
            }
        )
    } else if !gain.significant() {
        gain.not_significant()
    } else if beyond_force.delta_bic >= SIGNIFICANT_BIC {
        "Not named: the line in the force fits as well (weighed as the force drift).".into()
    } else if beyond_constant.delta_bic >= SIGNIFICANT_BIC {
        "Not named: a constant force, refitted, explains it as well (weighed as the force \
         offset)."
            .into()
    } else if let Some(g) = beyond_part.filter(|_| !own_share) {
        format!(
            "Not named: beside the force's part, the line removes {:.1}% of the squared error \
             the force's part alone leaves, less than the {:.0}% asked of an offset. The load \
             cell's error opened this check, and a small line in the displacement can take up \
             the model's own misfit: the load cell's checks speak for the record.",
            100.0 * g.share,
            100.0 * MIN_SHARE
        )
    } else if let Some(w) = held_words.filter(|_| slope_short) {
        format!(
            "Not named: the record starts away from rest (below); {w}, where an offset must \
             remove {:.0}% at a BIC change below -10.",
            100.0 * MIN_SHARE
        )
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
        with_force: (found.part == ForcePart::Constant).then_some(fa),
        line: Some([first, last]),
        force_line: (found.part == ForcePart::Line).then_some([fa, fb]),
        share: gain.share,
        nrmse_with: gain.nrmse_with,
        delta_bic: gain.delta_bic,
        n_eff: gain.n_eff,
        asymmetry_nrmse: None,
        evidence,
    })
}
