//! Physical effects on top of the Bouc-Wen base, one module each.
//!
//! The rate of the hysteretic displacement (thesis eq. 3.4) is written as
//!
//! ```text
//! dz/du = h * (A - nu |z|^n (beta sgn(du z) + gamma)) / eta
//! ```
//!
//! and the restoring force (eq. 3.2) as `R = k_el u + k_hys z`. Each effect
//! sets or scales some of these [`Coefficients`] and [`Stiffness`]es at the
//! current point ([`At`]): degradation makes A, nu, eta functions of the
//! dissipated energy (eqs 3.5-3.7), pinching sets h (eqs 3.9-3.11). With every
//! effect off the coefficients are A = nu = eta = h = 1, `k_el = alpha k0`,
//! `k_hys = (1 - alpha) k0`: plain Bouc-Wen.
//!
//! # Adding an effect
//!
//! 1. Write a module here with a `Copy` parameter struct, its `PARAMS`
//!    ([`ParamSpec`]s: name, symbol, equation, the value that
//!    switches it off, units, fitting range), a validating constructor that
//!    returns [`ParamError`] naming the field and rule, and an
//!    [`Effect`] implementation (with [`Effect::reads_energy`] false if it
//!    never reads `At::energy`).
//! 2. Register it in [`EffectKind`] and [`Effects`] (name, field, order of
//!    application).
//!
//! The integrator and the drivers only see [`Coefficients`], so they do not
//! change. Effects defined outside this crate implement [`Effect`] and are
//! passed to [`Bwbn`](super::Bwbn) as its extra-effect type parameter.

mod a_degradation;
mod asymmetry;
mod pinching;
mod stiffness_degradation;
mod strength_degradation;

pub use a_degradation::ADegradation;
pub use asymmetry::Asymmetry;
pub use pinching::{Pinching, ZuRule};
pub use stiffness_degradation::StiffnessDegradation;
pub use strength_degradation::StrengthDegradation;

use super::base::BoucWen;
use super::spec::{ParamError, ParamSpec, Rule};
use crate::scalar::Scalar;

/// Where the rate is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct At<S> {
    /// Total displacement u.
    pub u: S,
    /// Hysteretic displacement z.
    pub z: S,
    /// Hysteretic energy epsilon (eq. 3.8) accumulated so far.
    pub energy: S,
    /// Direction of loading: +1 or -1 (sgn of du, or of the velocity).
    pub dir: S,
}

/// The coefficients of the z-rate and of the restoring force at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients<S> {
    /// A (eq. 3.5): hysteretic stiffness factor.
    pub a: S,
    /// nu (eq. 3.6): strength factor; Zu scales with nu^(-1/n).
    pub nu: S,
    /// 1/eta (eq. 3.7): inverse stiffness-degradation factor.
    pub inv_eta: S,
    /// h(z) (eq. 3.9): pinching factor.
    pub h: S,
}

/// The two springs of the restoring force `R = el * u + hys * z` (eq. 3.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stiffness<S> {
    /// Stiffness of the linear spring, alpha k0.
    pub el: S,
    /// Stiffness of the hysteretic spring, (1 - alpha) k0.
    pub hys: S,
}

impl<S: Scalar> Stiffness<S> {
    /// The stiffnesses with every effect off.
    #[inline]
    pub fn plain(base: &BoucWen<S>) -> Self {
        Stiffness {
            el: base.alpha * base.k0,
            hys: (S::ONE - base.alpha) * base.k0,
        }
    }
}

impl<S: Scalar> Coefficients<S> {
    /// The coefficients with every effect off.
    pub const PLAIN: Self = Coefficients {
        a: S::ONE,
        nu: S::ONE,
        inv_eta: S::ONE,
        h: S::ONE,
    };

    /// Zu = (A/(nu (beta+gamma)))^(1/n) with the current A and nu (eq. 3.12),
    /// or `None` when beta + gamma <= 0.
    pub fn zu(&self, base: &BoucWen<S>, zu_plain: Option<S>) -> Option<S> {
        let zu1 = zu_plain?;
        if self.a == self.nu {
            Some(zu1)
        } else {
            Some(zu1 * (self.a / self.nu).powf(S::ONE / base.n))
        }
    }
}

