//! Column headers: a name, an optional unit, and the role the name suggests.
//!
//! A header field is read as `name (unit)`, `name [unit]` or `name_unit`
//! (the last only when `unit` is a known unit or `name` is a known role name,
//! so `axial_load` stays a name). Surrounding white space and double quotes
//! are removed.
//!
//! Role names (case-insensitive; the whole name or its last word, so
//! `Lead Actuator Force` is a force):
//!
//! | role | names |
//! |---|---|
//! | time | `time`, `t` |
//! | step (row order only) | `step`, `index` |
//! | displacement | `displacement`, `disp`, `drift`, `strain`, `deformation`, `deflection`, `delta` |
//! | force | `force`, `load`, `stress`, `shear`, `f`, `v` |
//! | displacement: a twist (angle unit, deg assumed) | `twist`, `rotation`, `angle` |
//! | force: a torque (torque unit, kN m assumed) | `torque`, `moment` |
//! | displacement or force, by unit | `u`, `x`, `y` (not read without a unit) |
//!
//! `strain` and `stress` follow the OpenSees convention of a uniaxial material
//! driven by a displacement: strain is a displacement in mm, stress a force in
//! kN.
//!
//! A torsion record (thesis ch. 5) is read into the same two channels: its
//! twist is the displacement channel (in deg), its torque the force channel
//! (in kN m). A twist or torque name needs a unit of its own quantity.

use super::units::Quantity;
use std::fmt;

/// What a column holds, as recognised from its header or given in the read
/// options.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// Time (s or ms).
    Time,
    /// A step or row counter: checked to increase, not kept.
    Step,
    /// Displacement.
    Displacement,
    /// Force.
    Force,
    /// Not read (only meaningful in read options, to silence a column).
    Ignore,
}

impl fmt::Display for Role {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Role::Time => "time",
            Role::Step => "step",
            Role::Displacement => "displacement",
            Role::Force => "force",
            Role::Ignore => "ignored",
        })
    }
}

/// Names recognised as time.
pub const TIME_NAMES: &[&str] = &["time", "t"];
/// Names recognised as a step counter.
pub const STEP_NAMES: &[&str] = &["step", "index"];
/// Names recognised as displacement.
pub const DISPLACEMENT_NAMES: &[&str] = &[
    "displacement",
    "disp",
    "drift",
    "strain",
    "deformation",
    "deflection",
    "delta",
];
/// Names recognised as force.
pub const FORCE_NAMES: &[&str] = &["force", "load", "stress", "shear", "f", "v"];
/// Names recognised as a twist (the displacement channel of a torsion record).
pub const TWIST_NAMES: &[&str] = &["twist", "rotation", "angle"];
/// Names recognised as a torque (the force channel of a torsion record).
pub const TORQUE_NAMES: &[&str] = &["torque", "moment"];
/// Signal names whose role comes from their unit (not read without one).
pub const GENERIC_NAMES: &[&str] = &["u", "x", "y"];

/// What a column name says about its role.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NameRole {
    /// A name of one role.
    Specific(Role),
    /// `u`, `x`, `y`: the unit decides.
    Generic,
    /// Not a known name.
    Unknown,
}

fn lookup(word: &str) -> NameRole {
    let w = word.to_ascii_lowercase();
    let w = w.as_str();
    if TIME_NAMES.contains(&w) {
        NameRole::Specific(Role::Time)
    } else if STEP_NAMES.contains(&w) {
        NameRole::Specific(Role::Step)
    } else if DISPLACEMENT_NAMES.contains(&w) || TWIST_NAMES.contains(&w) {
        NameRole::Specific(Role::Displacement)
    } else if FORCE_NAMES.contains(&w) || TORQUE_NAMES.contains(&w) {
        NameRole::Specific(Role::Force)
    } else if GENERIC_NAMES.contains(&w) {
        NameRole::Generic
    } else {
        NameRole::Unknown
    }
}

/// The role a column name suggests: the whole name, else its last word.
pub(crate) fn role_of_name(name: &str) -> NameRole {
    match lookup(name.trim()) {
        NameRole::Unknown => {}
        r => return r,
    }
    let last = name
        .split(|c: char| c.is_whitespace() || c == '_' || c == '-')
        .rfind(|w| !w.is_empty());
    match last {
        Some(w) if w.len() < name.trim().len() => match lookup(w) {
            // A generic letter as the last word ("lateral u") is not a name.
            NameRole::Generic => NameRole::Unknown,
            r => r,
        },
        _ => NameRole::Unknown,
    }
}

