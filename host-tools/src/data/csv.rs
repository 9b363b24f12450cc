//! The CSV reader: `#` comment lines, one header line naming the columns
//! (with units), an optional units line, then one sample a line.
//!
//! Rules, in order:
//! 1. Lines starting with `#` (after white space) are comments, kept in the
//!    record; blank lines are skipped. A UTF-8 byte-order mark is ignored.
//!    Below the header, a `#` line with as many fields as the header is a data
//!    row (a spreadsheet's `#N/A` or `#DIV/0!`, refused as not a number at its
//!    line), and a comment there is reported ([`Notice::CommentsAmongRows`]).
//! 2. The first other line is the header. Its fields are split on `,`; see
//!    [`columns`](super::columns) for how names and units are read.
//! 3. If the next line has no number and at least one known unit, it is a
//!    units line (as in `kN,mm` under `Lead Actuator Force,Lead Actuator
//!    Displacment`): its units apply to the columns whose header has none.
//! 4. A column's role is the role given in the read options; else the role of
//!    its unit's quantity (a length unit makes a displacement, a force unit a
//!    force, a time unit a time; an angle unit a displacement, i.e. a twist, a
//!    torque unit a force, i.e. a torque), which must agree with a role name;
//!    else the role of its name. A twist or torque name (`twist`, `torque`,
//!    ...) needs an angle or torque unit, and deg or kN m is assumed when it
//!    has none. Columns with no role are not read (reported).
//! 5. Every data line must have as many fields as the header; the fields of
//!    the columns read must be finite numbers; time and step must increase.

use super::columns::{parse_header_field, role_of_name, unquote, HeaderField, NameRole, Role};
use super::columns::{torsion_quantity, DISPLACEMENT_NAMES, FORCE_NAMES};
use super::columns::{TORQUE_NAMES, TWIST_NAMES};
use super::error::DataError;
use super::read::{ColumnRef, ReadOptions};
use super::record::{Channel, Notice, Record, Series};
use super::units::{Quantity, Unit};
use std::path::Path;

/// A column the record reads, with the unit its values are converted from.
#[derive(Clone, Debug)]
struct Col {
    index: usize,
    text: String,
    /// `None` for a step column, read as written.
    unit: Option<Unit>,
}

/// Which column plays which role.
#[derive(Debug, Default)]
struct Plan {
    time: Option<Col>,
    step: Option<Col>,
    displacement: Option<Col>,
    force: Option<Col>,
}

/// How a column got its role (for ambiguity and supersession).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Source {
    Options,
    Header,
}

fn quantity_role(q: Quantity) -> Role {
    match q {
        Quantity::Length | Quantity::Angle => Role::Displacement,
        Quantity::Force | Quantity::Torque => Role::Force,
        Quantity::Time => Role::Time,
    }
}

/// The quantity a role takes when nothing says otherwise (the unit assumed
/// and the units listed in messages).
fn role_quantity(r: Role) -> Option<Quantity> {
    match r {
        Role::Time => Some(Quantity::Time),
        Role::Displacement => Some(Quantity::Length),
        Role::Force => Some(Quantity::Force),
        Role::Step | Role::Ignore => None,
    }
}

/// The field separator of a file, from its header line: a comma where the
/// header has one, else a tab or a semicolon (spreadsheet exports in locales
/// that write a decimal comma), else a comma (a single column).
fn separator(header: &str) -> char {
    [',', '\t', ';']
        .into_iter()
        .find(|c| header.contains(*c))
        .unwrap_or(',')
}

/// `text` with a decimal comma made a point when it is a number written so
/// (`-1,5`, `2,75e-3`); anything else as it is.
fn decimal_point(text: &str) -> String {
    let t = text.trim();
    let candidate = t.replacen(',', ".", 1);
    if t.matches(',').count() == 1 && !t.contains('.') && candidate.parse::<f64>().is_ok() {
        candidate
    } else {
        text.to_string()
    }
}

fn is_units_line(fields: &[&str]) -> bool {
    let fields: Vec<&str> = fields.iter().map(|f| unquote(f)).collect();
    fields
        .iter()
        .all(|f| f.is_empty() || f.parse::<f64>().is_err())
        && fields.iter().any(|f| Unit::parse(f).is_some())
}

fn column_list(header: &[HeaderField]) -> String {
    let names: Vec<String> = header.iter().map(|h| format!("'{}'", h.text)).collect();
    names.join(", ")
}

