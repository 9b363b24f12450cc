//! The JSON layouts of our data sets, recognised by their keys.
//!
//! | layout | keys | units | data set |
//! |---|---|---|---|
//! | [`JsonLayout::PeerSpd`] | `data.disp`, `data.force` | mm, kN (the SPD's SI convention; not in the file) | `peer-spd-columns/raw_json` |
//! | [`JsonLayout::FastenerConnection`] | `test.displacement`, `test.force` | from `source[0].units` (`["inches", "lbf"]`) | `cfs-fastener-peterman2014` |
//! | [`JsonLayout::FrictionDamper`] | `data` rows `[t, displacement, friction force, ...]` | from `displacement units`, `friction force units`, `time units` | `friction-damper-brfd` |
//! | [`JsonLayout::SimCenterBrace`] | `test.axialDef`, `test.axialForce` | in, kip (the app's axis labels; not in the file) | `steel-braces-simcenter` |
//! | [`JsonLayout::Plain`] | `displacement`, `force` (and `time`) at the top | from `units.displacement`, `units.force`, `units.time`; else mm, kN, s, said in a note | a user's own export |
//!
//! All are displacement-driven tests. Column roles and units cannot be
//! given in the read options for JSON (the layout fixes them); the input
//! channel, a sample rate and rows to skip can. Errors name the place in the
//! document as a path (`data.force[17]`), since parsed JSON has no line
//! numbers; syntax errors carry serde_json's line and column.

use super::error::DataError;
use super::read::ReadOptions;
use super::record::{Channel, Notice, Record, Series};
use super::units::{Quantity, Unit};
use serde_json::{Map, Value};
use std::path::Path;

/// The JSON layouts the reader knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JsonLayout {
    /// PEER Structural Performance Database scrape (`data: {disp, force}`).
    PeerSpd,
    /// FastenerConnectionData (`test: {displacement, force}`, units in `source`).
    FastenerConnection,
    /// ARTS-Lab friction damper (`data: [[t, x, F_friction, v, F_act1, F_act2], ...]`).
    FrictionDamper,
    /// NHERI SimCenter BracedFrameModeling (`test: {axialDef, axialForce}`).
    SimCenterBrace,
    /// The arrays at the top, as a user writes them (`{"displacement": [...],
    /// "force": [...]}`, a `time` array and a `units` object optional).
    Plain,
}

impl JsonLayout {
    /// Every layout, in the order they are recognised and named.
    pub const ALL: [JsonLayout; 5] = [
        JsonLayout::PeerSpd,
        JsonLayout::FastenerConnection,
        JsonLayout::SimCenterBrace,
        JsonLayout::FrictionDamper,
        JsonLayout::Plain,
    ];

    /// Recognises the layout of a document by its keys: `None` when no
    /// layout or more than one matches (see [`matching`](Self::matching)).
    pub fn detect(root: &Value) -> Option<JsonLayout> {
        match Self::matching(root)[..] {
            [one] => Some(one),
            _ => None,
        }
    }

    /// Every layout whose keys the document has. A document with two (say
    /// `data.disp`/`data.force` and `test.displacement`/`test.force`) used
    /// to be read by the first and the other passed over in silence.
    pub fn matching(root: &Value) -> Vec<JsonLayout> {
        let Some(obj) = root.as_object() else {
            return Vec::new();
        };
        Self::ALL.into_iter().filter(|l| l.found_in(obj)).collect()
    }

    /// Whether the document `obj` has the keys of this layout.
    fn found_in(self, obj: &Map<String, Value>) -> bool {
        let has = |o: Option<&Value>, keys: &[&str]| {
            o.and_then(Value::as_object)
                .is_some_and(|m| keys.iter().all(|k| m.contains_key(*k)))
        };
        match self {
            JsonLayout::PeerSpd => has(obj.get("data"), &["disp", "force"]),
            JsonLayout::FastenerConnection => has(obj.get("test"), &["displacement", "force"]),
            JsonLayout::SimCenterBrace => has(obj.get("test"), &["axialDef", "axialForce"]),
            JsonLayout::FrictionDamper => {
                obj.get("data").is_some_and(Value::is_array)
                    && obj.contains_key("displacement units")
            }
            JsonLayout::Plain => ["displacement", "force"]
                .iter()
                .all(|k| obj.get(*k).is_some_and(Value::is_array)),
        }
    }

