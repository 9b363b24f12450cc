//! Colours, line dashes and fonts shared by every plot.
//!
//! The series colours are the Okabe–Ito palette (Okabe & Ito, *Color Universal
//! Design*, 2008), chosen so that the common forms of colour blindness still
//! tell them apart; its yellow is left out because it vanishes on white paper.
//! Measured data is always neutral grey so that models stand out over it.

use std::fmt;

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Colour(pub u8, pub u8, pub u8);

impl fmt::Display for Colour {
    /// `#rrggbb`, as SVG and CSS expect.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// Okabe–Ito blue.
pub const BLUE: Colour = Colour(0x00, 0x72, 0xb2);
/// Okabe–Ito vermillion.
pub const VERMILLION: Colour = Colour(0xd5, 0x5e, 0x00);
/// Okabe–Ito bluish green.
pub const GREEN: Colour = Colour(0x00, 0x9e, 0x73);
/// Okabe–Ito reddish purple.
pub const PURPLE: Colour = Colour(0xcc, 0x79, 0xa7);
/// Okabe–Ito orange.
pub const ORANGE: Colour = Colour(0xe6, 0x9f, 0x00);
/// Okabe–Ito sky blue.
pub const SKY: Colour = Colour(0x56, 0xb4, 0xe9);
/// Black, the palette's last entry.
pub const BLACK: Colour = Colour(0x00, 0x00, 0x00);
/// Measured data.
pub const MEASURED: Colour = Colour(0x8c, 0x8c, 0x8c);
/// Axis lines, tick labels and text.
pub const INK: Colour = Colour(0x22, 0x22, 0x22);
/// Grid lines.
pub const GRID: Colour = Colour(0xe4, 0xe4, 0xe4);
/// Shaded bands (cycles) behind data.
pub const BAND: Colour = Colour(0xf0, 0xf0, 0xf0);
/// Notes that warn about the data (skipped points).
pub const WARN: Colour = Colour(0xa0, 0x3c, 0x00);

/// Series colours in the order they are handed out.
pub const SERIES: [Colour; 7] = [BLUE, VERMILLION, GREEN, PURPLE, ORANGE, SKY, BLACK];

/// The `i`-th series colour, repeating after seven.
pub fn series(i: usize) -> Colour {
    SERIES[i % SERIES.len()]
}

/// SVG `stroke-dasharray` for the `i`-th series: solid for the first seven,
/// then dashed patterns so that an eighth series is not a repeat of the first.
pub fn dash(i: usize) -> Option<&'static str> {
    const DASHES: [&str; 3] = ["6 3", "2 3", "8 3 2 3"];
    match i / SERIES.len() {
        0 => None,
        k => Some(DASHES[(k - 1) % DASHES.len()]),
    }
}

/// The font stack of every text element (DejaVu Sans is what Debian ships).
pub const FONT_FAMILY: &str = "'DejaVu Sans', 'Helvetica Neue', Arial, sans-serif";
/// Tick labels, legend and notes.
pub const FONT_SMALL: f64 = 11.0;
/// Axis labels.
pub const FONT_LABEL: f64 = 12.0;
/// Panel titles.
pub const FONT_TITLE: f64 = 13.0;
/// Figure title.
pub const FONT_FIGURE: f64 = 15.0;

/// Width in pixels of `text` set in the sans font at `size` px.
///
/// An estimate from character classes (DejaVu Sans advances: digits 0.64 em,
/// lower case about 0.6 em, upper case about 0.7 em, narrow punctuation
/// 0.32 em); it errs wide so that layout leaves room rather than clipping.
pub fn text_width(text: &str, size: f64) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| match c {
            'i' | 'j' | 'l' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' => 0.32,
            ' ' | 'f' | 't' | 'r' | '(' | ')' | '[' | ']' | '-' => 0.42,
            'm' | 'w' | 'M' | 'W' | '%' | '\u{2014}' => 0.95,
            c if c.is_ascii_uppercase() => 0.72,
            c if c.is_ascii_digit() => 0.64,
            _ => 0.62,
        })
        .sum();
    em * size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_print_as_hex() {
        assert_eq!(BLUE.to_string(), "#0072b2");
        assert_eq!(series(7), BLUE);
        assert_eq!(dash(3), None);
        assert_eq!(dash(7), Some("6 3"));
    }

    #[test]
    fn palette_colours_are_distinct_from_measured_grey_and_white() {
        for c in SERIES {
            assert_ne!(c, MEASURED);
            assert_ne!(c, Colour(255, 255, 255));
        }
    }

    #[test]
    fn text_width_grows_with_text_and_size() {
        assert!(text_width("Force (kN)", 12.0) > text_width("Force", 12.0));
        assert!(text_width("10", 24.0) > text_width("10", 12.0));
        assert_eq!(text_width("", 12.0), 0.0);
    }
}
