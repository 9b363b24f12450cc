//! Plots as SVG and self-contained HTML reports, so that a model can be
//! compared with lab measurements by looking rather than reading.
//!
//! Three layers, each usable alone:
//!
//! - **Ready-made plots** ([`plots`]) over plain slices: [`plots::loop_overlay`]
//!   (force against displacement, measured thin and grey, models in colour),
//!   [`plots::time_series`], [`plots::residual_map`] (residual by branch class
//!   and by cycle), [`plots::per_cycle_bars`], [`plots::ladder`] (NRMSE on a
//!   log axis and ΔBIC as effects are added), [`plots::energy_curves`],
//!   [`plots::pareto_front`], [`plots::sensitivity`] (thesis Fig. 3.7) and
//!   [`plots::xy`]. They depend on no other module of this crate.
//! - **The plot model**: a [`Figure`] of [`Panel`]s, each with two [`Axis`]
//!   (linear, log or categorical) and [`Series`] (lines, dots, filled areas),
//!   grouped [`Bars`], reference lines, shaded bands and [`Annotation`]s.
//!   [`Figure::to_svg`] writes a standalone SVG file, [`Figure::to_svg_inline`]
//!   an element for a web page.
//! - **The page**: a [`Report`] of sections, paragraphs, [`Table`]s and
//!   figures, written as one HTML file with inline CSS and SVG, no scripts and
//!   nothing fetched from elsewhere, readable when printed.
//!
//! What the drawing takes care of:
//!
//! - Ticks at 1, 2 or 5 × 10ⁿ ([`ticks`]); large or small values get a common
//!   factor such as ×10³ beside the unit in the axis title; labels use a true
//!   minus sign and never show floating-point noise.
//! - The legend goes into an inside corner that covers no data, else into a
//!   row above the plot, else beside it. Panels in a row share their top edge,
//!   panels in a column their left and right edges.
//! - NaN or infinite points, and points at or below zero on a log axis, are
//!   not drawn, and the panel says how many in a note under it; data is never
//!   silently dropped, and no input makes the drawing panic. Inputs that do not
//!   fit together (lengths, units, indices) are refused with an [`Error`].
//! - Text that would not fit is shortened with an ellipsis, keeping the whole
//!   text in a tooltip.
//! - Colours are the Okabe–Ito palette, distinguishable with the common kinds
//!   of colour blindness ([`style`]); an eighth series is dashed.
//!
//! There is no plotting dependency: SVG is plain text, and owning the layout
//! is what lets legends avoid data and panels line up.
//!
//! # Example
//!
//! ```
//! use hyst::report::plots::{loop_overlay, Quantity, Trace};
//! use hyst::report::{Report, Table};
//!
//! // A measured loop and a model's, as plain slices.
//! let u: Vec<f64> = (0..200).map(|i| 5.0 * (i as f64 * 0.0314).sin()).collect();
//! let measured: Vec<f64> = u.iter().map(|u| 4.0 * u.tanh()).collect();
//! let model: Vec<f64> = u.iter().map(|u| 3.8 * u.tanh()).collect();
//!
//! let fig = loop_overlay(
//!     &[Trace::measured("measured", &u, &measured), Trace::model("bw", &u, &model)],
//!     Quantity::new("Displacement", "mm"),
//!     Quantity::new("Force", "kN"),
//! )?;
//! let svg = fig.to_svg();
//! assert!(svg.contains("Displacement (mm)"));
//!
//! let mut table = Table::new(&["Model", "Parameters", "NRMSE"]);
//! table.row(vec!["bw".into(), 6usize.into(), 0.0123.into()])?;
//! let mut page = Report::new("Column 415");
//! page.section("Loops")
//!     .paragraph("The model against the measured loops.")
//!     .figure(&fig, "Force against displacement.")
//!     .table(&table);
//! let path = std::env::temp_dir().join("hyst-report-doc-example.html");
//! page.write(&path)?;
//! # std::fs::remove_file(&path)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

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
