//! The rate of the hysteretic displacement, thesis eq. 3.4 (eq. 3.16 in the
//! state-space form), assembled from the coefficients the effects set:
//!
//! ```text
//! dz/du = h (A - nu |z|^n (beta sgn(du z) + gamma)) / eta
//! ```
//!
//! (`beta |du| |z|^(n-1) z + gamma du |z|^n = du |z|^n (beta sgn(du z) + gamma)`,
//! so one power suffices and z = 0 needs no special case.)

use super::effects::{At, Effect};
use super::params::BwbnParams;
use crate::element::StepError;
use crate::scalar::Scalar;

/// dz/du at `at` (along `at.dir`), or an error if the degradation functions
/// left their domain (A < 0, nu <= 0, eta <= 0: the energy went beyond where
/// the parameters are valid).
#[inline]
pub(crate) fn dz_du<S: Scalar, X: Effect<S>>(
    p: &BwbnParams<S>,
    extra: &X,
    at: &At<S>,
) -> Result<S, StepError> {
    let c = p.coefficients(extra, at);
    if !(c.nu > S::ZERO && c.inv_eta > S::ZERO && c.a >= S::ZERO && c.h >= S::ZERO) {
        return Err(StepError::EnergyOutOfRange);
    }
    let b = p.base();
    let zn = at.z.abs().powf(b.n);
    let psi = if at.z * at.dir > S::ZERO {
        b.gamma + b.beta
    } else {
        b.gamma - b.beta
    };
    Ok(c.h * (c.a - c.nu * zn * psi) * c.inv_eta)
}
