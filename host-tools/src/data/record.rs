//! A lab record: a displacement and a force signal in canonical units (mm, kN),
//! an optional time base (s), which signal drives the test, and what the reader
//! noticed on the way.

use super::baseline::Baseline;
use super::branches::{SegmentOptions, Segmentation};
use super::columns::Role;
use super::cycles::{CycleError, Cycles, Threshold};
use super::error::DataError;
use super::units::{Quantity, Unit};
use std::fmt;
use std::path::{Path, PathBuf};

/// The two signals of a hysteresis record.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Channel {
    /// Displacement (deformation, drift, strain), canonical unit mm; in a
    /// torsion record the twist, canonical unit deg.
    Displacement,
    /// Force (load, shear, stress), canonical unit kN; in a torsion record
    /// the torque, canonical unit kN m.
    Force,
}

impl Channel {
    /// The quantity of the channel's unit in a torsion record: angle (a
    /// twist) or torque.
    pub fn torsion_quantity(self) -> Quantity {
        match self {
            Channel::Displacement => Quantity::Angle,
            Channel::Force => Quantity::Torque,
        }
    }

    /// The quantity of the channel's unit.
    pub fn quantity(self) -> Quantity {
        match self {
            Channel::Displacement => Quantity::Length,
            Channel::Force => Quantity::Force,
        }
    }

    /// The other channel.
    pub fn other(self) -> Channel {
        match self {
            Channel::Displacement => Channel::Force,
            Channel::Force => Channel::Displacement,
        }
    }
}

/// How many times a channel's largest value an offset to subtract may be.
const SWAMPING: f64 = 1e6;

/// A constant or line in few characters, as `--subtract` reads it.
fn short_baseline(b: Baseline) -> String {
    if b.is_constant() {
        short(b.first)
    } else {
        format!("{}..{}", short(b.first), short(b.last))
    }
}

