//! The fitting problem: a model spec on a record, seen by the optimisers as a
//! function of a normalised parameter vector.

use super::experiment::{Drive, Experiment, Prediction};
use super::objectives::{Scores, Target, ENVELOPE_FLOOR};
use super::parametrization::Candidate;
use super::parametrization::Parametrization;
use crate::model::ModelSpec;
use anyhow::Result;
use hysteresis::bwbn::{Control, Method, Observer};

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

impl Problem {
    /// The problem of fitting `spec` to `exp` with `fixed` parameters
    /// (physical values).
    pub fn new(spec: ModelSpec, exp: Experiment, fixed: &[(String, f64)]) -> Result<Self> {
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
        let control = Control {
            method: Method::Dp54,
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
        let c = self.params(x)?;
        self.exp
            .simulate(&c.params, &c.extras, c.xi, self.control)
            .ok()
    }

    /// Scores at `x`.
    pub fn scores(&self, x: &[f64]) -> Option<Scores> {
        Some(self.target.score(&self.exp, &self.predict(x)?))
    }

    /// Least-squares residuals at `x` (`||r||^2 = nrmse^2`).
    pub fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        Some(self.target.residuals(&self.predict(x)?))
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

    /// Residuals of the observer-coupled model at homotopy parameter `lambda`
    /// (force drive only).
    pub fn residuals_coupled(&self, x: &[f64], lambda: f64) -> Option<Vec<f64>> {
        let k = self.observer_gains()?;
        let obs = Observer {
            k_u: lambda * k.k_u,
            k_v: lambda * k.k_v,
        };
        let c = self.params(x)?;
        let pred = self
            .exp
            .simulate_observed(&c.params, &c.extras, c.xi, self.control, Some(obs))
            .ok()?;
        Some(self.target.residuals(&pred))
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
}

impl<'a> Ortiz<'a> {
    /// Wraps a fitting problem.
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
        }
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
            let nrmse = self
                .problem
                .scores(&ind.variables)
                .map_or(f64::NAN, |s| s.nrmse);
            let vals: Vec<String> = names.iter().map(|n| phys[n].to_string()).collect();
            let objs: Vec<String> = ind.objectives.iter().map(|v| v.to_string()).collect();
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
        let objectives = match self.problem.scores(x) {
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
