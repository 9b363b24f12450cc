//! Pinching (thesis eqs 3.9-3.11, Baber and Noori):
//!
//! ```text
//! h(z)     = 1 - zeta1 exp(-(z sgn(du) - q Zu)^2 / zeta2^2)      (3.9)
//! zeta1(e) = zeta0 (1 - exp(-p e))                              (3.10)
//! zeta2(e) = (psi0 + delta_psi e) (lambda + zeta1)              (3.11)
//! Zu       = (A / (nu (beta + gamma)))^(1/n)                    (3.12)
//! ```
//!
//! h multiplies the z-rate: around `z = q Zu sgn(du)`, in a band of width
//! zeta2, the hysteretic stiffness drops by the factor `1 - zeta1`, which is
//! what makes the loops of shear-cracked RC members narrow near zero force on
//! reloading. The severity zeta1 grows with energy towards zeta0.
//!
//! Off: `zeta0 = 0` (then h = 1 and the other five parameters do nothing).
//!
//! Validation: Zu must exist (`beta + gamma > 0`); zeta2 must not vanish on
//! `[0, energy_limit]` (it divides); zeta1 must stay at or below 1 there, or h
//! turns negative and the hysteretic rate reverses. Negative zeta0 (h > 1,
//! "anti-pinching") is legal: the thesis' fits contain it (Table 3.3).
//!
//! OpenSees' `BWBN` material computes Zu as `(1/(beta+gamma))^(1/n)`,
//! ignoring A and nu; [`ZuRule::OpenSees`] reproduces that.

use super::{At, Coefficients, Effect};
use crate::bwbn::base::BoucWen;
use crate::bwbn::spec::{ParamError, ParamSpec, Rule, Unit};
use crate::scalar::Scalar;

/// How Zu in eq. 3.9 is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ZuRule {
    /// Eq. 3.12 with the current (degraded) A and nu.
    Thesis,
    /// `(1/(beta+gamma))^(1/n)`, as OpenSees' `BWBN` material.
    OpenSees,
}

/// Parameters of pinching.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pinching<S> {
    zeta0: S,
    p: S,
    q: S,
    psi0: S,
    delta_psi: S,
    lambda: S,
    zu_rule: ZuRule,
}

/// `zeta0`, `p`, `q`, `psi0`, `delta_psi`, `lambda`.
pub const PARAMS: [ParamSpec; 6] = [
    ParamSpec {
        name: "zeta0",
        symbol: "ζ₀",
        equation: "3.10",
        off: 0.0,
        unit: Unit::Dimensionless,
        fit_range: (0.0, 0.99),
        doc: "pinching severity reached at large energy (h drops to 1 - zeta0)",
    },
    ParamSpec {
        name: "p",
        symbol: "p",
        equation: "3.10",
        off: 1.0,
        unit: Unit::PerEnergy,
        fit_range: (0.0, 5.0),
        doc: "rate at which pinching severity grows with dissipated energy",
    },
    ParamSpec {
        name: "q",
        symbol: "q",
        equation: "3.9",
        off: 0.1,
        unit: Unit::Dimensionless,
        fit_range: (-0.5, 0.9),
        doc: "centre of the pinching band as a fraction of Zu",
    },
    ParamSpec {
        name: "psi0",
        symbol: "ψ₀",
        equation: "3.11",
        off: 0.2,
        unit: Unit::Displacement,
        fit_range: (0.02, 2.0),
        doc: "initial width of the pinching band",
    },
    ParamSpec {
        name: "delta_psi",
        symbol: "δ_ψ",
        equation: "3.11",
        off: 0.0,
        unit: Unit::DisplacementPerEnergy,
        fit_range: (0.0, 0.5),
        doc: "growth of the pinching band width with dissipated energy",
    },
    ParamSpec {
        name: "lambda",
        symbol: "λ",
        equation: "3.11",
        off: 0.5,
        unit: Unit::Dimensionless,
        fit_range: (0.05, 2.0),
        doc: "coupling of band width to severity",
    },
];

fn same_sign_nonzero<S: Scalar>(a: S, b: S) -> bool {
    (a > S::ZERO && b > S::ZERO) || (a < S::ZERO && b < S::ZERO)
}

impl<S: Scalar> Pinching<S> {
    /// Validates `[zeta0, p, q, psi0, delta_psi, lambda]` against the base model
    /// and the energy range (see the module docs for the rules).
    pub fn new(
        base: &BoucWen<S>,
        values: [S; 6],
        zu_rule: ZuRule,
        energy_limit: S,
    ) -> Result<Self, ParamError> {
        for (spec, v) in PARAMS.iter().zip(values) {
            if !v.is_finite() {
                return Err(ParamError::new(spec.name, Rule::NotFinite));
            }
        }
        let [zeta0, p, q, psi0, delta_psi, lambda] = values;
        if base.zu().is_none() {
            return Err(ParamError::new("beta + gamma", Rule::ZuUndefined));
        }
        let pin = Pinching {
            zeta0,
            p,
            q,
            psi0,
            delta_psi,
            lambda,
            zu_rule,
        };
        // zeta1 and the two factors of zeta2 are monotonic in e: check the ends.
        let (z1_start, z1_end) = (S::ZERO, pin.zeta1(energy_limit));
        if z1_start > S::ONE || z1_end > S::ONE {
            return Err(ParamError::new("zeta0", Rule::PinchingReversesRate));
        }
        if !same_sign_nonzero(lambda + z1_start, lambda + z1_end) {
            return Err(ParamError::new("lambda", Rule::DegradesToZero));
        }
        let psi_end = if delta_psi == S::ZERO {
            psi0
        } else {
            psi0 + delta_psi * energy_limit
        };
        if psi0 == S::ZERO {
            return Err(ParamError::new("psi0", Rule::Zero));
        }
        if !same_sign_nonzero(psi0, psi_end) {
            return Err(ParamError::new("delta_psi", Rule::DegradesToZero));
        }
        Ok(pin)
    }

    /// The same parameters with another rule for Zu.
    pub fn with_zu_rule(mut self, zu_rule: ZuRule) -> Self {
        self.zu_rule = zu_rule;
        self
    }

    /// How Zu is computed.
    pub fn zu_rule(&self) -> ZuRule {
        self.zu_rule
    }

    /// `[zeta0, p, q, psi0, delta_psi, lambda]`.
    pub fn values(&self) -> [S; 6] {
        [
            self.zeta0,
            self.p,
            self.q,
            self.psi0,
            self.delta_psi,
            self.lambda,
        ]
    }

    /// zeta1 at energy `e` (eq. 3.10).
    #[inline]
    fn zeta1(&self, e: S) -> S {
        if self.zeta0 == S::ZERO {
            return S::ZERO;
        }
        self.zeta0 * (S::ONE - (-(self.p * e)).exp())
    }
}

impl<S: Scalar> Effect<S> for Pinching<S> {
    #[inline]
    fn apply(&self, base: &BoucWen<S>, zu_plain: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        let zeta1 = self.zeta1(at.energy);
        if zeta1 == S::ZERO {
            return;
        }
        let zeta2 = (self.psi0 + self.delta_psi * at.energy) * (self.lambda + zeta1);
        let zu = match self.zu_rule {
            ZuRule::Thesis => c.zu(base, zu_plain),
            ZuRule::OpenSees => zu_plain,
        }
        .unwrap_or(S::ZERO);
        let x = (at.z * at.dir - self.q * zu) / zeta2;
        c.h *= S::ONE - zeta1 * (-(x * x)).exp();
    }
}