/// Finds the column an option names.
fn find_column(
    file: &Path,
    line: usize,
    header: &[HeaderField],
    r: &ColumnRef,
) -> Result<usize, DataError> {
    match r {
        ColumnRef::Number(k) if (1..=header.len()).contains(k) => Ok(k - 1),
        ColumnRef::Number(k) => Err(DataError::at(
            file,
            line,
            1,
            format!(
                "read options name column number {k}, but the header has {} columns",
                header.len()
            ),
        )),
        ColumnRef::Name(n) => {
            let n = n.trim();
            let hits: Vec<usize> = (0..header.len())
                .filter(|&i| header[i].text == n || header[i].name == n)
                .collect();
            match hits.as_slice() {
                [i] => Ok(*i),
                [] => Err(DataError::at(
                    file,
                    line,
                    1,
                    format!(
                        "read options name column '{n}', which is not in the header (columns: {})",
                        column_list(header)
                    ),
                )),
                [a, b, ..] => Err(DataError::at(
                    file,
                    line,
                    b + 1,
                    format!(
                        "read options name column '{n}', which matches columns {} and {}: use its number",
                        a + 1,
                        b + 1
                    ),
                )),
            }
        }
    }
}

struct Header<'a> {
    file: &'a Path,
    line: usize,
    fields: Vec<HeaderField>,
    /// Units line: its line number and fields.
    units: Option<(usize, Vec<String>)>,
}

