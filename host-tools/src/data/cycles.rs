//! Load reversals, half-cycles and cycles of a signal, peak force per
//! half-cycle and energy dissipated per cycle.
//!
//! **Reversals.** A reversal is a peak of the signal after which it moves back
//! by more than a threshold `h` (a hysteresis, or "zig-zag", filter): noise
//! smaller than `h` never makes a reversal, and the reversal is placed at the
//! extreme sample of the excursion. Excursions smaller than `h` are not seen
//! at all: the first peak counts only if it lies more than `h` from the first
//! sample, and a later cycle of amplitude `A` about the start needs a swing
//! `2A > h`. So `h` must stay below the first amplitude and the smallest swing
//! of interest, and above the noise's peak-to-peak. The default is 1 % of the
//! signal's range.
//!
//! **Half-cycles.** Half-cycle `k` runs from turning point `k` to turning
//! point `k + 1`, where the turning points are the first sample, the
//! reversals, and the last sample. It owns the samples after its start up to
//! and including its end (the first half-cycle also owns sample 0), so every
//! sample belongs to exactly one half-cycle, and a half-cycle's peak is its
//! last sample. The last half-cycle normally ends at the end of the record,
//! not at a reversal: it is incomplete.
//!
//! **Cycles.** Cycle `j` is half-cycles `2j` and `2j + 1`. For a protocol that
//! starts at rest with a push, cycle `j` holds the push to the `j`-th positive
//! peak and the pull to the `j`-th negative peak, so the count of complete
//! cycles is the protocol's count of cycles.
//!
//! **Energy.** The energy of a cycle is `∫ F du` along its path from its start
//! turning point to its end (trapezoidal rule), in kN·mm = J. It is the area
//! of the loop when the cycle closes (ends where it started, with the same
//! force); otherwise it also holds the change of stored elastic energy. The
//! energies of all cycles add up to `∫ F du` over the whole record.

use std::fmt;
use std::ops::{Range, RangeInclusive};

/// How far the signal must move back from a peak for the peak to count as a
/// reversal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Threshold {
    /// A fraction of the signal's range (max − min).
    FractionOfRange(f64),
    /// An absolute amount in the signal's unit.
    Absolute(f64),
}

impl Default for Threshold {
    /// 1 % of the range: above the noise of our records (0.2 mm sd on a 200 mm
    /// range gives 2 mm = 10 sd), below their smallest cycles.
    fn default() -> Self {
        Threshold::FractionOfRange(0.01)
    }
}

impl Threshold {
    /// The absolute threshold for a signal.
    pub fn resolve(self, x: &[f64]) -> Result<f64, CycleError> {
        let h = match self {
            Threshold::Absolute(h) => h,
            Threshold::FractionOfRange(f) => {
                if !(f.is_finite() && f >= 0.0) {
                    return Err(CycleError::Threshold(f));
                }
                let (lo, hi) = x
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                        (lo.min(v), hi.max(v))
                    });
                if x.is_empty() {
                    0.0
                } else {
                    f * (hi - lo)
                }
            }
        };
        if h.is_finite() && h >= 0.0 {
            Ok(h)
        } else {
            Err(CycleError::Threshold(h))
        }
    }
}

/// Why a signal could not be cut into cycles.
#[derive(Clone, Debug, PartialEq)]
pub enum CycleError {
    /// The threshold is negative or not finite.
    Threshold(f64),
    /// A value is not finite.
    NotFinite {
        /// Sample index.
        index: usize,
    },
    /// Two signals that must go together have different lengths.
    Length {
        /// What was expected.
        expected: usize,
        /// What was found.
        found: usize,
    },
    /// A fraction is outside `[0, 1]`.
    Fraction(f64),
}

impl fmt::Display for CycleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CycleError::Threshold(h) => write!(
                f,
                "expected a finite, non-negative reversal threshold, found {h}"
            ),
            CycleError::NotFinite { index } => {
                write!(
                    f,
                    "expected finite values, found a non-finite one at sample {index}"
                )
            }
            CycleError::Length { expected, found } => {
                write!(f, "expected {expected} samples, found {found}")
            }
            CycleError::Fraction(x) => write!(f, "expected a fraction in [0, 1], found {x}"),
        }
    }
}

impl std::error::Error for CycleError {}

