//! The plain Bouc-Wen oscillator (thesis eqs 3.3, 3.4 and 3.13 with A = nu = eta = 1 and no
//! pinching), per unit mass, on [`LANES`] parameter sets at once:
//!
//! ```text
//! u'' + 2 xi w0 u' + alpha w0^2 u + (1 - alpha) w0^2 z = f(t)/m,   w0^2 = k0/m
//! z'  = u' (1 - |z|^n (beta sgn(u' z) + gamma))
//! ```
//!
//! from rest, the forcing linear between samples as in [`Sdof::step`](hysteresis::bwbn::Sdof),
//! by classic Runge-Kutta (RK4) with `substeps` equal steps per sample, in `f32` (parameters and
//! forcing are given in `f64` and rounded once). Each step's increment is added to the state with
//! compensation (Kahan's summation: the part the addition rounds away is carried into the next
//! step), so that the roundings do not add up over thousands of steps (tested below).

use super::math::pow_abs;
use super::{Lanes, LANES};
use hysteresis::bwbn::{BoucWen, Forcing};

/// The state of every lane after a sample, in `f32`. (The search scores the displacement; the
/// energy input of its objectives is the applied force over it, so no work is integrated here.)
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LaneState {
    /// Displacement u.
    pub u: Lanes,
    /// Velocity u'.
    pub v: Lanes,
    /// Hysteretic displacement z.
    pub z: Lanes,
}

/// [`LANES`] plain Bouc-Wen oscillators with their own parameters.
#[derive(Clone, Debug)]
pub struct BoucWenLanes {
    /// alpha w0^2
    k_el: Lanes,
    /// (1 - alpha) w0^2
    k_hys: Lanes,
    beta: Lanes,
    gamma: Lanes,
    n: Lanes,
    two_xi_w0: Lanes,
}

/// The time derivative of every lane's `(u, v, z)` under the forcing `f` (per unit mass).
struct Rates {
    u: Lanes,
    v: Lanes,
    z: Lanes,
}

impl BoucWenLanes {
    /// The oscillators of `sets`: each a base parameter set per unit mass (`k0` is `w0^2`, as
    /// [`BwbnParams::per_unit_mass`](hysteresis::bwbn::BwbnParams::per_unit_mass) gives it) and
    /// a damping ratio. Lanes beyond `sets.len()` repeat the first set. `None` when `sets` is
    /// empty or longer than [`LANES`].
    pub fn new(sets: &[(BoucWen<f64>, f64)]) -> Option<Self> {
        if sets.is_empty() || sets.len() > LANES {
            return None;
        }
        let lane = |get: &dyn Fn(&BoucWen<f64>, f64) -> f64| -> Lanes {
            core::array::from_fn(|i| {
                let (p, xi) = sets.get(i).unwrap_or(&sets[0]);
                get(p, *xi) as f32
            })
        };
        Some(BoucWenLanes {
            k_el: lane(&|p, _| p.alpha * p.k0),
            k_hys: lane(&|p, _| (1.0 - p.alpha) * p.k0),
            beta: lane(&|p, _| p.beta),
            gamma: lane(&|p, _| p.gamma),
            n: lane(&|p, _| p.n),
            two_xi_w0: lane(&|p, xi| 2.0 * xi * p.k0.sqrt()),
        })
    }

    #[inline(always)]
    fn rates(&self, u: &Lanes, v: &Lanes, z: &Lanes, f: f32) -> Rates {
        let zn = pow_abs(z, &self.n);
        let mut r = Rates {
            u: *v,
            v: [0.0; LANES],
            z: [0.0; LANES],
        };
        for i in 0..LANES {
            r.v[i] = f - self.two_xi_w0[i] * v[i] - self.k_el[i] * u[i] - self.k_hys[i] * z[i];
            // beta sgn(v z), branch-free: the sign bit of v z moved onto beta.
            let sign = (v[i] * z[i]).to_bits() & (1 << 31);
            let beta = f32::from_bits(self.beta[i].to_bits() ^ sign);
            r.z[i] = v[i] * (1.0 - zn[i] * (beta + self.gamma[i]));
        }
        r
    }