impl Header<'_> {
    fn err(&self, column: usize, message: String) -> DataError {
        DataError::at(self.file, self.line, column, message)
    }

    /// The unit text of column `i` and the line/column it was found at.
    fn unit_text(&self, i: usize) -> Result<Option<(String, usize)>, DataError> {
        let from_header = self.fields[i].unit.clone();
        let from_units = self
            .units
            .as_ref()
            .map(|(_, u)| u[i].clone())
            .filter(|u| !u.is_empty());
        match (from_header, from_units) {
            (Some(h), Some(u)) if h != u => Err(DataError::at(
                self.file,
                self.units.as_ref().map_or(self.line, |(l, _)| *l),
                i + 1,
                format!(
                    "column '{}' has unit '{h}' in the header and '{u}' in the units line",
                    self.fields[i].text
                ),
            )),
            (Some(h), _) => Ok(Some((h, self.line))),
            (None, Some(u)) => Ok(Some((
                u,
                self.units.as_ref().map_or(self.line, |(l, _)| *l),
            ))),
            (None, None) => Ok(None),
        }
    }

    /// Decides the role and unit of every column.
    fn plan(
        &self,
        options: &ReadOptions,
        notices: &mut Vec<Notice>,
        ignored: &mut Vec<String>,
    ) -> Result<Plan, DataError> {
        let n = self.fields.len();
        let mut role_opt: Vec<Option<Role>> = vec![None; n];
        for (r, role) in &options.roles {
            let i = find_column(self.file, self.line, &self.fields, r)?;
            if role_opt[i].is_some_and(|old| old != *role) {
                return Err(self.err(
                    i + 1,
                    format!(
                        "read options give column '{}' two roles",
                        self.fields[i].text
                    ),
                ));
            }
            role_opt[i] = Some(*role);
        }
        let mut unit_opt: Vec<Option<Unit>> = vec![None; n];
        for (r, unit) in &options.units {
            let i = find_column(self.file, self.line, &self.fields, r)?;
            unit_opt[i] = Some(*unit);
        }

        // Role of each column and how it was found.
        let mut roles: Vec<Option<(Role, Source)>> = vec![None; n];
        let mut units: Vec<Option<Unit>> = vec![None; n];
        for i in 0..n {
            let h = &self.fields[i];
            let name_role = role_of_name(&h.name);
            let unit_text = self.unit_text(i)?;
            let parsed = unit_text.as_ref().and_then(|(t, _)| Unit::parse(t));
            // `disp_mm (cm)` states two units; the bracket's used to win without a word
            // (found by review).
            let in_name = super::columns::parse_header_field(&h.name)
                .unit
                .and_then(|t| Unit::parse(&t));
            if let (Some(a), Some(b), None) = (in_name, parsed, unit_opt[i]) {
                if a != b {
                    return Err(self.err(
                        i + 1,
                        format!(
                            "column '{}' states two units, {a} in its name and {b} after it: keep one",
                            h.text
                        ),
                    ));
                }
            }
            let unit = unit_opt[i].or(parsed);
            let (role, source) = if let Some(r) = role_opt[i] {
                (r, Source::Options)
            } else if let Some(u) = unit {
                let r = quantity_role(u.quantity());
                if let NameRole::Specific(named) = name_role {
                    if named != r {
                        // As written too when that differs: `nm` reads as N m, not nanometres.
                        let written = match &unit_text {
                            Some((t, _)) if unit_opt[i].is_none() && t.trim() != u.symbol() => {
                                format!(" (written '{}')", t.trim())
                            }
                            _ => String::new(),
                        };
                        let expected = role_quantity(named)
                            .map(|q| format!(": expected {}", q.known_symbols()))
                            .unwrap_or_default();
                        return Err(self.err(
                            i + 1,
                            format!(
                                "column '{}' is named like {named} but its unit {u}{written} is a {} unit{expected}",
                                h.text,
                                u.quantity()
                            ),
                        ));
                    }
                }
                if let Some(q) = torsion_quantity(&h.name) {
                    if u.quantity() != q {
                        return Err(self.err(
                            i + 1,
                            format!(
                                "column '{}' is named like {q} but its unit {u} is a {} unit: expected {}",
                                h.text,
                                u.quantity(),
                                q.known_symbols()
                            ),
                        ));
                    }
                }
                // A name that says nothing (`Lead Actuator Displacment`): the
                // unit decided, which is an assumption to say (`u`, `x`, `y`
                // are read by their unit as a rule).
                if name_role == NameRole::Unknown {
                    notices.push(Notice::RoleByUnit {
                        column: h.text.clone(),
                        role: r,
                        unit: u,
                    });
                }
                (r, Source::Header)
            } else if let Some((t, at)) = &unit_text {
                match name_role {
                    NameRole::Specific(Role::Step) => (Role::Step, Source::Header),
                    NameRole::Specific(r) => {
                        let q = torsion_quantity(&h.name)
                            .or(role_quantity(r))
                            .unwrap_or(Quantity::Length);
                        return Err(unknown_unit(self.file, *at, i, h, t, q));
                    }
                    NameRole::Generic => {
                        let known = format!(
                            "{}; {}",
                            Quantity::Length.known_symbols(),
                            Quantity::Force.known_symbols()
                        );
                        return Err(DataError::at(
                            self.file,
                            *at,
                            i + 1,
                            format!(
                                "unknown unit '{t}' for column '{}': expected a length or force unit ({known})",
                                h.text
                            ),
                        ));
                    }
                    NameRole::Unknown => {
                        ignored.push(format!("'{}' (unknown unit '{t}')", h.text));
                        continue;
                    }
                }
            } else {
                match name_role {
                    NameRole::Specific(r) => (r, Source::Header),
                    NameRole::Generic => {
                        ignored.push(format!(
                            "'{}' (no unit: u, x, y are read only with a length or force unit)",
                            h.text
                        ));
                        continue;
                    }
                    NameRole::Unknown => {
                        if h.text.is_empty() {
                            ignored.push(format!("column {} (unnamed)", i + 1));
                        } else {
                            ignored.push(format!("'{}'", h.text));
                        }
                        continue;
                    }
                }
            };
            if role == Role::Ignore {
                ignored.push(format!("'{}' (read options)", h.text));
                continue;
            }
            // The unit this role needs.
            if let Some(q) = role_quantity(role) {
                let q = torsion_quantity(&h.name)
                    .filter(|t| quantity_role(*t) == role)
                    .unwrap_or(q);
                let u = match (unit, &unit_text) {
                    (Some(u), _) => u,
                    (None, Some((t, at))) => return Err(unknown_unit(self.file, *at, i, h, t, q)),
                    (None, None) => {
                        let u = q.canonical();
                        notices.push(Notice::AssumedUnit {
                            column: h.text.clone(),
                            unit: u,
                        });
                        u
                    }
                };
                if quantity_role(u.quantity()) != role {
                    return Err(self.err(
                        i + 1,
                        format!(
                            "column '{}' has the role {role}, which needs a {q} unit, but its unit {u} is a {} unit",
                            h.text,
                            u.quantity()
                        ),
                    ));
                }
                if let (Some(o), Some((t, _))) = (unit_opt[i], &unit_text) {
                    if Unit::parse(t) != Some(o) {
                        notices.push(Notice::OverriddenUnit {
                            column: h.text.clone(),
                            file_unit: t.clone(),
                            unit: o,
                        });
                    }
                }
                units[i] = Some(u);
            }
            roles[i] = Some((role, source));
        }

        // A role given by the options is taken by no other column.
        for i in 0..n {
            if let Some((r, Source::Header)) = roles[i] {
                let given = (0..n).any(|j| roles[j] == Some((r, Source::Options)));
                if given {
                    ignored.push(format!(
                        "'{}' (the role {r} was given to another column)",
                        self.fields[i].text
                    ));
                    roles[i] = None;
                }
            }
        }

        let mut plan = Plan::default();
        for role in [Role::Time, Role::Step, Role::Displacement, Role::Force] {
            let cols: Vec<usize> = (0..n)
                .filter(|&i| roles[i].is_some_and(|(r, _)| r == role))
                .collect();
            let slot = match role {
                Role::Time => &mut plan.time,
                Role::Step => &mut plan.step,
                Role::Displacement => &mut plan.displacement,
                _ => &mut plan.force,
            };
            match cols.as_slice() {
                [] => {}
                [i] => {
                    *slot = Some(Col {
                        index: *i,
                        text: self.fields[*i].text.clone(),
                        unit: units[*i],
                    })
                }
                [a, b, ..] => {
                    return Err(self.err(
                        b + 1,
                        format!(
                            "columns '{}' ({}) and '{}' ({}) both look like {role}: choose one with the read options (`hyst ... --{role} COLUMN[:UNIT]`)",
                            self.fields[*a].text,
                            a + 1,
                            self.fields[*b].text,
                            b + 1
                        ),
                    ))
                }
            }
        }
        Ok(plan)
    }
}

