//! The primary (backbone) curve of thesis §5.2.1: the torque-twist envelope
//! under monotonic torsion, idealised as piecewise-linear segments for the
//! elastic stiffness, post-cracking hardening, the yield plateau and strength
//! deterioration (Fig. 5.2). Each direction has its own curve.
//!
//! A curve is a list of points `(twist, torque)` in magnitudes (both positive,
//! also for the negative direction), after the implicit origin:
//!
//! * point 0 is cracking `(theta_c, T_c)`: the initial stiffness is
//!   `k_T1 = T_c / theta_c`, the uncracked stiffness eqs 4 and the unloading
//!   rules refer to;
//! * point 1 is yield `(theta_y, T_y)`: the ductilities `theta_m / theta_c` and
//!   `theta_m / theta_y` of eqs 1-6 are taken against these two points;
//! * further points (plateau, deterioration) are optional, up to the capacity
//!   `N` of the type.
//!
//! Beyond the last point the torque stays at the last point's torque (a
//! residual-strength plateau, tangent 0); see `docs/phm.md`, gap G7.
//!
//! The curve is checked once, when it is built ([`Backbone::new`]); a curve
//! that breaks a rule is refused with a [`BackboneError`] naming the direction,
//! the point and the rule.

use crate::scalar::Scalar;
use core::fmt;
use heapless::Vec;

/// Which direction of twist a primary curve (or a rule) belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Direction {
    /// Positive twist and torque.
    Positive,
    /// Negative twist and torque.
    Negative,
}

impl Direction {
    /// Index into per-direction arrays: 0 for positive, 1 for negative.
    #[inline]
    pub const fn index(self) -> usize {
        match self {
            Direction::Positive => 0,
            Direction::Negative => 1,
        }
    }
}

/// The rule a primary curve broke.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum BackboneRule {
    /// Fewer than two points: cracking and yield are both required.
    TooFewPoints,
    /// More points than the capacity `N` of the curve's type (or than 254).
    TooManyPoints,
    /// A twist or torque is NaN or infinite (or saturated fixed point).
    NotFinite,
    /// Twists must increase strictly from the origin (the first twist is > 0).
    TwistNotIncreasing,
    /// Torques are magnitudes and must be greater than zero.
    TorqueNotPositive,
    /// The first two slopes (elastic and post-cracking) must be positive.
    SlopeNotPositive,
    /// A segment is stiffer than the initial (uncracked) stiffness
    /// `T_c / theta_c`; cracking and yielding only soften a column.
    SteeperThanInitial,
}

impl BackboneRule {
    fn text(self) -> &'static str {
        match self {
            BackboneRule::TooFewPoints => {
                "needs at least two points: cracking (theta_c, T_c) and yield (theta_y, T_y)"
            }
            BackboneRule::TooManyPoints => {
                "has more points than the capacity of its type (at most 254)"
            }
            BackboneRule::NotFinite => "must be finite numbers",
            BackboneRule::TwistNotIncreasing => "twists must increase strictly from zero",
            BackboneRule::TorqueNotPositive => "torques (magnitudes) must be greater than zero",
            BackboneRule::SlopeNotPositive => {
                "the elastic and post-cracking slopes must be positive"
            }
            BackboneRule::SteeperThanInitial => {
                "no segment may be stiffer than the initial stiffness T_c/theta_c"
            }
        }
    }
}

/// A primary curve was refused: `point` (0-based; the first point is
/// cracking) of the `direction` curve broke `rule`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BackboneError {
    /// The curve's direction.
    pub direction: Direction,
    /// The offending point (for [`BackboneRule::TooFewPoints`] and
    /// [`BackboneRule::TooManyPoints`], the number of points given).
    pub point: usize,
    /// The rule it broke.
    pub rule: BackboneRule,
}

impl fmt::Display for BackboneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let dir = match self.direction {
            Direction::Positive => "positive",
            Direction::Negative => "negative",
        };
        match self.rule {
            BackboneRule::TooFewPoints | BackboneRule::TooManyPoints => write!(
                f,
                "{dir} primary curve with {} points {}",
                self.point,
                self.rule.text()
            ),
            rule => write!(
                f,
                "{dir} primary curve, point {}: {}",
                self.point,
                rule.text()
            ),
        }
    }
}

