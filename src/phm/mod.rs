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
//! reloading. A partial unloading that reverses before zero torque (or after
//! it, while the twist has not yet crossed zero) reloads back to the point
//! where the unloading began, along the least concave majorant of the path
//! it came down (a straight chord unless that path is pinched past zero
//! torque), and there resumes the branch it left (return-point memory); a
//! partial reloading along such a chord that reverses before the cycle
//! counter counts it goes back the way it came in the same way. A chord
//! hands over on reaching its target, so a turn exactly there is a turn on
//! the resumed branch. No closed cycle the tests search returns energy
//! (`docs/phm.md`, "Passivity"). The branches to resume
//! are kept in a stack of fixed capacity `M` (a `heapless::Deque`, capacity in
//! the type); when it is full the oldest entry is dropped (O(1)) and counted
//! in [`Phm::forgotten`] (gap G8 in `docs/phm.md`). The full list of decisions on the gaps the
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
mod work;

pub use backbone::{Backbone, BackboneError, BackboneRule, Direction};
pub use branch::{Branch, Kind};
pub use params::{PhmError, PhmParams};
pub use rules::{CoefficientSpec, Coefficients, Level, MAX_CYCLES, SPECS};
pub use work::{closed_cycle_work, work_along};

use crate::element::{Element, Response, StepError};
use crate::scalar::Scalar;
use heapless::Deque;

/// The state of a [`Phm`] element (committed or trial): where it is and on
/// which part of which branch. The branch geometry and the rule memory
/// ([`Phm::branch`], [`Phm::levels`]) live beside it and change only at
/// reversals, so a step copies only this small cursor.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct State<S> {
    /// Twist.
    pub twist: S,
    /// Torque.
    pub torque: S,
    /// d(torque)/d(twist) along the direction of the last increment.
    pub tangent: S,
    /// Direction of the last increment: +1 or -1 (0 in the virgin state).
    dir: S,
    /// What is being followed: the branch (`Rule`, `Chord`, `Ray`), the
    /// primary curve (`Envelope`) or the elastic line (`Elastic`).
    kind: Kind,
    /// Segment of the branch (or, on the primary curve, of the curve) the
    /// twist lies on.
    seg: u8,
    /// Which of the two slots holds the branch and the rule memory.
    slot: u8,
}

impl<S: Copy> State<S> {
    /// What the element is following.
    pub fn kind(&self) -> Kind {
        self.kind
    }
    /// Direction of the last increment: +1 or -1 (0 in the virgin state).
    pub fn dir(&self) -> S {
        self.dir
    }
}

/// A branch with the rule memory in force while it is followed. The
/// committed state's slot is never written by a trial.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Slot<S> {
    branch: Branch<S>,
    levels: [Level<S>; 2],
}

/// A remembered branch and where on it the element left it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Frame<S> {
    branch: Branch<S>,
    kind: Kind,
    seg: u8,
}

/// The memory of the trial: how many committed entries survive, and whether
/// the committed branch is pushed (a reversal happened).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Pending {
    keep: usize,
    push: bool,
}

impl Pending {
    fn clear(&mut self) {
        self.keep = 0;
        self.push = false;
    }
}

/// A PHM element driven by twist (see the [module docs](self)). `N` is the
/// capacity of each primary curve, `M` the depth of the inner-cycle memory.
#[derive(Clone, Debug)]
pub struct Phm<S: Scalar, const N: usize = 8, const M: usize = 16> {
    params: PhmParams<S, N>,
    slots: [Slot<S>; 2],
    committed: State<S>,
    trial: State<S>,
    pending: Pending,
    memory: Deque<Frame<S>, M>,
    /// `memory.len()`, kept here because a ring buffer computes it.
    depth: usize,
    forgotten: u32,
}

