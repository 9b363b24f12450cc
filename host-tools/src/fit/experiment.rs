//! What is fitted: a record's input and output, how the model is driven, and
//! simulating a candidate parameter set on it.
//!
//! * [`Drive::Displacement`]: quasi-static tests (the RC columns). The imposed
//!   displacement drives a [`Bwbn`] element; the model predicts the force.
//! * [`Drive::Force`]: dynamic tests (thesis ch. 4, the Bouc-Wen benchmark).
//!   The applied force drives the oscillator of eqs 3.13-3.17 ([`Sdof`]); the
//!   model predicts the displacement; between samples the force is linear or
//!   cubic ([`Between`]).

pub use super::forcing::Between;
use crate::model::Extras;
use hysteresis::bwbn::{Bwbn, BwbnParams, Control, Effect, Observer, Sdof};
use hysteresis::{Element, Scalar, StepError};

/// How the model is driven by the record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Drive {
    /// Input displacement, output force.
    Displacement,
    /// Input force, output displacement, sampled every `dt` seconds, on a mass
    /// `mass` (force unit / (displacement unit / s^2)).
    Force {
        /// Sample interval (s).
        dt: f64,
        /// Mass in force / (displacement / s^2) (kN s^2/mm for kN and mm).
        mass: f64,
        /// How the force goes between samples.
        between: Between,
    },
}

/// A record ready for fitting.
#[derive(Clone, Debug)]
pub struct Experiment {
    /// What drives the model: displacement (quasi-static) or force (dynamic).
    pub input: Vec<f64>,
    /// What the model must reproduce: force (quasi-static) or displacement.
    pub output: Vec<f64>,
    /// How the model is driven.
    pub drive: Drive,
}

/// Why a candidate could not be simulated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SimError {
    /// The parameter set was rejected.
    Params(hysteresis::bwbn::ParamError),
    /// A step failed at this sample (0-based; shown counted from 1, as `simulate` does).
    Step(usize, StepError),
}

impl std::fmt::Display for SimError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SimError::Params(e) => write!(f, "invalid parameters: {e}"),
            SimError::Step(i, e) => write!(f, "step to sample {} failed: {e}", i + 1),
        }
    }
}

impl std::error::Error for SimError {}

/// A model prediction for every sample, with the model's hysteretic energy.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Prediction {
    /// The predicted output (force or displacement).
    pub output: Vec<f64>,
    /// Displacement (measured for displacement drive, predicted for force drive).
    pub displacement: Vec<f64>,
    /// Restoring force of the model (for force drive: per unit mass times the
    /// mass, i.e. in force units).
    pub force: Vec<f64>,
    /// Hysteretic energy of the model (eq. 3.8).
    pub energy: Vec<f64>,
}

