//! Parameter files: one flat JSON object keyed by the thesis' symbols spelled
//! out (`k0`, `alpha`, `n`, `beta`, `gamma`, `A0`, `delta_A`, `nu0`,
//! `delta_nu`, `eta0`, `delta_eta`, `zeta0`, `p`, `q`, `psi0`, `delta_psi`,
//! `lambda`, plus `m` and `xi` for dynamics and the optional `energy_limit`).
//!
//! Three more keys may appear: `"model"` (the spec the set belongs to, e.g.
//! `"bw+pinching"`), `"units"` (`{"displacement": "mm", "force": "kN"}`) and
//! `"fit"` (what `hyst fit` records about how the set was obtained). Every
//! other key must be a parameter of the model, with a finite number: a
//! misspelt or foreign name is an error, never ignored.
//!
//! ```json
//! {"model": "bw", "k0": 6.0, "alpha": 0.2, "n": 1.2, "beta": 2.0, "gamma": -1.0}
//! ```

use super::{Extras, ModelSpec};
use crate::data::json_place::JsonFile;
use crate::data::{Quantity, Unit};
use anyhow::{anyhow, bail, Context, Result};
use hysteresis::bwbn::{BwbnParams, ENERGY_LIMIT};
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Keys that are not model parameters.
const META: [&str; 3] = ["model", "units", "fit"];
/// Parameters of the oscillator, not of the hysteretic element.
const DYNAMIC: [&str; 2] = ["m", "xi"];

/// A parameter file as read.
#[derive(Clone, Debug, Default)]
pub struct ParamFile {
    /// Where it came from.
    pub path: PathBuf,
    /// The `model` key, if present.
    pub model: Option<ModelSpec>,
    /// Numeric parameters by name.
    pub values: BTreeMap<String, f64>,
    /// The `(displacement, force)` units, if stated (checked, and compared as units: `KN` is
    /// kN).
    pub units: Option<(Unit, Unit)>,
    /// The `fit` object, if present.
    pub fit: Option<Value>,
    /// The file's text, to place errors about its values.
    text: String,
}

