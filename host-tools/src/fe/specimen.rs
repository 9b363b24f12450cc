//! Specimen files: a reinforced-concrete column, its loading and the
//! numerical settings, in TOML. Every input the thesis does not give is
//! listed in the file's `[assumed]` table with its source. Errors name the
//! file, line and column and what was expected.
//!
//! ```toml
//! name = "TP-91"
//! [section]      # shape = "circular" | "square"; size = diameter or width
//! [column]       # height_m: the modelled height, fixed base to rigid top
//! [concrete]     # fc_mpa; elastic_modulus_mpa (default 4700 sqrt(fc)), poisson, density
//! [longitudinal] # count, bar_diameter_mm, yield_mpa
//! [transverse]   # kind = "spiral" | "hoops", bar_diameter_mm, spacing_mm, yield_mpa
//! [steel]        # elastic_modulus_mpa, density_kg_m3
//! [loading]      # axial_force_kn, axial_ramp_s, twist = [[s, rad], ...], interpolation
//! [analysis]     # element_size_mm, hourglass_scale, bulk_viscosity, dt_safety, time_step,
//!                # mass_scaling_dt_s, stop_below_peak, threads
//! [output]       # samples, vtk_every_s, [[output.rebar_station]]
//! [reference]    # Table 1.1 ratios, checked against the bar layout;
//!                # [reference.table_2_1]: the torques a run is compared with
//! [assumed]      # "key" = "why and from where"
//! ```

use super::concrete::{ConcreteDamagedPlasticity, ConcreteParams};
use super::explicit::{dof, Control, Damping};
use super::history::{History, Interpolation};
use super::material::{ElasticBar, Isotropic};
use super::mesh::{Mesh, Section};
use super::model::{Settings, TimeStep};
use super::rebar::{self, BarSet};
use super::steel::{HardeningSteel, HARDENING_RATIO};
use crate::data::Location;
use serde::Deserialize;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Cross-section shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    /// Circular, `size_mm` the diameter.
    Circular,
    /// Square, `size_mm` the width.
    Square,
}

/// The cross-section.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Shape.
    pub shape: Shape,
    /// Diameter or width, mm.
    pub size_mm: f64,
    /// Clear cover to the transverse steel, mm.
    pub clear_cover_mm: f64,
}

/// Column heights.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColumnSpec {
    /// Modelled height between the fixed base and the rigid top, m.
    pub height_m: f64,
    /// Total height of the test column (information), m.
    pub total_height_m: Option<f64>,
}

/// Concrete.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConcreteSpec {
    /// Cylinder strength, MPa.
    pub fc_mpa: f64,
    /// Young's modulus, MPa (default `4700 sqrt(fc)`, ACI 318).
    pub elastic_modulus_mpa: Option<f64>,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Density, kg/m^3.
    pub density_kg_m3: f64,
}

/// Longitudinal bars.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LongitudinalSpec {
    /// Number of bars (a multiple of 4 for squares: corners and equal
    /// numbers along each face).
    pub count: usize,
    /// Bar diameter, mm.
    pub bar_diameter_mm: f64,
    /// Yield strength, MPa.
    pub yield_mpa: f64,
}

/// Kind of transverse reinforcement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TransverseKind {
    /// A continuous helix (circular sections).
    Spiral,
    /// Closed hoops (circular or square).
    Hoops,
}

/// Transverse bars.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransverseSpec {
    /// Spiral or hoops.
    pub kind: TransverseKind,
    /// Bar diameter, mm.
    pub bar_diameter_mm: f64,
    /// Pitch or spacing, mm.
    pub spacing_mm: f64,
    /// Yield strength, MPa.
    pub yield_mpa: f64,
}

/// Steel properties common to all bars (thesis 2.2.2).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteelSpec {
    /// Young's modulus, MPa.
    pub elastic_modulus_mpa: f64,
    /// Density, kg/m^3.
    pub density_kg_m3: f64,
}

/// Two numbers, exactly: the TOML reader would take the first two of a longer array and drop
/// the rest without a word.
fn pair<'de, D: serde::Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    let v = Vec::<f64>::deserialize(d)?;
    <[f64; 2]>::try_from(v.as_slice())
        .map_err(|_| serde::de::Error::custom(format!("expected 2 numbers, found {}", v.len())))
}

/// A table of rows of two numbers each (see [`pair`]).
fn pairs<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<[f64; 2]>, D::Error> {
    Vec::<Vec<f64>>::deserialize(d)?
        .into_iter()
        .enumerate()
        .map(|(i, row)| {
            <[f64; 2]>::try_from(row.as_slice()).map_err(|_| {
                serde::de::Error::custom(format!(
                    "expected rows of 2 numbers, found {} in row {}",
                    row.len(),
                    i + 1
                ))
            })
        })
        .collect()
}

/// Loading (thesis 2.5): a constant axial force applied first, then the
/// twist history at the top reference point.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadingSpec {
    /// Axial compression, kN.
    pub axial_force_kn: f64,
    /// Time over which the axial force is brought on, s.
    pub axial_ramp_s: f64,
    /// Time the full axial force is held before the twist starts, s
    /// (default 0).
    #[serde(default)]
    pub axial_hold_s: f64,
    /// Mass-proportional damping during the axial ramp and hold, 1/s
    /// (default 0, none): the dynamic relaxation of the preload
    /// ([`super::explicit::Damping`]); `2 omega_1` of the first axial mode
    /// damps it critically.
    #[serde(default)]
    pub axial_damping_per_s: f64,
    /// Twist history `[time s, twist rad]`, time counted from the end of
    /// the axial ramp.
    #[serde(deserialize_with = "pairs")]
    pub twist: Vec<[f64; 2]>,
    /// Interpolation of the twist table.
    pub interpolation: Interpolation,
}

/// Numerical settings.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// Element size, mm.
    pub element_size_mm: f64,
    /// Hourglass stiffness scale (see [`Settings::hourglass_scale`]).
    pub hourglass_scale: f64,
    /// Bulk viscosity `[b1, b2]`.
    #[serde(deserialize_with = "pair")]
    pub bulk_viscosity: [f64; 2],
    /// Fraction of the stable step used.
    pub dt_safety: f64,
    /// How the stable step is estimated: `"global"` (default) or
    /// `"element"` (see [`TimeStep`]).
    pub time_step: Option<TimeStep>,
    /// Mass-scaling target step, s.
    pub mass_scaling_dt_s: Option<f64>,
    /// End the run once the torque, after its peak, has fallen below this
    /// fraction of the peak (none or 0: run the whole twist history).
    pub stop_below_peak: Option<f64>,
    /// Worker threads (default 2).
    pub threads: Option<usize>,
}

/// A rebar strain station: the truss of a bar set nearest to a height and
/// an angle around the axis.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StationSpec {
    /// Column name in the CSV.
    pub name: String,
    /// `longitudinal` or `transverse`.
    pub set: String,
    /// Height above the base, m.
    pub z_m: f64,
    /// Angle from the x axis, degrees.
    pub angle_deg: f64,
}

/// Output settings.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Rows of the torque-twist CSV over the run.
    pub samples: usize,
    /// Interval between VTK snapshots, s (none when absent).
    pub vtk_every_s: Option<f64>,
    /// Rebar strain stations.
    #[serde(default)]
    pub rebar_station: Vec<StationSpec>,
}

/// Reference values of thesis Table 1.1, checked against the layout.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// Longitudinal steel ratio, percent.
    pub longitudinal_ratio_pct: f64,
    /// Transverse (volumetric) steel ratio, percent.
    pub transverse_ratio_pct: f64,
    /// The torques of thesis Table 2.1, which a run is compared with and
    /// its torque-twist figure shows (optional: a column of one's own has
    /// none).
    #[serde(default)]
    pub table_2_1: Option<TorqueReference>,
}