    /// Simulates every lane from rest under `forcing` (force per unit mass at samples `dt`
    /// apart, linear in between, or with `rates` at the samples the cubic Hermite polynomial
    /// through them as in the core's `Forcing::Hermite`), `substeps` RK4 steps a sample (at
    /// least 1), and hands `sink` the state at each sample, the first one included (the rest it
    /// starts from).
    pub fn simulate(
        &self,
        forcing: &[f64],
        rates: Option<&[f64]>,
        dt: f64,
        substeps: usize,
        mut sink: impl FnMut(&LaneState),
    ) {
        let mut s = LaneState::default();
        if forcing.is_empty() {
            return;
        }
        sink(&s);
        let mut lost = LaneState::default();
        let k = substeps.max(1);
        let h = (dt / k as f64) as f32;
        let (h2, h6) = (0.5 * h, h / 6.0);
        let stage = |y: &Lanes, dy: &Lanes, c: f32| -> Lanes {
            core::array::from_fn(|i| dy[i].mul_add(c, y[i]))
        };
        for (i, w) in forcing.windows(2).enumerate() {
            let slope = (w[1] - w[0]) / k as f64;
            // The core's cubic through the samples, at time t into the sample interval. Rates
            // that are not finite make the run not finite, which the caller hands to the core.
            let cubic = rates.map(|r| {
                let forcing = Forcing::Hermite {
                    next: w[1],
                    rate_now: r[i],
                    rate_next: r[i + 1],
                };
                let [c1, c2, c3] = forcing.polynomial(w[0], dt).unwrap_or([f64::NAN; 3]);
                move |t: f64| w[0] + t * (c1 + t * (c2 + t * c3))
            });
            for j in 0..k {
                let [f0, fm, f1] = match &cubic {
                    None => {
                        let start = w[0] + slope * j as f64;
                        [start, start + 0.5 * slope, start + slope]
                    }
                    Some(at) => {
                        let (h, t) = (dt / k as f64, dt * j as f64 / k as f64);
                        [at(t), at(t + 0.5 * h), at(t + h)]
                    }
                }
                .map(|f| f as f32);
                let k1 = self.rates(&s.u, &s.v, &s.z, f0);
                let k2 = self.rates(
                    &stage(&s.u, &k1.u, h2),
                    &stage(&s.v, &k1.v, h2),
                    &stage(&s.z, &k1.z, h2),
                    fm,
                );
                let k3 = self.rates(
                    &stage(&s.u, &k2.u, h2),
                    &stage(&s.v, &k2.v, h2),
                    &stage(&s.z, &k2.z, h2),
                    fm,
                );
                let k4 = self.rates(
                    &stage(&s.u, &k3.u, h),
                    &stage(&s.v, &k3.v, h),
                    &stage(&s.z, &k3.z, h),
                    f1,
                );
                let advance = |y: &mut Lanes,
                               lost: &mut Lanes,
                               a: &Lanes,
                               b: &Lanes,
                               c: &Lanes,
                               d: &Lanes| {
                    for i in 0..LANES {
                        let step = h6 * (a[i] + 2.0 * (b[i] + c[i]) + d[i]) + lost[i];
                        let sum = y[i] + step;
                        lost[i] = step - (sum - y[i]);
                        y[i] = sum;
                    }
                };
                advance(&mut s.u, &mut lost.u, &k1.u, &k2.u, &k3.u, &k4.u);
                advance(&mut s.v, &mut lost.v, &k1.v, &k2.v, &k3.v, &k4.v);
                advance(&mut s.z, &mut lost.z, &k1.z, &k2.z, &k3.z, &k4.z);
            }
            sink(&s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hysteresis::bwbn::{BwbnParams, Control, Method, Sdof};

    /// The thesis' example (sec. 4.4): m = 500 kg, k = 6 kN/mm, F = t sin(2 pi t) kN, 10 s.
    const MASS: f64 = 5e-4;
    const TRUTH: (f64, f64, f64, f64, f64) = (0.2, 1.2, 2.0, -1.0, 0.05);

    /// A parameter set a lane around the truth (alpha, n, beta, gamma, xi: 70% to 130%), the
    /// truth first.
    fn sets() -> Vec<(BoucWen<f64>, f64)> {
        (0..LANES)
            .map(|i| {
                let f = 1.0 + 0.04 * (i as f64 - 7.5) * (i > 0) as u8 as f64;
                let (a, n, b, g, xi) = TRUTH;
                let base = BoucWen::new(6.0 / MASS, a * f, n * f, b / f, g * f).unwrap();
                (base, xi * f)
            })
            .collect()
    }

    fn forcing(rate_hz: f64) -> (Vec<f64>, f64) {
        let dt = 1.0 / rate_hz;
        let f = (0..=(10.0 * rate_hz) as usize)
            .map(|i| {
                let t = i as f64 * dt;
                t * (2.0 * std::f64::consts::PI * t).sin() / MASS
            })
            .collect();
        (f, dt)
    }

    /// The core's error-controlled oscillator at a tight tolerance: u at each sample, the force
    /// linear between samples or, with `rates`, cubic.
    fn reference(set: &(BoucWen<f64>, f64), f: &[f64], rates: Option<&[f64]>, dt: f64) -> Vec<f64> {
        let control = Control {
            method: Method::Dp54,
            tol: 1e-12,
            max_substeps: u16::MAX,
        };
        let mut osc = Sdof::new(BwbnParams::plain(set.0), set.1)
            .unwrap()
            .with_control(control)
            .unwrap();
        osc.set_forcing(f[0]).unwrap();
        let mut out = vec![0.0];
        for i in 1..f.len() {
            let forcing = crate::fit::forcing::step(f, 1.0, rates, i);
            out.push(osc.step_forced(dt, forcing).unwrap().u);
        }
        out
    }

    /// Largest error of u over every lane, relative to each lane's peak.
    fn error(f: &[f64], rates: Option<&[f64]>, dt: f64, substeps: usize, refs: &[Vec<f64>]) -> f64 {
        let lanes = BoucWenLanes::new(&sets()).unwrap();
        let peaks: Vec<f64> = refs
            .iter()
            .map(|r| r.iter().fold(0.0f64, |a, u| a.max(u.abs())))
            .collect();
        let (mut i, mut worst) = (0, 0.0f64);
        lanes.simulate(f, rates, dt, substeps, |s| {
            for ((r, peak), u) in refs.iter().zip(&peaks).zip(s.u) {
                worst = worst.max((f64::from(u) - r[i]).abs() / peak);
            }
            i += 1;
        });
        assert_eq!(i, f.len());
        worst
    }

    /// Against the core's converged solution at 100 Hz (the thesis example's rate: 5.7 samples a
    /// period). RK4 converges at second order here, not fourth: the rate has kinks that fixed
    /// steps cross, at every reversal (`sgn(u' z)`) and every zero of z (`|z|^n`, n = 1.2).
    /// Measured from 2 to 16 steps a sample: u from 9.0e-4 to 1.2e-5 of its peak (order 2.05,
    /// the same as the `f64` lanes measured before).
    ///
    /// Past that the `f32` rounding would show: a step's rounding of the phase is not damped,
    /// so without care it adds up as a random walk, about `sqrt(steps) eps` of peak (measured
    /// 2.6e-5 at 256 steps a sample). The states are summed with compensation (Kahan), which
    /// leaves the rounding of the rates alone: at 256 steps a sample, where the discretisation
    /// error is 3.5e-8 (measured in `f64`), u is 2.1e-7 off, under two `f32` roundings;
    /// asserted below 16.
    ///
    /// The same holds with the force cubic between samples (rates by
    /// [`forcing::rates`](crate::fit::forcing::rates)), against the core driven by the same
    /// cubic.
    #[test]
    fn converges_to_the_core_at_second_order_down_to_the_rounding() {
        let (f, dt) = forcing(100.0);
        let cubic = crate::fit::forcing::rates(&f, dt);
        for rates in [None, Some(cubic.as_slice())] {
            let refs: Vec<_> = sets().iter().map(|s| reference(s, &f, rates, dt)).collect();
            let errs: Vec<f64> = [2, 4, 8, 16]
                .iter()
                .map(|&k| error(&f, rates, dt, k, &refs))
                .collect();
            for w in errs.windows(2) {
                assert!(w[0] > 2.5 * w[1], "{errs:?}");
            }
            let order = (errs[0] / errs[3]).log2() / 3.0;
            assert!((1.8..2.6).contains(&order), "order {order}, {errs:?}");
            let floor = 16.0 * f64::from(f32::EPSILON);
            let e = error(&f, rates, dt, 256, &refs);
            assert!(e < floor, "{e:e} against {floor:e}");
        }
    }

    /// Each lane is its own oscillator: a set simulated in lane 5 among others gives bit for bit
    /// what it gives alone (where it fills every lane).
    #[test]
    fn lanes_are_independent() {
        let (f, dt) = forcing(500.0);
        let all = sets();
        let together = BoucWenLanes::new(&all).unwrap();
        let alone = BoucWenLanes::new(&all[5..6]).unwrap();
        let (mut a, mut b) = (vec![], vec![]);
        together.simulate(&f, None, dt, 1, |s| a.push((s.u[5], s.v[5], s.z[5])));
        alone.simulate(&f, None, dt, 1, |s| b.push((s.u[0], s.v[0], s.z[0])));
        assert_eq!(a, b);
        assert!(a.iter().any(|p| p.0 != 0.0));
    }

    /// alpha = 1: the linear damped oscillator, whose rate is smooth, so RK4 shows its fourth
    /// order; z carries no force. Checked against the exact response to a step
    /// force, u = F/k (1 - e^(-xi w0 t) (cos wd t + xi/sqrt(1 - xi^2) sin wd t)), at steps of
    /// 0.8 to 0.1 w0^-1, where the error (2.5e-2 to 6.1e-6 of F/k) is far above the `f32`
    /// rounding (about 3e-7 here).
    #[test]
    fn alpha_one_is_the_linear_oscillator_at_fourth_order() {
        let (w0sq, xi, f) = (400.0, 0.05, 2.0);
        let base = BoucWen::new(w0sq, 1.0, 1.5, 0.5, 0.5).unwrap();
        let lanes = BoucWenLanes::new(&[(base, xi)]).unwrap();
        let dt = 0.04;
        let forcing = vec![f; 401];
        let w0 = f64::sqrt(w0sq);
        let wd = w0 * (1.0 - xi * xi).sqrt();
        let worst = |substeps: usize| {
            let (mut i, mut worst) = (0, 0.0f64);
            lanes.simulate(&forcing, None, dt, substeps, |s| {
                let t = i as f64 * dt;
                let decay = (-xi * w0 * t).exp();
                let exact = f / w0sq
                    * (1.0
                        - decay * ((wd * t).cos() + xi / (1.0 - xi * xi).sqrt() * (wd * t).sin()));
                worst = worst.max((f64::from(s.u[0]) - exact).abs() / (f / w0sq));
                i += 1;
            });
            worst
        };
        let errs = [worst(1), worst(2), worst(4), worst(8)];
        for w in errs.windows(2) {
            let ratio = w[0] / w[1];
            assert!((14.0..18.5).contains(&ratio), "{errs:?}");
        }
        assert!(errs[3] < 1e-5, "{errs:?}");
    }

    #[test]
    fn rejects_no_sets_and_too_many() {
        assert!(BoucWenLanes::new(&[]).is_none());
        let many = vec![sets()[0]; LANES + 1];
        assert!(BoucWenLanes::new(&many).is_none());
    }
}
