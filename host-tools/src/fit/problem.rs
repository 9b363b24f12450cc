//! The fitting problem: a model spec on a record, seen by the optimisers as a
//! function of a normalised parameter vector.

use super::experiment::{Drive, Experiment, Prediction};
use super::objectives::{Scores, Target, ENVELOPE_FLOOR};
use super::parametrization::Parametrization;
use crate::model::ModelSpec;
use anyhow::Result;
use hysteresis::bwbn::{BwbnParams, Control, Method, Observer};

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

    /// The parameter set at `x`, if valid.
    pub fn params(&self, x: &[f64]) -> Option<(BwbnParams<f64>, f64)> {
        self.par.build(x).ok()
    }

    /// The prediction at `x` (None: invalid parameters or a failed step).
    pub fn predict(&self, x: &[f64]) -> Option<Prediction> {
        let (p, xi) = self.params(x)?;
        self.exp.simulate(&p, xi, self.control).ok()
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
        let (p, xi) = self.params(x)?;
        let pred = self
            .exp
            .simulate_observed(&p, xi, self.control, Some(obs))
            .ok()?;
        Some(self.target.residuals(&pred))
    }
}
