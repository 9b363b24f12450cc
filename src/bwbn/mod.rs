//! The Bouc-Wen-Baber-Noori model (thesis ch. 3, eqs 3.1-3.17) as element state.
//!
//! [`Bwbn`] is a displacement-driven element (quasi-static: given u, return
//! force and tangent) implementing [`Element`]; [`Sdof`] drives the same model
//! as a single-degree-of-freedom oscillator under a force history
//! (eqs 3.3, 3.13-3.17).
//!
//! The model is the Bouc-Wen base ([`BoucWen`], 5 parameters) plus effects
//! that can each be switched on ([`effects`]): A-degradation, strength
//! degradation, stiffness degradation and pinching; all four on is the
//! 17-parameter BWBN model of the thesis. Parameter sets are validated once, in
//! [`BwbnParams`]; steps never validate and never panic.
//!
//! # Units and conventions
//!
//! * Displacement u and hysteretic displacement z share one unit D (mm, say),
//!   force R one unit F (kN, say); `k0` is in F/D.
//! * The energy that drives degradation and pinching is the hysteretic work of
//!   eq. 3.8 in force times displacement, `e = (1 - alpha) k0 ∫ z du` (kN·mm),
//!   as in OpenSees. For the mass-normalised oscillator [`Sdof`] it is per
//!   unit mass, `e = (1 - alpha) w0^2 ∫ z du`, exactly as eq. 3.8. Degradation
//!   rates (`delta_nu`, ...) are per unit of that energy.
//! * `sgn(du)` is the direction of the current increment (or of the
//!   velocity), so z follows the loading direction within each increment.
//!
//! # Example
//!
//! ```
//! use hysteresis::bwbn::{Bwbn, BoucWen, BwbnParams};
//! use hysteresis::Element;
//!
//! let params = BwbnParams::plain(BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).unwrap());
//! let mut el = Bwbn::new(params);
//! for i in 1..=200 {
//!     let r = el.set_trial(i as f64 * 0.05).unwrap();
//!     assert!(r.tangent > 0.0);
//!     el.commit();
//! }
//! // At 10 mm, z has reached its asymptote Zu = 1: R = 0.2*6*10 + 0.8*6*1 = 16.8 kN,
//! // and the tangent is the post-yield stiffness alpha*k0 = 1.2 kN/mm.
//! assert!((el.response().force - 16.8).abs() < 1e-3);
//! assert!((el.response().tangent - 1.2).abs() < 1e-3);
//! ```

mod base;
mod dynamics;
pub mod effects;
mod integrate;
mod params;
mod rate;
#[cfg(any(test, feature = "selftest"))]
pub mod selftest;
pub mod series;
mod spec;

pub use base::{BoucWen, PARAMS as BASE_PARAMS};
pub use dynamics::{Forcing, Observer, Sdof, SdofState};
pub use effects::{Effect, EffectKind, EffectSet, Effects, ZuRule};
pub use integrate::{Control, Method};
pub use params::{specs, BwbnParams, ENERGY_LIMIT};
pub use spec::{ParamError, ParamSpec, Rule, Unit};

use crate::element::{Element, Response, StepError};
use crate::scalar::Scalar;
use effects::At;

/// The state of a [`Bwbn`] element (committed or trial). Small and `Copy`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct State<S> {
    /// Displacement u.
    pub u: S,
    /// Hysteretic displacement z.
    pub z: S,
    /// Hysteretic energy (eq. 3.8), force times displacement.
    pub energy: S,
    /// Direction of the increment that led here: +1 or -1.
    dir: S,
    /// dz/du at this state along `dir` (gives the tangent; reused as the
    /// first stage of the next increment in the same direction).
    dz: S,
    /// d(energy)/du at this state along `dir`.
    de: S,
    /// Sub-step size to try first on the next increment.
    h: S,
}

/// A BWBN element driven by displacement (see the [module docs](self)).
///
/// `X` is an optional extra effect defined outside this crate (see
/// [`Effect`]); it defaults to none.
#[derive(Clone, Copy, Debug)]
pub struct Bwbn<S: Scalar, X = ()> {
    params: BwbnParams<S>,
    extra: X,
    control: Control<S>,
    atol: [S; 2],
    committed: State<S>,
    trial: State<S>,
    response: Response<S>,
}

impl<S: Scalar> Bwbn<S> {
    /// An element in its virgin state, integrated with
    /// [`Control::default_for`].
    pub fn new(params: BwbnParams<S>) -> Self {
        Self::build(params, (), Control::default_for())
    }
}

impl<S: Scalar, X: Effect<S>> Bwbn<S, X> {
    /// An element with an extra effect and explicit integration control, which must pass
    /// [`Control::checked`].
    pub fn with_extra(
        params: BwbnParams<S>,
        extra: X,
        control: Control<S>,
    ) -> Result<Self, ParamError> {
        effects::energy_cannot_fall_below_zero(params.base(), extra.reads_energy())?;
        Ok(Self::build(params, extra, control.checked()?))
    }

