//! Linear least squares on the columns of a design matrix, shared by the
//! rate-dependence check of the diagnosis and the corner fits of a noisy
//! displacement.

use nalgebra::{DMatrix, DVector};

/// Least squares of `r` on the columns of `x`, by singular values as in the
/// identifiability analysis: the residual sum of squares and the
/// coefficients, or `None` when the columns are dependent (a singular value
/// below 1e-6 of the largest, about a pivot below 1e-12 in the normal
/// equations) or an entry is not finite (on which the decomposition would
/// not end).
pub fn regress(x: &DMatrix<f64>, r: &DVector<f64>) -> Option<(f64, DVector<f64>)> {
    if !x.iter().chain(r.iter()).all(|v| v.is_finite()) {
        return None;
    }
    let svd = x.clone().svd(true, true);
    let tol = 1e-6 * svd.singular_values.max();
    if svd.rank(tol) < x.ncols() {
        return None;
    }
    let coef = svd.solve(r, tol).ok()?;
    Some(((r - x * &coef).norm_squared(), coef))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regression_recovers_exact_coefficients() {
        let x = DMatrix::from_row_iterator(
            50,
            3,
            (0..50).flat_map(|i| {
                let v = (i as f64 * 0.37).sin() * (1.0 + i as f64 / 10.0);
                [1.0, v.signum(), v]
            }),
        );
        let r = DVector::from_fn(50, |i, _| 0.5 - 2.0 * x[(i, 1)] + 3.0 * x[(i, 2)]);
        let (rss, c) = regress(&x, &r).unwrap();
        assert!(rss < 1e-20, "{rss}");
        for (got, want) in c.iter().zip([0.5, -2.0, 3.0]) {
            assert!((got - want).abs() < 1e-10, "{c:?}");
        }
        // Dependent columns are refused, not solved.
        let dep = DMatrix::from_fn(50, 2, |i, j| (j + 1) as f64 * x[(i, 2)]);
        assert!(regress(&dep, &r).is_none());
        // So is a NaN, on which the decomposition would not end.
        let mut nan = r.clone();
        nan[7] = f64::NAN;
        assert!(regress(&x, &nan).is_none());
    }
}
