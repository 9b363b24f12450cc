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
use crate::data::Channel;

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

/// `∫ F du` from `(u0, f0)` to `(u1, f1)` by the trapezoidal rule: one term of [`energy_input`]
/// and of [`Running`].
#[inline(always)]
fn trapezoid((u0, f0): (f64, f64), (u1, f1): (f64, f64)) -> f64 {
    0.5 * (f1 + f0) * (u1 - u0)
}

/// Cumulative `∫ F du` by the trapezoidal rule.
pub fn energy_input(u: &[f64], f: &[f64]) -> Vec<f64> {
    let mut e = Vec::with_capacity(u.len());
    let mut acc = 0.0;
    e.push(0.0);
    for i in 1..u.len() {
        acc += trapezoid((u[i - 1], f[i - 1]), (u[i], f[i]));
        e.push(acc);
    }
    e
}

/// The net work `∫ F du` over the record and the gross work `∫ |F du|` (trapezoidal rule). A
/// passive specimen absorbs work: over whole cycles the net is positive, and it is a share of
/// the gross that grows with the loops' width (0.15 to 0.96 over the 409 PEER column records).
pub fn work(u: &[f64], f: &[f64]) -> (f64, f64) {
    u.windows(2)
        .zip(f.windows(2))
        .map(|(u, f)| trapezoid((u[0], f[0]), (u[1], f[1])))
        .fold((0.0, 0.0), |(net, gross), w| (net + w, gross + w.abs()))
}

/// Share of the gross work below which a net negative work marks a record as giving out
/// energy, which no passive specimen does: a channel's sign is flipped. The PEER columns absorb
/// at least 0.15 of their gross work; a record of elastic loading nets about zero either way.
pub const GIVES_OUT: f64 = 0.1;

