//! Running a fit with one of the methods and collecting what a user needs to
//! judge it: the parameters, the scores, the identifiability summary and the
//! cost in simulations.

use super::homotopy;
use super::identifiability::{self, Identifiability};
use super::lanes::{LaneResiduals, SearchModel, SearchSummary, Unsuited};
use super::lsq::{self, Options};
use super::nsga2::Nsga2;
use super::objectives::Scores;
use super::parametrization::AtBound;
use super::problem::{LeastSquares, Ortiz, Problem};
use anyhow::{anyhow, bail, Result};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// How to search.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Bounded Levenberg-Marquardt from the default start.
    Lsq,
    /// Homotopy with the observer coupling of eq. 4.6 (force drive).
    Homotopy,
    /// NSGA-II on the four Ortiz objectives (thesis ch. 3), with the thesis'
    /// choice of one solution from the front.
    Nsga2,
    /// Levenberg-Marquardt from several starts in parallel, best kept. For a force-driven
    /// plain Bouc-Wen fit the starts are first fitted with the fixed-step lane model and only the
    /// best of them refined with the core ([`Screening`]).
    Auto,
}

/// Starts of [`Method::Auto`].
pub const STARTS: usize = 8;

/// Screened starts of [`Method::Auto`] that the core refines: the best by the core's NRMSE at
/// the end of their screening. Next to it the core fits the given start directly, unscreened:
/// the fixed-step model's Jacobian is a few per cent off the core's, enough for least squares
/// to take another path, and on the Bouc-Wen benchmark record with linear forcing the core
/// reaches NRMSE 0.0145 from the default start only (seven random starts end at 0.29-0.64),
/// while every screened end, that start's included, scored 0.35-0.64. The two fits fill the
/// two cores.
pub const REFINED: usize = 1;

/// The step tolerance of a screening fit (of each variable's range; the core's fits use
/// [`Options::default`]'s 1e-8). The fixed-step model's minimum lies off the core's by the
/// model's error, so polishing it further only moves within that error.
pub const SCREEN_X_TOL: f64 = 1e-6;

/// How [`Method::Auto`] screened its starts with the fixed-step model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screening {
    /// The fixed-step model and the lane runs it took (its checks included).
    pub model: SearchSummary,
    /// Starts screened.
    pub starts: usize,
    /// Screened ends that the core refined (the given start was also fitted by the core
    /// directly).
    pub refined: usize,
}

impl std::fmt::Display for Screening {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let m = &self.model;
        let best = match self.refined {
            1 => "best end by the error-controlled model's NRMSE was".to_string(),
            n => format!("{n} best ends by the error-controlled model's NRMSE were"),
        };
        write!(
            f,
            "the {} starts were fitted first with RK4 at {} step{} a sample ({} candidates a run, \
             {} runs), whose NRMSE was within {:.1e} of the error-controlled model's at sixteen \
             points of the bounds; the {best} then refined with it, and the first start fitted \
             with it directly",
            self.starts,
            m.substeps,
            if m.substeps == 1 { "" } else { "s" },
            m.lanes,
            m.runs,
            m.checked_error,
        )
    }
}

impl FromStr for Method {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        Ok(match s {
            "lsq" => Method::Lsq,
            "homotopy" => Method::Homotopy,
            "nsga2" => Method::Nsga2,
            "auto" => Method::Auto,
            other => bail!("unknown method `{other}`: expected lsq, homotopy, nsga2 or auto"),
        })
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Method::Lsq => "lsq",
            Method::Homotopy => "homotopy",
            Method::Nsga2 => "nsga2",
            Method::Auto => "auto",
        })
    }
}

/// A finished fit.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The method that produced it.
    pub method: String,
    /// The normalised minimiser.
    pub x: Vec<f64>,
    /// Physical values of every parameter.
    pub values: BTreeMap<&'static str, f64>,
    /// Scores of the prediction.
    pub scores: Scores,
    /// What the data can and cannot determine.
    pub identifiability: Identifiability,
    /// Model simulations used.
    pub evaluations: usize,
    /// The fitted parameters that stopped at an end of their search range (none for
    /// [`evaluate_at`], where no search ran).
    pub at_bounds: Vec<AtBound>,
    /// For an evolutionary search: the fixed-step model it simulated with, or why it simulated
    /// with the core instead.
    pub search: Option<Result<SearchSummary, Unsuited>>,
    /// With [`Evolution::polish`]: the scores of the solution NSGA-II chose, which least squares
    /// then refined into this outcome.
    pub polished_from: Option<Scores>,
    /// For [`Method::Auto`] on a force-driven plain Bouc-Wen fit: how its starts were screened.
    pub screening: Option<Screening>,
}

