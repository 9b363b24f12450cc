//! The Bouc-Wen base model (thesis eqs 3.2 and 3.4 with A = nu = eta = h = 1).
//!
//! Restoring force (eq. 3.2): `R = alpha k0 u + (1 - alpha) k0 z`, with the
//! hysteretic displacement z obeying (eq. 3.4)
//!
//! ```text
//! dz/du = A - nu |z|^n (beta sgn(du z) + gamma)        (all effects off)
//! ```
//!
//! Five parameters: `k0`, `alpha`, `n`, `beta`, `gamma`. Sets with
//! `beta + gamma < 0` are legal: the hysteretic force then hardens instead of
//! approaching a plateau (the Bouc-Wen benchmark of Noel and Schoukens is such a
//! system); only effects that need the ultimate value Zu (eq. 3.12) require
//! `beta + gamma > 0`.

use super::spec::{ParamError, ParamSpec, Rule, Unit};
use crate::scalar::Scalar;

/// Parameters of the plain Bouc-Wen model.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BoucWen<S> {
    /// Initial stiffness k (eq. 3.2), force per displacement.
    pub k0: S,
    /// Rigidity ratio alpha in [0, 1] (eq. 3.2): the share of k0 that stays
    /// linear elastic.
    pub alpha: S,
    /// Smoothness n > 0 of the elastic-plastic transition (eq. 3.4).
    pub n: S,
    /// Loop shape parameter beta (eq. 3.4).
    pub beta: S,
    /// Loop shape parameter gamma (eq. 3.4).
    pub gamma: S,
}

/// The base parameters, in the order of [`BoucWen::values`].
pub const PARAMS: [ParamSpec; 5] = [
    ParamSpec {
        name: "k0",
        symbol: "k",
        equation: "3.2",
        off: 1.0,
        unit: Unit::Stiffness,
        fit_range: (0.3, 3.0),
        doc: "initial stiffness",
    },
    ParamSpec {
        name: "alpha",
        symbol: "α",
        equation: "3.2",
        off: 0.05,
        unit: Unit::Dimensionless,
        fit_range: (0.0, 0.5),
        doc: "rigidity ratio: post-yield to initial stiffness",
    },
    ParamSpec {
        name: "n",
        symbol: "n",
        equation: "3.4",
        off: 1.0,
        unit: Unit::Dimensionless,
        fit_range: (0.6, 4.0),
        doc: "smoothness of the elastic-plastic transition",
    },
    ParamSpec {
        name: "beta",
        symbol: "β",
        equation: "3.4",
        off: 0.5,
        unit: Unit::DisplacementPowMinusN,
        fit_range: (0.0, 20.0),
        doc: "loop shape (with gamma: size of the loop, Zu = (1/(beta+gamma))^(1/n))",
    },
    ParamSpec {
        name: "gamma",
        symbol: "γ",
        equation: "3.4",
        off: 0.5,
        unit: Unit::DisplacementPowMinusN,
        fit_range: (-20.0, 20.0),
        doc: "loop shape: unloading stiffness relative to loading",
    },
];

impl<S: Scalar> BoucWen<S> {
    /// Validates and builds the base parameters.
    ///
    /// ```
    /// use hysteresis::bwbn::BoucWen;
    /// let bw = BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).unwrap();
    /// assert_eq!(bw.zu(), Some(1.0));
    /// assert_eq!(BoucWen::new(6.0, 1.5, 1.2, 2.0, -1.0).unwrap_err().field, "alpha");
    /// ```
    pub fn new(k0: S, alpha: S, n: S, beta: S, gamma: S) -> Result<Self, ParamError> {
        let p = BoucWen {
            k0,
            alpha,
            n,
            beta,
            gamma,
        };
        for (spec, v) in PARAMS.iter().zip(p.values()) {
            if !v.is_finite() {
                return Err(ParamError::new(spec.name, Rule::NotFinite));
            }
        }
        if k0 <= S::ZERO {
            return Err(ParamError::new("k0", Rule::NotPositive));
        }
        if alpha < S::ZERO || alpha > S::ONE {
            return Err(ParamError::new("alpha", Rule::NotAFraction));
        }
        if n <= S::ZERO {
            return Err(ParamError::new("n", Rule::NotPositive));
        }
        // Zu^n = 1/(beta + gamma) is the value |z|^n approaches on loading
        // (eq. 3.12), and `r = |beta - gamma| Zu^n` the rate of |z|^n's term
        // on a reversal there: dz/du = 1 + r, the largest hysteretic
        // stiffness `k0 (1 + r)`, and `n r` the scale of the series' first
        // sub-step (`series.rs`). An arithmetic that cannot hold them
        // (Q15.16, when gamma nearly cancels beta) would saturate on the way
        // to Zu or at the reversal. Found by proptest (`tests/bwbn_series.rs`):
        // beta 0.05, gamma -0.04999 (Zu^n = 65,536), Q15.16 steps refused at
        // z = 19 of Zu = 22.9 after small increments and 41% off after one
        // long one; beta 18.94, gamma -18.94 (n r = 43,000), a reversal at
        // Zu refused.
        let sum = beta + gamma;
        if sum > S::ZERO {
            let zu_n = S::ONE / sum;
            let r = (beta - gamma).abs() * zu_n;
            let derived = [zu_n, k0 * (S::ONE + r), S::ONE + n * r];
            if !derived.iter().all(|v| v.is_finite()) {
                return Err(ParamError::new("gamma", Rule::DerivedOverflow));
            }
        }
        Ok(p)
    }

    /// The parameter values in the order of [`PARAMS`].
    pub fn values(&self) -> [S; 5] {
        [self.k0, self.alpha, self.n, self.beta, self.gamma]
    }

    /// Zu = (1/(beta+gamma))^(1/n), the asymptote of z under monotonic loading
    /// with A = nu = 1 (eq. 3.12), or `None` for hardening sets
    /// (`beta + gamma <= 0`).
    pub fn zu(&self) -> Option<S> {
        let s = self.beta + self.gamma;
        if s > S::ZERO {
            Some((S::ONE / s).powf(S::ONE / self.n))
        } else {
            None
        }
    }

    /// The displacement scale of z: Zu when it exists, otherwise the z at
    /// which the nonlinear term reaches the linear one,
    /// `(1/(|beta|+|gamma|))^(1/n)`. Integration tolerances are relative to it.
    pub fn z_scale(&self) -> S {
        match self.zu() {
            Some(zu) => zu,
            None => {
                let s = self.beta.abs() + self.gamma.abs();
                if s > S::ZERO {
                    (S::ONE / s).powf(S::ONE / self.n)
                } else {
                    S::ONE
                }
            }
        }
    }
}