    /// The keys that identify the layout, as the messages name them.
    pub fn keys(self) -> &'static str {
        match self {
            JsonLayout::PeerSpd => "data.disp/data.force",
            JsonLayout::FastenerConnection => "test.displacement/test.force",
            JsonLayout::SimCenterBrace => "test.axialDef/test.axialForce",
            JsonLayout::FrictionDamper => "data rows with 'displacement units'",
            JsonLayout::Plain => "displacement/force",
        }
    }
}

fn numbers(file: &Path, v: Option<&Value>, path: &str) -> Result<Vec<f64>, DataError> {
    let Some(items) = v.and_then(Value::as_array) else {
        return Err(DataError::json(file, path, "expected an array of numbers"));
    };
    items
        .iter()
        .enumerate()
        .map(|(k, x)| match x.as_f64() {
            Some(v) if v.is_finite() => Ok(v),
            _ => Err(DataError::json(
                file,
                format!("{path}[{k}]"),
                format!("expected a finite number, found {x}"),
            )),
        })
        .collect()
}

fn unit_at(file: &Path, v: Option<&Value>, path: &str, q: Quantity) -> Result<Unit, DataError> {
    let text = v
        .and_then(Value::as_str)
        .ok_or_else(|| DataError::json(file, path, format!("expected the {q} unit as a string")))?;
    match Unit::parse(text) {
        Some(u) if u.quantity() == q => Ok(u),
        _ => Err(DataError::json(
            file,
            path,
            format!(
                "expected a {q} unit ({}), found '{text}'",
                q.known_symbols()
            ),
        )),
    }
}

fn text_of(obj: &Map<String, Value>, key: &str) -> Option<String> {
    obj.get(key).and_then(Value::as_str).map(str::to_string)
}

/// The arrays in the object at `key` (the document itself for `None`) other
/// than the layout's `read` ones, as paths (`data.drift`, `drift`).
fn unread_arrays(obj: &Map<String, Value>, key: Option<&str>, read: &[&str]) -> Vec<String> {
    let within = match key {
        Some(key) => obj.get(key).and_then(Value::as_object),
        None => Some(obj),
    };
    within
        .into_iter()
        .flatten()
        .filter(|(k, v)| v.is_array() && !read.contains(&k.as_str()))
        .map(|(k, _)| key.map_or_else(|| k.clone(), |key| format!("{key}.{k}")))
        .collect()
}

/// The signals of a document before skipping and conversion.
struct Raw {
    time: Option<(String, Unit, Vec<f64>)>,
    disp: (String, Unit, Vec<f64>),
    force: (String, Unit, Vec<f64>),
    comments: Vec<String>,
    notices: Vec<Notice>,
}

fn peer(file: &Path, obj: &Map<String, Value>) -> Result<Raw, DataError> {
    let data = obj.get("data");
    let disp = numbers(file, data.and_then(|d| d.get("disp")), "data.disp")?;
    let force = numbers(file, data.and_then(|d| d.get("force")), "data.force")?;
    Ok(Raw {
        time: None,
        disp: ("data.disp".into(), Unit::Millimetre, disp),
        force: ("data.force".into(), Unit::Kilonewton, force),
        comments: text_of(obj, "Name").into_iter().collect(),
        notices: vec![Notice::UnitsByConvention {
            what: "PEER SPD data: displacement mm, force kN (the SPD's SI units)".into(),
        }],
    })
}

