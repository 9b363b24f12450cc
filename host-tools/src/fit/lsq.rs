//! Bounded least squares: Levenberg-Marquardt with an active set for the
//! bounds, and the Jacobian either exact (from a [`Residuals`] that computes
//! it, as a [`Problem`](super::problem::Problem) does in dual numbers) or by
//! forward differences (columns evaluated in parallel).
//!
//! Minimises `||r(x)||^2` for `lo <= x <= hi`. Each iteration solves
//! `(J^T J + mu diag(J^T J)) dx = -J^T r` over the variables not pinned at a
//! bound by the gradient, projects `x + dx` onto the box, and accepts the step
//! if the cost falls (then `mu` shrinks) or rejects it (then `mu` grows).
//! A residual function that returns `None` (the model could not be
//! simulated) counts as an infinite cost.

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// Options of [`minimize`].
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Most outer iterations.
    pub max_iter: usize,
    /// Stop when a step changes no variable by more than this fraction of
    /// its bound range. The default, 1e-8, is MINPACK's and SciPy's
    /// convention (`xtol`); on the thesis' BW example 1e-10 took 1.4x the
    /// simulations for the same parameters to two digits of their error.
    pub x_tol: f64,
    /// Stop when an accepted step lowers the cost by less than this fraction.
    pub f_tol: f64,
    /// Relative finite-difference step (of the bound range).
    pub fd_step: f64,
    /// While the Jacobian is exact and trials are accepted, evaluate each
    /// trial with its Jacobian from one simulation (see [`minimize`]). Off,
    /// trials are plain and an accepted one is simulated again for its
    /// Jacobian: the same path at more simulations (kept for comparison).
    pub jacobian_with_trial: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_iter: 200,
            x_tol: 1e-8,
            f_tol: 1e-12,
            fd_step: 1e-6,
            jacobian_with_trial: true,
        }
    }
}

/// The result of a least-squares fit.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The minimiser.
    pub x: Vec<f64>,
    /// Residuals there.
    pub residuals: Vec<f64>,
    /// `||r||^2`.
    pub cost: f64,
    /// Jacobian at `x` (rows: residuals, columns: variables).
    pub jacobian: DMatrix<f64>,
    /// Outer iterations.
    pub iterations: usize,
    /// Residual evaluations (model simulations).
    pub evaluations: usize,
}

/// A residual function `r(x)` for [`minimize`]. Every closure
/// `Fn(&[f64]) -> Option<Vec<f64>>` is one (with differenced Jacobians).
pub trait Residuals: Sync {
    /// `r(x)`; `None` where it cannot be evaluated.
    fn residuals(&self, x: &[f64]) -> Option<Vec<f64>>;

    /// `r(x)` and its exact Jacobian from one evaluation, where this function
    /// can compute them. `None` (the default) makes the solver use forward
    /// differences at `x`; it is asked again at every accepted point, so a
    /// refusal should be cheap (decided before evaluating).
    fn residuals_jacobian(&self, _x: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>)> {
        None
    }
}

impl<F: Fn(&[f64]) -> Option<Vec<f64>> + Sync> Residuals for F {
    fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        self(x)
    }
}