/// A `units` object of exactly the two `keys`, each a unit of its quantity, both given
/// (parameter files: `displacement` and `force`; PHM files: `twist` and `torque`): each unit as
/// written and as read, in the order of `keys`.
pub(super) fn checked_units<'a>(
    file: JsonFile,
    u: &'a Map<String, Value>,
    keys: [(&str, Quantity); 2],
) -> Result<[(&'a str, Unit); 2]> {
    if let Some(other) = u.keys().find(|k| keys.iter().all(|(key, _)| key != k)) {
        bail!(
            "{}: \"units\" has a key \"{other}\"; expected \"{}\" and \"{}\"",
            file.at(&["units", other]),
            keys[0].0,
            keys[1].0
        );
    }
    let unit = |(key, quantity): (&str, Quantity)| -> Result<(&'a str, Unit)> {
        let text = u.get(key).and_then(Value::as_str).ok_or_else(|| {
            anyhow!(
                "{}: \"units\" needs \"{key}\" as a string ({})",
                file.at(&["units", key]),
                quantity.known_symbols()
            )
        })?;
        match Unit::parse(text) {
            Some(unit) if unit.quantity() == quantity => Ok((text, unit)),
            _ => {
                let article = if quantity == Quantity::Angle {
                    "an"
                } else {
                    "a"
                };
                bail!(
                    "{}: \"units\".\"{key}\" is '{text}'; expected {article} {quantity} unit ({})",
                    file.at(&["units", key]),
                    quantity.known_symbols()
                )
            }
        }
    };
    Ok([unit(keys[0])?, unit(keys[1])?])
}

impl ParamFile {
    /// Reads and checks the form of a parameter file (names are checked
    /// against a model by [`ParamFile::build`]) for the verbs that simulate
    /// on the host, in mm and kN: a file whose `units` state others is
    /// refused, not read as mm and kN. (`hyst export` reads any stated units
    /// with [`parse`](Self::parse) and labels the table with them.)
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = crate::data::read_text(path)?;
        let file = Self::parse(path, &text)?;
        if let Some((d, f)) = file.units {
            if (d, f) != (Unit::Millimetre, Unit::Kilonewton) {
                bail!(
                    "{}: parameters in {d} and {f}, but hyst simulates in mm and kN: give them in mm and kN (a device table takes other units from `hyst export`)",
                    file.at(&["units"])
                );
            }
        }
        Ok(file)
    }

    /// Parses the text of a parameter file.
    pub fn parse(path: &Path, text: &str) -> Result<Self> {
        let value: Value = crate::data::unique_keys::parse_file(path, text)?;
        let at = JsonFile::new(path, Some(text));
        let Value::Object(mut map) = value else {
            bail!(
                "{}: expected a JSON object of parameters, found {}",
                path.display(),
                kind(&value)
            );
        };
        let mut file = ParamFile {
            path: path.to_path_buf(),
            text: text.to_string(),
            ..Default::default()
        };
        // The model first: a PHM file, or a misspelt model, was reported as its first
        // non-numeric key in alphabetical order (`"coefficients" must be a number`).
        if let Some(Value::String(s)) = map.get("model") {
            if s == super::PHM_MODEL {
                bail!(
                    "{}: a PHM file (model {s}): this command takes the parameters of a Bouc-Wen model (bw, bwbn, ...)",
                    at.at(&["model"])
                );
            }
            file.model = Some(
                ModelSpec::parse(s)
                    .with_context(|| format!("{}: key \"model\"", at.at(&["model"])))?,
            );
            map.remove("model");
        }
        for (key, v) in map {
            match (key.as_str(), v) {
                ("units", Value::Object(u)) => {
                    let [(_, d), (_, f)] = checked_units(
                        at,
                        &u,
                        [
                            ("displacement", Quantity::Length),
                            ("force", Quantity::Force),
                        ],
                    )?;
                    file.units = Some((d, f));
                }
                // What `hyst fit` records about the fit: an object.
                ("fit", v @ Value::Object(_)) => file.fit = Some(v),
                (k, v) if META.contains(&k) => bail!(
                    "{}: key \"{k}\" has the wrong type ({})",
                    at.at(&[k]),
                    kind(&v)
                ),
                (_, Value::Number(n)) => {
                    let x = n.as_f64().filter(|x| x.is_finite()).ok_or_else(|| {
                        anyhow!(
                            "{}: parameter \"{key}\" is not a finite number",
                            at.at(&[&key])
                        )
                    })?;
                    file.values.insert(key, x);
                }
                (_, v) => bail!(
                    "{}: parameter \"{key}\" must be a number, found {}",
                    at.at(&[&key]),
                    kind(&v)
                ),
            }
        }
        Ok(file)
    }

    /// The spec to use: `cli` if given (it must agree with the file's), else
    /// the file's.
    pub fn spec(&self, cli: Option<ModelSpec>) -> Result<ModelSpec> {
        match (cli, self.model) {
            (Some(c), Some(f)) if c != f => bail!(
                "--model {c} disagrees with {}, which holds parameters of model {f}",
                self.path.display()
            ),
            (Some(c), _) => Ok(c),
            (None, Some(f)) => Ok(f),
            (None, None) => bail!(
                "no model: give --model or a \"model\" key in {}",
                self.path.display()
            ),
        }
    }

    /// Notes for the effects of `spec` that have parameters, none of which the file
    /// gives: they take the values that switch the effect off, which a file
    /// naming the effect in its model most likely did not mean (it ran as
    /// the model without it, without a word: found by review).
    pub fn switched_off(&self, spec: ModelSpec) -> Vec<String> {
        spec.effects()
            .into_iter()
            .filter(|e| {
                !e.params().is_empty()
                    && e.params().iter().all(|p| !self.values.contains_key(p.name))
            })
            .map(|e| {
                let names: Vec<&str> = e.params().iter().map(|p| p.name).collect();
                format!(
                    "{}: model {spec} has {}, but none of its parameters ({}) is given: they take \
                     the values that switch it off",
                    self.path.display(),
                    e.name(),
                    names.join(", ")
                )
            })
            .collect()
    }

    /// The model parameter set of `spec` (validated), rejecting names that do
    /// not belong to it. `dynamic` allows `m` and `xi`.
    pub fn build(&self, spec: ModelSpec, dynamic: bool) -> Result<(BwbnParams<f64>, Extras)> {
        let all = spec.params();
        let mut known: Vec<&str> = all.iter().map(|s| s.name).collect();
        // The list of a model no effect of which reads the energy named
        // `energy_limit`, which it then refused (found by review).
        if spec.reads_energy() {
            known.push(ENERGY_LIMIT);
        }
        for name in self.values.keys() {
            let ok = known.contains(&name.as_str())
                || name == ENERGY_LIMIT
                || (dynamic && DYNAMIC.contains(&name.as_str()));
            if !ok {
                let hint = if DYNAMIC.contains(&name.as_str()) {
                    " (it belongs to force-driven dynamics)".to_string()
                } else {
                    format!("; model {spec} has {}", known.join(", "))
                };
                bail!(
                    "{}: \"{name}\" is not a parameter of model {spec}{hint}",
                    self.at(&[name])
                );
            }
        }
        let built = spec.build(|n| self.values.get(n).copied()).map_err(|e| {
            let limit =
                if e.rule.bounded_by_energy_limit() && !self.values.contains_key(ENERGY_LIMIT) {
                    "; the file gives no \"energy_limit\", so the rate is checked at every energy: \
                 give the largest the member dissipates (a fit writes twice its record's)"
                } else {
                    ""
                };
            anyhow!("{}: {e}{limit}", self.at(&[e.field]))
        })?;
        // A limit no effect reads did nothing, in silence.
        if self.values.contains_key(ENERGY_LIMIT) && !spec.reads_energy() {
            bail!(
                "{}: \"energy_limit\" bounds the energy that degradation and pinching read, and model {spec} has neither: it would change nothing (remove it)",
                self.at(&[ENERGY_LIMIT])
            );
        }
        Ok(built)
    }

    /// `path:line:column` of the value at the key path `keys` in the file
    /// (`["alpha"]`, `["fit", "forcing"]`), or its path alone if the file
    /// does not give it.
    pub fn at(&self, keys: &[&str]) -> String {
        JsonFile::new(&self.path, Some(&self.text)).at(keys)
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Writes a parameter file: `model`, the parameters in `values` (in the
/// spec's order; plus `extra` such as `xi`, `m`), `units` and `fit`.
pub fn to_json(
    spec: ModelSpec,
    values: &BTreeMap<&str, f64>,
    energy_limit: Option<f64>,
    extra: &[(&str, f64)],
    units: Option<(&str, &str)>,
    fit: Option<Value>,
) -> Value {
    let mut map = Map::new();
    map.insert("model".into(), Value::String(spec.to_string()));
    for s in spec.params() {
        if let Some(v) = values.get(s.name) {
            map.insert(s.name.into(), Value::from(*v));
        }
    }
    if let Some(limit) = energy_limit.filter(|l| *l < f64::MAX) {
        map.insert(ENERGY_LIMIT.into(), Value::from(limit));
    }
    for (k, v) in extra {
        map.insert((*k).into(), Value::from(*v));
    }
    if let Some((d, f)) = units {
        map.insert(
            "units".into(),
            serde_json::json!({"displacement": d, "force": f}),
        );
    }
    if let Some(fit) = fit {
        map.insert("fit".into(), fit);
    }
    Value::Object(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ParamFile> {
        ParamFile::parse(Path::new("p.json"), text)
    }

    #[test]
    fn reads_a_flat_file_and_builds_the_model() {
        let f = parse(r#"{"model": "bw+pinching", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "zeta0": 0.5}"#).unwrap();
        let spec = f.spec(None).unwrap();
        let (p, _) = f.build(spec, false).unwrap();
        assert_eq!(p.get("zeta0"), Some(0.5));
        assert_eq!(
            p.get("lambda"),
            Some(0.5),
            "missing effect parameters take their off values"
        );
        let mut values = BTreeMap::new();
        p.for_each(|s, v| {
            values.insert(s.name, v);
        });
        let back = to_json(spec, &values, None, &[], Some(("mm", "kN")), None);
        let again = parse(&back.to_string()).unwrap();
        assert_eq!(again.build(again.spec(None).unwrap(), false).unwrap().0, p);
    }

    #[test]
    fn an_effect_given_without_any_of_its_parameters_is_named_switched_off() {
        let f = parse(
            r#"{"model": "bw+pinching+strength-degradation", "k0": 6, "alpha": 0.2, "n": 1.2,
                "beta": 2, "gamma": -1, "delta_nu": 0.01}"#,
        )
        .unwrap();
        let notes = f.switched_off(f.spec(None).unwrap());
        assert_eq!(
            notes,
            [
                "p.json: model bw+strength-degradation+pinching has pinching, but none of its \
              parameters (zeta0, p, q, psi0, delta_psi, lambda) is given: they take the values \
              that switch it off"
            ]
        );
    }

    #[test]
    fn errors_name_the_file_and_the_problem() {
        let msg = |t: &str| {
            parse(t)
                .and_then(|f| f.build(f.spec(Some(ModelSpec::BW))?, false).map(|m| m.0))
                .unwrap_err()
                .to_string()
        };
        assert!(
            msg("[1, 2]").contains("p.json: expected a JSON object of parameters, found an array")
        );
        assert!(
            msg(r#"{"k0": "six"}"#).contains("parameter \"k0\" must be a number, found a string")
        );
        assert!(msg("{\"k0\": 6,\n \"alpha\": }").starts_with("p.json:2:"));
        let m = msg(r#"{"k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "zeta0": 0.5}"#);
        assert!(
            m.ends_with(
                "\"zeta0\" is not a parameter of model bw; model bw has k0, alpha, n, beta, gamma"
            ),
            "{m}"
        );
        // A model with an effect that reads the energy lists its limit.
        let m = parse(r#"{"k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "nu": 1}"#)
            .and_then(|f| f.build(ModelSpec::parse("bw+strength-degradation")?, false))
            .unwrap_err()
            .to_string();
        assert!(m.ends_with(", energy_limit"), "{m}");
        let m = msg(r#"{"k0": 6, "alpha": 1.2, "n": 1.2, "beta": 2, "gamma": -1}"#);
        assert_eq!(m, "p.json:1:20: alpha must lie in [0, 1]");
        let m = msg(r#"{"k0": 6, "fit": "x"}"#);
        assert!(
            m.ends_with("key \"fit\" has the wrong type (a string)"),
            "{m}"
        );
        let m = msg(r#"{"k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2}"#);
        assert_eq!(m, "p.json: gamma is required but missing");
        let m = parse(r#"{"model": "bwbn"}"#)
            .unwrap()
            .spec(Some(ModelSpec::BW))
            .unwrap_err()
            .to_string();
        assert!(m.contains("--model bw disagrees"), "{m}");
        // An energy limit where nothing reads the energy (plain bw, asymmetry) is refused; with
        // an effect that reads it, it is taken.
        let bw = r#"{"k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "energy_limit": 50}"#;
        let m = msg(bw);
        assert!(
            m.starts_with("p.json:1:75: \"energy_limit\" bounds the energy that degradation and pinching read, and model bw has neither"),
            "{m}"
        );
        let f = parse(&bw.replace("{", r#"{"model": "bw+asymmetry", "#)).unwrap();
        let e = f.build(f.spec(None).unwrap(), false).unwrap_err();
        assert!(
            e.to_string().contains("model bw+asymmetry has neither"),
            "{e}"
        );
        let f = parse(&bw.replace("{", r#"{"model": "bw+pinching", "zeta0": 0.5, "#)).unwrap();
        let (p, _) = f.build(f.spec(None).unwrap(), false).unwrap();
        assert_eq!(p.energy_limit(), 50.0);
        // A linear degradation reaches zero at some energy: without a limit the rule holds at
        // every energy, which the file is told, since it gave no limit to lower (found by review).
        let degrading = r#"{"model": "bw+a-degradation", "k0": 6, "alpha": 0.2, "n": 1.2,
            "beta": 2, "gamma": -1, "delta_A": 0.01"#;
        let own = |t: &str| {
            let f = parse(t).unwrap();
            f.build(f.spec(None).unwrap(), false).map(|_| ())
        };
        let m = own(&format!("{degrading}}}")).unwrap_err().to_string();
        assert!(
            m.contains("delta_A drives its degradation function to zero")
                && m.ends_with(
                    "the file gives no \"energy_limit\", so the rate is checked at every \
                     energy: give the largest the member dissipates (a fit writes twice its \
                     record's)"
                ),
            "{m}"
        );
        assert!(own(&format!("{degrading}, \"energy_limit\": 50}}")).is_ok());
        let m = own(&format!("{degrading}, \"energy_limit\": 500}}"))
            .unwrap_err()
            .to_string();
        assert!(
            m.contains("delta_A drives") && !m.contains("gives no"),
            "{m}"
        );
    }
}
