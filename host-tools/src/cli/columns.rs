//! The read options of the command line: which column of a CSV record is the
//! displacement, the force or the time, in which unit, and what to skip.
//! Every verb that reads a record takes them, so a file whose header the
//! readers cannot interpret alone (no units, two force-like columns, ...) is
//! read the same way by `fit`, `diagnose`, `discover`, `sensitivity` and
//! `simulate`.

use crate::data::{Baseline, Channel, ColumnRef, ReadOptions, Role, Unit};
use crate::model::ParamFile;
use anyhow::{anyhow, bail, Result};
use clap::Args;
use serde_json::{json, Value};

/// A column named on the command line, with an optional unit:
/// `D`, `D:cm`, `2`, `2:mm`.
#[derive(Clone, Debug, PartialEq)]
pub struct ColumnArg {
    /// The column, by header text or 1-based number.
    pub column: ColumnRef,
    /// The unit its values are in, replacing the file's.
    pub unit: Option<Unit>,
}

/// Parses `COLUMN[:UNIT]`: the text after the last `:` is the unit, which must
/// be one the readers know; a column given as a number counts from 1.
pub fn parse_column(text: &str) -> Result<ColumnArg> {
    let (name, unit) = match text.rsplit_once(':') {
        Some((name, unit)) => {
            let parsed = Unit::parse(unit).ok_or_else(|| {
                let known: Vec<_> = Unit::ALL.iter().map(|u| u.symbol()).collect();
                anyhow!(
                    "`{text}`: expected COLUMN or COLUMN:UNIT, and `{unit}` is not a unit the \
                     readers know ({})",
                    known.join(", ")
                )
            })?;
            (name, Some(parsed))
        }
        None => (text, None),
    };
    let name = name.trim();
    if name.is_empty() {
        bail!("`{text}`: expected a column name or number before the unit");
    }
    let column = match name.parse::<usize>() {
        Ok(0) => bail!("`{text}`: column numbers count from 1"),
        Ok(k) => ColumnRef::Number(k),
        Err(_) => ColumnRef::Name(name.to_string()),
    };
    Ok(ColumnArg { column, unit })
}

fn parse_column_ref(text: &str) -> Result<ColumnRef> {
    let c = parse_column(text)?;
    if c.unit.is_some() {
        bail!("`{text}`: a column that is not read takes no unit");
    }
    Ok(c.column)
}

/// Parses `displacement` or `force` for `--negate` (`twist` and `torque`,
/// their names in a torsion record, are the same channels).
pub fn parse_channel(text: &str) -> Result<Channel> {
    match text.trim() {
        "displacement" | "twist" => Ok(Channel::Displacement),
        "force" | "torque" => Ok(Channel::Force),
        other => bail!("expected displacement or force (twist or torque), found `{other}`"),
    }
}

/// Parses `CHANNEL=VALUE` or `CHANNEL=FIRST..LAST` for `--subtract`:
/// `displacement=0.5`, `force=-0.7`, `force=0.01..0.37` (a line in the sample
/// number from the first sample to the last).
pub fn parse_subtract(text: &str) -> Result<(Channel, Baseline)> {
    let (name, value) = text.split_once('=').ok_or_else(|| {
        anyhow!("`{text}`: expected CHANNEL=VALUE or CHANNEL=FIRST..LAST, e.g. force=0.7")
    })?;
    let channel = parse_channel(name).map_err(|e| anyhow!("`{text}`: {e} before `=`"))?;
    let value: Baseline = value.parse().map_err(|e| anyhow!("`{text}`: {e}"))?;
    Ok((channel, value))
}

/// A zero as a fit file records it: a constant as a number, a line as
/// `[first, last]`.
fn recorded(b: Baseline) -> Value {
    if b.is_constant() {
        json!(b.first)
    } else {
        json!([b.first, b.last])
    }
}

/// The zero a fit file records ([`recorded`]), if it is one.
fn recorded_baseline(value: &Value) -> Option<Baseline> {
    match value {
        Value::Array(ends) => match ends.as_slice() {
            [first, last] => Some(Baseline::line(first.as_f64()?, last.as_f64()?)),
            _ => None,
        },
        v => v.as_f64().map(Baseline::from),
    }
}

