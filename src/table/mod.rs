//! Parameter tables: the validated parameters of one or many elements as
//! bytes, from the host (`hyst export`) to the controller's flash.
//!
//! A table holds the elements of one model kind ([`ModelKind`]), with one
//! effect set, in one arithmetic ([`ScalarKind`]), with the units of the
//! data they were fitted to, followed by a CRC-32 of everything before it.
//! The byte-by-byte layout is in `docs/table-format.md`; in short:
//!
//! ```text
//! offset size field
//!      0    4 magic "HYTB"
//!      4    2 format version (1)
//!      6    1 model kind (1 BWBN, 2 PHM)
//!      7    1 scalar (1 f64, 2 f32, 3 Q15.16)
//!      8    1 effect bits (BWBN: EffectSet::bits; PHM: 0)
//!      9    1 model option (BWBN: Zu rule, 0 thesis / 1 OpenSees; PHM: points per curve)
//!     10    2 element count (>= 1)
//!     12    2 record size in bytes
//!     14    2 reserved (0)
//!     16    4 total length in bytes, CRC included
//!     20    8 displacement (twist) unit, ASCII, NUL-padded
//!     28    8 force (torque) unit, ASCII, NUL-padded
//!     36    - element records, count x record size
//! len - 4   4 CRC-32 (IEEE) of bytes 0 .. len - 4
//! ```
//!
//! All integers and values are little-endian.
//!
//! # Verified load
//!
//! [`BwbnTable::load`] and [`PhmTable::load`] check the whole table before
//! they return: length, magic, version, CRC, header fields, the arithmetic
//! and model the caller asked for, and every element through the model's own
//! validating constructor. Only a table that passed all of it exists as a
//! typed table, and elements come out of it only through
//! [`BwbnTable::get`]/[`BwbnTable::iter`] (decoded again from the same bytes,
//! so nothing is copied to RAM but the element being built). A table that
//! fails any check yields nothing, so nothing half-loaded can be used.
//! Loading never panics, never allocates, and reads the bytes in place (a
//! `&'static [u8]` in flash works as it is).
//!
//! ```
//! use hysteresis::bwbn::{BoucWen, Bwbn, BwbnParams};
//! use hysteresis::table::{self, BwbnTable, ScalarKind, TableError, Units};
//!
//! let p = BwbnParams::plain(BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).unwrap());
//! let units = Units::new("mm", "kN").unwrap();
//! let mut buf = [0u8; 128];
//! let n = table::write_bwbn(&mut buf, ScalarKind::F32, &units, &[p, p]).unwrap();
//! let bytes = &buf[..n];
//!
//! let t = BwbnTable::<f32>::load(bytes).unwrap();
//! assert_eq!(t.len(), 2);
//! let mut elements = t.iter().map(Bwbn::new);
//! assert!(elements.next().is_some());
//!
//! // The table was written in f32: loading it as f64 is refused.
//! assert!(matches!(BwbnTable::<f64>::load(bytes), Err(TableError::WrongScalar { .. })));
//! // So is a table with a flipped bit.
//! let mut bad = [0u8; 128];
//! bad[..n].copy_from_slice(bytes);
//! bad[40] ^= 1;
//! assert!(matches!(BwbnTable::<f32>::load(&bad[..n]), Err(TableError::Checksum { .. })));
//! ```

mod bwbn;
mod crc;
mod error;
mod phm;
mod scalar;
#[cfg(test)]
mod tests;
mod write;

pub use bwbn::{bwbn_record_size, BwbnTable};
pub use crc::{crc32, Crc32};
pub use error::{TableError, WriteError};
pub use phm::{phm_record_size, PhmTable};
pub use scalar::TableScalar;
pub use write::{bwbn_len, phm_len, write_bwbn, write_phm};

use crate::bwbn::EffectSet;

/// The first four bytes of every table.
pub const MAGIC: [u8; 4] = *b"HYTB";
/// The format version this crate reads and writes.
pub const VERSION: u16 = 1;
/// Bytes before the first element record.
pub const HEADER_LEN: usize = 36;
/// Bytes of the CRC at the end.
pub const CRC_LEN: usize = 4;
/// Bytes of each unit field.
pub const UNIT_LEN: usize = 8;

/// Which model a table's elements are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
#[repr(u8)]
pub enum ModelKind {
    /// Bouc-Wen-Baber-Noori ([`crate::bwbn`]).
    Bwbn = 1,
    /// Polygonal torsion model ([`crate::phm`]).
    Phm = 2,
}

impl ModelKind {
    /// The kind with header code `code`.
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            1 => Some(ModelKind::Bwbn),
            2 => Some(ModelKind::Phm),
            _ => None,
        }
    }
    /// Short name (`"bwbn"`, `"phm"`).
    pub const fn name(self) -> &'static str {
        match self {
            ModelKind::Bwbn => "bwbn",
            ModelKind::Phm => "phm",
        }
    }
}

