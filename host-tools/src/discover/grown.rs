//! A model with effects fitted by growing it from its base, as the
//! [`ladder`](super::ladder) grows one: the base model fitted afresh, each
//! effect added in turn from the fit before with starts of its own
//! ([`suspects::refit`]), then every parameter of the model as asked refined
//! together by least squares.
//!
//! Fitted directly, from starts around the default, a model with pinching
//! on an irregular record can stop with pinching's parameters at the ends of
//! their ranges: `diagnose --model bw+pinching` on a record with pinching
//! hidden stopped at NRMSE 0.0438 with `p`, `q` and `lambda` at their ends
//! and named stiffness degradation for what was left, where the ladder,
//! growing the same model from `bw`, reached 0.0251 (found by review). So
//! where a direct fit leaves a parameter of an effect at an end of its range
//! ([`cornered`]), the model is grown as well and the better fit kept.

use super::suspects::{self, WeighOptions};
use crate::fit::problem::Problem;
use crate::fit::run::{self, Method, Outcome, Quiet};

/// Parameter values by name, as `--fix` gives them.
type Values = Vec<(String, f64)>;

/// The parameters of the model's effects that the fit `outcome` of
/// `problem` left at an end of their search range.
pub fn cornered(problem: &Problem, outcome: &Outcome) -> Vec<&'static str> {
    let effects = problem.par.spec.effects();
    outcome
        .at_bounds
        .iter()
        .filter(|a| effects.iter().any(|e| e.owns(a.name)))
        .map(|a| a.name)
        .collect()
}

/// `problem`'s model grown from its base: `None` where the model has no
/// effect, or a step cannot be fitted.
pub fn fit(problem: &Problem) -> Option<Outcome> {
    let effects = problem.par.spec.effects();
    if effects.is_empty() {
        return None;
    }
    let base_spec = effects.iter().fold(problem.par.spec, |s, e| s.without(*e));
    let owned = |name: &str| effects.iter().any(|e| e.owns(name));
    // Values the user holds: the base's on the base, the effects' when
    // their effect is added.
    let (held, base_fixed): (Values, Values) = problem
        .par
        .fixed
        .iter()
        .map(|(k, v)| (k.to_string(), *v))
        .partition(|(k, _)| owned(k));
    let base = Problem::new(base_spec, problem.exp.clone(), &base_fixed).ok()?;
    let first = run::fit(&base, Method::Auto, &base.par.default_start(), &Quiet).ok()?;
    let starts = WeighOptions::default().starts;
    let (_, grown) = effects.iter().try_fold((base, first), |(p, o), &e| {
        suspects::refit(&p, &o, e, starts, &held, false).ok()
    })?;
    // The refits hold the initial values of the degradation laws at 1, as
    // the ladder does; the model as asked may free them.
    run::refit_from(problem, &grown, "grown from the base model").ok()
}
