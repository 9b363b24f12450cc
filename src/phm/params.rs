//! A validated PHM parameter set: the primary curve of each direction and the
//! rule coefficients.

use super::backbone::{Backbone, BackboneError, Direction};
use super::rules::Coefficients;
use crate::bwbn::ParamError;
use crate::scalar::Scalar;
use core::fmt;

/// Why a PHM parameter set was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PhmError {
    /// A primary curve broke a rule.
    Backbone(BackboneError),
    /// A rule coefficient broke a rule.
    Coefficient(ParamError),
}

impl fmt::Display for PhmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PhmError::Backbone(e) => e.fmt(f),
            PhmError::Coefficient(e) => e.fmt(f),
        }
    }
}

impl core::error::Error for PhmError {}

impl From<BackboneError> for PhmError {
    fn from(e: BackboneError) -> Self {
        PhmError::Backbone(e)
    }
}

impl From<ParamError> for PhmError {
    fn from(e: ParamError) -> Self {
        PhmError::Coefficient(e)
    }
}

/// The parameters of a [`Phm`](super::Phm) element, with room for `N` points
/// per primary curve. Validated when built; shared by any number of elements.
///
/// ```
/// use hysteresis::phm::{Coefficients, PhmParams};
/// // Primary curve (twist, torque) in magnitudes: cracking, yield, plateau end,
/// // deterioration. The negative direction may differ.
/// let pos = [[1.0, 5.0], [4.0, 6.5], [8.0, 5.5]];
/// let neg = [[1.2, 5.5], [4.0, 7.0], [8.0, 6.0]];
/// let p = PhmParams::<f64>::new(&pos, &neg, Coefficients::thesis()).unwrap();
/// assert_eq!(p.coefficients().get("eq4_b"), Some(-0.786));
///
/// let bad = PhmParams::<f64>::symmetric(&[[1.0, 5.0], [0.5, 6.0]], Coefficients::thesis());
/// assert_eq!(
///     bad.unwrap_err().to_string(),
///     "positive primary curve, point 1: twists must increase strictly from zero"
/// );
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PhmParams<S, const N: usize = 8> {
    primary: [Backbone<S, N>; 2],
    coefficients: Coefficients<S>,
}

impl<S: Scalar, const N: usize> PhmParams<S, N> {
    /// A parameter set from the primary curves of the positive and negative
    /// directions (`[twist, torque]` magnitudes, cracking point first) and the
    /// rule coefficients.
    pub fn new(
        positive: &[[S; 2]],
        negative: &[[S; 2]],
        coefficients: Coefficients<S>,
    ) -> Result<Self, PhmError> {
        Ok(PhmParams {
            primary: [
                Backbone::new(Direction::Positive, positive)?,
                Backbone::new(Direction::Negative, negative)?,
            ],
            coefficients: coefficients.validated()?,
        })
    }

    /// The same primary curve in both directions.
    pub fn symmetric(points: &[[S; 2]], coefficients: Coefficients<S>) -> Result<Self, PhmError> {
        Self::new(points, points, coefficients)
    }

    /// A parameter set with the coefficients given by name (see
    /// [`SPECS`](super::SPECS)); a coefficient `get` does not know keeps the
    /// thesis' value.
    pub fn from_named(
        positive: &[[S; 2]],
        negative: &[[S; 2]],
        get: impl FnMut(&str) -> Option<S>,
    ) -> Result<Self, PhmError> {
        Self::new(positive, negative, Coefficients::from_named(get)?)
    }

    /// The primary curve of `direction`.
    pub fn primary(&self, direction: Direction) -> &Backbone<S, N> {
        &self.primary[direction.index()]
    }

    /// Both primary curves, positive first.
    pub(crate) fn curves(&self) -> &[Backbone<S, N>; 2] {
        &self.primary
    }

    /// The rule coefficients.
    pub fn coefficients(&self) -> &Coefficients<S> {
        &self.coefficients
    }

    /// The largest torque magnitude of either primary curve: no response of
    /// the element exceeds it.
    pub fn peak(&self) -> S {
        self.primary[0].peak().max(self.primary[1].peak())
    }
}
