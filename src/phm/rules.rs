//! The unloading rules (thesis §5.2.2, eqs 1a-1d, 2a-2b, 3) and the
//! loading/reloading rules (§5.2.3, eqs 4, 5a-5b, 6), with their coefficients
//! as parameters, and the cycle counter n of each direction.
//!
//! Notation (all in the magnitudes of one direction): `theta_m, T_m` the
//! unloading point; `mu_c = theta_m / theta_c`, `mu_y = theta_m / theta_y`.
//!
//! ```text
//! unloading, theta_c < theta_m < theta_y          theta_m >= theta_y
//!   theta_ur1/theta_m = a mu_c + b       (1a)       a mu_y + b         (1b)
//!   T_ur1/T_m         = a mu_c + b       (1c)       a mu_y + b         (1d)
//!   theta_ur2/theta_m =  -                          a mu_y + b         (2a)
//!   T_ur2/T_m         =  -                          a mu_y + b         (2b)
//!   theta_su/theta_m  = a mu_c + b       (3a)       a mu_y + b         (3b)
//! reloading towards a direction with level theta_m, torque T_m, count n
//!   not cracked yet:   towards its cracking point (rule 2)
//!   theta_m < theta_y: slope k_Tr1 / k_T1 = a mu_c^b                  (4)
//!                      (cracked without a counted level: theta_m = theta_c)
//!   theta_m >= theta_y: through (theta_m, T_p) up to theta_cr, then to
//!                       (theta_m, T'_m), then on to the primary curve
//!     theta_cr/theta_m = (a n + b) mu_y + (c n + d)                   (5a)
//!     T_p/T_m          = (a n + b) mu_y^(c n + d) <= 1                (5b)
//!     T'_m/T_m         = a mu_y + (b n + c)       <= 1 (gap G5)       (6)
//! ```
//!
//! Eq. 2 is printed with `theta_m/theta_c`, its figure (5.6) with
//! `theta_m/theta_y`; the thesis' numbers only make sense with the latter
//! (with `mu_c` of 10 or more, 2a gives `theta_ur2 > theta_m`), so `mu_y` is
//! used (gap G1 in `docs/phm.md`).
//!
//! Past the fits' range (eq. 5a: `theta_cr >= theta_m` from n = 13 at
//! `mu_y = 1.6`; eq. 5b: `T_p <= 0`; eq. 6 below the pinched line) the
//! reloading still rises to the primary curve: `theta_cr` is held where a
//! segment of slope `k_T1` still reaches `(theta_m, T'_m)`, no reloading
//! segment is stiffer than `k_T1`, and a ray that would not rise rises with
//! `k_T1` (gap G10).

use super::backbone::{Backbone, Direction};
use super::branch::{Branch, Kind};
use crate::bwbn::{ParamError, Rule};
use crate::scalar::Scalar;

/// Description of one rule coefficient.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoefficientSpec {
    /// Name in parameter files (`"eq1a_a"`: equation 1a, coefficient a).
    pub name: &'static str,
    /// The thesis equation.
    pub equation: &'static str,
    /// The thesis' value as an exact fraction `(numerator, denominator)`.
    pub thesis: (i32, i32),
    /// One line of documentation.
    pub doc: &'static str,
}

macro_rules! specs {
    ($($idx:ident = $name:literal, $eq:literal, $num:literal / $den:literal, $doc:literal;)*) => {
        /// Indices into [`Coefficients`], in the order of [`SPECS`].
        #[allow(missing_docs)]
        pub mod idx {
            specs!(@idx 0usize; $($idx)*);
        }
        /// Every rule coefficient, in storage order.
        pub const SPECS: [CoefficientSpec; specs!(@count $($idx)*)] = [
            $(CoefficientSpec { name: $name, equation: $eq, thesis: ($num, $den), doc: $doc },)*
        ];
    };
    (@idx $n:expr; $first:ident $($rest:ident)*) => {
        pub const $first: usize = $n;
        specs!(@idx $n + 1usize; $($rest)*);
    };
    (@idx $n:expr;) => {};
    (@count $($idx:ident)*) => { 0usize $(+ { let _ = stringify!($idx); 1usize })* };
}

