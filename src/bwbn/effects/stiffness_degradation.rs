//! Stiffness degradation (thesis eq. 3.7):
//!
//! ```text
//! eta(e) = eta0 + delta_eta e,      dz/du = (...) / eta
//! ```
//!
//! eta divides the whole z-rate, so unloading and reloading stiffness fall as
//! energy is dissipated while Zu stays. Off: `eta0 = 1`, `delta_eta = 0`. eta
//! must stay positive inside `[0, energy_limit]`.

use super::{check_linear_positive, At, Coefficients, Effect};
use crate::bwbn::base::BoucWen;
use crate::bwbn::spec::{ParamError, ParamSpec, Unit};
use crate::scalar::Scalar;

/// Parameters of stiffness degradation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StiffnessDegradation<S> {
    eta0: S,
    delta_eta: S,
}

/// `eta0`, `delta_eta`.
pub const PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        name: "eta0",
        symbol: "η₀",
        equation: "3.7",
        off: 1.0,
        unit: Unit::Dimensionless,
        fit_range: (0.5, 2.0),
        doc: "initial stiffness degradation factor",
    },
    ParamSpec {
        name: "delta_eta",
        symbol: "δ_η",
        equation: "3.7",
        off: 0.0,
        unit: Unit::PerEnergy,
        fit_range: (0.0, 0.1),
        doc: "rate at which eta grows (stiffness falls) with dissipated energy",
    },
];

impl<S: Scalar> StiffnessDegradation<S> {
    /// Validates eta0 > 0 and eta(e) > 0 on `[0, energy_limit]`.
    pub fn new(eta0: S, delta_eta: S, energy_limit: S) -> Result<Self, ParamError> {
        check_linear_positive("eta0", eta0, "delta_eta", delta_eta, energy_limit)?;
        Ok(StiffnessDegradation { eta0, delta_eta })
    }
    /// `[eta0, delta_eta]`.
    pub fn values(&self) -> [S; 2] {
        [self.eta0, self.delta_eta]
    }
}

impl<S: Scalar> Effect<S> for StiffnessDegradation<S> {
    #[inline]
    fn apply(&self, _: &BoucWen<S>, _: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        c.inv_eta = c.inv_eta / (self.eta0 + self.delta_eta * at.energy);
    }
}