/// Parses `C` for `--dashpot`: a positive, finite viscous coefficient (a
/// negative one would feed energy in), refused here rather than as a fault of
/// the record read.
pub fn parse_dashpot(text: &str) -> Result<f64> {
    let c: f64 = text
        .trim()
        .parse()
        .map_err(|_| anyhow!("`{text}` is not a number"))?;
    if !(c.is_finite() && c > 0.0) {
        bail!(
            "expected a positive viscous coefficient for the dashpot (force per displacement/s; \
             a negative one would feed energy in), found {c}"
        );
    }
    Ok(c)
}

/// Parses `CHANNEL=SAMPLES` for `--lag`: `force=1` (the force reads one
/// sample late), `displacement=-2`.
pub fn parse_lag(text: &str) -> Result<(Channel, i64)> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| anyhow!("`{text}`: expected force=SAMPLES or displacement=SAMPLES"))?;
    let channel = parse_channel(name).map_err(|e| anyhow!("`{text}`: {e} before `=`"))?;
    let samples: i64 = value.trim().parse().map_err(|_| {
        anyhow!("`{text}`: `{value}` is not a whole number of samples (negative: early)")
    })?;
    Ok((channel, samples))
}

/// The samples the force reads late against the displacement for `--lag
/// CHANNEL=SAMPLES` (`displacement=1` is `force=-1`), as a fit file records
/// it.
pub fn force_lag((channel, samples): (Channel, i64)) -> i64 {
    match channel {
        Channel::Force => samples,
        Channel::Displacement => samples.saturating_neg(),
    }
}

/// How to read the record (CSV; a JSON layout fixes its columns).
#[derive(Clone, Debug, Default, Args)]
pub struct ReadArgs {
    /// Sample rate in Hz: sample k is at k / rate (for records without a
    /// time column, or to replace a jittery one).
    #[arg(long, allow_negative_numbers = true)]
    pub sample_rate: Option<f64>,
    /// Read this column as the displacement (header text or 1-based number),
    /// optionally in a unit that replaces the file's: `--displacement D:cm`.
    #[arg(long, value_name = "COLUMN[:UNIT]", value_parser = parse_column)]
    pub displacement: Option<ColumnArg>,
    /// Read this column as the force: `--force F:N`.
    #[arg(long, value_name = "COLUMN[:UNIT]", value_parser = parse_column)]
    pub force: Option<ColumnArg>,
    /// Read this column as the time: `--time t:s` (not with `--sample-rate`,
    /// which replaces the time column: two answers to one question).
    #[arg(long, value_name = "COLUMN[:UNIT]", value_parser = parse_column, conflicts_with = "sample_rate")]
    pub time: Option<ColumnArg>,
    /// Do not read this column (one the header suggests wrongly); repeatable.
    #[arg(long, value_name = "COLUMN", value_parser = parse_column_ref)]
    pub ignore: Vec<ColumnRef>,
    /// Skip this many leading data rows (each is reported).
    #[arg(long, default_value_t = 0)]
    pub skip_rows: usize,
    /// Read at most this many data rows after the skipped ones and not the
    /// rest of the file (a tail of other data or of text; how many rows were
    /// left is reported).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_rows: Option<u64>,
    /// Drive the model with the displacement (or twist) as measured, even where
    /// its noise makes most of its reversals (by default such a record is made
    /// monotone between the test's reversals, with a note).
    #[arg(long)]
    pub raw_displacement: bool,
    /// Take a constant off every sample of a channel, in mm or kN (deg or
    /// kN m for a torsion record, whose channels may be called `twist` and
    /// `torque`): a known zero offset of an instrument, as `hyst diagnose`
    /// names one, e.g. `--subtract force=0.73`; or a line in the sample
    /// number from FIRST at the first sample to LAST at the last, a zero that
    /// drifts, e.g. `--subtract force=0.01..0.37`. Given twice for a channel,
    /// both are taken off (they add up).
    #[arg(long, value_name = "CHANNEL=VALUE", value_parser = parse_subtract)]
    pub subtract: Vec<(Channel, Baseline)>,
    /// Flip the sign of a channel (`displacement` or `force`), before any
    /// `--subtract`: a transducer mounted the other way round, as the fitting
    /// verbs suspect when a record gives out energy. Once per channel.
    #[arg(long, value_name = "CHANNEL", value_parser = parse_channel)]
    pub negate: Vec<Channel>,
    /// A channel that reads this many samples late against the other
    /// (negative: early), realigned: each of its samples is paired with the
    /// other's that many before and the unpaired samples at the ends are
    /// dropped. Two acquisition systems out of step, as `hyst diagnose` names
    /// them, e.g. `--lag force=1`.
    #[arg(long, value_name = "CHANNEL=SAMPLES", value_parser = parse_lag)]
    pub lag: Option<(Channel, i64)>,
    /// Take a dashpot's force off the force: C times the speed of the
    /// displacement (central differences over two samples each side), C in
    /// kN s/mm (kN m s/deg for a torsion record). A viscous force beside the
    /// member, which no model here has, as `hyst diagnose` names one
    /// (`rate dependence`, with its C), e.g. `--dashpot 4.7653e-1`: run
    /// again with it to see which effects the record needs beside it. Needs
    /// the record's sample times (a time column or `--sample-rate`); applied
    /// after `--negate`, `--subtract` and `--lag`.
    #[arg(long, value_name = "C", allow_negative_numbers = true, value_parser = parse_dashpot)]
    pub dashpot: Option<f64>,
}

