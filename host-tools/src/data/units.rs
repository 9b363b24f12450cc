//! Units of the lab records and their conversion to the canonical units of the
//! project: millimetres, kilonewtons and seconds; for torsion records (the
//! torque-twist tests of thesis ch. 5) degrees of twist and kilonewton metres
//! of torque.

use std::fmt;

/// A physical quantity a column can hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Displacement (canonical unit mm).
    Length,
    /// Force (canonical unit kN).
    Force,
    /// Time (canonical unit s).
    Time,
    /// Angle of twist or rotation (canonical unit deg).
    Angle,
    /// Torque or moment (canonical unit kN m).
    Torque,
}

impl Quantity {
    /// The canonical unit of the quantity: mm, kN or s.
    pub fn canonical(self) -> Unit {
        match self {
            Quantity::Length => Unit::Millimetre,
            Quantity::Force => Unit::Kilonewton,
            Quantity::Time => Unit::Second,
            Quantity::Angle => Unit::Degree,
            Quantity::Torque => Unit::KilonewtonMetre,
        }
    }

    /// The units the reader knows for this quantity, by symbol, for messages.
    pub fn known_symbols(self) -> String {
        let names: Vec<_> = Unit::ALL
            .iter()
            .filter(|u| u.quantity() == self)
            .map(|u| u.symbol())
            .collect();
        names.join(", ")
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantity::Length => "length",
            Quantity::Force => "force",
            Quantity::Time => "time",
            Quantity::Angle => "angle",
            Quantity::Torque => "torque",
        })
    }
}

/// A unit the reader converts from.
///
/// Accepted spellings (see [`Unit::parse`]): length `mm`, `cm`, `m`, `in`
/// (`in.`, `inch`, `inches`); force `N`, `kN`, `MN`, `kip` (`kips`), `lbf`
/// (`lb`, `lbs`); time `s` (`sec`), `ms`; angle `deg` (`degree`, `degrees`,
/// `°`), `rad` (`radian`, `radians`); torque `kN m` and `N m` (the space may
/// also be `*`, `.`, `-`, `·` or nothing: `kNm`, `kN*m`, `kN-m`). Matching
/// ignores case except for `m` and `MN`: `M` and `mN` are refused rather than
/// guessed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unit {
    /// mm (canonical length).
    Millimetre,
    /// cm = 10 mm.
    Centimetre,
    /// m = 1000 mm.
    Metre,
    /// in = 25.4 mm (exact).
    Inch,
    /// N = 0.001 kN.
    Newton,
    /// kN (canonical force).
    Kilonewton,
    /// MN = 1000 kN.
    Meganewton,
    /// kip = 1000 lbf = 4.4482216152605 kN (exact).
    Kip,
    /// lbf = 4.4482216152605 N (exact: 0.45359237 kg × 9.80665 m/s²).
    PoundForce,
    /// s (canonical time).
    Second,
    /// ms = 0.001 s.
    Millisecond,
    /// deg (canonical angle).
    Degree,
    /// rad = 180/pi deg.
    Radian,
    /// kN m (canonical torque).
    KilonewtonMetre,
    /// N m = 0.001 kN m.
    NewtonMetre,
}

/// How a value in a unit becomes a value in the canonical unit: decimal
/// scalings divide or multiply by an exact integer so that the result is the
/// correctly rounded canonical value (`0.1 m` becomes exactly the `f64`
/// nearest to 100 mm).
#[derive(Clone, Copy)]
enum Scale {
    Mul(f64),
    Div(f64),
}

impl Unit {
    /// Every unit, lengths first, then forces, times, angles and torques.
    pub const ALL: [Unit; 15] = [
        Unit::Millimetre,
        Unit::Centimetre,
        Unit::Metre,
        Unit::Inch,
        Unit::Newton,
        Unit::Kilonewton,
        Unit::Meganewton,
        Unit::Kip,
        Unit::PoundForce,
        Unit::Second,
        Unit::Millisecond,
        Unit::Degree,
        Unit::Radian,
        Unit::KilonewtonMetre,
        Unit::NewtonMetre,
    ];