    /// The element with a control known to be valid.
    fn build(params: BwbnParams<S>, extra: X, control: Control<S>) -> Self {
        let atol = Self::atol(&params, &extra, &control);
        let control = Self::resolved(&params, &extra, control);
        let mut el = Bwbn {
            params,
            extra,
            control,
            atol,
            committed: Self::virgin(),
            trial: Self::virgin(),
            response: Response::default(),
        };
        el.reset();
        el
    }

    /// Absolute tolerances of z and energy: `tol` times their scales Zu and
    /// `k_hys Zu^2`.
    fn atol(params: &BwbnParams<S>, extra: &X, control: &Control<S>) -> [S; 2] {
        let zs = params.z_scale();
        let k_hys = params
            .stiffness(extra, &Self::at(S::ZERO, S::ZERO, S::ZERO, S::ONE))
            .hys;
        integrate::resolvable([
            control.tol * zs,
            control.tol * k_hys.abs().max(S::EPSILON) * zs * zs,
        ])
    }

    fn virgin() -> State<S> {
        State {
            u: S::ZERO,
            z: S::ZERO,
            energy: S::ZERO,
            dir: S::ONE,
            dz: S::ZERO,
            de: S::ZERO,
            h: S::ZERO,
        }
    }

    /// The same element with another integration control (the state is kept), which must pass
    /// [`Control::checked`].
    pub fn with_control(mut self, control: Control<S>) -> Result<Self, ParamError> {
        let control = control.checked()?;
        self.atol = Self::atol(&self.params, &self.extra, &control);
        self.control = Self::resolved(&self.params, &self.extra, control);
        Ok(self)
    }

    /// `control` as this element integrates: [`Method::Series`] sums plain
    /// Bouc-Wen only, so with any effect on it is the arithmetic's pair
    /// ([`Control::pair_for`]) at the same tolerance; likewise where the
    /// arithmetic cannot resolve the region of its sums near z = 0 (a small
    /// n with a large `|gamma - beta|`, see `series::resolves`). Decided
    /// once here, not at every step.
    fn resolved(params: &BwbnParams<S>, extra: &X, control: Control<S>) -> Control<S> {
        let plain = params.effect_set() == EffectSet::NONE && extra.is_none();
        if control.method == Method::Series && !(plain && series::resolves(params.base())) {
            Control {
                method: Control::<S>::pair_for(),
                ..control
            }
        } else {
            control
        }
    }

    /// The parameters.
    pub fn params(&self) -> &BwbnParams<S> {
        &self.params
    }
    /// The integration control, as the element integrates (`Series` becomes
    /// [`Control::pair_for`] when an effect is on, or where its sums near
    /// z = 0 are below the arithmetic's resolution).
    pub fn control(&self) -> &Control<S> {
        &self.control
    }
    /// The committed state.
    pub fn committed(&self) -> &State<S> {
        &self.committed
    }
    /// The trial state (equal to the committed one after commit or revert).
    pub fn trial(&self) -> &State<S> {
        &self.trial
    }

    fn at(u: S, z: S, energy: S, dir: S) -> At<S> {
        At { u, z, energy, dir }
    }

    fn response_of(&self, s: &State<S>) -> Response<S> {
        let k = self
            .params
            .stiffness(&self.extra, &Self::at(s.u, s.z, s.energy, s.dir));
        Response {
            force: k.el * s.u + k.hys * s.z,
            tangent: k.el + k.hys * s.dz,
        }
    }

    /// Plain Bouc-Wen from the committed state to displacement `u` by
    /// [`series`]. Kept out of line on bare-metal targets: inlined, it
    /// changed how the compiler laid out the Runge-Kutta path of the same
    /// function, whose Q15.16 steps then took 15% more instructions on the
    /// Cortex-M4F than before `Series` existed (out of line, 7%), and plain
    /// `f32` steps by `Series` itself 21% more (911 against 753). Inlined
    /// elsewhere: on the host the state then stays out of memory, 4% faster
    /// a step (`docs/benchmarks.md`).
    #[cfg_attr(target_os = "none", inline(never))]
    #[cfg_attr(not(target_os = "none"), inline)]
    fn advance_series(&self, u: S, dir: S, len: S) -> Result<State<S>, StepError> {
        let c = &self.committed;
        let base = self.params.base();
        let end = series::advance(base, &self.control, self.atol[0], (c.z, c.energy), dir, len)?;
        if !(end.z.is_finite() && end.dz_du.is_finite()) {
            return Err(StepError::NonFiniteState);
        }
        Ok(State {
            u,
            z: end.z,
            energy: end.energy,
            dir,
            dz: end.dz_du,
            de: end.de_du,
            h: c.h,
        })
    }

