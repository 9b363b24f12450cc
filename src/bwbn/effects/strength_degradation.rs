//! Strength degradation (thesis eq. 3.6):
//!
//! ```text
//! nu(e) = nu0 + delta_nu e
//! ```
//!
//! nu multiplies the nonlinear term of the z-rate, so the ultimate hysteretic
//! displacement Zu = (A/(nu(beta+gamma)))^(1/n) and with it the strength fall
//! as energy is dissipated. Off: `nu0 = 1`, `delta_nu = 0`. nu must stay
//! positive inside `[0, energy_limit]`.

use super::{check_linear_positive, At, Coefficients, Effect};
use crate::bwbn::base::BoucWen;
use crate::bwbn::spec::{ParamError, ParamSpec, Unit};
use crate::scalar::Scalar;

/// Parameters of strength degradation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrengthDegradation<S> {
    nu0: S,
    delta_nu: S,
}

/// `nu0`, `delta_nu`.
pub const PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        name: "nu0",
        symbol: "ν₀",
        equation: "3.6",
        off: 1.0,
        unit: Unit::Dimensionless,
        fit_range: (0.5, 2.0),
        doc: "initial strength degradation factor",
    },
    ParamSpec {
        name: "delta_nu",
        symbol: "δ_ν",
        equation: "3.6",
        off: 0.0,
        unit: Unit::PerEnergy,
        fit_range: (0.0, 0.1),
        doc: "rate at which nu grows (strength falls) with dissipated energy",
    },
];

impl<S: Scalar> StrengthDegradation<S> {
    /// Validates nu0 > 0 and nu(e) > 0 on `[0, energy_limit]`.
    pub fn new(nu0: S, delta_nu: S, energy_limit: S) -> Result<Self, ParamError> {
        check_linear_positive("nu0", nu0, "delta_nu", delta_nu, energy_limit)?;
        Ok(StrengthDegradation { nu0, delta_nu })
    }
    /// `[nu0, delta_nu]`.
    pub fn values(&self) -> [S; 2] {
        [self.nu0, self.delta_nu]
    }
}

impl<S: Scalar> Effect<S> for StrengthDegradation<S> {
    #[inline]
    fn apply(&self, _: &BoucWen<S>, _: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        c.nu *= self.nu0 + self.delta_nu * at.energy;
    }
}
