//! How well a prediction matches the measurement: the four objectives of
//! Ortiz et al. (thesis eqs 3.18-3.23) and the relative RMS error.
//!
//! The measured output `y` (force for quasi-static records, displacement for
//! dynamic ones) is compared with the prediction `y_hat`:
//!
//! * `f1 = sum |y - y_hat| / w` (eq. 3.18), `w` the envelope of |y| through
//!   its peaks, **floored** at a fraction of the peak (default 10%): as
//!   written, w is near zero at the start of a record, and there f1 weighs
//!   measurement noise by up to 1/w (measured: about 1,188 with 0.1 mm noise,
//!   throwing gamma off by up to 190%).
//! * `f2 = max |y - y_hat|` (eq. 3.19).
//! * `f3 = |E(t_end) - E_hat(t_end)|` (eq. 3.20), `E` the total energy input
//!   `∫ F du` (elastic plus hysteretic, eq. 3.21).
//! * `f4 = max |E(t) - E_hat(t)|` (eq. 3.23).
//! * `nrmse = RMS(y - y_hat) / RMS(y)`.

use super::experiment::{Experiment, Prediction};

/// The default floor of the envelope weight, as a fraction of the peak.
pub const ENVELOPE_FLOOR: f64 = 0.1;

/// What the objectives compare against, precomputed once per record.
#[derive(Clone, Debug)]
pub struct Target {
    /// Measured output.
    pub output: Vec<f64>,
    /// Envelope weight w(t) of eq. 3.18, floored.
    pub weight: Vec<f64>,
    /// Cumulative energy input `∫ F du` of the measurement.
    pub energy: Vec<f64>,
    /// RMS of the measured output.
    pub rms: f64,
}

/// The four Ortiz objectives and the relative RMS error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scores {
    /// f1..f4 of eqs 3.18-3.23.
    pub ortiz: [f64; 4],
    /// RMS(y - y_hat) / RMS(y).
    pub nrmse: f64,
}

/// The envelope of |y| through the peaks of its half-cycles (between zero
/// crossings), interpolated linearly and held at the ends, floored at
/// `floor * max|y|`.
pub fn envelope(y: &[f64], floor: f64) -> Vec<f64> {
    let mut peaks: Vec<(usize, f64)> = Vec::new();
    let mut start = 0;
    for i in 1..=y.len() {
        let crossed = i == y.len() || (y[i] > 0.0) != (y[start] > 0.0);
        if crossed {
            let (j, v) = (start..i).fold((start, 0.0f64), |b, k| {
                if y[k].abs() > b.1 {
                    (k, y[k].abs())
                } else {
                    b
                }
            });
            peaks.push((j, v));
            start = i;
        }
    }
    let top = peaks.iter().fold(0.0f64, |a, p| a.max(p.1));
    let mut w = vec![0.0; y.len()];
    for (i, wi) in w.iter_mut().enumerate() {
        let k = peaks.partition_point(|p| p.0 <= i);
        let v = match (k.checked_sub(1).map(|k| peaks[k]), peaks.get(k)) {
            (Some(a), Some(b)) => a.1 + (b.1 - a.1) * (i - a.0) as f64 / (b.0 - a.0) as f64,
            (Some(a), None) => a.1,
            (None, Some(b)) => b.1,
            (None, None) => 0.0,
        };
        *wi = v.max(floor * top).max(f64::MIN_POSITIVE);
    }
    w
}

/// Cumulative `∫ F du` by the trapezoidal rule.
pub fn energy_input(u: &[f64], f: &[f64]) -> Vec<f64> {
    let mut e = Vec::with_capacity(u.len());
    let mut acc = 0.0;
    e.push(0.0);
    for i in 1..u.len() {
        acc += 0.5 * (f[i] + f[i - 1]) * (u[i] - u[i - 1]);
        e.push(acc);
    }
    e
}

impl Target {
    /// The target of a record, with the envelope floor `floor`.
    pub fn new(exp: &Experiment, floor: f64) -> Target {
        let output = exp.output.clone();
        let rms = (output.iter().map(|v| v * v).sum::<f64>() / output.len().max(1) as f64).sqrt();
        Target {
            weight: envelope(&output, floor),
            energy: energy_input(exp.displacement(), exp.force()),
            output,
            rms,
        }
    }

    /// Scores of a prediction. `applied` is the force of the energy integral
    /// for the model: the predicted force (quasi-static) or the measured
    /// applied force (dynamic), integrated over the model's displacement.
    pub fn score(&self, exp: &Experiment, pred: &Prediction) -> Scores {
        let force = match exp.drive {
            super::experiment::Drive::Displacement => &pred.force,
            super::experiment::Drive::Force { .. } => &exp.input,
        };
        let e_hat = energy_input(&pred.displacement, force);
        let (mut f1, mut f2, mut sq) = (0.0, 0.0f64, 0.0);
        for ((y, yh), w) in self.output.iter().zip(&pred.output).zip(&self.weight) {
            let d = (y - yh).abs();
            f1 += d / w;
            f2 = f2.max(d);
            sq += d * d;
        }
        let f4 = self
            .energy
            .iter()
            .zip(&e_hat)
            .fold(0.0f64, |a, (e, eh)| a.max((e - eh).abs()));
        let f3 = (self.energy.last().unwrap_or(&0.0) - e_hat.last().unwrap_or(&0.0)).abs();
        let nrmse = (sq / self.output.len().max(1) as f64).sqrt() / self.rms.max(f64::MIN_POSITIVE);
        Scores {
            ortiz: [f1, f2, f3, f4],
            nrmse,
        }
    }

    /// The factor from prediction error to residual: `1 / (RMS(measured) sqrt(samples))`,
    /// so that the sum of squared residuals is NRMSE^2.
    pub fn residual_scale(&self) -> f64 {
        1.0 / (self.rms.max(f64::MIN_POSITIVE) * (self.output.len().max(1) as f64).sqrt())
    }

    /// Residual vector with `||r||^2 = nrmse^2`, for least squares.
    pub fn residuals(&self, pred: &Prediction) -> Vec<f64> {
        let s = self.residual_scale();
        self.output
            .iter()
            .zip(&pred.output)
            .map(|(y, yh)| (yh - y) * s)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn envelope_passes_through_the_peaks_and_is_floored() {
        // half-cycles peaking at 1, -2, 4
        let y = [0.5, 1.0, 0.5, -1.0, -2.0, -1.0, 2.0, 4.0, 2.0];
        let w = envelope(&y, 0.1);
        assert_eq!(w[1], 1.0);
        assert_eq!(w[4], 2.0);
        assert_eq!(w[7], 4.0);
        assert!((w[2] - (1.0 + (2.0 - 1.0) / 3.0)).abs() < 1e-12);
        assert_eq!(w[0], 1.0, "held before the first peak");
        let w = envelope(&[0.0, 0.01, 10.0], 0.1);
        assert_eq!(w[0], 1.0, "floored at 10% of the 10.0 peak");
    }

    #[test]
    fn energy_of_a_closed_rectangular_loop_is_its_area() {
        // u: 0 -> 1 at F = 1, back 1 -> 0 at F = -1: area 2
        let u = [0.0, 1.0, 1.0, 0.0, 0.0];
        let f = [1.0, 1.0, -1.0, -1.0, 1.0];
        let e = energy_input(&u, &f);
        assert!((e[4] - 2.0).abs() < 1e-12);
    }
}
