//! The fitting problem: a model spec on a record, seen by the optimisers as a
//! function of a normalised parameter vector.

use super::dual::Dual;
use super::experiment::{Drive, Experiment, Prediction, SimError};
use super::lanes::{SearchModel, SearchSummary, Unsuited, LANES};
use super::lsq::Residuals;
use super::objectives::{Scores, Target, ENVELOPE_FLOOR};
use super::parametrization::Candidate;
use super::parametrization::Parametrization;
use crate::model::ModelSpec;
use anyhow::Result;
use hysteresis::bwbn::{BwbnParams, Control, EffectKind, Method, Observer, ENERGY_LIMIT};
use hysteresis::Scalar;
use nalgebra::DMatrix;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The most free parameters whose Jacobian is computed in dual numbers (all
/// the built-in effects and `xi`).
pub const DUAL_MAX: usize = 20;

/// A model spec fitted to a record.
#[derive(Clone, Debug)]
pub struct Problem {
    /// The record.
    pub exp: Experiment,
    /// Free and fixed parameters.
    pub par: Parametrization,
    /// What the prediction is scored against.
    pub target: Target,
    /// Integration control of the simulations.
    pub control: Control<f64>,
}

/// A record a model can be fitted to: displacement and force both vary (a fit to a force that is
/// zero throughout "succeeds" with `k0` at the bottom of its range, and its NRMSE divides by
/// zero), and their squares stay finite (the NRMSE of forces near 1e155 kN was NaN).
fn check_signals(exp: &Experiment) -> Result<()> {
    check_signal("displacement", "mm", exp.displacement())?;
    check_signal("force", "kN", exp.force())
}

/// One signal of a record to fit (`name` and `unit` for the message): it
/// varies and its squares sum to a finite number above zero. (Forces of
/// 1e-299 kN vary, but their squares underflow to zero: the fit reported
/// NRMSE 0, found by review.)
pub(crate) fn check_signal(name: &str, unit: &str, values: &[f64]) -> Result<()> {
    if let Some(&first) = values.first() {
        if values.iter().all(|v| *v == first) {
            anyhow::bail!(
                "expected the {name} to vary, found {first} {unit} in every sample: nothing to fit"
            );
        }
    }
    let squares = values.iter().map(|v| v * v).sum::<f64>();
    let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !squares.is_finite() {
        anyhow::bail!(
            "expected {name}s whose squares sum to a finite number, found values up to {largest:e} {unit}: give the record in larger units"
        );
    }
    if !values.is_empty() && squares == 0.0 {
        anyhow::bail!(
            "expected {name}s whose squares do not underflow to zero, found values only up to {largest:e} {unit}: give the record in smaller units"
        );
    }
    Ok(())
}

impl Problem {
    /// The problem of fitting `spec` to `exp` with `fixed` parameters
    /// (physical values).
    pub fn new(spec: ModelSpec, exp: Experiment, fixed: &[(String, f64)]) -> Result<Self> {
        check_signals(&exp)?;
        let par = Parametrization::new(spec, &exp, fixed)?;
        if exp.len() <= par.dim() {
            anyhow::bail!(
                "the record has {} sample{}, too few to fit the {} free parameters of {spec} (it needs more samples than parameters)",
                exp.len(),
                if exp.len() == 1 { "" } else { "s" },
                par.dim()
            );
        }
        let target = Target::new(&exp, ENVELOPE_FLOOR);
        // Fitting needs accurate, smooth predictions but not 1e-9: the
        // finite-difference Jacobian steps are 1e-6 of the parameter ranges.
        // Plain Bouc-Wen driven by displacement is summed as series (12x
        // faster on a `bw` fit of Lehman 415, NRMSE the same to 7 digits);
        // with any effect on, and for the oscillator, it is Dormand-Prince.
        let control = Control {
            method: Method::Series,
            tol: 1e-8,
            max_substeps: 200,
        };
        Ok(Problem {
            exp,
            par,
            target,
            control,
        })
    }

    /// Number of free parameters.
    pub fn dim(&self) -> usize {
        self.par.dim()
    }

    /// The model at `x`, if valid.
    pub fn params(&self, x: &[f64]) -> Option<Candidate> {
        self.par.build(x).ok()
    }

    /// The prediction at `x` (None: invalid parameters or a failed step).
    pub fn predict(&self, x: &[f64]) -> Option<Prediction> {
        self.try_predict(x).ok()
    }

    /// The prediction at `x`, or why there is none.
    pub fn try_predict(&self, x: &[f64]) -> Result<Prediction, SimError> {
        let c = self.par.build(x).map_err(SimError::Params)?;
        self.exp.simulate(&c.params, &c.extras, c.xi, self.control)
    }

    /// Scores at `x`.
    pub fn scores(&self, x: &[f64]) -> Option<Scores> {
        Some(self.target.score(&self.exp, &self.predict(x)?))
    }

    /// Least-squares residuals at `x` (`||r||^2 = nrmse^2`).
    pub fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.residuals_observed(x, None)
    }

    /// Residuals and their exact Jacobian at `x` (rows: samples, columns: the
    /// free parameters) from one simulation in [`Dual`] numbers; `observer`
    /// couples the model to the measurement as in
    /// [`residuals_observed`](Self::residuals_observed). `None` when `x` cannot
    /// be simulated, when the model has custom effects (they are written in
    /// `f64`), when it has more than [`DUAL_MAX`] free parameters, when a
    /// derivative is not finite, for asymmetry with pinching, or for pinching
    /// at `zeta0 = 0` (where the core skips pinching's work, and with it the
    /// derivative with respect to `zeta0`): the caller then differences.
    /// (With pinching, asymmetry makes dz/du jump where z changes sign, as
    /// pinching's h(0) follows the side's Zu; the solution's derivative then
    /// jumps at each crossing, which differentiating the right-hand side cannot
    /// see: measured 1-5% off central differences.)
    pub fn residuals_jacobian(
        &self,
        x: &[f64],
        observer: Option<Observer<f64>>,
    ) -> Option<(Vec<f64>, DMatrix<f64>)> {
        if !self.has_exact_jacobian(x) {
            return None;
        }
        self.jacobian_in_duals(x, observer)
    }

    /// [`residuals_jacobian`](Self::residuals_jacobian) where
    /// [`has_exact_jacobian`](Self::has_exact_jacobian) holds.
    fn jacobian_in_duals(
        &self,
        x: &[f64],
        observer: Option<Observer<f64>>,
    ) -> Option<(Vec<f64>, DMatrix<f64>)> {
        match self.dim() {
            0 => None,
            1..=5 => self.dual_jacobian::<5>(x, observer),
            6..=8 => self.dual_jacobian::<8>(x, observer),
            9..=12 => self.dual_jacobian::<12>(x, observer),
            13..=16 => self.dual_jacobian::<16>(x, observer),
            17..=DUAL_MAX => self.dual_jacobian::<DUAL_MAX>(x, observer),
            _ => None,
        }
    }

    /// Whether [`residuals_jacobian`](Self::residuals_jacobian) computes the
    /// Jacobian at `x` rather than refusing before it simulates (custom
    /// effects, more than [`DUAL_MAX`] free parameters, asymmetry with
    /// pinching, pinching at `zeta0 = 0`). Cheap: no simulation.
    pub fn has_exact_jacobian(&self, x: &[f64]) -> bool {
        let effects = self.par.spec.effects;
        let pinching = effects.contains(EffectKind::Pinching);
        let jumps = pinching && effects.contains(EffectKind::Asymmetry);
        // Pinching skips its work when zeta0 is exactly 0 (the value is the
        // same, the derivative with respect to zeta0 is not: it is lost).
        let inert = pinching && self.par.physical(x).get("zeta0") == Some(&0.0);
        (1..=DUAL_MAX).contains(&self.dim()) && self.par.spec.custom == 0 && !jumps && !inert
    }

    fn dual_jacobian<const N: usize>(
        &self,
        x: &[f64],
        observer: Option<Observer<f64>>,
    ) -> Option<(Vec<f64>, DMatrix<f64>)> {
        let effects = self.par.spec.effects;
        let xd: Vec<Dual<N>> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Dual::var(v, i))
            .collect();
        let values = self.par.physical_in(&xd);
        let limit = self.par.energy_limit.map(Dual::cst);
        let params = BwbnParams::from_named(effects, |name| {
            if name == ENERGY_LIMIT {
                return limit;
            }
            values.get(name).copied()
        })
        .ok()?;
        let xi = values.get("xi").copied().unwrap_or(Dual::ZERO);
        let c = self.control;
        let control = Control {
            method: c.method,
            tol: Dual::cst(c.tol),
            max_substeps: c.max_substeps,
        };
        let observer = observer.map(|o| Observer {
            k_u: Dual::cst(o.k_u),
            k_v: Dual::cst(o.k_v),
        });
        let out = self.exp.outputs(params, xi, control, observer).ok()?;
        let s = self.target.residual_scale();
        let mut jac = DMatrix::zeros(out.len(), x.len());
        let mut r = Vec::with_capacity(out.len());
        for (i, (yh, y)) in out.iter().zip(&self.target.output).enumerate() {
            r.push((yh.v - y) * s);
            for j in 0..x.len() {
                jac[(i, j)] = yh.d[j] * s;
            }
        }
        jac.iter().all(|v| v.is_finite()).then_some((r, jac))
    }

    /// Observer gains `K` of eq. 4.6 for this record: a critically damped
    /// observer three times faster than the initial natural frequency.
    pub fn observer_gains(&self) -> Option<Observer<f64>> {
        let Drive::Force { mass, .. } = self.exp.drive else {
            return None;
        };
        let w = 3.0 * (self.par.scales.stiffness() / mass).sqrt();
        Some(Observer {
            k_u: 2.0 * w,
            k_v: w * w,
        })
    }

    /// The observer of homotopy parameter `lambda`: the gains of
    /// [`observer_gains`](Self::observer_gains) times `lambda` (force drive only).
    pub fn coupling(&self, lambda: f64) -> Option<Observer<f64>> {
        let k = self.observer_gains()?;
        Some(Observer {
            k_u: lambda * k.k_u,
            k_v: lambda * k.k_v,
        })
    }

    /// Residuals at `x` of the model coupled to the measurement by
    /// `observer` (thesis eq. 4.6; `None`: the free model).
    pub fn residuals_observed(
        &self,
        x: &[f64],
        observer: Option<Observer<f64>>,
    ) -> Option<Vec<f64>> {
        let c = self.params(x)?;
        let pred = self
            .exp
            .simulate_observed(&c.params, &c.extras, c.xi, self.control, observer)
            .ok()?;
        Some(self.target.residuals(&pred))
    }
}

