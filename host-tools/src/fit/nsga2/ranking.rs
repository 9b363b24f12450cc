//! Ranking of a population (Deb et al. 2002, section III): constraint domination, fast
//! non-dominated sorting into fronts, crowding distance within a front, and the crowded
//! comparison that tournaments and survival use.

use std::cmp::Ordering;

/// What ranking reads of a candidate: its objectives (all minimised) and its total constraint
/// violation (zero when feasible).
pub(super) trait Ranked {
    fn objectives(&self) -> &[f64];
    fn total_violation(&self) -> f64;
}

/// Which of two candidates constraint-dominates the other (Deb 2000; Deb et al. 2002, def. 1):
/// a feasible candidate beats an infeasible one; of two infeasible ones the smaller total
/// violation wins; of two feasible ones, Pareto domination decides (no worse in every objective
/// and better in at least one).
pub(super) fn constrained_domination<R: Ranked>(a: &R, b: &R) -> Ordering {
    let (va, vb) = (a.total_violation(), b.total_violation());
    match (va == 0.0, vb == 0.0) {
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        (false, false) => va.partial_cmp(&vb).unwrap_or(Ordering::Equal),
        (true, true) => pareto(a.objectives(), b.objectives()),
    }
}

/// `Less` when `a` dominates `b`, `Greater` when `b` dominates `a`, `Equal` when neither does.
fn pareto(a: &[f64], b: &[f64]) -> Ordering {
    let (mut a_better, mut b_better) = (false, false);
    for (x, y) in a.iter().zip(b) {
        if x < y {
            a_better = true;
        } else if y < x {
            b_better = true;
        }
        if a_better && b_better {
            return Ordering::Equal;
        }
    }
    match (a_better, b_better) {
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        _ => Ordering::Equal,
    }
}

/// Fast non-dominated sorting (Deb et al. 2002, fig. 1): the indices of `pop` in fronts, first
/// front first, each front in increasing index order. O(M N^2) comparisons, each pair once.
pub(super) fn non_dominated_fronts<R: Ranked>(pop: &[R]) -> Vec<Vec<usize>> {
    let n = pop.len();
    let mut dominated: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut domination_count = vec![0usize; n];
    for i in 0..n {
        for j in i + 1..n {
            match constrained_domination(&pop[i], &pop[j]) {
                Ordering::Less => {
                    dominated[i].push(j);
                    domination_count[j] += 1;
                }
                Ordering::Greater => {
                    dominated[j].push(i);
                    domination_count[i] += 1;
                }
                Ordering::Equal => {}
            }
        }
    }
    let mut fronts = Vec::new();
    let mut current: Vec<usize> = (0..n).filter(|&i| domination_count[i] == 0).collect();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &p in &current {
            for &q in &dominated[p] {
                domination_count[q] -= 1;
                if domination_count[q] == 0 {
                    next.push(q);
                }
            }
        }
        next.sort_unstable();
        fronts.push(current);
        current = next;
    }
    fronts
}

/// Crowding distances of the members of one front (Deb et al. 2002, fig. 3), in the order of
/// `front`: for each objective, the members are sorted by value, the two extremes get an infinite
/// distance and every other member adds the gap between its neighbours divided by the front's
/// range of that objective. An objective whose range is zero or not finite adds nothing.
pub(super) fn crowding_distances<R: Ranked>(pop: &[R], front: &[usize]) -> Vec<f64> {
    let n = front.len();
    let mut distance = vec![0.0; n];
    if n <= 2 {
        distance.fill(f64::INFINITY);
        return distance;
    }
    let objectives = pop[front[0]].objectives().len();
    let mut order: Vec<usize> = (0..n).collect();
    for m in 0..objectives {
        let value = |k: usize| pop[front[k]].objectives()[m];
        // Stable sort: ties keep index order, so the result does not depend on anything else.
        order.sort_by(|&x, &y| value(x).total_cmp(&value(y)));
        distance[order[0]] = f64::INFINITY;
        distance[order[n - 1]] = f64::INFINITY;
        let range = value(order[n - 1]) - value(order[0]);
        if !(range.is_finite() && range > 0.0) {
            continue;
        }
        for k in 1..n - 1 {
            distance[order[k]] += (value(order[k + 1]) - value(order[k - 1])) / range;
        }
    }
    distance
}

/// The crowded-comparison order (Deb et al. 2002, section III-C): lower rank first, then larger
/// crowding distance. `Equal` means a tie, which callers break at random.
pub(super) fn crowded_comparison(
    rank_a: usize,
    crowd_a: f64,
    rank_b: usize,
    crowd_b: f64,
) -> Ordering {
    rank_a
        .cmp(&rank_b)
        .then_with(|| crowd_b.partial_cmp(&crowd_a).unwrap_or(Ordering::Equal))
}

#[cfg(test)]
mod tests {
    use super::*;

    struct P(Vec<f64>, f64);

    impl Ranked for P {
        fn objectives(&self) -> &[f64] {
            &self.0
        }
        fn total_violation(&self) -> f64 {
            self.1
        }
    }

    fn feasible(objs: &[f64]) -> P {
        P(objs.to_vec(), 0.0)
    }