/// Progress reports of a running fit.
pub trait Progress: Sync {
    /// A better point was found: `evaluations` so far, current NRMSE.
    fn improved(&self, evaluations: usize, nrmse: f64);
    /// A stage finished (homotopy lambda, start number...): a line to keep.
    fn stage(&self, message: &str);
    /// The current status (replaces the previous one).
    fn status(&self, message: &str);
}

/// Reports nothing.
pub struct Quiet;

impl Progress for Quiet {
    fn improved(&self, _: usize, _: f64) {}
    fn stage(&self, _: &str) {}
    fn status(&self, _: &str) {}
}

/// Seeded starting points: `x0`, then points drawn uniformly in the middle
/// half of each bound range (xorshift from `seed`).
pub fn starts(x0: &[f64], lo: &[f64], hi: &[f64], count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut s = seed.max(1);
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut out = vec![x0.to_vec()];
    while out.len() < count {
        out.push(
            lo.iter()
                .zip(hi)
                .map(|(l, h)| l + (h - l) * (0.25 + 0.5 * next()))
                .collect(),
        );
    }
    out
}

/// Settings of the evolutionary search.
#[derive(Clone, Debug)]
pub struct Evolution {
    /// NSGA-II settings (population, generations, encoding, seed).
    pub nsga2: Nsga2,
    /// Where to write the final Pareto front (physical parameter values and
    /// the four objectives), if anywhere.
    pub front_csv: Option<std::path::PathBuf>,
    /// Refine the chosen solution by bounded least squares on the residuals of the predicted
    /// output (a hybrid search: the evolution finds the basin, the local method its bottom, as
    /// SciPy's differential evolution does by default). The thesis' method stops at the chosen
    /// solution, so this is off by default.
    pub polish: bool,
}

impl Default for Evolution {
    fn default() -> Self {
        Evolution {
            nsga2: Nsga2 {
                population: 100,
                generations: 100,
                seed: 1,
                ..Nsga2::default()
            },
            front_csv: None,
            polish: false,
        }
    }
}

/// Fits `problem` from `x0` with `method`.
pub fn fit(
    problem: &Problem,
    method: Method,
    x0: &[f64],
    progress: &dyn Progress,
) -> Result<Outcome> {
    fit_with(problem, method, x0, &Evolution::default(), progress)
}

/// `problem` refitted by bounded least squares from the values of `from`, a
/// fit of the same record with this model or a neighbouring one: parameters
/// `problem`'s model lacks are dropped, those `from` lacks start switched off.
/// The outcome's `method` says where it started: `lsq (LABEL)`.
pub fn refit_from(problem: &Problem, from: &Outcome, label: &str) -> Result<Outcome> {
    let x0 = problem.par.normalise(&from.values);
    let out = fit(problem, Method::Lsq, &x0, &Quiet)?;
    Ok(Outcome {
        method: format!("lsq ({label})"),
        ..out
    })
}

