//! Variation operators on real-valued variables, as in Deb's reference NSGA-II code
//! (nsga2-v1.1, Kanpur Genetic Algorithms Laboratory): simulated binary crossover with the bounded
//! spread (Deb and Agrawal 1995; Deb and Goyal 1996) and bounded polynomial mutation (Deb 2001).
//! Children never leave the bounds: the bounded forms shape their spread distributions so that
//! no probability falls outside, and the final `clamp` only guards the last rounding bit.

use super::Bounds;
use crate::random::Rng;

/// Parents closer than this in one variable are copied unchanged, as in the reference code
/// (SBX's spread factor divides by their distance).
const SAME_VALUE: f64 = 1.0e-14;

/// Simulated binary crossover of `a` and `b` in place, variable by variable: each variable is
/// crossed with probability 1/2, its two children spread around the parents' mean with the
/// polynomial distribution of index `eta` (large `eta`: children near the parents), bounded by
/// `bounds`, and the pair is swapped with probability 1/2. The parents' mean is preserved.
pub(super) fn sbx(a: &mut [f64], b: &mut [f64], bounds: &[Bounds], eta: f64, rng: &mut Rng) {
    for ((x1, x2), bound) in a.iter_mut().zip(b.iter_mut()).zip(bounds) {
        if !rng.chance(0.5) || (*x1 - *x2).abs() <= SAME_VALUE {
            continue;
        }
        let (y1, y2) = if *x1 < *x2 { (*x1, *x2) } else { (*x2, *x1) };
        let (lo, hi) = (bound.lower, bound.upper);
        let u = rng.uniform();
        let c1 = 0.5 * ((y1 + y2) - spread(1.0 + 2.0 * (y1 - lo) / (y2 - y1), eta, u) * (y2 - y1));
        let c2 = 0.5 * ((y1 + y2) + spread(1.0 + 2.0 * (hi - y2) / (y2 - y1), eta, u) * (y2 - y1));
        let (c1, c2) = (c1.clamp(lo, hi), c2.clamp(lo, hi));
        if rng.chance(0.5) {
            (*x1, *x2) = (c2, c1);
        } else {
            (*x1, *x2) = (c1, c2);
        }
    }
}

/// The spread factor beta_q of bounded SBX for the uniform draw `u`: the inverse of the
/// polynomial distribution's cumulative function, truncated so that the child stays within the
/// distance `beta` (in units of half the parents' distance) that reaches the bound.
fn spread(beta: f64, eta: f64, u: f64) -> f64 {
    let alpha = 2.0 - beta.powf(-(eta + 1.0));
    if u <= 1.0 / alpha {
        (u * alpha).powf(1.0 / (eta + 1.0))
    } else {
        (1.0 / (2.0 - u * alpha)).powf(1.0 / (eta + 1.0))
    }
}