/// Cracking and ultimate torques of thesis Table 2.1, kN m: the test's
/// (Experimental (B)) and the thesis's ABAQUS model's (FE Analysis (A)).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct TorqueReference {
    /// Measured cracking torque.
    pub test_cracking_knm: f64,
    /// Measured ultimate (peak) torque.
    pub test_peak_knm: f64,
    /// Cracking torque of the thesis's finite-element model.
    pub thesis_fe_cracking_knm: f64,
    /// Ultimate torque of the thesis's finite-element model.
    pub thesis_fe_peak_knm: f64,
}

/// A specimen file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Specimen {
    /// Specimen name.
    pub name: String,
    /// Where the data come from.
    pub source: String,
    /// Cross-section.
    pub section: SectionSpec,
    /// Heights.
    pub column: ColumnSpec,
    /// Concrete.
    pub concrete: ConcreteSpec,
    /// Longitudinal bars.
    pub longitudinal: LongitudinalSpec,
    /// Transverse bars.
    pub transverse: TransverseSpec,
    /// Steel.
    pub steel: SteelSpec,
    /// Loading.
    pub loading: LoadingSpec,
    /// Numerical settings.
    pub analysis: AnalysisSpec,
    /// Output.
    pub output: OutputSpec,
    /// Table 1.1 values.
    pub reference: ReferenceSpec,
    /// Inputs the thesis does not give: key path -> source.
    pub assumed: BTreeMap<String, String>,
}

/// The most elements a specimen's mesh may have: about 3.7 GB of state at
/// the 0.73 kB an element measured (TP-91 at 50 and 25 mm, maximum resident
/// size), and 45 times the 12.5 mm convergence run. A finer mesh is refused
/// when the file is read rather than failing to allocate after minutes.
const MAX_ELEMENTS: f64 = 5e6;

/// The one input a file may leave out whose default is a physical
/// assumption (`4700 sqrt(fc)`, [`Specimen::concrete`]): an `[assumed]`
/// entry may document it without the file giving it.
const ASSUMED_DEFAULT: &str = "concrete.elastic_modulus_mpa";

/// The most worker threads a run may ask for on this machine, and the
/// machine's hardware threads. Each step ends at a barrier for all threads:
/// past the hardware threads they only take turns (3,000 threads ran a
/// 0.01 s test run in 34 s, two in 0.01 s).
pub fn thread_limit() -> (usize, usize) {
    let hardware = std::thread::available_parallelism().map_or(1, |n| n.get());
    (4 * hardware, hardware)
}

/// A value [`Specimen::check`] refuses: its dotted key path (numbers index
/// arrays) and what was expected.
type Fault = (Cow<'static, str>, String);

/// An error in a specimen file, with its place.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError {
    /// The file.
    pub file: PathBuf,
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1.
    pub column: usize,
    /// What is wrong and what was expected.
    pub message: String,
}

impl std::fmt::Display for SpecError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file.display(),
            self.line,
            self.column,
            self.message
        )
    }
}

impl std::error::Error for SpecError {}

fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let before = &src[..offset.min(src.len())];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.len(), |p| before.len() - p - 1)
        + 1;
    (line, col)
}

/// A value of a specimen file replaced for one run (see
/// [`Specimen::load_with`]), and how it was given, which errors name.
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    /// Dotted key: `loading.axial_force_kn`; a number picks one of an array
    /// of tables, `output.rebar_station.1.z_m`.
    pub key: String,
    /// The new value, as TOML.
    pub value: String,
    /// How it was given: `--set KEY=VALUE`, or an option such as
    /// `--element-size 25`.
    pub given: String,
}

impl Override {
    /// The override `--set key=value`.
    pub fn set(key: &str, value: &str) -> Override {
        Override {
            key: key.to_string(),
            value: value.to_string(),
            given: format!("--set {key}={value}"),
        }
    }
}

/// The specimen text with each override applied (see
/// [`Specimen::load_with`]); the comments and layout of the file are kept,
/// so errors found later still point at the right lines.
fn apply_overrides(src: &str, overrides: &[Override]) -> Result<String, (usize, String)> {
    let mut doc: toml_edit::DocumentMut = src.parse().map_err(|e: toml_edit::TomlError| {
        (e.span().map_or(0, |s| s.start), e.message().to_string())
    })?;
    for o in overrides {
        let (key, value) = (&o.key, &o.value);
        // Placed at the value the override would replace, or the deepest table on its path.
        let refuse = |why: String| (locate(src, key), format!("{}: {why}", o.given));
        let parsed: toml_edit::Value = value
            .parse()
            .map_err(|_| refuse(format!("`{value}` is not a TOML value")))?;
        let mut segments: Vec<&str> = key.split('.').collect();
        let Some(last) = segments.pop().filter(|s| !s.is_empty()) else {
            return Err(refuse(
                "expected a dotted key such as loading.axial_force_kn".into(),
            ));
        };
        let mut item = doc.as_item_mut();
        for seg in &segments {
            let next = match seg.parse::<usize>() {
                Ok(i) => item.get_mut(i),
                Err(_) => item.get_mut(seg),
            };
            item = next
                .filter(|n| n.is_table_like() || n.is_array_of_tables())
                .ok_or_else(|| refuse(format!("the file has no table `{seg}`")))?;
        }
        let Some(table) = item.as_table_like_mut() else {
            return Err(refuse(format!("the file has no table for `{last}`")));
        };
        let keep = table
            .get(last)
            .and_then(|item| item.as_value())
            .map(|old| old.decor().clone());
        let mut new = parsed;
        if let Some(decor) = keep {
            *new.decor_mut() = decor;
        }
        table.insert(last, toml_edit::Item::Value(new));
    }
    Ok(doc.to_string())
}

/// The items along a dotted key path (numeric segments index arrays) below
/// `root`, as far as it has them.
fn walk<'a>(root: &'a toml_edit::Item, path: &str) -> Vec<&'a toml_edit::Item> {
    let mut items = Vec::new();
    let mut item = root;
    for seg in path.split('.') {
        let next = match seg.parse::<usize>() {
            Ok(i) => item.get(i),
            Err(_) => item.get(seg),
        };
        let Some(n) = next else { break };
        items.push(n);
        item = n;
    }
    items
}

/// Byte offset of the value at a dotted key path (numeric segments index
/// arrays), or of the deepest table on the path that exists.
fn locate(src: &str, path: &str) -> usize {
    let Ok(doc) = toml_edit::ImDocument::parse(src) else {
        return 0;
    };
    walk(doc.as_item(), path)
        .iter()
        .rev()
        .find_map(|item| item.span())
        .map_or(0, |s| s.start)
}

/// Whether a dotted key path names a value below `root`.
fn resolves(root: &toml_edit::Item, path: &str) -> bool {
    let items = walk(root, path);
    items.len() == path.split('.').count() && items.last().is_some_and(|i| i.is_value())
}

/// Specimen text as parsed, with what errors are placed against: the
/// file's own text and the `--set` overrides that changed it.
struct Source<'a> {
    text: &'a str,
    file_text: &'a str,
    overrides: &'a [Override],
    file: &'a Path,
}

