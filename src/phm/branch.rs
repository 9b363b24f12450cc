//! A branch of the hysteresis loop: the piecewise-linear path the element
//! follows between two reversals (thesis §5.2: "paths joining successive
//! control points are called branches").
//!
//! A branch is built once, when the twist reverses, and then only evaluated,
//! which keeps a step cheap. It is stored in the coordinates of its motion
//! `x = dir * twist`, `y = dir * torque`, so that x always increases along it.
//! Past its last vertex it continues as a ray with the last segment's slope.
//!
//! While loading in direction `dir` the torque may not exceed the bound of
//! that direction (the primary curve, rule 6 of §5.2.3). Both the branch and
//! the bound are piecewise linear, so the twist at which the branch first
//! meets the bound (`contact`) is found exactly when the branch is built; a
//! step then only compares its twist with `contact`, and the result does not
//! depend on the step size.

use super::backbone::Backbone;
use crate::scalar::Scalar;

/// The most vertices a branch needs: the reversal point, two unloading
/// control points, the zero-torque point, the crack-closing point and the
/// reloading target (eqs 1-6).
pub(crate) const VERTICES: usize = 6;

/// What a branch is and what happens at its special vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Kind {
    /// Virgin, uncracked state: the elastic part of the primary curve in both
    /// directions (unloading rule 1, loading rule 1).
    Elastic,
    /// On the primary curve (bound) of the direction of motion (rule 6).
    Envelope,
    /// A branch built by the thesis' rules (unloading eqs 1-3, then reloading
    /// by eq 4, 5-6 or towards cracking); crossing its zero-torque vertex
    /// ends the unloading.
    Rule,
    /// Reloading after a partial unloading: heads back to the point where the
    /// unloading began and resumes the branch that was left there.
    Chord,
    /// A chord whose resume point was forgotten (memory full): goes on
    /// straight until it meets the primary curve.
    Ray,
}

/// A branch of the hysteresis loop: the polyline between two reversals, in
/// the coordinates of its motion, with its contact twist on the primary curve.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Branch<S> {
    pub(crate) kind: Kind,
    /// Direction of motion: +1 or -1 (0 only for the virgin elastic state).
    pub(crate) dir: S,
    pub(crate) n: u8,
    /// Index of the first vertex at zero torque or beyond (rule branches).
    pub(crate) zero: u8,
    /// Index of the first vertex at or past both zero torque and zero twist
    /// (torque and twist on the side the branch reloads towards). Passing it
    /// forgets the remembered branches (gap G8): until then a reversal goes
    /// back to where the branch began (G3, G9).
    pub(crate) across: u8,
    /// `[x, y, k]` of each vertex: its coordinates and the slope from it to
    /// the next one (for the last vertex, the slope of the ray).
    pub(crate) v: [[S; 3]; VERTICES],
    /// First x at which the branch reaches the bound (`S::MAX`: never).
    pub(crate) contact: S,
}

impl<S: Scalar> Branch<S> {
    /// A branch without vertices (elastic or envelope).
    pub(crate) fn plain(kind: Kind, dir: S) -> Self {
        Branch {
            kind,
            dir,
            n: 0,
            zero: u8::MAX,
            across: u8::MAX,
            v: [[S::ZERO; 3]; VERTICES],
            contact: S::MAX,
        }
    }

    /// A branch starting at `start` (motion coordinates).
    pub(crate) fn starting(kind: Kind, dir: S, start: [S; 2]) -> Self {
        let mut b = Self::plain(kind, dir);
        b.v[0][0] = start[0];
        b.v[0][1] = start[1];
        b.n = 1;
        if !(start[1] < S::ZERO) {
            b.zero = 0;
        }
        if !(start[0] < S::ZERO || start[1] < S::ZERO) {
            b.across = 0;
        }
        b
    }

