//! PHM parameter files (the format proposed in `docs/phm.md`):
//!
//! ```json
//! {
//!   "model": "phm-torsion",
//!   "units": { "twist": "deg", "torque": "kN m" },
//!   "primary": {
//!     "positive": [[0.21, 105.0], [1.45, 168.0], [4.0, 172.0], [8.5, 140.0]],
//!     "negative": [[0.22, 101.0], [1.40, 162.0], [4.0, 165.0], [8.5, 131.0]]
//!   },
//!   "coefficients": { "eq4_a": 0.7513, "eq4_b": -0.786, "cycle_band": 0.05 },
//!   "memory": 16
//! }
//! ```
//!
//! `negative` may be left out (a symmetric column); a coefficient left out
//! keeps the thesis' value; an unknown key or coefficient name is an error.
//! `units` must name an angle and a torque unit the data reader knows
//! (default deg and kN m): records are converted to them before the model
//! runs. `hyst fit` adds a `fit` object (how the file was fitted), which the
//! reader skips.

use super::params::checked_units;
use crate::data::json_place::JsonFile;
use crate::data::{Quantity, Unit};
use anyhow::{anyhow, bail, Result};
use hysteresis::phm::{BackboneRule, Direction, Phm, PhmError, PhmParams, SPECS};
use hysteresis::Element;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};

/// The `model` value of a PHM file.
pub const PHM_MODEL: &str = "phm-torsion";

/// Points per primary curve the host reads (the core's default capacity).
pub const PHM_POINTS: usize = 8;

/// A PHM parameter file as read and validated.
#[derive(Clone, Debug)]
pub struct PhmFile {
    /// Where it came from.
    pub path: PathBuf,
    /// The validated parameter set.
    pub params: PhmParams<f64, PHM_POINTS>,
    /// `(twist, torque)` units, if stated.
    pub units: Option<(Unit, Unit)>,
    /// The `(twist, torque)` units the parameters are in: the stated ones,
    /// else deg and kN m.
    pub data_units: (Unit, Unit),
}

/// Whether the JSON text is a PHM file (its `model` is `phm-torsion`).
pub fn is_phm(value: &Value) -> bool {
    value.get("model").and_then(Value::as_str) == Some(PHM_MODEL)
}

fn points(file: JsonFile, key: &str, v: &Value) -> Result<Vec<[f64; 2]>> {
    let bad = |at: &[&str]| {
        anyhow!(
            "{}: primary.{key} must be an array of [twist, torque] pairs of finite numbers",
            file.at(at)
        )
    };
    v.as_array()
        .ok_or_else(|| bad(&["primary", key]))?
        .iter()
        .enumerate()
        .map(|(i, p)| match p.as_array().map(Vec::as_slice) {
            Some([x, y]) => match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => Ok([x, y]),
                _ => Err(bad(&["primary", key, &i.to_string()])),
            },
            _ => Err(bad(&["primary", key, &i.to_string()])),
        })
        .collect()
}

