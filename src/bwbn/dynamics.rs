//! The force-driven single-degree-of-freedom oscillator (thesis eqs 3.3,
//! 3.13-3.17), mass-normalised:
//!
//! ```text
//! y1' = y2                                               (3.14)  u
//! y2' = f(t) - 2 xi w0 y2 - alpha w0^2 y1 - (1-alpha) w0^2 y3   (3.15)  u'
//! y3' = y2 * dz/du(y3, y4, sgn y2)                       (3.16)  z
//! y4' = (1-alpha) w0^2 y2 y3                             (3.17)  energy
//! ```
//!
//! with `w0^2 = k/m` and `f = F/m`. The model parameters are the same
//! [`BwbnParams`] as for the element, with `k0` set to `w0^2` (stiffness per
//! unit mass, see [`Sdof::from_physical`]), so energies are per unit mass as
//! in eq. 3.8. Within a step the forcing is linear between the samples
//! ([`Sdof::step`]: all a controller reading a force sensor knows), or the
//! cubic Hermite polynomial through the samples and their rates
//! ([`Forcing::Hermite`]: for a recorded, band-limited force whose rates can
//! be estimated from the neighbouring samples). Each step is integrated with
//! the same error-controlled scheme as the element.
//!
//! [`Sdof::step_observed`] adds the observer coupling of thesis eq. 4.6,
//! `x' = f(x, p, t) + lambda K e(t)` with `e = u_measured - u`, which makes the
//! simulation track a measured displacement: the homotopy parameter
//! identification of thesis ch. 4 is built on it, and a controller can use it
//! as a state estimator.

use super::effects::{At, Effect};
use super::integrate::{self, Control, Method};
use super::params::BwbnParams;
use super::rate;
use super::spec::{ParamError, Rule};
use crate::element::StepError;
use crate::scalar::Scalar;

/// The oscillator's state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SdofState<S> {
    /// Time since the start (or the last [`Sdof::reset`]). In Q15.16 it
    /// reaches the arithmetic's end after 32767 s (9.1 h); a step past it
    /// fails with [`StepError::NonFiniteState`] and changes nothing.
    pub t: S,
    /// Displacement u (y1).
    pub u: S,
    /// Velocity u' (y2).
    pub v: S,
    /// Hysteretic displacement z (y3).
    pub z: S,
    /// Hysteretic energy per unit mass (y4, eq. 3.8).
    pub energy: S,
    /// Mass-normalised forcing f(t) at `t`.
    pub f: S,
}

/// Observer gains (thesis eqs 4.6, 4.10): `lambda K1` on the displacement
/// equation and `lambda K2` on the velocity equation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Observer<S> {
    /// Gain on u' (1/s).
    pub k_u: S,
    /// Gain on u'' (1/s^2).
    pub k_v: S,
}

/// The mass-normalised applied force within one step, from its value at the
/// current time to the one at the end of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Forcing<S> {
    /// Linear to `next` at the end of the step.
    Linear {
        /// Forcing at the end of the step.
        next: S,
    },
    /// The cubic Hermite polynomial with value `next` at the end of the step
    /// and rates (per second) `rate_now` and `rate_next` at its two ends. A
    /// force that is itself a cubic in time is reproduced exactly.
    ///
    /// In Q15.16 its coefficients in powers of t (see [`Forcing::polynomial`])
    /// are quotients by `dt^2`: a step under about 2.7 ms is refused
    /// ([`StepError::NonFiniteInput`]: `dt^2` rounds to zero), and just above
    /// that the cubic coefficient is mostly rounding. Fixed-point controllers
    /// drive the oscillator with [`Forcing::Linear`].
    Hermite {
        /// Forcing at the end of the step.
        next: S,
        /// Rate of the forcing at the current time (1/s).
        rate_now: S,
        /// Rate of the forcing at the end of the step (1/s).
        rate_next: S,
    },
}

