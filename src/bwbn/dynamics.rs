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
//! in eq. 3.8. The forcing is taken as linear between samples, and each sample
//! interval is integrated with the same error-controlled scheme as the element.

use super::effects::{At, Effect};
use super::integrate::{self, Control};
use super::params::BwbnParams;
use super::rate;
use super::spec::{ParamError, Rule};
use crate::element::StepError;
use crate::scalar::Scalar;

/// The oscillator's state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SdofState<S> {
    /// Time.
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

/// A BWBN oscillator under a mass-normalised force history (see the
/// [module docs](self)).
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
        if !mass.is_finite() {
            return Err(ParamError::new("m", Rule::NotFinite));
        }
        if mass <= S::ZERO {
            return Err(ParamError::new("m", Rule::NotPositive));
        }
        let set = params.effect_set();
        let normalised = BwbnParams::from_named(set, |name| {
            if name == "k0" {
                Some(params.base().k0 / mass)
            } else {
                params.get(name)
            }
        })?
        .with_zu_rule(params.zu_rule());
        Self::new(normalised, xi)
    }
}

impl<S: Scalar, X: Effect<S>> Sdof<S, X> {
    /// An oscillator with an extra effect and explicit integration control.
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
        let w0 = params.base().k0.sqrt();
        let zs = params.z_scale();
        let tol = control.tol;
        let k_hys = params.base().k0 * (S::ONE - params.base().alpha);
        let atol = [
            tol * zs,
            tol * zs * w0,
            tol * zs,
            tol * k_hys.max(S::EPSILON) * zs * zs,
        ];
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
        if !(dt.is_finite() && f_next.is_finite()) || dt <= S::ZERO {
            return Err(StepError::NonFiniteInput);
        }
        let (p, x) = (&self.params, &self.extra);
        let (f0, two_xi_w0) = (self.state.f, self.two_xi_w0);
        let slope = (f_next - f0) / dt;
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
            Ok([
                v,
                f0 + slope * t - two_xi_w0 * v - k.el * u - k.hys * z,
                v * dz,
                k.hys * v * z,
            ])
        };
        let s = &self.state;
        let y0 = [s.u, s.v, s.z, s.energy];
        let dy0 = match self.dy {
            Some(dy) => dy,
            None => rhs(S::ZERO, &y0)?,
        };
        let end = integrate::advance(&self.control, &mut rhs, y0, dy0, dt, &self.atol, self.h)?;
        if !end.y.iter().chain(end.dy.iter()).all(|v| v.is_finite()) {
            return Err(StepError::NonFiniteState);
        }
        if end.y[3] > self.params.energy_limit() {
            return Err(StepError::EnergyOutOfRange);
        }
        let [u, v, z, energy] = end.y;
        self.state = SdofState {
            t: s.t + dt,
            u,
            v,
            z,
            energy,
            f: f_next,
        };
        self.dy = Some(end.dy);
        self.h = end.h_next;
        Ok(self.state)
    }
}
