//! Can the record determine the parameters? The Jacobian of the residuals at
//! the fit tells: its singular values (rank and condition), the parameter
//! covariance `s^2 (J^T J)^-1` with its correlations, and the directions in
//! parameter space along which the output hardly changes.
//!
//! Known cases this reports: a 17-parameter BWBN fitted to one record reaches
//! a tiny error with parameters far from the truth (many combinations give the
//! same loops), and in the Bouc-Wen benchmark beta, gamma and delta cannot be
//! separated.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// A direction the data hardly constrain.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct WeakDirection {
    /// Singular value relative to the largest.
    pub relative_singular_value: f64,
    /// The parameters with the largest weights in the direction, with their
    /// components (the combination that can change without changing the
    /// output).
    pub parameters: Vec<(String, f64)>,
}

/// The identifiability summary of a fit.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Identifiability {
    /// Number of free parameters.
    pub parameters: usize,
    /// Numerical rank of the Jacobian (singular values above 1e-6 of the
    /// largest).
    pub rank: usize,
    /// Largest over smallest singular value.
    pub condition: f64,
    /// Relative standard error of each parameter (std / |value|), from the
    /// residual variance; infinite where the Jacobian is rank deficient.
    pub relative_std: Vec<(String, f64)>,
    /// Pairs with |correlation| above 0.95.
    pub correlated: Vec<(String, String, f64)>,
    /// Directions with singular value below 1e-3 of the largest.
    pub weak: Vec<WeakDirection>,
    /// Parameters the data cannot determine (relative std above 50%, or a
    /// major part of a weak direction).
    pub undetermined: Vec<String>,
}

impl Identifiability {
    /// One paragraph in plain words.
    pub fn summary(&self) -> String {
        let condition = if self.condition.is_finite() {
            format!("{:.3e}", self.condition)
        } else {
            "infinite".to_string()
        };
        let mut s = format!(
            "Jacobian rank {} of {} parameters, condition number {condition}.",
            self.rank, self.parameters
        );
        if self.undetermined.is_empty() {
            s.push_str(" Every parameter is determined by the data.");
        } else {
            s.push_str(&format!(
                " The data cannot determine {}: other values fit about as well.",
                self.undetermined.join(", ")
            ));
            for w in &self.weak {
                let names: Vec<_> = w
                    .parameters
                    .iter()
                    .map(|(n, c)| format!("{c:+.2} {n}"))
                    .collect();
                if w.relative_singular_value > 0.0 {
                    s.push_str(&format!(
                        " The combination [{}] is {:.1e} times less visible in the output than the best-determined one.",
                        names.join(", "),
                        w.relative_singular_value
                    ));
                } else {
                    s.push_str(&format!(
                        " The combination [{}] does not change the output at all.",
                        names.join(", ")
                    ));
                }
            }
            s.push_str(" Fix some of them (--fix name=value) or add data that exercises them.");
        }
        s
    }
}

/// `cost / (n_obs - p)`: the residual variance of a fit of `p` parameters.
fn residual_variance(cost: f64, n_obs: usize, p: usize) -> f64 {
    cost / n_obs.saturating_sub(p).max(1) as f64
}

/// `(J^T J)^+ = V diag(1/s^2) V^T` from the singular values and `V^T` of
/// `J`; a parameter in a null direction gets an infinite variance.
fn normal_inverse(sv: &[f64], v_t: &DMatrix<f64>, smax: f64) -> DMatrix<f64> {
    let p = v_t.ncols();
    let mut cov: DMatrix<f64> = DMatrix::zeros(p, p);
    for (k, &s) in sv.iter().enumerate() {
        if s > 1e-12 * smax {
            let w = 1.0 / (s * s);
            for i in 0..p {
                for j in 0..p {
                    cov[(i, j)] += v_t[(k, i)] * v_t[(k, j)] * w;
                }
            }
        } else {
            // A null direction: the parameters in it have no finite variance.
            for i in 0..p {
                if v_t[(k, i)].abs() > 1e-8 {
                    cov[(i, i)] = f64::INFINITY;
                }
            }
        }
    }
    cov
}

/// The parameter covariance `s^2 (J^T J)^+` of a fit with Jacobian `jac`
/// and residual sum of squares `cost` over `n_obs` observations (infinite
/// variances in the directions the Jacobian does not see).
pub fn covariance(jac: &DMatrix<f64>, cost: f64, n_obs: usize) -> DMatrix<f64> {
    let (sv, v_t, smax) = decompose(jac);
    normal_inverse(sv.as_slice(), &v_t, smax) * residual_variance(cost, n_obs, jac.ncols())
}

/// The singular values of `jac`, its `V^T`, and the largest singular value
/// (at least the smallest positive float, so that ratios to it are finite).
/// A Jacobian with a non-finite entry determines nothing: its singular
/// values are taken as zero (rank 0, every parameter undetermined), where
/// the decomposition itself would not end (nalgebra's iteration never
/// converges on NaN; a PHM fit of a torque that was zero throughout hung
/// there).
fn decompose(jac: &DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>, f64) {
    let (sv, v_t) = match jac
        .iter()
        .all(|v| v.is_finite())
        .then(|| jac.clone().svd(false, true))
    {
        Some(svd) => (svd.singular_values, svd.v_t.expect("requested V^T")),
        None => (
            DVector::zeros(jac.ncols().min(jac.nrows())),
            DMatrix::identity(jac.ncols().min(jac.nrows()), jac.ncols()),
        ),
    };
    let smax = sv
        .iter()
        .cloned()
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    (sv, v_t, smax)
}