impl<S: Scalar> Forcing<S> {
    /// The forcing at the end of the step.
    pub fn next(&self) -> S {
        match *self {
            Forcing::Linear { next } | Forcing::Hermite { next, .. } => next,
        }
    }

    /// `[c1, c2, c3]` of `f(t) = f0 + t (c1 + t (c2 + t c3))` over a step of
    /// `dt` that starts at `f0`, or `None` when a value is not finite: the
    /// force the oscillator sees at time `t` into the step.
    pub fn polynomial(&self, f0: S, dt: S) -> Option<[S; 3]> {
        let c = match *self {
            Forcing::Linear { next } => [(next - f0) / dt, S::ZERO, S::ZERO],
            Forcing::Hermite {
                next,
                rate_now,
                rate_next,
            } => {
                // Hermite basis on s = t / dt, collected in powers of t.
                let secant = (next - f0) / dt;
                let c2 = (S::from_i32(3) * secant - rate_now - rate_now - rate_next) / dt;
                let c3 = (rate_now + rate_next - secant - secant) / (dt * dt);
                [rate_now, c2, c3]
            }
        };
        let finite = c.iter().all(|v| v.is_finite()) && self.next().is_finite();
        finite.then_some(c)
    }
}

/// A BWBN oscillator under a mass-normalised force history (see the
/// documentation of `src/bwbn/dynamics.rs`).
///
/// ```
/// use hysteresis::bwbn::{BoucWen, BwbnParams, Sdof};
/// // m = 500 kg, k = 6 kN/mm = 6e6 N/m, xi = 0.05: thesis section 4.4.
/// let base = BoucWen::new(6e6, 0.2, 1.2, 2.0, -1.0).unwrap();
/// let params = BwbnParams::plain(base);
/// let mut osc = Sdof::from_physical(params, 500.0, 0.05).unwrap();
/// let dt = 1e-3;
/// for k in 1..=1000 {
///     let t = k as f64 * dt;
///     let force = 1e3 * t * (2.0 * std::f64::consts::PI * t).sin(); // F = t sin(2 pi t) kN
///     osc.step(dt, force / 500.0).unwrap();
/// }
/// assert!(osc.state().u.abs() < 1e-2);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Sdof<S: Scalar, X = ()> {
    params: BwbnParams<S>,
    extra: X,
    control: Control<S>,
    two_xi_w0: S,
    atol: [S; 4],
    state: SdofState<S>,
    /// Derivative at the current state (first stage of the next step), when
    /// known.
    dy: Option<[S; 4]>,
    h: S,
}

impl<S: Scalar> Sdof<S> {
    /// An oscillator at rest. `params.k0` must be the stiffness per unit mass
    /// `w0^2`; `xi` is the viscous damping ratio (eq. 3.3).
    pub fn new(params: BwbnParams<S>, xi: S) -> Result<Self, ParamError> {
        Self::with_extra(params, xi, (), Control::default_for())
    }

    /// An oscillator of mass `mass` and stiffness `params.k0` at rest: the
    /// parameters are converted to per unit mass (`k0 / mass`; degradation
    /// rates then refer to energy per unit mass).
    pub fn from_physical(params: BwbnParams<S>, mass: S, xi: S) -> Result<Self, ParamError> {
        Self::new(params.per_unit_mass(mass)?, xi)
    }
}

impl<S: Scalar, X: Effect<S>> Sdof<S, X> {
    /// An oscillator with an extra effect and explicit integration control, which must pass
    /// [`Control::checked`].
    pub fn with_extra(
        params: BwbnParams<S>,
        xi: S,
        extra: X,
        control: Control<S>,
    ) -> Result<Self, ParamError> {
        if !xi.is_finite() {
            return Err(ParamError::new("xi", Rule::NotFinite));
        }
        if xi < S::ZERO {
            return Err(ParamError::new("xi", Rule::Negative));
        }
        let control = control.checked()?;
        super::effects::energy_cannot_fall_below_zero(params.base(), extra.reads_energy())?;
        let w0 = params.base().k0.sqrt();
        let atol = Self::atol(&params, &control);
        let mut osc = Sdof {
            params,
            extra,
            control,
            two_xi_w0: (xi + xi) * w0,
            atol,
            state: SdofState::default(),
            dy: None,
            h: S::ZERO,
        };
        osc.reset();
        Ok(osc)
    }

