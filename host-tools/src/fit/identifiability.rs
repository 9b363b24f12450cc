//! Can the record determine the parameters? The Jacobian of the residuals at
//! the fit tells: its singular values (rank and condition), the parameter
//! covariance `s^2 (J^T J)^-1` with its correlations, and the directions in
//! parameter space along which the output hardly changes.
//!
//! One rule decides what is undetermined: a parameter whose standard error
//! is more than half its value (or infinite: the output does not depend on
//! it). A direction is reported as weak when one standard error along it
//! moves one of its major parts (component above 0.3) by more than half its
//! value, so every parameter named in a weak direction is also undetermined.
//! How much less visible a direction is than the best one (its singular value
//! ratio) does not decide this by itself: with noise-free data a direction
//! 1e-4 times less visible can still be pinned to 1e-13, and the fit's own
//! standard errors say so.
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
    /// The parameters with a component above 0.3 that one standard error
    /// along the direction moves by more than half their value, largest
    /// weight first: name, component
    /// (the combination that can change without changing the output beyond
    /// the noise) and that move relative to the value (infinite where the
    /// output does not depend on the direction at all).
    pub parameters: Vec<(String, f64, f64)>,
}

/// The identifiability summary of a fit.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Identifiability {
    /// Number of free parameters.
    pub parameters: usize,
    /// Numerical rank of the Jacobian (singular values above 1e-6 of the
    /// largest: the directions it resolves).
    pub rank: usize,
    /// Largest over smallest singular value.
    pub condition: f64,
    /// Relative standard error of each parameter (std / |value|), from the
    /// residual variance; infinite for a parameter in a direction the
    /// Jacobian does not resolve (it is rank deficient there).
    pub relative_std: Vec<(String, f64)>,
    /// Pairs with |correlation| above 0.95.
    pub correlated: Vec<(String, String, f64)>,
    /// Directions along which one standard error moves a parameter with a
    /// component above 0.3 by more than half its value, least visible first.
    pub weak: Vec<WeakDirection>,
    /// Parameters the data cannot determine: relative std above 50% or not
    /// finite.
    pub undetermined: Vec<String>,
    /// Standard error of each value, in its units (infinite where the
    /// Jacobian does not resolve it).
    pub std: Vec<(String, f64)>,
    /// Values at exactly zero (the end of a range, or an effect switched
    /// off): their relative error is undefined, so they are undetermined by
    /// the rule, and [`std`](Self::std) says how far from zero the data
    /// allow them.
    pub at_zero: Vec<String>,
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
            // Undetermined through no weak combination of their own (a value
            // scaled by an uncertain exponent, or spread over several
            // directions): their standard errors say how much.
            let unexplained: Vec<String> = self
                .relative_std
                .iter()
                .zip(&self.std)
                .filter(|((n, r), _)| {
                    self.undetermined.contains(n)
                        && r.is_finite()
                        && !self
                            .weak
                            .iter()
                            .any(|w| w.parameters.iter().any(|p| &p.0 == n))
                })
                .map(|((n, r), (_, sd))| match self.at_zero.contains(n) {
                    true => format!("{n} = 0 +- {sd:.2e}"),
                    false => format!("{n} {:.0} %", 100.0 * r),
                })
                .collect();
            if !unexplained.is_empty() {
                s.push_str(&format!(
                    " Standard errors against the values: {}.",
                    unexplained.join(", ")
                ));
            }
            let mut null = vec![];
            for w in &self.weak {
                let names: Vec<_> = w
                    .parameters
                    .iter()
                    .map(|(n, c, _)| format!("{c:+.2} {n}"))
                    .collect();
                let combination = format!("[{}]", names.join(", "));
                if w.parameters.iter().all(|p| p.2.is_finite()) {
                    let moves: Vec<_> = w
                        .parameters
                        .iter()
                        .map(|(n, _, m)| format!("{n} by {:.0} %", 100.0 * m))
                        .collect();
                    s.push_str(&format!(
                        " The combination {combination} is {:.1e} times less visible in the output than the best-determined one: one standard error along it moves {}.",
                        w.relative_singular_value,
                        moves.join(", ")
                    ));
                } else {
                    null.push(combination);
                }
            }
            if !null.is_empty() {
                let (what, verb) = if null.len() == 1 {
                    ("The combination", "does")
                } else {
                    ("The combinations", "do")
                };
                s.push_str(&format!(
                    " {what} {} {verb} not change the output by even 1e-6 of what the best-determined one does.",
                    null.join(", ")
                ));
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

/// Whether singular value `s` is a direction the Jacobian resolves: above
/// 1e-6 of the largest, `smax`. The same cut gives the rank. A Jacobian
/// differenced with steps of 1e-6 of each range (the least-squares default)
/// is about that accurate, so a smaller singular value may be its error, and
/// a standard error computed from it would be invented: a PHM fit to
/// noise-free data gave ±5e-7 to a breakpoint the record never reached,
/// from a singular value of 7e-11 smax.
fn seen(s: f64, smax: f64) -> bool {
    s > 1e-6 * smax
}

/// Whether a parameter with component `c` in a direction that is not
/// [`seen`] takes part in it. The SVD separates such a vector from the seen
/// ones only to about (error of J) / (gap in singular values), so small
/// components can be rounding or differencing error, and would make a
/// determined parameter infinitely uncertain (the noise-free PHM fit above
/// had components near 4e-8 of parameters pinned to 1e-9).
fn in_null(c: f64) -> bool {
    c.abs() > 1e-3
}

/// `(J^T J)^+ = V diag(1/s^2) V^T` from the singular values and `V^T` of
/// `J`; a parameter in a null direction gets an infinite variance.
fn normal_inverse(sv: &[f64], v_t: &DMatrix<f64>, smax: f64) -> DMatrix<f64> {
    let p = v_t.ncols();
    let mut cov: DMatrix<f64> = DMatrix::zeros(p, p);
    for (k, &s) in sv.iter().enumerate() {
        if seen(s, smax) {
            let w = 1.0 / (s * s);
            for i in 0..p {
                for j in 0..p {
                    cov[(i, j)] += v_t[(k, i)] * v_t[(k, j)] * w;
                }
            }
        } else {
            // A null direction: the parameters in it have no finite variance.
            for i in 0..p {
                if in_null(v_t[(k, i)]) {
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

/// Analyses the Jacobian `jac` (rows: residuals, columns: the parameters `x`
/// named `names`, which are their own reported values) at a fit with
/// residual sum of squares `cost` over `n_obs` observations.
pub fn analyse(
    jac: &DMatrix<f64>,
    names: &[&str],
    x: &[f64],
    cost: f64,
    n_obs: usize,
) -> Identifiability {
    let identity = DMatrix::identity(x.len(), x.len());
    analyse_physical(jac, names, x, &identity, cost, n_obs)
}

/// As [`analyse`], for a fit in normalised variables whose reported values
/// are `values`, with `to_physical` the Jacobian of the map (row `i`: how
/// value `i` moves with each variable). Rank, condition, correlations and
/// the directions are those of the normalised problem, which is scaled for
/// them; the standard errors and moves are of the values reported. They
/// differ where a value's scale depends on another variable: beta and gamma
/// are fitted as multiples of `D^-n`, so an uncertain `n` makes them
/// uncertain (a `bw` fit of Lehman 430 had `beta` to 9 % normalised and to
/// 89 % as printed, found by review).
pub fn analyse_physical(
    jac: &DMatrix<f64>,
    names: &[&str],
    values: &[f64],
    to_physical: &DMatrix<f64>,
    cost: f64,
    n_obs: usize,
) -> Identifiability {
    let p = names.len();
    let (sv, v_t, smax) = decompose(jac);
    let smin = sv.iter().cloned().fold(f64::INFINITY, f64::min);
    let rank = sv.iter().filter(|&&s| seen(s, smax)).count();
    let s2 = residual_variance(cost, n_obs, p);
    let cov = normal_inverse(sv.as_slice(), &v_t, smax);
    // How far value i moves along direction k per unit of it (row i, column
    // k), and whether it takes part in an unresolved direction (its move
    // against its own variable's, by the rule of `in_null`).
    let along = to_physical * v_t.transpose();
    let part_of_null = |k: usize, i: usize| in_null(along[(i, k)] / to_physical[(i, i)]);
    let mut var = vec![0.0f64; p];
    for (k, &s) in sv.iter().enumerate() {
        for (i, v) in var.iter_mut().enumerate() {
            if seen(s, smax) {
                *v += (along[(i, k)] / s).powi(2);
            } else if part_of_null(k, i) {
                *v = f64::INFINITY;
            }
        }
    }
    let relative = |r: f64, value: f64| r / value.abs().max(1e-12);
    let std: Vec<(String, f64)> = names
        .iter()
        .zip(&var)
        .map(|(n, v)| (n.to_string(), (v * s2).sqrt()))
        .collect();
    let at_zero: Vec<String> = names
        .iter()
        .zip(values)
        .filter(|(_, v)| **v == 0.0)
        .map(|(n, _)| n.to_string())
        .collect();
    let relative_std: Vec<(String, f64)> = names
        .iter()
        .zip(&var)
        .zip(values)
        .map(|((n, v), value)| (n.to_string(), relative((v * s2).sqrt(), *value)))
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
    for (k, &s) in sv.iter().enumerate().rev() {
        // One standard error along direction k, sigma / s in normalised
        // units, moves value i by `along` times that.
        // A value at zero moves by an undefined fraction of itself: its
        // standard error speaks for it (a direction 0.46 as visible as the
        // best was listed for moving zeros by 2e10 %).
        let mut loose: Vec<(String, f64, f64)> = (0..p)
            .filter(|&i| values[i] != 0.0)
            .map(|i| {
                let c = v_t[(k, i)];
                let m = if seen(s, smax) {
                    relative(along[(i, k)].abs() * s2.sqrt() / s, values[i])
                } else if part_of_null(k, i) {
                    f64::INFINITY
                } else {
                    0.0
                };
                (names[i].to_string(), c, m)
            })
            // The combination: its major parts. A small component moving a
            // parameter near zero by a large fraction belongs to some other
            // direction's story (that parameter's own standard error).
            .filter(|(_, c, m)| *m > 0.5 && c.abs() > 0.3)
            .collect();
        loose.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        if !loose.is_empty() {
            weak.push(WeakDirection {
                relative_singular_value: s / smax,
                parameters: loose,
            });
        }
    }
    let undetermined: Vec<String> = relative_std
        .iter()
        .filter(|(_, r)| r.is_nan() || *r > 0.5)
        .map(|(n, _)| n.clone())
        .collect();
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
        std,
        at_zero,
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

    /// y = a t + b (t + 1e-4 sin t): the two columns differ by 1e-4, so one
    /// direction is about 1e-5 times less visible than the other. With
    /// residuals of 1e-13 that direction is still pinned far below half of
    /// any value, and a and b are determined; with residuals of 1e-3 one
    /// standard error along it moves both by hundreds of per cent, and the
    /// report names the combination and the moves.
    #[test]
    fn a_weak_direction_is_undetermined_only_when_the_noise_says_so() {
        let jac = DMatrix::from_fn(40, 2, |i, j| {
            let t = i as f64 / 4.0;
            if j == 0 {
                t
            } else {
                t + 1e-4 * t.sin()
            }
        });
        let names = ["a", "b"];
        let exact = analyse(&jac, &names, &[1.0, 1.0], 40.0 * 1e-26, 40);
        assert!(exact.condition > 1e4, "{}", exact.condition);
        assert!(exact.undetermined.is_empty(), "{:?}", exact.undetermined);
        assert!(exact.weak.is_empty(), "{:?}", exact.weak);
        assert!(exact.relative_std.iter().all(|(_, r)| *r < 1e-6));
        assert!(exact.summary().contains("Every parameter is determined"));

        let noisy = analyse(&jac, &names, &[1.0, 1.0], 40.0 * 1e-6, 40);
        assert_eq!(noisy.undetermined, ["a", "b"]);
        assert_eq!(noisy.weak.len(), 1);
        let w = &noisy.weak[0];
        assert!(w.relative_singular_value < 1e-4, "{w:?}");
        // Each named parameter's move along the direction is at most its
        // whole standard error.
        for (name, _, moved) in &w.parameters {
            let (_, r) = noisy.relative_std.iter().find(|(n, _)| n == name).unwrap();
            assert!(
                *moved > 0.5 && *moved <= *r * (1.0 + 1e-12),
                "{name}: {moved} vs {r}"
            );
        }
        let s = noisy.summary();
        assert!(s.contains("cannot determine a, b"), "{s}");
        assert!(s.contains("one standard error along it moves"), "{s}");
    }

    /// b = x_b D^-n with n fitted: the standard errors of n and b as printed
    /// match those of the Jacobian in (n, b) itself, computed another way
    /// (J_p = J_x (dp/dx)^-1, then (J_p^T J_p)^-1), and b's is three times
    /// what x_b's relative error says alone.
    #[test]
    fn values_scaled_by_a_fitted_exponent_carry_its_uncertainty() {
        let jac = DMatrix::from_fn(30, 2, |i, j| {
            let t = i as f64 / 10.0;
            if j == 0 {
                t.sin()
            } else {
                t.cos() + 0.3 * t
            }
        });
        let (n, xb, d) = (1.3f64, 0.8, 20.0f64);
        let b = xb * d.powf(-n);
        let to = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, -d.ln() * b, d.powf(-n)]);
        let (cost, obs) = (1e-2, 30);
        let id = analyse_physical(&jac, &["n", "b"], &[n, b], &to, cost, obs);
        let jp = &jac * to.clone().try_inverse().unwrap();
        let cov = (jp.transpose() * &jp).try_inverse().unwrap() * (cost / 28.0);
        for (i, v) in [n, b].iter().enumerate() {
            let expect = cov[(i, i)].sqrt() / v.abs();
            let got = id.relative_std[i].1;
            assert!(
                (got - expect).abs() < 1e-9 * expect,
                "{i}: {got} vs {expect}"
            );
        }
        let normalised = analyse(&jac, &["n", "b"], &[n, xb], cost, obs);
        // 2.5 % against 0.84 % here.
        assert!(id.relative_std[1].1 > 2.0 * normalised.relative_std[1].1);
    }

    /// A value at exactly zero (an effect off, at the end of its range) is
    /// undetermined by the relative rule, but the summary gives its absolute
    /// standard error, not a fraction of zero, and no direction is listed for
    /// moving it (one 0.46 as visible as the best was, "moving" zeros by
    /// 2e10 %: found by review).
    #[test]
    fn a_value_at_zero_is_reported_with_its_absolute_error() {
        let jac = DMatrix::from_fn(20, 2, |i, j| if j == 0 { 1.0 } else { i as f64 / 20.0 });
        let id = analyse(&jac, &["offset", "rate"], &[2.0, 0.0], 20.0 * 1e-4, 20);
        assert_eq!(id.undetermined, ["rate"]);
        assert_eq!(id.at_zero, ["rate"]);
        assert!(id.weak.is_empty(), "{:?}", id.weak);
        let sd = id.std[1].1;
        assert!(sd > 0.0 && sd < 0.1, "{sd}");
        let s = id.summary();
        assert!(s.contains(&format!("rate = 0 +- {sd:.2e}")), "{s}");
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
            s.contains("The combination [+1.00 beta] does not change the output by even 1e-6"),
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