impl core::error::Error for BackboneError {}

/// The primary curve of one direction (thesis §5.2.1, see [`phm`](crate::phm)), with
/// room for `N` points.
#[derive(Clone, Debug, PartialEq)]
pub struct Backbone<S, const N: usize> {
    /// `[twist, torque]` magnitudes.
    points: Vec<[S; 2], N>,
    /// `slopes[i]`: slope of the segment ending at point i (`slopes[0] = k_T1`).
    slopes: Vec<S, N>,
}

impl<S: Scalar, const N: usize> Backbone<S, N> {
    /// Builds and checks the curve of `direction` from `[twist, torque]`
    /// magnitudes (cracking first, then yield, then any further points).
    pub fn new(direction: Direction, points: &[[S; 2]]) -> Result<Self, BackboneError> {
        let err = |point, rule| BackboneError {
            direction,
            point,
            rule,
        };
        if points.len() < 2 {
            return Err(err(points.len(), BackboneRule::TooFewPoints));
        }
        // The element keeps its segment on the curve in a u8.
        if points.len() > N || points.len() > u8::MAX as usize - 1 {
            return Err(err(points.len(), BackboneRule::TooManyPoints));
        }
        let mut curve = Backbone {
            points: Vec::new(),
            slopes: Vec::new(),
        };
        let mut prev = [S::ZERO; 2];
        let mut k1 = S::ZERO;
        for (i, &[x, y]) in points.iter().enumerate() {
            if !(x.is_finite() && y.is_finite()) {
                return Err(err(i, BackboneRule::NotFinite));
            }
            if !(x > prev[0]) {
                return Err(err(i, BackboneRule::TwistNotIncreasing));
            }
            if !(y > S::ZERO) {
                return Err(err(i, BackboneRule::TorqueNotPositive));
            }
            let slope = (y - prev[1]) / (x - prev[0]);
            if !slope.is_finite() {
                return Err(err(i, BackboneRule::NotFinite));
            }
            if i < 2 && !(slope > S::ZERO) {
                return Err(err(i, BackboneRule::SlopeNotPositive));
            }
            if i == 0 {
                k1 = slope;
            } else if slope > k1 {
                return Err(err(i, BackboneRule::SteeperThanInitial));
            }
            // Capacity was checked above: neither push can fail.
            let _ = curve.points.push([x, y]);
            let _ = curve.slopes.push(slope);
            prev = [x, y];
        }
        Ok(curve)
    }

    /// The points, `[twist, torque]` magnitudes, cracking first.
    pub fn points(&self) -> &[[S; 2]] {
        &self.points
    }
    /// Cracking point `(theta_c, T_c)`.
    #[inline]
    pub fn cracking(&self) -> [S; 2] {
        self.points[0]
    }
    /// Yield point `(theta_y, T_y)`.
    #[inline]
    pub fn yielding(&self) -> [S; 2] {
        self.points[1]
    }
    /// Initial (uncracked) stiffness `k_T1 = T_c / theta_c`.
    #[inline]
    pub fn k1(&self) -> S {
        self.slopes[0]
    }
    /// The largest torque of the curve.
    pub fn peak(&self) -> S {
        self.points
            .iter()
            .fold(S::ZERO, |m, p| if p[1] > m { p[1] } else { m })
    }

    /// The number of segments of [`bound`](Self::bound): the flat part below
    /// cracking, one per pair of points, and the flat part past the last point.
    #[inline]
    pub(crate) fn segments(&self) -> usize {
        self.points.len() + 1
    }

    /// The segment of [`bound`](Self::bound) holding `x`: 0 below cracking, i
    /// for `[x_(i-1), x_i)`, `len` at or past the last point.
    #[inline]
    pub(crate) fn locate(&self, x: S) -> usize {
        self.points
            .iter()
            .position(|p| x < p[0])
            .unwrap_or(self.points.len())
    }

    /// The start of segment `i` of the bound (its breakpoint), for `i >= 1`.
    #[inline]
    pub(crate) fn breakpoint(&self, i: usize) -> S {
        self.points[i - 1][0]
    }

