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

use anyhow::{bail, Result};
use hysteresis::bwbn::{EffectKind, EffectSet};
use std::fmt;

/// The base of a model spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// Plain Bouc-Wen (5 parameters).
    Bw,
}

/// A parsed model spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelSpec {
    /// The base model.
    pub base: Base,
    /// The effects on top of it.
    pub effects: EffectSet,
}

impl ModelSpec {
    /// Plain Bouc-Wen.
    pub const BW: ModelSpec = ModelSpec {
        base: Base::Bw,
        effects: EffectSet::NONE,
    };

    /// Parses a spec such as `bw+pinching+strength-degradation`.
    pub fn parse(text: &str) -> Result<Self> {
        let mut parts = text.trim().split('+').map(str::trim);
        let base = parts.next().unwrap_or_default();
        let mut effects = match base {
            "bw" => EffectSet::NONE,
            "bwbn" => EffectSet::BWBN,
            "" => bail!("empty model spec: expected a base, `bw` or `bwbn`, optionally followed by +effect terms"),
            other => bail!("unknown model base `{other}` in `{text}`: expected `bw` or `bwbn`"),
        };
        for name in parts {
            let Some(kind) = EffectKind::from_name(name) else {
                let known: Vec<_> = EffectKind::ALL.iter().map(|k| k.name()).collect();
                bail!(
                    "unknown effect `{name}` in `{text}`: known effects are {}",
                    known.join(", ")
                );
            };
            if effects.contains(kind) {
                bail!("effect `{name}` appears twice in `{text}` (`bwbn` already includes the four thesis effects)");
            }
            effects = effects.with(kind);
        }
        Ok(ModelSpec {
            base: Base::Bw,
            effects,
        })
    }

    /// The spec with `kind` added.
    pub fn with(self, kind: EffectKind) -> Self {
        ModelSpec {
            effects: self.effects.with(kind),
            ..self
        }
    }
}

impl fmt::Display for ModelSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let thesis = EffectKind::THESIS.iter().all(|k| self.effects.contains(*k));
        f.write_str(if thesis { "bwbn" } else { "bw" })?;
        for k in self.effects.iter() {
            if !(thesis && EffectKind::THESIS.contains(&k)) {
                write!(f, "+{}", k.name())?;
            }
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
        assert_eq!(
            ModelSpec::parse("bwbn+asymmetry").unwrap().to_string(),
            "bwbn+asymmetry"
        );
        let all4 = "bw+asymmetry+pinching+a-degradation+strength-degradation+stiffness-degradation";
        assert_eq!(
            ModelSpec::parse(all4).unwrap().to_string(),
            "bwbn+asymmetry"
        );
        assert_eq!(ModelSpec::parse(" bw ").unwrap(), ModelSpec::BW);
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
    }
}
