//! Reading a record from a file: the options, and the choice between the CSV
//! and JSON readers by file extension.

use super::baseline::Baseline;
use super::columns::Role;
use super::error::DataError;
use super::record::{Channel, Record};
use super::units::Unit;
use super::{csv, json};
use std::fmt;
use std::path::Path;

/// A column of a CSV file, by header text or by 1-based position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ColumnRef {
    /// The header field as written (trimmed, unquoted), or its name without
    /// the unit: `force_kN` and `force` both name the column `force_kN`.
    Name(String),
    /// The 1-based column number.
    Number(usize),
}

impl From<&str> for ColumnRef {
    fn from(s: &str) -> Self {
        ColumnRef::Name(s.to_string())
    }
}

impl From<usize> for ColumnRef {
    fn from(n: usize) -> Self {
        ColumnRef::Number(n)
    }
}

impl fmt::Display for ColumnRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ColumnRef::Name(n) => write!(f, "'{n}'"),
            ColumnRef::Number(k) => write!(f, "number {k}"),
        }
    }
}

/// How to read a record. The defaults recognise roles and units from the
/// header (see [`columns`](super::columns)); every option overrides one guess.
///
/// ```
/// use hyst::data::{Channel, ReadOptions, Role, Unit};
/// // The MR-damper file has no units in its header and two force-like columns.
/// let options = ReadOptions::default()
///     .role("D", Role::Displacement)
///     .unit("D", Unit::Centimetre)
///     .role("F", Role::Force)
///     .unit("F", Unit::Newton);
/// // The Bouc-Wen benchmark has no time column: sample k is at k / 750 s.
/// let benchmark = ReadOptions::default().sample_rate(750.0).input(Channel::Force);
/// # let _ = (options, benchmark);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// Roles given to columns (CSV only). A role given here is taken by no
    /// other column.
    pub roles: Vec<(ColumnRef, Role)>,
    /// Units given to columns (CSV only); they replace the file's unit, with a
    /// notice.
    pub units: Vec<(ColumnRef, Unit)>,
    /// The input channel; by default displacement, or force when the force
    /// column is named `u` (the system-identification convention of the
    /// Bouc-Wen benchmark), or what a JSON layout documents.
    pub input: Option<Channel>,
    /// Build the time base from this sample rate (Hz): sample `k` is at
    /// `k / rate`. Replaces a time column of the file, with a notice.
    pub sample_rate_hz: Option<f64>,
    /// Skip this many leading data rows (e.g. a point count written as a data
    /// row); each skipped row is reported as a notice.
    pub skip_rows: usize,
    /// Read at most this many data rows after the skipped ones; the rest of
    /// the file is not read (a tail of other data or of text), and how much
    /// of it there was is reported as a notice.
    pub max_rows: Option<usize>,
    /// Constants or lines taken off a channel once it is read (a known zero
    /// offset or drift of an instrument; [`Record::subtract`]), in turn, each
    /// reported as a notice; two for one channel add up.
    pub subtract: Vec<(Channel, Baseline)>,
    /// Channels whose sign is flipped once read, before any constant is
    /// subtracted ([`Record::negate`]).
    pub negate: Vec<Channel>,
    /// A channel read this many samples late against the other, realigned
    /// once read ([`Record::realign`]).
    pub lag: Option<(Channel, i64)>,
    /// A dashpot's coefficient: its force, this times the speed of the
    /// displacement, is taken off the force once the record is read and
    /// realigned ([`Record::take_dashpot`]).
    pub dashpot: Option<f64>,
}

impl ReadOptions {
    /// Gives a column a role.
    pub fn role(mut self, column: impl Into<ColumnRef>, role: Role) -> Self {
        self.roles.push((column.into(), role));
        self
    }

    /// Gives a column a unit.
    pub fn unit(mut self, column: impl Into<ColumnRef>, unit: Unit) -> Self {
        self.units.push((column.into(), unit));
        self
    }

    /// Sets the input channel.
    pub fn input(mut self, channel: Channel) -> Self {
        self.input = Some(channel);
        self
    }

    /// Sets the sample rate in Hz.
    pub fn sample_rate(mut self, hz: f64) -> Self {
        self.sample_rate_hz = Some(hz);
        self
    }

    /// Skips leading data rows.
    pub fn skip_rows(mut self, rows: usize) -> Self {
        self.skip_rows = rows;
        self
    }

    /// Reads at most `rows` data rows after the skipped ones.
    pub fn max_rows(mut self, rows: usize) -> Self {
        self.max_rows = Some(rows);
        self
    }

    /// Takes `value`, a constant or a line in the sample number, off every
    /// sample of `channel` once it is read.
    pub fn subtract(mut self, channel: Channel, value: impl Into<Baseline>) -> Self {
        self.subtract.push((channel, value.into()));
        self
    }

    /// Flips the sign of `channel` once it is read.
    pub fn negate(mut self, channel: Channel) -> Self {
        self.negate.push(channel);
        self
    }

    /// Takes a dashpot of coefficient `c` off the force once it is read.
    pub fn dashpot(mut self, c: f64) -> Self {
        self.dashpot = Some(c);
        self
    }

    /// Realigns `channel`, read `samples` samples late against the other.
    pub fn lag(mut self, channel: Channel, samples: i64) -> Self {
        self.lag = Some((channel, samples));
        self
    }