impl PhmFile {
    /// Reads and validates a PHM parameter file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = crate::data::read_text(path)?;
        let value: Value = crate::data::unique_keys::parse_file(path, &text)?;
        Self::from_json(JsonFile::new(path, Some(&text)), &value)
    }

    /// Validates a PHM file built in memory; its errors name `path` alone.
    pub fn from_value(path: &Path, value: &Value) -> Result<Self> {
        Self::from_json(JsonFile::new(path, None), value)
    }

    /// Validates a parsed PHM file; its errors name the line and column of
    /// the value they are about where `file` has the text.
    pub fn from_json(file: JsonFile, value: &Value) -> Result<Self> {
        let path = file.path();
        let Some(map) = value.as_object() else {
            bail!("{}: expected a JSON object", path.display());
        };
        if let Some(m) = map.get("model").filter(|_| !is_phm(value)) {
            bail!(
                "{}: \"model\" is {m}: expected \"{PHM_MODEL}\" in a PHM file",
                file.at(&["model"])
            );
        }
        let mut positive = None;
        let mut negative = None;
        let mut coefficients = Map::new();
        let mut units = None;
        let mut data_units = (Unit::Degree, Unit::KilonewtonMetre);
        for (key, v) in map {
            match key.as_str() {
                "model" => {}
                "fit" => {}
                "memory" => {
                    if v.as_u64() != Some(16) {
                        bail!(
                            "{}: \"memory\" must be 16, the inner-cycle depth the host uses",
                            file.at(&["memory"])
                        );
                    }
                }
                "units" => {
                    let Some(u) = v.as_object() else {
                        bail!(
                            "{}: \"units\" must be {{\"twist\": ..., \"torque\": ...}}",
                            file.at(&["units"])
                        );
                    };
                    let [(_, twist), (_, torque)] = checked_units(
                        file,
                        u,
                        [("twist", Quantity::Angle), ("torque", Quantity::Torque)],
                    )?;
                    data_units = (twist, torque);
                    units = Some((twist, torque));
                }
                "primary" => {
                    let Some(p) = v.as_object() else {
                        bail!("{}: \"primary\" must be an object", file.at(&["primary"]));
                    };
                    for (k, curve) in p {
                        match k.as_str() {
                            "positive" => positive = Some(points(file, k, curve)?),
                            "negative" => negative = Some(points(file, k, curve)?),
                            other => bail!(
                                "{}: primary.{other}: expected \"positive\" or \"negative\"",
                                file.at(&["primary", other])
                            ),
                        }
                    }
                }
                "coefficients" => {
                    let Some(c) = v.as_object() else {
                        bail!(
                            "{}: \"coefficients\" must be an object",
                            file.at(&["coefficients"])
                        );
                    };
                    for (name, x) in c {
                        if !SPECS.iter().any(|s| s.name == name) {
                            bail!(
                                "{}: \"{name}\" is not a PHM coefficient; known: {}",
                                file.at(&["coefficients", name]),
                                SPECS.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
                            );
                        }
                        if !x.as_f64().is_some_and(f64::is_finite) {
                            bail!(
                                "{}: coefficient \"{name}\" is not a finite number",
                                file.at(&["coefficients", name])
                            );
                        }
                    }
                    coefficients = c.clone();
                }
                other => bail!(
                    "{}: unknown key \"{other}\" in a PHM file (model, units, primary, coefficients, memory, fit)",
                    file.at(&[other])
                ),
            }
        }
        let positive = positive
            .ok_or_else(|| anyhow!("{}: primary.positive is missing", file.at(&["primary"])))?;
        for (side, curve) in [
            ("positive", Some(&positive)),
            ("negative", negative.as_ref()),
        ] {
            if let Some(c) = curve.filter(|c| c.len() > PHM_POINTS) {
                bail!(
                    "{}: primary.{side} has {} points; a curve here has at most {PHM_POINTS}",
                    file.at(&["primary", side]),
                    c.len()
                );
            }
        }
        let negative = negative.unwrap_or_else(|| positive.clone());
        let params = PhmParams::from_named(&positive, &negative, |name| {
            coefficients.get(name).and_then(Value::as_f64)
        })
        .map_err(|e| {
            let point;
            let at: Vec<&str> = match &e {
                PhmError::Backbone(b) => {
                    let side = match b.direction {
                        Direction::Positive => "positive",
                        Direction::Negative => "negative",
                    };
                    point = b.point.to_string();
                    match b.rule {
                        BackboneRule::TooFewPoints | BackboneRule::TooManyPoints => {
                            vec!["primary", side]
                        }
                        _ => vec!["primary", side, &point],
                    }
                }
                PhmError::Coefficient(c) => vec!["coefficients", c.field],
            };
            anyhow!("{}: {e}", file.at(&at))
        })?;
        Ok(PhmFile {
            path: path.to_path_buf(),
            params,
            units,
            data_units,
        })
    }
}

