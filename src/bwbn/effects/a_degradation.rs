//! Degradation of the hysteretic stiffness factor A with energy (thesis eq. 3.5):
//!
//! ```text
//! A(e) = A0 - delta_A e
//! ```
//!
//! Off: `A0 = 1`, `delta_A = 0`. A positive `delta_A` lowers A (and with it the
//! tangent of the hysteretic spring, `dz/du = A` at z = 0, and Zu); it must not
//! reach zero inside `[0, energy_limit]`.

use super::{check_linear_positive, At, Coefficients, Effect};
use crate::bwbn::base::BoucWen;
use crate::bwbn::spec::{ParamError, ParamSpec, Unit};
use crate::scalar::Scalar;

/// Parameters of A-degradation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ADegradation<S> {
    a0: S,
    delta_a: S,
}

/// `A0`, `delta_A`.
pub const PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        name: "A0",
        symbol: "A₀",
        equation: "3.5",
        off: 1.0,
        unit: Unit::Dimensionless,
        fit_range: (0.5, 2.0),
        doc: "initial hysteretic stiffness factor",
    },
    ParamSpec {
        name: "delta_A",
        symbol: "δ_A",
        equation: "3.5",
        off: 0.0,
        unit: Unit::PerEnergy,
        fit_range: (-0.05, 0.05),
        doc: "rate at which A falls with dissipated energy",
    },
];

impl<S: Scalar> ADegradation<S> {
    /// Validates A0 > 0 and A(e) > 0 on `[0, energy_limit]`.
    pub fn new(a0: S, delta_a: S, energy_limit: S) -> Result<Self, ParamError> {
        check_linear_positive("A0", a0, "delta_A", -delta_a, energy_limit)?;
        Ok(ADegradation { a0, delta_a })
    }
    /// `[A0, delta_A]`.
    pub fn values(&self) -> [S; 2] {
        [self.a0, self.delta_a]
    }
}

impl<S: Scalar> Effect<S> for ADegradation<S> {
    #[inline]
    fn apply(&self, _: &BoucWen<S>, _: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        c.a = self.a0 - self.delta_a * at.energy;
    }
}