    /// Absolute tolerances of u, u', z and energy: `tol` times Zu, w0 Zu, Zu
    /// and `k_hys Zu^2`.
    fn atol(params: &BwbnParams<S>, control: &Control<S>) -> [S; 4] {
        let (zs, tol) = (params.z_scale(), control.tol);
        let k0 = params.base().k0;
        let k_hys = k0 * (S::ONE - params.base().alpha);
        integrate::resolvable([
            tol * zs,
            tol * zs * k0.sqrt(),
            tol * zs,
            tol * k_hys.max(S::EPSILON) * zs * zs,
        ])
    }

    /// The same oscillator with another integration control (state kept), which must pass
    /// [`Control::checked`].
    pub fn with_control(mut self, control: Control<S>) -> Result<Self, ParamError> {
        let control = control.checked()?;
        self.atol = Self::atol(&self.params, &control);
        self.control = control;
        Ok(self)
    }

    /// Back to rest at t = 0 with zero forcing.
    pub fn reset(&mut self) {
        self.state = SdofState::default();
        self.dy = None;
        self.h = S::ZERO;
    }

    /// Sets the forcing at the current time (for a record that does not start
    /// at zero force). Non-finite values are refused.
    pub fn set_forcing(&mut self, f: S) -> Result<(), StepError> {
        if !f.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        self.state.f = f;
        self.dy = None;
        Ok(())
    }

    /// The current state.
    pub fn state(&self) -> SdofState<S> {
        self.state
    }

    /// The parameters (per unit mass).
    pub fn params(&self) -> &BwbnParams<S> {
        &self.params
    }

    /// Mass-normalised restoring force `alpha w0^2 u + (1-alpha) w0^2 z` of the
    /// current state (the hysteretic spring's force per unit mass).
    pub fn restoring(&self) -> S {
        let s = &self.state;
        let k = self.params.stiffness(
            &self.extra,
            &At {
                u: s.u,
                z: s.z,
                energy: s.energy,
                dir: S::ONE,
            },
        );
        k.el * s.u + k.hys * s.z
    }

    /// Advances by `dt` with the forcing going linearly from its current value
    /// to `f_next`. On error the state is unchanged.
    pub fn step(&mut self, dt: S, f_next: S) -> Result<SdofState<S>, StepError> {
        self.advance(dt, Forcing::Linear { next: f_next }, None)
    }

    /// Advances by `dt` under `forcing` (linear or cubic within the step). On
    /// error, non-finite values included, the state is unchanged.
    pub fn step_forced(&mut self, dt: S, forcing: Forcing<S>) -> Result<SdofState<S>, StepError> {
        self.advance(dt, forcing, None)
    }

    /// Like [`step_forced`](Self::step_forced), with the observer coupling of
    /// eq. 4.6: the measured displacement goes linearly from `u_meas_now` to
    /// `u_meas_next` over the step and pulls the state with the gains `obs`.
    pub fn step_observed(
        &mut self,
        dt: S,
        forcing: Forcing<S>,
        u_meas_now: S,
        u_meas_next: S,
        obs: Observer<S>,
    ) -> Result<SdofState<S>, StepError> {
        let finite = [u_meas_now, u_meas_next, obs.k_u, obs.k_v];
        if !finite.iter().all(|v| v.is_finite()) {
            return Err(StepError::NonFiniteInput);
        }
        self.advance(dt, forcing, Some((u_meas_now, u_meas_next, obs)))
    }

