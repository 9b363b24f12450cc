//! Writing records and simulation results as CSV that the reader reads back
//! exactly: `#` comment lines, one header line with units in parentheses, then
//! one row a sample. Numbers are written in the shortest form that parses back
//! to the same `f64` (full precision, no rounding); no trailing commas.

use super::record::{Channel, Record};
use std::fmt;
use std::io::{self, Write};

/// Why a table could not be written.
#[derive(Debug)]
pub enum WriteError {
    /// The writer failed.
    Io(io::Error),
    /// A header is empty or holds a comma, a quote or a line break.
    BadHeader(String),
    /// A column has another length than the first.
    Length {
        /// The column's header.
        column: String,
        /// Its length.
        found: usize,
        /// The first column's length.
        expected: usize,
    },
    /// A value is not finite (the reader would refuse it).
    NotFinite {
        /// The column's header.
        column: String,
        /// Row (0-based sample index).
        row: usize,
        /// The value.
        value: f64,
    },
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            // The OS error is the source, which a chain of errors prints next.
            WriteError::Io(_) => write!(f, "cannot write"),
            WriteError::BadHeader(h) => write!(
                f,
                "expected a non-empty header without commas, quotes or line breaks, found '{h}'"
            ),
            WriteError::Length {
                column,
                found,
                expected,
            } => write!(
                f,
                "expected {expected} values in column '{column}' like the first column, found {found}"
            ),
            WriteError::NotFinite { column, row, value } => write!(
                f,
                "expected finite values, found {value} in column '{column}' at sample {row}"
            ),
        }
    }
}

impl std::error::Error for WriteError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            WriteError::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<io::Error> for WriteError {
    fn from(e: io::Error) -> Self {
        WriteError::Io(e)
    }
}

/// Writes columns as CSV: each `(header, values)` pair is one column, e.g.
/// `("force (kN)", &force)`. Comments are written first as `# ` lines.
/// Everything is checked before the first byte is written.
///
/// ```
/// use hyst::data::write_columns;
/// let mut out = Vec::new();
/// let u = [0.0, 0.1, 0.2];
/// let f = [0.0, 0.6, 1.0 / 3.0];
/// write_columns(&mut out, &["made by a doc test".into()], &[("displacement (mm)", &u), ("force (kN)", &f)])?;
/// assert_eq!(
///     String::from_utf8(out).unwrap(),
///     "# made by a doc test\ndisplacement (mm),force (kN)\n0,0\n0.1,0.6\n0.2,0.3333333333333333\n"
/// );
/// # Ok::<(), hyst::data::WriteError>(())
/// ```
pub fn write_columns<W: Write>(
    out: W,
    comments: &[String],
    columns: &[(&str, &[f64])],
) -> Result<(), WriteError> {
    let n = columns.first().map_or(0, |c| c.1.len());
    for (h, v) in columns {
        if h.trim().is_empty() || h.contains([',', '"', '\n', '\r']) {
            return Err(WriteError::BadHeader(h.to_string()));
        }
        if v.len() != n {
            return Err(WriteError::Length {
                column: h.to_string(),
                found: v.len(),
                expected: n,
            });
        }
        if let Some(row) = v.iter().position(|x| !x.is_finite()) {
            return Err(WriteError::NotFinite {
                column: h.to_string(),
                row,
                value: v[row],
            });
        }
    }
    let mut out = io::BufWriter::new(out);
    for c in comments {
        for line in c.lines() {
            writeln!(out, "# {line}")?;
        }
    }
    let header: Vec<&str> = columns.iter().map(|c| c.0).collect();
    writeln!(out, "{}", header.join(","))?;
    for k in 0..n {
        for (j, (_, v)) in columns.iter().enumerate() {
            if j > 0 {
                out.write_all(b",")?;
            }
            // `Display` of f64 is the shortest text that parses back exactly.
            write!(out, "{}", v[k])?;
        }
        out.write_all(b"\n")?;
    }
    out.flush()?;
    Ok(())
}

/// Writes a record in canonical units: `time (s)` if it has a time base, then
/// `displacement (mm)` and `force (kN)` for the signals it has; its comments
/// are written as `#` lines. [`read`](super::read) gives the same values back.
pub fn write_record<W: Write>(out: W, record: &Record) -> Result<(), WriteError> {
    let mut columns: Vec<(&str, &[f64])> = Vec::new();
    if let Some(t) = record.time() {
        columns.push(("time (s)", t));
    }
    for (channel, header) in [
        (Channel::Displacement, "displacement (mm)"),
        (Channel::Force, "force (kN)"),
    ] {
        if let Some(s) = record.series(channel) {
            columns.push((header, &s.values));
        }
    }
    write_columns(out, record.comments(), &columns)
}
