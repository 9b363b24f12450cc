//! Synthetic displacement histories (mm) to drive models: step-wise
//! increasing-amplitude protocols such as the OpenSees reference history, and
//! an irregular earthquake-like path from a seeded random process.
//!
//! ```
//! use hyst::data::{Irregular, Protocol};
//! let h = Protocol::opensees_reference().generate().unwrap();
//! assert_eq!(h.len(), 3601);
//! assert_eq!(h[50], 0.5); // first peak
//! let q = Irregular { peak: 30.0, seed: 7, ..Irregular::default() }.generate().unwrap();
//! assert_eq!(q.iter().fold(0.0f64, |m, v| m.max(v.abs())), 30.0);
//! ```

use std::f64::consts::PI;
use std::fmt;

use crate::random::SplitMix64;

/// A generator parameter out of range.
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryError(String);

impl fmt::Display for HistoryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for HistoryError {}

fn require(ok: bool, message: impl FnOnce() -> String) -> Result<(), HistoryError> {
    if ok {
        Ok(())
    } else {
        Err(HistoryError(message()))
    }
}

/// The wave form of one protocol cycle: `0 → +A → 0 → −A → 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Straight ramps (constant rate), as in quasi-static lab tests.
    Triangular,
    /// `A sin(2π k / N)`.
    Sine,
}

/// A step-wise increasing-amplitude cyclic protocol: a number of cycles at
/// each amplitude, each cycle `0 → +A → 0 → −A → 0` in `steps_per_cycle`
/// steps, starting from 0 (so `1 + amplitudes × cycles × steps` samples).
#[derive(Clone, Debug, PartialEq)]
pub struct Protocol {
    /// Amplitudes in mm, in order.
    pub amplitudes: Vec<f64>,
    /// Cycles at each amplitude.
    pub cycles_per_amplitude: usize,
    /// Steps a cycle (at least 4).
    pub steps_per_cycle: usize,
    /// Wave form.
    pub shape: Shape,
}

impl Protocol {
    /// The history of `../shared/data/opensees-reference/history.csv`: 3
    /// triangular cycles at each of 0.5, 1, 2, 4, 6, 8 mm, 200 steps a cycle.
    pub fn opensees_reference() -> Protocol {
        Protocol {
            amplitudes: vec![0.5, 1.0, 2.0, 4.0, 6.0, 8.0],
            cycles_per_amplitude: 3,
            steps_per_cycle: 200,
            shape: Shape::Triangular,
        }
    }

    /// Amplitudes growing geometrically from `first` by `ratio` while they do
    /// not exceed `last` (e.g. ratio 1.4 as in FEMA 461's protocol).
    pub fn geometric(
        first: f64,
        ratio: f64,
        last: f64,
        cycles_per_amplitude: usize,
        steps_per_cycle: usize,
    ) -> Result<Protocol, HistoryError> {
        require(first.is_finite() && first > 0.0, || {
            format!("expected a positive first amplitude, found {first}")
        })?;
        require(ratio.is_finite() && ratio > 1.0, || {
            format!("expected an amplitude ratio above 1, found {ratio}")
        })?;
        require(last.is_finite() && last >= first, || {
            format!("expected a last amplitude of at least {first}, found {last}")
        })?;
        let mut amplitudes = Vec::new();
        let mut a = first;
        while a <= last * (1.0 + 1e-12) {
            amplitudes.push(a);
            a *= ratio;
        }
        Ok(Protocol {
            amplitudes,
            cycles_per_amplitude,
            steps_per_cycle,
            shape: Shape::Triangular,
        })
    }

    /// The displacements, mm.
    pub fn generate(&self) -> Result<Vec<f64>, HistoryError> {
        let n = self.steps_per_cycle;
        require(n >= 4, || {
            format!("expected at least 4 steps a cycle, found {n}")
        })?;
        require(self.cycles_per_amplitude >= 1, || {
            "expected at least one cycle at each amplitude, found 0".into()
        })?;
        if let Some(a) = self
            .amplitudes
            .iter()
            .find(|a| !(a.is_finite() && **a >= 0.0))
        {
            return Err(HistoryError(format!(
                "expected finite, non-negative amplitudes, found {a}"
            )));
        }
        let nf = n as f64;
        let mut out = Vec::with_capacity(1 + self.amplitudes.len() * self.cycles_per_amplitude * n);
        out.push(0.0);
        for &a in &self.amplitudes {
            for _ in 0..self.cycles_per_amplitude {
                for k in 1..=n {
                    // Quarter-periods counted in integers, so that each value
                    // is A·m/N with one rounding and the peaks are exact.
                    let q = 4 * k as i64;
                    let n4 = n as i64;
                    let m = if q <= n4 {
                        q
                    } else if q <= 3 * n4 {
                        2 * n4 - q
                    } else {
                        q - 4 * n4
                    };
                    let v = match self.shape {
                        Shape::Triangular => a * m as f64 / nf,
                        Shape::Sine => a * (2.0 * PI * k as f64 / nf).sin(),
                    };
                    out.push(v);
                }
            }
        }
        Ok(out)
    }
}

