//! Rate dependence: an effect the library does not model, looked for so that
//! the diagnosis can name it instead of pinning the error on an effect it does
//! model.
//!
//! A viscous force grows with the speed of loading (a dashpot, the fluid of a
//! damper, strain-rate effects); the Bouc-Wen models are rate independent, so
//! their residual then follows the velocity `v = du/dt`. The check regresses
//! the residual of a displacement-driven fit on `v`, next to terms that a
//! misfit of the rate-independent model leaves:
//!
//! ```text
//! r ≈ a + b sgn(v) + e sgn(v) A(t) + k u + c v
//! ```
//!
//! `a` is a force offset, `b sgn(v)` a loop too wide or too thin, `e sgn(v) A`
//! one whose error grows with the amplitude `A(t)` reached so far, `k u` a
//! wrong elastic stiffness. In a test loaded at constant speed `v` is
//! `sgn(v)` times a constant, and in one run at a constant period with
//! triangular cycles it is `sgn(v) A` times a constant: such tests cannot
//! separate rate dependence from a rate-independent misfit, and the check
//! stays silent on them. Only what `c v` explains beyond the four counts, and
//! only a dissipating `c > 0` (a dashpot; `c < 0` would feed energy in). The
//! evidence
//! is weighed like a suspect's (see [`suspects`](super::suspects)): BIC with
//! the residual's effective sample size, significant below -10, and, since the
//! user cannot add the effect from the library, only when `c v` removes at
//! least [`MIN_SHARE`] of the squared error. The model is not refitted with the
//! viscous term, so the improvement is a lower bound of what a joint fit would
//! find: the check errs towards silence.

use super::diagnosis::Diagnosis;
use super::suspects::{effective_n, SIGNIFICANT_BIC};
use crate::fit::regression::regress;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Smallest share of the squared error a viscous term must remove to be
/// reported as significant (1% of the NRMSE): on very long records the BIC
/// alone would name effects too small to matter. Measured
/// (`tests/discover_rate.rs`): 0.0-0.9% without a dashpot, 4.9-7.5% with one
/// of a tenth of the strength (most of which the fit absorbs into its loop).
pub const MIN_SHARE: f64 = 0.02;

/// Half-width (samples) of the central difference that estimates velocity.
const HALF_WIDTH: usize = 2;

/// What the residual says about rate dependence.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct RateCheck {
    /// Evidence strong enough (delta-BIC below -10 and at least
    /// [`MIN_SHARE`] of the squared error removed).
    pub significant: bool,
    /// The viscous coefficient `c` fitted to the residual, force per
    /// (displacement/s) (kN s/mm for kN and mm): the model lacks `c v`. A
    /// lower bound of a joint fit's, as the rate-independent fit has absorbed
    /// part of any dashpot into a wider loop.
    pub viscous: f64,
    /// Share of the squared error `c v` removes beyond the constant and the
    /// direction term.
    pub share: f64,
    /// NRMSE of the model with `c v` added.
    pub nrmse_with: f64,
    /// BIC change from adding `c v`.
    pub delta_bic: f64,
    /// Effective sample size used.
    pub n_eff: f64,
    /// The evidence in words.
    pub evidence: String,
}

/// Velocity by central differences over `HALF_WIDTH` samples each side
/// (one-sided at the ends); `None` if the times do not increase.
fn velocity(u: &[f64], t: &[f64]) -> Option<Vec<f64>> {
    let n = u.len();
    if n < 3 || t.len() != n {
        return None;
    }
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(HALF_WIDTH), (i + HALF_WIDTH).min(n - 1));
            let dt = t[b] - t[a];
            (dt > 0.0).then(|| (u[b] - u[a]) / dt)
        })
        .collect()
}

