//! An instrument's zero, to take off a channel as it is read: a constant (a
//! load cell that does not read zero at zero force) or a straight line in the
//! sample number (a zero that drifts as the cell warms up or creeps), as
//! `hyst diagnose` names them (its force offset and force drift).

use std::fmt;
use std::str::FromStr;

/// A zero that runs in a straight line, in the sample number, from `first`
/// at the record's first sample to `last` at its last; a constant where the
/// two are equal. In the channel's canonical unit (mm or kN).
///
/// ```
/// use hyst::data::Baseline;
/// let line: Baseline = "0.5..2.5".parse().unwrap();
/// assert_eq!(line.at(0, 5), 0.5);
/// assert_eq!(line.at(2, 5), 1.5);
/// assert_eq!(line.at(4, 5), 2.5);
/// assert_eq!(line.to_string(), "0.5..2.5");
/// assert_eq!(Baseline::from(-0.7).to_string(), "-0.7");
/// assert!("0.1..".parse::<Baseline>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Baseline {
    /// The zero at the first sample.
    pub first: f64,
    /// The zero at the last sample.
    pub last: f64,
}

impl Baseline {
    /// A zero that runs from `first` at the first sample to `last` at the
    /// last.
    pub fn line(first: f64, last: f64) -> Self {
        Baseline { first, last }
    }

    /// A constant zero.
    pub fn is_constant(&self) -> bool {
        self.first == self.last
    }

    /// The zero at sample `k` of `n`: `first + (last - first) k / (n - 1)`,
    /// the sample number scaled as the drift check scales it.
    pub fn at(&self, k: usize, n: usize) -> f64 {
        if self.is_constant() || n < 2 {
            return self.first;
        }
        self.first + (self.last - self.first) * (k as f64 / (n - 1) as f64)
    }

    /// Whether `other` is this zero to within rounding (1e-9 of the larger
    /// end): two offsets added up may differ from one in the last place.
    pub fn agrees_with(&self, other: Baseline) -> bool {
        let scale = self.largest().max(other.largest());
        (self.first - other.first).abs() <= 1e-9 * scale
            && (self.last - other.last).abs() <= 1e-9 * scale
    }

    /// The larger of the two ends in size.
    pub fn largest(&self) -> f64 {
        self.first.abs().max(self.last.abs())
    }
}

impl std::ops::Add for Baseline {
    type Output = Baseline;

    /// Two zeros taken off one after the other.
    fn add(self, other: Baseline) -> Baseline {
        Baseline::line(self.first + other.first, self.last + other.last)
    }
}

impl From<f64> for Baseline {
    fn from(value: f64) -> Self {
        Baseline::line(value, value)
    }
}

impl fmt::Display for Baseline {
    /// `VALUE` for a constant, `FIRST..LAST` for a line: what `--subtract`
    /// reads.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // `-0` prints as `0`.
        let (first, last) = (self.first + 0.0, self.last + 0.0);
        if self.is_constant() {
            write!(f, "{first}")
        } else {
            write!(f, "{first}..{last}")
        }
    }
}

/// Why a text is not a [`Baseline`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BaselineError(String);

impl fmt::Display for BaselineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BaselineError {}

impl FromStr for Baseline {
    type Err = BaselineError;

    /// `VALUE` or `FIRST..LAST`, finite numbers.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let number = |part: &str| {
            let value: f64 = part
                .trim()
                .parse()
                .map_err(|_| BaselineError(format!("`{part}` is not a number")))?;
            if value.is_finite() {
                Ok(value)
            } else {
                Err(BaselineError(format!("`{part}` is not a finite number")))
            }
        };
        if text.contains("...") {
            return Err(BaselineError(format!(
                "`{text}` has three dots: expected FIRST..LAST"
            )));
        }
        let end = |part: &str, which: &str| {
            if part.trim().is_empty() {
                Err(BaselineError(format!(
                    "the value at the {which} sample is missing: expected FIRST..LAST"
                )))
            } else {
                number(part)
            }
        };
        match text.split_once("..") {
            Some((first, last)) => Ok(Baseline::line(end(first, "first")?, end(last, "last")?)),
            None => number(text).map(Baseline::from),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_reads_back_as_written_and_runs_through_its_ends() {
        for text in ["0.5", "-0.7", "1e-3..-2.5", "-0.0048..0.3661"] {
            let b: Baseline = text.parse().unwrap();
            assert_eq!(b.to_string().parse::<Baseline>().unwrap(), b, "{text}");
        }
        let b = Baseline::line(-1.0, 3.0);
        assert_eq!((b.at(0, 3), b.at(1, 3), b.at(2, 3)), (-1.0, 1.0, 3.0));
        assert_eq!(b.at(0, 1), -1.0);
        assert_eq!(b.largest(), 3.0);
        assert!(Baseline::from(2.0).is_constant());
        assert_eq!(Baseline::from(2.0).at(7, 10), 2.0);
        assert_eq!(Baseline::from(-0.0).to_string(), "0");
        assert_eq!(b + Baseline::from(1.0), Baseline::line(0.0, 4.0));
        let sum = Baseline::from(0.2) + Baseline::line(0.0, 0.7);
        assert_ne!(sum, Baseline::line(0.2, 0.9));
        assert!(sum.agrees_with(Baseline::line(0.2, 0.9)));
        assert!(!sum.agrees_with(Baseline::line(0.2, 0.9001)));
    }

    #[test]
    fn malformed_text_is_refused_with_the_part_at_fault() {
        let e = "0.1..x".parse::<Baseline>().unwrap_err().to_string();
        assert!(e.contains("`x` is not a number"), "{e}");
        let e = "..1".parse::<Baseline>().unwrap_err().to_string();
        assert!(
            e.contains("the value at the first sample is missing"),
            "{e}"
        );
        let e = "1..".parse::<Baseline>().unwrap_err().to_string();
        assert!(e.contains("the value at the last sample is missing"), "{e}");
        // Not 1 to 0.2 (found by review).
        let e = "1...2".parse::<Baseline>().unwrap_err().to_string();
        assert!(e.contains("three dots"), "{e}");
        let e = "inf".parse::<Baseline>().unwrap_err().to_string();
        assert!(e.contains("not a finite number"), "{e}");
        assert!("1..2..3".parse::<Baseline>().is_err());
    }
}