impl Source<'_> {
    fn parse(&self) -> Result<Specimen, SpecError> {
        let spec: Specimen = toml::from_str(self.text).map_err(|e| {
            let at = e.span().map_or(0, |s| s.start);
            self.error_at(at, e.message().to_string())
        })?;
        spec.check().map_err(|(path, expected)| {
            self.error_on(&path, format!("`{path}`: expected {expected}"))
        })?;
        // Parsed once for all entries; the text is TOML, as it just deserialised.
        let doc = toml_edit::ImDocument::parse(self.text).ok();
        for key in spec.assumed.keys() {
            let given = doc.as_ref().is_some_and(|d| resolves(d.as_item(), key));
            if key != ASSUMED_DEFAULT && !given {
                return Err(self.error_on(
                    &format!("assumed.{key}"),
                    format!(
                        "[assumed] \"{key}\": expected the dotted key of a value this file gives, such as \"transverse.spacing_mm\", or \"{ASSUMED_DEFAULT}\", whose default is an assumption"
                    ),
                ));
            }
        }
        Ok(spec)
    }

    /// An error at a byte offset of the parsed text. Without overrides that
    /// is the file's own place; with them, the key there is found again in
    /// the file, as inserted keys move the lines below them.
    fn error_at(&self, offset: usize, message: String) -> SpecError {
        match path_at(self.text, offset) {
            Some(path) if !self.overrides.is_empty() => self.error_on(&path, message),
            _ => self.error(line_col(self.text, offset), message),
        }
    }

    /// An error about the value at a dotted key path: at its place in the
    /// file, or, where an override gave it, naming that override (placed at
    /// the key it replaced, or at the table it was added to). A check that
    /// compares values (the cover against the size, a station against the
    /// height) can refuse a value the file kept because an override changed
    /// another; unless the file alone fails the same way, such an error
    /// lists the overrides.
    fn error_on(&self, path: &str, message: String) -> SpecError {
        let own = self.overrides.iter().rev().find(|o| {
            path == o.key
                || path
                    .strip_prefix(o.key.as_str())
                    .is_some_and(|r| r.starts_with('.'))
        });
        if let Some(o) = own {
            return self.error(self.place(&o.key), format!("{}: {message}", o.given));
        }
        let plain = self.error(self.place(path), message);
        if self.overrides.is_empty() {
            return plain;
        }
        let file_alone = Source {
            text: self.file_text,
            file_text: self.file_text,
            overrides: &[],
            file: self.file,
        }
        .parse();
        if file_alone.is_err_and(|e| e.line == plain.line && e.message == plain.message) {
            return plain;
        }
        let given: Vec<&str> = self.overrides.iter().map(|o| o.given.as_str()).collect();
        SpecError {
            message: format!("{} (with {})", plain.message, given.join(" ")),
            ..plain
        }
    }

    /// Line and column in the file of the value at a dotted key path:
    /// `[assumed]` entries by their quoted key, the rest by [`locate`].
    fn place(&self, path: &str) -> (usize, usize) {
        let at = path
            .strip_prefix("assumed.")
            .and_then(|key| assumed_entry(self.file_text, key))
            .unwrap_or_else(|| locate(self.file_text, path));
        line_col(self.file_text, at)
    }

    fn error(&self, (line, column): (usize, usize), message: String) -> SpecError {
        SpecError {
            file: self.file.to_owned(),
            line,
            column,
            message,
        }
    }
}

/// The dotted key path (numbers index arrays) of the innermost key or
/// value whose text contains the byte `offset`.
fn path_at(src: &str, offset: usize) -> Option<String> {
    fn consider(
        span: Option<Range<usize>>,
        path: &str,
        offset: usize,
        best: &mut Option<(usize, String)>,
    ) {
        if let Some(s) = span {
            if s.contains(&offset) && best.as_ref().is_none_or(|(len, _)| s.len() <= *len) {
                *best = Some((s.len(), path.to_string()));
            }
        }
    }
    fn join(path: &str, key: &str) -> String {
        if path.is_empty() {
            key.to_string()
        } else {
            format!("{path}.{key}")
        }
    }
    fn value(v: &toml_edit::Value, path: &str, offset: usize, best: &mut Option<(usize, String)>) {
        consider(v.span(), path, offset, best);
        match v {
            toml_edit::Value::Array(a) => {
                for (i, e) in a.iter().enumerate() {
                    value(e, &join(path, &i.to_string()), offset, best);
                }
            }
            toml_edit::Value::InlineTable(t) => {
                for (k, e) in t.iter() {
                    let p = join(path, k);
                    consider(t.key(k).and_then(|k| k.span()), &p, offset, best);
                    value(e, &p, offset, best);
                }
            }
            _ => {}
        }
    }
    fn table(t: &toml_edit::Table, path: &str, offset: usize, best: &mut Option<(usize, String)>) {
        consider(t.span(), path, offset, best);
        for (k, item) in t.iter() {
            let p = join(path, k);
            consider(t.key(k).and_then(|k| k.span()), &p, offset, best);
            match item {
                toml_edit::Item::Value(v) => value(v, &p, offset, best),
                toml_edit::Item::Table(t) => table(t, &p, offset, best),
                toml_edit::Item::ArrayOfTables(a) => {
                    for (i, t) in a.iter().enumerate() {
                        table(t, &join(&p, &i.to_string()), offset, best);
                    }
                }
                toml_edit::Item::None => {}
            }
        }
    }
    let doc = toml_edit::ImDocument::parse(src).ok()?;
    let mut best = None;
    table(doc.as_table(), "", offset, &mut best);
    best.map(|(_, path)| path).filter(|p| !p.is_empty())
}

/// Byte offset of the entry `key` of the `[assumed]` table (whose keys are
/// quoted dotted paths, so [`locate`] cannot walk to them), if it has one.
fn assumed_entry(src: &str, key: &str) -> Option<usize> {
    let doc = toml_edit::ImDocument::parse(src).ok()?;
    let t = doc.get("assumed")?.as_table()?;
    t.key(key)?.span().map(|s| s.start)
}

/// The text of a specimen file, or an error naming it.
fn read_source(path: &Path) -> Result<String, SpecError> {
    crate::data::read_text(path).map_err(|e| {
        let (line, column) = match e.location() {
            Location::Text { line, column } => (*line, *column),
            Location::File | Location::Json(_) => (1, 1),
        };
        SpecError {
            file: path.to_owned(),
            line,
            column,
            message: e.message().replace("the file", "the specimen file"),
        }
    })
}

impl Specimen {
    /// Reads and checks a specimen file.
    pub fn load(path: &Path) -> Result<Specimen, SpecError> {
        let src = read_source(path)?;
        Specimen::parse(&src, path)
    }

    /// Reads a specimen file with some values replaced, for parametric
    /// runs: each `(key, value)` sets the dotted key (`loading.axial_force_kn`,
    /// `transverse.spacing_mm`) to the TOML value before the file is checked.
    /// A key whose table does not exist, or a value that is not TOML, is an
    /// error naming the override; the checks of [`Specimen::parse`] then
    /// apply to the changed file as to any other (unknown keys included),
    /// and an error in a replaced value names its `--set`.
    pub fn load_with(path: &Path, overrides: &[Override]) -> Result<Specimen, SpecError> {
        if overrides.is_empty() {
            return Specimen::load(path);
        }
        let src = read_source(path)?;
        let changed = apply_overrides(&src, overrides).map_err(|(at, message)| {
            let (line, column) = line_col(&src, at);
            SpecError {
                file: path.to_owned(),
                line,
                column,
                message,
            }
        })?;
        Source {
            text: &changed,
            file_text: &src,
            overrides,
            file: path,
        }
        .parse()
    }

    /// Parses and checks specimen text; `file` names it in errors.
    pub fn parse(src: &str, file: &Path) -> Result<Specimen, SpecError> {
        Source {
            text: src,
            file_text: src,
            overrides: &[],
            file,
        }
        .parse()
    }