/// The quantity a twist or torque name requires (the whole name, else its
/// last word); `None` for every other name.
pub(crate) fn torsion_quantity(name: &str) -> Option<Quantity> {
    let is = |w: &str| {
        let w = w.to_ascii_lowercase();
        if TWIST_NAMES.contains(&w.as_str()) {
            Some(Quantity::Angle)
        } else if TORQUE_NAMES.contains(&w.as_str()) {
            Some(Quantity::Torque)
        } else {
            None
        }
    };
    is(name.trim()).or_else(|| {
        name.split(|c: char| c.is_whitespace() || c == '_' || c == '-')
            .rfind(|w| !w.is_empty())
            .and_then(is)
    })
}

/// A header field split into its name and unit text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct HeaderField {
    /// The field as written, trimmed and unquoted (used in messages).
    pub text: String,
    /// The name without the unit.
    pub name: String,
    /// The unit text, if the field states one.
    pub unit: Option<String>,
}

/// Removes surrounding white space and one pair of double quotes.
pub(crate) fn unquote(field: &str) -> &str {
    let t = field.trim();
    t.strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .map_or(t, str::trim)
}

/// Splits a header field into name and unit.
pub(crate) fn parse_header_field(field: &str) -> HeaderField {
    let text = unquote(field).to_string();
    for (open, close) in [('(', ')'), ('[', ']')] {
        if let Some(body) = text.strip_suffix(close) {
            if let Some(at) = body.rfind(open) {
                return HeaderField {
                    name: body[..at].trim().to_string(),
                    unit: Some(body[at + 1..].trim().to_string()),
                    text,
                };
            }
        }
    }
    if let Some(at) = text.rfind('_') {
        let (name, suffix) = (&text[..at], &text[at + 1..]);
        let unit_like = super::units::Unit::parse(suffix).is_some();
        if !name.is_empty()
            && !suffix.is_empty()
            && (unit_like || lookup(name) != NameRole::Unknown)
        {
            return HeaderField {
                name: name.trim().to_string(),
                unit: Some(suffix.trim().to_string()),
                text,
            };
        }
    }
    HeaderField {
        name: text.clone(),
        unit: None,
        text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn split(f: &str) -> (String, Option<String>) {
        let h = parse_header_field(f);
        (h.name, h.unit)
    }

    #[test]
    fn header_forms_of_our_data() {
        let s = |n: &str, u: Option<&str>| (n.to_string(), u.map(str::to_string));
        assert_eq!(split("time (s)"), s("time", Some("s")));
        assert_eq!(split(" force [kN] "), s("force", Some("kN")));
        assert_eq!(split("disp_mm"), s("disp", Some("mm")));
        assert_eq!(split("force_kN"), s("force", Some("kN")));
        assert_eq!(split("u_N"), s("u", Some("N")));
        assert_eq!(split("y_m"), s("y", Some("m")));
        assert_eq!(split("\"t\""), s("t", None));
        assert_eq!(split("axial_load"), s("axial_load", None));
        // A role name before the underscore makes the suffix a unit, known or not.
        assert_eq!(split("disp_furlong"), s("disp", Some("furlong")));
        assert_eq!(
            split("Lead Actuator Force "),
            s("Lead Actuator Force", None)
        );
    }

    #[test]
    fn roles_by_name() {
        use NameRole::*;
        assert_eq!(role_of_name("time"), Specific(Role::Time));
        assert_eq!(role_of_name("T"), Specific(Role::Time));
        assert_eq!(role_of_name("step"), Specific(Role::Step));
        assert_eq!(role_of_name("strain"), Specific(Role::Displacement));
        assert_eq!(role_of_name("stress"), Specific(Role::Force));
        assert_eq!(role_of_name("V"), Specific(Role::Force));
        assert_eq!(role_of_name("Lead Actuator Force"), Specific(Role::Force));
        assert_eq!(role_of_name("axial_load"), Specific(Role::Force));
        assert_eq!(
            role_of_name("lateral displacement"),
            Specific(Role::Displacement)
        );
        assert_eq!(role_of_name("Twist"), Specific(Role::Displacement));
        assert_eq!(role_of_name("applied torque"), Specific(Role::Force));
        assert_eq!(torsion_quantity("applied torque"), Some(Quantity::Torque));
        assert_eq!(torsion_quantity("rotation"), Some(Quantity::Angle));
        assert_eq!(torsion_quantity("force"), None);
        assert_eq!(role_of_name("y"), Generic);
        assert_eq!(role_of_name("lateral u"), Unknown);
        assert_eq!(role_of_name("tangent"), Unknown);
        assert_eq!(role_of_name("Lead Actuator Displacment"), Unknown);
    }
}