fn fastener(file: &Path, obj: &Map<String, Value>) -> Result<Raw, DataError> {
    let test = obj.get("test");
    let units = obj
        .get("source")
        .and_then(|s| s.get(0))
        .and_then(|s| s.get("units"));
    let du = unit_at(
        file,
        units.and_then(|u| u.get(0)),
        "source[0].units[0]",
        Quantity::Length,
    )?;
    let fu = unit_at(
        file,
        units.and_then(|u| u.get(1)),
        "source[0].units[1]",
        Quantity::Force,
    )?;
    let disp = numbers(
        file,
        test.and_then(|t| t.get("displacement")),
        "test.displacement",
    )?;
    let force = numbers(file, test.and_then(|t| t.get("force")), "test.force")?;
    let name = test
        .and_then(|t| t.get("name"))
        .and_then(Value::as_str)
        .map(|n| format!("test: {n}"));
    Ok(Raw {
        time: None,
        disp: ("test.displacement".into(), du, disp),
        force: ("test.force".into(), fu, force),
        comments: name.into_iter().collect(),
        notices: Vec::new(),
    })
}

fn brace(file: &Path, obj: &Map<String, Value>) -> Result<Raw, DataError> {
    let test = obj.get("test");
    let disp = numbers(file, test.and_then(|t| t.get("axialDef")), "test.axialDef")?;
    let force = numbers(
        file,
        test.and_then(|t| t.get("axialForce")),
        "test.axialForce",
    )?;
    let name = obj
        .get("brace")
        .and_then(|b| b.get("sxn"))
        .and_then(Value::as_str)
        .map(|n| format!("brace: {n}"));
    Ok(Raw {
        time: None,
        disp: ("test.axialDef".into(), Unit::Inch, disp),
        force: ("test.axialForce".into(), Unit::Kip, force),
        comments: name.into_iter().collect(),
        notices: vec![Notice::UnitsByConvention {
            what: "SimCenter brace test: axial deformation in, axial force kip (the app's axis labels)"
                .into(),
        }],
    })
}

fn friction(file: &Path, obj: &Map<String, Value>) -> Result<Raw, DataError> {
    let tu = unit_at(file, obj.get("time units"), "time units", Quantity::Time)?;
    let du = unit_at(
        file,
        obj.get("displacement units"),
        "displacement units",
        Quantity::Length,
    )?;
    let fu = unit_at(
        file,
        obj.get("friction force units"),
        "friction force units",
        Quantity::Force,
    )?;
    let rows = obj
        .get("data")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    let width = rows.first().and_then(Value::as_array).map_or(0, Vec::len);
    if width < 3 {
        return Err(DataError::json(
            file,
            "data[0]",
            format!("expected rows of at least 3 numbers (time, displacement, friction force), found {width}"),
        ));
    }
    let (mut t, mut d, mut f) = (Vec::new(), Vec::new(), Vec::new());
    for (k, row) in rows.iter().enumerate() {
        let path = format!("data[{k}]");
        let r = numbers(file, Some(row), &path)?;
        if r.len() != width {
            return Err(DataError::json(
                file,
                path,
                format!("expected {width} numbers as in data[0], found {}", r.len()),
            ));
        }
        t.push(r[0]);
        d.push(r[1]);
        f.push(r[2]);
    }
    let mut notices = Vec::new();
    if width > 3 {
        notices.push(Notice::IgnoredColumns {
            columns: vec!["data[*][3..]: velocity, actuator forces 1 and 2".into()],
        });
    }
    Ok(Raw {
        time: Some(("data[*][0]".into(), tu, t)),
        disp: ("data[*][1]".into(), du, d),
        force: ("data[*][2]".into(), fu, f),
        comments: Vec::new(),
        notices,
    })
}

