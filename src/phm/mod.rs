//! The polygonal hysteresis model (PHM) of circular RC columns under cyclic
//! torsion (thesis ch. 5) as element state.
//!
//! [`Phm`] is a twist-driven element implementing [`Element`]: given a trial
//! twist it returns torque and tangent. The model is a primary curve per
//! direction ([`Backbone`], §5.2.1) and rules that send the path from control
//! point to control point ([`rules`], §5.2.2-5.2.3): unloading by eqs 1-3
//! towards a residual twist, reloading towards the other direction's cracking
//! point (rule 2), along a degraded stiffness (eq. 4) or along a pinched path
//! (eqs 5-6), and back onto the primary curve (rule 6).
//!
//! # How a step works
//!
//! Every path between two reversals is a [`Branch`]: a polyline built once,
//! at the reversal (that is where the thesis' equations, with their powers,
//! are evaluated), together with the exact twist at which it meets the
//! primary curve. A step in the same direction only finds its segment and
//! interpolates, so its cost is a few comparisons and one multiply-add, and
//! the result does not depend on the step size.
//!
//! # Inner cycles and memory
//!
//! The thesis' rules describe unloading from the primary curve and full
//! reloading. A partial unloading that reverses before zero torque reloads
//! along a chord back to the point where the unloading began and there
//! resumes the branch it left (return-point memory). The branches to resume
//! are kept in a stack of fixed capacity `M` (heapless, in the type); when it
//! is full the oldest entry is dropped and counted in [`Phm::forgotten`]
//! (gap G8 in `docs/phm.md`). The full list of decisions on the gaps the
//! thesis leaves is in `docs/phm.md`.
//!
//! # Units
//!
//! Twist and torque in any consistent units (deg and kN m, or mm and kN as in
//! the OpenSees comparison); the rules are ratios. For [`Fixed`](crate::Fixed)
//! keep both within about ±30000 with a resolution of 2^-16.
//!
//! # Example
//!
//! ```
//! use hysteresis::phm::{Coefficients, Phm, PhmParams};
//! use hysteresis::Element;
//!
//! let p = PhmParams::<f64>::symmetric(&[[1.0, 5.0], [4.0, 6.5], [8.0, 5.5]], Coefficients::thesis())
//!     .unwrap();
//! let mut el: Phm<f64> = Phm::new(p);
//! // Up the primary curve to 5 (past yield at 4): 6.5 - 0.25 * 1 = 6.25.
//! for i in 1..=50 {
//!     el.set_trial(i as f64 * 0.1).unwrap();
//!     el.commit();
//! }
//! assert!((el.response().force - 6.25).abs() < 1e-12);
//! // Unloading (eq. 1 with the stiffness cap): steep, with the initial stiffness 5.
//! let r = el.set_trial(4.99).unwrap();
//! assert!((r.tangent - 5.0).abs() < 1e-12);
//! ```

mod backbone;
mod branch;
mod params;
pub mod rules;
#[cfg(any(test, feature = "selftest"))]
pub mod selftest;

pub use backbone::{Backbone, BackboneError, BackboneRule, Direction};
pub use branch::{Branch, Kind};
pub use params::{PhmError, PhmParams};
pub use rules::{CoefficientSpec, Coefficients, Level, SPECS};

use crate::element::{Element, Response, StepError};
use crate::scalar::Scalar;
use heapless::Vec;

/// The state of a [`Phm`] element (committed or trial).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct State<S> {
    /// Twist.
    pub twist: S,
    /// Torque.
    pub torque: S,
    /// d(torque)/d(twist) along the direction of the last increment.
    pub tangent: S,
    /// The branch being followed.
    pub branch: Branch<S>,
    /// What the rules remember of each direction (positive first).
    pub levels: [Level<S>; 2],
}

/// The memory of the trial: how many committed entries survive and the one
/// entry a reversal adds.
#[derive(Clone, Copy, Debug)]
struct Pending<S> {
    keep: usize,
    pushed: Option<Branch<S>>,
}

impl<S: Scalar> Pending<S> {
    fn clear(&mut self) {
        self.keep = 0;
        self.pushed = None;
    }
}