impl Experiment {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.output.len()
    }

    /// True when the record has no samples.
    pub fn is_empty(&self) -> bool {
        self.output.is_empty()
    }

    /// The measured displacement history.
    pub fn displacement(&self) -> &[f64] {
        match self.drive {
            Drive::Displacement => &self.input,
            Drive::Force { .. } => &self.output,
        }
    }

    /// The measured force history.
    pub fn force(&self) -> &[f64] {
        match self.drive {
            Drive::Displacement => &self.output,
            Drive::Force { .. } => &self.input,
        }
    }

    /// Simulates the model with `params` and custom effects `extras` (`xi`
    /// for force drive) on the record.
    pub fn simulate(
        &self,
        params: &BwbnParams<f64>,
        extras: &Extras,
        xi: f64,
        control: Control<f64>,
    ) -> Result<Prediction, SimError> {
        self.simulate_observed(params, extras, xi, control, None)
    }

    /// Like [`simulate`](Self::simulate), with the observer coupling of thesis
    /// eq. 4.6 pulling the model towards the measured displacement (force
    /// drive only; `None` simulates freely).
    pub fn simulate_observed(
        &self,
        params: &BwbnParams<f64>,
        extras: &Extras,
        xi: f64,
        control: Control<f64>,
        observer: Option<Observer<f64>>,
    ) -> Result<Prediction, SimError> {
        let n = self.len();
        let mut out = Prediction {
            output: Vec::with_capacity(n),
            displacement: Vec::with_capacity(n),
            force: Vec::with_capacity(n),
            energy: Vec::with_capacity(n),
        };
        self.run(*params, extras, xi, control, observer, |s| {
            out.output.push(s.output);
            out.displacement.push(s.displacement);
            out.force.push(s.force);
            out.energy.push(s.energy);
        })?;
        Ok(out)
    }

    /// The predicted output in any arithmetic, for the built-in effects (no
    /// custom ones): in [`Dual`](super::dual::Dual) numbers it carries the
    /// derivatives of the prediction with respect to the parameters.
    pub fn outputs<S: Scalar>(
        &self,
        params: BwbnParams<S>,
        xi: S,
        control: Control<S>,
        observer: Option<Observer<S>>,
    ) -> Result<Vec<S>, SimError> {
        let mut out = Vec::with_capacity(self.len());
        self.run(params, (), xi, control, observer, |s| out.push(s.output))?;
        Ok(out)
    }

    /// Drives the model through the record, handing every sample to `sink`.
    fn run<S: Scalar, X: Effect<S>>(
        &self,
        params: BwbnParams<S>,
        extra: X,
        xi: S,
        control: Control<S>,
        observer: Option<Observer<S>>,
        mut sink: impl FnMut(Sample<S>),
    ) -> Result<(), SimError> {
        match self.drive {
            Drive::Displacement => {
                let mut el = Bwbn::with_extra(params, extra, control).map_err(SimError::Params)?;
                for (i, &u) in self.input.iter().enumerate() {
                    let r = el
                        .set_trial(S::from_f64(u))
                        .map_err(|e| SimError::Step(i, e))?;
                    el.commit();
                    sink(Sample {
                        output: r.force,
                        displacement: S::from_f64(u),
                        force: r.force,
                        energy: el.committed().energy,
                    });
                }
            }
            Drive::Force { dt, mass, between } => {
                let m = S::from_f64(mass);
                let per_mass = params.per_unit_mass(m).map_err(SimError::Params)?;
                let mut osc =
                    Sdof::with_extra(per_mass, xi, extra, control).map_err(SimError::Params)?;
                let first = self.input.first().copied().unwrap_or(0.0);
                osc.set_forcing(S::from_f64(first / mass))
                    .map_err(|e| SimError::Step(0, e))?;
                let sample = |osc: &Sdof<S, X>| {
                    let s = osc.state();
                    Sample {
                        output: s.u,
                        displacement: s.u,
                        force: osc.restoring() * m,
                        energy: s.energy * m,
                    }
                };
                sink(sample(&osc));
                let rates = (between == Between::Cubic).then(|| {
                    let per_mass: Vec<f64> = self.input.iter().map(|f| f / mass).collect();
                    super::forcing::rates(&per_mass, dt)
                });
                let dt = S::from_f64(dt);
                for i in 1..self.len() {
                    let f = super::forcing::step(&self.input, mass, rates.as_deref(), i);
                    let step = match observer {
                        Some(obs) => osc.step_observed(
                            dt,
                            f,
                            S::from_f64(self.output[i - 1]),
                            S::from_f64(self.output[i]),
                            obs,
                        ),
                        None => osc.step_forced(dt, f),
                    };
                    step.map_err(|e| SimError::Step(i, e))?;
                    sink(sample(&osc));
                }
            }
        }
        Ok(())
    }
}

/// One sample of a simulation.
struct Sample<S> {
    output: S,
    displacement: S,
    force: S,
    energy: S,
}

/// Refuses a mass (kg) the mass-normalised oscillator cannot be simulated
/// with on a record from `src` (applied `force` in kN, measured
/// `displacement` in mm where there is one), sampled every `dt` seconds: one
/// whose peak force over mass is beyond `f64` (the mass was taken and the
/// failure blamed on k0, found by review), or one that makes the oscillator
/// turn more than [`MAX_RADIANS_A_SAMPLE`] in a sample interval with the
/// record's secant stiffness (peak force over peak displacement), or with
/// `k0` (its value and where it was given) for a record without
/// displacement: an explicit integrator follows it a few radians a sub-step,
/// 1000 sub-steps a sample at most, so that is a unit slip (kN s^2/mm for kg
/// turns it 1000x faster), not a record (`--mass 1e-300` failed as "model
/// diverged").
pub fn check_mass(
    src: impl std::fmt::Display,
    mass: f64,
    force: &[f64],
    displacement: Option<&[f64]>,
    k0: Option<(f64, &str)>,
    dt: f64,
) -> anyhow::Result<()> {
    let peak = |x: &[f64]| x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let peak_force = peak(force);
    // kg = N s^2/m = 1e-6 kN s^2/mm
    let m = mass * 1e-6;
    if !(m.is_normal() && (peak_force / m).is_finite()) {
        anyhow::bail!(
            "{src}: the mass of {mass:e} kg is too small for this record: its peak force over the mass ({peak_force:e} kN / {m:e} kN s^2/mm) is beyond the range of f64"
        );
    }
    let stiffness = match (displacement.map(peak), k0) {
        (Some(peak_u), _) if peak_u > 0.0 => Some((
            peak_force / peak_u,
            "secant stiffness, peak force over peak displacement".to_string(),
        )),
        (_, Some((k, place))) => Some((k, format!("initial stiffness k0 ({place})"))),
        _ => None,
    };
    let Some((k, what)) = stiffness else {
        return Ok(());
    };
    let radians = (k / m).sqrt() * dt;
    if k.is_finite() && (radians.is_nan() || radians > MAX_RADIANS_A_SAMPLE) {
        anyhow::bail!(
            "{src}: the mass of {mass:e} kg is too small for this record: with its {what} ({k:e} kN/mm) the oscillator turns {radians:.3e} radians in one sample interval ({dt:e} s), where it can be followed up to {MAX_RADIANS_A_SAMPLE}; the mass is in kg (the thesis' example: 500 kg on 6 kN/mm at 500 Hz, 0.22 radians a sample)"
        );
    }
    Ok(())
}

