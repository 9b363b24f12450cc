//! Standard test problems with known Pareto fronts, and the distances that measure how near a
//! computed front comes to them. They check the optimiser against independent expectations
//! (tests, benchmarks) and let a user check a build (`ZDT1` at population 100 for 250
//! generations should reach an IGD below 0.01).
//!
//! ZDT1-3: Zitzler, Deb and Thiele (2000). CONSTR: Deb (2001), section 14.1. TNK: Tanaka et al.
//! (1995). The fronts are sampled from their closed forms.

use std::f64::consts::PI;

use super::{Bounds, Evaluation, Problem};

/// Which of the three unconstrained ZDT problems.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ZdtKind {
    /// Convex front f2 = 1 - sqrt(f1).
    Zdt1,
    /// Concave front f2 = 1 - f1^2.
    Zdt2,
    /// Five disconnected pieces of f2 = 1 - sqrt(f1) - f1 sin(10 pi f1).
    Zdt3,
}

/// A ZDT problem on [0, 1]^n: f1 = x1, g = 1 + 9 / (n - 1) * sum(x2..xn), f2 = g h(f1, g).
/// The Pareto set is x2 = ... = xn = 0 (g = 1).
#[derive(Clone, Debug)]
pub struct Zdt {
    kind: ZdtKind,
    bounds: Vec<Bounds>,
}

impl Zdt {
    /// The problem with `n` >= 2 variables (30 in the original paper).
    pub fn new(kind: ZdtKind, n: usize) -> Self {
        Zdt {
            kind,
            bounds: vec![Bounds::new(0.0, 1.0); n.max(2)],
        }
    }

    /// `samples` points of the Pareto front, evenly spaced in f1 (for ZDT3, those of an even
    /// grid that are non-dominated, so slightly fewer).
    pub fn pareto_front(&self, samples: usize) -> Vec<[f64; 2]> {
        let curve = (0..samples).map(|i| {
            let f1 = i as f64 / (samples - 1) as f64;
            [f1, self.h(f1, 1.0)]
        });
        match self.kind {
            ZdtKind::Zdt3 => non_dominated_2d(curve.collect()),
            _ => curve.collect(),
        }
    }

    fn h(&self, f1: f64, g: f64) -> f64 {
        let r = f1 / g;
        match self.kind {
            ZdtKind::Zdt1 => 1.0 - r.sqrt(),
            ZdtKind::Zdt2 => 1.0 - r * r,
            ZdtKind::Zdt3 => 1.0 - r.sqrt() - r * (10.0 * PI * f1).sin(),
        }
    }
}

impl Problem for Zdt {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let f1 = x[0];
        let g = 1.0 + 9.0 * x[1..].iter().sum::<f64>() / (x.len() - 1) as f64;
        Evaluation::unconstrained(vec![f1, g * self.h(f1, g)])
    }
}

/// Deb's CONSTR: minimise x1 and (1 + x2) / x1 on [0.1, 1] x [0, 5] subject to
/// x2 + 9 x1 >= 6 and -x2 + 9 x1 >= 1. The first constraint shapes the left part of the front.
#[derive(Clone, Debug)]
pub struct Constr {
    bounds: [Bounds; 2],
}

impl Default for Constr {
    fn default() -> Self {
        Constr {
            bounds: [Bounds::new(0.1, 1.0), Bounds::new(0.0, 5.0)],
        }
    }
}

impl Constr {
    /// `samples` points of the front, evenly spaced in f1 over [7/18, 1]: f2 = (7 - 9 f1) / f1
    /// where x2 = 6 - 9 x1 (f1 <= 2/3, the constraint active) and f2 = 1 / f1 where x2 = 0.
    pub fn pareto_front(samples: usize) -> Vec<[f64; 2]> {
        let (a, b) = (7.0 / 18.0, 1.0);
        (0..samples)
            .map(|i| {
                let f1 = a + (b - a) * i as f64 / (samples - 1) as f64;
                let f2 = if f1 <= 2.0 / 3.0 {
                    (7.0 - 9.0 * f1) / f1
                } else {
                    1.0 / f1
                };
                [f1, f2]
            })
            .collect()
    }
}

