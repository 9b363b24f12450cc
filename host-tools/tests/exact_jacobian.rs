//! The exact Jacobians of the least-squares fits (one simulation in dual
//! numbers, `Problem::residuals_jacobian`) against central differences of the
//! `f64` simulation, and their residuals against the `f64` residuals.
//!
//! Both are computed with a tight integration tolerance (1e-12), so that the
//! central differences (step 1e-5 of a normalised parameter) are limited by
//! their truncation error (about 1e-10), not by the integrator's.

use hyst::data::{read, ReadOptions};
use hyst::fit::experiment::{Between, Drive, Experiment};
use hyst::fit::lsq::{self, Residuals};
use hyst::fit::problem::{LeastSquares, Problem};
use hyst::model::ModelSpec;
use hysteresis::bwbn::{Control, Method};
use nalgebra::DMatrix;
use std::collections::BTreeMap;

#[path = "support/thesis_bw.rs"]
mod thesis_bw;

/// The problem's own method (`Series`, which is Dormand-Prince wherever an
/// effect is on or the drive is a force) at tolerance `tol`.
fn with_tol(mut p: Problem, tol: f64) -> Problem {
    p.control = Control {
        tol,
        max_substeps: 5000,
        ..p.control
    };
    p
}

/// Central differences of the (optionally observer-coupled) residuals.
fn central(f: &LeastSquares, x: &[f64], h: f64) -> DMatrix<f64> {
    let r0 = f.residuals(x).expect("simulates at x");
    let mut jac = DMatrix::zeros(r0.len(), x.len());
    for j in 0..x.len() {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[j] += h;
        xm[j] -= h;
        let (rp, rm) = (f.residuals(&xp).unwrap(), f.residuals(&xm).unwrap());
        for i in 0..r0.len() {
            jac[(i, j)] = (rp[i] - rm[i]) / (2.0 * h);
        }
    }
    jac
}

/// The largest difference, relative to the column's 2-norm, between the exact
/// Jacobian and central differences (step 1e-4 of the normalised parameters),
/// and the largest uncertainty of those differences (their change when the
/// step shrinks to 1e-5), after asserting that the residuals are the `f64`
/// ones, bit for bit.
fn worst_column(f: &LeastSquares, x: &[f64], names: &[&str]) -> (f64, f64) {
    let (r, exact) = f.residuals_jacobian(x).expect("an exact Jacobian");
    assert_eq!(
        r,
        f.residuals(x).unwrap(),
        "the dual simulation's values are the f64 simulation's"
    );
    let (fd, finer) = (central(f, x, 1e-4), central(f, x, 1e-5));
    let (mut worst, mut spread) = (0.0f64, 0.0f64);
    for (j, name) in names.iter().enumerate() {
        let d = fd.column(j);
        let rel = (exact.column(j) - d).norm() / d.norm();
        let unc = (finer.column(j) - d).norm() / d.norm();
        eprintln!(
            "{name}: |J| {:.3e}, exact - differenced {rel:.1e}, differences' uncertainty {unc:.1e}",
            d.norm()
        );
        worst = worst.max(rel);
        spread = spread.max(unc);
    }
    (worst, spread)
}

/// The exact and differenced Jacobians agree to 1e-4 at a tolerance of
/// 1e-13, and their difference shrinks with the tolerance unless it is
/// already within the differences' own uncertainty: it is the integrator's
/// error (the exact Jacobian is the derivative of the sub-steps the simulation
/// took, the differences see neighbouring simulations take others), not an
/// error of the derivatives.
fn assert_exact(p: &Problem, f: for<'a> fn(&'a Problem) -> LeastSquares<'a>, x: &[f64]) {
    let names = p.par.names();
    let at = |tol: f64| {
        let q = with_tol(p.clone(), tol);
        let (worst, spread) = worst_column(&f(&q), x, &names);
        eprintln!("tolerance {tol:e}: worst column {worst:.2e}, uncertainty {spread:.2e}");
        (worst, spread)
    };
    let ((loose, _), (tight, spread)) = (at(1e-10), at(1e-13));
    assert!(tight < 1e-4, "exact and differenced differ by {tight:e}");
    assert!(
        tight < 0.2 * loose || loose < 3.0 * spread || tight < 1.5 * spread,
        "the difference does not shrink with the tolerance: {loose:e} at 1e-10, {tight:e} at 1e-13 (differences uncertain by {spread:e})"
    );
}