/// [`fit`] with explicit settings for [`Method::Nsga2`].
pub fn fit_with(
    problem: &Problem,
    method: Method,
    x0: &[f64],
    evolution: &Evolution,
    progress: &dyn Progress,
) -> Result<Outcome> {
    if method == Method::Nsga2 {
        return evolve(problem, evolution, progress);
    }
    let (lo, hi) = problem.par.bounds();
    let evals = AtomicUsize::new(0);
    let best = Mutex::new(f64::INFINITY);
    let residuals = LeastSquares::new(problem).counting(&evals);
    let report = |cost: f64| {
        let mut b = best.lock().expect("progress lock");
        if cost < *b {
            *b = cost;
            progress.improved(evals.load(Ordering::Relaxed), cost.sqrt());
        }
    };
    let opts = Options::default();
    let mut screening = None;
    let solution = match method {
        Method::Lsq => lsq::minimize_observed(&residuals, x0, &lo, &hi, opts, |_, c| report(c)),
        Method::Auto => {
            let all = starts(x0, &lo, &hi, STARTS, 0x5eed);
            let screened = SearchModel::for_problem(problem)
                .ok()
                .and_then(|model| screen(problem, &model, &all, &residuals, &report, progress));
            let ends = match &screened {
                Some((ends, _)) => &[vec![x0.to_vec()], ends.clone()].concat(),
                None => &all,
            };
            let sols: Vec<_> = ends
                .par_iter()
                .enumerate()
                .filter_map(|(i, s)| {
                    let sol =
                        lsq::minimize_observed(&residuals, s, &lo, &hi, opts, |_, c| report(c));
                    progress.stage(&match (&screened, i) {
                        (Some(_), 0) => "first start fitted directly".to_string(),
                        (Some(_), _) => format!("screened end {i} of {} refined", ends.len() - 1),
                        (None, _) => format!("start {} of {} done", i + 1, ends.len()),
                    });
                    sol
                })
                .collect();
            screening = screened.map(|(ends, model)| Screening {
                model,
                starts: all.len(),
                refined: ends.len(),
            });
            sols.into_iter().min_by(|a, b| a.cost.total_cmp(&b.cost))
        }
        Method::Nsga2 => unreachable!("handled above"),
        Method::Homotopy => {
            if problem.observer_gains().is_none() {
                bail!(
                    "homotopy (thesis ch. 4) couples an observer into the equation of motion, so it needs a \
                     force-driven record; this record is driven by displacement: use --method lsq, nsga2 or auto"
                );
            }
            let coupled = |lambda: f64| {
                LeastSquares::coupled(problem, lambda)
                    .expect("a force-driven record has an observer")
                    .counting(&evals)
            };
            homotopy::run(
                &coupled,
                x0,
                &lo,
                &hi,
                &homotopy::linear_schedule(10),
                opts,
                |s| {
                    progress.stage(&format!("lambda {:.1}: cost {:.3e}", s.lambda, s.cost));
                    if s.lambda == 0.0 {
                        report(s.cost);
                    }
                },
            )
            .map(|p| p.solution)
        }
    };
    let sol = solution.ok_or_else(|| {
        let from = if method == Method::Auto {
            "any of its starts"
        } else {
            "its starting point"
        };
        let why = match problem.try_predict(x0) {
            Err(e) => format!(" (at the first: {e})"),
            Ok(_) => String::new(),
        };
        let fixed = if problem.par.fixed.is_empty() {
            ""
        } else {
            "; check the fixed parameters"
        };
        anyhow!("the model could not be simulated from {from}{why}{fixed}")
    })?;
    Ok(Outcome {
        screening,
        ..finish(
            problem,
            &method.to_string(),
            sol,
            evals.load(Ordering::Relaxed),
        )?
    })
}

/// The screening of [`Method::Auto`]: fits every start with the fixed-step `model`
/// ([`LaneResiduals`], to [`SCREEN_X_TOL`]), scores each end with the core (`core`, which counts
/// the simulations; `report` gets each end's cost) and returns the [`REFINED`] best ends, with
/// what the model did. `None` when no end can be simulated by the core (the caller then refines
/// every start with the core).
fn screen(
    problem: &Problem,
    model: &SearchModel,
    starts: &[Vec<f64>],
    core: &LeastSquares,
    report: &(dyn Fn(f64) + Sync),
    progress: &dyn Progress,
) -> Option<(Vec<Vec<f64>>, SearchSummary)> {
    let (lo, hi) = problem.par.bounds();
    let lanes = LaneResiduals::new(problem, model);
    let opts = Options {
        x_tol: SCREEN_X_TOL,
        ..Options::default()
    };
    let mut ends: Vec<(Vec<f64>, f64)> = starts
        .par_iter()
        .enumerate()
        .filter_map(|(i, s)| {
            // A start the fixed-step model cannot simulate is scored as it is.
            let x = lsq::minimize(&lanes, s, &lo, &hi, opts).map_or_else(|| s.clone(), |e| e.x);
            let cost = lsq::Residuals::residuals(core, &x)
                .map(|r| lsq::cost(&r))
                .filter(|c| c.is_finite());
            if let Some(c) = cost {
                report(c);
            }
            let nrmse = cost.map(f64::sqrt);
            progress.stage(&format!(
                "start {} of {} screened with the fixed-step model: NRMSE {}",
                i + 1,
                starts.len(),
                nrmse.map_or("not simulated".into(), |v| format!("{v:.4e}"))
            ));
            Some((x, nrmse?))
        })
        .collect();
    ends.sort_by(|a, b| a.1.total_cmp(&b.1));
    ends.dedup_by(|a, b| a.0 == b.0);
    ends.truncate(REFINED);
    if ends.is_empty() {
        return None;
    }
    Some((ends.into_iter().map(|e| e.0).collect(), model.summary()))
}

