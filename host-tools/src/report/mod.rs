//! Plots as SVG and self-contained HTML reports.

mod figure;
mod html;
pub mod plots;
mod render;
pub mod style;
pub mod ticks;
mod xml;

use std::fmt;

pub use figure::{Anchor, Annotation, Axis, Bars, Figure, Panel, Scale, Series};
pub use html::{significant, Cell, Report, Table};

/// Input a plot or table cannot be built from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Error {
    /// Two inputs that must match in length do not.
    Length {
        /// What was being counted.
        what: String,
        /// The length it must have.
        expected: usize,
        /// The length it has.
        found: usize,
    },
    /// An index points past the end of what it indexes.
    Index {
        /// What the index selects.
        what: String,
        /// The index given.
        index: usize,
        /// How many there are.
        len: usize,
    },
    /// Values that must share a unit do not.
    Unit {
        /// Whose unit differs.
        what: String,
        /// The unit the others have.
        expected: String,
        /// The unit it has.
        found: String,
    },
    /// Values that must ascend do not.
    Order {
        /// What must ascend, and where it does not.
        what: String,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Length {
                what,
                expected,
                found,
            } => write!(f, "{what}: expected {expected}, found {found}"),
            Self::Index { what, index, len } => {
                write!(f, "{what}: index {index} is out of range (there are {len})")
            }
            Self::Unit {
                what,
                expected,
                found,
            } => write!(f, "{what}: expected unit '{expected}', found '{found}'"),
            Self::Order { what } => write!(f, "{what} must ascend"),
        }
    }
}

impl std::error::Error for Error {}