/// Which arithmetic a table's values are stored in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
#[repr(u8)]
pub enum ScalarKind {
    /// IEEE 754 binary64.
    F64 = 1,
    /// IEEE 754 binary32.
    F32 = 2,
    /// Q15.16 fixed point ([`Fixed`](crate::Fixed)), the raw `i32`.
    Q16 = 3,
}

impl ScalarKind {
    /// Every arithmetic.
    pub const ALL: [ScalarKind; 3] = [ScalarKind::F64, ScalarKind::F32, ScalarKind::Q16];

    /// The kind with header code `code`.
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            1 => Some(ScalarKind::F64),
            2 => Some(ScalarKind::F32),
            3 => Some(ScalarKind::Q16),
            _ => None,
        }
    }
    /// The name [`Scalar::NAME`](crate::Scalar::NAME) of the arithmetic
    /// (`"f64"`, `"f32"`, `"q16"`).
    pub const fn name(self) -> &'static str {
        match self {
            ScalarKind::F64 => "f64",
            ScalarKind::F32 => "f32",
            ScalarKind::Q16 => "q16",
        }
    }
    /// The kind named `name` (as [`name`](Self::name)).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The units of a table's values: displacement (twist for PHM) and force
/// (torque), each at most 8 printable ASCII characters (`"mm"`, `"kN"`,
/// `"deg"`, `"kN m"`); empty means unstated. The models do not convert
/// units: these tell the firmware what its sensors must deliver.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Units {
    displacement: [u8; UNIT_LEN],
    force: [u8; UNIT_LEN],
}

impl Units {
    /// The units, or `None` if a name is longer than 8 bytes or not
    /// printable ASCII.
    pub fn new(displacement: &str, force: &str) -> Option<Self> {
        Some(Units {
            displacement: unit_field(displacement)?,
            force: unit_field(force)?,
        })
    }

    /// The displacement (twist) unit.
    pub fn displacement(&self) -> &str {
        unit_str(&self.displacement)
    }

    /// The force (torque) unit.
    pub fn force(&self) -> &str {
        unit_str(&self.force)
    }

    fn from_fields(d: [u8; UNIT_LEN], f: [u8; UNIT_LEN]) -> Option<Self> {
        (valid_unit(&d) && valid_unit(&f)).then_some(Units {
            displacement: d,
            force: f,
        })
    }
}

fn unit_field(s: &str) -> Option<[u8; UNIT_LEN]> {
    let mut f = [0u8; UNIT_LEN];
    f.get_mut(..s.len())?.copy_from_slice(s.as_bytes());
    valid_unit(&f).then_some(f)
}

/// Printable ASCII, then NUL padding only.
fn valid_unit(f: &[u8; UNIT_LEN]) -> bool {
    let len = f.iter().position(|&b| b == 0).unwrap_or(UNIT_LEN);
    f[..len].iter().all(|b| (0x20..0x7f).contains(b)) && f[len..].iter().all(|&b| b == 0)
}

fn unit_str(f: &[u8; UNIT_LEN]) -> &str {
    let len = f.iter().position(|&b| b == 0).unwrap_or(UNIT_LEN);
    core::str::from_utf8(&f[..len]).unwrap_or("")
}

/// The header of a table whose structure and CRC were checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Header {
    /// The elements' model.
    pub model: ModelKind,
    /// The arithmetic of the values.
    pub scalar: ScalarKind,
    /// BWBN: the effects that are on (none for PHM).
    pub effects: EffectSet,
    /// BWBN: 0 = Zu by the thesis, 1 = Zu as OpenSees; PHM: points per
    /// primary curve in each record.
    pub option: u8,
    /// Number of elements.
    pub count: u16,
    /// Bytes per element record.
    pub record_size: u16,
    /// Total length in bytes, CRC included.
    pub len: u32,
    /// Units of the values.
    pub units: Units,
}

/// A table whose structure was checked (length, magic, version, CRC, header
/// fields, record size), but not yet its elements: turn it into a
/// [`BwbnTable`] or [`PhmTable`] to use them.
#[derive(Clone, Copy, Debug)]
pub struct Table<'a> {
    bytes: &'a [u8],
    header: Header,
}