/// A PHM element driven by twist (see the [module docs](self)). `N` is the
/// capacity of each primary curve, `M` the depth of the inner-cycle memory.
#[derive(Clone, Debug)]
pub struct Phm<S: Scalar, const N: usize = 8, const M: usize = 16> {
    params: PhmParams<S, N>,
    committed: State<S>,
    trial: State<S>,
    pending: Pending<S>,
    memory: Vec<Branch<S>, M>,
    forgotten: u32,
}

impl<S: Scalar, const N: usize, const M: usize> Phm<S, N, M> {
    /// An element in its virgin state.
    pub fn new(params: PhmParams<S, N>) -> Self {
        let virgin = Self::virgin(&params);
        Phm {
            params,
            committed: virgin,
            trial: virgin,
            pending: Pending {
                keep: 0,
                pushed: None,
            },
            memory: Vec::new(),
            forgotten: 0,
        }
    }

    fn virgin(params: &PhmParams<S, N>) -> State<S> {
        State {
            twist: S::ZERO,
            torque: S::ZERO,
            tangent: params.curves()[0].k1(),
            branch: Branch::plain(Kind::Elastic, S::ZERO),
            levels: [Level::default(); 2],
        }
    }

    /// The parameters.
    pub fn params(&self) -> &PhmParams<S, N> {
        &self.params
    }
    /// The committed state.
    pub fn committed(&self) -> &State<S> {
        &self.committed
    }
    /// The trial state (equal to the committed one after commit or revert).
    pub fn trial(&self) -> &State<S> {
        &self.trial
    }
    /// The number of committed branches waiting to be resumed (inner cycles
    /// in progress).
    pub fn memory_depth(&self) -> usize {
        self.memory.len()
    }
    /// How many remembered branches were dropped because the memory (capacity
    /// `M`) was full. Non-zero means some inner cycle will not close on the
    /// point where it began but run on to the primary curve (gap G8).
    pub fn forgotten(&self) -> u32 {
        self.forgotten
    }

    /// Elastic state: the uncracked part of both primary curves.
    fn elastic(&self, st: &mut State<S>, theta: S, dir: S) {
        let [pos, neg] = self.params.curves();
        let (curve, side) = if theta < S::ZERO { (neg, 1) } else { (pos, 0) };
        if theta.abs() > curve.cracking()[0] {
            st.branch = Branch::plain(Kind::Envelope, dir);
            st.levels[side].cracked = true;
            let (y, k) = curve.bound(theta.abs());
            st.torque = dir * y;
            st.tangent = k;
        } else {
            st.branch.dir = dir;
            st.torque = curve.k1() * theta;
            st.tangent = curve.k1();
        }
    }

    /// The twist reversed at the committed point: start the branch of the
    /// new direction `dir` and remember the one left.
    fn reverse(&self, st: &mut State<S>, pending: &mut Pending<S>, dir: S) {
        let old = st.branch;
        let d = old.dir;
        let t = d * st.torque;
        let q = [dir * st.twist, dir * st.torque];
        if t > S::ZERO {
            // Unloading: rules 2-4 from this point, whatever branch it is on.
            let from = if d > S::ZERO {
                Direction::Positive
            } else {
                Direction::Negative
            };
            let c = self.params.coefficients();
            let x = d * st.twist;
            let theta_c = self.params.curves()[from.index()].cracking()[0];
            st.levels[from.index()].count_unloading(x, t, theta_c, c.0[rules::idx::CYCLE_BAND]);
            st.branch = rules::unloading_branch(c, self.params.curves(), from, [x, t], &st.levels);
        } else {
            // Reloading before zero torque: back to where the unloading began.
            let to = [-old.x[0], -old.y[0]];
            st.branch = Branch::chord(dir, q, to, self.bound(dir));
        }
        pending.pushed = Some(old);
    }

    #[inline]
    fn bound(&self, dir: S) -> &Backbone<S, N> {
        &self.params.curves()[if dir > S::ZERO { 0 } else { 1 }]
    }