/// `v` in few characters: plain between 1e-4 and 1e6, else with an exponent
/// (an offset of 1e15 printed sixteen digits: found by review).
fn short(v: f64) -> String {
    if v == 0.0 || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

impl Channel {
    /// Its name: `displacement` or `force`.
    pub fn name(self) -> &'static str {
        match self {
            Channel::Displacement => "displacement",
            Channel::Force => "force",
        }
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One signal of a record: its values in the canonical unit, and the column
/// name and unit it was read from.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The column name as written in the file (or a description, for series
    /// that did not come from a column).
    pub name: String,
    /// The unit of the file; `values` are already converted from it.
    pub unit: Unit,
    /// The values in the canonical unit of `unit`'s quantity (mm, kN or s).
    pub values: Vec<f64>,
}

impl Series {
    /// A series already in the canonical unit of `quantity`.
    pub fn canonical(name: impl Into<String>, quantity: Quantity, values: Vec<f64>) -> Self {
        Series {
            name: name.into(),
            unit: quantity.canonical(),
            values,
        }
    }
}

/// Something the reader did that the caller should know about: nothing is
/// dropped or assumed silently.
#[derive(Clone, Debug, PartialEq)]
pub enum Notice {
    /// A column had no unit; the canonical unit of its role was assumed.
    AssumedUnit {
        /// The column.
        column: String,
        /// The unit assumed.
        unit: Unit,
    },
    /// A column whose name says nothing of its role was given the role of
    /// its unit's quantity.
    RoleByUnit {
        /// The column.
        column: String,
        /// The role it was given.
        role: Role,
        /// Its unit.
        unit: Unit,
    },
    /// A unit given by the read options replaced the unit the file states.
    OverriddenUnit {
        /// The column.
        column: String,
        /// The unit in the file.
        file_unit: String,
        /// The unit used.
        unit: Unit,
    },
    /// Units were not stated in the file; the format's documented convention
    /// was used.
    UnitsByConvention {
        /// The convention and where it is documented.
        what: String,
    },
    /// Columns present in the file that the record does not hold.
    IgnoredColumns {
        /// Their names (with a reason when one is useful).
        columns: Vec<String>,
    },
    /// Data rows past the most the caller asked to read, not read.
    RowsNotRead {
        /// Where they begin: `line 1204` (CSV) or `sample 1200` (JSON).
        from: String,
        /// How many there were.
        rows: usize,
    },
    /// A data row the caller asked to skip, with its text.
    SkippedRow {
        /// Where: `line 4` (CSV) or `sample 0` (JSON).
        at: String,
        /// The row as written.
        text: String,
    },
    /// The fields of a CSV file are separated by a tab or a semicolon, not a
    /// comma (read from its header line).
    Separator {
        /// The separator.
        separator: char,
        /// Values written with a decimal comma, read as numbers.
        decimal_commas: usize,
    },
    /// Comment lines between data rows (CSV), skipped.
    CommentsAmongRows {
        /// Their line numbers.
        lines: Vec<usize>,
    },
    /// A step or index column was checked to increase and used only as the row
    /// order.
    StepColumn {
        /// The column.
        column: String,
    },
    /// A constant, or a line in the sample number, was taken off every
    /// sample of a column (read options).
    Subtracted {
        /// The column.
        column: String,
        /// The constant or line, in `unit`.
        value: Baseline,
        /// The canonical unit the constant is in.
        unit: Unit,
    },
    /// The sign of every sample of a column was flipped (read options).
    Negated {
        /// The column.
        column: String,
    },
    /// A channel read out of step with the other was realigned (read
    /// options): the samples that lost their partner were dropped.
    Realigned {
        /// The column that read late.
        late: String,
        /// The other column.
        other: String,
        /// How many samples late.
        samples: usize,
    },
    /// A dashpot's force, a coefficient times the speed of the displacement,
    /// was taken off every sample of the force (read options).
    Dashpot {
        /// The force's column.
        column: String,
        /// The displacement's column.
        displacement: String,
        /// The coefficient, in `unit`.
        coefficient: f64,
        /// Its unit: the force's canonical unit per (displacement's per s).
        unit: String,
    },
    /// The time base was built from a sample rate: sample `k` is at `k / rate`.
    TimeFromSampleRate {
        /// The rate in Hz.
        hz: f64,
        /// A time column of the file that this replaced, if any.
        replaced: Option<String>,
    },
}

impl fmt::Display for Notice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Notice::AssumedUnit { column, unit } => {
                write!(f, "column '{column}' states no unit: assumed {unit}")
            }
            Notice::OverriddenUnit {
                column,
                file_unit,
                unit,
            } => write!(
                f,
                "column '{column}': unit '{file_unit}' of the file replaced by {unit} (read options)"
            ),
            Notice::UnitsByConvention { what } => write!(f, "units not stated in the file: {what}"),
            Notice::RoleByUnit { column, role, unit } => write!(
                f,
                "column '{column}' is not named like a {role}: read as the {role} by its unit \
                 ({unit}); name the column's role with --{role} if that is wrong"
            ),
            Notice::IgnoredColumns { columns } => {
                write!(f, "columns not read: {}", columns.join(", "))
            }
            Notice::RowsNotRead { from, rows } => {
                let s = if *rows == 1 { "" } else { "s" };
                write!(
                    f,
                    "{rows} row{s} from {from} on not read, as asked (read options)"
                )
            }
            Notice::SkippedRow { at, text } => {
                write!(f, "row at {at} skipped as asked: '{text}'")
            }
            Notice::Separator {
                separator,
                decimal_commas,
            } => {
                let name = if *separator == '\t' { "tabs" } else { "semicolons" };
                write!(f, "fields separated by {name}, as the header is")?;
                if *decimal_commas > 0 {
                    write!(
                        f,
                        "; {decimal_commas} values written with a decimal comma (1,5 = 1.5)"
                    )?;
                }
                Ok(())
            }
            Notice::CommentsAmongRows { lines } => {
                let shown: Vec<String> = lines.iter().take(5).map(|l| l.to_string()).collect();
                let more = if lines.len() > 5 {
                    format!(" and {} more", lines.len() - 5)
                } else {
                    String::new()
                };
                write!(
                    f,
                    "comment lines among the data rows skipped (line {}{more})",
                    shown.join(", ")
                )
            }
            Notice::StepColumn { column } => write!(
                f,
                "column '{column}' checked to increase and used only as the row order"
            ),
            Notice::Subtracted {
                column,
                value,
                unit,
            } if value.is_constant() => write!(
                f,
                "column '{column}': {} {unit} subtracted from every sample (read options)",
                short(value.first)
            ),
            Notice::Subtracted {
                column,
                value,
                unit,
            } => write!(
                f,
                "column '{column}': a line from {} {unit} at the first sample to {} {unit} at \
                 the last subtracted from its samples (read options)",
                short(value.first),
                short(value.last)
            ),
            Notice::Negated { column } => write!(
                f,
                "column '{column}': the sign of every sample flipped (read options)"
            ),
            Notice::Realigned {
                late,
                other,
                samples,
            } => {
                let s = if *samples == 1 { "" } else { "s" };
                write!(
                    f,
                    "column '{late}' read {samples} sample{s} late: each of its samples paired \
                     with the one of '{other}' {samples} before, and the time of that one; its \
                     first {samples} sample{s} and the last {samples} of '{other}' dropped (read \
                     options)"
                )
            }
            Notice::Dashpot {
                column,
                displacement,
                coefficient,
                unit,
            } => write!(
                f,
                "column '{column}': a dashpot's force, {} {unit} times the speed of \
                 '{displacement}' (central differences over {} samples each side), taken off \
                 every sample (read options)",
                short(*coefficient),
                super::speed::HALF_WIDTH
            ),
            Notice::TimeFromSampleRate { hz, replaced } => {
                write!(f, "time built from the sample rate {hz} Hz (t = k / {hz})")?;
                if let Some(c) = replaced {
                    write!(f, ", replacing the time column '{c}'")?;
                }
                Ok(())
            }
        }
    }
}