specs! {
    EQ1A_A = "eq1a_a", "1a", -28 / 10000, "theta_ur1/theta_m slope on mu_c (pre-yield)";
    EQ1A_B = "eq1a_b", "1a", 10498 / 10000, "theta_ur1/theta_m intercept (pre-yield)";
    EQ1B_A = "eq1b_a", "1b", -4 / 10000, "theta_ur1/theta_m slope on mu_y (post-yield)";
    EQ1B_B = "eq1b_b", "1b", 10047 / 10000, "theta_ur1/theta_m intercept (post-yield)";
    EQ1C_A = "eq1c_a", "1c", -9 / 10000, "T_ur1/T_m slope on mu_c (pre-yield)";
    EQ1C_B = "eq1c_b", "1c", 8527 / 10000, "T_ur1/T_m intercept (pre-yield)";
    EQ1D_A = "eq1d_a", "1d", -6 / 10000, "T_ur1/T_m slope on mu_y (post-yield)";
    EQ1D_B = "eq1d_b", "1d", 8623 / 10000, "T_ur1/T_m intercept (post-yield)";
    EQ2A_A = "eq2a_a", "2a", 363 / 10000, "theta_ur2/theta_m slope on mu_y";
    EQ2A_B = "eq2a_b", "2a", 7101 / 10000, "theta_ur2/theta_m intercept";
    EQ2B_A = "eq2b_a", "2b", -126 / 10000, "T_ur2/T_m slope on mu_y";
    EQ2B_B = "eq2b_b", "2b", 3243 / 10000, "T_ur2/T_m intercept";
    EQ3A_A = "eq3a_a", "3a", -15 / 10000, "theta_su/theta_m slope on mu_c (pre-yield)";
    EQ3A_B = "eq3a_b", "3a", 2358 / 10000, "theta_su/theta_m intercept (pre-yield)";
    EQ3B_A = "eq3b_a", "3b", 1012 / 10000, "theta_su/theta_m slope on mu_y (post-yield)";
    EQ3B_B = "eq3b_b", "3b", 848 / 10000, "theta_su/theta_m intercept (post-yield)";
    EQ4_A = "eq4_a", "4", 7513 / 10000, "k_Tr1/k_T1 factor";
    EQ4_B = "eq4_b", "4", -786 / 1000, "k_Tr1/k_T1 exponent of mu_c";
    EQ5A_A = "eq5a_a", "5a", -67 / 10000, "theta_cr/theta_m: n coefficient of the mu_y slope";
    EQ5A_B = "eq5a_b", "5a", 766 / 10000, "theta_cr/theta_m: constant of the mu_y slope";
    EQ5A_C = "eq5a_c", "5a", 782 / 10000, "theta_cr/theta_m: n coefficient of the intercept";
    EQ5A_D = "eq5a_d", "5a", 37 / 10000, "theta_cr/theta_m: constant of the intercept";
    EQ5B_A = "eq5b_a", "5b", -783 / 10000, "T_p/T_m: n coefficient of the factor";
    EQ5B_B = "eq5b_b", "5b", 9425 / 10000, "T_p/T_m: constant of the factor";
    EQ5B_C = "eq5b_c", "5b", 1155 / 10000, "T_p/T_m: n coefficient of the exponent of mu_y";
    EQ5B_D = "eq5b_d", "5b", -13943 / 10000, "T_p/T_m: constant of the exponent of mu_y";
    EQ6_A = "eq6_a", "6", -5557 / 100000, "T'_m/T_m slope on mu_y";
    EQ6_B = "eq6_b", "6", 177 / 10000, "T'_m/T_m: n coefficient";
    EQ6_C = "eq6_c", "6", 9842 / 10000, "T'_m/T_m: constant";
    CYCLE_BAND = "cycle_band", "5", 5 / 100, "n counts unloadings within (1 +/- band) theta_m";
}

/// The coefficients of eqs 1-6 and the band of the cycle counter, stored in
/// the order of [`SPECS`]. [`Coefficients::thesis`] (also `Default`) holds the
/// thesis' values.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Coefficients<S>(pub(crate) [S; SPECS.len()]);

impl<S: Scalar> Coefficients<S> {
    /// The values of thesis chapter 5.
    pub fn thesis() -> Self {
        let mut v = [S::ZERO; SPECS.len()];
        for (v, s) in v.iter_mut().zip(SPECS.iter()) {
            *v = S::ratio(s.thesis.0, s.thesis.1);
        }
        Coefficients(v)
    }

    /// Builds a set from named values (names as in [`SPECS`]); a coefficient
    /// that `get` does not know keeps the thesis' value.
    pub fn from_named(mut get: impl FnMut(&str) -> Option<S>) -> Result<Self, ParamError> {
        let mut c = Self::thesis();
        for (v, s) in c.0.iter_mut().zip(SPECS.iter()) {
            if let Some(x) = get(s.name) {
                *v = x;
            }
        }
        c.validated()
    }

