//! A validated BWBN parameter set: the base model, its effects and the energy
//! range the set is valid for.

use super::base::{self, BoucWen};
use super::effects::At;
use super::effects::{Coefficients, Effect, EffectKind, EffectSet, Effects, Stiffness, ZuRule};
use super::spec::{ParamError, ParamSpec, Rule};
use crate::scalar::Scalar;

/// Name of the optional energy-range parameter.
pub const ENERGY_LIMIT: &str = "energy_limit";

/// A validated parameter set of the Bouc-Wen-Baber-Noori model.
///
/// Built once (validation happens here, never during a step), then shared by
/// any number of elements.
///
/// ```
/// use hysteresis::bwbn::{BwbnParams, EffectSet, EffectKind};
/// let set = EffectSet::NONE.with(EffectKind::Pinching);
/// let p = BwbnParams::<f64>::from_named(set, |name| match name {
///     "k0" => Some(6.0), "alpha" => Some(0.2), "n" => Some(1.2),
///     "beta" => Some(2.0), "gamma" => Some(-1.0), "zeta0" => Some(0.9),
///     _ => None, // the other pinching parameters take their defaults
/// }).unwrap();
/// assert_eq!(p.get("zeta0"), Some(0.9));
/// assert_eq!(p.len(), 5 + 6);
///
/// // Pinching needs Zu, which a hardening set (beta + gamma <= 0) lacks:
/// let err = BwbnParams::<f64>::from_named(set, |name| match name {
///     "k0" => Some(6.0), "alpha" => Some(0.2), "n" => Some(1.2),
///     "beta" => Some(1.0), "gamma" => Some(-1.5), _ => None,
/// }).unwrap_err();
/// assert_eq!(err.to_string(), "beta + gamma pinching needs Zu = (A/(nu(beta+gamma)))^(1/n) (eq. 3.12), undefined when beta + gamma <= 0");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BwbnParams<S> {
    base: BoucWen<S>,
    effects: Effects<S>,
    energy_limit: S,
    zu_plain: Option<S>,
    z_scale: S,
}

impl<S: Scalar> BwbnParams<S> {
    /// Plain Bouc-Wen.
    pub fn plain(base: BoucWen<S>) -> Self {
        BwbnParams {
            base,
            effects: Effects::default(),
            energy_limit: S::MAX,
            zu_plain: base.zu(),
            z_scale: base.z_scale(),
        }
    }

    /// Builds a parameter set with the effects in `set` from named values
    /// (names as in [`ParamSpec::name`], plus the optional `energy_limit`,
    /// default: no limit). Base parameters are required; a missing effect
    /// parameter takes the value that switches its effect off.
    pub fn from_named(
        set: EffectSet,
        mut get: impl FnMut(&str) -> Option<S>,
    ) -> Result<Self, ParamError> {
        let mut vals = [S::ZERO; 5];
        for (v, spec) in vals.iter_mut().zip(base::PARAMS.iter()) {
            *v = get(spec.name).ok_or(ParamError::new(spec.name, Rule::Missing))?;
        }
        let [k0, alpha, n, beta, gamma] = vals;
        let b = BoucWen::new(k0, alpha, n, beta, gamma)?;
        let energy_limit = match get(ENERGY_LIMIT) {
            Some(l) if !l.is_finite() => {
                return Err(ParamError::new(ENERGY_LIMIT, Rule::NotFinite))
            }
            Some(l) if l <= S::ZERO => {
                return Err(ParamError::new(ENERGY_LIMIT, Rule::NotPositive))
            }
            Some(l) => l,
            None => S::MAX,
        };
        let effects = Effects::build(set, &b, energy_limit, &mut |name| get(name))?;
        let mut p = Self::plain(b);
        p.effects = effects;
        p.energy_limit = energy_limit;
        p.z_scale = p.z_scale_with_effects();
        Ok(p)
    }

    /// The same parameter set with pinching's Zu computed the way OpenSees'
    /// `BWBN` material does (see [`ZuRule`]).
    pub fn with_zu_rule(mut self, rule: ZuRule) -> Self {
        self.effects.pinching = self.effects.pinching.map(|p| p.with_zu_rule(rule));
        self
    }