/// An irregular, earthquake-like displacement path: Gaussian white noise
/// from a seeded generator, band-pass filtered twice around `frequency_hz`
/// (a fourth-order band of relative width about `1/q`), shaped by a slowly
/// varying envelope that rises as `(t/t_p)² e^{2(1 − t/t_p)}` to 1 at
/// `t_p = peak_time_fraction × duration` and decays, with a cosine taper over
/// the last 10 % so that the path ends at rest, and scaled so that its
/// largest `|u|` is `peak`. The same parameters and seed give the same path
/// on every platform.
#[derive(Clone, Debug, PartialEq)]
pub struct Irregular {
    /// Number of samples.
    pub samples: usize,
    /// Time step, s.
    pub dt: f64,
    /// Centre frequency of the band, Hz (below the Nyquist frequency `1/(2 dt)`).
    pub frequency_hz: f64,
    /// Quality factor of each band-pass pass (centre frequency / bandwidth).
    pub q: f64,
    /// Largest `|u|`, mm.
    pub peak: f64,
    /// Where the envelope peaks, as a fraction of the duration, in (0, 0.9).
    pub peak_time_fraction: f64,
    /// Seed of the random generator.
    pub seed: u64,
}

impl Default for Irregular {
    /// 20 s at 100 Hz, a band around 1 Hz with q = 2, peak 20 mm, envelope
    /// peak at 30 % of the duration, seed 1.
    fn default() -> Self {
        Irregular {
            samples: 2001,
            dt: 0.01,
            frequency_hz: 1.0,
            q: 2.0,
            peak: 20.0,
            peak_time_fraction: 0.3,
            seed: 1,
        }
    }
}

impl Irregular {
    /// The displacements, mm; `u[0] = u[last] = 0`.
    pub fn generate(&self) -> Result<Vec<f64>, HistoryError> {
        let n = self.samples;
        require(n >= 3, || format!("expected at least 3 samples, found {n}"))?;
        require(self.dt.is_finite() && self.dt > 0.0, || {
            format!("expected a positive time step, found {} s", self.dt)
        })?;
        let f = self.frequency_hz;
        require(f.is_finite() && f > 0.0 && f * self.dt < 0.5, || {
            format!(
                "expected a frequency between 0 and the Nyquist frequency {} Hz, found {f} Hz",
                0.5 / self.dt
            )
        })?;
        require(self.q.is_finite() && self.q > 0.0, || {
            format!("expected a positive quality factor, found {}", self.q)
        })?;
        require(self.peak.is_finite() && self.peak > 0.0, || {
            format!("expected a positive peak, found {} mm", self.peak)
        })?;
        let tpf = self.peak_time_fraction;
        require(tpf > 0.0 && tpf < 0.9, || {
            format!("expected the envelope peak time fraction in (0, 0.9), found {tpf}")
        })?;

        let mut noise = Normal::new(self.seed);
        let white: Vec<f64> = (0..n).map(|_| noise.sample()).collect();
        let band = BandPass::new(f, self.q, self.dt);
        let filtered = band.filter(&band.filter(&white));

        let duration = (n - 1) as f64 * self.dt;
        let tp = tpf * duration;
        let taper_start = 0.9 * duration;
        let envelope = |t: f64| {
            let r = t / tp;
            let rise = r * r * (2.0 * (1.0 - r)).exp();
            let taper = if t > taper_start {
                0.5 * (1.0 + (PI * (t - taper_start) / (duration - taper_start)).cos())
            } else {
                1.0
            };
            rise * taper
        };
        let mut u: Vec<f64> = filtered
            .iter()
            .enumerate()
            .map(|(k, y)| envelope(k as f64 * self.dt) * y)
            .collect();
        // The taper ends at cos(π) = -1 up to rounding: put the end at rest exactly.
        u[n - 1] = 0.0;
        let max = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        require(max > 0.0, || "the filtered noise is zero everywhere".into())?;
        let scale = self.peak / max;
        Ok(u.iter()
            .map(|v| {
                // Exactly `peak` at the largest sample; +0.0 turns -0 into 0.
                if v.abs() == max {
                    self.peak.copysign(*v)
                } else {
                    v * scale + 0.0
                }
            })
            .collect())
    }
}

/// Standard normal deviates by the Box-Muller transform, from a seeded
/// SplitMix64 stream (the same seed gives the same deviates everywhere).
#[derive(Clone, Debug)]
pub struct Normal {
    rng: SplitMix64,
    spare: Option<f64>,
}

impl Normal {
    /// A stream seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Normal {
            rng: SplitMix64::new(seed),
            spare: None,
        }
    }

    /// The next deviate.
    pub fn sample(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let r = (-2.0 * self.rng.open01().ln()).sqrt();
        let theta = 2.0 * PI * self.rng.open01();
        self.spare = Some(r * theta.sin());
        r * theta.cos()
    }
}

/// Second-order band-pass `H(s) = (s/Q) / (s² + s/Q + 1)` (frequency
/// normalised by the centre), discretised by the bilinear transform with the
/// centre frequency pre-warped: unit gain at the centre, zero at 0 and at the
/// Nyquist frequency.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BandPass {
    b0: f64,
    a1: f64,
    a2: f64,
}

impl BandPass {
    pub(crate) fn new(frequency_hz: f64, q: f64, dt: f64) -> Self {
        let k = (PI * frequency_hz * dt).tan();
        let norm = 1.0 / (1.0 + k / q + k * k);
        BandPass {
            b0: k / q * norm,
            a1: 2.0 * (k * k - 1.0) * norm,
            a2: (1.0 - k / q + k * k) * norm,
        }
    }

    /// Filters `x` from rest.
    pub(crate) fn filter(&self, x: &[f64]) -> Vec<f64> {
        let (mut x1, mut x2, mut y1, mut y2) = (0.0, 0.0, 0.0, 0.0);
        x.iter()
            .map(|&x0| {
                let y0 = self.b0 * (x0 - x2) - self.a1 * y1 - self.a2 * y2;
                (x2, x1) = (x1, x0);
                (y2, y1) = (y1, y0);
                y0
            })
            .collect()
    }
}