    /// Checks the sample rate.
    pub(crate) fn checked_sample_rate(&self, file: &Path) -> Result<Option<f64>, DataError> {
        match self.sample_rate_hz {
            // 1e-320 Hz is positive, but its sample times are not finite.
            Some(hz) if !(hz.is_finite() && hz > 0.0 && hz.recip().is_finite()) => {
                let shown = if hz == 0.0 || (1e-6..1e12).contains(&hz.abs()) {
                    format!("{hz}")
                } else {
                    format!("{hz:e}")
                };
                // 1e-320 Hz was refused as if it were not positive (found by review).
                let expected = if hz > 0.0 && hz.is_finite() {
                    "a sample rate whose interval 1/rate is finite"
                } else {
                    "a positive finite sample rate"
                };
                Err(DataError::file(
                    file,
                    format!("expected {expected}, found {shown} Hz"),
                ))
            }
            other => Ok(other),
        }
    }
}

/// The formats the readers know, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header (`.csv`, `.txt`, `.tsv`; tabs or
    /// semicolons where the header has no comma).
    Csv,
    /// One of the JSON layouts of [`json`](super::json) (`.json`).
    Json,
}

impl Format {
    /// The format of a path, from its extension.
    pub fn of(path: &Path) -> Result<Format, DataError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("csv") | Some("txt") | Some("tsv") => Ok(Format::Csv),
            Some("json") => Ok(Format::Json),
            other => Err(DataError::file(
                path,
                format!(
                    "expected a .csv, .tsv, .txt or .json file, found {} (MATLAB .mat and HDF5 files \
                     are not read: use their CSV copies)",
                    other.map_or("no extension".to_string(), |e| format!("'.{e}'"))
                ),
            )),
        }
    }
}

/// Reads a record from a file, choosing the reader by extension.
///
/// ```no_run
/// use hyst::data::{read, ReadOptions};
/// let r = read("../shared/data/peer-spd-columns/fd/spd_369.csv", &ReadOptions::default())?;
/// let (u, f) = r.displacement_force()?;
/// println!("{} samples, peak force {} kN", u.len(), f.iter().fold(0.0f64, |m, v| m.max(v.abs())));
/// # Ok::<(), hyst::data::DataError>(())
/// ```
pub fn read(path: impl AsRef<Path>, options: &ReadOptions) -> Result<Record, DataError> {
    let path = path.as_ref();
    let format = Format::of(path)?;
    let text = read_text(path)?;
    read_str(path, &text, format, options)
}

/// The text of a file every reader takes (records, parameter, PHM and
/// specimen files): UTF-8, with a leading byte-order mark dropped (a
/// spreadsheet's or Notepad's; the JSON and TOML parsers refuse it at 1:1).
/// A byte that is not UTF-8 is an error at its line and column.
pub fn read_text(path: &Path) -> Result<String, DataError> {
    let bytes = std::fs::read(path)
        .map_err(|e| DataError::file(path, format!("cannot read the file: {e}")))?;
    let mut text = String::from_utf8(bytes).map_err(|e| not_utf8(path, &e))?;
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(text)
}

/// Where the text stops being UTF-8: the line and column (in characters) of
/// the first byte that is not, and the byte.
fn not_utf8(path: &Path, e: &std::string::FromUtf8Error) -> DataError {
    let bytes = e.as_bytes();
    let good = e.utf8_error().valid_up_to();
    // The prefix is valid UTF-8 by the error's own account.
    let before = std::str::from_utf8(&bytes[..good]).unwrap_or_default();
    // Lines end as the reader ends them: LF, CRLF or a lone CR.
    let start = before.rfind(['\n', '\r']).map_or(0, |i| i + 1);
    let line = csv::lines(before).count() + usize::from(start == before.len());
    let column = before[start..].chars().count() + 1;
    DataError::at(
        path,
        line,
        column,
        format!(
            "byte {:#04x} is not UTF-8: save the file as UTF-8 (a Latin-1 '°' or 'µ' is one such byte)",
            bytes.get(good).copied().unwrap_or_default()
        ),
    )
}

/// Reads a record from text already in memory; `name` is used in messages.
pub fn read_str(
    name: impl AsRef<Path>,
    text: &str,
    format: Format,
    options: &ReadOptions,
) -> Result<Record, DataError> {
    if options.max_rows == Some(0) {
        return Err(DataError::file(
            name.as_ref(),
            "expected a positive number of rows to read at most, found 0",
        ));
    }
    let mut record = match format {
        Format::Csv => csv::parse(name.as_ref(), text, options),
        Format::Json => json::parse(name.as_ref(), text, options),
    }?;
    for (i, &channel) in options.negate.iter().enumerate() {
        if options.negate[..i].contains(&channel) {
            return Err(DataError::file(
                name.as_ref(),
                format!("expected the {channel} to be negated once, found it asked twice"),
            ));
        }
        record.negate(channel)?;
    }
    // Offsets given twice for a channel are both taken off (they add up): the
    // checks of `hyst diagnose` name what is left once a first one is off.
    for &(channel, value) in &options.subtract {
        record.subtract(channel, value)?;
    }
    if let Some((channel, samples)) = options.lag {
        record.realign(channel, samples)?;
    }
    if let Some(c) = options.dashpot {
        record.take_dashpot(c)?;
    }
    Ok(record)
}