    /// Checks the set: every value finite, the cycle band in [0, 1].
    pub fn validated(self) -> Result<Self, ParamError> {
        for (v, s) in self.0.iter().zip(SPECS.iter()) {
            if !v.is_finite() {
                return Err(ParamError::new(s.name, Rule::NotFinite));
            }
        }
        let band = self.0[idx::CYCLE_BAND];
        if !(band >= S::ZERO && band <= S::ONE) {
            return Err(ParamError::new(
                SPECS[idx::CYCLE_BAND].name,
                Rule::NotAFraction,
            ));
        }
        Ok(self)
    }

    /// The value of the coefficient `name`.
    pub fn get(&self, name: &str) -> Option<S> {
        SPECS.iter().position(|s| s.name == name).map(|i| self.0[i])
    }

    /// Calls `f` with every coefficient, in the order of [`SPECS`].
    pub fn for_each(&self, mut f: impl FnMut(&'static CoefficientSpec, S)) {
        SPECS.iter().zip(self.0.iter()).for_each(|(s, &v)| f(s, v));
    }

    #[inline]
    fn lin(&self, a: usize, mu: S) -> S {
        self.0[a] * mu + self.0[a + 1]
    }
}

impl<S: Scalar> Default for Coefficients<S> {
    fn default() -> Self {
        Self::thesis()
    }
}

/// The largest value of the cycle counter n (eqs 5a, 5b, 6): 32767, the
/// largest integer Q15.16 ([`Fixed`](crate::Fixed)) represents. The counter
/// stops there, in every arithmetic, so that `n` reaches eqs 5-6 exactly
/// (past it `S::from_i32(n)` saturated in fixed point and the response
/// jumped) and `f64`, `f32` and fixed point count alike (gap G4 in
/// `docs/phm.md`).
pub const MAX_CYCLES: u16 = 32767;

/// What the rules remember about one direction: the deformation level
/// `theta_m` of its last counted unloading, the torque `T_m` there, the cycle
/// counter n and whether the direction has cracked.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Level<S> {
    /// `theta_m` (magnitude); meaningful when `cycles > 0`.
    pub twist: S,
    /// `T_m` (magnitude) at the last counted unloading.
    pub torque: S,
    /// The cycle counter n of eqs 5 and 6 (0: no unloading counted yet; at
    /// most [`MAX_CYCLES`]).
    pub cycles: u16,
    /// The element has been on this direction's primary curve past cracking
    /// (or at its cracking torque).
    pub cracked: bool,
}

impl<S: Scalar> Level<S> {
    /// Whether an unloading from twist `x` (magnitude) is counted by
    /// [`count_unloading`](Self::count_unloading): the direction has cracked,
    /// `x` is past cracking, and it is a first level, a new one or within the
    /// band `(1 +/- band) theta_m` (at or above its lower edge).
    pub(crate) fn counts(&self, x: S, theta_c: S, band: S) -> bool {
        self.cracked && x > theta_c && (self.cycles == 0 || !(x < self.twist - self.twist * band))
    }

    /// Counts an unloading from twist `x`, torque `t` (magnitudes) with the
    /// thesis' rule for n (§5.2.3 rule 5): n = 1 at a new level, incremented
    /// for an unloading within `(1 +/- band) theta_m`. Gaps G3/G4: an
    /// unloading below the band is an inner cycle and changes nothing;
    /// within the band `theta_m` becomes the larger of the two twists and
    /// `T_m` the torque of the path there: this unloading's `t` when it is
    /// at or past `theta_m`, else `at_theta_m()`, the torque at `theta_m` of
    /// the branch it left (taking `t`, a torque at a smaller twist, broke
    /// the pair: an inner cycle reversed at 7.60 of `theta_m = 8` took the
    /// next peak 14% below one reversed at 7.59; found by review). Nothing is counted before the
    /// direction has cracked (rule 1 of §5.2.2 governs), nor from a twist
    /// below cracking (reached only on the torque cap below cracking, gap
    /// G6), so that `theta_m > theta_c` always holds where eqs 4-6 use it.
    /// n stops at [`MAX_CYCLES`]: a further unloading within the band still
    /// updates `theta_m` and `T_m`.
    ///
    /// [`counts`](Self::counts) says beforehand whether it will count.
    pub(crate) fn count_unloading(
        &mut self,
        (x, t): (S, S),
        at_theta_m: impl FnOnce(S) -> S,
        theta_c: S,
        band: S,
    ) {
        if !self.counts(x, theta_c, band) {
            return;
        }
        if self.cycles == 0 || x > self.twist + self.twist * band {
            *self = Level {
                twist: x,
                torque: t,
                cycles: 1,
                cracked: true,
            };
        } else {
            self.cycles = self.cycles.saturating_add(1).min(MAX_CYCLES);
            if x < self.twist {
                self.torque = at_theta_m(self.twist);
            } else {
                self.twist = x;
                self.torque = t;
            }
        }
    }
}