/// The direction a half-cycle moves the signal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// The signal increases (a push, for displacement).
    Increasing,
    /// The signal decreases (a pull).
    Decreasing,
}

impl Direction {
    /// `+1.0` or `-1.0`.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Increasing => 1.0,
            Direction::Decreasing => -1.0,
        }
    }
}

/// One half-cycle: from one turning point to the next.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HalfCycle {
    /// Its number, from 0.
    pub index: usize,
    /// The turning point it starts at (sample index).
    pub from: usize,
    /// The turning point it ends at: its peak (sample index).
    pub to: usize,
    /// Which way it moves the signal.
    pub direction: Direction,
    /// Whether it ends at a reversal (the last half-cycle usually does not).
    pub complete: bool,
}

impl HalfCycle {
    /// The samples it owns: `from + 1 ..= to`, or `0 ..= to` for the first.
    pub fn samples(&self) -> Range<usize> {
        let start = if self.index == 0 { 0 } else { self.from + 1 };
        start..self.to + 1
    }

    /// The path it traces, from its start turning point to its end.
    pub fn path(&self) -> RangeInclusive<usize> {
        self.from..=self.to
    }

    /// The cycle it belongs to.
    pub fn cycle(&self) -> usize {
        self.index / 2
    }
}

/// One cycle: two consecutive half-cycles (or the last, lone one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cycle {
    /// Its number, from 0.
    pub index: usize,
    /// The half-cycles it holds (indices).
    pub half_cycles: Range<usize>,
    /// The turning point it starts at.
    pub from: usize,
    /// The turning point it ends at.
    pub to: usize,
    /// Whether it has two half-cycles and ends at a reversal.
    pub complete: bool,
}

impl Cycle {
    /// The samples it owns.
    pub fn samples(&self) -> Range<usize> {
        let start = if self.index == 0 { 0 } else { self.from + 1 };
        start..self.to + 1
    }

    /// The path it traces, from its start turning point to its end.
    pub fn path(&self) -> RangeInclusive<usize> {
        self.from..=self.to
    }
}

/// The extreme force of a half-cycle in its direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// Sample index.
    pub index: usize,
    /// The force there (kN): the largest force of an increasing half-cycle,
    /// the smallest (most negative) of a decreasing one.
    pub value: f64,
}

/// The reversals, half-cycles and cycles of a signal.
///
/// ```
/// use hyst::data::{Cycles, Threshold};
/// // 0 -> 2 -> -2 -> 2 -> 0 with a wiggle at the first peak (of two equal
/// // extremes, the first is the reversal)
/// let x = [0.0, 1.0, 2.0, 1.9, 2.0, 1.0, 0.0, -1.0, -2.0, -1.0, 0.0, 1.0, 2.0, 1.0, 0.0];
/// let c = Cycles::find(&x, Threshold::Absolute(0.5)).unwrap();
/// assert_eq!(c.reversals(), &[2, 8, 12]);
/// assert_eq!(c.half_cycles().len(), 4); // the last, 2 -> 0, ends at no reversal
/// assert_eq!(c.cycles().len(), 2);
/// assert_eq!(c.complete_cycles(), 1);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Cycles {
    threshold: f64,
    len: usize,
    reversals: Vec<usize>,
    half_cycles: Vec<HalfCycle>,
    cycles: Vec<Cycle>,
}

/// Finds the reversals of `x` with an absolute threshold `h >= 0`.
fn reversals(x: &[f64], h: f64) -> Vec<usize> {
    let mut out = Vec::new();
    let Some(&first) = x.first() else {
        return out;
    };
    // Before the first move larger than h the direction is unknown.
    let (mut lo, mut hi) = (first, first);
    let mut dir: Option<Direction> = None;
    let mut extreme = 0;
    for (i, &v) in x.iter().enumerate() {
        match dir {
            None => {
                lo = lo.min(v);
                hi = hi.max(v);
                if v - lo > h {
                    dir = Some(Direction::Increasing);
                    extreme = i;
                } else if hi - v > h {
                    dir = Some(Direction::Decreasing);
                    extreme = i;
                }
            }
            Some(Direction::Increasing) => {
                if v > x[extreme] {
                    extreme = i;
                } else if x[extreme] - v > h {
                    out.push(extreme);
                    dir = Some(Direction::Decreasing);
                    extreme = i;
                }
            }
            Some(Direction::Decreasing) => {
                if v < x[extreme] {
                    extreme = i;
                } else if v - x[extreme] > h {
                    out.push(extreme);
                    dir = Some(Direction::Increasing);
                    extreme = i;
                }
            }
        }
    }
    out
}