/// A PHM parameter file as JSON (the format [`PhmFile::read`] reads): both
/// primary curves, every coefficient, units and, if given, the `fit` object.
pub fn phm_json(
    params: &PhmParams<f64, PHM_POINTS>,
    units: (Unit, Unit),
    fit: Option<Value>,
) -> Value {
    let curve = |d| {
        params
            .primary(d)
            .points()
            .iter()
            .map(|p| json!([p[0], p[1]]))
            .collect::<Vec<_>>()
    };
    let mut coefficients = Map::new();
    params.coefficients().for_each(|s, v| {
        coefficients.insert(s.name.to_string(), json!(v));
    });
    let mut v = json!({
        "model": PHM_MODEL,
        "units": { "twist": units.0.symbol(), "torque": units.1.symbol() },
        "primary": {
            "positive": curve(Direction::Positive),
            "negative": curve(Direction::Negative),
        },
        "coefficients": coefficients,
        "memory": 16,
    });
    if let Some(fit) = fit {
        v["fit"] = fit;
    }
    v
}

/// The response of a PHM element along a twist history.
#[derive(Clone, Debug, Default)]
pub struct PhmRun {
    /// Twist, as given.
    pub twist: Vec<f64>,
    /// Torque.
    pub torque: Vec<f64>,
    /// Tangent d(torque)/d(twist).
    pub tangent: Vec<f64>,
    /// The cycle counter n of eqs 5-6 of each direction (positive first)
    /// after each step.
    pub cycles: [Vec<f64>; 2],
    /// Remembered branches dropped because the inner-cycle memory was full
    /// (gap G8 of `docs/phm.md`).
    pub forgotten: u32,
}

/// Runs a PHM element (inner-cycle memory 16) over a twist history, one
/// committed step per sample. Errors name the sample.
pub fn simulate_phm(params: &PhmParams<f64, PHM_POINTS>, twist: &[f64]) -> Result<PhmRun> {
    let mut el: Phm<f64, PHM_POINTS> = Phm::new(params.clone());
    let mut run = PhmRun::default();
    for (i, &x) in twist.iter().enumerate() {
        let r = el
            .set_trial(x)
            .map_err(|e| anyhow!("step to sample {} (twist {x}): {e}", i + 1))?;
        el.commit();
        run.twist.push(x);
        run.torque.push(r.force);
        run.tangent.push(r.tangent);
        for (c, l) in run.cycles.iter_mut().zip(el.levels()) {
            c.push(f64::from(l.cycles));
        }
    }
    run.forgotten = el.forgotten();
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn read(v: Value) -> Result<PhmFile> {
        PhmFile::from_value(Path::new("t.json"), &v)
    }

    #[test]
    fn reads_the_documented_example() {
        let f = read(json!({
            "model": "phm-torsion",
            "units": { "twist": "deg", "torque": "kN m" },
            "primary": {
                "positive": [[0.21, 105.0], [1.45, 168.0], [4.0, 172.0], [8.5, 140.0]],
                "negative": [[0.22, 101.0], [1.40, 162.0], [4.0, 165.0], [8.5, 131.0]]
            },
            "coefficients": { "eq4_a": 0.7513, "eq4_b": -0.786, "cycle_band": 0.05 },
            "memory": 16
        }))
        .unwrap();
        assert_eq!(f.params.coefficients().get("eq4_b"), Some(-0.786));
        assert_eq!(f.units, Some((Unit::Degree, Unit::KilonewtonMetre)));
        let back = PhmFile::from_value(
            Path::new("b.json"),
            &phm_json(&f.params, f.data_units, Some(json!({"nrmse": 0.1}))),
        )
        .unwrap();
        assert_eq!(back.params, f.params);
    }

    #[test]
    fn errors_name_the_file_and_the_key() {
        let e = |v: Value| read(v).unwrap_err().to_string();
        let curve = json!([[1.0, 5.0], [4.0, 6.5]]);
        assert!(e(json!({"model": "phm-torsion", "primary": {"positive": curve}, "coefficients": {"eq9": 1.0}}))
            .starts_with("t.json: \"eq9\" is not a PHM coefficient"));
        assert_eq!(
            e(json!({"model": "phm-torsion", "primary": {"positive": [[1.0, 5.0], [0.5, 6.0]]}})),
            "t.json: positive primary curve, point 1: twists must increase strictly from zero"
        );
        assert!(
            e(json!({"model": "phm-torsion", "primary": {"positive": curve}, "memroy": 16}))
                .contains("unknown key \"memroy\"")
        );
    }
}
