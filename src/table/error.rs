//! Why a table was refused (loading) or could not be written.

use super::{ModelKind, ScalarKind};
use crate::bwbn::ParamError;
use crate::phm::{Direction, PhmError};
use core::fmt;

/// Why a table was refused. Each variant names the first check that failed
/// (the order is that of [`Table::parse`](super::Table::parse), then the
/// elements in order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum TableError {
    /// Fewer bytes than the header (or the length the header declares)
    /// needs.
    Truncated {
        /// Bytes needed.
        needed: usize,
        /// Bytes given.
        found: usize,
    },
    /// More bytes than the header declares.
    TrailingBytes {
        /// The declared total length.
        declared: usize,
        /// Bytes given.
        found: usize,
    },
    /// The first four bytes are not `"HYTB"`: not a table.
    BadMagic,
    /// A format version this crate does not read.
    UnsupportedVersion(u16),
    /// The stored CRC-32 does not match the bytes: the table was corrupted.
    Checksum {
        /// The CRC at the end of the table.
        stored: u32,
        /// The CRC of the bytes before it.
        computed: u32,
    },
    /// The model code names no model.
    UnknownModel(u8),
    /// The scalar code names no arithmetic.
    UnknownScalar(u8),
    /// The effect bits name an effect that does not exist (or a PHM table
    /// has effect bits).
    UnknownEffects(u8),
    /// The model option byte is out of range (BWBN: Zu rule 0 or 1; PHM:
    /// 2 to 254 points per curve).
    BadOption(u8),
    /// A reserved field is not zero.
    ReservedNotZero {
        /// Its offset.
        offset: usize,
    },
    /// A unit field is not printable ASCII followed by NUL padding.
    BadUnits,
    /// The record size does not match the model, effects and arithmetic.
    RecordSize {
        /// The size the header's other fields imply.
        expected: usize,
        /// The size the header states.
        found: usize,
    },
    /// The table holds no element.
    NoElements,
    /// Element count times record size does not fill the declared length.
    LengthMismatch {
        /// Header + records + CRC.
        expected: usize,
        /// The declared total length.
        declared: usize,
    },
    /// The table holds another model than the caller loads.
    WrongModel {
        /// The model asked for.
        expected: ModelKind,
        /// The table's.
        found: ModelKind,
    },
    /// The table is in another arithmetic than the caller loads.
    WrongScalar {
        /// The arithmetic asked for.
        expected: ScalarKind,
        /// The table's.
        found: ScalarKind,
    },
    /// A PHM record's point count exceeds the points per curve of the
    /// table, or an unused point slot is not zero.
    PointCount {
        /// The element (0-based).
        element: u16,
        /// The curve.
        direction: Direction,
        /// The count stored.
        count: u8,
    },
    /// A reserved byte of element `element`'s record is not zero.
    RecordReserved {
        /// The element (0-based).
        element: u16,
    },
    /// A BWBN element's parameters fail the model's validation.
    Bwbn {
        /// The element (0-based).
        element: u16,
        /// What the parameter set refused.
        error: ParamError,
    },
    /// A PHM element's parameters fail the model's validation.
    Phm {
        /// The element (0-based).
        element: u16,
        /// What the parameter set refused.
        error: PhmError,
    },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use TableError::*;
        match *self {
            Truncated { needed, found } => {
                write!(f, "truncated: {found} bytes, the table needs {needed}")
            }
            TrailingBytes { declared, found } => write!(
                f,
                "{found} bytes, but the header declares a table of {declared}"
            ),
            BadMagic => f.write_str("not a parameter table (magic is not \"HYTB\")"),
            UnsupportedVersion(v) => write!(
                f,
                "format version {v}; this build reads version {}",
                super::VERSION
            ),
            Checksum { stored, computed } => write!(
                f,
                "corrupted: stored CRC-32 {stored:#010x}, computed {computed:#010x}"
            ),
            UnknownModel(c) => write!(f, "unknown model code {c}"),
            UnknownScalar(c) => write!(f, "unknown scalar code {c}"),
            UnknownEffects(b) => write!(f, "effect bits {b:#04x} name no effect set of this model"),
            BadOption(o) => write!(f, "model option {o} out of range"),
            ReservedNotZero { offset } => write!(f, "reserved field at offset {offset} is not zero"),
            BadUnits => f.write_str("a unit field is not printable ASCII padded with NUL"),
            RecordSize { expected, found } => write!(
                f,
                "record size {found} bytes; the model, effects and scalar need {expected}"
            ),
            NoElements => f.write_str("the table holds no element"),
            LengthMismatch { expected, declared } => write!(
                f,
                "the declared length {declared} does not match header + records + CRC = {expected}"
            ),
            WrongModel { expected, found } => write!(
                f,
                "the table holds {} elements, not {}",
                found.name(),
                expected.name()
            ),
            WrongScalar { expected, found } => write!(
                f,
                "the table is in {}, not {}",
                found.name(),
                expected.name()
            ),
            PointCount {
                element,
                direction,
                count,
            } => write!(
                f,
                "element {element}: {} primary curve has {count} points, more than the table's points per curve, or unused slots are not zero",
                match direction {
                    Direction::Positive => "positive",
                    Direction::Negative => "negative",
                }
            ),
            RecordReserved { element } => {
                write!(f, "element {element}: reserved bytes are not zero")
            }
            Bwbn { element, error } => write!(f, "element {element}: {error}"),
            Phm { element, error } => write!(f, "element {element}: {error}"),
        }
    }
}

impl core::error::Error for TableError {}

/// Why a table could not be written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum WriteError {
    /// No element given.
    NoElements,
    /// More than 65535 elements.
    TooManyElements(usize),
    /// The output buffer is too small.
    BufferTooSmall {
        /// Bytes needed.
        needed: usize,
        /// Bytes given.
        found: usize,
    },
    /// Element `element` has another effect set (or Zu rule, or more points
    /// per curve than 254) than element 0: one table holds one kind.
    Mixed {
        /// The element (0-based).
        element: usize,
    },
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            WriteError::NoElements => f.write_str("no element to write"),
            WriteError::TooManyElements(n) => {
                write!(f, "{n} elements; a table holds at most 65535")
            }
            WriteError::BufferTooSmall { needed, found } => {
                write!(f, "buffer of {found} bytes; the table needs {needed}")
            }
            WriteError::Mixed { element } => write!(
                f,
                "element {element} has another effect set or Zu rule than element 0; one table holds elements of one kind"
            ),
        }
    }
}

impl core::error::Error for WriteError {}
