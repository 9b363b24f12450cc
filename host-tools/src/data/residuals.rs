//! Sums of squared residuals grouped the way an engineer reads a hysteresis
//! record: by cycle, by half-cycle, by branch class and by the near-zero-force
//! region. A diagnosis compares these groups: pinching shows as residuals
//! concentrated on reloading near zero force, degradation as residuals that
//! grow with the cycle number.

use super::branches::{Branch, Segmentation};
use super::cycles::CycleError;

/// A count of samples and their sum of squared residuals.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Number of samples.
    pub count: usize,
    /// Sum of the squared residuals.
    pub sum_sq: f64,
}

impl Tally {
    /// Adds one residual.
    pub fn add(&mut self, residual: f64) {
        self.count += 1;
        self.sum_sq += residual * residual;
    }

    /// Root mean square, `None` for no samples.
    pub fn rms(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.sum_sq / self.count as f64).sqrt())
    }
}

/// Residuals of one record summed by group. Every sample is counted once in
/// `total`, once in `by_half_cycle`, once in `by_cycle`, and once in
/// `by_branch_zone` (branch × near zero force).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Breakdown {
    /// All samples.
    pub total: Tally,
    /// Indexed by half-cycle.
    pub by_half_cycle: Vec<Tally>,
    /// Indexed by cycle.
    pub by_cycle: Vec<Tally>,
    /// Indexed by [`Branch::index`], then `[away from zero force, near zero force]`.
    pub by_branch_zone: [[Tally; 2]; 3],
}

impl Breakdown {
    /// Sums `residuals` (one a sample) over the groups of `segmentation`.
    pub fn new(segmentation: &Segmentation, residuals: &[f64]) -> Result<Breakdown, CycleError> {
        let labels = segmentation.labels();
        if residuals.len() != labels.len() {
            return Err(CycleError::Length {
                expected: labels.len(),
                found: residuals.len(),
            });
        }
        if let Some(index) = residuals.iter().position(|r| !r.is_finite()) {
            return Err(CycleError::NotFinite { index });
        }
        let cycles = segmentation.cycles();
        let mut b = Breakdown {
            by_half_cycle: vec![Tally::default(); cycles.half_cycles().len()],
            by_cycle: vec![Tally::default(); cycles.cycles().len()],
            ..Breakdown::default()
        };
        for (l, &r) in labels.iter().zip(residuals) {
            b.total.add(r);
            b.by_half_cycle[l.half_cycle].add(r);
            b.by_cycle[l.cycle].add(r);
            b.by_branch_zone[l.branch.index()][usize::from(l.near_zero_force)].add(r);
        }
        Ok(b)
    }

    /// All samples of a branch class.
    pub fn branch(&self, branch: Branch) -> Tally {
        let [a, b] = self.by_branch_zone[branch.index()];
        Tally {
            count: a.count + b.count,
            sum_sq: a.sum_sq + b.sum_sq,
        }
    }

    /// The samples of a branch class near zero force (`true`) or away from it.
    pub fn branch_zone(&self, branch: Branch, near_zero_force: bool) -> Tally {
        self.by_branch_zone[branch.index()][usize::from(near_zero_force)]
    }

    /// All samples near zero force (`true`) or away from it.
    pub fn zone(&self, near_zero_force: bool) -> Tally {
        Branch::ALL.iter().fold(Tally::default(), |acc, &b| {
            let t = self.branch_zone(b, near_zero_force);
            Tally {
                count: acc.count + t.count,
                sum_sq: acc.sum_sq + t.sum_sq,
            }
        })
    }
}