/// A sentence when the displacement-driven record `(u, f)` gives out energy (net work below
/// `-GIVES_OUT` of the gross), `None` otherwise.
pub fn gives_out_energy(u: &[f64], f: &[f64], negated: &[Channel]) -> Option<String> {
    let (net, gross) = work(u, f);
    // A record read with `--negate` is named so, not told to use it again
    // (found by review).
    let remedy = match negated {
        [] => "`--negate force` flips it".to_string(),
        _ => {
            let given: Vec<String> = negated.iter().map(|c| format!("--negate {c}")).collect();
            format!(
                "it was read with `{}`: without it each channel has its sign as measured",
                given.join(" ")
            )
        }
    };
    (gross > 0.0 && net < -GIVES_OUT * gross).then(|| {
        format!(
            "the force does {net:.4e} kN mm of work on the displacement over the record, {:.0}% \
             of the {gross:.4e} it does in all: the record gives out energy, which no passive \
             specimen does, so the force or the displacement is likely of the wrong sign \
             ({remedy}); the models here absorb energy and cannot follow it",
            100.0 * net / gross
        )
    })
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

    /// Scores of a prediction. The energy integral of the model is taken over its displacement
    /// with its predicted force (quasi-static) or the measured applied force (dynamic).
    pub fn score(&self, exp: &Experiment, pred: &Prediction) -> Scores {
        let force = match exp.drive {
            super::experiment::Drive::Displacement => &pred.force,
            super::experiment::Drive::Force { .. } => &exp.input,
        };
        let mut running = self.running::<1>();
        for ((y_hat, u_hat), f) in pred.output.iter().zip(&pred.displacement).zip(force) {
            running.push(&[*y_hat], &[*u_hat], &[*f]);
        }
        let [scores] = running.scores();
        scores
    }

    /// The scores accumulated sample by sample for `L` predictions that are not stored (the
    /// fixed-step search model hands over its lanes' samples as it computes them).
    pub fn running<const L: usize>(&self) -> Running<'_, L> {
        Running {
            target: self,
            i: 0,
            f1: [0.0; L],
            f2: [0.0; L],
            sq: [0.0; L],
            e_hat: [0.0; L],
            f4: [0.0; L],
            last_u: [0.0; L],
            last_f: [0.0; L],
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

/// [`Target::score`] one sample at a time ([`Target::running`]) for `L` predictions at once
/// (vector lanes): the sums and maxima of the objectives, and each model's energy input by the
/// same trapezoidal rule as [`energy_input`].
#[derive(Clone, Debug)]
pub struct Running<'a, const L: usize> {
    target: &'a Target,
    /// Samples pushed.
    i: usize,
    f1: [f64; L],
    f2: [f64; L],
    sq: [f64; L],
    /// The models' energy input to the last sample.
    e_hat: [f64; L],
    f4: [f64; L],
    /// The last sample's displacements and forces.
    last_u: [f64; L],
    last_f: [f64; L],
}

impl<const L: usize> Running<'_, L> {
    /// The models' next samples: outputs, displacements and the forces of their energy
    /// integrals. Samples beyond the record's are ignored, as [`Target::score`]'s comparison
    /// ends with it.
    #[inline]
    pub fn push(&mut self, y_hat: &[f64; L], u_hat: &[f64; L], force: &[f64; L]) {
        let t = self.target;
        let (Some(&y), Some(&w), Some(&e)) = (
            t.output.get(self.i),
            t.weight.get(self.i),
            t.energy.get(self.i),
        ) else {
            return;
        };
        let first = self.i == 0;
        for l in 0..L {
            if !first {
                self.e_hat[l] += trapezoid((self.last_u[l], self.last_f[l]), (u_hat[l], force[l]));
            }
            let d = (y - y_hat[l]).abs();
            self.f1[l] += d / w;
            self.f2[l] = self.f2[l].max(d);
            self.sq[l] += d * d;
            self.f4[l] = self.f4[l].max((e - self.e_hat[l]).abs());
        }
        self.last_u = *u_hat;
        self.last_f = *force;
        self.i += 1;
    }

    /// The scores of the samples pushed, one per lane. Before the last sample of the record,
    /// `f3` compares the energies at the last sample pushed.
    pub fn scores(&self) -> [Scores; L] {
        let t = self.target;
        let last = self.i.checked_sub(1).and_then(|k| t.energy.get(k));
        let e_end = last.copied().unwrap_or(0.0);
        let n = t.output.len().max(1) as f64;
        core::array::from_fn(|l| Scores {
            ortiz: [
                self.f1[l],
                self.f2[l],
                (e_end - self.e_hat[l]).abs(),
                self.f4[l],
            ],
            nrmse: (self.sq[l] / n).sqrt() / t.rms.max(f64::MIN_POSITIVE),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One cycle `u = cos t` with `f = -s sin t + k u`: the loop encloses `s π`, the work the
    /// force does over the cycle (positive for `s > 0`, a passive loop), whatever the elastic
    /// part `k u`; the gross work is `s π` plus what the elastic part does both ways.
    fn ellipse(s: f64, k: f64) -> (Vec<f64>, Vec<f64>) {
        let t = (0..=2000).map(|i| i as f64 * std::f64::consts::TAU / 2000.0);
        t.map(|t| (t.cos(), -s * t.sin() + k * t.cos())).unzip()
    }

    #[test]
    fn the_work_of_a_loop_is_its_area_and_a_flipped_loop_gives_energy_out() {
        use std::f64::consts::PI;
        let (u, f) = ellipse(1.0, 0.0);
        let (net, gross) = work(&u, &f);
        // Trapezoidal rule on 2,000 intervals: error O(h^2), about 1e-6 here.
        assert!((net - PI).abs() < 1e-5, "{net}");
        assert!((gross - PI).abs() < 1e-5, "{gross}");
        assert!(gives_out_energy(&u, &f, &[]).is_none());
        let flipped: Vec<f64> = f.iter().map(|f| -f).collect();
        let words = gives_out_energy(&u, &flipped, &[]).expect("a flipped loop gives energy out");
        assert!(words.contains("(`--negate force` flips it)"), "{words}");
        // Read with `--negate` already, the note names it rather than suggesting it.
        let words = gives_out_energy(&u, &flipped, &[Channel::Force]).unwrap();
        assert!(
            words.contains("(it was read with `--negate force`: without it each channel"),
            "{words}"
        );
        // An elastic record does no net work either way round: not flagged.
        let (u, f) = ellipse(0.0, 2.0);
        assert!(work(&u, &f).0.abs() < 1e-9);
        assert!(gives_out_energy(&u, &f.iter().map(|f| -f).collect::<Vec<_>>(), &[]).is_none());
        // A thin loop flipped gives out 5% of its gross work: below the threshold, not named.
        let (u, f) = ellipse(0.1, 2.0);
        let (net, gross) = work(&u, &f);
        assert!(net > 0.0 && net < GIVES_OUT * gross, "{net} {gross}");
        assert!(gives_out_energy(&u, &f.iter().map(|f| -f).collect::<Vec<_>>(), &[]).is_none());
    }

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

    /// The objectives of a three-sample quasi-static record, worked out by hand: measured force
    /// 0, 2, -1 and predicted 0, 1, -2 over the displacements 0, 1, 0. Envelope weights (peaks
    /// 2 and 1, floor 0.2): 0.2, 2, 1. Energies by the trapezoidal rule: measured 0, 1, 0.5,
    /// model 0, 0.5, 1.
    #[test]
    fn scores_of_a_record_worked_out_by_hand() {
        use super::super::experiment::Drive;
        let exp = Experiment {
            input: vec![0.0, 1.0, 0.0],
            output: vec![0.0, 2.0, -1.0],
            drive: Drive::Displacement,
        };
        let force = vec![0.0, 1.0, -2.0];
        let pred = Prediction {
            output: force.clone(),
            displacement: exp.input.clone(),
            force,
            energy: vec![0.0; 3],
        };
        let expected = Scores {
            // f1 = 0/0.2 + 1/2 + 1/1; f2 = 1; f3 = |0.5 - 1|; f4 = max(0, 0.5, 0.5)
            ortiz: [1.5, 1.0, 0.5, 0.5],
            // sqrt(2/3) / sqrt(5/3)
            nrmse: (2.0f64 / 5.0).sqrt(),
        };
        let target = Target::new(&exp, ENVELOPE_FLOOR);
        let close = |a: Scores| {
            let pairs = a.ortiz.iter().zip(&expected.ortiz);
            pairs
                .chain([(&a.nrmse, &expected.nrmse)])
                .all(|(x, y)| (x - y).abs() < 1e-15)
        };
        assert!(
            close(target.score(&exp, &pred)),
            "{:?}",
            target.score(&exp, &pred)
        );
        // The same prediction in the second of two lanes, next to a perfect one.
        let mut lanes = target.running::<2>();
        for i in 0..3 {
            let y = [exp.output[i], pred.output[i]];
            let u = [exp.input[i]; 2];
            lanes.push(&y, &u, &y);
        }
        let [perfect, lane] = lanes.scores();
        assert!(close(lane), "{lane:?}");
        assert_eq!(perfect.ortiz, [0.0; 4]);
        assert_eq!(perfect.nrmse, 0.0);
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