/// The most radians the undamped oscillator may turn in one sample interval
/// with the record's secant stiffness ([`check_mass`]). A lab record turns
/// well under one (0.22 for the thesis' example and the benchmark). The
/// thesis' record with smaller masses, least squares from the default start
/// (a review, 2026-11-30): 30 radians converged in 72 simulations, 60 and 95
/// returned the start after one simulation (NRMSE 0.49), 123 stalled after
/// two, and from 151 the first simulation ran out of its 1000 sub-steps a
/// sample.
pub const MAX_RADIANS_A_SAMPLE: f64 = 30.0;

impl Experiment {
    /// The experiment of a lab record (canonical units mm, kN, s). A
    /// force-driven record needs a uniform time base and the mass in kg.
    pub fn from_record(record: &crate::data::Record, mass_kg: Option<f64>) -> anyhow::Result<Self> {
        use crate::data::Channel;
        use anyhow::{anyhow, bail};
        let src = record.source().display();
        if record.is_torsion() {
            bail!(
                "{src}: {}: a twist/torque record, which the Bouc-Wen models do not take: fit it with --model phm-torsion, or give the column a length or force unit (--force COLUMN:kN)",
                record.channels_in_words()
            );
        }
        let (u, f) = record.displacement_force()?;
        match record.input_channel() {
            Channel::Displacement => {
                if mass_kg.is_some() {
                    bail!("{src}: --mass is for force-driven records; this one is driven by displacement");
                }
                Ok(Experiment {
                    input: u.to_vec(),
                    output: f.to_vec(),
                    drive: Drive::Displacement,
                })
            }
            Channel::Force => {
                let mass = mass_kg.ok_or_else(|| {
                    anyhow!("{src}: the record is driven by force, so the oscillator needs its mass: give --mass KG")
                })?;
                if !(mass.is_finite() && mass > 0.0) {
                    bail!("--mass must be a positive number of kg, got {mass}");
                }
                let dt = uniform_step(record)?;
                check_mass(&src, mass, f, Some(u), None, dt)?;
                let m = mass * 1e-6;
                Ok(Experiment {
                    input: f.to_vec(),
                    output: u.to_vec(),
                    drive: Drive::Force {
                        dt,
                        mass: m,
                        between: Between::Linear,
                    },
                })
            }
        }
    }

    /// The same experiment with the force going `between` samples as given;
    /// an error for a displacement-driven one, whose model has no forcing.
    pub fn with_forcing(mut self, between: Between) -> anyhow::Result<Self> {
        match &mut self.drive {
            Drive::Force { between: b, .. } => *b = between,
            Drive::Displacement => anyhow::bail!(
                "--forcing is for force-driven records (give --mass); this one is driven by displacement"
            ),
        }
        Ok(self)
    }
}

/// The time step of a force-driven record, which must be uniform (the
/// oscillator is stepped sample by sample).
pub fn uniform_step(record: &crate::data::Record) -> anyhow::Result<f64> {
    use anyhow::{anyhow, bail};
    let src = record.source().display();
    let t = record.time().ok_or_else(|| {
        anyhow!("{src}: a force-driven record needs a time column or --sample-rate")
    })?;
    if t.len() < 2 {
        bail!("{src}: a force-driven record needs at least two samples");
    }
    // Each step against the median one: against the mean, one missing row shifted the
    // reference and the check blamed the first sample instead of the gap (found by review).
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    let typical = steps[steps.len() / 2];
    if let Some(i) = (1..t.len()).find(|&i| ((t[i] - t[i - 1]) - typical).abs() > 1e-6 * typical) {
        bail!(
            "{src}: sample {} is {} s after the previous one, where the record's steps are {typical} s: force-driven models need uniform sampling",
            i + 1,
            t[i] - t[i - 1]
        );
    }
    Ok((t[t.len() - 1] - t[0]) / (t.len() - 1) as f64)
}