// Readers of the fixed-size header: constant offsets into an array, so the
// compiler proves them in bounds (no panic path in the firmware).
fn u16_at<const L: usize>(b: &[u8; L], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn u32_at<const L: usize>(b: &[u8; L], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn field8(b: &[u8; HEADER_LEN], at: usize) -> [u8; UNIT_LEN] {
    let mut f = [0u8; UNIT_LEN];
    for (i, x) in f.iter_mut().enumerate() {
        *x = b[at + i];
    }
    f
}

impl<'a> Table<'a> {
    /// Checks the structure of `bytes`, which must be exactly one table.
    ///
    /// The checks run in this order, so each error means what it says:
    /// shorter than a header ([`TableError::Truncated`]), magic, version,
    /// declared length against `bytes.len()` (truncated or trailing bytes),
    /// CRC, then the header fields.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, TableError> {
        let found = bytes.len();
        // Magic and version are read before anything else: a later format
        // version may lay out the rest differently.
        let truncated = TableError::Truncated {
            needed: HEADER_LEN + CRC_LEN,
            found,
        };
        let start: &[u8; 6] = bytes.first_chunk().ok_or(truncated)?;
        if start[..4] != MAGIC {
            return Err(TableError::BadMagic);
        }
        let version = u16_at(start, 4);
        if version != VERSION {
            return Err(TableError::UnsupportedVersion(version));
        }
        if found < HEADER_LEN + CRC_LEN {
            return Err(truncated);
        }
        let h: &[u8; HEADER_LEN] = bytes.first_chunk().ok_or(truncated)?;
        let declared = u32_at(h, 16) as usize;
        if declared > found {
            return Err(TableError::Truncated {
                needed: declared,
                found,
            });
        }
        if declared < found {
            return Err(TableError::TrailingBytes { declared, found });
        }
        let (body, tail) = bytes.split_last_chunk::<CRC_LEN>().ok_or(truncated)?;
        let stored = u32::from_le_bytes(*tail);
        let computed = crc32(body);
        if stored != computed {
            return Err(TableError::Checksum { stored, computed });
        }
        let model = ModelKind::from_code(h[6]).ok_or(TableError::UnknownModel(h[6]))?;
        let scalar = ScalarKind::from_code(h[7]).ok_or(TableError::UnknownScalar(h[7]))?;
        let effects = EffectSet::from_bits(h[8]).ok_or(TableError::UnknownEffects(h[8]))?;
        let option = h[9];
        let count = u16_at(h, 10);
        let record_size = u16_at(h, 12);
        if u16_at(h, 14) != 0 {
            return Err(TableError::ReservedNotZero { offset: 14 });
        }
        let units = Units::from_fields(field8(h, 20), field8(h, 28)).ok_or(TableError::BadUnits)?;
        let expected = match model {
            ModelKind::Bwbn => {
                if option > 1 {
                    return Err(TableError::BadOption(option));
                }
                bwbn_record_size(effects, scalar)
            }
            ModelKind::Phm => {
                if effects != EffectSet::NONE {
                    return Err(TableError::UnknownEffects(h[8]));
                }
                if !(2..=phm::MAX_POINTS).contains(&option) {
                    return Err(TableError::BadOption(option));
                }
                phm_record_size(option as usize, scalar)
            }
        };
        if record_size as usize != expected {
            return Err(TableError::RecordSize {
                expected,
                found: record_size as usize,
            });
        }
        if count == 0 {
            return Err(TableError::NoElements);
        }
        let body_len = HEADER_LEN + count as usize * expected + CRC_LEN;
        if body_len != found {
            return Err(TableError::LengthMismatch {
                expected: body_len,
                declared,
            });
        }
        Ok(Table {
            bytes,
            header: Header {
                model,
                scalar,
                effects,
                option,
                count,
                record_size,
                len: declared as u32,
                units,
            },
        })
    }

    /// The header.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// The bytes of record `i` (`None` if `i >= count`).
    fn record(&self, i: usize) -> Option<&'a [u8]> {
        if i >= self.header.count as usize {
            return None;
        }
        let size = self.header.record_size as usize;
        let start = HEADER_LEN + i * size;
        self.bytes.get(start..start + size)
    }

    /// The table as BWBN elements in `S`, every element validated.
    pub fn bwbn<S: TableScalar>(self) -> Result<BwbnTable<'a, S>, TableError> {
        BwbnTable::verify(self)
    }

    /// The table as PHM elements in `S` with room for `N` points per
    /// primary curve, every element validated.
    pub fn phm<S: TableScalar, const N: usize>(self) -> Result<PhmTable<'a, S, N>, TableError> {
        PhmTable::verify(self)
    }

    fn expect(&self, model: ModelKind, scalar: ScalarKind) -> Result<(), TableError> {
        if self.header.model != model {
            return Err(TableError::WrongModel {
                expected: model,
                found: self.header.model,
            });
        }
        if self.header.scalar != scalar {
            return Err(TableError::WrongScalar {
                expected: scalar,
                found: self.header.scalar,
            });
        }
        Ok(())
    }
}
