//! Parameter tables for the device: reading fitted parameter files,
//! encoding them in the core's table format (`hysteresis::table`,
//! `docs/table-format.md`) and rendering the bytes as a binary blob, a Rust
//! `static` or a C header. Every table written here is first loaded back with
//! the device's own loader.

pub mod precision;
mod render;

pub use render::{render, Format};

use crate::data::json_place::JsonFile;
use crate::data::Unit;
use crate::model::{is_phm, ModelSpec, ParamFile, PhmFile, PHM_POINTS};
use anyhow::{anyhow, bail, Result};
use hysteresis::bwbn::BwbnParams;
use hysteresis::phm::{Direction, PhmParams};
use hysteresis::table::{
    self, BwbnTable, Header, ModelKind, PhmTable, ScalarKind, Table, TableError, TableScalar, Units,
};
use hysteresis::{Fixed, Scalar};
use std::path::{Path, PathBuf};

/// The elements of one table, in the order of the files given.
#[derive(Clone, Debug)]
pub enum Elements {
    /// BWBN parameter sets (one effect set).
    Bwbn(Vec<BwbnParams<f64>>),
    /// PHM parameter sets.
    Phm(Vec<PhmParams<f64, PHM_POINTS>>),
}

impl Elements {
    /// The number of elements.
    pub fn len(&self) -> usize {
        match self {
            Elements::Bwbn(v) => v.len(),
            Elements::Phm(v) => v.len(),
        }
    }
    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Parameter files read for export.
#[derive(Clone, Debug)]
pub struct Sources {
    /// The files, one element each.
    pub files: Vec<PathBuf>,
    /// Their parameter sets.
    pub elements: Elements,
    /// The units they share (empty if none states them).
    pub units: Units,
    /// The unit of the elements' input (displacement or twist): the one the
    /// files state, else the records' canonical mm (Bouc-Wen) or deg (PHM).
    pub input: Unit,
    /// What was read but is not part of the table, a line each.
    pub notes: Vec<String>,
}

/// Reads parameter files (flat BWBN files as `hyst fit` writes them, or PHM
/// files, `"model": "phm-torsion"`), one element each. All must be of one
/// model kind and effect set, and state the same units (or none).
pub fn read(paths: &[PathBuf]) -> Result<Sources> {
    if paths.is_empty() {
        bail!("no parameter file given");
    }
    let mut bwbn = vec![];
    let mut phm = vec![];
    let mut units: Option<(PathBuf, (Unit, Unit))> = None;
    let mut unstated: Vec<String> = vec![];
    let mut notes = vec![];
    for path in paths {
        let text = crate::data::read_text(path)?;
        let value = crate::data::unique_keys::parse_file(path, &text)?;
        let (stated, kind) = if is_phm(&value) {
            let f = PhmFile::from_json(JsonFile::new(path, Some(&text)), &value)?;
            phm.push(f.params);
            (f.units, ModelKind::Phm)
        } else {
            let f = ParamFile::parse(path, &text)?;
            let spec = f.model.ok_or_else(|| {
                anyhow!(
                    "{}: no \"model\" key: a table needs to know the model (\"model\": \"bw\", \"bwbn\", ...)",
                    path.display()
                )
            })?;
            if spec.custom != 0 {
                bail!(
                    "{}: model {spec} has an effect defined outside the library; device tables hold the core's effects only",
                    path.display()
                );
            }
            // A force-driven fit also holds the test's mass and damping (thesis eq. 3.3); the
            // element is the hysteretic spring alone.
            let (p, _) = f.build(spec, true)?;
            notes.extend(f.switched_off(spec));
            let dynamic: Vec<&str> = ["m", "xi"]
                .into_iter()
                .filter(|k| f.values.contains_key(*k))
                .collect();
            if !dynamic.is_empty() {
                notes.push(format!(
                    "{}: {} belong{} to the oscillator of the force-driven test it was fitted on, \
                     not to the element (the hysteretic spring of thesis eq. 3.3): not in the table",
                    path.display(),
                    dynamic.join(" and "),
                    if dynamic.len() == 1 { "s" } else { "" }
                ));
            }
            if let Some(first) = bwbn.first().map(BwbnParams::effect_set) {
                if first != p.effect_set() {
                    bail!(
                        "{}: model {spec} differs from {}'s {}; one table holds one model",
                        path.display(),
                        paths[0].display(),
                        ModelSpec {
                            base: crate::model::Base::Bw,
                            effects: first,
                            custom: 0,
                        }
                    );
                }
            }
            bwbn.push(p);
            (f.units, ModelKind::Bwbn)
        };
        if !bwbn.is_empty() && !phm.is_empty() {
            bail!(
                "{}: a {} file among {} files; one table holds one model",
                path.display(),
                kind.name(),
                if kind == ModelKind::Phm {
                    "BWBN"
                } else {
                    "PHM"
                }
            );
        }
        // Compared and labelled by unit, not by spelling: `KN` is kN.
        if let Some(u) = stated {
            match &units {
                Some((first, v)) if *v != u => bail!(
                    "{}: units {} / {} differ from {}'s {} / {}",
                    path.display(),
                    u.0,
                    u.1,
                    first.display(),
                    v.0,
                    v.1
                ),
                Some(_) => {}
                None => units = Some((path.clone(), u)),
            }
        } else {
            unstated.push(path.display().to_string());
        }
    }
    if let (Some((first, (d, f))), false) = (&units, unstated.is_empty()) {
        notes.push(format!(
            "{} state{} no units: the table takes {d} / {f} from {} for every element",
            unstated.join(", "),
            if unstated.len() == 1 { "s" } else { "" },
            first.display()
        ));
    }
    let input = match &units {
        Some((_, (d, _))) => *d,
        None if phm.is_empty() => Unit::Millimetre,
        None => Unit::Degree,
    };
    let units = match units {
        // Labelled by symbol, which always fits (`every_symbol_fits_a_device_table`).
        Some((_, (d, f))) => Units::new(d.symbol(), f.symbol()).expect("a unit symbol fits"),
        None => Units::default(),
    };
    let elements = if phm.is_empty() {
        Elements::Bwbn(bwbn)
    } else {
        Elements::Phm(phm)
    };
    Ok(Sources {
        files: paths.to_vec(),
        elements,
        units,
        input,
        notes,
    })
}

/// Why `x` cannot be held in `scalar`, if it cannot: beyond its range, or
/// not zero but rounded to zero (which would switch a term of the model off).
fn unheld(scalar: ScalarKind, x: f64) -> Option<String> {
    fn held<S: Scalar>(x: f64) -> f64 {
        S::from_f64(x).to_f64()
    }
    let (h, step) = match scalar {
        ScalarKind::F32 => (held::<f32>(x), f64::from(f32::from_bits(1))),
        ScalarKind::Q16 => (held::<Fixed>(x), 1.0 / 65536.0),
        // f64 holds every value a parameter file can state.
        _ => return None,
    };
    if !h.is_finite() {
        Some(format!("is beyond the range of {}", scalar.name()))
    } else if x != 0.0 && h == 0.0 {
        Some(format!(
            "rounds to 0 in {} (its smallest step is {step:.2e})",
            scalar.name()
        ))
    } else {
        None
    }
}

/// Encodes `src` in `scalar` and loads the result back with the device's
/// loader; a value the arithmetic cannot hold (beyond ±32768 in Q15.16, a
/// rate that rounds to zero) is refused here, naming the file.
pub fn encode(src: &Sources, scalar: ScalarKind) -> Result<Vec<u8>> {
    if let Elements::Bwbn(v) = &src.elements {
        for (p, file) in v.iter().zip(&src.files) {
            let mut refused = None;
            p.for_each(|spec, x| {
                if refused.is_none() {
                    refused = unheld(scalar, x).map(|why| format!("{} = {x} {why}", spec.name));
                }
            });
            if let Some(why) = refused {
                let wider = if scalar == ScalarKind::Q16 {
                    "f32 or f64"
                } else {
                    "f64"
                };
                bail!(
                    "{}: {why}; export in a wider arithmetic (--scalar {wider}), or state the \
                     parameters in units that bring it into range",
                    file.display()
                );
            }
        }
    }
    let n = src.elements.len();
    let len = match &src.elements {
        Elements::Bwbn(v) => table::bwbn_len(v[0].effect_set(), scalar, n),
        Elements::Phm(_) => table::phm_len(PHM_POINTS, scalar, n),
    }
    .ok_or_else(|| anyhow!("{n} elements make a table larger than this machine can address"))?;
    let mut out = vec![0u8; len];
    let len = match &src.elements {
        Elements::Bwbn(v) => table::write_bwbn(&mut out, scalar, &src.units, v),
        Elements::Phm(v) => table::write_phm(&mut out, scalar, &src.units, v),
    }
    .map_err(|e| anyhow!("cannot write the table: {e}"))?;
    out.truncate(len);
    if let Err(e) = verify(&out) {
        let file = match e {
            TableError::Bwbn { element, .. } | TableError::Phm { element, .. } => src
                .files
                .get(element as usize)
                .map(|p| format!("{}: ", p.display()))
                .unwrap_or_default(),
            _ => String::new(),
        };
        bail!(
            "{file}the parameters do not survive rounding to {}: {e}",
            scalar.name()
        );
    }
    Ok(out)
}

/// The elements of a verified table, as `f64` values for listing.
#[derive(Clone, Debug)]
pub enum Listing {
    /// BWBN elements.
    Bwbn(Vec<BwbnListing>),
    /// PHM: each element's curves (positive, negative) and the
    /// coefficients that differ from the thesis' values.
    Phm(Vec<PhmListing>),
}

/// One BWBN element for listing.
#[derive(Clone, Debug)]
pub struct BwbnListing {
    /// `(name, value)` of every parameter, in table order.
    pub values: Vec<(&'static str, f64)>,
    /// `energy_limit` (`None` = no limit).
    pub energy_limit: Option<f64>,
}

/// One PHM element for listing.
#[derive(Clone, Debug)]
pub struct PhmListing {
    /// `[twist, torque]` of the positive curve.
    pub positive: Vec<[f64; 2]>,
    /// `[twist, torque]` of the negative curve.
    pub negative: Vec<[f64; 2]>,
    /// `(name, value)` of the coefficients that differ from the thesis.
    pub coefficients: Vec<(&'static str, f64)>,
}

/// Loads `bytes` with the device's loader in the arithmetic and model its
/// header names, and returns the header and the elements.
pub fn verify(bytes: &[u8]) -> Result<(Header, Listing), TableError> {
    let t = Table::parse(bytes)?;
    let h = *t.header();
    let listing = match (h.model, h.scalar) {
        (ModelKind::Bwbn, ScalarKind::F64) => list_bwbn(t.bwbn::<f64>()?),
        (ModelKind::Bwbn, ScalarKind::F32) => list_bwbn(t.bwbn::<f32>()?),
        (ModelKind::Bwbn, ScalarKind::Q16) => list_bwbn(t.bwbn::<Fixed>()?),
        (ModelKind::Phm, ScalarKind::F64) => list_phm(t.phm::<f64, 254>()?),
        (ModelKind::Phm, ScalarKind::F32) => list_phm(t.phm::<f32, 254>()?),
        (ModelKind::Phm, ScalarKind::Q16) => list_phm(t.phm::<Fixed, 254>()?),
        _ => return Err(TableError::UnknownModel(h.model as u8)),
    };
    Ok((h, listing))
}

fn list_bwbn<S: TableScalar>(t: BwbnTable<'_, S>) -> Listing {
    Listing::Bwbn(
        t.iter()
            .map(|p| {
                let mut v = vec![];
                p.for_each(|s, x| v.push((s.name, x.to_f64())));
                BwbnListing {
                    values: v,
                    energy_limit: (p.energy_limit() != S::MAX).then(|| p.energy_limit().to_f64()),
                }
            })
            .collect(),
    )
}

fn list_phm<S: TableScalar>(t: PhmTable<'_, S, 254>) -> Listing {
    let thesis = hysteresis::phm::Coefficients::<S>::thesis();
    Listing::Phm(
        t.iter()
            .map(|p| {
                let curve = |d| {
                    p.primary(d)
                        .points()
                        .iter()
                        .map(|q: &[S; 2]| q.map(|x| x.to_f64()))
                        .collect()
                };
                let mut coefficients = vec![];
                p.coefficients().for_each(|s, x| {
                    if thesis.get(s.name) != Some(x) {
                        coefficients.push((s.name, x.to_f64()));
                    }
                });
                PhmListing {
                    positive: curve(Direction::Positive),
                    negative: curve(Direction::Negative),
                    coefficients,
                }
            })
            .collect(),
    )
}

/// One line describing a verified table's header.
pub fn describe(h: &Header) -> String {
    let model = match h.model {
        ModelKind::Bwbn => format!(
            "BWBN, model {}, Zu rule {}",
            ModelSpec {
                base: crate::model::Base::Bw,
                effects: h.effects,
                custom: 0,
            },
            if h.option == 1 { "OpenSees" } else { "thesis" }
        ),
        _ => format!("PHM, {} points per curve", h.option),
    };
    let unit = |u: &str| {
        if u.is_empty() {
            "-".to_string()
        } else {
            u.to_string()
        }
    };
    format!(
        "format {}: {model}, {}, units {} / {}, {} element{}, {} bytes",
        table::VERSION,
        h.scalar.name(),
        unit(h.units.displacement()),
        unit(h.units.force()),
        h.count,
        if h.count == 1 { "" } else { "s" },
        h.len
    )
}

/// The file name without directories, for reports.
pub fn short(path: &Path) -> String {
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}