/// A physical effect: modifies the coefficients at a point.
pub trait Effect<S: Scalar> {
    /// Sets or scales the z-rate coefficients `c` for the state `at`.
    /// `zu_plain` is Zu of the base model with A = nu = 1 (precomputed),
    /// `None` for hardening sets.
    fn apply(&self, base: &BoucWen<S>, zu_plain: Option<S>, at: &At<S>, c: &mut Coefficients<S>);

    /// Sets or scales the restoring-force springs for the state `at`. Most
    /// effects leave them alone.
    #[inline(always)]
    fn stiffness(&self, _base: &BoucWen<S>, _at: &At<S>, _k: &mut Stiffness<S>) {}

    /// Whether the effect reads `at.energy`. Where no effect does, the
    /// hysteretic energy is only reported: a value the arithmetic cannot hold
    /// (Q15.16 past 32767) reads as non-finite but does not stop the element.
    /// The default, `true`, is the safe answer for an effect that may.
    #[inline(always)]
    fn reads_energy(&self) -> bool {
        true
    }

    /// Whether the effect changes nothing: no coefficient and no stiffness.
    /// Only then can [`Method::Series`](super::Method::Series), which sums
    /// plain Bouc-Wen, step an element that carries it. The default, `false`,
    /// is the safe answer.
    #[inline(always)]
    fn is_none(&self) -> bool {
        false
    }
}

/// No extra effect: the default extension of [`Bwbn`](super::Bwbn).
impl<S: Scalar> Effect<S> for () {
    #[inline(always)]
    fn apply(&self, _: &BoucWen<S>, _: Option<S>, _: &At<S>, _: &mut Coefficients<S>) {}
    #[inline(always)]
    fn reads_energy(&self) -> bool {
        false
    }
    #[inline(always)]
    fn is_none(&self) -> bool {
        true
    }
}

impl<S: Scalar, E: Effect<S> + ?Sized> Effect<S> for &E {
    #[inline(always)]
    fn apply(&self, base: &BoucWen<S>, zu: Option<S>, at: &At<S>, c: &mut Coefficients<S>) {
        (**self).apply(base, zu, at, c)
    }
    #[inline(always)]
    fn stiffness(&self, base: &BoucWen<S>, at: &At<S>, k: &mut Stiffness<S>) {
        (**self).stiffness(base, at, k)
    }
    #[inline(always)]
    fn reads_energy(&self) -> bool {
        (**self).reads_energy()
    }
    #[inline(always)]
    fn is_none(&self) -> bool {
        (**self).is_none()
    }
}

/// The built-in effects, by the names used in model specs (`bw+pinching`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum EffectKind {
    /// Degradation of A with energy (eq. 3.5).
    ADegradation = 0,
    /// Strength degradation, nu (eq. 3.6).
    StrengthDegradation = 1,
    /// Stiffness degradation, eta (eq. 3.7).
    StiffnessDegradation = 2,
    /// Pinching, h(z) (eqs 3.9-3.11).
    Pinching = 3,
    /// Unequal strength and stiffness in the two directions (not in the
    /// thesis).
    Asymmetry = 4,
}

impl EffectKind {
    /// Every built-in effect.
    pub const ALL: [EffectKind; 5] = [
        EffectKind::ADegradation,
        EffectKind::StrengthDegradation,
        EffectKind::StiffnessDegradation,
        EffectKind::Pinching,
        EffectKind::Asymmetry,
    ];
    /// The effects of the 17-parameter BWBN model of the thesis.
    pub const THESIS: [EffectKind; 4] = [
        EffectKind::ADegradation,
        EffectKind::StrengthDegradation,
        EffectKind::StiffnessDegradation,
        EffectKind::Pinching,
    ];