/// Analyses the Jacobian `jac` (rows: residuals, columns: the normalised
/// parameters `x` named `names`) at a fit with residual sum of squares
/// `cost` over `n_obs` observations. Relative errors are scale-free, so
/// normalised and physical values give the same ones.
pub fn analyse(
    jac: &DMatrix<f64>,
    names: &[&str],
    x: &[f64],
    cost: f64,
    n_obs: usize,
) -> Identifiability {
    let p = names.len();
    let (sv, v_t, smax) = decompose(jac);
    let smin = sv.iter().cloned().fold(f64::INFINITY, f64::min);
    let rank = sv.iter().filter(|&&s| s > 1e-6 * smax).count();
    let s2 = residual_variance(cost, n_obs, p);
    let cov = normal_inverse(sv.as_slice(), &v_t, smax);
    let var: Vec<f64> = (0..p).map(|i| cov[(i, i)] * s2).collect();
    let relative_std: Vec<(String, f64)> = names
        .iter()
        .zip(&var)
        .zip(x)
        .map(|((n, v), xi)| (n.to_string(), v.sqrt() / xi.abs().max(1e-12)))
        .collect();
    let mut correlated = vec![];
    for i in 0..p {
        for j in i + 1..p {
            let c = cov[(i, j)] / (cov[(i, i)] * cov[(j, j)]).sqrt();
            if c.is_finite() && c.abs() > 0.95 {
                correlated.push((names[i].to_string(), names[j].to_string(), c));
            }
        }
    }
    let mut weak = vec![];
    let mut undetermined: Vec<String> = vec![];
    for (k, &s) in sv.iter().enumerate() {
        if s < 1e-3 * smax {
            let mut comps: Vec<(String, f64)> = (0..p)
                .map(|i| (names[i].to_string(), v_t[(k, i)]))
                .collect();
            comps.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
            comps.retain(|(_, c)| c.abs() > 0.3);
            for (n, _) in &comps {
                if !undetermined.contains(n) {
                    undetermined.push(n.clone());
                }
            }
            weak.push(WeakDirection {
                relative_singular_value: s / smax,
                parameters: comps,
            });
        }
    }
    for (n, r) in &relative_std {
        if (r.is_nan() || *r > 0.5) && !undetermined.contains(n) {
            undetermined.push(n.clone());
        }
    }
    undetermined.sort_by_key(|n| names.iter().position(|m| m == n));
    Identifiability {
        parameters: p,
        rank,
        // A zero singular value (a parameter the output does not depend on)
        // makes the condition infinite (`null` in JSON).
        condition: if smin > 0.0 {
            smax / smin
        } else {
            f64::INFINITY
        },
        relative_std,
        correlated,
        weak,
        undetermined,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y = a t + b t with columns identical: a and b cannot be separated.
    #[test]
    fn a_jacobian_with_nan_determines_nothing() {
        let mut jac = DMatrix::from_fn(10, 2, |i, j| (i + j) as f64);
        jac[(3, 1)] = f64::NAN;
        let id = analyse(&jac, &["a", "b"], &[1.0, 2.0], 1.0, 10);
        assert_eq!((id.rank, id.condition), (0, f64::INFINITY));
        assert_eq!(id.undetermined, ["a", "b"]);
    }

    #[test]
    fn finds_a_confounded_pair() {
        let t: Vec<f64> = (0..20).map(|i| i as f64).collect();
        let jac = DMatrix::from_fn(20, 3, |i, j| match j {
            0 | 1 => t[i],
            _ => (t[i] * 0.3).sin(),
        });
        let id = analyse(&jac, &["a", "b", "c"], &[1.0, 1.0, 1.0], 1e-6, 20);
        assert_eq!(id.rank, 2);
        assert_eq!(id.undetermined, vec!["a", "b"]);
        assert_eq!(id.weak.len(), 1);
        let w = &id.weak[0].parameters;
        assert!(
            (w[0].1.abs() - 0.5f64.sqrt()).abs() < 1e-9 && w[0].1 * w[1].1 < 0.0,
            "{w:?}"
        );
        assert!(id.summary().contains("cannot determine a, b"));
    }

    /// A parameter the output does not depend on at all (alpha fixed at 1 leaves the
    /// hysteretic parameters without effect): the condition is infinite, and the summary says
    /// so in words, not as 3.9e307 (the largest singular value over the smallest positive
    /// float) and "0.0e0 times less visible".
    #[test]
    fn a_parameter_without_effect_is_reported_in_words() {
        let jac = DMatrix::from_fn(10, 2, |i, j| if j == 0 { i as f64 } else { 0.0 });
        let id = analyse(&jac, &["k0", "beta"], &[1.0, 1.0], 1e-6, 10);
        assert_eq!(id.condition, f64::INFINITY);
        let s = id.summary();
        assert!(s.contains("condition number infinite"), "{s}");
        assert!(
            s.contains("[+1.00 beta] does not change the output at all"),
            "{s}"
        );
    }

    #[test]
    fn well_posed_problems_are_reported_as_determined() {
        let jac = DMatrix::from_fn(30, 2, |i, j| if j == 0 { 1.0 } else { i as f64 / 30.0 });
        let id = analyse(&jac, &["offset", "slope"], &[2.0, 3.0], 1e-8, 30);
        assert_eq!(id.rank, 2);
        assert!(id.undetermined.is_empty(), "{:?}", id.undetermined);
        assert!(id.summary().contains("Every parameter is determined"));
        let r = id.relative_std.iter().map(|x| x.1).fold(0.0, f64::max);
        assert!(r < 1e-3);
    }
}