fn unknown_unit(
    file: &Path,
    line: usize,
    i: usize,
    h: &HeaderField,
    unit: &str,
    q: Quantity,
) -> DataError {
    DataError::at(
        file,
        line,
        i + 1,
        format!(
            "unknown unit '{unit}' for column '{}': expected a {q} unit ({})",
            h.text,
            q.known_symbols()
        ),
    )
}

fn missing_column(file: &Path, line: usize, channel: Channel, header: &[HeaderField]) -> DataError {
    let (names, torsion) = match channel {
        Channel::Displacement => (DISPLACEMENT_NAMES, TWIST_NAMES),
        Channel::Force => (FORCE_NAMES, TORQUE_NAMES),
    };
    let names = [names, torsion].concat();
    DataError::at(
        file,
        line,
        1,
        format!(
            "expected a {channel} column (named {}, or with a {} or {} unit, or given the role in the read options: `hyst ... --{channel} COLUMN[:UNIT]`), found columns {}",
            names.join(", "),
            channel.quantity(),
            channel.torsion_quantity(),
            column_list(header)
        ),
    )
}

/// A column's values as they are parsed, with the previous text for the
/// increasing-order checks.
struct Reader {
    col: Col,
    values: Vec<f64>,
    increasing: bool,
    last: Option<(f64, usize, String)>,
}

impl Reader {
    fn new(col: Col, increasing: bool) -> Self {
        Reader {
            col,
            values: Vec::new(),
            increasing,
            last: None,
        }
    }

    fn take(&mut self, file: &Path, line: usize, fields: &[&str]) -> Result<(), DataError> {
        let column = self.col.index + 1;
        let text = fields[self.col.index].trim();
        let value: f64 = text.parse().map_err(|_| {
            DataError::at(
                file,
                line,
                column,
                format!(
                    "expected a number for column '{}', found '{text}'",
                    self.col.text
                ),
            )
        })?;
        let canonical = self.col.unit.map_or(value, |u| u.to_canonical(value));
        if !canonical.is_finite() {
            let column_name = &self.col.text;
            // Finite as written (1e306 m) and not in mm, or not finite at all.
            let expected = match self.col.unit {
                Some(u) if value.is_finite() => format!(
                    "a number for column '{column_name}' that stays finite in {}",
                    u.quantity().canonical().symbol()
                ),
                _ => format!("a finite number for column '{column_name}'"),
            };
            return Err(DataError::at(
                file,
                line,
                column,
                format!("expected {expected}, found '{text}'"),
            ));
        }
        let value = canonical;
        if self.increasing {
            if let Some((prev, prev_line, prev_text)) = &self.last {
                if value <= *prev {
                    return Err(DataError::at(
                        file,
                        line,
                        column,
                        format!(
                            "expected '{}' to increase after '{prev_text}' on line {prev_line}, found '{text}'",
                            self.col.text
                        ),
                    ));
                }
            }
            self.last = Some((value, line, text.to_string()));
        }
        self.values.push(value);
        Ok(())
    }

