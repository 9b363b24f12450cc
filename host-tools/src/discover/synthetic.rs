//! Lab-like records with hidden effects, made with the project's own
//! simulator, to test that the discovery loop names what is missing and
//! invents nothing when nothing is.
//!
//! A column-like Bouc-Wen base in mm and kN (k0 = 20 kN/mm, alpha = 0.03,
//! n = 1.5, beta = 0.6, gamma = 0.4, so Zu = 1 mm and the hysteretic
//! strength about 19 kN), optionally with hidden effects at moderate
//! strength, driven along a step-wise protocol (two cycles at each of 0.5, 1,
//! 2, 3, 4, 6 and 8 mm, 60 samples a cycle) or an irregular earthquake-like
//! path (peak 6 mm), with Gaussian noise on the measured displacement and
//! force (two levels). [`record_with_gap`] puts the base behind a gap: slip,
//! which no effect of the library models.

use crate::data::{Irregular, Normal, Protocol, Shape};
use crate::fit::experiment::{Drive, Experiment};
use crate::model::{EffectRef, ModelSpec};
use anyhow::{anyhow, Result};
use hysteresis::bwbn::{Bwbn, Control, EffectKind, Method};
use hysteresis::Element;

/// The displacement path of a synthetic test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// Two cycles at each of 0.5, 1, 2, 3, 4, 6, 8 mm.
    StepWise,
    /// Earthquake-like, peak 6 mm, from this seed.
    Irregular(u64),
}

/// Measurement noise. The displacement noise is given against the yield
/// displacement Zu = 1 mm: the elastic stiffness turns it into force noise
/// (k0 = 20 kN/mm against a strength of about 19 kN), so 1% of Zu is already
/// 1% of the strength, as in the shared synthetic records (0.2 mm on a yield
/// displacement of about 17 mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Noise {
    /// Standard deviation of the displacement noise, mm.
    pub displacement: f64,
    /// Standard deviation of the force noise, as a fraction of the peak force.
    pub force: f64,
}

impl Noise {
    /// 0.5% of Zu and 0.5% of peak force.
    pub const LOW: Noise = Noise {
        displacement: 0.005,
        force: 0.005,
    };
    /// 1.5% of Zu and 1.5% of peak force (the shared records: 1.2% and 1%).
    pub const HIGH: Noise = Noise {
        displacement: 0.015,
        force: 0.015,
    };
}

/// The base model's parameters.
pub const BASE: [(&str, f64); 5] = [
    ("k0", 20.0),
    ("alpha", 0.03),
    ("n", 1.5),
    ("beta", 0.6),
    ("gamma", 0.4),
];

/// The hidden parameters of each effect, at a strength a lab would see.
pub fn hidden_values(kind: EffectKind) -> &'static [(&'static str, f64)] {
    match kind {
        EffectKind::Pinching => &[
            ("zeta0", 0.85),
            ("p", 0.02),
            ("q", 0.1),
            ("psi0", 0.25),
            ("delta_psi", 0.0),
            ("lambda", 0.5),
        ],
        EffectKind::StrengthDegradation => &[("delta_nu", 1.2e-3)],
        EffectKind::StiffnessDegradation => &[("delta_eta", 1e-3)],
        EffectKind::ADegradation => &[("delta_A", 1.5e-4)],
        EffectKind::Asymmetry => &[("asym_strength", 0.3)],
    }
}

/// The displacement path, mm.
pub fn path(path: Path) -> Vec<f64> {
    match path {
        Path::StepWise => Protocol {
            amplitudes: vec![0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0],
            cycles_per_amplitude: 2,
            steps_per_cycle: 60,
            shape: Shape::Triangular,
        }
        .generate(),
        Path::Irregular(seed) => Irregular {
            samples: 1501,
            dt: 0.02,
            frequency_hz: 0.5,
            q: 2.0,
            peak: 6.0,
            peak_time_fraction: 0.4,
            seed,
        }
        .generate(),
    }
    .expect("the synthetic paths have valid settings")
}