    fn advance(
        &mut self,
        dt: S,
        forcing: Forcing<S>,
        observed: Option<(S, S, Observer<S>)>,
    ) -> Result<SdofState<S>, StepError> {
        if !dt.is_finite() || dt <= S::ZERO {
            return Err(StepError::NonFiniteInput);
        }
        let (p, x) = (&self.params, &self.extra);
        let (f0, two_xi_w0) = (self.state.f, self.two_xi_w0);
        let [c1, c2, c3] = forcing
            .polynomial(f0, dt)
            .ok_or(StepError::NonFiniteInput)?;
        let mut rhs = |t: S, y: &[S; 4]| -> Result<[S; 4], StepError> {
            let [u, v, z, e] = *y;
            let dir = if v < S::ZERO { -S::ONE } else { S::ONE };
            let at = At {
                u,
                z,
                energy: e,
                dir,
            };
            let k = p.stiffness(x, &at);
            let dz = rate::dz_du(p, x, &at)?;
            let mut d = [
                v,
                f0 + t * (c1 + t * (c2 + t * c3)) - two_xi_w0 * v - k.el * u - k.hys * z,
                v * dz,
                k.hys * v * z,
            ];
            if let Some((um0, um1, obs)) = observed {
                let err = um0 + (um1 - um0) * (t / dt) - u;
                d[0] += obs.k_u * err;
                d[1] += obs.k_v * err;
            }
            Ok(d)
        };
        let s = &self.state;
        let y0 = [s.u, s.v, s.z, s.energy];
        // With an observer the derivative depends on the measurement, which
        // a cached derivative did not see.
        let dy0 = match (self.dy, observed) {
            (Some(dy), None) => dy,
            _ => rhs(S::ZERO, &y0)?,
        };
        let (ctl, atol, h) = (&self.control, &self.atol, self.h);
        let method = match ctl.method {
            Method::Series => Control::<S>::pair_for(),
            m => m,
        };
        let end = if method == Method::Dp54 {
            // v and z are kinks: `sgn(v z)` changes at either, and `|z|^n` is
            // not smooth at z = 0. Landing on both took random oscillators
            // from 4.8e-7 to 6.0e-9 of peak displacement in `f64` (either
            // alone: 3.7e-7, 4.6e-7). Bogacki-Shampine (`f32`, fixed point)
            // gained nothing from it, its sub-steps being shorter, and
            // refused steps of more sets for its budget (9 of 400 against
            // 4; `tests/bwbn_oscillator.rs`), so it does not land.
            let kink = |index| integrate::Kink {
                index,
                reach: S::MAX,
            };
            integrate::advance(ctl, &mut rhs, y0, dy0, dt, atol, h, [kink(1), kink(2)])
        } else {
            integrate::advance(ctl, &mut rhs, y0, dy0, dt, atol, h, [])
        }?;
        // The clock too: Q15.16 runs out at 32767 s (9.1 h).
        let t = s.t + dt;
        // Energy that no effect reads is only reported: past what the
        // arithmetic holds it reads as non-finite, and the oscillator goes on.
        let reads_energy = self.params.effects().reads_energy(&self.extra);
        let finite = |v: &[S; 4]| v[..3].iter().all(|x| x.is_finite());
        if !(t.is_finite()
            && finite(&end.y)
            && finite(&end.dy)
            && (!reads_energy || (end.y[3].is_finite() && end.dy[3].is_finite())))
        {
            return Err(StepError::NonFiniteState);
        }
        if reads_energy && end.y[3] > self.params.energy_limit() {
            return Err(StepError::EnergyOutOfRange);
        }
        let [u, v, z, energy] = end.y;
        self.state = SdofState {
            t,
            u,
            v,
            z,
            energy,
            f: forcing.next(),
        };
        self.dy = if observed.is_some() {
            None
        } else {
            Some(end.dy)
        };
        self.h = end.h_next;
        Ok(self.state)
    }
}