    fn series(self, quantity: Quantity) -> Series {
        Series {
            name: self.col.text,
            unit: self.col.unit.unwrap_or(quantity.canonical()),
            values: self.values,
        }
    }
}

/// The lines of `text`, ended by `\n`, `\r\n` or a lone `\r` (the line end
/// of classic Mac OS, which some spreadsheet exports still write: read with
/// `str::lines` such a file was one line, a header without data).
pub(crate) fn lines(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = text;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        let (line, next) = match rest.find(['\n', '\r']) {
            Some(i) if rest[i..].starts_with("\r\n") => (&rest[..i], i + 2),
            Some(i) => (&rest[..i], i + 1),
            None => (rest, rest.len()),
        };
        rest = &rest[next..];
        Some(line)
    })
}

/// Parses CSV text; `file` names it in messages.
pub(crate) fn parse(file: &Path, text: &str, options: &ReadOptions) -> Result<Record, DataError> {
    let sample_rate = options.checked_sample_rate(file)?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut comments = Vec::new();
    let mut content: Vec<(usize, &str)> = Vec::new();
    // Lines starting with `#` below the header: data rows when they have the header's
    // fields (a spreadsheet's `#N/A` or `#DIV/0!` in the first column, which the number
    // check then refuses at its line), otherwise comments, reported as such.
    let mut width_below = None;
    let mut sep = ',';
    let mut comments_among_rows = Vec::new();
    let mut n_lines = 0;
    for (k, line) in lines(text).enumerate() {
        n_lines = k + 1;
        let t = line.trim();
        if let Some(c) = t.strip_prefix('#') {
            if width_below.is_some_and(|w| w > 1 && line.split(sep).count() == w) {
                content.push((k + 1, line));
            } else {
                if width_below.is_some() {
                    comments_among_rows.push(k + 1);
                }
                comments.push(c.trim().to_string());
            }
        } else if !t.is_empty() {
            if width_below.is_none() {
                sep = separator(line);
                width_below = Some(line.split(sep).count());
            }
            content.push((k + 1, line));
        }
    }
    let Some(&(header_line, header_text)) = content.first() else {
        return Err(if comments.is_empty() {
            DataError::at(
                file,
                1,
                1,
                "empty file: expected a header line naming the columns",
            )
        } else {
            DataError::at(
                file,
                n_lines + 1,
                1,
                "expected a header line naming the columns, found end of file",
            )
        });
    };
    let fields: Vec<HeaderField> = header_text.split(sep).map(parse_header_field).collect();
    let width = fields.len();
    let field_count = |line: usize, found: usize| {
        DataError::at(
            file,
            line,
            found.min(width) + 1,
            format!("expected {width} fields as in the header (line {header_line}), found {found}"),
        )
    };

    let mut rest = &content[1..];
    let mut units = None;
    if let Some(&(line, t)) = rest.first() {
        let f: Vec<&str> = t.split(sep).collect();
        if is_units_line(&f) {
            if f.len() != width {
                return Err(field_count(line, f.len()));
            }
            units = Some((line, f.iter().map(|s| unquote(s).to_string()).collect()));
            rest = &rest[1..];
        }
    }
    let header = Header {
        file,
        line: header_line,
        fields,
        units,
    };

    let mut notices = Vec::new();
    let mut ignored = Vec::new();
    let plan = header.plan(options, &mut notices, &mut ignored)?;
    let input = match options.input {
        Some(c) => c,
        None => match &plan.force {
            Some(f) if header.fields[f.index].name.eq_ignore_ascii_case("u") => Channel::Force,
            _ => Channel::Displacement,
        },
    };
    let has_input = match input {
        Channel::Displacement => plan.displacement.is_some(),
        Channel::Force => plan.force.is_some(),
    };
    if !has_input {
        return Err(missing_column(file, header_line, input, &header.fields));
    }

    let replaced_time = match (sample_rate, &plan.time) {
        (Some(_), Some(t)) => Some(t.text.clone()),
        _ => None,
    };
    let mut time = match sample_rate {
        Some(_) => None,
        None => plan.time.map(|c| Reader::new(c, true)),
    };
    let mut step = plan.step.map(|c| Reader::new(c, true));
    let mut disp = plan.displacement.map(|c| Reader::new(c, false));
    let mut force = plan.force.map(|c| Reader::new(c, false));
    if let Some(s) = &step {
        notices.push(Notice::StepColumn {
            column: s.col.text.clone(),
        });
    }

    let mut skipped = 0;
    let mut decimal_commas = 0;
    // The first value of a column read written with a decimal comma, and the
    // first with a decimal point: (line, column, text).
    let read_columns: Vec<usize> = [&time, &step, &disp, &force]
        .into_iter()
        .flatten()
        .map(|r| r.col.index)
        .collect();
    let (mut first_comma, mut first_point) = (None, None);
    let mut taken = 0;
    for (k, &(line, t)) in rest.iter().enumerate() {
        // Rows past the most asked for are not read at all: a tail of other
        // data or of text is what the option is for.
        if options.max_rows == Some(taken) {
            notices.push(Notice::RowsNotRead {
                from: format!("line {line}"),
                rows: rest.len() - k,
            });
            break;
        }
        let raw: Vec<&str> = t.split(sep).collect();
        if raw.len() != width {
            return Err(field_count(line, raw.len()));
        }
        // Fields separated by `;` or tabs may write numbers with a decimal
        // comma (a spreadsheet's export in many locales).
        let points: Vec<String>;
        let f: Vec<&str> = if sep != ',' && raw.iter().any(|v| v.contains(',')) {
            points = raw.iter().map(|v| decimal_point(v)).collect();
            decimal_commas += raw
                .iter()
                .zip(&points)
                .filter(|(a, b)| **a != b.as_str())
                .count();
            points.iter().map(String::as_str).collect()
        } else {
            raw.clone()
        };
        if skipped < options.skip_rows {
            skipped += 1;
            notices.push(Notice::SkippedRow {
                at: format!("line {line}"),
                text: t.trim().to_string(),
            });
            continue;
        }
        if sep != ',' {
            let written = |with: char| {
                read_columns
                    .iter()
                    .find(|&&k| raw[k].contains(with) && f[k].parse::<f64>().is_ok())
                    .map(|&k| (line, k + 1, raw[k].trim().to_string()))
            };
            first_comma = first_comma.or_else(|| written(','));
            first_point = first_point.or_else(|| written('.'));
        }
        // A file that writes both, `1,5` and `1.000`, leaves `1.000` a
        // thousand or a one (found by review: read as 1.0 without a word);
        // rows skipped by the read options aside.
        if let (Some(c), Some(p)) = (&first_comma, &first_point) {
            let (at_line, at_column) = (c.0, c.1).max((p.0, p.1));
            return Err(DataError::at(
                file,
                at_line,
                at_column,
                format!(
                    "'{}' (line {}) is written with a decimal point and '{}' (line {}) with a \
                     decimal comma: expected one of the two in a file (where commas are decimal, \
                     a point can separate thousands)",
                    p.2, p.0, c.2, c.0
                ),
            ));
        }
        for r in [&mut time, &mut step, &mut disp, &mut force]
            .into_iter()
            .flatten()
        {
            r.take(file, line, &f)?;
        }
        taken += 1;
    }
    let rows = match (&disp, &force) {
        (Some(d), _) => d.values.len(),
        (None, Some(f)) => f.values.len(),
        (None, None) => 0,
    };
    if rows == 0 {
        let message = if skipped > 0 {
            format!("expected a data row after skipping {skipped} rows, found end of file")
        } else {
            format!("expected a data row after the header (line {header_line}), found end of file")
        };
        return Err(DataError::at(file, n_lines + 1, 1, message));
    }

    let time = match sample_rate {
        Some(hz) => {
            notices.push(Notice::TimeFromSampleRate {
                hz,
                replaced: replaced_time,
            });
            Some(Series::canonical(
                format!("sample rate {hz} Hz"),
                Quantity::Time,
                (0..rows).map(|k| k as f64 / hz).collect(),
            ))
        }
        None => time.map(|r| r.series(Quantity::Time)),
    };
    if !ignored.is_empty() {
        notices.push(Notice::IgnoredColumns { columns: ignored });
    }
    if sep != ',' {
        notices.push(Notice::Separator {
            separator: sep,
            decimal_commas,
        });
    }
    if !comments_among_rows.is_empty() {
        notices.push(Notice::CommentsAmongRows {
            lines: comments_among_rows,
        });
    }
    Ok(Record::new(
        file,
        input,
        disp.map(|r| r.series(Quantity::Length)),
        force.map(|r| r.series(Quantity::Force)),
        time,
    )?
    .with_comments(comments)
    .with_notices(notices))
}