impl Problem for Constr {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn num_constraints(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::new(
            vec![x[0], (1.0 + x[1]) / x[0]],
            vec![6.0 - x[1] - 9.0 * x[0], 1.0 + x[1] - 9.0 * x[0]],
        )
    }
}

/// Tanaka's TNK: minimise x1 and x2 on [0, pi]^2 subject to
/// x1^2 + x2^2 - 1 - 0.1 cos(16 atan(x1 / x2)) >= 0 and (x1 - 0.5)^2 + (x2 - 0.5)^2 <= 0.5.
/// The front is made of disconnected pieces of the first constraint's boundary.
#[derive(Clone, Debug)]
pub struct Tnk {
    bounds: [Bounds; 2],
}

impl Default for Tnk {
    fn default() -> Self {
        Tnk {
            bounds: [Bounds::new(0.0, PI), Bounds::new(0.0, PI)],
        }
    }
}

impl Tnk {
    /// The non-dominated points among `samples` points of the first constraint's boundary
    /// r(phi)^2 = 1 + 0.1 cos(16 phi), x1 = r sin(phi), x2 = r cos(phi), phi evenly spaced in
    /// [0, pi/2], that satisfy the second constraint.
    pub fn pareto_front(samples: usize) -> Vec<[f64; 2]> {
        let points = (0..samples)
            .map(|i| {
                let phi = 0.5 * PI * i as f64 / (samples - 1) as f64;
                let r = (1.0 + 0.1 * (16.0 * phi).cos()).sqrt();
                [r * phi.sin(), r * phi.cos()]
            })
            .filter(|p| (p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2) <= 0.5)
            .collect();
        non_dominated_2d(points)
    }
}

impl Problem for Tnk {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn num_constraints(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        // atan2(x1, x2) is atan(x1 / x2) for x2 > 0 and its limit pi/2 at x2 = 0.
        let wave = 1.0 + 0.1 * (16.0 * x[0].atan2(x[1])).cos();
        Evaluation::new(
            vec![x[0], x[1]],
            vec![
                wave - x[0] * x[0] - x[1] * x[1],
                (x[0] - 0.5).powi(2) + (x[1] - 0.5).powi(2) - 0.5,
            ],
        )
    }
}

/// The sphere sum(x_i^2) on [-5.12, 5.12]^n: one objective, minimum 0 at the origin.
#[derive(Clone, Debug)]
pub struct Sphere {
    bounds: Vec<Bounds>,
}

impl Sphere {
    /// The sphere in `n` variables.
    pub fn new(n: usize) -> Self {
        Sphere {
            bounds: vec![Bounds::new(-5.12, 5.12); n],
        }
    }
}

impl Problem for Sphere {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        1
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::unconstrained(vec![x.iter().map(|v| v * v).sum()])
    }
}