    /// Removes the chord's own entry and the entry of its target; returns
    /// the branch to resume, or `None` if they were forgotten.
    fn pop_two(&self, pending: &mut Pending<S>) -> Option<Branch<S>> {
        let available = pending.keep + pending.pushed.is_some() as usize;
        if available < 2 {
            pending.clear();
            return None;
        }
        if pending.pushed.take().is_none() {
            pending.keep -= 1;
        }
        pending.keep -= 1;
        Some(self.memory[pending.keep])
    }

    /// Follows the branch in its direction of motion up to `theta`.
    fn walk(&self, st: &mut State<S>, pending: &mut Pending<S>, theta: S) {
        let dir = st.branch.dir;
        let x = dir * theta;
        loop {
            let b = &mut st.branch;
            if b.kind != Kind::Envelope && !(x < b.contact) {
                b.kind = Kind::Envelope;
                pending.clear();
            }
            if b.kind == Kind::Envelope {
                let side = if dir > S::ZERO { 0 } else { 1 };
                st.levels[side].cracked = true;
                let (y, k) = self.bound(dir).bound(x);
                st.torque = dir * y;
                st.tangent = k;
                return;
            }
            let mut resumed = None;
            while (b.seg as usize) + 1 < b.n as usize && x > b.x[b.seg as usize + 1] {
                b.seg += 1;
                match b.kind {
                    Kind::Rule if b.seg == b.zero => pending.clear(),
                    Kind::Chord if b.seg + 1 == b.n => {
                        match self.pop_two(pending) {
                            Some(r) => resumed = Some(r),
                            None => b.kind = Kind::Ray,
                        }
                        break;
                    }
                    _ => {}
                }
            }
            if let Some(r) = resumed {
                st.branch = r;
                continue;
            }
            let (y, k) = b.at(x);
            st.torque = dir * y;
            st.tangent = k;
            return;
        }
    }
}

impl<S: Scalar, const N: usize, const M: usize> Element<S> for Phm<S, N, M> {
    fn set_trial(&mut self, theta: S) -> Result<Response<S>, StepError> {
        let c = &self.committed;
        let delta = theta - c.twist;
        if !(theta.is_finite() && delta.is_finite()) {
            return Err(StepError::NonFiniteInput);
        }
        let mut st = *c;
        let mut pending = Pending {
            keep: self.memory.len(),
            pushed: None,
        };
        if delta != S::ZERO {
            let dir = if delta > S::ZERO { S::ONE } else { -S::ONE };
            if st.branch.kind == Kind::Elastic {
                self.elastic(&mut st, theta, dir);
            } else {
                if dir != st.branch.dir {
                    self.reverse(&mut st, &mut pending, dir);
                }
                self.walk(&mut st, &mut pending, theta);
            }
            st.twist = theta;
        }
        if !(st.torque.is_finite() && st.tangent.is_finite()) {
            return Err(StepError::NonFiniteState);
        }
        self.trial = st;
        self.pending = pending;
        Ok(Response {
            force: st.torque,
            tangent: st.tangent,
        })
    }

    fn commit(&mut self) {
        let p = &mut self.pending;
        self.memory.truncate(p.keep);
        if let Some(b) = p.pushed.take() {
            if self.memory.is_full() {
                if !self.memory.is_empty() {
                    self.memory.remove(0);
                }
                self.forgotten = self.forgotten.saturating_add(1);
            }
            // Room was made just above (with M = 0 the entry is counted in
            // `forgotten` instead).
            let _ = self.memory.push(b);
        }
        p.keep = self.memory.len();
        self.committed = self.trial;
    }

    fn revert(&mut self) {
        self.trial = self.committed;
        self.pending = Pending {
            keep: self.memory.len(),
            pushed: None,
        };
    }

    fn reset(&mut self) {
        self.committed = Self::virgin(&self.params);
        self.trial = self.committed;
        self.memory.clear();
        self.pending = Pending {
            keep: 0,
            pushed: None,
        };
        self.forgotten = 0;
    }

    fn response(&self) -> Response<S> {
        Response {
            force: self.trial.torque,
            tangent: self.trial.tangent,
        }
    }

    fn displacement(&self) -> S {
        self.committed.twist
    }
}

#[cfg(test)]
mod tests;
