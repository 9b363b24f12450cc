//! Branch classes of a hysteresis record: every sample is on the loading
//! envelope, on an unloading branch or on a reloading branch, and may lie in
//! the near-zero-force region where pinching shows.
//!
//! Within half-cycle `k` (direction `d`, starting at a reversal) the branches
//! follow each other in this order, each possibly empty:
//!
//! 1. **unloading**: from the reversal until the force crosses zero, i.e.
//!    until the first sample with `d·F ≥ 0`;
//! 2. **reloading**: after the force zero crossing, towards the next peak,
//!    inside the previous envelope;
//! 3. **loading**: from the first sample whose displacement is beyond every
//!    displacement before the half-cycle in direction `d` (a new peak: on the
//!    envelope) to the end of the half-cycle. Loading wins over the other two.
//!
//! The first half-cycle, from rest to the first reversal, is the virgin
//! loading curve: all of it is loading.
//!
//! A sample is **near zero force** when `|F|` is below a fraction (default
//! 20 %) of the largest `|F|` of its cycle.
//!
//! The direction `d` is the direction of the signal that was cut into cycles
//! (the record's input); the envelope is always one of displacement.

use super::cycles::{CycleError, Cycles, Direction, Peak, Threshold};
use super::residuals::Breakdown;
use std::fmt;

/// The branch class of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Branch {
    /// On the envelope: displacement beyond all previous peaks in the
    /// direction of motion.
    Loading,
    /// From a reversal until the force crosses zero.
    Unloading,
    /// After the force zero crossing, towards the next peak, inside the
    /// previous envelope.
    Reloading,
}

impl Branch {
    /// All classes, in index order.
    pub const ALL: [Branch; 3] = [Branch::Loading, Branch::Unloading, Branch::Reloading];

    /// Position in [`Branch::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The engineer's word: `loading`, `unloading`, `reloading`.
    pub fn name(self) -> &'static str {
        match self {
            Branch::Loading => "loading",
            Branch::Unloading => "unloading",
            Branch::Reloading => "reloading",
        }
    }
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Where a sample lies in the record's cycle structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Label {
    /// The half-cycle owning the sample.
    pub half_cycle: usize,
    /// The cycle owning the sample.
    pub cycle: usize,
    /// Its branch class.
    pub branch: Branch,
    /// Whether `|F|` is below the near-zero fraction of its cycle's peak.
    pub near_zero_force: bool,
}

/// Options of [`Segmentation::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentOptions {
    /// Reversal threshold on the input signal.
    pub threshold: Threshold,
    /// The near-zero-force region: `|F| <` this fraction of the cycle's peak
    /// `|F|` (default 0.2).
    pub near_zero_fraction: f64,
}

impl Default for SegmentOptions {
    fn default() -> Self {
        SegmentOptions {
            threshold: Threshold::default(),
            near_zero_fraction: 0.2,
        }
    }
}

/// A record cut into cycles, half-cycles and branches, with its peak forces
/// and energies; the frame in which a diagnosis sums residuals.
///
/// ```
/// use hyst::data::{Branch, SegmentOptions, Segmentation, Threshold};
/// // Elastic-perfectly-plastic: stiffness 1, yield force 2, amplitude 3.
/// let u = [0., 1., 2., 3., 2., 1., 0., -1., -2., -3., -2., -1., 0., 1., 2., 3.];
/// let f = [0., 1., 2., 2., 1., 0., -1., -2., -2., -2., -1., 0., 1., 2., 2., 2.];
/// let options = SegmentOptions { threshold: Threshold::Absolute(0.5), ..Default::default() };
/// let s = Segmentation::new(&u, &f, &u, &options).unwrap();
/// assert_eq!(s.cycles().reversals(), &[3, 9]);
/// use Branch::*;
/// let (l, un, re) = (Loading, Unloading, Reloading);
/// let branches: Vec<Branch> = s.labels().iter().map(|l| l.branch).collect();
/// assert_eq!(branches, [l, l, l, l, un, re, re, l, l, l, un, re, re, re, re, re]);
/// // A model's residuals summed by branch class:
/// let b = s.breakdown(&[0.1; 16]).unwrap();
/// assert_eq!(b.branch(Reloading).count, 7);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Segmentation {
    cycles: Cycles,
    labels: Vec<Label>,
    peak_forces: Vec<Peak>,
    energy: Vec<f64>,
}