/// A lab record: displacement and force in mm and kN, an optional time base in
/// s, which of the two signals drives the test (the input), the comment lines
/// of the file and the notices of the reader.
///
/// A record always holds its input signal; the output may be missing (a
/// displacement history to simulate has no force yet). All signals have the
/// same length, and every value is finite.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    source: PathBuf,
    time: Option<Series>,
    displacement: Option<Series>,
    force: Option<Series>,
    input: Channel,
    comments: Vec<String>,
    notices: Vec<Notice>,
}

impl Record {
    /// Builds a record, checking that the input signal is present, that every
    /// series has the same length, that values are finite, and that time
    /// increases. Values must already be in canonical units.
    pub fn new(
        source: impl Into<PathBuf>,
        input: Channel,
        displacement: Option<Series>,
        force: Option<Series>,
        time: Option<Series>,
    ) -> Result<Record, DataError> {
        let source = source.into();
        let record = Record {
            source,
            time,
            displacement,
            force,
            input,
            comments: Vec::new(),
            notices: Vec::new(),
        };
        record.check()?;
        Ok(record)
    }

    /// A displacement history (mm) with no force, e.g. to simulate; with
    /// `dt` (s) sample `k` is at `k * dt`.
    ///
    /// ```
    /// use hyst::data::Record;
    /// let r = Record::from_history("ramp", vec![0.0, 0.5, 1.0], Some(0.1)).unwrap();
    /// assert_eq!(r.input(), &[0.0, 0.5, 1.0]);
    /// assert_eq!(r.time().unwrap()[2], 0.2);
    /// assert!(r.force().is_none());
    /// ```
    pub fn from_history(
        name: impl Into<PathBuf>,
        displacement_mm: Vec<f64>,
        dt: Option<f64>,
    ) -> Result<Record, DataError> {
        let name = name.into();
        let time = match dt {
            Some(dt) if dt.is_finite() && dt > 0.0 => Some(Series::canonical(
                format!("dt = {dt} s"),
                Quantity::Time,
                (0..displacement_mm.len()).map(|k| k as f64 * dt).collect(),
            )),
            Some(dt) => {
                return Err(DataError::file(
                    &name,
                    format!("expected a positive finite time step, found {dt} s"),
                ))
            }
            None => None,
        };
        let d = Series::canonical("displacement", Quantity::Length, displacement_mm);
        Record::new(name, Channel::Displacement, Some(d), None, time)
    }