/// The base model with the `hidden` effects at [`hidden_values`], where
/// `values` does not say otherwise, integrated far more tightly than any fit
/// does.
fn element(hidden: &[EffectKind], values: &[(&str, f64)]) -> Result<Bwbn<f64>> {
    let mut spec = ModelSpec::BW;
    for k in hidden {
        spec = spec.with(EffectRef::Builtin(*k));
    }
    let values: Vec<(&str, f64)> = values
        .iter()
        .copied()
        .chain(BASE.iter().copied())
        .chain(
            hidden
                .iter()
                .flat_map(|k| hidden_values(*k).iter().copied()),
        )
        .collect();
    let (params, _) = spec
        .build(|n| {
            if n == hysteresis::bwbn::ENERGY_LIMIT {
                return Some(5000.0);
            }
            values.iter().find(|(k, _)| *k == n).map(|(_, v)| *v)
        })
        .map_err(|e| anyhow!("synthetic model: {e}"))?;
    let tight = Control {
        method: Method::Dp54,
        tol: 1e-10,
        max_substeps: 2000,
    };
    Bwbn::new(params)
        .with_control(tight)
        .map_err(|e| anyhow!("synthetic model: {e}"))
}

/// A record of the base model with the `hidden` effects, along `path`, with
/// `noise` from `seed`.
pub fn record(
    hidden: &[EffectKind],
    path_kind: Path,
    noise: Noise,
    seed: u64,
) -> Result<Experiment> {
    record_with(hidden, &[], path_kind, noise, seed)
}

/// As [`record`], with `values` in place of the base's and the hidden
/// effects' own (`("p", 0.0018)`: pinching that grows over the test).
pub fn record_with(
    hidden: &[EffectKind],
    values: &[(&str, f64)],
    path_kind: Path,
    noise: Noise,
    seed: u64,
) -> Result<Experiment> {
    let u = path(path_kind);
    let mut el = element(hidden, values)?;
    let mut f = Vec::with_capacity(u.len());
    for &ui in &u {
        f.push(
            el.set_trial(ui)
                .map_err(|e| anyhow!("synthetic record: {e}"))?
                .force,
        );
        el.commit();
    }
    Ok(measured(&u, &f, noise, seed))
}

/// The record as a lab measures it: `u` and `f` with `noise` from `seed`.
fn measured(u: &[f64], f: &[f64], noise: Noise, seed: u64) -> Experiment {
    let peak = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut gauss = Normal::new(seed);
    let u_meas = u
        .iter()
        .map(|v| v + noise.displacement * gauss.sample())
        .collect();
    let f_meas = f
        .iter()
        .map(|v| v + noise.force * peak * gauss.sample())
        .collect();
    Experiment {
        input: u_meas,
        output: f_meas,
        drive: Drive::Displacement,
    }
}

/// A record of the base model behind a gap: slip, an effect the library
/// does not have (bars slipping in their anchorage, a bolt in an oversized
/// hole, backlash). The base element sits in series with a slider that moves
/// freely at zero force within `[-gap, gap]` (mm) and bears at its ends; it
/// starts centred. On every reversal the element unloads to zero force, the
/// slider crosses the gap at zero force, and the element loads again from
/// there: a flat plateau of zero force `2 gap` long.
pub fn record_with_gap(gap: f64, path_kind: Path, noise: Noise, seed: u64) -> Result<Experiment> {
    if !(gap.is_finite() && gap >= 0.0) {
        return Err(anyhow!("the gap must be a finite length >= 0, not {gap}"));
    }
    let mut el = element(&[], &[])?;
    let trial = |el: &mut Bwbn<f64>, y: f64| {
        el.set_trial(y)
            .map(|r| r.force)
            .map_err(|e| anyhow!("synthetic record: {e}"))
    };
    let u = path(path_kind);
    let mut f = Vec::with_capacity(u.len());
    // The slider's position and the element's committed force.
    let (mut slip, mut force) = (0.0f64, 0.0f64);
    for &ui in &u {
        let trial_force = trial(&mut el, ui - slip)?;
        let bearing = (slip >= gap && trial_force >= 0.0) || (slip <= -gap && trial_force <= 0.0);
        if bearing {
            el.commit();
            force = trial_force;
            f.push(force);
            continue;
        }
        // The element unloads to zero force first: bisect for that point
        // between the committed displacement and the trial.
        let y_committed = el.committed().u;
        let mut zero = y_committed;
        if force != 0.0 {
            let (mut a, mut b) = (y_committed, ui - slip);
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if trial(&mut el, m)?.signum() == force.signum() {
                    a = m;
                } else {
                    b = m;
                }
            }
            zero = 0.5 * (a + b);
            trial(&mut el, zero)?;
            el.commit();
        }
        // Then the slider moves, and bears again at the other end.
        slip = (ui - zero).clamp(-gap, gap);
        force = if (ui - zero).abs() <= gap {
            0.0
        } else {
            let r = trial(&mut el, ui - slip)?;
            el.commit();
            r
        };
        f.push(force);
    }
    Ok(measured(&u, &f, noise, seed))
}