/// Builds the branch that starts with an unloading from `p = [twist, torque]`
/// (magnitudes in direction `from`, torque > 0): unloading rules 2-4 down to
/// zero torque, then the reloading rule that applies towards the opposite
/// direction, then the ray that meets its primary curve (rule 6).
pub(crate) fn unloading_branch<S: Scalar, const N: usize>(
    c: &Coefficients<S>,
    primary: &[Backbone<S, N>; 2],
    from: Direction,
    p: [S; 2],
    levels: &[Level<S>; 2],
) -> Branch<S> {
    let (to, dir) = match from {
        Direction::Positive => (Direction::Negative, -S::ONE),
        Direction::Negative => (Direction::Positive, S::ONE),
    };
    let v = &c.0;
    let own = &primary[from.index()];
    let [xm, tm] = p;
    // Motion coordinates of the unloading are the negated magnitudes.
    let mut b = Branch::starting(Kind::Rule, dir, [-xm, -tm]);
    let mut cap = own.k1();
    let theta_y = own.yielding()[0];
    if !(xm < theta_y) {
        // Unloading rules 2-4 past yield: eqs 1b/1d, 2a/2b, 3b.
        let mu = xm / theta_y;
        b.push_unloading(
            [
                -(xm * c.lin(idx::EQ1B_A, mu)),
                -(tm * c.lin(idx::EQ1D_A, mu)),
            ],
            &mut cap,
        );
        b.push_unloading(
            [
                -(xm * c.lin(idx::EQ2A_A, mu)),
                -(tm * c.lin(idx::EQ2B_A, mu)),
            ],
            &mut cap,
        );
        b.push_unloading([-(xm * c.lin(idx::EQ3B_A, mu)), S::ZERO], &mut cap);
    } else {
        // Unloading rules 2 and 4 before yield: eqs 1a/1c, 3a.
        let mu = xm / own.cracking()[0];
        b.push_unloading(
            [
                -(xm * c.lin(idx::EQ1A_A, mu)),
                -(tm * c.lin(idx::EQ1C_A, mu)),
            ],
            &mut cap,
        );
        b.push_unloading([-(xm * c.lin(idx::EQ3A_A, mu)), S::ZERO], &mut cap);
    }
    let other = &primary[to.index()];
    let level = &levels[to.index()];
    let [x0, y0] = b.last();
    let [xc, tc] = other.cracking();
    let theta_y = other.yielding()[0];
    // Reloading segments are no stiffer than k_T1 (gap G10).
    let k1 = other.k1();
    if !level.cracked {
        // Loading rule 2: towards the cracking point of the other direction.
        b.push_rising([xc, tc], k1);
    } else if level.cycles == 0 || level.twist < theta_y {
        // Loading rule 3 ("when cracking load on both directions has been
        // reached"): a straight line of slope k_Tr1 (eq. 4). A direction
        // that reached its cracking torque without a counted unloading (it
        // reversed at its cracking point, or on the torque cap below it, G6)
        // is at theta_m = theta_c as far as eq. 4 is concerned.
        let theta_m = if level.cycles == 0 { xc } else { level.twist };
        let k = k1 * v[idx::EQ4_A] * (theta_m / xc).powf(v[idx::EQ4_B]);
        b.push_rising([x0 + xc, y0 + k * xc], k1);
    } else {
        // Loading rules 4-5: the pinched line through (theta_m, T_p) up to
        // theta_cr (eq. 5), then towards (theta_m, T'_m) (eq. 6).
        let (xm, tm) = (level.twist, level.torque);
        let mu = xm / theta_y;
        // n <= MAX_CYCLES, an integer every arithmetic represents.
        let n = S::from_i32(level.cycles.min(MAX_CYCLES) as i32);
        let tp = tm
            * ((v[idx::EQ5B_A] * n + v[idx::EQ5B_B])
                * mu.powf(v[idx::EQ5B_C] * n + v[idx::EQ5B_D]))
            .min(S::ONE);
        let xcr =
            xm * ((v[idx::EQ5A_A] * n + v[idx::EQ5A_B]) * mu + v[idx::EQ5A_C] * n + v[idx::EQ5A_D]);
        let tm2 = tm * (v[idx::EQ6_A] * mu + v[idx::EQ6_B] * n + v[idx::EQ6_C]).min(S::ONE);
        if xm > x0 {
            // Gap G10: the cracks close no later than theta_m, and early
            // enough for the segment to (theta_m, T'_m) to be no stiffer
            // than k_T1. Eq. 5a leaves this range for large n (theta_cr >=
            // theta_m from n = 13 at mu_y = 1.6, with eq. 5b's T_p <= 0):
            // the pinched line then ends where k_T1 still reaches T'_m at
            // theta_m. `s` is the pinched line's slope as followed (a
            // falling line is held at the torque reached, G5).
            let s = ((tp - y0) / (xm - x0)).max(S::ZERO);
            // Written about theta_m: `k1 xm` alone left Q15.16's range on
            // stiff columns (k_T1 = 5000 kN m/deg at 8 deg), the saturated
            // bound dropped out of the `min`s below, and the element turned
            // at zero torque from the 15th cycle on (found by review).
            let latest = if k1 > s {
                xm - (tm2 - y0 - s * (xm - x0)) / (k1 - s)
            } else {
                xm
            };
            let xcr = xcr.min(latest).min(xm);
            if xcr > x0 {
                b.push_rising([xcr, y0 + (tp - y0) * ((xcr - x0) / (xm - x0))], k1);
            }
        }
        b.push_rising([xm, tm2], k1);
    }
    // Rule 6 presumes that the reloading meets the primary curve: the ray
    // past the last point rises (with k_T1 where eqs 4-6 give no rise, G10).
    b.finish_rising(other, k1);
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_values_are_exact_fractions() {
        let c = Coefficients::<f64>::thesis();
        assert_eq!(c.get("eq1a_a"), Some(-0.0028));
        assert_eq!(c.get("eq5b_d"), Some(-1.3943));
        assert_eq!(c.get("eq6_a"), Some(-0.05557));
        assert_eq!(c.get("cycle_band"), Some(0.05));
        assert_eq!(SPECS.len(), 30);
        assert_eq!(SPECS[idx::EQ4_B].name, "eq4_b");
        let mut names = std::vec::Vec::new();
        c.for_each(|s, _| names.push(s.name));
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), SPECS.len(), "names are unique");
    }

    #[test]
    fn named_values_are_validated() {
        let c = Coefficients::<f64>::from_named(|n| (n == "eq4_a").then_some(0.5)).unwrap();
        assert_eq!(c.get("eq4_a"), Some(0.5));
        assert_eq!(c.get("eq4_b"), Some(-0.786));
        let e = Coefficients::<f64>::from_named(|n| (n == "eq2b_a").then_some(f64::NAN));
        assert_eq!(e.unwrap_err().to_string(), "eq2b_a must be a finite number");
        let e = Coefficients::<f64>::from_named(|n| (n == "cycle_band").then_some(1.5));
        assert_eq!(e.unwrap_err().to_string(), "cycle_band must lie in [0, 1]");
    }

    /// The cycle counter of §5.2.3: theta_m = 4, band 5 %: 4.1 is in the band
    /// (n = 2, theta_m = 4.1), 3.9 too (n = 3, theta_m stays 4.1), 3.8 is
    /// below 0.95 * 4.1 = 3.895 (inner cycle: nothing), 4.4 > 1.05 * 4.1 =
    /// 4.305 starts a new level (n = 1).
    #[test]
    fn cycle_counter() {
        let band = 0.05;
        // The torque at theta_m of the branch an unloading below theta_m
        // leaves.
        let path = |x: f64| 1.5 * x;
        let mut l = Level::<f64> {
            cracked: true,
            ..Level::default()
        };
        l.count_unloading((4.0, 6.0), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.0, 6.0, 1));
        l.count_unloading((4.1, 5.8), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.1, 5.8, 2));
        l.count_unloading((3.9, 5.7), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.1, 1.5 * 4.1, 3));
        l.count_unloading((3.8, 5.0), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.1, 1.5 * 4.1, 3));
        l.count_unloading((4.4, 6.1), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.4, 6.1, 1));
        // n stops at MAX_CYCLES; theta_m and T_m are still updated.
        l.cycles = MAX_CYCLES - 1;
        l.count_unloading((4.4, 6.0), path, 1.0, band);
        assert_eq!(l.cycles, MAX_CYCLES);
        l.count_unloading((4.3, 5.9), path, 1.0, band);
        assert_eq!((l.twist, l.torque, l.cycles), (4.4, 1.5 * 4.4, MAX_CYCLES));
        let mut uncracked = Level::<f64>::default();
        uncracked.count_unloading((0.5, 1.0), path, 1.0, band);
        assert_eq!(uncracked.cycles, 0);
    }
}