    fn check(&self) -> Result<(), DataError> {
        let file = &self.source;
        let Some(input) = self.series(self.input) else {
            return Err(DataError::file(
                file,
                format!("expected a {} signal: it is the record's input", self.input),
            ));
        };
        let n = input.values.len();
        let all = [&self.time, &self.displacement, &self.force];
        for s in all.into_iter().flatten() {
            if s.values.len() != n {
                return Err(DataError::file(
                    file,
                    format!(
                        "expected every signal to have {n} samples like '{}', found {} in '{}'",
                        input.name,
                        s.values.len(),
                        s.name
                    ),
                ));
            }
            if let Some(k) = s.values.iter().position(|v| !v.is_finite()) {
                return Err(DataError::file(
                    file,
                    format!(
                        "expected finite values, found {} at sample {k} of '{}'",
                        s.values[k], s.name
                    ),
                ));
            }
        }
        if let Some(t) = &self.time {
            if let Some(k) = t.values.windows(2).position(|w| w[1] <= w[0]) {
                return Err(DataError::file(
                    file,
                    format!(
                        "expected time to increase, found {} s after {} s at sample {}",
                        t.values[k + 1],
                        t.values[k],
                        k + 1
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The record with these comment lines (written as `#` lines by
    /// [`write_record`](super::write_record)).
    pub fn with_comments(mut self, comments: Vec<String>) -> Self {
        self.comments = comments;
        self
    }

    pub(crate) fn with_notices(mut self, notices: Vec<Notice>) -> Self {
        self.notices = notices;
        self
    }

    /// The file the record was read from (or the name it was given).
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.input().len()
    }

    /// Whether the record has no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Time in s, if the file had a time base or a sample rate was given.
    pub fn time(&self) -> Option<&[f64]> {
        self.time.as_ref().map(|s| s.values.as_slice())
    }

    /// Displacement in mm.
    pub fn displacement(&self) -> Option<&[f64]> {
        self.displacement.as_ref().map(|s| s.values.as_slice())
    }

    /// Force in kN.
    pub fn force(&self) -> Option<&[f64]> {
        self.force.as_ref().map(|s| s.values.as_slice())
    }

    /// The series of a channel, with its column name and original unit.
    pub fn series(&self, channel: Channel) -> Option<&Series> {
        match channel {
            Channel::Displacement => self.displacement.as_ref(),
            Channel::Force => self.force.as_ref(),
        }
    }

    /// The quantity of a channel as read: length or angle (a twist) for the
    /// displacement, force or torque for the force; `None` if it is missing.
    pub fn quantity(&self, channel: Channel) -> Option<Quantity> {
        self.series(channel).map(|s| s.unit.quantity())
    }

    /// Whether either channel is a twist or a torque (a torsion record, for
    /// the PHM of thesis ch. 5, not for the BWBN models).
    pub fn is_torsion(&self) -> bool {
        [Channel::Displacement, Channel::Force]
            .into_iter()
            .any(|c| self.quantity(c) == Some(c.torsion_quantity()))
    }

    /// The two channels in words, for a message about a torsion record:
    /// `column 'force (kNm)' is a torque (kN m), column 'displacement (mm)' a length (mm)`.
    /// A torque unit beside a length is most often a misspelt force unit.
    pub fn channels_in_words(&self) -> String {
        let words: Vec<String> = [Channel::Displacement, Channel::Force]
            .into_iter()
            .filter_map(|c| {
                let s = self.series(c)?;
                let q = s.unit.quantity();
                let a = if q == Quantity::Angle { "an" } else { "a" };
                Some(format!("column '{}' is {a} {q} ({})", s.name, s.unit))
            })
            .collect();
        words.join(", ")
    }

    /// The time series with its column name and original unit.
    pub fn time_series(&self) -> Option<&Series> {
        self.time.as_ref()
    }

    /// Which channel drives the test: displacement for displacement-controlled
    /// quasi-static tests, force for force-driven records such as the Bouc-Wen
    /// benchmark.
    pub fn input_channel(&self) -> Channel {
        self.input
    }

    /// The input signal (always present).
    pub fn input(&self) -> &[f64] {
        match self.series(self.input) {
            Some(s) => &s.values,
            None => &[],
        }
    }

    /// The output signal, if the record has one.
    pub fn output(&self) -> Option<&[f64]> {
        self.series(self.input.other()).map(|s| s.values.as_slice())
    }

    /// Takes `value` (in the channel's canonical unit: mm or kN, deg or kN m
    /// for a torsion record) off every sample of `channel`: a known zero
    /// offset of an instrument, a constant, or a zero that drifts along a
    /// straight line in the sample number ([`Baseline`]). Said in a notice; an
    /// error if the record has no such channel, `value` is not finite or
    /// swamps the channel's values.
    ///
    /// ```
    /// use hyst::data::{Baseline, Channel, Record};
    /// let mut r = Record::from_history("ramp", vec![0.5, 1.0, 1.5], None).unwrap();
    /// r.subtract(Channel::Displacement, 0.5).unwrap();
    /// assert_eq!(r.input(), &[0.0, 0.5, 1.0]);
    /// r.subtract(Channel::Displacement, Baseline::line(0.0, 0.5)).unwrap();
    /// assert_eq!(r.input(), &[0.0, 0.25, 0.5]);
    /// assert!(r.subtract(Channel::Force, 1.0).is_err());
    /// ```
    pub fn subtract(
        &mut self,
        channel: Channel,
        value: impl Into<Baseline>,
    ) -> Result<(), DataError> {
        let value = value.into();
        let source = self.source.clone();
        let series =
            self.series_to_change(channel, &format!("subtract {} from", short_baseline(value)))?;
        if !(value.first.is_finite() && value.last.is_finite()) {
            return Err(DataError::file(
                &self.source,
                format!("expected a finite offset to subtract from the {channel}, found {value}"),
            ));
        }
        // An instrument's zero offset is of the size of the record's values;
        // one a million times larger leaves them a few digits (found by
        // review: 1e16 kN accepted, the fit then at NRMSE 1).
        let largest = series.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if value.largest() > SWAMPING * largest {
            let unit = series.unit.quantity().canonical();
            return Err(DataError::file(
                &source,
                format!(
                    "an offset of {} {unit} to subtract from column '{}' is more than {} times its \
                     largest value ({} {unit}): expected an offset of the size of the record's values",
                    short(value.largest()),
                    series.name,
                    short(SWAMPING),
                    short(largest)
                ),
            ));
        }
        let varied = series.values.iter().any(|v| *v != series.values[0]);
        let n = series.values.len();
        series
            .values
            .iter_mut()
            .enumerate()
            .for_each(|(k, v)| *v -= value.at(k, n));
        let unit = series.unit.quantity().canonical();
        let column = series.name.clone();
        // An offset so large that the samples round to one value would be
        // blamed on the record by the check below (found by review: 1e300).
        if varied && series.values.iter().all(|v| *v == series.values[0]) {
            let cause = if value.is_constant() {
                "the offset swamps the values"
            } else {
                "nothing is left to fit"
            };
            return Err(DataError::file(
                &self.source,
                format!(
                    "subtracting {} {unit} from column '{column}' leaves every sample the same: \
                     {cause}; expected an offset of the size of the record's",
                    short_baseline(value)
                ),
            ));
        }
        self.check()?;
        self.notices.push(Notice::Subtracted {
            column,
            value,
            unit,
        });
        Ok(())
    }

    /// Flips the sign of every sample of `channel` (a transducer mounted the
    /// other way round). Said in a notice; an error if the record has no such
    /// channel.
    ///
    /// ```
    /// use hyst::data::{Channel, Record};
    /// let mut r = Record::from_history("ramp", vec![0.5, 1.0], None).unwrap();
    /// r.negate(Channel::Displacement).unwrap();
    /// assert_eq!(r.input(), &[-0.5, -1.0]);
    /// assert!(r.negate(Channel::Force).is_err());
    /// ```
    pub fn negate(&mut self, channel: Channel) -> Result<(), DataError> {
        let series = self.series_to_change(channel, "negate")?;
        series.values.iter_mut().for_each(|v| *v = -*v);
        let column = series.name.clone();
        self.notices.push(Notice::Negated { column });
        Ok(())
    }

    /// Realigns a channel that reads `samples` samples late against the other
    /// (early where negative): each of its samples is paired with the other
    /// channel's sample (and time) that many before, and the samples left
    /// without a partner at the two ends are dropped. Two acquisition systems
    /// out of step, as `hyst diagnose` names them. Said in a notice (nothing
    /// for 0); an error if the record lacks either channel or would keep
    /// fewer than two samples.
    ///
    /// ```
    /// use hyst::data::{Channel, Quantity, Record, Series};
    /// let u = Series::canonical("u", Quantity::Length, vec![0.0, 1.0, 2.0, 3.0]);
    /// let f = Series::canonical("f", Quantity::Force, vec![9.0, 10.0, 20.0, 30.0]);
    /// let mut r = Record::new("late", Channel::Displacement, Some(u), Some(f), None).unwrap();
    /// r.realign(Channel::Force, 1).unwrap();
    /// assert_eq!(r.input(), &[0.0, 1.0, 2.0]);
    /// assert_eq!(r.force().unwrap(), &[10.0, 20.0, 30.0]);
    /// assert!(r.realign(Channel::Displacement, 2).is_err());
    /// ```
    pub fn realign(&mut self, channel: Channel, samples: i64) -> Result<(), DataError> {
        if samples == 0 {
            return Ok(());
        }
        let other = channel.other();
        // Said of the channel that reads late.
        let (late, early) = if samples > 0 {
            (channel, other)
        } else {
            (other, channel)
        };
        let k = samples.unsigned_abs();
        let n = self.len();
        let kept = usize::try_from(k)
            .ok()
            .and_then(|k| n.checked_sub(k))
            .filter(|kept| *kept >= 2);
        // Said of the channel asked for, against the other (`--lag
        // displacement=1` on a record without a force was "cannot realign the
        // force": found by review).
        let said = |c: Channel| self.channel_word(c);
        for c in [channel, other] {
            if self.series(c).is_none() {
                return Err(DataError::file(
                    &self.source,
                    format!(
                        "cannot realign the {} against the {}: the record has no {}",
                        said(channel),
                        said(other),
                        said(c)
                    ),
                ));
            }
        }
        let late_name = self.series_to_change(late, "realign")?.name.clone();
        let early_name = self.series_to_change(early, "realign")?.name.clone();
        let Some(kept) = kept else {
            return Err(DataError::file(
                &self.source,
                format!(
                    "a lag of {samples} sample{} between '{late_name}' and '{early_name}' leaves \
                     fewer than 2 of the record's {n} samples: expected a lag of at most {}",
                    if k == 1 { "" } else { "s" },
                    n.saturating_sub(2)
                ),
            ));
        };
        let drop = n - kept;
        self.series_to_change(late, "realign")?.values.drain(..drop);
        self.series_to_change(early, "realign")?
            .values
            .truncate(kept);
        if let Some(t) = &mut self.time {
            t.values.truncate(kept);
        }
        self.check()?;
        self.notices.push(Notice::Realigned {
            late: late_name,
            other: early_name,
            samples: drop,
        });
        Ok(())
    }

    /// Takes a dashpot's force `c v` off every sample of the force, `v` the
    /// speed of the displacement ([`speed::of`](super::speed::of)) and `c`
    /// in the force's canonical unit per displacement's per second (kN s/mm;
    /// kN m s/deg for a torsion record): a viscous force in parallel with
    /// the member, which no model here has, as `hyst diagnose` names one.
    /// Said in a notice; an error if `c` is not positive and finite, or the
    /// record lacks a channel or its sample times.
    ///
    /// ```
    /// use hyst::data::{Channel, Quantity, Record, Series};
    /// let t = Series::canonical("t", Quantity::Time, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
    /// let u = Series::canonical("u", Quantity::Length, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
    /// let f = Series::canonical("f", Quantity::Force, vec![5.0, 6.0, 7.0, 8.0, 9.0]);
    /// let mut r = Record::new("damped", Channel::Displacement, Some(u), Some(f), Some(t)).unwrap();
    /// r.take_dashpot(0.5).unwrap();
    /// assert_eq!(r.force().unwrap(), &[4.0, 5.0, 6.0, 7.0, 8.0]);
    /// assert!(r.take_dashpot(-0.5).is_err());
    /// ```
    pub fn take_dashpot(&mut self, c: f64) -> Result<(), DataError> {
        if !(c.is_finite() && c > 0.0) {
            return Err(DataError::file(
                &self.source,
                format!(
                    "expected a positive viscous coefficient for the dashpot (force per \
                     displacement/s; a negative one would feed energy in), found {c}"
                ),
            ));
        }
        let (Some(t), Some(u)) = (&self.time, &self.displacement) else {
            let missing = if self.time.is_none() {
                "sample times: give a time column or --sample-rate"
            } else {
                "displacement"
            };
            return Err(DataError::file(
                &self.source,
                format!("cannot take a dashpot off the force: the record has no {missing}"),
            ));
        };
        let (displacement, du) = (u.name.clone(), u.unit.quantity().canonical());
        let v = super::speed::of(&u.values, &t.values).ok_or_else(|| {
            DataError::file(
                &self.source,
                "cannot take a dashpot off the force: the record has fewer than 3 samples",
            )
        })?;
        let series = self.series_to_change(Channel::Force, "take a dashpot off")?;
        for (f, v) in series.values.iter_mut().zip(&v) {
            *f -= c * v;
        }
        let unit = format!("{} s/{du}", series.unit.quantity().canonical());
        let column = series.name.clone();
        self.check()?;
        self.notices.push(Notice::Dashpot {
            column,
            displacement,
            coefficient: c,
            unit,
        });
        Ok(())
    }

    /// The word for `channel` in a message: a torsion record's channels are
    /// the twist and the torque.
    fn channel_word(&self, channel: Channel) -> &'static str {
        match (self.is_torsion(), channel) {
            (true, Channel::Displacement) => "twist",
            (true, Channel::Force) => "torque",
            (false, c) => c.name(),
        }
    }

    /// The series of `channel`, to change in place, or an error saying the
    /// record has none: "cannot `{doing}` the {channel}".
    fn series_to_change(
        &mut self,
        channel: Channel,
        doing: &str,
    ) -> Result<&mut Series, DataError> {
        let name = self.channel_word(channel);
        let series = match channel {
            Channel::Displacement => self.displacement.as_mut(),
            Channel::Force => self.force.as_mut(),
        };
        series.ok_or_else(|| {
            DataError::file(
                &self.source,
                format!("cannot {doing} the {name}: the record has no {name}"),
            )
        })
    }

    /// The record with another input channel (which must be present).
    pub fn with_input(mut self, input: Channel) -> Result<Record, DataError> {
        self.input = input;
        self.check()?;
        Ok(self)
    }

    /// Displacement (mm) and force (kN) together, or an error naming the file
    /// if one is missing.
    pub fn displacement_force(&self) -> Result<(&[f64], &[f64]), DataError> {
        match (self.displacement(), self.force()) {
            (Some(d), Some(f)) => Ok((d, f)),
            (d, _) => {
                let missing = if d.is_none() { "displacement" } else { "force" };
                Err(DataError::file(
                    &self.source,
                    format!("expected displacement and force, found no {missing} signal"),
                ))
            }
        }
    }

    /// The `#` comment lines of the file, without the `#`.
    pub fn comments(&self) -> &[String] {
        &self.comments
    }

    /// What the reader assumed, skipped or ignored.
    pub fn notices(&self) -> &[Notice] {
        &self.notices
    }

    /// Reversals, half-cycles and cycles of the input signal.
    pub fn cycles(&self, threshold: Threshold) -> Result<Cycles, CycleError> {
        Cycles::find(self.input(), threshold)
    }

    /// Cycles of the input signal, branch classes, near-zero-force flags, peak
    /// force per half-cycle and energy per cycle; needs displacement and force.
    pub fn segment(&self, options: &SegmentOptions) -> Result<Segmentation, DataError> {
        let (d, f) = self.displacement_force()?;
        Segmentation::new(d, f, self.input(), options)
            .map_err(|e| DataError::file(&self.source, e.to_string()))
    }
}