/// The points of a two-objective set that no other point dominates, sorted by f1.
fn non_dominated_2d(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let mut front: Vec<[f64; 2]> = Vec::new();
    for p in points {
        if front.last().is_none_or(|last| p[1] < last[1]) {
            front.push(p);
        }
    }
    front
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn mean_nearest<A: AsRef<[f64]>, B: AsRef<[f64]>>(from: &[A], to: &[B]) -> f64 {
    let total: f64 = from
        .iter()
        .map(|p| {
            to.iter()
                .map(|q| distance(p.as_ref(), q.as_ref()))
                .fold(f64::INFINITY, f64::min)
        })
        .sum();
    total / from.len() as f64
}

/// Inverted generational distance: the mean, over the `reference` front, of the distance to the
/// nearest point of `found`. Small only when `found` is both near the front and spread along it.
pub fn igd<A: AsRef<[f64]>, B: AsRef<[f64]>>(found: &[A], reference: &[B]) -> f64 {
    mean_nearest(reference, found)
}

/// Generational distance: the mean, over `found`, of the distance to the nearest point of the
/// `reference` front. Measures convergence only.
pub fn generational_distance<A: AsRef<[f64]>, B: AsRef<[f64]>>(
    found: &[A],
    reference: &[B],
) -> f64 {
    mean_nearest(found, reference)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zdt_objectives_on_the_pareto_set_lie_on_the_closed_form_front() {
        for kind in [ZdtKind::Zdt1, ZdtKind::Zdt2, ZdtKind::Zdt3] {
            let p = Zdt::new(kind, 30);
            let mut x = vec![0.0; 30];
            x[0] = 0.25;
            let f = p.evaluate(&x).objectives;
            let expected = match kind {
                ZdtKind::Zdt1 => 0.5,
                ZdtKind::Zdt2 => 0.9375,
                // 1 - 0.5 - 0.25 sin(2.5 pi) = 0.25
                ZdtKind::Zdt3 => 0.25,
            };
            assert_eq!(f[0], 0.25);
            assert!((f[1] - expected).abs() < 1e-15, "{kind:?}: {}", f[1]);
        }
        // Off the Pareto set: x = (0.25, 1, ..., 1) gives g = 10, f2 = 10 (1 - sqrt(0.025)).
        let mut x = vec![1.0; 30];
        x[0] = 0.25;
        let f = Zdt::new(ZdtKind::Zdt1, 30).evaluate(&x).objectives;
        assert!((f[1] - 10.0 * (1.0 - 0.025f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn zdt3_front_has_five_pieces_within_the_published_f1_ranges() {
        let front = Zdt::new(ZdtKind::Zdt3, 30).pareto_front(100_001);
        // The published pieces start at f1 = 0, 0.1822, 0.4093, 0.6184 and 0.8233.
        let mut starts = vec![front[0][0]];
        for w in front.windows(2) {
            if w[1][0] - w[0][0] > 1.0e-3 {
                starts.push(w[1][0]);
            }
        }
        let published = [0.0, 0.182_228_8, 0.409_313_7, 0.618_396_6, 0.823_332_8];
        assert_eq!(starts.len(), 5, "{starts:?}");
        for (s, p) in starts.iter().zip(published) {
            assert!((s - p).abs() < 2.0e-5, "piece starts at {s}, published {p}");
        }
    }

    #[test]
    fn constr_front_points_are_feasible_with_the_first_constraint_active_on_the_left() {
        let p = Constr::default();
        for [f1, f2] in Constr::pareto_front(50) {
            // Invert: x1 = f1, x2 = f1 f2 - 1.
            let x = [f1, f1 * f2 - 1.0];
            let e = p.evaluate(&x);
            assert!(e.constraint_violations.iter().all(|&g| g <= 1e-12), "{x:?}");
            assert!((e.objectives[1] - f2).abs() < 1e-12);
            if f1 < 2.0 / 3.0 {
                assert!(e.constraint_violations[0].abs() < 1e-12);
            }
        }
    }

    #[test]
    fn tnk_front_lies_on_the_wavy_boundary_inside_the_circle() {
        let p = Tnk::default();
        let front = Tnk::pareto_front(20_001);
        assert!(front.len() > 1000);
        for q in &front {
            let e = p.evaluate(q);
            assert!(e.constraint_violations[0].abs() < 1e-12);
            assert!(e.constraint_violations[1] <= 0.0);
        }
        // Its extremes are where the boundary meets the circle, near (0.0417, 1.0384) and
        // (1.0384, 0.0417) (the front is symmetric about x1 = x2).
        let (first, last) = (front[0], front[front.len() - 1]);
        assert!((first[0] - last[1]).abs() < 1e-3 && (first[1] - last[0]).abs() < 1e-3);
        assert!(first[0] < 0.06 && first[1] > 1.0, "{first:?}");
    }

    #[test]
    fn distances_of_hand_made_sets() {
        let reference = [[0.0, 1.0], [1.0, 0.0]];
        let found = [[0.0, 1.0]];
        // IGD: (0 + sqrt(2)) / 2; GD: 0.
        assert!((igd(&found, &reference) - 0.5 * 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(generational_distance(&found, &reference), 0.0);
        let shifted = [[0.0, 1.1], [1.0, 0.1]];
        assert!((generational_distance(&shifted, &reference) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn sphere_is_zero_at_the_origin_only() {
        let p = Sphere::new(3);
        assert_eq!(p.evaluate(&[0.0; 3]).objectives, vec![0.0]);
        assert_eq!(p.evaluate(&[1.0, -2.0, 0.5]).objectives, vec![5.25]);
    }
}