impl ReadArgs {
    /// The read options the fit in `file` recorded (`fit.subtract`,
    /// `fit.negate`, `fit.lag`, `fit.dashpot`) that these arguments do not repeat, as notes: a verb that
    /// compares a fit with its record would otherwise compare it with a record
    /// read differently, without a word (found by review: a fit of NRMSE
    /// 1.5e-10 read back at 0.113 with a force offset named).
    pub fn unrepeated(&self, file: &ParamFile) -> Vec<String> {
        let Some(fit) = &file.fit else {
            return vec![];
        };
        let mut missing = vec![];
        if let Some(Value::Array(names)) = fit.get("negate") {
            for name in names.iter().filter_map(Value::as_str) {
                if !self.negate.iter().any(|c| c.name() == name) {
                    missing.push(format!("--negate {name}"));
                }
            }
        }
        let mut notes = vec![];
        match fit.get("subtract") {
            Some(Value::Object(given)) => {
                for (name, value) in given {
                    let Some(value) = recorded_baseline(value) else {
                        notes.push(format!(
                            "{}: `fit.subtract.{name}` is {value}, not a number or a pair of \
                             numbers: not compared with this command's --subtract",
                            file.path.display()
                        ));
                        continue;
                    };
                    let here = self.subtracted().find(|(c, _)| c.name() == name);
                    match here {
                        // Two offsets added up may differ from one in the last place.
                        Some((_, v)) if v.agrees_with(value) => {}
                        // Another value is given: said as such, not as none (found
                        // by review).
                        Some((_, v)) => notes.push(format!(
                            "the fit in {} was made on a record read with `--subtract {name}={value}`; \
                             this command gives `--subtract {name}={v}` instead",
                            file.path.display()
                        )),
                        None => missing.push(format!("--subtract {name}={value}")),
                    }
                }
            }
            Some(other) => notes.push(format!(
                "{}: `fit.subtract` is {other}, not an object of offsets: not compared with this \
                 command's --subtract",
                file.path.display()
            )),
            None => {}
        }
        match fit.get("lag") {
            Some(Value::Object(given)) if given.len() == 1 => {
                for (name, value) in given {
                    // `1.0` is whole too.
                    let whole = value
                        .as_f64()
                        .filter(|v| v.fract() == 0.0 && v.abs() < 9e15);
                    let Some(value) = value.as_i64().or(whole.map(|v| v as i64)) else {
                        notes.push(format!(
                            "{}: `fit.lag.{name}` is {value}, not a whole number: not compared \
                             with this command's --lag",
                            file.path.display()
                        ));
                        continue;
                    };
                    let Ok(channel) = parse_channel(name) else {
                        notes.push(format!(
                            "{}: `fit.lag.{name}` names no channel: not compared with this \
                             command's --lag",
                            file.path.display()
                        ));
                        continue;
                    };
                    let here = self.lag.map(force_lag).unwrap_or(0);
                    let there = force_lag((channel, value));
                    match self.lag {
                        _ if here == there => {}
                        Some((c, v)) => notes.push(format!(
                            "the fit in {} was made on a record read with `--lag {name}={value}`; \
                             this command gives `--lag {}={v}` instead",
                            file.path.display(),
                            c.name()
                        )),
                        None => missing.push(format!("--lag {name}={value}")),
                    }
                }
            }
            Some(other) => notes.push(format!(
                "{}: `fit.lag` is {other}, not an object of one channel's lag: not compared with \
                 this command's --lag",
                file.path.display()
            )),
            None => {}
        }
        match (fit.get("dashpot"), self.dashpot) {
            (None, _) => {}
            (Some(there), here) => match (there.as_f64(), here) {
                (None, _) => notes.push(format!(
                    "{}: `fit.dashpot` is {there}, not a number: not compared with this \
                     command's --dashpot",
                    file.path.display()
                )),
                (Some(c), Some(h)) if c == h => {}
                (Some(c), Some(h)) => notes.push(format!(
                    "the fit in {} was made on a record read with `--dashpot {c}`; this command \
                     gives `--dashpot {h}` instead",
                    file.path.display()
                )),
                (Some(c), None) => missing.push(format!("--dashpot {c}")),
            },
        }
        notes.extend(missing.into_iter().map(|option| {
            format!(
                "the fit in {} was made on a record read with `{option}`, which is not given here: \
                 the record is read without it; give it again to compare the fit with what it was fitted to",
                file.path.display()
            )
        }));
        // And the other way round: an option given here that the fit was made
        // without (found by review: only the missing ones were said).
        let in_file = |key: &str, name: &str| match fit.get(key) {
            Some(Value::Object(m)) => m.contains_key(name),
            Some(Value::Array(a)) => a.iter().any(|v| v.as_str() == Some(name)),
            _ => false,
        };
        let mut extra: Vec<String> = self
            .negate
            .iter()
            .filter(|c| !in_file("negate", &c.to_string()))
            .map(|c| format!("--negate {c}"))
            .collect();
        extra.extend(
            self.subtracted()
                .filter(|(c, _)| !in_file("subtract", &c.to_string()))
                .map(|(c, v)| format!("--subtract {c}={v}")),
        );
        if let Some((c, v)) = self.lag.filter(|l| force_lag(*l) != 0) {
            if fit.get("lag").is_none() {
                extra.push(format!("--lag {}={v}", c.name()));
            }
        }
        if let Some(c) = self.dashpot.filter(|_| fit.get("dashpot").is_none()) {
            extra.push(format!("--dashpot {c}"));
        }
        notes.extend(extra.into_iter().map(|option| {
            format!(
                "the fit in {} was made on a record read without `{option}`, which this command \
                 gives: the record is read with it, unlike the one the fit was fitted to",
                file.path.display()
            )
        }));
        notes
    }