/// A user's own arrays at the top of the document, in the units of its
/// `units` object or, where that does not name one, mm, kN and s (said).
fn plain(file: &Path, obj: &Map<String, Value>) -> Result<Raw, DataError> {
    let units = obj.get("units");
    if units.is_some_and(|u| !u.is_object()) {
        return Err(DataError::json(
            file,
            "units",
            "expected an object of units by array name (`{\"displacement\": \"mm\", ...}`)",
        ));
    }
    let mut notices = Vec::new();
    let mut signal = |key: &str, q: Quantity, fallback: Unit| {
        let values = numbers(file, obj.get(key), key)?;
        let unit = match units.and_then(|u| u.get(key)) {
            Some(v) => unit_at(file, Some(v), &format!("units.{key}"), q)?,
            None => {
                notices.push(Notice::AssumedUnit {
                    column: key.into(),
                    unit: fallback,
                });
                fallback
            }
        };
        Ok::<_, DataError>((key.to_string(), unit, values))
    };
    let disp = signal("displacement", Quantity::Length, Unit::Millimetre)?;
    let force = signal("force", Quantity::Force, Unit::Kilonewton)?;
    let time = match obj.get("time") {
        Some(_) => Some(signal("time", Quantity::Time, Unit::Second)?),
        None => None,
    };
    Ok(Raw {
        time,
        disp,
        force,
        comments: Vec::new(),
        notices,
    })
}

/// Where value `k` of the signal read from `name` is in the document:
/// `data[4][0]` for a column of rows (`data[*][0]`), `time[4]` for an array.
fn place(name: &str, k: usize) -> String {
    if name.contains("[*]") {
        name.replacen("[*]", &format!("[{k}]"), 1)
    } else {
        format!("{name}[{k}]")
    }
}

/// The values from `skip` on, in the canonical unit; a value too large for it is an error at
/// its place in the document.
fn series(
    file: &Path,
    name: String,
    unit: Unit,
    values: Vec<f64>,
    skip: usize,
) -> Result<Series, DataError> {
    let values = values
        .into_iter()
        .enumerate()
        .skip(skip)
        .map(|(k, v)| {
            let canonical = unit.to_canonical(v);
            if canonical.is_finite() {
                return Ok(canonical);
            }
            Err(DataError::json(
                file,
                place(&name, k),
                format!(
                    "expected a number that stays finite in {}, found {v:e} {unit}",
                    unit.quantity().canonical().symbol()
                ),
            ))
        })
        .collect::<Result<_, _>>()?;
    Ok(Series { name, unit, values })
}

