//! The element API every model implements: trial, commit, revert.
//!
//! A structural controller (or a finite-element code) drives an element with a
//! sequence of trial displacements. [`Element::set_trial`] computes the state at
//! the new displacement from the *committed* state and returns force and
//! tangent; it may be called any number of times, and it never changes the
//! committed state. [`Element::commit`] accepts the last successful trial,
//! [`Element::revert`] discards it. A trial that fails returns a typed
//! [`StepError`] and leaves the element exactly as it was before the call.

use crate::scalar::Scalar;
use core::fmt;

/// Force and consistent tangent stiffness at a trial displacement.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Response<S> {
    /// Restoring force.
    pub force: S,
    /// d(force)/d(displacement) along the direction of the last increment.
    pub tangent: S,
}

/// Why a step was refused. The element's committed and trial states are
/// unchanged whenever one of these is returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum StepError {
    /// The input (displacement, time step or forcing) was NaN or infinite, or cannot be
    /// used as given: a time step that is not positive, or in fixed point an increment
    /// `u - u_committed` or a time step squared beyond the arithmetic's range.
    NonFiniteInput,
    /// The integrator could not meet its error tolerance within the work budget
    /// of one step (the maximum number of sub-steps).
    ToleranceNotMet,
    /// The implicit (OpenSees-compatible) scheme's Newton iteration did not
    /// converge within its iteration budget.
    NotConverged,
    /// The new state is not finite: the model blew up (a hardening model driven
    /// far enough diverges in finite displacement) or a fixed-point value
    /// saturated.
    NonFiniteState,
    /// The dissipated energy left the range `[0, energy_limit]` in which the
    /// parameter set was validated, or a degradation function (A, nu, eta)
    /// reached zero.
    EnergyOutOfRange,
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            StepError::NonFiniteInput => {
                "input is NaN or infinite, or beyond the arithmetic's range (or a time step <= 0)"
            }
            StepError::ToleranceNotMet => {
                "the step could not meet its error tolerance within its sub-step budget"
            }
            StepError::NotConverged => {
                "the implicit step did not converge within its iteration budget"
            }
            StepError::NonFiniteState => {
                "the new state is not finite (model diverged or arithmetic saturated)"
            }
            StepError::EnergyOutOfRange => {
                "the dissipated energy left the range the parameters were validated for"
            }
        })
    }
}

impl core::error::Error for StepError {}

/// A hysteretic element driven by displacement.
pub trait Element<S: Scalar> {
    /// Computes the trial state at displacement `u`, starting from the
    /// committed state, and returns its force and tangent. On error nothing
    /// changes.
    fn set_trial(&mut self, u: S) -> Result<Response<S>, StepError>;
    /// Makes the last successful trial the committed state.
    fn commit(&mut self);
    /// Discards the trial: the trial state becomes the committed state again.
    fn revert(&mut self);
    /// Returns to the virgin state (zero displacement, no history).
    fn reset(&mut self);
    /// Force and tangent of the current trial state (the committed state right
    /// after [`commit`](Element::commit) or [`revert`](Element::revert)).
    fn response(&self) -> Response<S>;
    /// The committed displacement.
    fn displacement(&self) -> S;
}