impl<S: Scalar, const N: usize, const M: usize> Phm<S, N, M> {
    /// An element in its virgin state.
    pub fn new(params: PhmParams<S, N>) -> Self {
        let virgin = Self::virgin(&params);
        let slot = Slot {
            branch: Branch::plain(Kind::Elastic, S::ZERO),
            levels: [Level::default(); 2],
        };
        Phm {
            params,
            slots: [slot; 2],
            committed: virgin,
            trial: virgin,
            pending: Pending {
                keep: 0,
                push: false,
            },
            memory: Deque::new(),
            depth: 0,
            forgotten: 0,
        }
    }

    fn virgin(params: &PhmParams<S, N>) -> State<S> {
        State {
            twist: S::ZERO,
            torque: S::ZERO,
            tangent: params.curves()[0].k1(),
            dir: S::ZERO,
            kind: Kind::Elastic,
            seg: 0,
            slot: 0,
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
    /// The branch of the trial state (as built at its reversal; see
    /// [`State::kind`] for what is followed now).
    pub fn branch(&self) -> &Branch<S> {
        &self.slots[self.trial.slot as usize].branch
    }
    /// What the rules remember of each direction (positive first), in the
    /// trial state.
    pub fn levels(&self) -> &[Level<S>; 2] {
        &self.slots[self.trial.slot as usize].levels
    }
    /// The number of committed branches waiting to be resumed (inner cycles
    /// in progress).
    pub fn memory_depth(&self) -> usize {
        self.depth
    }
    /// How many remembered branches were dropped because the memory (capacity
    /// `M`) was full. Non-zero means some inner cycle will not close on the
    /// point where it began but run on to the primary curve (gap G8).
    pub fn forgotten(&self) -> u32 {
        self.forgotten
    }

    /// The slot a trial may write: the one the committed state does not use.
    /// Makes `st` use it, copying the current slot there first.
    fn writable(&mut self, st: &mut State<S>) -> &mut Slot<S> {
        let other = 1 - self.committed.slot;
        if st.slot != other {
            self.slots[other as usize] = self.slots[st.slot as usize];
            st.slot = other;
        }
        &mut self.slots[other as usize]
    }

    /// Marks direction `side` cracked (the first time only: a slot copy).
    #[cold]
    #[inline(never)]
    fn crack(&mut self, st: &mut State<S>, side: usize) {
        if !self.slots[st.slot as usize].levels[side].cracked {
            self.writable(st).levels[side].cracked = true;
        }
    }

    #[inline]
    fn bound(&self, dir: S) -> &Backbone<S, N> {
        &self.params.curves()[if dir > S::ZERO { 0 } else { 1 }]
    }

    /// Elastic state: the uncracked part of both primary curves.
    fn elastic(&mut self, st: &mut State<S>, theta: S, dir: S) {
        let side = if theta < S::ZERO { 1 } else { 0 };
        let curve = &self.params.curves()[side];
        st.dir = dir;
        if theta.abs() > curve.cracking()[0] {
            st.seg = curve.locate(theta.abs()) as u8;
            let (y, k) = curve.bound_in(st.seg as usize, theta.abs());
            st.kind = Kind::Envelope;
            st.torque = signed(dir, y);
            st.tangent = k;
            self.crack(st, side);
        } else {
            st.torque = curve.k1() * theta;
            st.tangent = curve.k1();
        }
    }

    /// The twist reversed at the committed point: start the branch of the
    /// new direction `dir` and remember the one left. Out of line: a step
    /// without reversal stays small.
    #[cold]
    #[inline(never)]
    fn reverse(&mut self, st: &mut State<S>, pending: &mut Pending, dir: S) {
        let d = st.dir;
        let t = signed(d, st.torque);
        let current = &self.slots[st.slot as usize];
        let mut levels = current.levels;
        let from = if d > S::ZERO {
            Direction::Positive
        } else {
            Direction::Negative
        };
        let c = self.params.coefficients();
        let x = signed(d, st.twist);
        let theta_c = self.params.curves()[from.index()].cracking()[0];
        let band = c.0[rules::idx::CYCLE_BAND];
        // Two unloadings go back to where the branch followed began and
        // resume the branch left there, as a reloading before zero torque
        // does (gaps G3, G8 and G9 in docs/phm.md):
        // - from a chord (a partial reloading) that the counter does not
        //   count: by the rules, as if from the primary curve, its line could
        //   run flatter than the chord and above it, so the excursion never
        //   closed (0 -> 8 -> 2 -> 3 -> 2 on the test curve came back to 2 at
        //   a torque of 1.66 instead of 0.04; found by review). One the
        //   counter counts is a repeated cycle: the rules;
        // - from a rule branch whose torque has crossed zero while its twist
        //   has not (x <= 0): eqs 1-3 would take theta_m < 0, crept to zero
        //   torque and reloaded inside the path they came up on; cycles
        //   repeated between such a point and the branch's start returned
        //   energy (-1.28 a cycle between -4.5 and -1 after -11.5, -0.625).
        // - from the primary curve's torque cap, reached by such a branch
        //   before zero twist (G9): eqs 1-3 took theta_m < 0 there too, and
        //   on a column curve cycles between the cap and the branch below it
        //   returned 19.4 each (one of 2,036 closed cycles on random curves
        //   with the thesis' coefficients).
        let retrace = st.kind == Kind::Chord && !levels[from.index()].counts(x, theta_c, band);
        let back = retrace
            || match st.kind {
                Kind::Rule => !(x > S::ZERO),
                Kind::Envelope => current.branch.capped_before_zero_twist(x),
                _ => false,
            };
        let branch = if t > S::ZERO && !back {
            // Unloading: rules 2-4 from this point. T_m is the torque of the
            // path at theta_m (G4); past a chord's target the path is the
            // branch resumed there (remembered two entries down), not the
            // chord extended: after 8, -8, 7.7, 7.0, 7.65 on the test curve
            // that gave 19.84 where the path is at 18.26 (found by review).
            let on_path = |xm: S| {
                let (mut b, mut kind, mut below) = (&current.branch, st.kind, self.depth);
                while kind == Kind::Chord && xm > b.last()[0] && below >= 2 {
                    below -= 2;
                    let Some(f) = self.memory.get(below) else {
                        break;
                    };
                    (b, kind) = (&f.branch, f.kind);
                }
                if kind == Kind::Envelope || !(xm < b.contact) {
                    self.bound(d).bound(xm).0
                } else {
                    b.torque_at(xm)
                }
            };
            levels[from.index()].count_unloading((x, t), on_path, theta_c, band);
            rules::unloading_branch(c, self.params.curves(), from, [x, t], &levels)
        } else {
            // Reloading before zero torque, or one of the two above: back
            // to where the branch followed began: along a rule branch's
            // concave majorant, or the way a chord (or ray) came.
            let from = [signed(dir, st.twist), signed(dir, st.torque)];
            let bound = self.bound(dir);
            let (path, seg) = if st.kind == Kind::Envelope {
                // The branch up to the cap, then along the cap.
                let path = current.branch.up_to_contact(self.bound(d));
                (path, path.n - 1)
            } else {
                (current.branch, st.seg)
            };
            if path.kind == Kind::Rule {
                Branch::back(dir, from, &path, seg, bound)
            } else {
                Branch::retrace(dir, from, &path, seg, bound)
            }
        };
        st.kind = branch.kind;
        st.seg = 0;
        st.dir = dir;
        st.slot = 1 - self.committed.slot;
        self.slots[st.slot as usize] = Slot { branch, levels };
        pending.push = true;
    }

    /// Removes the chord's own entry and the entry of its target; returns
    /// the frame to resume, or `None` if they were forgotten.
    fn pop_two(memory: &Deque<Frame<S>, M>, pending: &mut Pending) -> Option<Frame<S>> {
        let available = pending.keep + pending.push as usize;
        if available < 2 {
            pending.clear();
            return None;
        }
        if pending.push {
            pending.push = false;
        } else {
            pending.keep -= 1;
        }
        pending.keep -= 1;
        memory.get(pending.keep).copied()
    }

    /// The branch met the primary curve (rule 6): follow it from here on;
    /// nothing remembered can be returned to any more, unless it met the
    /// torque cap before zero twist (G9): a reversal there still goes back
    /// to where the branch began, so the memory stays until the twist
    /// crosses zero ([`walk`](Self::walk)).
    #[cold]
    #[inline(never)]
    fn reach_envelope(&mut self, st: &mut State<S>, pending: &mut Pending, x: S) {
        st.kind = Kind::Envelope;
        st.seg = self.bound(st.dir).locate(x) as u8;
        if !self.slots[st.slot as usize]
            .branch
            .capped_before_zero_twist(x)
        {
            pending.clear();
        }
        self.crack(st, if st.dir > S::ZERO { 0 } else { 1 });
    }

    /// An inner cycle closed: resume the remembered branch.
    #[cold]
    #[inline(never)]
    fn resume(&mut self, st: &mut State<S>, f: Frame<S>) {
        st.kind = f.kind;
        st.seg = f.seg;
        self.writable(st).branch = f.branch;
    }

    /// Applies the trial's changes to the memory: drops the entries it
    /// closed, then pushes the branch left at its reversal (the oldest entry
    /// goes if the memory is full, counted in `forgotten`, gap G8).
    #[cold]
    #[inline(never)]
    fn commit_memory(&mut self) {
        let p = self.pending;
        self.memory.truncate(p.keep);
        if p.push {
            let c = &self.committed;
            let frame = Frame {
                branch: self.slots[c.slot as usize].branch,
                kind: c.kind,
                seg: c.seg,
            };
            if self.memory.is_full() {
                // A ring buffer: dropping the oldest entry is O(1).
                self.memory.pop_front();
                self.forgotten = self.forgotten.saturating_add(1);
            }
            // Room was made just above (with M = 0 the entry is counted in
            // `forgotten` instead).
            let _ = self.memory.push_back(frame);
        }
        self.depth = self.memory.len();
        self.pending = Pending {
            keep: self.depth,
            push: false,
        };
    }

    /// Follows the branch in its direction of motion up to `theta`.
    fn walk(&mut self, st: &mut State<S>, pending: &mut Pending, theta: S) {
        let dir = st.dir;
        let x = signed(dir, theta);
        'walk: loop {
            let b = &self.slots[st.slot as usize].branch;
            // A chord's contact past its target lies on its ray, which is
            // followed only once the chord has become a ray: at the target
            // the remembered branch resumes. (A step across both went
            // straight to the primary curve: one step from 4 to 7 after 8, 2,
            // 5, 4 on the test curve gave a torque of 20, small steps 16.67.)
            // (A chord's last vertex is its target; one that meets the
            // primary curve exactly there hands over first, and the branch
            // resumed follows the curve.)
            let on_ray = st.kind == Kind::Chord && !(b.contact < b.last()[0]);
            if st.kind != Kind::Envelope && !on_ray && !(x < b.contact) {
                self.reach_envelope(st, pending, x);
            }
            if st.kind == Kind::Envelope {
                if x > S::ZERO && pending.keep + pending.push as usize != 0 {
                    // Past zero twist on the cap (G9): nothing to go back to.
                    pending.clear();
                }
                let (y, k) = self.bound(dir).follow(&mut st.seg, x);
                st.torque = signed(dir, y);
                st.tangent = k;
                return;
            }
            let b = &self.slots[st.slot as usize].branch;
            let mut resumed = None;
            // A chord hands over on reaching its target, not only past it: a
            // turn exactly there is a turn on the remembered branch (it used
            // to retrace the chord and remember one more entry, so cycles
            // repeated between two fixed twists did no work after the first
            // and filled the memory).
            while st.seg + 1 < b.n && {
                let next = b.v[st.seg as usize + 1][0];
                x > next || (x == next && st.kind == Kind::Chord && st.seg + 2 == b.n)
            } {
                st.seg += 1;
                match st.kind {
                    Kind::Rule if st.seg == b.across => pending.clear(),
                    Kind::Chord if st.seg + 1 == b.n => {
                        match Self::pop_two(&self.memory, pending) {
                            Some(f) => resumed = Some(f),
                            None => {
                                // Its ray now: check the ray's contact.
                                st.kind = Kind::Ray;
                                continue 'walk;
                            }
                        }
                        break;
                    }
                    _ => {}
                }
            }
            if let Some(f) = resumed {
                self.resume(st, f);
                continue;
            }
            let (y, k) = b.at(st.seg, x);
            st.torque = signed(dir, y);
            st.tangent = k;
            return;
        }
    }

    /// The trial at `theta` from the committed state. On success the trial
    /// state and its memory changes are stored; on failure only the slot
    /// the committed state does not use may have been written (see
    /// [`Element::set_trial`] for how the pending trial is then restored).
    /// Inlined: it is the step; the second caller is the cold
    /// [`restore_pending`](Self::restore_pending).
    #[inline(always)]
    fn try_trial(&mut self, theta: S) -> Result<Response<S>, StepError> {
        let mut st = self.committed;
        if !theta.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        let mut pending = Pending {
            keep: self.depth,
            push: false,
        };
        if theta != st.twist {
            let dir = if theta > st.twist { S::ONE } else { -S::ONE };
            if st.kind == Kind::Elastic {
                self.elastic(&mut st, theta, dir);
            } else {
                if dir != st.dir {
                    self.reverse(&mut st, &mut pending, dir);
                    if !self.slots[st.slot as usize].branch.is_defined() {
                        return Err(StepError::NonFiniteState);
                    }
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

    /// After a failed trial: if the pending trial's branch and rule memory
    /// sit in the slot the failed trial may have written, compute the
    /// pending trial again (it succeeded before from the same committed
    /// state, and gives the same slot, state and memory changes).
    #[cold]
    #[inline(never)]
    fn restore_pending(&mut self) {
        if self.trial.slot != self.committed.slot {
            let _ = self.try_trial(self.trial.twist);
        }
    }
}

impl<S: Scalar, const N: usize, const M: usize> Element<S> for Phm<S, N, M> {
    /// A trial that fails changes nothing (the [`Element`] contract): the
    /// committed state and the last successful trial stay as they were, so
    /// that [`commit`](Element::commit) after a failed trial commits the
    /// last successful one. A trial writes the slot the committed state does
    /// not use, which may hold the pending trial's branch and rule memory; if
    /// it fails after writing it, the pending trial is computed again (it
    /// succeeded before and depends only on the committed state, so it gives
    /// the same slot, state and memory changes). Only failing steps pay for
    /// this.
    fn set_trial(&mut self, theta: S) -> Result<Response<S>, StepError> {
        let r = self.try_trial(theta);
        if r.is_err() {
            self.restore_pending();
        }
        r
    }

    fn commit(&mut self) {
        if self.pending.push || self.pending.keep != self.depth {
            self.commit_memory();
        }
        self.committed = self.trial;
    }

    fn revert(&mut self) {
        self.trial = self.committed;
        self.pending = Pending {
            keep: self.depth,
            push: false,
        };
    }

    fn reset(&mut self) {
        *self = Self::new(self.params.clone());
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

/// `v` with the sign of `dir` (+1 or -1) applied: a negation, not a
/// multiplication (which costs a wide multiply and saturation checks in fixed
/// point).
#[inline(always)]
fn signed<S: Scalar>(dir: S, v: S) -> S {
    if dir < S::ZERO {
        -v
    } else {
        v
    }
}

#[cfg(test)]
mod tests;