    /// Name in model specs.
    pub const fn name(self) -> &'static str {
        match self {
            EffectKind::ADegradation => "a-degradation",
            EffectKind::StrengthDegradation => "strength-degradation",
            EffectKind::StiffnessDegradation => "stiffness-degradation",
            EffectKind::Pinching => "pinching",
            EffectKind::Asymmetry => "asymmetry",
        }
    }

    /// The effect with this spec name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Its parameters.
    pub const fn params(self) -> &'static [ParamSpec] {
        match self {
            EffectKind::ADegradation => &a_degradation::PARAMS,
            EffectKind::StrengthDegradation => &strength_degradation::PARAMS,
            EffectKind::StiffnessDegradation => &stiffness_degradation::PARAMS,
            EffectKind::Pinching => &pinching::PARAMS,
            EffectKind::Asymmetry => &asymmetry::PARAMS,
        }
    }

    /// One sentence on what the effect models.
    pub const fn doc(self) -> &'static str {
        match self {
            EffectKind::ADegradation => {
                "hysteretic stiffness A changes with dissipated energy (eq. 3.5)"
            }
            EffectKind::StrengthDegradation => {
                "strength falls with dissipated energy: nu grows, Zu shrinks (eq. 3.6)"
            }
            EffectKind::StiffnessDegradation => {
                "unloading/reloading stiffness falls with dissipated energy: eta grows (eq. 3.7)"
            }
            EffectKind::Pinching => {
                "the loop narrows near zero force on reloading, growing with energy (eqs 3.9-3.11)"
            }
            EffectKind::Asymmetry => {
                "the two directions reach different strengths (and stiffnesses)"
            }
        }
    }
}

/// A set of built-in effects (bit i = `EffectKind` with discriminant i).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EffectSet(u8);

impl EffectSet {
    /// No effect: plain Bouc-Wen.
    pub const NONE: EffectSet = EffectSet(0);
    /// All four effects of the thesis' BWBN model.
    pub const BWBN: EffectSet = EffectSet(0b1111);
    /// Every built-in effect.
    pub const ALL: EffectSet = EffectSet(0b1_1111);

    /// The set with `kind` added.
    pub const fn with(self, kind: EffectKind) -> Self {
        EffectSet(self.0 | 1 << kind as u8)
    }
    /// Whether `kind` is in the set.
    pub const fn contains(self, kind: EffectKind) -> bool {
        self.0 & (1 << kind as u8) != 0
    }
    /// The bits (for tables).
    pub const fn bits(self) -> u8 {
        self.0
    }
    /// The set with these bits, or `None` if a bit names no effect.
    pub const fn from_bits(bits: u8) -> Option<Self> {
        if bits & !Self::ALL.0 == 0 {
            Some(EffectSet(bits))
        } else {
            None
        }
    }
    /// The effects in the set, in order of application.
    pub fn iter(self) -> impl Iterator<Item = EffectKind> {
        EffectKind::ALL
            .into_iter()
            .filter(move |k| self.contains(*k))
    }
}

/// The built-in effects of one parameter set; `None` = off.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Effects<S> {
    /// A-degradation (eq. 3.5).
    pub a_degradation: Option<ADegradation<S>>,
    /// Strength degradation (eq. 3.6).
    pub strength_degradation: Option<StrengthDegradation<S>>,
    /// Stiffness degradation (eq. 3.7).
    pub stiffness_degradation: Option<StiffnessDegradation<S>>,
    /// Pinching (eqs 3.9-3.11).
    pub pinching: Option<Pinching<S>>,
    /// Asymmetry.
    pub asymmetry: Option<Asymmetry<S>>,
}

/// `Ok` unless `reads_energy` (an effect that is on reads the energy) and beta < 0
/// ([`Rule::EnergyCanFallBelowZero`]). With beta = -0.25, gamma = 0.75 and n = 1 (Zu = 2),
/// loading to u = 3 and back to 0 took the energy from 2.89 to -10.7, where the degradation
/// and pinching functions were never checked (found by review).
pub(crate) fn energy_cannot_fall_below_zero<S: Scalar>(
    base: &BoucWen<S>,
    reads_energy: bool,
) -> Result<(), ParamError> {
    if reads_energy && base.beta < S::ZERO {
        return Err(ParamError::new("beta", Rule::EnergyCanFallBelowZero));
    }
    Ok(())
}