/// The free model's residuals (a function, as `assert_exact` takes).
fn free(q: &Problem) -> LeastSquares<'_> {
    LeastSquares::new(q)
}

fn thesis_example() -> Problem {
    Problem::new(ModelSpec::BW, thesis_bw::record(), &[("k0".into(), 6.0)]).unwrap()
}

fn near_truth(p: &Problem, factor: f64) -> Vec<f64> {
    let values: BTreeMap<&str, f64> = thesis_bw::TRUTH
        .iter()
        .map(|(k, v)| (*k, v * factor))
        .collect();
    p.par.normalise(&values)
}

#[test]
fn force_driven_bouc_wen_jacobian_is_exact() {
    let p = thesis_example();
    assert_exact(&p, free, &near_truth(&p, 1.3));
}

/// The oscillator lands its sub-steps on v = 0 and z = 0; at n = 0.6 the
/// shift of `integrate::shift_along` keeps its Jacobian exact too (without
/// it: 1.7e-5 off at 1e-13, within 2.5e-7 with it).
#[test]
fn force_driven_bouc_wen_jacobian_is_exact_below_n_1() {
    let p = thesis_example();
    let values: BTreeMap<&str, f64> = thesis_bw::TRUTH
        .iter()
        .map(|(k, v)| (*k, if *k == "n" { 0.6 } else { v * 1.1 }))
        .collect();
    assert_exact(&p, free, &p.par.normalise(&values));
}

#[test]
fn observer_coupled_jacobian_is_exact() {
    fn coupled(q: &Problem) -> LeastSquares<'_> {
        LeastSquares::coupled(q, 0.5).expect("force drive has an observer")
    }
    let p = thesis_example();
    assert_exact(&p, coupled, &near_truth(&p, 0.7));
}

/// A displacement-driven problem on a cyclic history of growing amplitude
/// (three cycles to 4 displacement scales), at a point inside the bounds where
/// every effect of `spec` is active.
fn cyclic(spec: &str) -> (Problem, Vec<f64>) {
    cyclic_at(spec, 1.4)
}

/// [`cyclic`] with the exponent `n`.
fn cyclic_at(spec: &str, n: f64) -> (Problem, Vec<f64>) {
    let u: Vec<f64> = (0..=1200)
        .map(|i| {
            let t = i as f64 / 400.0;
            (1.0 + t) * (2.0 * std::f64::consts::PI * t).sin()
        })
        .collect();
    let force = u.iter().map(|v| 6.0 * v.tanh()).collect();
    let exp = Experiment {
        input: u,
        output: force,
        drive: Drive::Displacement,
    };
    let p = Problem::new(ModelSpec::parse(spec).unwrap(), exp, &[]).unwrap();
    let x: Vec<f64> = p
        .par
        .free
        .iter()
        .map(|f| match f.spec.name {
            "k0" => 1.0,
            "alpha" => 0.1,
            "n" => n,
            "beta" => 0.6,
            "gamma" => 0.2,
            _ => f.lo + 0.2 * (f.hi - f.lo),
        })
        .collect();
    p.params(&x).expect("a valid parameter set");
    (p, x)
}

/// Plain Bouc-Wen driven by displacement is summed as series (`Method::Series`):
/// the dual numbers run through its adaptive order and its Newton iterations
/// near z = 0, and the Jacobian is still the derivative of what it computes.
#[test]
fn displacement_driven_series_jacobian_is_exact() {
    let (p, x) = cyclic("bw");
    assert_eq!(p.control.method, Method::Series);
    assert_exact(&p, free, &x);
}

#[test]
fn displacement_driven_bwbn_jacobian_is_exact() {
    let (p, x) = cyclic("bwbn");
    assert_eq!(p.dim(), 17);
    assert_exact(&p, free, &x);
}

/// Below n = 1 the right-hand side's derivative in z, `n |z|^(n-1)`, is
/// unbounded at z = 0, next to which the element's sub-steps end when they
/// land on it: before such a sub-step the derivatives are moved along the
/// solution (`integrate::shift_along`), so the Jacobian stays exact. (Without
/// the shift this set was 4.1e-4 off at 1e-13.)
#[test]
fn displacement_driven_bwbn_jacobian_is_exact_below_n_1() {
    let (p, x) = cyclic_at("bwbn", 0.6);
    assert_exact(&p, free, &x);
}

