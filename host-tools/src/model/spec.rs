//! The one grammar for model specs used by every verb:
//!
//! ```text
//! spec   = base { "+" effect }
//! base   = "bw" | "bwbn"
//! effect = "a-degradation" | "strength-degradation" | "stiffness-degradation"
//!        | "pinching" | "asymmetry" | a registered custom effect
//! ```
//!
//! `bwbn` is `bw` with the four effects of the thesis' 17-parameter model.

use super::custom::{self, CustomEffect, Extras};
use anyhow::{bail, Result};
use hysteresis::bwbn::{specs, BwbnParams, EffectKind, EffectSet, ParamError, ParamSpec, Rule};
use std::fmt;

/// The base of a model spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// Plain Bouc-Wen (5 parameters).
    Bw,
}

/// One effect a spec can hold: built into the core or registered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EffectRef {
    /// A core effect module.
    Builtin(EffectKind),
    /// The registered custom effect with this index.
    Custom(usize),
}

impl EffectRef {
    /// Its name in specs.
    pub fn name(self) -> &'static str {
        match self {
            EffectRef::Builtin(k) => k.name(),
            EffectRef::Custom(i) => custom::registered()[i].name(),
        }
    }
    /// Its parameters.
    pub fn params(self) -> &'static [ParamSpec] {
        match self {
            EffectRef::Builtin(k) => k.params(),
            EffectRef::Custom(i) => custom::registered()[i].params(),
        }
    }
    /// Whether `name` is one of its parameters (names are unique across
    /// effects: registration refuses a taken one).
    pub fn owns(self, name: &str) -> bool {
        self.params().iter().any(|p| p.name == name)
    }
    /// One sentence on what it models.
    pub fn doc(self) -> &'static str {
        match self {
            EffectRef::Builtin(k) => k.doc(),
            EffectRef::Custom(i) => custom::registered()[i].doc(),
        }
    }
    /// The effect with this name, built in or registered.
    pub fn from_name(name: &str) -> Option<Self> {
        EffectKind::from_name(name)
            .map(EffectRef::Builtin)
            .or_else(|| custom::find(name).map(|(i, _)| EffectRef::Custom(i)))
    }
    /// Every effect: the built-in ones, then the registered ones.
    pub fn all() -> Vec<EffectRef> {
        let mut v: Vec<EffectRef> = EffectKind::ALL
            .iter()
            .map(|k| EffectRef::Builtin(*k))
            .collect();
        v.extend((0..custom::registered().len()).map(EffectRef::Custom));
        v
    }
}

/// A parsed model spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelSpec {
    /// The base model.
    pub base: Base,
    /// The built-in effects on top of it.
    pub effects: EffectSet,
    /// The registered effects on top of it (bit i = registered effect i).
    pub custom: u32,
}

impl ModelSpec {
    /// Plain Bouc-Wen.
    pub const BW: ModelSpec = ModelSpec {
        base: Base::Bw,
        effects: EffectSet::NONE,
        custom: 0,
    };

    /// Parses a spec such as `bw+pinching+strength-degradation`, in any
    /// case (`BW+Pinching`: units are read in any case, and so are these).
    pub fn parse(text: &str) -> Result<Self> {
        let mut parts = text.trim().split('+').map(str::trim);
        let base = parts.next().unwrap_or_default();
        let mut spec = match base.to_ascii_lowercase().as_str() {
            "bw" => ModelSpec::BW,
            "bwbn" => ModelSpec { effects: EffectSet::BWBN, ..ModelSpec::BW },
            "" if text.contains('+') => bail!("`{text}` has no base: expected `bw` or `bwbn` before the +effect terms, e.g. `bw{}`", text.trim()),
            "" => bail!("empty model spec: expected a base, `bw` or `bwbn`, optionally followed by +effect terms"),
            other if other.starts_with("phm") => bail!("unknown model base `{other}` in `{text}`: expected `bw` or `bwbn`; the torsion PHM is `phm-torsion`, which `fit` and `simulate` read"),
            other => bail!("unknown model base `{other}` in `{text}`: expected `bw` or `bwbn`"),
        };
        for name in parts {
            if name.is_empty() {
                bail!("`{text}` has a `+` with no effect after it: expected `+EFFECT`, e.g. `bw+pinching`");
            }
            let Some(effect) = EffectRef::all()
                .into_iter()
                .find(|e| e.name().eq_ignore_ascii_case(name))
            else {
                let known: Vec<_> = EffectRef::all().iter().map(|e| e.name()).collect();
                bail!(
                    "unknown effect `{name}` in `{text}`: known effects are {}",
                    known.join(", ")
                );
            };
            if spec.contains(effect) {
                let thesis = base.eq_ignore_ascii_case("bwbn")
                    && EffectSet::BWBN
                        .iter()
                        .any(|k| EffectRef::Builtin(k) == effect);
                match thesis {
                    true => bail!("effect `{name}` appears twice in `{text}`: `bwbn` already includes the four thesis effects"),
                    false => bail!("effect `{name}` appears twice in `{text}`"),
                }
            }
            spec = spec.with(effect);
        }
        Ok(spec)
    }

    /// Whether the spec holds `effect`.
    pub fn contains(&self, effect: EffectRef) -> bool {
        match effect {
            EffectRef::Builtin(k) => self.effects.contains(k),
            EffectRef::Custom(i) => self.custom & (1 << i) != 0,
        }
    }

    /// The spec with `effect` added.
    pub fn with(self, effect: EffectRef) -> Self {
        match effect {
            EffectRef::Builtin(k) => ModelSpec {
                effects: self.effects.with(k),
                ..self
            },
            EffectRef::Custom(i) => ModelSpec {
                custom: self.custom | 1 << i,
                ..self
            },
        }
    }