impl<S: Scalar> Effects<S> {
    /// Which effects are on.
    pub fn set(&self) -> EffectSet {
        let mut s = EffectSet::NONE;
        if self.a_degradation.is_some() {
            s = s.with(EffectKind::ADegradation);
        }
        if self.strength_degradation.is_some() {
            s = s.with(EffectKind::StrengthDegradation);
        }
        if self.stiffness_degradation.is_some() {
            s = s.with(EffectKind::StiffnessDegradation);
        }
        if self.pinching.is_some() {
            s = s.with(EffectKind::Pinching);
        }
        if self.asymmetry.is_some() {
            s = s.with(EffectKind::Asymmetry);
        }
        s
    }

    /// Builds the effects in `set` from named values; a missing value takes
    /// the value that switches its effect off.
    pub fn build(
        set: EffectSet,
        base: &BoucWen<S>,
        energy_limit: S,
        get: &mut dyn FnMut(&'static str) -> Option<S>,
    ) -> Result<Self, ParamError> {
        let mut value = |spec: &ParamSpec| get(spec.name).unwrap_or(S::lit(spec.off));
        let mut e = Effects::default();
        if set.contains(EffectKind::ADegradation) {
            let [a0, da] = a_degradation::PARAMS.each_ref().map(&mut value);
            e.a_degradation = Some(ADegradation::new(a0, da, energy_limit)?);
        }
        if set.contains(EffectKind::StrengthDegradation) {
            let [nu0, dnu] = strength_degradation::PARAMS.each_ref().map(&mut value);
            e.strength_degradation = Some(StrengthDegradation::new(nu0, dnu, energy_limit)?);
        }
        if set.contains(EffectKind::StiffnessDegradation) {
            let [eta0, deta] = stiffness_degradation::PARAMS.each_ref().map(&mut value);
            e.stiffness_degradation = Some(StiffnessDegradation::new(eta0, deta, energy_limit)?);
        }
        if set.contains(EffectKind::Pinching) {
            let [zeta0, p, q, psi0, dpsi, lambda] = pinching::PARAMS.each_ref().map(&mut value);
            e.pinching = Some(Pinching::new(
                base,
                [zeta0, p, q, psi0, dpsi, lambda],
                ZuRule::Thesis,
                energy_limit,
            )?);
        }
        if set.contains(EffectKind::Asymmetry) {
            let [a, b] = asymmetry::PARAMS.each_ref().map(&mut value);
            e.asymmetry = Some(Asymmetry::new(base, a, b)?);
        }
        energy_cannot_fall_below_zero(base, e.reads_energy(&()))?;
        e.asymptote_fits(base, energy_limit)?;
        Ok(e)
    }

    /// `Ok` if the arithmetic holds `|z|^n` at the asymptote with the effects, `A(e) /
    /// (nu(e) nu_a (beta + gamma))` (eq. 3.12, with `nu_a` the asymmetry's weaker side), at zero
    /// energy and, where a negative rate makes it grow with the energy, at `energy_limit`
    /// (the ratio of two linear functions is largest at an end); otherwise
    /// [`Rule::DerivedOverflow`] on the parameter whose factor took it out of range.
    /// [`BoucWen::new`] checks plain Bouc-Wen's `1 / (beta + gamma)` only; in Q15.16
    /// `nu0 = 0.2` took a set that passed (8,192) to 40,960, and `|z|^n` saturated on the way
    /// there (found by review).
    fn asymptote_fits(&self, base: &BoucWen<S>, energy_limit: S) -> Result<(), ParamError> {
        let sum = base.beta + base.gamma;
        if sum <= S::ZERO {
            return Ok(());
        }
        let [a0, da] = self.a_degradation.map_or([S::ONE, S::ZERO], |x| x.values());
        let [nu0, dnu] = self
            .strength_degradation
            .map_or([S::ONE, S::ZERO], |x| x.values());
        let grows = da < S::ZERO || dnu < S::ZERO;
        let ends = [
            (S::ZERO, "A0", "nu0"),
            (energy_limit, "delta_A", "delta_nu"),
        ];
        for (e, a_name, nu_name) in ends.into_iter().take(if grows { 2 } else { 1 }) {
            let mut zu_n = S::ONE / sum;
            let factors = [
                (a_name, self.a_degradation.map(|_| a0 - da * e)),
                (
                    nu_name,
                    self.strength_degradation.map(|_| S::ONE / (nu0 + dnu * e)),
                ),
                (
                    "asym_strength",
                    self.asymmetry.map(|x| S::ONE / x.weaker_side()),
                ),
            ];
            for (name, factor) in factors {
                if let Some(f) = factor {
                    zu_n *= f;
                    if !zu_n.is_finite() {
                        return Err(ParamError::new(name, Rule::DerivedOverflow));
                    }
                }
            }
        }
        Ok(())
    }

    /// Calls `f` with every parameter of the effects that are on.
    pub fn for_each_value(&self, f: &mut dyn FnMut(&'static ParamSpec, S)) {
        if let Some(x) = &self.a_degradation {
            a_degradation::PARAMS
                .iter()
                .zip(x.values())
                .for_each(|(s, v)| f(s, v));
        }
        if let Some(x) = &self.strength_degradation {
            strength_degradation::PARAMS
                .iter()
                .zip(x.values())
                .for_each(|(s, v)| f(s, v));
        }
        if let Some(x) = &self.stiffness_degradation {
            stiffness_degradation::PARAMS
                .iter()
                .zip(x.values())
                .for_each(|(s, v)| f(s, v));
        }
        if let Some(x) = &self.pinching {
            pinching::PARAMS
                .iter()
                .zip(x.values())
                .for_each(|(s, v)| f(s, v));
        }
        if let Some(x) = &self.asymmetry {
            asymmetry::PARAMS
                .iter()
                .zip(x.values())
                .for_each(|(s, v)| f(s, v));
        }
    }

    /// Whether an effect that is on reads the energy (degradation of A, nu
    /// or eta, pinching; asymmetry does not), or the extra effect may.
    pub fn reads_energy<X: Effect<S>>(&self, extra: &X) -> bool {
        self.a_degradation.is_some()
            || self.strength_degradation.is_some()
            || self.stiffness_degradation.is_some()
            || self.pinching.is_some()
            || extra.reads_energy()
    }

    /// Applies the effects: degradation and asymmetry first, then the extra
    /// effect, then pinching (which reads the degraded A and nu through Zu).
    #[inline]
    pub fn apply<X: Effect<S>>(
        &self,
        extra: &X,
        base: &BoucWen<S>,
        zu_plain: Option<S>,
        at: &At<S>,
        c: &mut Coefficients<S>,
    ) {
        if let Some(x) = &self.a_degradation {
            x.apply(base, zu_plain, at, c);
        }
        if let Some(x) = &self.strength_degradation {
            x.apply(base, zu_plain, at, c);
        }
        if let Some(x) = &self.stiffness_degradation {
            x.apply(base, zu_plain, at, c);
        }
        if let Some(x) = &self.asymmetry {
            x.apply(base, zu_plain, at, c);
        }
        extra.apply(base, zu_plain, at, c);
        if let Some(x) = &self.pinching {
            x.apply(base, zu_plain, at, c);
        }
    }

    /// The restoring-force springs at `at` (asymmetry, then the extra
    /// effect).
    #[inline]
    pub fn stiffness<X: Effect<S>>(
        &self,
        extra: &X,
        base: &BoucWen<S>,
        at: &At<S>,
    ) -> Stiffness<S> {
        let mut k = Stiffness::plain(base);
        if let Some(x) = &self.asymmetry {
            x.stiffness(base, at, &mut k);
        }
        extra.stiffness(base, at, &mut k);
        k
    }
}

/// Checks that `v(e) = v0 + rate * e` stays positive for e in [0, limit].
pub(crate) fn check_linear_positive<S: Scalar>(
    v0_name: &'static str,
    v0: S,
    rate_name: &'static str,
    rate: S,
    limit: S,
) -> Result<(), ParamError> {
    if !v0.is_finite() {
        return Err(ParamError::new(v0_name, Rule::NotFinite));
    }
    if !rate.is_finite() {
        return Err(ParamError::new(rate_name, Rule::NotFinite));
    }
    if v0 <= S::ZERO {
        return Err(ParamError::new(v0_name, Rule::NotPositive));
    }
    if rate < S::ZERO {
        let end = v0 + rate * limit;
        if !(end > S::ZERO) || !end.is_finite() {
            return Err(ParamError::new(rate_name, Rule::DegradesToZero));
        }
    }
    Ok(())
}