/// Parses a JSON document of one of the known layouts.
pub(crate) fn parse(file: &Path, text: &str, options: &ReadOptions) -> Result<Record, DataError> {
    if !options.roles.is_empty() || !options.units.is_empty() {
        return Err(DataError::file(
            file,
            "column roles and units in the read options apply to CSV files; a JSON layout fixes them",
        ));
    }
    let sample_rate = options.checked_sample_rate(file)?;
    let root: Value = super::unique_keys::parse(text).map_err(|e| {
        DataError::at(
            file,
            e.line().max(1),
            e.column().max(1),
            format!("invalid JSON: {e}"),
        )
    })?;
    let layouts = JsonLayout::matching(&root);
    if let [a, b, ..] = layouts[..] {
        return Err(DataError::file(
            file,
            format!(
                "expected one known JSON layout, found two: {} and {}; \
                 keep the one to read in a file of its own",
                a.keys(),
                b.keys()
            ),
        ));
    }
    let (Some(&layout), Some(obj)) = (layouts.first(), root.as_object()) else {
        // Said as what it is ("found keys no object": found by review).
        let found = match &root {
            Value::Object(o) if o.is_empty() => "an empty object".to_string(),
            Value::Object(o) => format!(
                "keys {}",
                o.keys()
                    .map(|k| format!("'{k}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Value::Array(_) => "an array at the top, not an object".to_string(),
            other => format!("{other} at the top, not an object"),
        };
        let [rest @ .., last] = JsonLayout::ALL.map(JsonLayout::keys);
        return Err(DataError::file(
            file,
            format!(
                "expected a known JSON layout ({}, or {last}), found {found}",
                rest.join(", ")
            ),
        ));
    };
    let mut raw = match layout {
        JsonLayout::PeerSpd => peer(file, obj)?,
        JsonLayout::FastenerConnection => fastener(file, obj)?,
        JsonLayout::FrictionDamper => friction(file, obj)?,
        JsonLayout::SimCenterBrace => brace(file, obj)?,
        JsonLayout::Plain => plain(file, obj)?,
    };
    // Arrays beside the two a layout reads (a drift or a second load cell added to an SPD
    // file) were passed over in silence.
    let unread: Vec<String> = match layout {
        JsonLayout::PeerSpd => unread_arrays(obj, Some("data"), &["disp", "force"]),
        JsonLayout::FastenerConnection => {
            unread_arrays(obj, Some("test"), &["displacement", "force"])
        }
        JsonLayout::SimCenterBrace => unread_arrays(obj, Some("test"), &["axialDef", "axialForce"]),
        JsonLayout::FrictionDamper => Vec::new(),
        JsonLayout::Plain => unread_arrays(obj, None, &["displacement", "force", "time"]),
    };
    if !unread.is_empty() {
        raw.notices.push(Notice::IgnoredColumns { columns: unread });
    }
    let n = raw.disp.2.len();
    if raw.force.2.len() != n {
        return Err(DataError::json(
            file,
            raw.force.0.clone(),
            format!(
                "expected as many values as {} ({n}), found {}",
                raw.disp.0,
                raw.force.2.len()
            ),
        ));
    }
    let skip = options.skip_rows;
    if n <= skip {
        return Err(DataError::json(
            file,
            raw.disp.0.clone(),
            format!("expected a sample after skipping {skip}, found {n} in all"),
        ));
    }
    // Samples past the most asked for are not read.
    let n = match options.max_rows {
        Some(most) if n - skip > most => {
            let kept = skip + most;
            raw.disp.2.truncate(kept);
            raw.force.2.truncate(kept);
            // A time array of another length is left to the check below.
            if let Some(t) = raw.time.as_mut().filter(|t| t.2.len() == n) {
                t.2.truncate(kept);
            }
            raw.notices.push(Notice::RowsNotRead {
                from: format!("sample {kept}"),
                rows: n - kept,
            });
            kept
        }
        _ => n,
    };
    let mut notices = raw.notices;
    for k in 0..skip {
        notices.push(Notice::SkippedRow {
            at: format!("sample {k}"),
            text: format!("{}, {}", raw.disp.2[k], raw.force.2[k]),
        });
    }
    let time = match (sample_rate, raw.time) {
        (Some(hz), replaced) => {
            notices.push(Notice::TimeFromSampleRate {
                hz,
                replaced: replaced.map(|t| t.0),
            });
            Some(Series::canonical(
                format!("sample rate {hz} Hz"),
                Quantity::Time,
                (0..n - skip).map(|k| k as f64 / hz).collect(),
            ))
        }
        (None, Some((name, unit, values))) => {
            if values.len() != n {
                return Err(DataError::json(
                    file,
                    name,
                    format!(
                        "expected as many values as {} ({n}), found {}",
                        raw.disp.0,
                        values.len()
                    ),
                ));
            }
            if let Some(k) = values.windows(2).skip(skip).position(|w| w[1] <= w[0]) {
                let k = k + skip + 1;
                return Err(DataError::json(
                    file,
                    place(&name, k),
                    format!(
                        "expected time to increase after {} {unit}, found {} {unit}",
                        values[k - 1],
                        values[k]
                    ),
                ));
            }
            Some(series(file, name, unit, values, skip)?)
        }
        (None, None) => None,
    };
    let (dn, du, dv) = raw.disp;
    let (f_name, fu, fv) = raw.force;
    Ok(Record::new(
        file,
        options.input.unwrap_or(Channel::Displacement),
        Some(series(file, dn, du, dv, skip)?),
        Some(series(file, f_name, fu, fv, skip)?),
        time,
    )?
    .with_comments(raw.comments)
    .with_notices(notices))
}