#[test]
fn asymmetry_with_degradation_jacobian_is_exact() {
    let (p, x) = cyclic("bw+asymmetry+a-degradation+strength-degradation+stiffness-degradation");
    assert_exact(&p, free, &x);
}

/// With pinching, asymmetry makes dz/du jump where z changes sign (pinching's
/// h(0) depends on Zu, which differs on the two sides), and the derivative of
/// the solution then has a jump term at each crossing that differentiating the
/// right-hand side cannot see (measured: 1-5% off the differences). Such
/// models are differenced.
#[test]
fn asymmetry_with_pinching_is_differenced() {
    let (p, x) = cyclic("bwbn+asymmetry");
    assert!(p.residuals_jacobian(&x, None).is_none());
    let (p, x) = cyclic("bw+asymmetry+pinching");
    assert!(p.residuals_jacobian(&x, None).is_none());
    assert!(LeastSquares::new(&p).residuals(&x).is_some());
}

/// At `zeta0 = 0` pinching is inert and the core skips its work, which loses
/// the derivative with respect to `zeta0` (measured: a zero column where the
/// differences give 5.8e-2, so a fit that reached the bound stayed there).
/// Such points are differenced.
#[test]
fn pinching_at_zero_severity_is_differenced() {
    let (p, mut x) = cyclic("bw+pinching");
    let i = p.par.names().iter().position(|n| *n == "zeta0").unwrap();
    assert!(p.residuals_jacobian(&x, None).is_some());
    x[i] = 0.0;
    assert!(p.residuals_jacobian(&x, None).is_none());
    let f = LeastSquares::new(&p);
    let (lo, hi) = p.par.bounds();
    let (_, jac, used) = lsq::evaluate(&f, &x, &lo, &hi, 1e-6).unwrap();
    assert_eq!(used, 1 + x.len(), "differenced");
    assert!(
        jac.column(i).norm() > 0.0,
        "zeta0 still moves the prediction"
    );
}

/// Points spread over a problem's search box (a fixed lattice, so that the
/// test is the same every run).
fn spread(p: &Problem, count: usize) -> Vec<Vec<f64>> {
    let (lo, hi) = p.par.bounds();
    (0..count)
        .map(|k| {
            let cell = |j: usize| ((k * 7 + j * 3) % 11) as f64 + 0.5;
            let at = |(j, (l, h)): (usize, (&f64, &f64))| l + (h - l) * cell(j) / 11.0;
            lo.iter().zip(&hi).enumerate().map(at).collect()
        })
        .collect()
}

/// The dual-number simulation's values are the `f64` simulation's, bit for
/// bit, at points spread over the search box of a force-driven multisine
/// (the first 2,000 samples of Forgione's record of the Bouc-Wen benchmark,
/// force linear and cubic between samples) and of the cyclic
/// displacement-driven record, so that a least-squares fit takes the same
/// path whether a trial is simulated with its Jacobian or alone. (Until
/// 2026-11-29 a landing on a kink in the first sub-step of an increment took
/// the rate there afresh in dual numbers and from the end of the previous
/// increment in `f64`, which differ in the last place: 25 of 36 such points
/// differed, by up to 1.7e-9.)
#[test]
fn dual_values_are_the_plain_values() {
    let record = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/boucwen-benchmark/csv/train_multisine_forgione.csv"
    );
    let r = read(record, &ReadOptions::default()).expect("the benchmark record");
    let (force, u) = (r.force().unwrap(), r.displacement().unwrap());
    let mut problems = vec![cyclic_at("bwbn", 0.8).0];
    for between in [Between::Linear, Between::Cubic] {
        let exp = Experiment {
            input: force[..2000].to_vec(),
            output: u[..2000].to_vec(),
            // 2 kg in kN s^2 / mm (the reader gives kN and mm).
            drive: Drive::Force {
                dt: 1.0 / 750.0,
                mass: 2e-6,
                between,
            },
        };
        problems.push(Problem::new(ModelSpec::BW, exp, &[]).unwrap());
    }
    for p in &problems {
        let f = LeastSquares::new(p);
        let mut compared = 0;
        for x in spread(p, 30) {
            let (Some(plain), Some((dual, _))) = (f.residuals(&x), f.residuals_jacobian(&x)) else {
                continue;
            };
            assert_eq!(plain, dual, "at {x:?}");
            compared += 1;
        }
        assert!(compared >= 15, "only {compared} points simulated");
    }
}
