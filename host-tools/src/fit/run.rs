//! Running a fit with one of the methods and collecting what a user needs to
//! judge it: the parameters, the scores, the identifiability summary and the
//! cost in simulations.

use super::homotopy;
use super::identifiability::{self, Identifiability};
use super::lanes::{SearchSummary, Unsuited};
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
    /// Levenberg-Marquardt from several starts in parallel, best kept.
    Auto,
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
    /// The fitted parameters that stopped at an end of their search range.
    pub at_bounds: Vec<AtBound>,
    /// For an evolutionary search: the fixed-step model it simulated with, or why it simulated
    /// with the core instead.
    pub search: Option<Result<SearchSummary, Unsuited>>,
    /// With [`Evolution::polish`]: the scores of the solution NSGA-II chose, which least squares
    /// then refined into this outcome.
    pub polished_from: Option<Scores>,
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
    let solution = match method {
        Method::Lsq => lsq::minimize_observed(&residuals, x0, &lo, &hi, opts, |_, c| report(c)),
        Method::Auto => {
            let all = starts(x0, &lo, &hi, 8, 0x5eed);
            let sols: Vec<_> = all
                .par_iter()
                .enumerate()
                .filter_map(|(i, s)| {
                    let sol =
                        lsq::minimize_observed(&residuals, s, &lo, &hi, opts, |_, c| report(c));
                    progress.stage(&format!("start {} of {} done", i + 1, all.len()));
                    sol
                })
                .collect();
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
        anyhow!("the model could not be simulated from the starting point; check the fixed parameters and bounds")
    })?;
    finish(
        problem,
        &method.to_string(),
        sol,
        evals.load(Ordering::Relaxed),
    )
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
        .map_err(|e| anyhow!("NSGA-II: {e}"))?;
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
    let identifiability =
        identifiability::analyse(&sol.jacobian, &names, &sol.x, sol.cost, sol.residuals.len());
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
    })
}

/// The outcome at a given point `x` (a parameter file's values): scores and
/// identifiability without fitting.
pub fn evaluate_at(problem: &Problem, x: &[f64], method: &str) -> Result<Outcome> {
    let sol = solution_at(problem, x).ok_or_else(|| {
        anyhow!("the given parameters, or ones next to them, cannot be simulated on this record")
    })?;
    let evaluations = sol.evaluations;
    finish(problem, method, sol, evaluations)
}