    /// The quantity the unit measures.
    pub fn quantity(self) -> Quantity {
        match self {
            Unit::Millimetre | Unit::Centimetre | Unit::Metre | Unit::Inch => Quantity::Length,
            Unit::Newton | Unit::Kilonewton | Unit::Meganewton | Unit::Kip | Unit::PoundForce => {
                Quantity::Force
            }
            Unit::Second | Unit::Millisecond => Quantity::Time,
            Unit::Degree | Unit::Radian => Quantity::Angle,
            Unit::KilonewtonMetre | Unit::NewtonMetre => Quantity::Torque,
        }
    }

    /// The usual symbol (`mm`, `kN`, `lbf`, ...).
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::Millimetre => "mm",
            Unit::Centimetre => "cm",
            Unit::Metre => "m",
            Unit::Inch => "in",
            Unit::Newton => "N",
            Unit::Kilonewton => "kN",
            Unit::Meganewton => "MN",
            Unit::Kip => "kip",
            Unit::PoundForce => "lbf",
            Unit::Second => "s",
            Unit::Millisecond => "ms",
            Unit::Degree => "deg",
            Unit::Radian => "rad",
            Unit::KilonewtonMetre => "kN m",
            Unit::NewtonMetre => "N m",
        }
    }

    fn scale(self) -> Scale {
        match self {
            Unit::Millimetre
            | Unit::Kilonewton
            | Unit::Second
            | Unit::Degree
            | Unit::KilonewtonMetre => Scale::Mul(1.0),
            Unit::Centimetre => Scale::Mul(10.0),
            Unit::Metre | Unit::Meganewton => Scale::Mul(1000.0),
            Unit::Inch => Scale::Mul(25.4),
            Unit::Newton | Unit::Millisecond | Unit::NewtonMetre => Scale::Div(1000.0),
            Unit::Radian => Scale::Mul(180.0 / std::f64::consts::PI),
            Unit::Kip => Scale::Mul(4.448_221_615_260_5),
            Unit::PoundForce => Scale::Mul(0.004_448_221_615_260_5),
        }
    }

    /// Converts a value in this unit to the canonical unit of its quantity.
    ///
    /// ```
    /// use hyst::data::Unit;
    /// assert_eq!(Unit::Metre.to_canonical(0.25), 250.0);
    /// assert_eq!(Unit::Newton.to_canonical(1500.0), 1.5);
    /// assert_eq!(Unit::Inch.to_canonical(1.0), 25.4);
    /// ```
    pub fn to_canonical(self, value: f64) -> f64 {
        match self.scale() {
            Scale::Mul(k) => value * k,
            Scale::Div(k) => value / k,
        }
    }

    /// Converts a value in the canonical unit of this unit's quantity to this unit.
    pub fn from_canonical(self, value: f64) -> f64 {
        match self.scale() {
            Scale::Mul(k) => value / k,
            Scale::Div(k) => value * k,
        }
    }

    /// Parses a unit as written in a header (`mm`, `kN`, `inches`, ...).
    /// Surrounding white space is ignored; anything else unknown is `None`.
    pub fn parse(text: &str) -> Option<Unit> {
        let t = text.trim();
        match t {
            "m" => return Some(Unit::Metre),
            "MN" => return Some(Unit::Meganewton),
            _ => {}
        }
        let lower = t.to_ascii_lowercase();
        if lower == "m" || lower == "mn" {
            // `M` (mega?) and `mN` (millinewton?) are not guessed.
            return None;
        }
        Some(match lower.as_str() {
            "mm" | "millimetre" | "millimetres" | "millimeter" | "millimeters" => Unit::Millimetre,
            "cm" | "centimetre" | "centimetres" | "centimeter" | "centimeters" => Unit::Centimetre,
            "metre" | "metres" | "meter" | "meters" => Unit::Metre,
            "in" | "in." | "inch" | "inches" => Unit::Inch,
            "n" | "newton" | "newtons" => Unit::Newton,
            "kn" | "kilonewton" | "kilonewtons" => Unit::Kilonewton,
            "kip" | "kips" => Unit::Kip,
            "lbf" | "lb" | "lbs" => Unit::PoundForce,
            "s" | "sec" | "second" | "seconds" => Unit::Second,
            "ms" => Unit::Millisecond,
            "deg" | "degree" | "degrees" | "°" => Unit::Degree,
            "rad" | "radian" | "radians" => Unit::Radian,
            _ => {
                // Torque: force unit, separator, metre.
                let compact: String = lower
                    .chars()
                    .filter(|c| !matches!(c, ' ' | '*' | '.' | '-' | '·' | '⋅'))
                    .collect();
                match compact.as_str() {
                    "knm" => Unit::KilonewtonMetre,
                    "nm" => Unit::NewtonMetre,
                    _ => return None,
                }
            }
        })
    }
}

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A device table labels its units by symbol, in at most 8 ASCII characters each.
    #[test]
    fn every_symbol_fits_a_device_table() {
        for u in Unit::ALL {
            assert!(
                hysteresis::table::Units::new(u.symbol(), u.symbol()).is_some(),
                "{u}"
            );
        }
    }

    #[test]
    fn every_symbol_parses_back_to_its_unit() {
        for u in Unit::ALL {
            assert_eq!(Unit::parse(u.symbol()), Some(u), "{u}");
        }
    }

    #[test]
    fn spellings_and_refusals() {
        assert_eq!(Unit::parse(" KN "), Some(Unit::Kilonewton));
        assert_eq!(Unit::parse("inches"), Some(Unit::Inch));
        assert_eq!(Unit::parse("kips"), Some(Unit::Kip));
        assert_eq!(Unit::parse("lb"), Some(Unit::PoundForce));
        assert_eq!(Unit::parse("M"), None);
        assert_eq!(Unit::parse("mN"), None);
        assert_eq!(Unit::parse("furlong"), None);
        assert_eq!(Unit::parse(""), None);
        assert_eq!(Unit::parse("Degrees"), Some(Unit::Degree));
        assert_eq!(Unit::parse("°"), Some(Unit::Degree));
        for t in ["kN m", "kNm", "kN*m", "kN.m", "kN-m", "kN·m", "KN M"] {
            assert_eq!(Unit::parse(t), Some(Unit::KilonewtonMetre), "{t}");
        }
        assert_eq!(Unit::parse("N m"), Some(Unit::NewtonMetre));
        assert_eq!(Unit::parse("kN mm"), None);
    }

    #[test]
    fn conversions_match_the_definitions() {
        // Definitions: 1 in = 25.4 mm; 1 lbf = 0.45359237 kg * 9.80665 m/s^2.
        let lbf_in_n = 0.453_592_37 * 9.806_65;
        assert!((Unit::PoundForce.to_canonical(1.0) * 1000.0 - lbf_in_n).abs() < 1e-15);
        assert!((Unit::Kip.to_canonical(1.0) - lbf_in_n).abs() < 1e-14);
        assert_eq!(Unit::Inch.to_canonical(2.0), 50.8);
        assert_eq!(Unit::Centimetre.to_canonical(0.5), 5.0);
        assert_eq!(Unit::Meganewton.to_canonical(0.002), 2.0);
        assert_eq!(Unit::Millisecond.to_canonical(250.0), 0.25);
        assert_eq!(Unit::NewtonMetre.to_canonical(1500.0), 1.5);
        assert!((Unit::Radian.to_canonical(std::f64::consts::PI) - 180.0).abs() < 1e-12);
        // Decimal scalings are correctly rounded: 0.1 m is the f64 nearest 100 mm.
        assert_eq!(Unit::Metre.to_canonical(0.1), 100.0);
        assert_eq!(Unit::Newton.to_canonical(100.0), 0.1);
        for u in Unit::ALL {
            let v = 3.7;
            assert!(
                (u.from_canonical(u.to_canonical(v)) - v).abs() < 1e-14,
                "{u}"
            );
            assert_eq!(u.quantity().canonical().to_canonical(v), v);
        }
    }
}