    /// The spec with `effect` removed.
    pub fn without(self, effect: EffectRef) -> Self {
        match effect {
            EffectRef::Builtin(k) => ModelSpec {
                effects: self
                    .effects
                    .iter()
                    .filter(|e| *e != k)
                    .fold(EffectSet::NONE, EffectSet::with),
                ..self
            },
            EffectRef::Custom(i) => ModelSpec {
                custom: self.custom & !(1 << i),
                ..self
            },
        }
    }

    /// The effects in the spec, built-in first.
    pub fn effects(&self) -> Vec<EffectRef> {
        EffectRef::all()
            .into_iter()
            .filter(|e| self.contains(*e))
            .collect()
    }

    /// The effects not in the spec: the candidates a diagnosis weighs.
    pub fn missing(&self) -> Vec<EffectRef> {
        EffectRef::all()
            .into_iter()
            .filter(|e| !self.contains(*e))
            .collect()
    }

    /// Whether an effect of the model reads the hysteretic energy (the
    /// thesis' four do; asymmetry does not; a registered effect may), so
    /// that `energy_limit` means something for it.
    pub fn reads_energy(&self) -> bool {
        self.custom != 0 || EffectKind::THESIS.iter().any(|&k| self.effects.contains(k))
    }

    /// Every parameter of the model: base, built-in effects, custom effects.
    pub fn params(&self) -> Vec<ParamSpec> {
        let mut v: Vec<ParamSpec> = specs(self.effects).copied().collect();
        for (i, e) in custom::registered().iter().enumerate() {
            if self.custom & (1 << i) != 0 {
                v.extend_from_slice(e.params());
            }
        }
        v
    }

    /// Builds the model from named values: built-in parameters through the
    /// core's validation, custom ones through their effect's `build`. A
    /// missing effect parameter takes its off value.
    pub fn build(
        &self,
        get: impl Fn(&str) -> Option<f64>,
    ) -> Result<(BwbnParams<f64>, Extras), ParamError> {
        let params = BwbnParams::from_named(self.effects, &get)?;
        let mut extras = Extras::default();
        for (i, e) in custom::registered().iter().enumerate() {
            if self.custom & (1 << i) == 0 {
                continue;
            }
            let values: Vec<f64> = e
                .params()
                .iter()
                .map(|s| get(s.name).unwrap_or(s.off as f64))
                .collect();
            if let Some((s, _)) = e.params().iter().zip(&values).find(|(_, v)| !v.is_finite()) {
                return Err(ParamError {
                    field: s.name,
                    rule: Rule::NotFinite,
                });
            }
            extras
                .0
                .push(CustomEffect::build(*e, params.base(), &values)?);
        }
        Ok((params, extras))
    }
}

impl fmt::Display for ModelSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let thesis = EffectKind::THESIS.iter().all(|k| self.effects.contains(*k));
        f.write_str(if thesis { "bwbn" } else { "bw" })?;
        for e in self.effects() {
            if let EffectRef::Builtin(k) = e {
                if thesis && EffectKind::THESIS.contains(&k) {
                    continue;
                }
            }
            write!(f, "+{}", e.name())?;
        }
        Ok(())
    }
}

impl std::str::FromStr for ModelSpec {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        Self::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_prints_canonically() {
        let s = ModelSpec::parse("bw+pinching+strength-degradation").unwrap();
        assert!(s.effects.contains(EffectKind::Pinching));
        assert_eq!(s.to_string(), "bw+strength-degradation+pinching");
        assert_eq!(ModelSpec::parse("bwbn").unwrap().to_string(), "bwbn");
        assert_eq!(ModelSpec::parse(" bw ").unwrap(), ModelSpec::BW);
        assert_eq!(
            ModelSpec::parse("bwbn+asymmetry").unwrap().to_string(),
            "bwbn+asymmetry"
        );
        let all = "bw+asymmetry+pinching+a-degradation+strength-degradation+stiffness-degradation";
        assert_eq!(ModelSpec::parse(all).unwrap().to_string(), "bwbn+asymmetry");
        assert_eq!(
            ModelSpec::BW.missing().len(),
            EffectKind::ALL.len() + custom::registered().len()
        );
    }

    #[test]
    fn rejects_with_a_reason() {
        let e = ModelSpec::parse("bw+pinch").unwrap_err().to_string();
        assert!(
            e.contains("unknown effect `pinch`") && e.contains("pinching"),
            "{e}"
        );
        assert!(ModelSpec::parse("bwbn+pinching")
            .unwrap_err()
            .to_string()
            .contains("twice"));
        assert!(ModelSpec::parse("xyz")
            .unwrap_err()
            .to_string()
            .contains("unknown model base"));
        assert!(ModelSpec::parse("").is_err());
        // Found by review: "unknown effect ``", and no word of the PHM.
        let e = ModelSpec::parse("bw+").unwrap_err().to_string();
        assert!(e.contains("a `+` with no effect after it"), "{e}");
        let e = ModelSpec::parse("phm").unwrap_err().to_string();
        assert!(e.contains("`phm-torsion`"), "{e}");
    }

    /// Units are read in any case; so are specs (found by review: `BW` was refused).
    #[test]
    fn reads_a_spec_in_any_case() {
        assert_eq!(ModelSpec::parse("BW").unwrap(), ModelSpec::BW);
        assert_eq!(
            ModelSpec::parse("BW+Pinching").unwrap(),
            ModelSpec::BW.with(EffectRef::Builtin(EffectKind::Pinching))
        );
        assert_eq!(ModelSpec::parse("BWBN").unwrap().to_string(), "bwbn");
    }
}