    #[test]
    fn pareto_domination_needs_no_worse_everywhere_and_better_somewhere() {
        let cd = |a: &[f64], b: &[f64]| constrained_domination(&feasible(a), &feasible(b));
        assert_eq!(cd(&[1.0, 2.0], &[2.0, 3.0]), Ordering::Less);
        assert_eq!(cd(&[1.0, 3.0], &[1.0, 2.0]), Ordering::Greater);
        assert_eq!(cd(&[1.0, 3.0], &[2.0, 2.0]), Ordering::Equal);
        assert_eq!(
            cd(&[1.0, 2.0], &[1.0, 2.0]),
            Ordering::Equal,
            "equal points do not dominate"
        );
    }

    #[test]
    fn constraint_domination_puts_feasibility_first_then_violation() {
        let good_but_infeasible = P(vec![0.0, 0.0], 0.1);
        let bad_but_feasible = P(vec![9.0, 9.0], 0.0);
        let worse_violation = P(vec![-5.0, -5.0], 2.0);
        assert_eq!(
            constrained_domination(&bad_but_feasible, &good_but_infeasible),
            Ordering::Less
        );
        assert_eq!(
            constrained_domination(&good_but_infeasible, &worse_violation),
            Ordering::Less
        );
        assert_eq!(
            constrained_domination(&worse_violation, &good_but_infeasible),
            Ordering::Greater
        );
        let same_violation = P(vec![100.0, 100.0], 0.1);
        assert_eq!(
            constrained_domination(&good_but_infeasible, &same_violation),
            Ordering::Equal,
            "equal violations: objectives are not compared"
        );
    }

    #[test]
    fn fronts_of_a_hand_made_set() {
        // Minimising both: A(1,5) B(2,3) C(4,1) are mutually non-dominated; D(3,4) is dominated
        // by B only; E(5,5) by A, B, C, D; F(2,3) duplicates B; G infeasible.
        let pop = vec![
            feasible(&[3.0, 4.0]),  // 0 D
            feasible(&[1.0, 5.0]),  // 1 A
            feasible(&[5.0, 5.0]),  // 2 E
            P(vec![0.0, 0.0], 1.0), // 3 G
            feasible(&[2.0, 3.0]),  // 4 B
            feasible(&[4.0, 1.0]),  // 5 C
            feasible(&[2.0, 3.0]),  // 6 F
        ];
        assert_eq!(
            non_dominated_fronts(&pop),
            vec![vec![1, 4, 5, 6], vec![0], vec![2], vec![3]]
        );
    }

    #[test]
    fn infeasible_candidates_rank_by_violation_with_ties_sharing_a_front() {
        let pop = vec![
            P(vec![0.0], 3.0),
            P(vec![5.0], 1.0),
            P(vec![1.0], 1.0),
            P(vec![9.0], 0.0),
        ];
        assert_eq!(
            non_dominated_fronts(&pop),
            vec![vec![3], vec![1, 2], vec![0]]
        );
    }

    #[test]
    fn crowding_distance_of_a_hand_made_front() {
        // Points on f2 = 10 - f1: (0,10) (1,9) (4,6) (10,0). Ranges 10 and 10.
        // (1,9): (4 - 0)/10 + (10 - 6)/10 = 0.8; (4,6): (10 - 1)/10 + (9 - 0)/10 = 1.8.
        let pop = vec![
            feasible(&[4.0, 6.0]),
            feasible(&[0.0, 10.0]),
            feasible(&[10.0, 0.0]),
            feasible(&[1.0, 9.0]),
        ];
        let d = crowding_distances(&pop, &[0, 1, 2, 3]);
        assert!((d[0] - 1.8).abs() < 1e-15);
        assert_eq!(d[1], f64::INFINITY);
        assert_eq!(d[2], f64::INFINITY);
        assert!((d[3] - 0.8).abs() < 1e-15);
    }

    #[test]
    fn crowding_distance_of_small_fronts_is_infinite_and_flat_objectives_add_nothing() {
        let pop = vec![
            feasible(&[1.0, 2.0]),
            feasible(&[2.0, 2.0]),
            feasible(&[3.0, 2.0]),
        ];
        assert_eq!(crowding_distances(&pop, &[0, 2]), vec![f64::INFINITY; 2]);
        let d = crowding_distances(&pop, &[0, 1, 2]);
        // f1 gives the middle one (3 - 1)/2 = 1; f2 is flat. The flat objective's sort keeps
        // index order, so its extremes (first and last index) are the f1 extremes too.
        assert_eq!(d, vec![f64::INFINITY, 1.0, f64::INFINITY]);
    }

    #[test]
    fn crowded_comparison_prefers_lower_rank_then_larger_distance() {
        assert_eq!(crowded_comparison(0, 0.1, 1, 9.0), Ordering::Less);
        assert_eq!(crowded_comparison(2, 0.5, 2, 0.2), Ordering::Less);
        assert_eq!(crowded_comparison(2, 0.2, 2, 0.5), Ordering::Greater);
        assert_eq!(
            crowded_comparison(1, f64::INFINITY, 1, f64::INFINITY),
            Ordering::Equal
        );
    }
}