impl Cycles {
    /// Finds the reversals of `x` and cuts it into half-cycles and cycles.
    pub fn find(x: &[f64], threshold: Threshold) -> Result<Cycles, CycleError> {
        if let Some(index) = x.iter().position(|v| !v.is_finite()) {
            return Err(CycleError::NotFinite { index });
        }
        let h = threshold.resolve(x)?;
        let reversals = reversals(x, h);
        let mut half_cycles = Vec::new();
        if !x.is_empty() {
            let last = x.len() - 1;
            let mut turning = Vec::with_capacity(reversals.len() + 2);
            turning.push(0);
            turning.extend(&reversals);
            // A reversal is confirmed by a later sample, so it is never the last.
            turning.push(last);
            for (k, w) in turning.windows(2).enumerate() {
                let (from, to) = (w[0], w[1]);
                half_cycles.push(HalfCycle {
                    index: k,
                    from,
                    to,
                    direction: if x[to] >= x[from] {
                        Direction::Increasing
                    } else {
                        Direction::Decreasing
                    },
                    complete: k < reversals.len(),
                });
            }
        }
        let cycles = half_cycles
            .chunks(2)
            .enumerate()
            .map(|(j, pair)| {
                let (first, last) = (&pair[0], &pair[pair.len() - 1]);
                Cycle {
                    index: j,
                    half_cycles: first.index..last.index + 1,
                    from: first.from,
                    to: last.to,
                    complete: pair.len() == 2 && last.complete,
                }
            })
            .collect();
        Ok(Cycles {
            threshold: h,
            len: x.len(),
            reversals,
            half_cycles,
            cycles,
        })
    }

    /// The absolute threshold used.
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// Number of samples of the signal.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the signal was empty.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Sample indices of the reversals, in order.
    pub fn reversals(&self) -> &[usize] {
        &self.reversals
    }

    /// The half-cycles, in order.
    pub fn half_cycles(&self) -> &[HalfCycle] {
        &self.half_cycles
    }

    /// The cycles, in order (the last may be incomplete).
    pub fn cycles(&self) -> &[Cycle] {
        &self.cycles
    }

    /// Number of complete cycles.
    pub fn complete_cycles(&self) -> usize {
        self.cycles.iter().filter(|c| c.complete).count()
    }

    /// The half-cycle owning each sample.
    pub fn half_cycle_of_samples(&self) -> Vec<usize> {
        let mut out = vec![0; self.len];
        for h in &self.half_cycles {
            out[h.samples()].fill(h.index);
        }
        out
    }

    fn check(&self, name_len: usize) -> Result<(), CycleError> {
        if name_len != self.len {
            return Err(CycleError::Length {
                expected: self.len,
                found: name_len,
            });
        }
        Ok(())
    }

    /// The extreme force of each half-cycle in its direction, over the samples
    /// it owns.
    pub fn peak_forces(&self, force: &[f64]) -> Result<Vec<Peak>, CycleError> {
        self.check(force.len())?;
        Ok(self
            .half_cycles
            .iter()
            .map(|h| {
                let s = h.direction.sign();
                let index = h.samples().fold(h.samples().start, |best, i| {
                    if s * force[i] > s * force[best] {
                        i
                    } else {
                        best
                    }
                });
                Peak {
                    index,
                    value: force[index],
                }
            })
            .collect())
    }

    /// `∫ F du` along each cycle's path (trapezoidal rule), in the product of
    /// the units (kN·mm = J for a record).
    pub fn energy(&self, displacement: &[f64], force: &[f64]) -> Result<Vec<f64>, CycleError> {
        self.check(displacement.len())?;
        self.check(force.len())?;
        Ok(self
            .cycles
            .iter()
            .map(|c| work(displacement, force, c.path()))
            .collect())
    }
}

/// `∫ F du` over `path` by the trapezoidal rule.
fn work(displacement: &[f64], force: &[f64], path: RangeInclusive<usize>) -> f64 {
    let (a, b) = (*path.start(), *path.end());
    (a..b)
        .map(|i| 0.5 * (force[i] + force[i + 1]) * (displacement[i + 1] - displacement[i]))
        .sum()
}
