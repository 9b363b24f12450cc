//! Ready-made plots of the quantities this project compares: hysteresis
//! loops, signals, residuals, per-cycle errors and energies, model ladders,
//! Pareto fronts and parameter sensitivity.
//!
//! Every function takes plain slices and names, returns a [`Figure`](super::Figure) (or an
//! [`Error`] for inputs that do not fit together) and never panics. Measured
//! data is drawn thin and grey, models in the palette's colours on top.

mod loops;
mod models;
mod residuals;
mod signals;

pub use loops::{energy_curves, loop_overlay};
pub use models::{ladder, pareto_front, sensitivity, Pareto, Rung};
pub use residuals::{per_cycle_bars, residual_map, Residuals};
pub use signals::{time_series, xy};

use super::style::{self, Colour};
use super::{Error, Series};

/// Whether a curve was measured or predicted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// Lab data: thin grey.
    Measured,
    /// A model's prediction: a palette colour.
    Model,
}

/// A named quantity and its unit, for axis labels (`Force`, `kN`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantity<'a> {
    /// What is measured.
    pub name: &'a str,
    /// Its unit (may be empty).
    pub unit: &'a str,
}

impl<'a> Quantity<'a> {
    /// `name` in `unit`.
    pub fn new(name: &'a str, unit: &'a str) -> Self {
        Self { name, unit }
    }
}

/// A named curve `y(x)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trace<'a> {
    /// Legend name.
    pub name: &'a str,
    /// Measured or model.
    pub source: Source,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates, one per abscissa.
    pub y: &'a [f64],
}

impl<'a> Trace<'a> {
    /// A measured curve.
    pub fn measured(name: &'a str, x: &'a [f64], y: &'a [f64]) -> Self {
        Self {
            name,
            source: Source::Measured,
            x,
            y,
        }
    }

    /// A model's curve.
    pub fn model(name: &'a str, x: &'a [f64], y: &'a [f64]) -> Self {
        Self {
            name,
            source: Source::Model,
            x,
            y,
        }
    }
}

/// A named sequence of values in one unit (a force record, per-cycle errors).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Signal<'a> {
    /// Legend name.
    pub name: &'a str,
    /// Measured or model.
    pub source: Source,
    /// Unit of the values.
    pub unit: &'a str,
    /// The values.
    pub values: &'a [f64],
}

impl<'a> Signal<'a> {
    /// A measured signal.
    pub fn measured(name: &'a str, unit: &'a str, values: &'a [f64]) -> Self {
        Self {
            name,
            source: Source::Measured,
            unit,
            values,
        }
    }

    /// A model's signal.
    pub fn model(name: &'a str, unit: &'a str, values: &'a [f64]) -> Self {
        Self {
            name,
            source: Source::Model,
            unit,
            values,
        }
    }
}

/// What signals are plotted against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeBase<'a> {
    /// The sample index 0, 1, 2, …
    Index,
    /// Sample times, one per sample, in `unit`.
    Time {
        /// The times.
        values: &'a [f64],
        /// Their unit.
        unit: &'a str,
    },
}

impl TimeBase<'_> {
    /// The abscissae for `n` samples, or an error naming `what` when the
    /// times do not number `n`.
    fn abscissae(&self, n: usize, what: &str) -> Result<Vec<f64>, Error> {
        match self {
            Self::Index => Ok((0..n).map(|i| i as f64).collect()),
            Self::Time { values, .. } if values.len() == n => Ok(values.to_vec()),
            Self::Time { values, .. } => Err(Error::Length {
                what: format!("samples of {what} (one per time value)"),
                expected: values.len(),
                found: n,
            }),
        }
    }

    /// The x axis quantity.
    fn quantity(&self) -> Quantity<'_> {
        match self {
            Self::Index => Quantity::new("Sample", ""),
            Self::Time { unit, .. } => Quantity::new("Time", unit),
        }
    }
}

/// Gives measured curves thin grey lines and models the palette in turn.
#[derive(Debug, Default)]
struct Painter {
    models: usize,
}

impl Painter {
    /// Index of the next model in the palette.
    fn next_model(&mut self) -> usize {
        self.models += 1;
        self.models - 1
    }

    /// `s` styled for its source.
    fn paint(&mut self, s: Series, source: Source) -> Series {
        match source {
            Source::Measured => s.measured(),
            Source::Model => s.palette(self.next_model()),
        }
    }

    /// The fill colour for bars of the given source.
    fn colour(&mut self, source: Source) -> Colour {
        match source {
            Source::Measured => style::MEASURED,
            Source::Model => style::series(self.next_model()),
        }
    }
}

/// Checks that every signal is in `unit`.
fn same_unit(signals: &[Signal], unit: &str) -> Result<(), Error> {
    match signals.iter().find(|s| s.unit != unit) {
        Some(s) => Err(Error::Unit {
            what: format!("signal '{}'", s.name),
            expected: unit.into(),
            found: s.unit.into(),
        }),
        None => Ok(()),
    }
}

/// Checks that every signal has `n` values.
fn same_length(signals: &[Signal], n: usize) -> Result<(), Error> {
    match signals.iter().find(|s| s.values.len() != n) {
        Some(s) => Err(Error::Length {
            what: format!("values of '{}'", s.name),
            expected: n,
            found: s.values.len(),
        }),
        None => Ok(()),
    }
}
