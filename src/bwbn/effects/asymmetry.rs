//! Asymmetry: unequal strength, and if the data ask for it unequal stiffness,
//! in the two directions of loading. Not in the thesis; added as an effect
//! module like the others (section "Adding an effect" of [`super`]).
//!
//! ```text
//! Zu+ = Zu (1 + a),   Zu- = Zu (1 - a)                 strength
//! R   = alpha k0 (1 + b sgn u) u + (1 - alpha) k0 (1 + b sgn z) z   stiffness
//! ```
//!
//! The strength asymmetry `a` scales nu by `(1 + a sgn z)^-n` (Zu is
//! proportional to `nu^(-1/n)`, eq. 3.12); both factors are computed once,
//! when the parameters are built. The stiffness asymmetry `b` scales each
//! spring by the sign of its own displacement, which keeps the force
//! continuous (each spring's force is zero where its factor jumps) and makes
//! the hysteretic energy `∫ k_hys z du` follow the stiffer side.
//!
//! Off: `a = b = 0`. Both must lie in (-1, 1).

use super::{At, Coefficients, Effect, Stiffness};
use crate::bwbn::base::BoucWen;
use crate::bwbn::spec::{ParamError, ParamSpec, Rule, Unit};
use crate::scalar::Scalar;

/// Parameters of asymmetry.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Asymmetry<S> {
    a: S,
    b: S,
    nu_pos: S,
    nu_neg: S,
}

/// `asym_strength`, `asym_stiffness`.
pub const PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        name: "asym_strength",
        symbol: "a",
        equation: "Zu± = Zu (1 ± a)",
        off: 0.0,
        unit: Unit::Dimensionless,
        fit_range: (-0.6, 0.6),
        doc: "strength asymmetry: positive Zu is (1+a) Zu, negative (1-a) Zu",
    },
    ParamSpec {
        name: "asym_stiffness",
        symbol: "b",
        equation: "k± = k0 (1 ± b)",
        off: 0.0,
        unit: Unit::Dimensionless,
        fit_range: (-0.6, 0.6),
        doc: "stiffness asymmetry: springs are (1+b) k0 on the positive side, (1-b) k0 on the negative",
    },
];

fn check_fraction<S: Scalar>(name: &'static str, v: S) -> Result<(), ParamError> {
    if !v.is_finite() {
        return Err(ParamError::new(name, Rule::NotFinite));
    }
    if !(v > -S::ONE && v < S::ONE) {
        return Err(ParamError::new(name, Rule::NotASignedFraction));
    }
    Ok(())
}

impl<S: Scalar> Asymmetry<S> {
    /// Validates `a` and `b` in (-1, 1) and precomputes the nu factors.
    pub fn new(base: &BoucWen<S>, a: S, b: S) -> Result<Self, ParamError> {
        check_fraction("asym_strength", a)?;
        check_fraction("asym_stiffness", b)?;
        let minus_n = -base.n;
        let (nu_pos, nu_neg) = ((S::ONE + a).powf(minus_n), (S::ONE - a).powf(minus_n));
        // With a near ±1 and a large n one factor leaves the arithmetic's range (f32 `inf`,
        // a saturated Q15.16), and every step towards that side would fail.
        if !(nu_pos.is_finite() && nu_neg.is_finite()) {
            return Err(ParamError::new("asym_strength", Rule::DerivedOverflow));
        }
        Ok(Asymmetry {
            a,
            b,
            nu_pos,
            nu_neg,
        })
    }

    /// `[asym_strength, asym_stiffness]`.
    pub fn values(&self) -> [S; 2] {
        [self.a, self.b]
    }

    /// The smaller of the two strength factors `(1 ± a)^-n`: the side whose `|z|^n` reaches
    /// the highest asymptote.
    pub(crate) fn weaker_side(&self) -> S {
        self.nu_pos.min(self.nu_neg)
    }
}

impl<S: Scalar> Effect<S> for Asymmetry<S> {
    #[inline]
    fn apply(&self, _: &BoucWen<S>, _: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        if at.z > S::ZERO {
            c.nu *= self.nu_pos;
        } else if at.z < S::ZERO {
            c.nu *= self.nu_neg;
        }
    }

    #[inline]
    fn stiffness(&self, _: &BoucWen<S>, at: &At<S>, k: &mut Stiffness<S>) {
        k.el *= S::ONE + self.b * at.u.signum0();
        k.hys *= S::ONE + self.b * at.z.signum0();
    }
}
