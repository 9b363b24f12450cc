//! What exporting in `f32` or Q15.16 costs: the exported elements (decoded by
//! the device's loader, run in the device's arithmetic with its default
//! integration control) against the `f64` fit, force by force, over a
//! displacement history.
//!
//! The default history is the shape of the OpenSees reference history
//! (`../shared/data/opensees-reference/history.csv`): three triangular cycles
//! at each of 0.5, 1, 2, 4, 6 and 8 times a scale, 200 steps a cycle, 3601
//! points. The scale is the element's own: Zu (the ultimate hysteretic
//! displacement, `BwbnParams::z_scale`) for BWBN, so the reference set (Zu = 1
//! mm) gets exactly the reference history, and half the yield twist for PHM
//! (amplitudes from a quarter of yield to four times yield).

use super::{Elements, Sources};
use anyhow::{anyhow, Result};
use hysteresis::bwbn::{Bwbn, BwbnParams};
use hysteresis::phm::{Phm, PhmParams};
use hysteresis::table::{BwbnTable, PhmTable, ScalarKind, Table, TableScalar};
use hysteresis::{Element, Fixed, Scalar};

/// Amplitudes of the reference history, in units of the scale.
const AMPLITUDES: [f64; 6] = [0.5, 1.0, 2.0, 4.0, 6.0, 8.0];
const STEPS_PER_CYCLE: usize = 200;
const CYCLES: usize = 3;

/// The reference history's shape scaled by `scale`: 3601 points.
pub fn protocol(scale: f64) -> Vec<f64> {
    let mut u = vec![0.0];
    for a in AMPLITUDES {
        for _ in 0..CYCLES {
            for k in 1..=STEPS_PER_CYCLE {
                let tri = match k {
                    0..=50 => k as f64,
                    51..=150 => 100.0 - k as f64,
                    _ => k as f64 - 200.0,
                };
                u.push(scale * a * tri / 50.0);
            }
        }
    }
    u
}

/// One element's loss of precision.
#[derive(Clone, Debug, PartialEq)]
pub struct Precision {
    /// Largest |force| of the f64 element.
    pub peak: f64,
    /// Largest |force - force_f64|.
    pub max_error: f64,
    /// Points compared.
    pub points: usize,
    /// Why the comparison stopped before the end of the history, if it did
    /// (a step either element refused, e.g. beyond `energy_limit`).
    pub stopped: Option<String>,
    /// The exported element refused a step the `f64` one took: the device
    /// cannot follow this history, and its precision over it is unknown.
    pub device_stopped: bool,
}

impl Precision {
    /// The error as a fraction of the peak.
    pub fn relative(&self) -> f64 {
        if self.peak > 0.0 {
            self.max_error / self.peak
        } else {
            0.0
        }
    }
}

fn run<S: Scalar>(
    mut reference: impl Element<f64>,
    mut exported: impl Element<S>,
    u: &[f64],
) -> Precision {
    let mut p = Precision {
        peak: 0.0,
        max_error: 0.0,
        points: 0,
        stopped: None,
        device_stopped: false,
    };
    for (i, &x) in u.iter().enumerate().skip(1) {
        let stop = |who: &str, err| Some(format!("point {i} (u = {x}): the {who} element: {err}"));
        let r = match reference.set_trial(x) {
            Ok(r) => r,
            Err(err) => {
                p.stopped = stop("f64", err);
                break;
            }
        };
        let e = match exported.set_trial(S::from_f64(x)) {
            Ok(e) => e,
            Err(err) => {
                p.stopped = stop(S::NAME, err);
                p.device_stopped = true;
                break;
            }
        };
        p.peak = p.peak.max(r.force.abs());
        p.max_error = p.max_error.max((e.force.to_f64() - r.force).abs());
        p.points += 1;
        reference.commit();
        exported.commit();
    }
    p
}

fn bwbn<S: TableScalar>(
    fits: &[BwbnParams<f64>],
    bytes: &[u8],
    history: Option<&[f64]>,
) -> Result<Vec<Precision>> {
    let t = BwbnTable::<S>::load(bytes).map_err(|e| anyhow!("{e}"))?;
    Ok(fits
        .iter()
        .zip(t.iter())
        .map(|(fit, dev)| {
            let own;
            let u = match history {
                Some(h) => h,
                None => {
                    own = protocol(fit.z_scale());
                    &own
                }
            };
            run(Bwbn::new(*fit), Bwbn::<S>::new(dev), u)
        })
        .collect())
}

fn phm<S: TableScalar>(
    fits: &[PhmParams<f64, { crate::model::PHM_POINTS }>],
    bytes: &[u8],
    history: Option<&[f64]>,
) -> Result<Vec<Precision>> {
    let t = PhmTable::<S, { crate::model::PHM_POINTS }>::load(bytes).map_err(|e| anyhow!("{e}"))?;
    Ok(fits
        .iter()
        .zip(t.iter())
        .map(|(fit, dev)| {
            let own;
            let u = match history {
                Some(h) => h,
                None => {
                    let yield_twist =
                        fit.primary(hysteresis::phm::Direction::Positive).points()[1][0];
                    own = protocol(yield_twist / 2.0);
                    &own
                }
            };
            run(
                Phm::<f64, { crate::model::PHM_POINTS }>::new(fit.clone()),
                Phm::<S, { crate::model::PHM_POINTS }>::new(dev),
                u,
            )
        })
        .collect())
}

/// Compares every exported element of `bytes` (written from `src`) with its
/// f64 fit over `history` (default: the reference protocol at each
/// element's scale).
pub fn compare(src: &Sources, bytes: &[u8], history: Option<&[f64]>) -> Result<Vec<Precision>> {
    let scalar = Table::parse(bytes)
        .map_err(|e| anyhow!("{e}"))?
        .header()
        .scalar;
    match (&src.elements, scalar) {
        (Elements::Bwbn(f), ScalarKind::F64) => bwbn::<f64>(f, bytes, history),
        (Elements::Bwbn(f), ScalarKind::F32) => bwbn::<f32>(f, bytes, history),
        (Elements::Bwbn(f), _) => bwbn::<Fixed>(f, bytes, history),
        (Elements::Phm(f), ScalarKind::F64) => phm::<f64>(f, bytes, history),
        (Elements::Phm(f), ScalarKind::F32) => phm::<f32>(f, bytes, history),
        (Elements::Phm(f), _) => phm::<Fixed>(f, bytes, history),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn protocol_at_scale_one_is_the_opensees_reference_history() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/data/opensees-reference/history.csv");
        let text = std::fs::read_to_string(&path).unwrap();
        let reference: Vec<f64> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        let ours = protocol(1.0);
        assert_eq!(ours.len(), reference.len());
        for (i, (a, b)) in ours.iter().zip(&reference).enumerate() {
            assert!((a - b).abs() < 1e-12, "point {i}: {a} vs {b}");
        }
    }
}
