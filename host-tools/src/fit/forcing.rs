//! How a recorded force goes between its samples when it drives the
//! oscillator (thesis eqs 3.13-3.17).
//!
//! A lab force is a continuous, band-limited signal that the data logger
//! sampled. Linear interpolation between the samples (what a controller reading
//! a sensor has) cuts the peaks of every component: at five samples a period,
//! the top of the Bouc-Wen benchmark's band at 750 Hz, it misses a sine by up
//! to 19% of its amplitude. The cubic Hermite polynomial through the samples
//! and rates estimated from their neighbours misses it by 0.75%
//! ([`rates`]: eighth-order central differences), and the benchmark's true
//! model then reproduces its multisine test output to 2.5e-7 m at the data's
//! own rate, where linear forcing gives 7.3e-6 m (`tests/bwbn_dynamics.rs` of
//! the core, with rates from the spectrum: 2.4e-7 m).

use hysteresis::bwbn::Forcing;
use hysteresis::Scalar;

/// The force between two samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Between {
    /// Linear from sample to sample.
    #[default]
    Linear,
    /// Cubic Hermite through the samples and their rates ([`rates`]).
    Cubic,
}

impl Between {
    /// The name used on the command line and in fit files.
    pub fn name(self) -> &'static str {
        match self {
            Between::Linear => "linear",
            Between::Cubic => "cubic",
        }
    }

    /// The value of a name given by [`name`](Self::name).
    pub fn from_name(name: &str) -> Option<Self> {
        [Between::Linear, Between::Cubic]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

impl std::fmt::Display for Between {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Central-difference weights of orders 2, 4, 6 and 8 for `(x[i+k] -
/// x[i-k]) / dt`, k = 1, 2, ... (Fornberg 1988, Table 1).
const CENTRAL: [&[f64]; 4] = [
    &[1.0 / 2.0],
    &[2.0 / 3.0, -1.0 / 12.0],
    &[3.0 / 4.0, -3.0 / 20.0, 1.0 / 60.0],
    &[4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0],
];

/// Fourth-order weights for `x[i + k] / dt`, k = 0..4 (the first sample)
/// and k = -1..3 (the second); mirrored and negated at the other end.
const EDGE: [[f64; 5]; 2] = [
    [-25.0 / 12.0, 4.0, -3.0, 4.0 / 3.0, -1.0 / 4.0],
    [-1.0 / 4.0, -5.0 / 6.0, 3.0 / 2.0, -1.0 / 2.0, 1.0 / 12.0],
];

/// Rates of `x` sampled every `dt`: eighth-order central differences inside,
/// the highest central order the samples allow towards the ends (sixth,
/// fourth), and fourth-order one-sided differences for the first two and last
/// two samples (records of two to four samples: first and second order).
/// Higher one-sided orders are not used: their weights would multiply the
/// noise of the first samples by up to 78.
pub fn rates(x: &[f64], dt: f64) -> Vec<f64> {
    let n = x.len();
    (0..n)
        .map(|i| {
            let reach = i.min(n - 1 - i).min(CENTRAL.len());
            if reach >= 2 || (reach == 1 && n < 5) {
                let w = CENTRAL[reach - 1];
                let sum: f64 = (1..=reach).map(|k| w[k - 1] * (x[i + k] - x[i - k])).sum();
                sum / dt
            } else if n >= 5 {
                // first two samples forward, last two backward
                let (w, start, sign) = if i < 2 {
                    (&EDGE[i], 0, 1.0)
                } else {
                    (&EDGE[n - 1 - i], n - 5, -1.0)
                };
                let sum: f64 = (0..5)
                    .map(|k| {
                        let weight = if sign > 0.0 { w[k] } else { w[4 - k] };
                        weight * x[start + k]
                    })
                    .sum();
                sign * sum / dt
            } else if n == 2 {
                (x[1] - x[0]) / dt
            } else if n < 2 {
                0.0
            } else if i == 0 {
                (-3.0 * x[0] + 4.0 * x[1] - x[2]) / (2.0 * dt)
            } else {
                (3.0 * x[i] - 4.0 * x[i - 1] + x[i - 2]) / (2.0 * dt)
            }
        })
        .collect()
}

/// The forcing of the step from sample `i - 1` to sample `i` of the force
/// `f`, divided by `mass`; `rates` are those of `f / mass` ([`rates`]) when
/// the force is cubic between samples, `None` when it is linear.
pub fn step<S: Scalar>(f: &[f64], mass: f64, rates: Option<&[f64]>, i: usize) -> Forcing<S> {
    let next = S::from_f64(f[i] / mass);
    match rates {
        None => Forcing::Linear { next },
        Some(r) => Forcing::Hermite {
            next,
            rate_now: S::from_f64(r[i - 1]),
            rate_next: S::from_f64(r[i]),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of order 2k are exact for polynomials of degree
    /// 2k: inside, degree 8 comes out exact; the ends use lower orders, exact
    /// for lower degrees.
    #[test]
    fn rates_are_exact_for_polynomials_of_their_order() {
        let dt = 0.1;
        let t: Vec<f64> = (0..20).map(|i| i as f64 * dt).collect();
        for degree in 0..=8 {
            let x: Vec<f64> = t.iter().map(|t| t.powi(degree)).collect();
            let exact: Vec<f64> = t
                .iter()
                .map(|t| f64::from(degree) * t.powi((degree - 1).max(0)))
                .collect();
            let r = rates(&x, dt);
            for i in 0..t.len() {
                let reach = i.min(t.len() - 1 - i).min(4);
                // order 2 * reach inside, 4 for the two samples at each end
                let order = if reach < 2 { 4 } else { 2 * reach as i32 };
                if degree <= order {
                    let scale = 1.0 + exact[i].abs();
                    assert!(
                        (r[i] - exact[i]).abs() < 1e-9 * scale,
                        "degree {degree}, sample {i}: {} against {}",
                        r[i],
                        exact[i]
                    );
                }
            }
        }
    }

    /// On a sine at five samples a period (the benchmark's top frequency at
    /// 750 Hz), the eighth-order rates are within 1% of the true ones (their
    /// gain there is 0.9936), where second-order differences lose 24%
    /// (`sin(w dt) / (w dt)` = 0.757).
    #[test]
    fn rates_of_a_sine_near_the_nyquist_rate() {
        let (w, dt) = (2.0 * std::f64::consts::PI / 5.0, 1.0);
        let x: Vec<f64> = (0..60).map(|i| (w * i as f64 + 0.3).sin()).collect();
        let r = rates(&x, dt);
        for (i, r) in r.iter().enumerate().take(50).skip(10) {
            let exact = w * (w * i as f64 + 0.3).cos();
            assert!((r - exact).abs() < 0.01 * w, "{i}: {r} against {exact}");
        }
    }

    #[test]
    fn short_records() {
        assert_eq!(rates(&[], 1.0), Vec::<f64>::new());
        assert_eq!(rates(&[3.0], 1.0), vec![0.0]);
        assert_eq!(rates(&[1.0, 3.0], 0.5), vec![4.0, 4.0]);
        // a straight line: the cubic is the line, its rates the slope
        let f = [1.0, 3.0, 5.0];
        let r = rates(&f, 0.5);
        assert_eq!(
            step::<f64>(&f, 1.0, Some(&r), 2),
            Forcing::Hermite {
                next: 5.0,
                rate_now: 4.0,
                rate_next: 4.0
            }
        );
        assert_eq!(step::<f64>(&f, 2.0, None, 2), Forcing::Linear { next: 2.5 });
    }

    #[test]
    fn names_round_trip() {
        for b in [Between::Linear, Between::Cubic] {
            assert_eq!(Between::from_name(b.name()), Some(b));
        }
        assert_eq!(Between::from_name("spline"), None);
    }
}