    /// Integrates from the committed state to displacement `u`.
    fn advance(&self, u: S) -> Result<State<S>, StepError> {
        let c = &self.committed;
        let du = u - c.u;
        if !du.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        let dir = if du > S::ZERO { S::ONE } else { -S::ONE };
        let len = du.abs();
        if self.control.method == Method::Series {
            return self.advance_series(u, dir, len);
        }
        self.advance_pair(u, dir, len)
    }

    /// The increment to displacement `u` by the Runge-Kutta pair of the
    /// control (or OpenSees' scheme). Kept out of line on bare-metal targets
    /// like [`Self::advance_series`]: inlined into `set_trial`, the
    /// Cortex-M4F took 1,881 instructions a step with all four effects in
    /// `f32`, out of line 1,730 (Q15.16: 9,033 and 8,560;
    /// `docs/benchmarks.md`).
    #[cfg_attr(target_os = "none", inline(never))]
    #[cfg_attr(not(target_os = "none"), inline)]
    fn advance_pair(&self, u: S, dir: S, len: S) -> Result<State<S>, StepError> {
        let c = &self.committed;
        let (p, x) = (&self.params, &self.extra);
        let (u0, dirv) = (c.u, dir);
        // y = [z, energy] as functions of s = |u - u0|: dy/ds = dir * dy/du.
        let mut rhs = |s: S, y: &[S; 2]| -> Result<[S; 2], StepError> {
            let at = Self::at(u0 + dirv * s, y[0], y[1], dirv);
            let dz = rate::dz_du(p, x, &at)?;
            let k_hys = p.stiffness(x, &at).hys;
            Ok([dirv * dz, dirv * k_hys * y[0]])
        };
        let y0 = [c.z, c.energy];
        // z is a kink: `|z|^n` and `sgn(z du)` change form at z = 0. After it,
        // and after a reversal (where z, nearly still at Zu before, leaves it
        // at 2 beta / (beta + gamma) times the elastic rate), the first
        // sub-step moves z by at most REVERSAL_REACH of its scale.
        let kink = integrate::Kink {
            index: 0,
            reach: S::lit(integrate::REVERSAL_REACH) * self.params.z_scale(),
        };
        let (dy0, h_try) = if c.dir == dir {
            ([dir * c.dz, dir * c.de], c.h)
        } else {
            let dy0 = rhs(S::ZERO, &y0)?;
            let floor = integrate::smallest_substep(len) * S::lit(8.0);
            (
                dy0,
                c.h.min(integrate::reach_size(kink.reach, dy0[0], floor)),
            )
        };
        let end = integrate::advance(
            &self.control,
            &mut rhs,
            y0,
            dy0,
            len,
            &self.atol,
            h_try,
            [kink],
        )?;
        let [z, energy] = end.y;
        // Energy that no effect reads is only reported: past what the
        // arithmetic holds it reads as non-finite, and the element goes on.
        let reads_energy = self.params.effects().reads_energy(&self.extra);
        if !(z.is_finite() && end.dy[0].is_finite() && (energy.is_finite() || !reads_energy)) {
            return Err(StepError::NonFiniteState);
        }
        if reads_energy && energy > self.params.energy_limit() {
            return Err(StepError::EnergyOutOfRange);
        }
        Ok(State {
            u,
            z,
            energy,
            dir,
            dz: dir * end.dy[0],
            de: dir * end.dy[1],
            h: end.h_next,
        })
    }
}

impl<S: Scalar, X: Effect<S>> Element<S> for Bwbn<S, X> {
    fn set_trial(&mut self, u: S) -> Result<Response<S>, StepError> {
        if !u.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        let state = if u == self.committed.u {
            self.committed
        } else {
            self.advance(u)?
        };
        let response = self.response_of(&state);
        if !(response.force.is_finite() && response.tangent.is_finite()) {
            return Err(StepError::NonFiniteState);
        }
        self.trial = state;
        self.response = response;
        Ok(response)
    }

    fn commit(&mut self) {
        self.committed = self.trial;
    }

    fn revert(&mut self) {
        self.trial = self.committed;
        self.response = self.response_of(&self.committed);
    }

    fn reset(&mut self) {
        let mut s = Self::virgin();
        let at = Self::at(S::ZERO, S::ZERO, S::ZERO, S::ONE);
        s.dz = rate::dz_du(&self.params, &self.extra, &at).unwrap_or(S::ONE);
        s.de = S::ZERO;
        self.committed = s;
        self.trial = s;
        self.response = self.response_of(&s);
    }

    fn response(&self) -> Response<S> {
        self.response
    }

    fn displacement(&self) -> S {
        self.committed.u
    }
}