    /// The same set per unit mass: `k0 / mass` (the oscillator's `w0^2`),
    /// everything else unchanged, for [`Sdof`](super::Sdof).
    pub fn per_unit_mass(&self, mass: S) -> Result<Self, ParamError> {
        if !mass.is_finite() {
            return Err(ParamError::new("m", Rule::NotFinite));
        }
        if mass <= S::ZERO {
            return Err(ParamError::new("m", Rule::NotPositive));
        }
        let k0 = self.base.k0 / mass;
        Ok(Self::from_named(self.effect_set(), |name| {
            if name == "k0" {
                Some(k0)
            } else {
                self.get(name)
            }
        })?
        .with_zu_rule(self.zu_rule()))
    }

    /// How pinching computes Zu ([`ZuRule::Thesis`] without pinching).
    pub fn zu_rule(&self) -> ZuRule {
        self.effects
            .pinching
            .map(|p| p.zu_rule())
            .unwrap_or(ZuRule::Thesis)
    }

    /// The base model.
    pub fn base(&self) -> &BoucWen<S> {
        &self.base
    }
    /// The built-in effects.
    pub fn effects(&self) -> &Effects<S> {
        &self.effects
    }
    /// Which built-in effects are on.
    pub fn effect_set(&self) -> EffectSet {
        self.effects.set()
    }
    /// The largest dissipated energy the set was validated for.
    pub fn energy_limit(&self) -> S {
        self.energy_limit
    }
    /// Zu of the base model (A = nu = 1), `None` for hardening sets.
    pub fn zu(&self) -> Option<S> {
        self.zu_plain
    }
    /// The scale of z that integration tolerances refer to (Zu with the
    /// initial A and nu when it exists).
    pub fn z_scale(&self) -> S {
        self.z_scale
    }

    fn z_scale_with_effects(&self) -> S {
        let at = At {
            u: S::ZERO,
            z: S::ZERO,
            energy: S::ZERO,
            dir: S::ONE,
        };
        let mut c = Coefficients::PLAIN;
        self.effects
            .apply(&(), &self.base, self.zu_plain, &at, &mut c);
        c.zu(&self.base, self.zu_plain)
            .unwrap_or(self.base.z_scale())
    }

    /// Calls `f` with every parameter of the set (base first, then the effects
    /// in order of application).
    pub fn for_each(&self, mut f: impl FnMut(&'static ParamSpec, S)) {
        base::PARAMS
            .iter()
            .zip(self.base.values())
            .for_each(|(s, v)| f(s, v));
        self.effects.for_each_value(&mut f);
    }

    /// The value of the parameter `name`, if the set has it.
    pub fn get(&self, name: &str) -> Option<S> {
        if name == ENERGY_LIMIT {
            return Some(self.energy_limit);
        }
        let mut found = None;
        self.for_each(|s, v| {
            if s.name == name {
                found = Some(v);
            }
        });
        found
    }

    /// The number of parameters (5 for plain Bouc-Wen, 17 for the thesis' BWBN).
    pub fn len(&self) -> usize {
        let mut n = 0;
        self.for_each(|_, _| n += 1);
        n
    }

    /// Always false: every set has the five base parameters.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The rate coefficients and springs at `at`.
    #[inline]
    pub(crate) fn coefficients<X: Effect<S>>(&self, extra: &X, at: &At<S>) -> Coefficients<S> {
        let mut c = Coefficients::PLAIN;
        self.effects
            .apply(extra, &self.base, self.zu_plain, at, &mut c);
        c
    }

    /// The restoring-force springs at `at`.
    #[inline]
    pub(crate) fn stiffness<X: Effect<S>>(&self, extra: &X, at: &At<S>) -> Stiffness<S> {
        self.effects.stiffness(extra, &self.base, at)
    }
}

/// The parameter specs of a model with the effects in `set`, in the order of
/// [`BwbnParams::for_each`].
pub fn specs(set: EffectSet) -> impl Iterator<Item = &'static ParamSpec> {
    base::PARAMS
        .iter()
        .chain(set.iter().flat_map(|k: EffectKind| k.params().iter()))
}