    /// The bound on torque while loading in this direction at twist `x` (in
    /// this direction's magnitudes), and its slope: the primary curve past
    /// cracking; `T_c` below cracking (gap G6 in `docs/phm.md`); the last
    /// torque past the last point.
    #[inline]
    pub fn bound(&self, x: S) -> (S, S) {
        self.bound_in(self.locate(x), x)
    }

    /// [`bound`](Self::bound) for a twist that only grows: `seg` is the
    /// segment of the previous twist and is moved forward to this one's.
    #[inline]
    pub(crate) fn follow(&self, seg: &mut u8, x: S) -> (S, S) {
        let mut i = *seg as usize;
        while i < self.points.len() && !(x < self.points[i][0]) {
            i += 1;
        }
        *seg = i as u8;
        self.bound_in(i, x)
    }

    /// [`bound`](Self::bound) with the segment already known.
    #[inline]
    pub(crate) fn bound_in(&self, seg: usize, x: S) -> (S, S) {
        let n = self.points.len();
        if seg == 0 {
            (self.points[0][1], S::ZERO)
        } else if seg >= n {
            (self.points[n - 1][1], S::ZERO)
        } else {
            let [x0, y0] = self.points[seg - 1];
            let k = self.slopes[seg];
            (S::line(y0, k, x, x0), k)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(p: &[[f64; 2]]) -> Result<Backbone<f64, 6>, BackboneError> {
        Backbone::new(Direction::Negative, p)
    }

    #[test]
    fn each_rule_is_named() {
        let cases: &[(&[[f64; 2]], usize, BackboneRule)] = &[
            (&[[1.0, 5.0]], 1, BackboneRule::TooFewPoints),
            (
                &[
                    [1.0, 5.0],
                    [2.0, 6.0],
                    [3.0, 6.0],
                    [4.0, 6.0],
                    [5.0, 6.0],
                    [6.0, 6.0],
                    [7.0, 6.0],
                ],
                7,
                BackboneRule::TooManyPoints,
            ),
            (&[[1.0, 5.0], [f64::NAN, 6.0]], 1, BackboneRule::NotFinite),
            (
                &[[1.0, 5.0], [1.0, 6.0]],
                1,
                BackboneRule::TwistNotIncreasing,
            ),
            (
                &[[0.0, 5.0], [1.0, 6.0]],
                0,
                BackboneRule::TwistNotIncreasing,
            ),
            (
                &[[1.0, 5.0], [2.0, 6.0], [3.0, 0.0]],
                2,
                BackboneRule::TorqueNotPositive,
            ),
            (&[[1.0, 5.0], [2.0, 5.0]], 1, BackboneRule::SlopeNotPositive),
            (
                &[[1.0, 5.0], [2.0, 11.0]],
                1,
                BackboneRule::SteeperThanInitial,
            ),
        ];
        for &(pts, point, rule) in cases {
            let e = curve(pts).unwrap_err();
            assert_eq!((e.point, e.rule), (point, rule), "{pts:?}");
            assert_eq!(e.direction, Direction::Negative);
        }
        let e = curve(&[[1.0, 5.0], [1.0, 6.0]]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "negative primary curve, point 1: twists must increase strictly from zero"
        );
    }

    /// The bound: flat T_c below cracking, the curve past it, flat past the
    /// last point. Hysteretic backbone of the OpenSees cases:
    /// (1, 5), (4, 6.5), (8, 5.5): slopes 5, 0.5, -0.25.
    #[test]
    fn bound_follows_the_points() {
        let b = curve(&[[1.0, 5.0], [4.0, 6.5], [8.0, 5.5]]).unwrap();
        assert_eq!(b.k1(), 5.0);
        assert_eq!(b.bound(-3.0), (5.0, 0.0));
        assert_eq!(b.bound(0.5), (5.0, 0.0));
        assert_eq!(b.bound(1.0), (5.0, 0.5));
        assert_eq!(b.bound(2.0), (5.5, 0.5)); // 5 + 0.5 * 1
        assert_eq!(b.bound(6.0), (6.0, -0.25)); // 6.5 - 0.25 * 2
        assert_eq!(b.bound(8.0), (5.5, 0.0));
        assert_eq!(b.bound(100.0), (5.5, 0.0));
        assert_eq!(b.peak(), 6.5);
    }
}