impl Segmentation {
    /// Cuts `input` into cycles and classifies every sample of the
    /// `displacement`–`force` record. `input` is the signal whose reversals
    /// define the half-cycles: the displacement for a displacement-driven
    /// test, the force for a force-driven one.
    pub fn new(
        displacement: &[f64],
        force: &[f64],
        input: &[f64],
        options: &SegmentOptions,
    ) -> Result<Segmentation, CycleError> {
        let n = input.len();
        for s in [displacement, force] {
            if s.len() != n {
                return Err(CycleError::Length {
                    expected: n,
                    found: s.len(),
                });
            }
            if let Some(index) = s.iter().position(|v| !v.is_finite()) {
                return Err(CycleError::NotFinite { index });
            }
        }
        let frac = options.near_zero_fraction;
        if !(0.0..=1.0).contains(&frac) {
            return Err(CycleError::Fraction(frac));
        }
        let cycles = Cycles::find(input, options.threshold)?;
        let peak_forces = cycles.peak_forces(force)?;
        let energy = cycles.energy(displacement, force)?;

        // Envelope of displacement up to and including each sample.
        let mut hi = Vec::with_capacity(n);
        let mut lo = Vec::with_capacity(n);
        for (i, &u) in displacement.iter().enumerate() {
            hi.push(if i == 0 { u } else { u.max(hi[i - 1]) });
            lo.push(if i == 0 { u } else { u.min(lo[i - 1]) });
        }

        let mut labels = Vec::with_capacity(n);
        for h in cycles.half_cycles() {
            let d = h.direction.sign();
            let env = match h.direction {
                Direction::Increasing => hi[h.from],
                Direction::Decreasing => lo[h.from],
            };
            let samples = h.samples();
            let first = |test: &dyn Fn(usize) -> bool| {
                samples.clone().find(|&i| test(i)).unwrap_or(samples.end)
            };
            let zero = first(&|i| d * force[i] >= 0.0);
            let beyond = if h.index == 0 {
                samples.start
            } else {
                first(&|i| d * (displacement[i] - env) > 0.0)
            };
            for i in samples.clone() {
                let branch = if i >= beyond {
                    Branch::Loading
                } else if i < zero {
                    Branch::Unloading
                } else {
                    Branch::Reloading
                };
                labels.push(Label {
                    half_cycle: h.index,
                    cycle: h.cycle(),
                    branch,
                    near_zero_force: false,
                });
            }
        }
        for c in cycles.cycles() {
            let peak = c.samples().fold(0.0f64, |m, i| m.max(force[i].abs()));
            for i in c.samples() {
                labels[i].near_zero_force = force[i].abs() < frac * peak;
            }
        }
        Ok(Segmentation {
            cycles,
            labels,
            peak_forces,
            energy,
        })
    }

    /// The reversals, half-cycles and cycles.
    pub fn cycles(&self) -> &Cycles {
        &self.cycles
    }

    /// One label a sample.
    pub fn labels(&self) -> &[Label] {
        &self.labels
    }

    /// The extreme force of each half-cycle, in its direction.
    pub fn peak_forces(&self) -> &[Peak] {
        &self.peak_forces
    }

    /// `∫ F du` of each cycle (kN·mm = J).
    pub fn energy(&self) -> &[f64] {
        &self.energy
    }

    /// Sums of squared residuals (e.g. model force − measured force) by cycle,
    /// half-cycle, branch class and near-zero-force region.
    pub fn breakdown(&self, residuals: &[f64]) -> Result<Breakdown, CycleError> {
        Breakdown::new(self, residuals)
    }
}