    /// What `--subtract` takes off each channel named: what is given for it,
    /// added up.
    fn subtracted(&self) -> impl Iterator<Item = (Channel, Baseline)> + '_ {
        [Channel::Displacement, Channel::Force]
            .into_iter()
            .filter_map(|channel| {
                self.subtract
                    .iter()
                    .filter(|(c, _)| *c == channel)
                    .map(|(_, v)| *v)
                    .reduce(|a, b| a + b)
                    // Lines that cancel take nothing off (found by review: recorded as 0).
                    .filter(|v| *v != Baseline::from(0.0))
                    .map(|v| (channel, v))
            })
    }

    /// Writes what was done to the record as it was read into a fit file's
    /// `fit` object, so that a later `simulate` or `diagnose --params` of the
    /// file can be given the same (found by review): `negate`, the channels
    /// flipped; `subtract`, for each channel what is taken off it, a constant
    /// as a number, a line as `[first, last]`; `lag`, the force's lag,
    /// whichever channel was named; `dashpot`, its coefficient.
    pub fn record_into(&self, fit: &mut Value) {
        if !self.negate.is_empty() {
            let names: Vec<String> = self.negate.iter().map(|c| c.to_string()).collect();
            fit["negate"] = json!(names);
        }
        let subtract: serde_json::Map<String, Value> = self
            .subtracted()
            .map(|(c, v)| (c.to_string(), recorded(v)))
            .collect();
        if !subtract.is_empty() {
            fit["subtract"] = Value::Object(subtract);
        }
        if let Some(samples) = self.lag.map(force_lag).filter(|s| *s != 0) {
            fit["lag"] = json!({ "force": samples });
        }
        if let Some(c) = self.dashpot {
            fit["dashpot"] = json!(c);
        }
    }

    /// The read options these arguments ask for.
    pub fn options(&self) -> ReadOptions {
        let mut opts = ReadOptions::default().skip_rows(self.skip_rows);
        if let Some(rows) = self.max_rows {
            opts = opts.max_rows(usize::try_from(rows).unwrap_or(usize::MAX));
        }
        if let Some(hz) = self.sample_rate {
            opts = opts.sample_rate(hz);
        }
        for (arg, role) in [
            (&self.displacement, Role::Displacement),
            (&self.force, Role::Force),
            (&self.time, Role::Time),
        ] {
            if let Some(c) = arg {
                opts = opts.role(c.column.clone(), role);
                if let Some(unit) = c.unit {
                    opts = opts.unit(c.column.clone(), unit);
                }
            }
        }
        for c in &self.ignore {
            opts = opts.role(c.clone(), Role::Ignore);
        }
        for &channel in &self.negate {
            opts = opts.negate(channel);
        }
        for &(channel, value) in &self.subtract {
            opts = opts.subtract(channel, value);
        }
        if let Some((channel, samples)) = self.lag {
            opts = opts.lag(channel, samples);
        }
        if let Some(c) = self.dashpot {
            opts = opts.dashpot(c);
        }
        opts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_parse_by_name_number_and_unit() {
        assert_eq!(
            parse_column("D:cm").unwrap(),
            ColumnArg {
                column: ColumnRef::Name("D".into()),
                unit: Some(Unit::Centimetre)
            }
        );
        assert_eq!(
            parse_column("2").unwrap(),
            ColumnArg {
                column: ColumnRef::Number(2),
                unit: None
            }
        );
        assert_eq!(
            parse_column("Lead Actuator Force :kN").unwrap().column,
            ColumnRef::Name("Lead Actuator Force".into())
        );
    }

    #[test]
    fn bad_columns_say_what_was_expected() {
        let e = parse_column("F:newtonz").unwrap_err().to_string();
        assert!(e.contains("`newtonz` is not a unit"), "{e}");
        let e = parse_column("0").unwrap_err().to_string();
        assert!(e.contains("count from 1"), "{e}");
        let e = parse_column(":mm").unwrap_err().to_string();
        assert!(e.contains("expected a column name"), "{e}");
        let e = parse_column_ref("V:cm").unwrap_err().to_string();
        assert!(e.contains("takes no unit"), "{e}");
    }

    #[test]
    fn options_carry_roles_units_and_skips() {
        let args = ReadArgs {
            sample_rate: Some(3004.8),
            displacement: Some(parse_column("D:cm").unwrap()),
            force: Some(parse_column("F:N").unwrap()),
            ignore: vec![ColumnRef::Name("V".into())],
            skip_rows: 1,
            ..ReadArgs::default()
        };
        let o = args.options();
        assert_eq!(o.sample_rate_hz, Some(3004.8));
        assert_eq!(o.skip_rows, 1);
        assert_eq!(
            o.roles,
            vec![
                (ColumnRef::Name("D".into()), Role::Displacement),
                (ColumnRef::Name("F".into()), Role::Force),
                (ColumnRef::Name("V".into()), Role::Ignore),
            ]
        );
        assert_eq!(
            o.units,
            vec![
                (ColumnRef::Name("D".into()), Unit::Centimetre),
                (ColumnRef::Name("F".into()), Unit::Newton),
            ]
        );
    }
}