    fn check(&self) -> Result<(), Fault> {
        fn pos(v: f64, path: &'static str, what: &str) -> Result<(), Fault> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err((
                    path.into(),
                    format!("{what} (a positive number), found {v}"),
                ))
            }
        }
        let s = &self.section;
        pos(s.size_mm, "section.size_mm", "the diameter or width in mm")?;
        if !(s.clear_cover_mm >= 0.0) {
            return Err((
                "section.clear_cover_mm".into(),
                "a cover of 0 mm or more".into(),
            ));
        }
        pos(
            self.column.height_m,
            "column.height_m",
            "the modelled height in m",
        )?;
        // Information only, but a negative or NaN height was accepted (found by review).
        if let Some(h) = self.column.total_height_m {
            pos(h, "column.total_height_m", "the test column's height in m")?;
        }
        let c = &self.concrete;
        pos(c.fc_mpa, "concrete.fc_mpa", "the cylinder strength in MPa")?;
        if let Some(e) = c.elastic_modulus_mpa {
            pos(e, "concrete.elastic_modulus_mpa", "Young's modulus in MPa")?;
        }
        if !(c.poisson >= 0.0 && c.poisson < 0.5) {
            return Err((
                "concrete.poisson".into(),
                format!("a Poisson's ratio in [0, 0.5), found {}", c.poisson),
            ));
        }
        pos(
            c.density_kg_m3,
            "concrete.density_kg_m3",
            "the density in kg/m^3",
        )?;
        let l = &self.longitudinal;
        pos(
            l.bar_diameter_mm,
            "longitudinal.bar_diameter_mm",
            "the bar diameter in mm",
        )?;
        pos(
            l.yield_mpa,
            "longitudinal.yield_mpa",
            "the yield strength in MPa",
        )?;
        let bad_count = match s.shape {
            Shape::Circular => l.count < 3,
            Shape::Square => l.count < 4 || l.count % 4 != 0,
        };
        if bad_count {
            return Err((
                "longitudinal.count".into(),
                format!(
                    "at least 3 bars (circular) or a multiple of 4 (square), found {}",
                    l.count
                ),
            ));
        }
        let t = &self.transverse;
        pos(
            t.bar_diameter_mm,
            "transverse.bar_diameter_mm",
            "the bar diameter in mm",
        )?;
        pos(
            t.spacing_mm,
            "transverse.spacing_mm",
            "the pitch or spacing in mm",
        )?;
        pos(
            t.yield_mpa,
            "transverse.yield_mpa",
            "the yield strength in MPa",
        )?;
        if s.shape == Shape::Square && t.kind == TransverseKind::Spiral {
            return Err((
                "transverse.kind".into(),
                "\"hoops\" for a square section".into(),
            ));
        }
        let inner = s.size_mm - 2.0 * (s.clear_cover_mm + t.bar_diameter_mm + l.bar_diameter_mm);
        if !(inner > 0.0) {
            return Err((
                "section.clear_cover_mm".into(),
                "cover and bars that fit inside the section".into(),
            ));
        }
        // Neighbouring longitudinal bars may touch, not overlap (their centre line, from
        // `radii`, in mm).
        let rl = s.size_mm / 2.0 - s.clear_cover_mm - t.bar_diameter_mm - l.bar_diameter_mm / 2.0;
        let pitch = match s.shape {
            Shape::Circular => 2.0 * rl * (PI / l.count as f64).sin(),
            Shape::Square => 2.0 * rl / (l.count / 4) as f64,
        };
        if pitch < l.bar_diameter_mm {
            return Err((
                "longitudinal.count".into(),
                format!(
                    "bars that fit side by side: {} bars of {} mm are {pitch:.1} mm apart, centre to centre",
                    l.count, l.bar_diameter_mm
                ),
            ));
        }
        // Hoops sit at s/2, 3s/2, ... below the top (`bar_sets`): at least one must fit.
        if t.kind == TransverseKind::Hoops && t.spacing_mm / 2.0 >= self.column.height_m * 1000.0 {
            return Err((
                "transverse.spacing_mm".into(),
                format!(
                    "a spacing that places at least one hoop (below twice the column's height, {} mm)",
                    2.0 * self.column.height_m * 1000.0
                ),
            ));
        }
        pos(
            self.steel.elastic_modulus_mpa,
            "steel.elastic_modulus_mpa",
            "Young's modulus in MPa",
        )?;
        pos(
            self.steel.density_kg_m3,
            "steel.density_kg_m3",
            "the density in kg/m^3",
        )?;
        pos(
            self.reference.longitudinal_ratio_pct,
            "reference.longitudinal_ratio_pct",
            "the longitudinal steel ratio in %",
        )?;
        pos(
            self.reference.transverse_ratio_pct,
            "reference.transverse_ratio_pct",
            "the transverse steel ratio in %",
        )?;
        if let Some(t) = &self.reference.table_2_1 {
            for (v, path) in [
                (t.test_cracking_knm, "reference.table_2_1.test_cracking_knm"),
                (t.test_peak_knm, "reference.table_2_1.test_peak_knm"),
                (
                    t.thesis_fe_cracking_knm,
                    "reference.table_2_1.thesis_fe_cracking_knm",
                ),
                (
                    t.thesis_fe_peak_knm,
                    "reference.table_2_1.thesis_fe_peak_knm",
                ),
            ] {
                pos(v, path, "a torque in kN m")?;
            }
        }
        let ld = &self.loading;
        if !(ld.axial_force_kn.is_finite() && ld.axial_force_kn >= 0.0) {
            return Err((
                "loading.axial_force_kn".into(),
                "a compression of 0 kN or more".into(),
            ));
        }
        if ld.axial_force_kn > 0.0 {
            pos(
                ld.axial_ramp_s,
                "loading.axial_ramp_s",
                "the time to apply the axial force in s",
            )?;
        }
        for (v, path, what) in [
            (ld.axial_hold_s, "loading.axial_hold_s", "a time in s"),
            (
                ld.axial_damping_per_s,
                "loading.axial_damping_per_s",
                "a damping in 1/s",
            ),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err((path.into(), format!("{what}, 0 or more, found {v}")));
            }
        }
        // The top starts untwisted: a first row [0, 0.05] would be read as [0, 0].
        if ld.twist.len() < 2 || ld.twist[0] != [0.0, 0.0] {
            return Err((
                "loading.twist".into(),
                "a table of at least two [time s, twist rad] rows starting at [0, 0]".into(),
            ));
        }
        for w in ld.twist.windows(2) {
            if !(w[1][0] > w[0][0] && w[1][0].is_finite() && w[1][1].is_finite()) {
                return Err((
                    "loading.twist".into(),
                    "strictly increasing finite times and finite twists".into(),
                ));
            }
        }
        let a = &self.analysis;
        pos(
            a.element_size_mm,
            "analysis.element_size_mm",
            "the element size in mm",
        )?;
        // The mesh rounds the section to whole cells (`Section::square`, `Section::circle`):
        // below four across, a twisted section has no interior to carry its shear flow.
        if a.element_size_mm * 4.0 > s.size_mm {
            return Err((
                "analysis.element_size_mm".into(),
                format!(
                    "at most a quarter of the section's {} mm (4 elements across), found {}",
                    s.size_mm, a.element_size_mm
                ),
            ));
        }
        let across = s.size_mm / a.element_size_mm;
        let elements = across * across * self.column.height_m * 1000.0 / a.element_size_mm;
        if elements > MAX_ELEMENTS {
            return Err((
                "analysis.element_size_mm".into(),
                format!(
                    "a mesh of at most {MAX_ELEMENTS:.0} elements, found {} mm, which gives about {elements:.2e}",
                    a.element_size_mm
                ),
            ));
        }
        if !(a.hourglass_scale >= 0.0 && a.hourglass_scale.is_finite()) {
            return Err((
                "analysis.hourglass_scale".into(),
                "a finite scale of 0 or more".into(),
            ));
        }
        if !a.bulk_viscosity.iter().all(|b| *b >= 0.0 && b.is_finite()) {
            return Err((
                "analysis.bulk_viscosity".into(),
                "[b1, b2], both finite and 0 or more".into(),
            ));
        }
        if !(a.dt_safety > 0.0 && a.dt_safety <= 1.0) {
            return Err(("analysis.dt_safety".into(), "a fraction in (0, 1]".into()));
        }
        if let Some(m) = a.mass_scaling_dt_s {
            pos(m, "analysis.mass_scaling_dt_s", "a target time step in s")?;
        }
        if let Some(f) = a.stop_below_peak {
            if !(0.0..1.0).contains(&f) {
                return Err((
                    "analysis.stop_below_peak".into(),
                    "a fraction of the peak torque in [0, 1) (0 runs the whole twist history)"
                        .into(),
                ));
            }
        }
        if let Some(t) = a.threads {
            let (most, hardware) = thread_limit();
            if !(1..=most).contains(&t) {
                return Err((
                    "analysis.threads".into(),
                    format!("1 to {most} threads (4 for each of this machine's {hardware} hardware threads), found {t}"),
                ));
            }
        }
        if self.output.samples < 2 {
            return Err(("output.samples".into(), "at least 2 rows".into()));
        }
        if let Some(v) = self.output.vtk_every_s {
            pos(v, "output.vtk_every_s", "an interval in s")?;
        }
        for (i, st) in self.output.rebar_station.iter().enumerate() {
            let at = |key: &str| Cow::Owned(format!("output.rebar_station.{i}.{key}"));
            // Each names a column of `rebar_strains.csv` (two stations of one name gave the
            // file two columns of that name: found by review).
            if self.output.rebar_station[..i]
                .iter()
                .any(|o| o.name == st.name)
            {
                return Err((
                    at("name"),
                    format!("a name no other station has, found {:?} again", st.name),
                ));
            }
            if st.set != "longitudinal" && st.set != "transverse" {
                return Err((
                    at("set"),
                    format!("\"longitudinal\" or \"transverse\", found {:?}", st.set),
                ));
            }
            if !st.angle_deg.is_finite() {
                return Err((
                    at("angle_deg"),
                    format!("a finite angle in degrees, found {}", st.angle_deg),
                ));
            }
            if !(st.z_m >= 0.0 && st.z_m <= self.column.height_m) {
                return Err((
                    at("z_m"),
                    format!(
                        "a height within the column's {} m, found {}",
                        self.column.height_m, st.z_m
                    ),
                ));
            }
        }
        Ok(())
    }

    /// What to know before comparing a run with the file's column: where
    /// the bar layout's steel ratios ([`Specimen::steel_ratios`]) differ by
    /// more than 3% from the `[reference]` ratios (Table 1.1), as they do
    /// when `--set` changes the bars or the file's layout is not the
    /// column it names.
    pub fn notes(&self) -> Vec<String> {
        let (rl, rt) = self.steel_ratios();
        let r = &self.reference;
        [
            ("longitudinal", 100.0 * rl, r.longitudinal_ratio_pct),
            ("transverse", 100.0 * rt, r.transverse_ratio_pct),
        ]
        .into_iter()
        .filter(|(_, layout, reference)| (layout / reference - 1.0).abs() > 0.03)
        .map(|(set, layout, reference)| {
            format!(
                "the {set} bars give a steel ratio of {layout:.3}%, where [reference] says {reference}%"
            )
        })
        .collect()
    }

    /// Element size, m.
    pub fn element_size(&self) -> f64 {
        self.analysis.element_size_mm / 1000.0
    }

    /// The concrete's elastic properties.
    pub fn concrete(&self) -> Isotropic {
        let c = &self.concrete;
        let e = c.elastic_modulus_mpa.unwrap_or(4700.0 * c.fc_mpa.sqrt());
        Isotropic {
            e: e * 1e6,
            nu: c.poisson,
            density: c.density_kg_m3,
        }
    }

    /// Elastic steel, one per bar set (longitudinal, transverse).
    pub fn steel(&self) -> Vec<ElasticBar> {
        let s = ElasticBar {
            e: self.steel.elastic_modulus_mpa * 1e6,
            density: self.steel.density_kg_m3,
        };
        vec![s, s]
    }

    /// Concrete damaged plasticity of thesis 2.2.1 with this concrete's
    /// strength and elastic properties.
    pub fn concrete_damaged(&self) -> ConcreteDamagedPlasticity {
        let params = ConcreteParams::thesis(self.concrete(), self.concrete.fc_mpa * 1e6);
        ConcreteDamagedPlasticity::new(params)
    }

    /// Yielding steel of thesis 2.2.2, one per bar set (longitudinal,
    /// transverse), with the yield strengths of the file (Table 1.1).
    pub fn steel_yielding(&self) -> Vec<HardeningSteel> {
        let e = self.steel.elastic_modulus_mpa * 1e6;
        let bar = |fy_mpa: f64| HardeningSteel {
            e,
            fy: fy_mpa * 1e6,
            hardening: HARDENING_RATIO * e,
            density: self.steel.density_kg_m3,
        };
        vec![
            bar(self.longitudinal.yield_mpa),
            bar(self.transverse.yield_mpa),
        ]
    }

    /// The mesh at `element_size_mm`.
    pub fn mesh(&self) -> Mesh {
        let h = self.element_size();
        let size = self.section.size_mm / 1000.0;
        let section = match self.section.shape {
            Shape::Circular => Section::circle(size / 2.0, h),
            Shape::Square => Section::square(size, h),
        };
        Mesh::extrude(section, self.column.height_m, h)
    }

    fn radii(&self) -> (f64, f64) {
        let half = self.section.size_mm / 2000.0;
        let c = self.section.clear_cover_mm / 1000.0;
        let dt = self.transverse.bar_diameter_mm / 1000.0;
        let dl = self.longitudinal.bar_diameter_mm / 1000.0;
        // Centre lines of the longitudinal bars and of the transverse bars.
        (half - c - dt - dl / 2.0, half - c - dt / 2.0)
    }

    /// The bar sets `[longitudinal, transverse]`, in segments of the
    /// element size.
    pub fn bar_sets(&self) -> Vec<BarSet> {
        let h = self.element_size();
        let height = self.column.height_m;
        let (rl, rt) = self.radii();
        let l = &self.longitudinal;
        let pts: Vec<(f64, f64)> = match self.section.shape {
            Shape::Circular => (0..l.count)
                .map(|k| {
                    let th = 2.0 * PI * k as f64 / l.count as f64;
                    (rl * th.cos(), rl * th.sin())
                })
                .collect(),
            Shape::Square => {
                let per = l.count / 4;
                let corners = [(-rl, -rl), (rl, -rl), (rl, rl), (-rl, rl)];
                (0..4)
                    .flat_map(|c| {
                        let p = corners[c];
                        let q = corners[(c + 1) % 4];
                        (0..per).map(move |i| {
                            let s = i as f64 / per as f64;
                            (p.0 + s * (q.0 - p.0), p.1 + s * (q.1 - p.1))
                        })
                    })
                    .collect()
            }
        };
        let long = BarSet {
            name: "longitudinal".into(),
            area: PI * (l.bar_diameter_mm / 1000.0).powi(2) / 4.0,
            bars: pts
                .iter()
                .map(|&(x, y)| rebar::vertical(x, y, 0.0, height, h))
                .collect(),
        };
        let t = &self.transverse;
        let s = t.spacing_mm / 1000.0;
        let levels: Vec<f64> = (0..)
            .map(|k| s / 2.0 + k as f64 * s)
            .take_while(|&z| z < height)
            .collect();
        let bars = match (self.section.shape, t.kind) {
            (_, TransverseKind::Spiral) => vec![rebar::helix(rt, s, 0.0, height, h)],
            (Shape::Circular, TransverseKind::Hoops) => levels
                .iter()
                .map(|&z| rebar::circular_hoop(rt, z, h))
                .collect(),
            (Shape::Square, TransverseKind::Hoops) => levels
                .iter()
                .map(|&z| rebar::square_hoop(rt, z, h))
                .collect(),
        };
        let trans = BarSet {
            name: "transverse".into(),
            area: PI * (t.bar_diameter_mm / 1000.0).powi(2) / 4.0,
            bars,
        };
        vec![long, trans]
    }

    /// Longitudinal ratio `n A_b / A_g` and transverse volumetric ratio
    /// (`4 A_t / (d_c s)` with `d_c` the centre-line diameter or width of
    /// the spiral or hoop), as fractions.
    pub fn steel_ratios(&self) -> (f64, f64) {
        let d = self.section.size_mm;
        let ag = match self.section.shape {
            Shape::Circular => PI * d * d / 4.0,
            Shape::Square => d * d,
        };
        let ab = PI * self.longitudinal.bar_diameter_mm.powi(2) / 4.0;
        let at = PI * self.transverse.bar_diameter_mm.powi(2) / 4.0;
        let dc = 2.0 * self.radii().1 * 1000.0;
        (
            self.longitudinal.count as f64 * ab / ag,
            4.0 * at / (dc * self.transverse.spacing_mm),
        )
    }

    /// Saint-Venant torsional stiffness `G J / L` of the gross concrete
    /// section, N m/rad (`J = pi D^4 / 32` or `0.1406 b^4`).
    pub fn saint_venant_stiffness(&self) -> f64 {
        let d = self.section.size_mm / 1000.0;
        let j = match self.section.shape {
            Shape::Circular => PI * d.powi(4) / 32.0,
            Shape::Square => {
                let mut s = 0.0;
                for n in 0..50 {
                    let m = (2 * n + 1) as f64;
                    s += (m * PI / 2.0).tanh() / m.powi(5);
                }
                d.powi(4) * (1.0 / 3.0 - 64.0 / PI.powi(5) * s)
            }
        };
        self.concrete().shear_modulus() * j / self.column.height_m
    }

    /// Start of the twist, s: after the axial ramp and hold.
    pub fn twist_start(&self) -> f64 {
        if self.loading.axial_force_kn > 0.0 {
            self.loading.axial_ramp_s + self.loading.axial_hold_s
        } else {
            0.0
        }
    }

    /// The damping of the axial preload, if any: over the ramp and hold
    /// (none without an axial force, like the ramp and hold themselves, so
    /// that `--set loading.axial_force_kn=0` runs the file unloaded).
    pub fn preload_damping(&self) -> Option<Damping> {
        (self.loading.axial_force_kn > 0.0 && self.loading.axial_damping_per_s > 0.0).then(|| {
            Damping {
                alpha: self.loading.axial_damping_per_s,
                until: self.twist_start(),
            }
        })
    }

    /// End of the analysis, s.
    pub fn end_time(&self) -> f64 {
        self.twist_start() + self.loading.twist.last().map_or(0.0, |p| p[0])
    }

    /// Control of the top reference point: twist driven, axial force
    /// applied (smooth step), the other four degrees of freedom free.
    pub fn controls(&self) -> [Control; 6] {
        let t0 = self.twist_start();
        let mut c: [Control; 6] = std::array::from_fn(|_| Control::free());
        let mut twist = vec![(0.0, 0.0)];
        twist.extend(self.loading.twist.iter().map(|p| (t0 + p[0], p[1])));
        twist.dedup_by(|b, a| a.0 == b.0);
        c[dof::RZ] = Control::Motion(History::new(twist, self.loading.interpolation));
        let p = -self.loading.axial_force_kn * 1e3;
        c[dof::UZ] = Control::Force(if p == 0.0 {
            History::constant(0.0)
        } else {
            History::new(
                vec![(0.0, 0.0), (self.loading.axial_ramp_s, p)],
                Interpolation::SmoothStep,
            )
        });
        c
    }

    /// Numerical settings.
    pub fn settings(&self) -> Settings {
        let a = &self.analysis;
        Settings {
            hourglass_scale: a.hourglass_scale,
            bulk_linear: a.bulk_viscosity[0],
            bulk_quadratic: a.bulk_viscosity[1],
            dt_safety: a.dt_safety,
            time_step: a.time_step.unwrap_or(TimeStep::Global),
            mass_scaling_dt: a.mass_scaling_dt_s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn specimens() -> Vec<(PathBuf, Specimen)> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens");
        ["tp-91", "tp-92", "hd6-0.73", "hd3-1.32", "missouri-square"]
            .iter()
            .map(|n| {
                let p = dir.join(format!("{n}.toml"));
                let s = Specimen::load(&p).unwrap_or_else(|e| panic!("{e}"));
                (p, s)
            })
            .collect()
    }

    #[test]
    fn overrides_replace_values_and_keep_the_file_checked() {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-92.toml");
        let path = file.as_path();
        let src = std::fs::read_to_string(path).unwrap();
        let set = |k: &str, v: &str| vec![Override::set(k, v)];
        let changed = apply_overrides(&src, &set("loading.axial_force_kn", "320")).unwrap();
        assert!(
            changed.contains("axial_force_kn = 320     # Table 1.1"),
            "{changed}"
        );
        assert_eq!(changed.lines().count(), src.lines().count());
        let s = Specimen::load_with(path, &set("transverse.spacing_mm", "94.0")).unwrap();
        assert_eq!(s.transverse.spacing_mm, 94.0);
        let e = Specimen::load_with(path, &set("transverse.spacing_mm", "-1")).unwrap_err();
        assert!(e.message.contains("transverse.spacing_mm"), "{e}");
        let e = Specimen::load_with(path, &set("transverse.spacing", "94")).unwrap_err();
        assert!(e.message.contains("unknown field"), "{e}");
        let e = Specimen::load_with(path, &set("hoops.spacing_mm", "94")).unwrap_err();
        assert!(e.message.contains("no table `hoops`"), "{e}");
        let e = Specimen::load_with(path, &set("transverse.spacing_mm", "9 4")).unwrap_err();
        assert!(e.message.contains("not a TOML value"), "{e}");
        // At the value it would have replaced (it used to be 1:1).
        assert_eq!(e.line, line_of(&src, "spacing_mm = "), "{e}");
        // A file that is not TOML keeps its own error place under an override.
        let file =
            std::env::temp_dir().join(format!("hyst-spec-syntax-{}.toml", std::process::id()));
        std::fs::write(&file, src.replacen("poisson = 0.2", "poisson = = 0.2", 1)).unwrap();
        let e = Specimen::load_with(&file, &set("transverse.spacing_mm", "94")).unwrap_err();
        assert_eq!(e.line, line_of(&src, "poisson = 0.2"), "{e}");
        std::fs::remove_file(&file).ok();
    }

    #[test]
    fn specimen_layouts_reproduce_table_1_1_ratios() {
        for (p, s) in specimens() {
            let (rl, rt) = s.steel_ratios();
            let r = &s.reference;
            let el = 100.0 * rl / r.longitudinal_ratio_pct - 1.0;
            let et = 100.0 * rt / r.transverse_ratio_pct - 1.0;
            assert!(
                el.abs() < 0.03,
                "{}: longitudinal {:.3}% vs {}%",
                p.display(),
                100.0 * rl,
                r.longitudinal_ratio_pct
            );
            assert!(
                et.abs() < 0.03,
                "{}: transverse {:.3}% vs {}%",
                p.display(),
                100.0 * rt,
                r.transverse_ratio_pct
            );
        }
    }

    #[test]
    fn specimen_elastic_stiffness_is_issue_8_gj_over_l() {
        // Issue 8: GJ/L from Table 1.1 with Ec = 4700 sqrt(fc'), nu = 0.2.
        let want = [27_800.0, 27_800.0, 44_900.0, 76_900.0, 47_500.0];
        for ((p, s), w) in specimens().into_iter().zip(want) {
            let k = s.saint_venant_stiffness() / 1e3;
            assert!(
                (k / w - 1.0).abs() < 0.005,
                "{}: {k:.0} vs {w}",
                p.display()
            );
        }
    }

    #[test]
    fn assumed_keys_name_inputs_of_the_file() {
        for (p, s) in specimens() {
            assert!(!s.assumed.is_empty());
            let src = std::fs::read_to_string(&p).expect("read");
            for key in s.assumed.keys() {
                let last = key.rsplit('.').next().unwrap_or(key);
                assert!(
                    locate(&src, key) > 0 && src.contains(last),
                    "{}: {key}",
                    p.display()
                );
            }
            // Every bar lies inside the concrete.
            let mesh = s.mesh();
            rebar::embed(&mesh, &s.bar_sets()).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        }
    }

    /// A byte-order mark (Notepad's) is dropped; a Latin-1 byte is refused at
    /// its line and column, not as "stream did not contain valid UTF-8".
    #[test]
    fn a_bom_is_read_and_a_latin1_byte_is_placed() {
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read(&tp91).expect("read");
        let dir = std::env::temp_dir().join(format!("hyst-specimen-bytes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let bom = dir.join("bom.toml");
        std::fs::write(&bom, [&b"\xef\xbb\xbf"[..], &src].concat()).expect("write");
        let read = Specimen::load(&bom).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read, Specimen::load(&tp91).expect("tp-91"));
        let text = String::from_utf8(src).expect("utf-8");
        let at = text.find("size_mm").expect("size_mm");
        let line = text[..at].matches('\n').count() + 1;
        let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
        let column = text[start..at].chars().count() + 1;
        let latin1 = dir.join("latin1.toml");
        let mut bytes = text.into_bytes();
        bytes[at] = 0xb5;
        std::fs::write(&latin1, bytes).expect("write");
        let e = Specimen::load(&latin1).expect_err("not UTF-8");
        assert_eq!((e.line, e.column), (line, column), "{e}");
        assert!(e.message.starts_with("byte 0xb5 is not UTF-8"), "{e}");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn errors_name_line_column_and_expectation() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&dir).expect("read");
        let bad = src.replacen("size_mm = 400.0", "size_mm = -400.0", 1);
        let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err("negative size");
        let line = bad
            .lines()
            .position(|l| l.contains("size_mm = -400.0"))
            .map(|i| i + 1);
        assert_eq!(Some(e.line), line, "{e}");
        assert!(e.to_string().starts_with("x.toml:"), "{e}");
        assert!(
            e.message.contains("section.size_mm") && e.message.contains("positive"),
            "{e}"
        );
        let typo = src.replacen("fc_mpa", "fc_mp", 1);
        let e = Specimen::parse(&typo, Path::new("x.toml")).expect_err("unknown key");
        assert!(e.message.contains("fc_mp"), "{e}");
        assert!(e.line > 1);
        let bad = src.replacen("test_peak_knm = 76.6", "test_peak_knm = nan", 1);
        let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err("NaN torque");
        let line = bad.lines().position(|l| l.contains("= nan")).map(|i| i + 1);
        assert_eq!(Some(e.line), line, "{e}");
        assert!(
            e.message.contains("reference.table_2_1.test_peak_knm"),
            "{e}"
        );
    }

    /// Values that used to be accepted and then ignored (a first twist other than 0) or that
    /// ran forever or panicked (an infinite time, hourglass scale or bulk viscosity).
    #[test]
    fn twist_tables_and_analysis_values_must_be_usable() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&dir).expect("read");
        let twist = src
            .lines()
            .find(|l| l.starts_with("twist = "))
            .expect("a twist line")
            .to_string();
        let cases = [
            (
                twist.clone(),
                "twist = [[0.0, 0.05], [0.1, 0.1]]".to_string(),
                "starting at [0, 0]",
            ),
            (
                twist.clone(),
                "twist = [[0.0, 0.0], [inf, 0.1]]".to_string(),
                "strictly increasing finite times",
            ),
            (
                twist.clone(),
                "twist = [[0.0, 0.0, 9.0], [0.1, 0.1, 1.0]]".to_string(),
                "expected rows of 2 numbers, found 3 in row 1",
            ),
            (
                "bulk_viscosity = [0.06, 1.2]".to_string(),
                "bulk_viscosity = [0.06, 1.2, 5.0]".to_string(),
                "expected 2 numbers, found 3",
            ),
            (
                "angle_deg = 0.0".to_string(),
                "angle_deg = nan".to_string(),
                "a finite angle in degrees",
            ),
            (
                "count = 16".to_string(),
                "count = 400".to_string(),
                "400 bars of 12.7 mm are 3.2 mm apart",
            ),
            (
                "spacing_mm = 47.0".to_string(),
                "spacing_mm = 5000.0".to_string(),
                "at least one hoop (below twice the column's height, 2700 mm)",
            ),
            (
                "hourglass_scale = 1.0".to_string(),
                "hourglass_scale = inf".to_string(),
                "a finite scale of 0 or more",
            ),
            (
                "bulk_viscosity = [0.06, 1.2]".to_string(),
                "bulk_viscosity = [inf, 1.2]".to_string(),
                "both finite and 0 or more",
            ),
            // One element across the section used to run as a 1-element mesh; 0.5 mm asked
            // for 1.7e9 elements and failed only when allocating.
            (
                "element_size_mm = 25.0".to_string(),
                "element_size_mm = 1e9".to_string(),
                "at most a quarter of the section's 400 mm (4 elements across)",
            ),
            (
                "element_size_mm = 25.0".to_string(),
                "element_size_mm = 0.5".to_string(),
                "a mesh of at most 5000000 elements, found 0.5 mm, which gives about 1.73e9",
            ),
            (
                "time_step = \"global\"".to_string(),
                "time_step = \"fast\"".to_string(),
                "unknown variant `fast`, expected `element` or `global`",
            ),
            (
                "axial_ramp_s = 0.0".to_string(),
                "axial_ramp_s = 0.0\naxial_hold_s = -1.0".to_string(),
                "a time in s, 0 or more, found -1",
            ),
            (
                "axial_ramp_s = 0.0".to_string(),
                "axial_ramp_s = 0.0\naxial_damping_per_s = nan".to_string(),
                "a damping in 1/s, 0 or more, found NaN",
            ),
            (
                "stop_below_peak = 0.5".to_string(),
                "stop_below_peak = 1.0".to_string(),
                "a fraction of the peak torque in [0, 1)",
            ),
            (
                "transverse_ratio_pct = 0.79".to_string(),
                "transverse_ratio_pct = 0.0".to_string(),
                "the transverse steel ratio in % (a positive number)",
            ),
        ];
        for (from, to, expected) in cases {
            let bad = src.replacen(&from, &to, 1);
            assert_ne!(bad, src, "{from} is not in the file");
            let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err(&to);
            assert!(e.message.contains(expected), "{to}: {e}");
        }
    }

    #[test]
    fn specimen_files_carry_table_2_1() {
        // Thesis Table 2.1: test cracking, test ultimate, FE cracking, FE
        // ultimate (kN m), in the order of `specimens()`.
        let table = [
            [60.7, 76.6, 62.9, 82.0],
            [76.6, 84.4, 58.0, 84.1],
            [180.9, 281.1, 190.7, 287.7],
            [184.6, 327.5, 224.1, 338.8],
            [189.3, 328.0, 212.3, 283.7],
        ];
        let files = specimens();
        assert_eq!(files.len(), table.len());
        for ((p, s), want) in files.iter().zip(table) {
            let r = s.reference.table_2_1.expect("a [reference.table_2_1]");
            let got = [
                r.test_cracking_knm,
                r.test_peak_knm,
                r.thesis_fe_cracking_knm,
                r.thesis_fe_peak_knm,
            ];
            assert_eq!(got, want, "{}", p.display());
        }
    }

    /// The 1-based line of the first line of `src` containing `needle`.
    fn line_of(src: &str, needle: &str) -> usize {
        src.lines()
            .position(|l| l.contains(needle))
            .map(|i| i + 1)
            .unwrap_or_else(|| panic!("{needle} is not in the text"))
    }

    /// A `--set` that adds a key inserts a line, which used to move every error below it one
    /// line down; and an error in a value a `--set` gave pointed into the file as if the file
    /// held it.
    #[test]
    fn override_errors_point_at_the_file_and_name_the_override() {
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&tp91).expect("read");
        let file =
            std::env::temp_dir().join(format!("hyst-spec-lines-{}.toml", std::process::id()));
        std::fs::write(&file, src.replacen("samples = 1000", "samples = 1", 1)).expect("write");
        let set = |pairs: &[(&str, &str)]| -> Vec<Override> {
            pairs.iter().map(|(k, v)| Override::set(k, v)).collect()
        };
        let added = ("concrete.elastic_modulus_mpa", "25000.0");
        let plain = Specimen::parse(&src, &tp91).expect("tp-91");
        assert_eq!(
            plain.concrete.elastic_modulus_mpa, None,
            "the key must be new"
        );

        // The file's own error, below the inserted line, at the file's line.
        let e = Specimen::load_with(&file, &set(&[added])).expect_err("samples = 1");
        assert_eq!(
            (e.line, e.column),
            (line_of(&src, "samples = 1000"), 11),
            "{e}"
        );
        assert!(!e.message.contains("--set"), "{e}");

        // An overridden value that fails a check: named, at the value it replaced.
        std::fs::write(&file, &src).expect("write");
        let e = Specimen::load_with(&file, &set(&[added, ("analysis.dt_safety", "5")]))
            .expect_err("dt_safety 5");
        assert_eq!(e.line, line_of(&src, "dt_safety = 0.9"), "{e}");
        assert!(e.message.starts_with("--set analysis.dt_safety=5: "), "{e}");

        // A value of the wrong type, found by the parser rather than the checks.
        let e = Specimen::load_with(&file, &set(&[added, ("output.samples", "-1")]))
            .expect_err("samples -1");
        assert_eq!(e.line, line_of(&src, "samples = 1000"), "{e}");
        assert!(e.message.starts_with("--set output.samples=-1: "), "{e}");

        // A new key that fails: at the table it was added to.
        let e = Specimen::load_with(&file, &set(&[("concrete.elastic_modulus_mpa", "-1")]))
            .expect_err("E = -1");
        assert_eq!(e.line, line_of(&src, "[concrete]"), "{e}");
        assert!(
            e.message.contains("--set concrete.elastic_modulus_mpa=-1"),
            "{e}"
        );

        // A check comparing two values fails on one the file kept: it lists the overrides,
        // which the file alone does not fail without.
        let e = Specimen::load_with(&file, &set(&[("section.size_mm", "60")]))
            .expect_err("a 60 mm section");
        assert_eq!(e.line, line_of(&src, "clear_cover_mm = 27.5"), "{e}");
        assert!(
            e.message.ends_with(
                "cover and bars that fit inside the section (with --set section.size_mm=60)"
            ),
            "{e}"
        );

        // An array of tables is reached by index, as the errors print it.
        let e = Specimen::load_with(&file, &set(&[("output.rebar_station.1.z_m", "9.0")]))
            .expect_err("z_m 9");
        let second = src.rfind("z_m = 0.675").expect("a second station");
        assert_eq!(e.line, src[..second].lines().count() + 1, "{e}");
        assert!(
            e.message
                .starts_with("--set output.rebar_station.1.z_m=9.0: `output.rebar_station.1.z_m`"),
            "{e}"
        );

        // `[assumed]` entries, whose keys hold dots, are placed at the entry under an override
        // too; one the override added names it.
        let bad = src.replacen(
            "\"transverse.kind\" = \"closed",
            "\"transverse.kind\" = 5 # \"closed",
            1,
        );
        std::fs::write(&file, &bad).expect("write");
        let e = Specimen::load_with(&file, &set(&[added])).expect_err("an entry of 5");
        assert_eq!(e.line, line_of(&bad, "\"transverse.kind\" = 5"), "{e}");
        std::fs::write(&file, &src).expect("write");
        let e = Specimen::load_with(&file, &set(&[("assumed.foo", "\"x\"")]))
            .expect_err("an entry for nothing");
        assert!(
            e.message
                .starts_with("--set assumed.foo=\"x\": [assumed] \"foo\""),
            "{e}"
        );
        let header = src.lines().position(|l| l == "[assumed]").map(|i| i + 1);
        assert_eq!(Some(e.line), header, "{e}");
        std::fs::remove_file(&file).ok();
    }

    /// Errors in the second of two `[[output.rebar_station]]` tables used to name the
    /// first one's line.
    #[test]
    fn rebar_station_errors_name_the_station() {
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&tp91).expect("read");
        let second = src.rfind("z_m = 0.675").expect("a second station");
        let bad = format!("{}z_m = 9.0{}", &src[..second], &src[second + 11..]);
        let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err("z_m 9");
        assert_eq!((e.line, e.column), (line_of(&bad, "z_m = 9.0"), 7), "{e}");
        assert!(e.message.contains("`output.rebar_station.1.z_m`"), "{e}");
        assert!(
            e.message.contains("within the column's 1.35 m, found 9"),
            "{e}"
        );
        let bad = src.replacen("set = \"longitudinal\"", "set = \"hoops\"", 1);
        let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err("set hoops");
        assert_eq!(e.line, line_of(&bad, "set = \"hoops\""), "{e}");
        assert!(e.message.contains("`output.rebar_station.0.set`"), "{e}");
    }

    /// Two stations of one name, and a total height that is not a positive number, are refused
    /// at their line.
    #[test]
    fn station_names_are_unique_and_the_total_height_positive() {
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&tp91).expect("read");
        let bad = src.replacen(
            "name = \"transverse-mid\"",
            "name = \"longitudinal-mid\"",
            1,
        );
        let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err("twice");
        assert!(e.message.contains("`output.rebar_station.1.name`"), "{e}");
        assert!(
            e.message.contains("found \"longitudinal-mid\" again"),
            "{e}"
        );
        for h in ["-1.75", "nan"] {
            let bad = src.replacen("total_height_m = 1.75", &format!("total_height_m = {h}"), 1);
            let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err(h);
            assert!(e.message.contains("`column.total_height_m`"), "{h}: {e}");
        }
    }

    /// An `[assumed]` entry must document a value the file gives; a misspelt key used to be
    /// accepted, leaving the input it meant undocumented.
    #[test]
    fn assumed_entries_must_name_a_value_of_the_file() {
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let src = std::fs::read_to_string(&tp91).expect("read");
        for key in ["transverse.knd", "transverse", "loading.twist.7"] {
            let bad = src.replacen("\"transverse.kind\" =", &format!("\"{key}\" ="), 1);
            let e = Specimen::parse(&bad, Path::new("x.toml")).expect_err(key);
            assert_eq!(
                (e.line, e.column),
                (line_of(&bad, &format!("\"{key}\" =")), 1),
                "{e}"
            );
            assert!(e.message.contains(&format!("[assumed] \"{key}\"")), "{e}");
        }
        // A key naming an element of an array is a value of the file.
        let ok = src.replacen("\"transverse.kind\" =", "\"loading.twist.1\" =", 1);
        Specimen::parse(&ok, Path::new("x.toml")).expect("an array element");
        // The default modulus is an assumption the file may document without giving it...
        let entry = format!("\"{ASSUMED_DEFAULT}\" =");
        let ok = src.replacen("\"transverse.kind\" =", &entry, 1);
        let s = Specimen::parse(&ok, Path::new("x.toml")).expect("the default modulus");
        assert_eq!(s.concrete.elastic_modulus_mpa, None);
        // ... and the key is the field's: given in the file, it is read.
        let given = ok.replacen(
            "poisson = 0.2",
            "poisson = 0.2\nelastic_modulus_mpa = 25000.0",
            1,
        );
        let s = Specimen::parse(&given, Path::new("x.toml")).expect("a given modulus");
        assert_eq!(s.concrete.elastic_modulus_mpa, Some(25000.0));
    }

    /// The five specimens' bars give their Table 1.1 ratios (no note); changing the bars says
    /// that the run no longer models the column the `[reference]` describes.
    #[test]
    fn a_layout_unlike_the_reference_is_noted() {
        for (p, s) in specimens() {
            assert!(s.notes().is_empty(), "{}: {:?}", p.display(), s.notes());
        }
        let tp91 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-91.toml");
        let set = vec![Override::set("transverse.spacing_mm", "94")];
        let s = Specimen::load_with(&tp91, &set).expect("spacing 94");
        // Twice the spacing, half the ratio: 4 A_t / (b_c s) with A_t = pi 6.35^2 / 4 and
        // b_c = 400 - 2 (27.5 + 6.35 / 2) mm.
        let bc = 400.0 - 2.0 * (27.5 + 6.35 / 2.0);
        let want = 100.0 * 4.0 * PI * 6.35 * 6.35 / 4.0 / (bc * 94.0);
        assert_eq!(
            s.notes(),
            vec![format!(
                "the transverse bars give a steel ratio of {want:.3}%, where [reference] says 0.79%"
            )]
        );
    }
}