/// The problem as least squares sees it: its residuals, free or coupled to
/// the measurement by an observer, with exact Jacobians where
/// [`Problem::residuals_jacobian`] can compute them. Counts its evaluations
/// when given a counter (for progress display).
#[derive(Clone, Copy)]
pub struct LeastSquares<'a> {
    problem: &'a Problem,
    observer: Option<Observer<f64>>,
    counter: Option<&'a AtomicUsize>,
}

impl<'a> LeastSquares<'a> {
    /// The free model's residuals.
    pub fn new(problem: &'a Problem) -> Self {
        LeastSquares {
            problem,
            observer: None,
            counter: None,
        }
    }

    /// The residuals of the model coupled at homotopy parameter `lambda`
    /// (`None` for a displacement-driven record, which has no observer).
    pub fn coupled(problem: &'a Problem, lambda: f64) -> Option<Self> {
        Some(LeastSquares {
            observer: Some(problem.coupling(lambda)?),
            ..Self::new(problem)
        })
    }

    /// The same residuals, adding one to `counter` per evaluation.
    pub fn counting(self, counter: &'a AtomicUsize) -> Self {
        LeastSquares {
            counter: Some(counter),
            ..self
        }
    }

    fn count(&self) {
        if let Some(c) = self.counter {
            c.fetch_add(1, Ordering::Relaxed);
        }
    }
}