    /// The vertices in motion coordinates.
    pub fn vertices(&self) -> impl Iterator<Item = [S; 2]> + '_ {
        (0..self.n as usize).map(|i| [self.v[i][0], self.v[i][1]])
    }

    /// The kind of branch as built (the element's [`State::kind`](super::State::kind)
    /// tells whether it has since met the primary curve).
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// Direction of motion along the branch (+1 or -1).
    pub fn dir(&self) -> S {
        self.dir
    }

    /// Whether every vertex, slope and the contact is a number (not NaN). A
    /// coefficient far outside the fits can overflow a power (eq. 4's
    /// `mu^eq4_b` with `eq4_b = 1000`) and make the contact NaN, and the
    /// element then jumped to the primary curve without an error (found by
    /// review). An infinite or saturated contact is one never reached, as
    /// `S::MAX`; fixed point has no NaN.
    pub(crate) fn is_defined(&self) -> bool {
        let used = &self.v[..(self.n as usize).min(VERTICES)];
        core::iter::once(&self.contact)
            .chain(used.iter().flatten())
            .all(|c| c.partial_cmp(c).is_some())
    }

    #[inline]
    pub(crate) fn last(&self) -> [S; 2] {
        let i = self.n as usize - 1;
        [self.v[i][0], self.v[i][1]]
    }

    fn append(&mut self, x: S, y: S) {
        let i = self.n as usize;
        // A rule branch has at most VERTICES points by construction (P, two
        // unloading points, su, cr, m'); a chord has two.
        if i >= VERTICES {
            return;
        }
        self.v[i - 1][2] = (y - self.v[i - 1][1]) / (x - self.v[i - 1][0]);
        self.v[i][0] = x;
        self.v[i][1] = y;
        if self.zero == u8::MAX && !(y < S::ZERO) {
            self.zero = i as u8;
        }
        if self.across == u8::MAX && !(x < S::ZERO || y < S::ZERO) {
            self.across = i as u8;
        }
        self.n += 1;
    }

    /// Appends an unloading control point, projected so that the unloading
    /// stays monotone and convex (gap G2 in `docs/phm.md`): its torque is
    /// clamped at zero, and the segment is no stiffer than `cap`, which then
    /// becomes this segment's slope (so no later segment is stiffer). A point
    /// whose torque does not drop below the previous one is dropped (a flat
    /// segment would stop the unloading short of zero torque).
    pub(crate) fn push_unloading(&mut self, p: [S; 2], cap: &mut S) {
        let [x0, y0] = self.last();
        let y = p[1].min(S::ZERO);
        if !(y > y0) {
            // No torque drop: the point adds nothing to the unloading.
            return;
        }
        let x = p[0].max(x0 + (y - y0) / *cap);
        if x > x0 {
            self.append(x, y);
            let k = self.v[self.n as usize - 2][2];
            if k < *cap {
                *cap = k;
            }
        }
    }

    /// Appends a reloading control point (loading rules 2-5, eqs 4-6),
    /// projected like the unloading points (gaps G5 and G10 in
    /// `docs/phm.md`): the torque never falls while reloading (it is raised
    /// to the previous torque if needed), and the segment is no stiffer than
    /// `cap` (`k_T1` of the direction reloaded towards): a point that the
    /// equations put closer is moved along its torque level to where that
    /// slope reaches it. So a point is only dropped when it lies behind the
    /// previous one at the previous torque (it adds nothing), never because
    /// eq. 5a put the crack-closing twist `theta_cr` at or past `theta_m`.
    pub(crate) fn push_rising(&mut self, p: [S; 2], cap: S) {
        let [x0, y0] = self.last();
        let y = p[1].max(y0);
        let x = p[0].max(x0 + (y - y0) / cap);
        if x > x0 {
            self.append(x, y);
        }
    }

    /// Closes the branch: the ray past the last vertex keeps the last slope,
    /// and the contact with `bound` (the primary curve of the direction of
    /// motion) is computed.
    pub(crate) fn finish<const N: usize>(&mut self, bound: &Backbone<S, N>) {
        let n = self.n as usize;
        if n >= 2 {
            self.v[n - 1][2] = self.v[n - 2][2];
        }
        self.contact = self.first_contact(bound);
    }

    /// Closes a rule branch like [`finish`](Self::finish), but the ray past
    /// the last vertex must rise (gap G10): where the reloading rules left
    /// their range and the last segment does not rise (eq. 6 puts `T'_m` at
    /// or below the pinched line of eq. 5, eq. 4 gives a slope <= 0, or the
    /// last vertex is the reversal point itself), the ray rises with `k`
    /// (`k_T1` of the direction reloaded towards), so that it meets the
    /// primary curve (rule 6), whose tail is flat (G7).
    pub(crate) fn finish_rising<const N: usize>(&mut self, bound: &Backbone<S, N>, k: S) {
        self.finish(bound);
        let last = self.n as usize - 1;
        if !(self.v[last][2] > S::ZERO) {
            self.v[last][2] = k;
            self.contact = self.first_contact(bound);
        }
    }

    /// The first x >= x[0] where the branch reaches the bound: both are
    /// linear between the union of their breakpoints, so it is enough to
    /// look at those and interpolate.
    fn first_contact<const N: usize>(&self, bound: &Backbone<S, N>) -> S {
        let n = self.n as usize;
        // Before the segment that ends at the zero-torque vertex the torque
        // is of the other sign and cannot reach the bound (which is
        // positive): start the search on that segment. (Not at the vertex
        // itself: the segment crosses zero torque and, when the unloading
        // points were dropped because the reversal was a hair above zero
        // torque, runs straight to the reloading target and may cross the
        // bound before it.)
        let mut i = if (self.zero as usize) < n {
            (self.zero as usize).saturating_sub(1)
        } else {
            n - 1
        };
        let mut a = self.v[i][0];
        let mut j = bound.locate(a);
        let mut da = self.v[i][1] - bound.bound_in(j, a).0;
        if !(da < S::ZERO) {
            return a;
        }
        loop {
            let next_vertex = (i + 1 < n).then(|| self.v[i + 1][0]);
            let next_break = (j + 1 < bound.segments()).then(|| bound.breakpoint(j + 1));
            let b = match (next_vertex, next_break) {
                (None, None) => {
                    let closing = self.v[i][2] - bound.bound_in(j, a).1;
                    return if closing > S::ZERO {
                        a - da / closing
                    } else {
                        S::MAX
                    };
                }
                (Some(v), None) => v,
                (None, Some(w)) => w,
                (Some(v), Some(w)) => v.min(w),
            };
            // At a vertex of either polyline its own torque, not the segment
            // interpolated to it: rule 2 aims exactly at the cracking point,
            // a corner of the bound, and a unit of rounding either way
            // decided whether the branch met the primary curve there (found
            // by review: 29 of 400 first reloadings of the docs' column
            // missed it in f64, and f32 and Q15.16 missed others, up to 45%
            // of peak torque apart).
            // `S::line`, as the bound's value is computed: in Q15.16 one
            // range check on the sum, so a product out of range whose sum is
            // not (a steep segment from a low torque) stays exact. (The
            // review's stiff column needed more: the sum itself out of
            // range, below.)
            let yb = if next_vertex == Some(b) {
                self.v[i + 1][1]
            } else {
                S::line(self.v[i][1], self.v[i][2], b, self.v[i][0])
            };
            let tb = if next_break == Some(b) {
                bound.bound_in(j + 1, b).0
            } else {
                bound.bound_in(j, b).0
            };
            let db = yb - tb;
            if !(db < S::ZERO) {
                // A steep segment evaluated at a far breakpoint can leave
                // Q15.16's range while its slope does not (9,504 kN m/deg
                // over 5.3 deg: found by review), and the interpolation then
                // put the contact at `a`: the crossing from the two slopes
                // instead. (A saturated slope keeps the interpolation, whose
                // result the step refuses.) Floats never take this path.
                if !db.is_finite() && self.v[i][2].is_finite() {
                    return a - da / (self.v[i][2] - bound.bound_in(j, a).1);
                }
                return a + (b - a) * (-da / (db - da));
            }
            if next_vertex == Some(b) {
                i += 1;
            }
            if next_break == Some(b) {
                j += 1;
            }
            a = b;
            da = db;
        }
    }

    /// A chord from `from` back to `to` (motion coordinates, `to` ahead).
    pub(crate) fn chord<const N: usize>(
        dir: S,
        from: [S; 2],
        to: [S; 2],
        bound: &Backbone<S, N>,
    ) -> Self {
        let mut b = Self::starting(Kind::Chord, dir, from);
        if to[0] > from[0] {
            b.append(to[0], to[1]);
        } else {
            // Cannot happen for a reversal away from the branch start; keep a
            // well-defined branch anyway.
            b.kind = Kind::Ray;
            b.v[0][2] = bound.k1();
        }
        b.finish(bound);
        b
    }

    /// The way back from `from` (motion coordinates of the return) to the
    /// start of `path`, the rule branch followed up to `from` on its segment
    /// `seg` (gap G9 in `docs/phm.md`): the least concave majorant of that
    /// path, so that the return lies on or above it everywhere and the
    /// excursion dissipates. Past zero torque a rule branch reloads along a
    /// pinched line that can be steeper than the unloading before it, and a
    /// straight chord back cut below the path: cycles between such a point
    /// and the branch's start returned energy (after -2.75, 11.375 on the
    /// test curve, 0.64 a cycle between 0.625 and 4.375; found when a turn at
    /// a chord's target first resumed the branch). The return follows the
    /// path back to its zero-torque vertex where the path is not concave,
    /// then goes straight to the start. The unloading part of a rule branch
    /// is concave as seen from the return (its slopes only flatten,
    /// [`push_unloading`](Self::push_unloading)), so only the vertices from
    /// zero torque on can lie above the chord; with at most two reloading
    /// points per branch the return needs at most five vertices.
    pub(crate) fn back<const N: usize>(
        dir: S,
        from: [S; 2],
        path: &Branch<S>,
        seg: u8,
        bound: &Backbone<S, N>,
    ) -> Self {
        let first = (path.zero as usize).max(1);
        Self::way_back(dir, from, path, seg, first, true, bound)
    }

    /// The way back from `from` (motion coordinates of the return) along
    /// `chord` (or the ray it became), followed up to `from` on its segment
    /// `seg`, to its start: the same polyline reversed, so an excursion along
    /// a chord that the counter does not count does no work and closes where
    /// it began (G8).
    pub(crate) fn retrace<const N: usize>(
        dir: S,
        from: [S; 2],
        chord: &Branch<S>,
        seg: u8,
        bound: &Backbone<S, N>,
    ) -> Self {
        Self::way_back(dir, from, chord, seg, 1, false, bound)
    }

    /// Whether an element that followed this branch onto the primary curve
    /// and is now at `x` (motion coordinates) is on the torque cap, met after
    /// the branch's start and before zero twist (G9): a reversal there goes
    /// back to where the branch began. A branch that starts above the cap is
    /// cut down to it at once, a jump that no way back retraces (with
    /// coefficients scaled as a fit may, going back then returned energy).
    pub(crate) fn capped_before_zero_twist(&self, x: S) -> bool {
        !(x > S::ZERO) && self.n > 0 && self.contact > self.v[0][0]
    }

    /// The branch up to where it met `bound`, that point included: the path
    /// an element followed before the primary curve took over (G9, a
    /// reversal on the torque cap before zero twist). The contact lies past
    /// zero torque, so the vertices before it and it fit.
    pub(crate) fn up_to_contact<const N: usize>(&self, bound: &Backbone<S, N>) -> Self {
        let mut b = *self;
        let n = (self.n as usize).min(VERTICES);
        b.n = (1..n).take_while(|&i| self.v[i][0] < self.contact).count() as u8 + 1;
        b.append(self.contact, bound.bound(self.contact).0);
        b
    }

    /// A chord from `from` to the start of `path` through some of the
    /// vertices `first..=seg` of `path` (in return coordinates): the
    /// steepest one ahead each time (`steepest`: the concave majorant of
    /// [`back`](Self::back)), or every one ([`retrace`](Self::retrace)). The
    /// start is always the last vertex; the ones between are as many as fit.
    fn way_back<const N: usize>(
        dir: S,
        from: [S; 2],
        path: &Branch<S>,
        seg: u8,
        first: usize,
        steepest: bool,
        bound: &Backbone<S, N>,
    ) -> Self {
        let to = [-path.v[0][0], -path.v[0][1]];
        if !(to[0] > from[0]) {
            return Self::chord(dir, from, to, bound);
        }
        let mut b = Self::starting(Kind::Chord, dir, from);
        let last = (seg as usize).min((path.n as usize).saturating_sub(1));
        // Candidates are tried farthest first (the farthest wins a tie).
        let mut next = last + 1;
        while next > first && (b.n as usize) + 1 < VERTICES {
            let [x0, y0] = b.last();
            let ahead = |k: usize| {
                let p = [-path.v[k][0], -path.v[k][1]];
                (p[0] > x0 && p[0] < to[0]).then_some(p)
            };
            let pick = if steepest {
                let slope = |p: [S; 2]| (p[1] - y0) / (p[0] - x0);
                let mut best = slope(to);
                let mut pick = None;
                for k in first..next {
                    if let Some(s) = ahead(k).map(slope).filter(|&s| s > best) {
                        best = s;
                        pick = Some(k);
                    }
                }
                pick
            } else {
                (first..next).rev().find(|&k| ahead(k).is_some())
            };
            let Some(k) = pick else {
                break;
            };
            b.append(-path.v[k][0], -path.v[k][1]);
            next = k;
        }
        b.append(to[0], to[1]);
        b.finish(bound);
        b
    }

    /// Torque (motion coordinates) at `x`, at or past the first vertex, on
    /// the polyline and its ray (without the bound).
    pub(crate) fn torque_at(&self, x: S) -> S {
        let n = (self.n as usize).min(VERTICES);
        let seg = (1..n)
            .take_while(|&i| !(x < self.v[i][0]))
            .last()
            .unwrap_or(0);
        self.at(seg as u8, x).0
    }

    /// Torque (motion coordinates) and slope on segment `seg` (the ray for
    /// the last vertex).
    #[inline]
    pub(crate) fn at(&self, seg: u8, x: S) -> (S, S) {
        let [x0, y0, k] = self.v[seg as usize];
        (S::line(y0, k, x, x0), k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::phm::backbone::Direction;

    fn hysteretic() -> Backbone<f64, 4> {
        Backbone::new(Direction::Positive, &[[1.0, 5.0], [4.0, 6.5], [8.0, 5.5]]).unwrap()
    }

    /// Unloading projection: torques clamped between the previous torque and
    /// zero, slopes capped by the previous slope.
    #[test]
    fn unloading_points_are_projected() {
        let mut b = Branch::starting(Kind::Rule, -1.0, [-4.0, -6.5]);
        let mut cap = 5.0;
        // Eq. 1 would put this point at larger twist (x = -4.1 < -4): the cap
        // moves it to x = -4 + (-5.5 + 6.5) / 5 = -3.8.
        b.push_unloading([-4.1, -5.5], &mut cap);
        assert!((b.last()[0] + 3.8).abs() < 1e-15 && b.last()[1] == -5.5);
        assert!((cap - 5.0).abs() < 1e-14);
        // A torque that does not drop is dropped (also when equal).
        b.push_unloading([-3.9, -6.0], &mut cap);
        b.push_unloading([-3.0, -5.5], &mut cap);
        assert_eq!(b.n, 2);
        // Slope (0 + 5.5) / (-1 + 3.8) = 1.964..: accepted, becomes the cap.
        b.push_unloading([-1.0, 0.0], &mut cap);
        assert_eq!(b.n, 3);
        assert!((cap - 5.5 / 2.8).abs() < 1e-15);
        assert_eq!(b.zero, 2);
        // Zero torque at x = -1: the twist has not yet crossed zero.
        assert_eq!(b.across, u8::MAX);
    }

    /// Contact of a rising line with the bound (1,5),(4,6.5),(8,5.5):
    /// y = 2 (x + 1) is below T_c = 5 up to x = 1 (y = 4 there); on [1, 4]
    /// the bound is 5 + 0.5 (x - 1): 2x + 2 = 4.5 + 0.5x at x = 5/3.
    #[test]
    fn contact_is_exact() {
        let bound = hysteretic();
        let mut b = Branch::starting(Kind::Rule, 1.0, [-1.0, 0.0]);
        b.push_rising([0.0, 2.0], 5.0);
        b.finish(&bound);
        assert!((b.contact - 5.0 / 3.0).abs() < 1e-12, "{}", b.contact);
        // A flat ray at 4.9, below every part of the bound, never meets it.
        let mut flat = Branch::starting(Kind::Rule, 1.0, [-1.0, 0.0]);
        flat.push_rising([0.0, 4.9], 5.0);
        flat.push_rising([9.0, 4.9], 5.0);
        flat.finish(&bound);
        assert_eq!(flat.contact, f64::MAX);
        // A rule branch closed with `finish_rising` rises past such a
        // vertex with the given slope (G10): 4.9 + 5 (x - 9) = 5.5 at 9.12.
        flat.finish_rising(&bound, 5.0);
        assert!((flat.contact - 9.12).abs() < 1e-12, "{}", flat.contact);
    }

    /// A branch from just below zero torque straight to a point far above
    /// the bound (the unloading points were dropped): the contact lies on
    /// the first segment, before the zero-torque vertex (the search used to
    /// start at that vertex and found 4.0, above the bound).
    #[test]
    fn contact_on_the_segment_that_crosses_zero() {
        let bound = hysteretic();
        let mut b = Branch::starting(Kind::Rule, 1.0, [0.0, -1e-9]);
        b.push_rising([4.0, 20.0], 5.0);
        b.finish(&bound);
        assert_eq!(b.zero, 1);
        // Twist zero at the start, torque zero on the first segment.
        assert_eq!(b.across, 1);
        // The line y = 5 x - 1e-9 (to 3e-10) meets the bound
        // 5 + 0.5 (x - 1) at x = (4.5 + 1e-9) / 4.5.
        let want = (4.5 + 1e-9) / 4.5;
        assert!(b.contact < 1.5, "{}", b.contact);
        assert!((b.contact - want).abs() < 1e-9, "{}", b.contact);
    }

    /// Reloading points are no stiffer than the cap (G10): a point at or
    /// behind the previous twist is moved along its torque level, not
    /// dropped; one that adds nothing (behind, at the previous torque) is.
    #[test]
    fn reloading_points_are_projected() {
        let mut b = Branch::starting(Kind::Rule, 1.0, [-1.0, 0.0]);
        b.push_rising([2.0, 0.0], 10.0);
        b.push_rising([1.5, 20.0], 10.0);
        assert_eq!(b.n, 3);
        assert_eq!(b.last(), [4.0, 20.0]);
        b.push_rising([3.0, 10.0], 10.0);
        assert_eq!(b.n, 3);
    }
}