/// NSGA-II on the Ortiz objectives; the thesis' solution (nearest the origin
/// of the normalised front).
fn evolve(problem: &Problem, evolution: &Evolution, progress: &dyn Progress) -> Result<Outcome> {
    let ortiz = Ortiz::new(problem);
    let settings = &evolution.nsga2;
    let outcome = settings
        .run_with(&ortiz, |g| {
            if let Some(best) = g.best_objectives() {
                progress.status(&format!(
                    "generation {}/{}, {} simulations: best f1 {:.3e}, f2 {:.3e}, f3 {:.3e}, f4 {:.3e}; front {} of {}",
                    g.index + 1,
                    settings.generations,
                    g.evaluations,
                    best[0],
                    best[1],
                    best[2],
                    best[3],
                    g.first_front_len(),
                    g.population.len()
                ));
            }
            std::ops::ControlFlow::Continue(())
        })
        .map_err(|e| anyhow!("{e}"))?;
    let chosen = outcome.chosen().ok_or_else(|| {
        anyhow!("NSGA-II found no feasible parameter set (beta + gamma > 0, beta - gamma > 0)")
    })?;
    if let Some(path) = &evolution.front_csv {
        ortiz.write_front(path, &outcome.first_front())?;
    }
    let sol = solution_at(problem, &chosen.variables).ok_or_else(|| {
        anyhow!("the chosen parameter set, or one next to it, cannot be simulated")
    })?;
    let mut evaluations = outcome.evaluations + sol.evaluations;
    let search = Some(ortiz.search_summary());
    if !evolution.polish {
        let sol = lsq::Solution {
            iterations: settings.generations,
            ..sol
        };
        return Ok(Outcome {
            search,
            ..finish(problem, "nsga2", sol, evaluations)?
        });
    }
    let chosen_scores = problem
        .scores(&sol.x)
        .ok_or_else(|| anyhow!("the chosen parameter set cannot be simulated"))?;
    progress.stage(&format!(
        "NSGA-II chose NRMSE {:.4e}; least squares from there",
        chosen_scores.nrmse
    ));
    let (lo, hi) = problem.par.bounds();
    let evals = AtomicUsize::new(0);
    let residuals = LeastSquares::new(problem).counting(&evals);
    let polished = lsq::minimize_observed(
        &residuals,
        &sol.x,
        &lo,
        &hi,
        Options::default(),
        |_, cost| progress.improved(evaluations + evals.load(Ordering::Relaxed), cost.sqrt()),
    );
    evaluations += evals.load(Ordering::Relaxed);
    // Least squares only accepts steps that lower the cost, so its result is never worse than
    // its start; a start it cannot simulate around leaves the chosen solution as it was.
    let sol = polished.unwrap_or(sol);
    Ok(Outcome {
        search,
        polished_from: Some(chosen_scores),
        ..finish(problem, "nsga2+lsq", sol, evaluations)?
    })
}

/// The least-squares view of `problem` at `x`: residuals and Jacobian,
/// exact where it can be had.
fn solution_at(problem: &Problem, x: &[f64]) -> Option<lsq::Solution> {
    let (lo, hi) = problem.par.bounds();
    let f = LeastSquares::new(problem);
    lsq::solution_at(&f, x, &lo, &hi, Options::default().fd_step)
}

/// Scores and identifiability of a least-squares solution.
pub fn finish(
    problem: &Problem,
    method: &str,
    sol: lsq::Solution,
    evaluations: usize,
) -> Result<Outcome> {
    let scores = problem
        .scores(&sol.x)
        .ok_or_else(|| anyhow!("the fitted parameters cannot be simulated"))?;
    let names = problem.par.names();
    let (values, to_physical) = problem.par.physical_jacobian(&sol.x);
    let identifiability = identifiability::analyse_physical(
        &sol.jacobian,
        &names,
        &values,
        &to_physical,
        sol.cost,
        sol.residuals.len(),
    );
    Ok(Outcome {
        method: method.to_string(),
        values: problem.par.physical(&sol.x),
        at_bounds: problem.par.at_bounds(&sol.x),
        x: sol.x,
        scores,
        identifiability,
        evaluations,
        search: None,
        polished_from: None,
        screening: None,
    })
}

/// The outcome at a given point `x` (a parameter file's values): scores and
/// identifiability without fitting. No search ran, so no range stopped one: given values at or
/// beyond an end are not reported as stops (`diagnose --params` printed one, found by review).
pub fn evaluate_at(problem: &Problem, x: &[f64], method: &str) -> Result<Outcome> {
    let sol = solution_at(problem, x).ok_or_else(|| {
        anyhow!("the given parameters, or ones next to them, cannot be simulated on this record")
    })?;
    let evaluations = sol.evaluations;
    Ok(Outcome {
        at_bounds: vec![],
        ..finish(problem, method, sol, evaluations)?
    })
}