/// Bounded polynomial mutation in place: each variable mutates with probability `p`, moved by a
/// polynomially distributed step of index `eta` whose two sides are scaled to the distances to
/// the lower and upper bound.
pub(super) fn polynomial_mutation(
    x: &mut [f64],
    bounds: &[Bounds],
    p: f64,
    eta: f64,
    rng: &mut Rng,
) {
    for (xi, bound) in x.iter_mut().zip(bounds) {
        if !rng.chance(p) {
            continue;
        }
        let (lo, hi) = (bound.lower, bound.upper);
        let delta1 = (*xi - lo) / (hi - lo);
        let delta2 = (hi - *xi) / (hi - lo);
        let u = rng.uniform();
        let power = 1.0 / (eta + 1.0);
        let step = if u < 0.5 {
            let v = 2.0 * u + (1.0 - 2.0 * u) * (1.0 - delta1).powf(eta + 1.0);
            v.powf(power) - 1.0
        } else {
            let v = 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * (1.0 - delta2).powf(eta + 1.0);
            1.0 - v.powf(power)
        };
        *xi = (*xi + step * (hi - lo)).clamp(lo, hi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(n: usize) -> Vec<Bounds> {
        vec![Bounds::new(0.0, 1.0); n]
    }

    #[test]
    fn sbx_keeps_children_in_bounds_on_either_side_of_the_parents_mean() {
        let bounds = vec![Bounds::new(-2.0, 3.0); 4];
        let mut rng = Rng::seed_from_u64(1);
        let mut crossed = 0;
        for _ in 0..20_000 {
            let p1: Vec<f64> = (0..4).map(|_| -2.0 + 5.0 * rng.uniform()).collect();
            let p2: Vec<f64> = (0..4).map(|_| -2.0 + 5.0 * rng.uniform()).collect();
            let (mut c1, mut c2) = (p1.clone(), p2.clone());
            sbx(&mut c1, &mut c2, &bounds, 15.0, &mut rng);
            for j in 0..4 {
                assert!((-2.0..=3.0).contains(&c1[j]) && (-2.0..=3.0).contains(&c2[j]));
                // c1 = mean - beta_q1 d / 2 and c2 = mean + beta_q2 d / 2 with beta_q >= 0:
                // the children straddle the parents' mean (the bounded spreads of the two sides
                // differ, so their own mean moves only when a bound is near).
                let (lo, hi) = (c1[j].min(c2[j]), c1[j].max(c2[j]));
                let mean = 0.5 * (p1[j] + p2[j]);
                assert!(lo <= mean + 1e-12 && mean <= hi + 1e-12);
                if c1[j] != p1[j] && c1[j] != p2[j] {
                    crossed += 1;
                }
            }
        }
        // Each variable crosses with probability 1/2.
        let fraction = crossed as f64 / 80_000.0;
        assert!((fraction - 0.5).abs() < 0.01, "crossed fraction {fraction}");
    }

    #[test]
    fn sbx_far_from_the_bounds_matches_the_unbounded_spread_distribution() {
        // Far from the bounds, beta -> infinity and alpha -> 2, and the spread factor has the
        // distribution of Deb and Agrawal (1995): P(beta_q <= b) = b^(eta+1) / 2 for b <= 1.
        let eta = 2.0;
        let bounds = vec![Bounds::new(-1.0e6, 1.0e6)];
        let mut rng = Rng::seed_from_u64(9);
        let (mut below_half, mut total) = (0usize, 0usize);
        while total < 40_000 {
            let (mut a, mut b) = (vec![-0.5], vec![0.5]);
            sbx(&mut a, &mut b, &bounds, eta, &mut rng);
            if a[0] == -0.5 && b[0] == 0.5 {
                continue; // this variable was not crossed
            }
            total += 1;
            // Children at mean -/+ beta_q * (distance / 2) = -/+ beta_q / 2.
            let beta_q = (a[0] - b[0]).abs();
            if beta_q <= 0.5 {
                below_half += 1;
            }
        }
        let expected = 0.5f64.powf(eta + 1.0) / 2.0; // 0.0625
        let got = below_half as f64 / total as f64;
        // Binomial standard error sqrt(p(1-p)/n) = 1.2e-3; allow five.
        assert!(
            (got - expected).abs() < 6.0e-3,
            "P(beta_q <= 0.5) = {got}, expected {expected}"
        );
    }

    #[test]
    fn sbx_copies_identical_parents() {
        let mut rng = Rng::seed_from_u64(2);
        let (mut a, mut b) = (vec![0.3, 0.7], vec![0.3, 0.7]);
        sbx(&mut a, &mut b, &unit(2), 20.0, &mut rng);
        assert_eq!((a, b), (vec![0.3, 0.7], vec![0.3, 0.7]));
    }

    #[test]
    fn polynomial_mutation_stays_in_bounds_and_reaches_both_bounds_regions() {
        let bounds = unit(1);
        let mut rng = Rng::seed_from_u64(4);
        let (mut left, mut right) = (0, 0);
        for _ in 0..50_000 {
            let mut x = vec![0.02];
            polynomial_mutation(&mut x, &bounds, 1.0, 20.0, &mut rng);
            assert!((0.0..=1.0).contains(&x[0]));
            if x[0] < 0.02 {
                left += 1;
            } else if x[0] > 0.02 {
                right += 1;
            }
        }
        // The bounded operator moves down or up with probability 1/2 each, however near the
        // bound the variable sits (that is what its scaled sides are for).
        let fraction = left as f64 / (left + right) as f64;
        assert!((fraction - 0.5).abs() < 0.01, "left fraction {fraction}");
    }

    #[test]
    fn polynomial_mutation_step_has_the_polynomial_distribution_in_the_middle_of_the_range() {
        // At the centre of [0, 1], delta1 = delta2 = 1/2 and, with c = 2^-(eta+1), a draw
        // u < 1/2 gives the step (2u (1 - c) + c)^(1/(eta+1)) - 1. That step lies in (-s, 0)
        // exactly when u* < u < 1/2 with u* = ((1 - s)^(eta+1) - c) / (2 (1 - c)).
        let eta: f64 = 5.0;
        let s: f64 = 0.1;
        let c = 0.5f64.powf(eta + 1.0);
        let u_star = ((1.0 - s).powf(eta + 1.0) - c) / (2.0 * (1.0 - c));
        let expected = 0.5 - u_star;
        let bounds = unit(1);
        let mut rng = Rng::seed_from_u64(8);
        let n = 100_000;
        let mut hits = 0;
        for _ in 0..n {
            let mut x = vec![0.5];
            polynomial_mutation(&mut x, &bounds, 1.0, eta, &mut rng);
            if x[0] < 0.5 && x[0] > 0.5 - s {
                hits += 1;
            }
        }
        let got = hits as f64 / n as f64;
        assert!(
            (got - expected).abs() < 5.0e-3,
            "P(-s < step < 0) = {got}, expected {expected}"
        );
    }

    #[test]
    fn mutation_probability_zero_changes_nothing() {
        let mut rng = Rng::seed_from_u64(6);
        let mut x = vec![0.1, 0.2, 0.3];
        polynomial_mutation(&mut x, &unit(3), 0.0, 20.0, &mut rng);
        assert_eq!(x, vec![0.1, 0.2, 0.3]);
    }
}
