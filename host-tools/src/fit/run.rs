//! Running a fit with one of the methods and collecting what a user needs to
//! judge it: the parameters, the scores, the identifiability summary and the
//! cost in simulations.

use super::homotopy;
use super::identifiability::{self, Identifiability};
use super::lsq::{self, Options};
use super::objectives::Scores;
use super::problem::Problem;
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
    /// Levenberg-Marquardt from several starts in parallel, best kept.
    Auto,
}

impl FromStr for Method {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        Ok(match s {
            "lsq" => Method::Lsq,
            "homotopy" => Method::Homotopy,
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
}

/// Progress reports of a running fit.
pub trait Progress: Sync {
    /// A better point was found: `evaluations` so far, current NRMSE.
    fn improved(&self, evaluations: usize, nrmse: f64);
    /// A stage finished (homotopy lambda, start number...).
    fn stage(&self, message: &str);
}

/// Reports nothing.
pub struct Quiet;

impl Progress for Quiet {
    fn improved(&self, _: usize, _: f64) {}
    fn stage(&self, _: &str) {}
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

/// Fits `problem` from `x0` with `method`.
pub fn fit(
    problem: &Problem,
    method: Method,
    x0: &[f64],
    progress: &dyn Progress,
) -> Result<Outcome> {
    let (lo, hi) = problem.par.bounds();
    let evals = AtomicUsize::new(0);
    let best = Mutex::new(f64::INFINITY);
    let residuals = |x: &[f64]| {
        evals.fetch_add(1, Ordering::Relaxed);
        problem.residuals(x)
    };
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
        Method::Homotopy => {
            if problem.observer_gains().is_none() {
                bail!(
                    "homotopy (thesis ch. 4) couples an observer into the equation of motion, so it needs a \
                     force-driven record; this record is driven by displacement: use --method lsq, nsga2 or auto"
                );
            }
            let coupled = |x: &[f64], lambda: f64| {
                evals.fetch_add(1, Ordering::Relaxed);
                problem.residuals_coupled(x, lambda)
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
        x: sol.x,
        scores,
        identifiability,
        evaluations,
    })
}