/// Looks for rate dependence in the residual of `d` (a displacement-driven
/// fit with NRMSE `nrmse`), with the sample times `time`. `None` when the
/// record has no usable time base or the loading never changes speed.
pub fn check(d: &Diagnosis, time: &[f64], nrmse: f64) -> Option<RateCheck> {
    let v = velocity(&d.displacement, time)?;
    let s = |v: f64| {
        if v > 0.0 {
            1.0
        } else if v < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    let u = &d.displacement;
    // The amplitude reached so far: in tests run at a constant period the
    // speed grows with it, and so may a misfit of the rate-independent model.
    let envelope: Vec<f64> = u
        .iter()
        .scan(0.0f64, |a, x| {
            *a = a.max(x.abs());
            Some(*a)
        })
        .collect();
    // Columns: the four nuisance terms, then the velocity.
    let x = DMatrix::from_row_iterator(
        v.len(),
        5,
        v.iter().zip(u).zip(&envelope).flat_map(|((&v, &u), &a)| {
            let dir = s(v);
            [1.0, dir, dir * a, u, v]
        }),
    );
    let r = DVector::from_column_slice(&d.residual);
    let (rss_base, _) = regress(&x.columns(0, 4).into_owned(), &r)?;
    let (rss_full, coef) = regress(&x, &r)?;
    let total = r.norm_squared();
    if !(total > 0.0 && rss_full > 0.0) {
        return None;
    }
    let gain = (rss_base - rss_full).max(0.0);
    let share = gain / total;
    let floor = d.segmentation.cycles().half_cycles().len();
    let n_eff = effective_n(&d.residual, 1, floor);
    let delta_bic = n_eff * (rss_full / rss_base).ln() + n_eff.ln();
    let nrmse_with = nrmse * (1.0 - share).max(0.0).sqrt();
    // The model's force is measured + r, so the missing force is -r ≈ -c v.
    let viscous = -coef[4];
    // A dashpot dissipates: c < 0 would feed energy in, which no material
    // does; such a correlation is a misfit of another kind.
    let significant = delta_bic < SIGNIFICANT_BIC && share >= MIN_SHARE && viscous > 0.0;
    let speeds: Vec<f64> = v.iter().map(|v| v.abs()).filter(|v| *v > 0.0).collect();
    let (lo, hi) = quantiles(&speeds);
    let evidence = format!(
        "Fitted beyond the loading direction and amplitude, a viscous force c v with \
         c = {viscous:.4e} (force per displacement/s; fitted to the residual of the \
         rate-independent fit, which has absorbed part of any dashpot into its loop, so a lower \
         bound) takes the NRMSE from {nrmse:.4} to {nrmse_with:.4} ({:.1}% of the squared \
         error; delta-BIC {delta_bic:+.0}). The speed of loading ranges from {lo:.3e} to \
         {hi:.3e} (10th to 90th percentile). {}",
        100.0 * share,
        if significant {
            "No effect in the library grows with speed: the models here are rate independent, so \
             model it outside them (a dashpot in parallel, a rate-dependent law)."
        } else {
            if viscous > 0.0 {
                "Not significant: the residual does not grow with speed enough to name it."
            } else {
                "Not significant: with c < 0 the term would feed energy in, so this is a misfit \
                 of another kind, not viscosity."
            }
        }
    );
    Some(RateCheck {
        significant,
        viscous,
        share,
        nrmse_with,
        delta_bic,
        n_eff,
        evidence,
    })
}

/// The 10th and 90th percentiles (0 for an empty slice).
fn quantiles(x: &[f64]) -> (f64, f64) {
    if x.is_empty() {
        return (0.0, 0.0);
    }
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let at = |q: f64| s[((s.len() - 1) as f64 * q).round() as usize];
    (at(0.1), at(0.9))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn velocity_of_a_ramp_is_its_slope() {
        let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.01).collect();
        let u: Vec<f64> = t.iter().map(|t| 3.0 * t).collect();
        for v in velocity(&u, &t).unwrap() {
            assert!((v - 3.0).abs() < 1e-12, "{v}");
        }
        let backwards: Vec<f64> = t.iter().rev().copied().collect();
        assert!(velocity(&u, &backwards).is_none());
    }
}