/// The cost `||r||^2` of residuals `r`.
pub fn cost(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// Forward-difference Jacobian (backward where the forward step would leave
/// the box or cannot be evaluated). Columns are evaluated in parallel. A
/// variable whose neighbours on both sides cannot be evaluated (it sits at
/// the edge of the valid region) gets a zero column: the solver then leaves
/// it, and the identifiability analysis reports it.
pub fn jacobian<F>(
    f: &F,
    x: &[f64],
    r0: &[f64],
    lo: &[f64],
    hi: &[f64],
    rel: f64,
) -> Option<DMatrix<f64>>
where
    F: Residuals + ?Sized,
{
    let cols: Vec<Vec<f64>> = (0..x.len())
        .into_par_iter()
        .map(|j| {
            let range = (hi[j] - lo[j]).abs().max(1e-12);
            let step = rel * range.max(x[j].abs());
            let order = if x[j] + step > hi[j] {
                [-step, step]
            } else {
                [step, -step]
            };
            for h in order {
                let mut xp = x.to_vec();
                xp[j] += h;
                if let Some(rp) = f.residuals(&xp) {
                    return rp.iter().zip(r0).map(|(a, b)| (a - b) / h).collect();
                }
            }
            vec![0.0; r0.len()]
        })
        .collect();
    let mut jac = DMatrix::zeros(r0.len(), x.len());
    for (j, col) in cols.into_iter().enumerate() {
        jac.set_column(j, &DVector::from_vec(col));
    }
    Some(jac)
}

/// `r(x)` and its Jacobian: exact where `f` computes it, else by forward
/// differences ([`jacobian`]); with the number of evaluations it took.
pub fn evaluate<F>(
    f: &F,
    x: &[f64],
    lo: &[f64],
    hi: &[f64],
    rel: f64,
) -> Option<(Vec<f64>, DMatrix<f64>, usize)>
where
    F: Residuals + ?Sized,
{
    if let Some((r, jac)) = f.residuals_jacobian(x) {
        return Some((r, jac, 1));
    }
    let r = f.residuals(x)?;
    let jac = jacobian(f, x, &r, lo, hi, rel)?;
    Some((r, jac, 1 + x.len()))
}

/// The [`Solution`] at `x` without iterating: `r(x)`, its cost and its
/// Jacobian ([`evaluate`]), with the evaluations they took.
pub fn solution_at<F>(f: &F, x: &[f64], lo: &[f64], hi: &[f64], rel: f64) -> Option<Solution>
where
    F: Residuals + ?Sized,
{
    let (residuals, jacobian, evaluations) = evaluate(f, x, lo, hi, rel)?;
    Some(Solution {
        x: x.to_vec(),
        cost: cost(&residuals),
        residuals,
        jacobian,
        iterations: 0,
        evaluations,
    })
}

/// Whether a trial step that took the cost from `c` to `cn` is accepted: the
/// cost fell, and by at least 1e-4 of the decrease the linear model
/// predicted, which must be positive (MINPACK's rule). A step the linear
/// model does not call a descent is not taken on luck: on the thesis' BW
/// example such a step (clamped to the bounds, predicted -0.019, actual
/// +0.031 of a cost of 0.27) led one fit of twenty to a degenerate corner
/// (beta = 0, n at its bound) it never left.
fn gain_accepted(c: f64, cn: f64, predicted: f64) -> bool {
    cn < c && predicted > 0.0 && c - cn >= 1e-4 * predicted
}

/// The decrease of the cost the linear model predicts for `step`:
/// `||r||^2 - ||r + J step||^2`, written as `-(2 r.Js + ||Js||^2)` so that it
/// keeps its digits when it is small against the cost (as a difference of the
/// two costs it cancels: at a cost of 1e18 a predicted decrease of 20 came
/// out as 0 or 128).
fn predicted_decrease(r: &[f64], jac: &DMatrix<f64>, step: &DVector<f64>) -> f64 {
    let js = jac * step;
    let cross: f64 = r.iter().zip(js.iter()).map(|(a, b)| a * b).sum();
    -(2.0 * cross + js.norm_squared())
}

/// Minimises `||f(x)||^2` over the box from `x0`. Returns `None` if `f(x0)`
/// cannot be evaluated.
///
/// At an accepted point the Jacobian is computed exactly where `f` can at
/// that point (counted as one evaluation in [`Solution::evaluations`]) and
/// differenced otherwise (one evaluation per variable). A fit can so start
/// differenced (where the exact path refuses) and go exact when it leaves
/// that point. While the Jacobian is exact and the last trial was accepted,
/// the next trial is evaluated with its Jacobian in one go (one evaluation;
/// if `f` refuses there, a second, plain one); after a rejection trials are
/// evaluated alone until one is accepted. The path is the same either way
/// wherever `f`'s two evaluations return the same residuals. A trial the
/// linear model predicts to raise the cost (a step clamped to the box can)
/// is rejected without being evaluated.
pub fn minimize<F>(f: &F, x0: &[f64], lo: &[f64], hi: &[f64], opts: Options) -> Option<Solution>
where
    F: Residuals + ?Sized,
{
    minimize_observed(f, x0, lo, hi, opts, |_, _| {})
}

/// [`minimize`], calling `on_iter(iteration, cost)` after every accepted
/// step (for progress display).
pub fn minimize_observed<F>(
    f: &F,
    x0: &[f64],
    lo: &[f64],
    hi: &[f64],
    opts: Options,
    mut on_iter: impl FnMut(usize, f64),
) -> Option<Solution>
where
    F: Residuals + ?Sized,
{
    let n = x0.len();
    let mut x: Vec<f64> = x0
        .iter()
        .zip(lo.iter().zip(hi))
        .map(|(v, (l, h))| v.clamp(*l, *h))
        .collect();
    let (mut r, mut jac, mut evals) = evaluate(f, &x, lo, hi, opts.fd_step)?;
    // Whether the next trial is evaluated with its exact Jacobian at once:
    // while steps are accepted (most are, away from the noise floor) the
    // Jacobian is needed at the trial point anyway, and computing both from
    // one simulation in dual numbers spares the plain one. After a rejection
    // the trials are plain until one is accepted. (`evaluate` counts one
    // evaluation exactly when its Jacobian is exact.)
    let mut speculate = opts.jacobian_with_trial && evals == 1;
    let mut c = cost(&r);
    let mut mu = 1e-3;
    let mut iterations = 0;
    'outer: while iterations < opts.max_iter {
        iterations += 1;
        let jt = jac.transpose();
        let a = &jt * &jac;
        let g = &jt * DVector::from_column_slice(&r);
        // Variables at a bound whose gradient pushes outwards stay there.
        let active: Vec<usize> = (0..n)
            .filter(|&j| {
                let at_lo = x[j] <= lo[j] && g[j] > 0.0;
                let at_hi = x[j] >= hi[j] && g[j] < 0.0;
                !(at_lo || at_hi)
            })
            .collect();
        if active.is_empty() {
            break;
        }
        let m = active.len();
        let mut accepted = false;
        for _ in 0..30 {
            let mut lhs = DMatrix::zeros(m, m);
            let mut rhs = DVector::zeros(m);
            for (p, &i) in active.iter().enumerate() {
                rhs[p] = -g[i];
                for (q, &k) in active.iter().enumerate() {
                    lhs[(p, q)] = a[(i, k)];
                }
                lhs[(p, p)] += mu * a[(i, i)].max(1e-12);
            }
            let Some(chol) = lhs.clone().cholesky() else {
                mu *= 10.0;
                continue;
            };
            let dx = chol.solve(&rhs);
            let mut xn = x.clone();
            let mut moved = 0.0f64;
            for (p, &i) in active.iter().enumerate() {
                xn[i] = (x[i] + dx[p]).clamp(lo[i], hi[i]);
                moved = moved.max((xn[i] - x[i]).abs() / (hi[i] - lo[i]).abs().max(1e-12));
            }
            if moved < opts.x_tol {
                break 'outer;
            }
            // The decrease the linear model predicts for the step as taken
            // (clamped to the box, which can make it predict an increase).
            let step = DVector::from_iterator(n, xn.iter().zip(&x).map(|(a, b)| a - b));
            let predicted = predicted_decrease(&r, &jac, &step);
            if predicted <= 0.0 {
                // `gain_accepted` would reject it whatever its cost: a
                // shorter step is tried without simulating this one.
                mu *= 4.0;
                continue;
            }
            evals += 1;
            // The trial's residuals and, if it was asked for and given, its
            // exact Jacobian (`Some(None)`: asked for and refused).
            let (trial, trial_jac) = match speculate.then(|| f.residuals_jacobian(&xn)) {
                Some(Some((rn, j))) => (Some(rn), Some(Some(j))),
                Some(None) => {
                    evals += 1;
                    (f.residuals(&xn), Some(None))
                }
                None => (f.residuals(&xn), None),
            };
            match trial.map(|rn| (cost(&rn), rn)) {
                Some((cn, rn)) if gain_accepted(c, cn, predicted) => {
                    let small = c - cn < opts.f_tol * c;
                    // Exact where it can be had at this point, else
                    // differenced.
                    let exact = trial_jac.unwrap_or_else(|| {
                        f.residuals_jacobian(&xn).map(|(_, j)| {
                            evals += 1;
                            j
                        })
                    });
                    (jac, speculate) = match exact {
                        Some(j) => (j, opts.jacobian_with_trial),
                        None => {
                            evals += n;
                            (jacobian(f, &xn, &rn, lo, hi, opts.fd_step)?, false)
                        }
                    };
                    x = xn;
                    r = rn;
                    c = cn;
                    mu = (mu / 3.0).max(1e-15);
                    accepted = true;
                    on_iter(iterations, c);
                    if small {
                        break 'outer;
                    }
                    break;
                }
                _ => {
                    mu *= 4.0;
                    speculate = false;
                }
            }
        }
        if !accepted {
            break;
        }
    }
    Some(Solution {
        x,
        residuals: r,
        cost: c,
        jacobian: jac,
        iterations,
        evaluations: evals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The predicted decrease keeps its digits where the cost is large: for
    /// r = 1e9, J = 1 and a step of -1e-8 it is 2 r 1e-8 - 1e-16 = 20 to the
    /// last place, where `||r||^2 - ||r + J s||^2` gives 0 (the costs are
    /// 1e18, whose floating-point spacing is 128).
    #[test]
    fn predicted_decrease_does_not_cancel() {
        let jac = DMatrix::from_element(1, 1, 1.0);
        let step = DVector::from_element(1, -1e-8);
        let predicted = predicted_decrease(&[1e9], &jac, &step);
        assert!((predicted - 20.0).abs() < 1e-12, "{predicted}");
        let r = DVector::from_element(1, 1e9);
        let cancelled = r.norm_squared() - (&r + &jac * &step).norm_squared();
        assert!((cancelled - 20.0).abs() > 1.0, "{cancelled}");
    }

    /// Rosenbrock as least squares: r = (10 (y - x^2), 1 - x); minimum (1, 1).
    #[test]
    fn finds_the_rosenbrock_minimum() {
        let f = |x: &[f64]| Some(vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]]);
        let s = minimize(
            &f,
            &[-1.2, 1.0],
            &[-5.0, -5.0],
            &[5.0, 5.0],
            Options::default(),
        )
        .unwrap();
        assert!(
            (s.x[0] - 1.0).abs() < 1e-6 && (s.x[1] - 1.0).abs() < 1e-6,
            "{:?}",
            s.x
        );
    }

    /// With the unconstrained minimum (1, 1) outside the box, the solution
    /// is the constrained minimum on the bound.
    #[test]
    fn respects_bounds() {
        let f = |x: &[f64]| Some(vec![x[0] - 1.0, x[1] - 1.0]);
        let s = minimize(
            &f,
            &[0.0, 0.0],
            &[-1.0, -1.0],
            &[0.5, 2.0],
            Options::default(),
        )
        .unwrap();
        assert!((s.x[0] - 0.5).abs() < 1e-12, "{:?}", s.x);
        assert!((s.x[1] - 1.0).abs() < 1e-8, "{:?}", s.x);
    }

    /// On a linear problem the linear model is exact, so a trial raises the
    /// cost exactly when the model predicts it would. A step clamped to the
    /// box can predict a rise (here the first: the unconstrained minimum is
    /// at (-56.6, -35) and its step clamped to (-1, -1) raises the cost from
    /// 1.05 to 1.42); such a trial is not simulated. So every point evaluated
    /// after the start lowers the cost, and the end satisfies the bound
    /// constraints' optimality conditions.
    #[test]
    fn a_trial_predicted_to_raise_the_cost_is_not_simulated() {
        use std::sync::Mutex;
        let jac = DMatrix::from_row_slice(2, 2, &[0.51, -0.8, 0.51, -0.84]);
        let b = [-0.89, 0.51];
        let values = |x: &[f64]| {
            let r = &jac * DVector::from_column_slice(x);
            vec![r[0] - b[0], r[1] - b[1]]
        };
        struct Linear<'a, V> {
            values: V,
            jac: &'a DMatrix<f64>,
            seen: Mutex<Vec<Vec<f64>>>,
        }
        impl<V: Fn(&[f64]) -> Vec<f64> + Sync> Residuals for Linear<'_, V> {
            fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
                self.seen.lock().unwrap().push(x.to_vec());
                Some((self.values)(x))
            }
            fn residuals_jacobian(&self, x: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>)> {
                self.seen.lock().unwrap().push(x.to_vec());
                Some(((self.values)(x), self.jac.clone()))
            }
        }
        let f = Linear {
            values,
            jac: &jac,
            seen: Mutex::new(Vec::new()),
        };
        let (lo, hi) = ([-1.0, -1.0], [1.0, 1.0]);
        let s = minimize(&f, &[0.0, 0.0], &lo, &hi, Options::default()).unwrap();
        let seen = f.seen.into_inner().unwrap();
        let costs: Vec<f64> = seen.iter().map(|x| cost(&values(x))).collect();
        assert!(
            costs.windows(2).all(|c| c[1] <= c[0]),
            "a trial that raised the cost was simulated: {costs:?} at {seen:?}"
        );
        let g = jac.transpose() * DVector::from_column_slice(&s.residuals);
        for j in 0..2 {
            let optimal = if s.x[j] <= lo[j] {
                g[j] >= 0.0
            } else if s.x[j] >= hi[j] {
                g[j] <= 0.0
            } else {
                g[j].abs() < 1e-9
            };
            assert!(optimal, "x {:?}, gradient {g:?}", s.x);
        }
    }

    /// An exponential-decay fit (nonlinear in the rate) from a poor start,
    /// with differenced Jacobians (the exact one is refused everywhere, as a
    /// plain closure's is).
    #[test]
    fn fits_an_exponential() {
        let s = Decay::new(|_| true).fit(Options::default());
        assert!(s.cost < 1e-16);
    }

    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Where the [`Decay`] fits start.
    const START: [f64; 2] = [1.0, 0.2];

    /// `r_i = a exp(-b t_i) - y_i` with its exact Jacobian, counting both
    /// kinds of evaluation; the exact one is refused where `refuse` holds.
    struct Decay {
        t: Vec<f64>,
        y: Vec<f64>,
        refuse: fn(&[f64]) -> bool,
        plain: AtomicUsize,
        exact: AtomicUsize,
    }

    impl Residuals for Decay {
        fn residuals(&self, p: &[f64]) -> Option<Vec<f64>> {
            self.plain.fetch_add(1, Ordering::Relaxed);
            Some(self.values(p))
        }
        fn residuals_jacobian(&self, p: &[f64]) -> Option<(Vec<f64>, DMatrix<f64>)> {
            if (self.refuse)(p) {
                return None;
            }
            self.exact.fetch_add(1, Ordering::Relaxed);
            let jac = DMatrix::from_fn(self.t.len(), 2, |i, j| {
                let e = (-p[1] * self.t[i]).exp();
                [e, -p[0] * self.t[i] * e][j]
            });
            Some((self.values(p), jac))
        }
    }

    impl Decay {
        /// Data from a = 3, b = 1.3.
        fn new(refuse: fn(&[f64]) -> bool) -> Self {
            let t: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
            let y = t.iter().map(|t| 3.0 * (-1.3 * t).exp()).collect();
            Decay {
                t,
                y,
                refuse,
                plain: AtomicUsize::new(0),
                exact: AtomicUsize::new(0),
            }
        }
        /// The fit from a = 1, b = 0.2 in the box [0, 10]^2 with `opts`,
        /// after asserting that it reached the truth.
        fn fit(&self, opts: Options) -> Solution {
            let s = minimize(self, &START, &[0.0, 0.0], &[10.0, 10.0], opts).unwrap();
            assert!(
                (s.x[0] - 3.0).abs() < 1e-6 && (s.x[1] - 1.3).abs() < 1e-6,
                "{:?}",
                s.x
            );
            s
        }
        fn values(&self, p: &[f64]) -> Vec<f64> {
            let r = self.t.iter().zip(&self.y);
            r.map(|(t, y)| p[0] * (-p[1] * t).exp() - y).collect()
        }
        fn calls(&self) -> (usize, usize) {
            (
                self.plain.load(Ordering::Relaxed),
                self.exact.load(Ordering::Relaxed),
            )
        }
    }

    /// The exponential fit with an exact Jacobian that is refused at the
    /// starting point (as the dual path refuses pinching at zeta0 = 0): the
    /// solver differences there and goes exact once it has moved.
    #[test]
    fn goes_exact_after_a_start_where_the_exact_jacobian_is_refused() {
        let f = Decay::new(|p| p == START);
        let s = f.fit(Options::default());
        let (plain, exact) = f.calls();
        assert!(exact > 0, "never exact after the start");
        // The count is honest: every plain and every exact evaluation.
        assert_eq!(s.evaluations, plain + exact);
    }

    /// Where the exact Jacobian is refused over a band (0.5 <= b < 0.9,
    /// crossed on the way from b = 0.2 to 1.3), a trial asked for it there
    /// is evaluated plain and an accepted point is differenced: the fit
    /// still converges, and the refused request counts as an evaluation.
    #[test]
    fn a_trial_refused_its_jacobian_is_evaluated_plain() {
        let f = Decay::new(|p| (0.5..0.9).contains(&p[1]));
        let s = f.fit(Options::default());
        let (plain, exact) = f.calls();
        assert!(exact > 0 && plain > 0);
        // One trial asked for its Jacobian was refused (it is counted, and
        // neither counter saw it).
        assert_eq!(s.evaluations, plain + exact + 1);
    }

    /// Evaluating accepted trials with their Jacobian takes the same path
    /// (the same iterates, to the last bit, since both evaluations return the
    /// same residuals) at fewer evaluations: every accepted trial but those
    /// after a rejection spares its second one.
    #[test]
    fn trials_with_their_jacobian_take_the_same_path_in_fewer_evaluations() {
        let run = |jacobian_with_trial: bool| {
            let f = Decay::new(|_| false);
            let s = f.fit(Options {
                jacobian_with_trial,
                ..Options::default()
            });
            let (plain, exact) = f.calls();
            assert_eq!(s.evaluations, plain + exact, "the count is honest");
            (s, plain, exact)
        };
        let (together, plain_t, exact_t) = run(true);
        let (apart, plain_a, exact_a) = run(false);
        assert_eq!(together.x, apart.x);
        assert_eq!(together.iterations, apart.iterations);
        // Apart: one exact evaluation at the start and one per accepted
        // trial, every trial plain. Together: the accepted trials' exact
        // evaluations are the trials themselves (plus any trial rejected
        // after it was evaluated exactly).
        assert!(exact_t >= exact_a && plain_t < plain_a);
        assert!(
            together.evaluations < apart.evaluations,
            "{} against {}",
            together.evaluations,
            apart.evaluations
        );
    }
}