impl Residuals for LeastSquares<'_> {
    fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.count();
        self.problem.residuals_observed(x, self.observer)
    }

    fn residuals_jacobian(&self, x: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>)> {
        if !self.problem.has_exact_jacobian(x) {
            return None;
        }
        self.count();
        self.problem.jacobian_in_duals(x, self.observer)
    }
}

/// The problem as NSGA-II sees it: the four objectives of Ortiz et al.
/// (eqs 3.18-3.23) and, for quasi-static records, the thesis' stability
/// constraints beta + gamma > 0 and beta - gamma > 0 (section 3.4; they
/// exclude hardening sets, which dynamic records such as the Bouc-Wen
/// benchmark need, so they are off for force-driven records).
pub struct Ortiz<'a> {
    problem: &'a Problem,
    bounds: Vec<super::nsga2::Bounds>,
    constrained: bool,
    /// The fixed-step model the search simulates candidates with, several at a time, or why the
    /// problem allows none ([`SearchModel::for_problem`]).
    search: Result<SearchModel, Unsuited>,
}

impl<'a> Ortiz<'a> {
    /// Wraps a fitting problem, evaluating candidates with the lane-batched fixed-step model
    /// where [`SearchModel::for_problem`] finds one accurate enough.
    pub fn new(problem: &'a Problem) -> Self {
        let bounds = problem
            .par
            .free
            .iter()
            .map(|f| super::nsga2::Bounds {
                lower: f.lo,
                upper: f.hi,
            })
            .collect();
        let constrained = matches!(problem.exp.drive, Drive::Displacement);
        Ortiz {
            problem,
            bounds,
            constrained,
            search: SearchModel::for_problem(problem),
        }
    }

