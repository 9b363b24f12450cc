//! Homotopy optimisation (thesis ch. 4, after Vyasarayani et al. 2011).
//!
//! The model's state equations get the observer coupling of eq. 4.6,
//! `x' = f(x, p, t) + lambda K e(t)`, `e = x_measured - x`. At lambda = 1 a
//! large gain K makes the simulation track the measurement whatever p is, and
//! the objective `J(p, lambda) = 1/2 ∫ (x1e - x1)^2 dt` (eq. 4.5) is nearly
//! convex. Lambda is stepped down to 0; at each value a bounded local
//! optimiser ([`lsq::minimize`]) minimises J starting
//! from the previous minimiser. At lambda = 0 the coupling is gone and J is
//! the plain output error, whose nearest local minimum from a remote start is
//! often not the global one (the thesis' pendulum: from p = 15 a plain local
//! search stops at 14.74, homotopy reaches 10).

use super::lsq::{self, Options, Residuals};

/// One point of the homotopy path.
#[derive(Clone, Debug, PartialEq)]
pub struct Stage {
    /// The homotopy parameter.
    pub lambda: f64,
    /// The minimiser at this lambda.
    pub x: Vec<f64>,
    /// `||r||^2` there.
    pub cost: f64,
    /// Simulations this stage took.
    pub evaluations: usize,
}

/// The result of a homotopy run.
#[derive(Clone, Debug)]
pub struct Path {
    /// Stages from lambda = 1 down to 0.
    pub stages: Vec<Stage>,
    /// The final (lambda = 0) least-squares solution.
    pub solution: lsq::Solution,
}

impl Path {
    /// Total simulations.
    pub fn evaluations(&self) -> usize {
        self.stages.iter().map(|s| s.evaluations).sum()
    }
}

/// `steps + 1` values of lambda from 1 down to 0, equally spaced.
pub fn linear_schedule(steps: usize) -> Vec<f64> {
    (0..=steps)
        .map(|i| 1.0 - i as f64 / steps.max(1) as f64)
        .collect()
}

/// Runs the homotopy: `stage(lambda)` is the residual function of the
/// coupled model at `lambda` (its residuals are `None` where it cannot be
/// simulated; a [`LeastSquares::coupled`](super::problem::LeastSquares::coupled)
/// also gives exact Jacobians). `on_stage` is called after each stage (for
/// progress display). Returns `None` if a stage cannot start.
pub fn run<G, R>(
    stage: &G,
    x0: &[f64],
    lo: &[f64],
    hi: &[f64],
    schedule: &[f64],
    opts: Options,
    mut on_stage: impl FnMut(&Stage),
) -> Option<Path>
where
    G: Fn(f64) -> R,
    R: Residuals,
{
    let mut x = x0.to_vec();
    let mut stages = Vec::with_capacity(schedule.len());
    let mut last = None;
    for &lambda in schedule {
        let sol = lsq::minimize(&stage(lambda), &x, lo, hi, opts)?;
        x.clone_from(&sol.x);
        let stage = Stage {
            lambda,
            x: sol.x.clone(),
            cost: sol.cost,
            evaluations: sol.evaluations,
        };
        on_stage(&stage);
        stages.push(stage);
        last = Some(sol);
    }
    Some(Path {
        stages,
        solution: last?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thesis' pendulum (section 4.3.2): x1' = x2 + lambda K1 (x1e - x1),
    /// x2' = -p sin(x1) + lambda K2 (x1e - x1), x1(0) = pi/6, x2(0) = 0,
    /// t in [0, 40], true p = 10, K1 = K2 = 10. RK4 at dt = 0.01 with the
    /// measured x1e linear between samples.
    const DT: f64 = 0.01;
    const STEPS: usize = 4001;

    /// x1(t) at the samples, coupled to `measured` (empty: uncoupled).
    fn simulate(p: f64, lambda: f64, measured: &[f64]) -> Vec<f64> {
        let k = 10.0 * lambda;
        let mut x = [std::f64::consts::FRAC_PI_6, 0.0];
        let mut out = vec![x[0]];
        for i in 1..STEPS {
            let rhs = |x: [f64; 2], frac: f64| {
                let e = match measured {
                    [] => 0.0,
                    m => m[i - 1] + (m[i] - m[i - 1]) * frac - x[0],
                };
                [x[1] + k * e, -p * x[0].sin() + k * e]
            };
            let a = rhs(x, 0.0);
            let b = rhs([x[0] + 0.5 * DT * a[0], x[1] + 0.5 * DT * a[1]], 0.5);
            let c = rhs([x[0] + 0.5 * DT * b[0], x[1] + 0.5 * DT * b[1]], 0.5);
            let d = rhs([x[0] + DT * c[0], x[1] + DT * c[1]], 1.0);
            for j in 0..2 {
                x[j] += DT / 6.0 * (a[j] + 2.0 * b[j] + 2.0 * c[j] + d[j]);
            }
            out.push(x[0]);
        }
        out
    }

    /// J = 1/2 ∫ e^2 dt as least squares: residuals sqrt(dt) e.
    fn residuals(measured: &[f64], p: f64, lambda: f64) -> Option<Vec<f64>> {
        let sim = simulate(p, lambda, measured);
        Some(
            sim.iter()
                .zip(measured)
                .map(|(a, b)| (a - b) * DT.sqrt())
                .collect(),
        )
    }

    #[test]
    fn plain_local_search_from_15_stops_near_14_74() {
        let measured = simulate(10.0, 0.0, &[]);
        let f = |x: &[f64]| residuals(&measured, x[0], 0.0);
        let s = lsq::minimize(&f, &[15.0], &[0.0], &[30.0], Options::default()).unwrap();
        assert!((s.x[0] - 14.74).abs() < 0.02, "stopped at {}", s.x[0]);
        assert!(
            s.cost > 1e-2,
            "a local, not the global, minimum: cost {}",
            s.cost
        );
    }

    #[test]
    fn homotopy_from_15_reaches_10() {
        let measured = simulate(10.0, 0.0, &[]);
        let measured = &measured;
        let stage = |lambda: f64| move |x: &[f64]| residuals(measured, x[0], lambda);
        let path = run(
            &stage,
            &[15.0],
            &[0.0],
            &[30.0],
            &linear_schedule(10),
            Options::default(),
            |_| {},
        )
        .unwrap();
        let p = path.solution.x[0];
        assert!((p - 10.0).abs() < 1e-3, "homotopy ended at {p}");
        assert_eq!(path.stages.first().unwrap().lambda, 1.0);
        assert_eq!(path.stages.last().unwrap().lambda, 0.0);
    }
}
