//! Effects defined outside this crate.
//!
//! A program that links `hyst` can add a physical effect of its own without
//! editing the library: implement [`CustomEffect`] (its name in model specs,
//! its parameters, and how to build the core [`Effect`] from their values),
//! [`register`] it at start-up, and every verb (`simulate`, `fit`,
//! `diagnose`, `discover`) accepts `bw+yourname`, fits its parameters,
//! reports them and proposes it as a suspect. `examples/custom_effect.rs`
//! shows a complete program.

use anyhow::{bail, Result};
use hysteresis::bwbn::effects::{At, Coefficients, Effect, Stiffness};
use hysteresis::bwbn::{BoucWen, EffectKind, ParamError, ParamSpec};
use std::sync::RwLock;

/// An effect defined outside the library.
pub trait CustomEffect: Send + Sync + 'static {
    /// Its name in model specs (`bw+NAME`); lower case, `-` between words.
    fn name(&self) -> &'static str;
    /// Its parameters (names must not clash with the built-in ones).
    fn params(&self) -> &'static [ParamSpec];
    /// One sentence on what it models (shown with the suspects).
    fn doc(&self) -> &'static str;
    /// The effect with `values` (in the order of [`params`](Self::params)),
    /// validated: reject what cannot work with a [`ParamError`].
    fn build(
        &self,
        base: &BoucWen<f64>,
        values: &[f64],
    ) -> Result<Box<dyn Effect<f64> + Send + Sync>, ParamError>;
}

static REGISTRY: RwLock<Vec<&'static dyn CustomEffect>> = RwLock::new(Vec::new());

/// Makes `effect` available to model specs. Fails if its name or a parameter
/// name is taken, or more than 32 effects are registered.
pub fn register(effect: &'static dyn CustomEffect) -> Result<()> {
    let mut reg = REGISTRY.write().expect("effect registry lock");
    let name = effect.name();
    if name == "bw"
        || name == "bwbn"
        || EffectKind::from_name(name).is_some()
        || reg.iter().any(|e| e.name() == name)
    {
        bail!("cannot register effect `{name}`: the name is taken");
    }
    let builtin = hysteresis::bwbn::specs(hysteresis::bwbn::EffectSet::ALL).map(|s| s.name);
    let taken: Vec<&str> = builtin
        .chain(reg.iter().flat_map(|e| e.params().iter().map(|s| s.name)))
        .collect();
    for p in effect.params() {
        if taken.contains(&p.name) || ["m", "xi", "energy_limit"].contains(&p.name) {
            bail!(
                "cannot register effect `{name}`: parameter `{}` is taken",
                p.name
            );
        }
    }
    if reg.len() >= 32 {
        bail!("cannot register effect `{name}`: at most 32 custom effects");
    }
    reg.push(effect);
    Ok(())
}

/// The registered effects, in registration order (bit i of a spec's custom
/// mask is effect i).
pub fn registered() -> Vec<&'static dyn CustomEffect> {
    REGISTRY.read().expect("effect registry lock").clone()
}

/// The registered effect with this name and its index.
pub fn find(name: &str) -> Option<(usize, &'static dyn CustomEffect)> {
    registered()
        .into_iter()
        .enumerate()
        .find(|(_, e)| e.name() == name)
}

/// The custom effects of one model, applied in registration order after the
/// built-in degradation and asymmetry and before pinching.
#[derive(Default)]
pub struct Extras(pub Vec<Box<dyn Effect<f64> + Send + Sync>>);

impl std::fmt::Debug for Extras {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Extras({} effects)", self.0.len())
    }
}

impl Effect<f64> for Extras {
    #[inline]
    fn apply(&self, base: &BoucWen<f64>, zu: Option<f64>, at: &At<f64>, c: &mut Coefficients<f64>) {
        for e in &self.0 {
            e.apply(base, zu, at, c);
        }
    }
    #[inline]
    fn stiffness(&self, base: &BoucWen<f64>, at: &At<f64>, k: &mut Stiffness<f64>) {
        for e in &self.0 {
            e.stiffness(base, at, k);
        }
    }
    /// No custom effect (the usual case): plain Bouc-Wen can be summed as
    /// series, as in the dual-number simulation of the same model.
    #[inline]
    fn is_none(&self) -> bool {
        self.0.iter().all(|e| e.is_none())
    }
    /// Whether one of the registered effects reads the energy: none does when there is none.
    /// (The trait's default, `true`, made a plain `bw` set with beta < 0 count as reading it,
    /// and be refused for it.)
    fn reads_energy(&self) -> bool {
        self.0.iter().any(|e| e.reads_energy())
    }
}