    /// The search model in use, or why there is none.
    pub fn search_summary(&self) -> Result<SearchSummary, Unsuited> {
        self.search
            .as_ref()
            .map(SearchModel::summary)
            .map_err(|u| *u)
    }

    fn evaluation(&self, x: &[f64], scores: Option<Scores>) -> super::nsga2::Evaluation {
        let objectives = match scores {
            Some(s) => s.ortiz.to_vec(),
            None => vec![f64::INFINITY; 4],
        };
        let violations = if self.constrained {
            let phys = self.problem.par.physical(x);
            let (b, g) = (phys["beta"], phys["gamma"]);
            // violation > 0 when broken: beta + gamma > 0 and beta - gamma > 0
            vec![-(b + g), -(b - g)]
        } else {
            vec![]
        };
        super::nsga2::Evaluation::new(objectives, violations)
    }

    /// Writes the front with physical parameter values.
    pub fn write_front(
        &self,
        path: &std::path::Path,
        front: &[&super::nsga2::Individual],
    ) -> Result<()> {
        use std::io::Write;
        let mut out = std::io::BufWriter::new(
            std::fs::File::create(path)
                .map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", path.display()))?,
        );
        let names = self.problem.par.names();
        writeln!(out, "{},f1,f2,f3,f4,nrmse", names.join(","))?;
        for ind in front {
            let phys = self.problem.par.physical(&ind.variables);
            // Scored again with the core's oscillator: the search's own objectives may come
            // from the fixed-step model.
            let scores = self.problem.scores(&ind.variables);
            let nrmse = scores.as_ref().map_or(f64::NAN, |s| s.nrmse);
            let vals: Vec<String> = names.iter().map(|n| phys[n].to_string()).collect();
            let objs: Vec<String> = match &scores {
                Some(s) => s.ortiz.iter().map(|v| v.to_string()).collect(),
                None => vec![f64::NAN.to_string(); 4],
            };
            writeln!(out, "{},{},{nrmse}", vals.join(","), objs.join(","))?;
        }
        Ok(())
    }
}

impl super::nsga2::Problem for Ortiz<'_> {
    fn bounds(&self) -> &[super::nsga2::Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        4
    }
    fn num_constraints(&self) -> usize {
        if self.constrained {
            2
        } else {
            0
        }
    }
    fn evaluate(&self, x: &[f64]) -> super::nsga2::Evaluation {
        self.evaluate_batch(&[x]).remove(0)
    }
    fn batch_size(&self) -> usize {
        if self.search.is_ok() {
            LANES
        } else {
            1
        }
    }
    fn evaluate_batch(&self, xs: &[&[f64]]) -> Vec<super::nsga2::Evaluation> {
        let scores: Vec<Option<Scores>> = match &self.search {
            Ok(model) => model.scores(self.problem, xs),
            Err(_) => xs.iter().map(|x| self.problem.scores(x)).collect(),
        };
        xs.iter()
            .zip(scores)
            .map(|(x, s)| self.evaluation(x, s))
            .collect()
    }
    fn variable_names(&self) -> Vec<String> {
        self.problem
            .par
            .names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
    fn objective_names(&self) -> Vec<String> {
        ["f1", "f2", "f3", "f4"].map(String::from).to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_shorter_than_the_parameter_count_is_refused() {
        let exp = |n: usize| Experiment {
            input: (0..n).map(|i| i as f64).collect(),
            output: (0..n).map(|i| 2.0 * i as f64).collect(),
            drive: Drive::Displacement,
        };
        let err = Problem::new(ModelSpec::BW, exp(5), &[])
            .expect_err("5 samples for 5 parameters")
            .to_string();
        assert!(
            err.contains("5 samples, too few to fit the 5 free parameters"),
            "{err}"
        );
        assert!(Problem::new(ModelSpec::BW, exp(6), &[]).is_ok());
    }
}
