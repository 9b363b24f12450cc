//! A self-contained HTML page: headings, paragraphs, tables and inline SVG
//! figures, with its CSS inline and no scripts or outside resources, so one
//! file can be mailed, archived or printed as it is.

use std::fmt::Write;
use std::io;
use std::path::Path;

use super::style;
use super::ticks::superscript;
use super::xml::escape;
use super::{Error, Figure};

/// A table cell: text (left-aligned) or a number (right-aligned when its
/// whole column is numeric).
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// Text as given.
    Text(String),
    /// A number and how it is written.
    Number(f64, String),
}

impl Cell {
    /// A number with `decimals` digits after the point.
    pub fn fixed(v: f64, decimals: usize) -> Self {
        let text = if v.is_finite() {
            format!("{v:.decimals$}").replace('-', "\u{2212}")
        } else {
            non_finite(v)
        };
        Self::Number(v, text)
    }
}

impl From<&str> for Cell {
    fn from(s: &str) -> Self {
        Self::Text(s.into())
    }
}

impl From<String> for Cell {
    fn from(s: String) -> Self {
        Self::Text(s)
    }
}

impl From<f64> for Cell {
    /// Four significant digits; powers of ten beyond 10⁻³ … 10⁶.
    fn from(v: f64) -> Self {
        Self::Number(v, significant(v, 4))
    }
}

impl From<usize> for Cell {
    fn from(v: usize) -> Self {
        Self::Number(v as f64, v.to_string())
    }
}

impl From<i64> for Cell {
    fn from(v: i64) -> Self {
        Self::Number(v as f64, v.to_string().replace('-', "\u{2212}"))
    }
}

fn non_finite(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v > 0.0 {
        "\u{221e}".into()
    } else {
        "\u{2212}\u{221e}".into()
    }
}

/// `v` to `digits` significant digits, in plain decimals for magnitudes from
/// 10⁻³ to below 10⁶ and as `m×10ⁿ` outside.
pub fn significant(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return non_finite(v);
    }
    if v == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    let e = v.abs().log10().floor() as i32;
    let s = if (-3..6).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        let m = v / 10f64.powi(e);
        // Rounding the mantissa can carry into the next power (9.9996 → 10.00).
        let (m, e) = if format!("{:.*}", digits - 1, m.abs()).starts_with("10") {
            (m / 10.0, e + 1)
        } else {
            (m, e)
        };
        format!("{m:.prec$}\u{00d7}10{}", superscript(e), prec = digits - 1)
    };
    s.replace('-', "\u{2212}")
}

/// A table with a header row, body rows of equal width, and a caption.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    caption: String,
    header: Vec<String>,
    rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these column headings.
    pub fn new<S: AsRef<str>>(header: &[S]) -> Self {
        Self {
            caption: String::new(),
            header: header.iter().map(|h| h.as_ref().to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Caption shown above the table.
    pub fn caption(&mut self, text: &str) -> &mut Self {
        self.caption = text.into();
        self
    }

    /// Add a row, which must have one cell per column.
    pub fn row(&mut self, cells: Vec<Cell>) -> Result<&mut Self, Error> {
        if cells.len() != self.header.len() {
            return Err(Error::Length {
                what: format!(
                    "cells in row {} of the table (one per column)",
                    self.rows.len() + 1
                ),
                expected: self.header.len(),
                found: cells.len(),
            });
        }
        self.rows.push(cells);
        Ok(self)
    }

    /// Whether column `c` holds numbers only.
    fn numeric(&self, c: usize) -> bool {
        !self.rows.is_empty() && self.rows.iter().all(|r| matches!(r[c], Cell::Number(..)))
    }
}

/// An HTML report under construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    title: String,
    body: String,
    sections: Vec<String>,
    figures: usize,
    tables: usize,
}

const CSS: &str = "
:root { color-scheme: light; }
body { font-family: FONT; color: #222; background: #fff; max-width: 1000px; margin: 2em auto; padding: 0 1.5em; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; margin-top: 1.8em; border-bottom: 1px solid #ddd; padding-bottom: 0.2em; }
h3 { font-size: 1.05em; margin-top: 1.4em; }
nav ol { padding-left: 1.4em; margin: 0.4em 0 1.2em; }
nav a { color: #0072b2; }
figure { margin: 1.2em 0; }
figure svg { display: block; max-width: 100%; height: auto; }
figcaption, caption { font-size: 0.92em; color: #444; text-align: left; padding: 0.3em 0; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.95em; }
th, td { padding: 0.25em 0.8em; border-bottom: 1px solid #e2e2e2; text-align: left; }
th { border-bottom: 2px solid #aaa; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
footer { margin-top: 3em; font-size: 0.85em; color: #777; }
@media print {
  body { max-width: none; margin: 0; padding: 0; }
  nav { display: none; }
  h2, h3 { break-after: avoid; }
  figure, table { break-inside: avoid; }
}
@page { margin: 15mm; }
";

impl Report {
    /// An empty report with a title.
    pub fn new(title: &str) -> Self {
        Self {
            title: title.into(),
            body: String::new(),
            sections: Vec::new(),
            figures: 0,
            tables: 0,
        }
    }

    /// Start a section (listed in the contents at the top).
    pub fn section(&mut self, heading: &str) -> &mut Self {
        self.sections.push(heading.into());
        let _ = writeln!(
            self.body,
            "<h2 id=\"s{}\">{}</h2>",
            self.sections.len(),
            escape(heading)
        );
        self
    }

    /// A smaller heading inside a section.
    pub fn subsection(&mut self, heading: &str) -> &mut Self {
        let _ = writeln!(self.body, "<h3>{}</h3>", escape(heading));
        self
    }

    /// A paragraph of plain text.
    pub fn paragraph(&mut self, text: &str) -> &mut Self {
        let _ = writeln!(self.body, "<p>{}</p>", escape(text));
        self
    }

    /// A numbered table; numeric columns are right-aligned.
    pub fn table(&mut self, t: &Table) -> &mut Self {
        self.tables += 1;
        let numeric: Vec<bool> = (0..t.header.len()).map(|c| t.numeric(c)).collect();
        let class = |c: usize| if numeric[c] { " class=\"num\"" } else { "" };
        let _ = write!(
            self.body,
            "<table id=\"t{n}\">\n<caption>Table {n}. {}</caption>\n<thead><tr>",
            escape(&t.caption),
            n = self.tables
        );
        for (c, h) in t.header.iter().enumerate() {
            let _ = write!(self.body, "<th{}>{}</th>", class(c), escape(h));
        }
        self.body.push_str("</tr></thead>\n<tbody>\n");
        for r in &t.rows {
            self.body.push_str("<tr>");
            for (c, cell) in r.iter().enumerate() {
                let text = match cell {
                    Cell::Text(s) | Cell::Number(_, s) => s,
                };
                let _ = write!(self.body, "<td{}>{}</td>", class(c), escape(text));
            }
            self.body.push_str("</tr>\n");
        }
        self.body.push_str("</tbody>\n</table>\n");
        self
    }

    /// A numbered figure drawn inline as SVG, with a caption below.
    pub fn figure(&mut self, fig: &Figure, caption: &str) -> &mut Self {
        self.figures += 1;
        let n = self.figures;
        let _ = write!(
            self.body,
            "<figure id=\"f{n}\">\n{}<figcaption>Figure {n}. {}</figcaption>\n</figure>\n",
            fig.to_svg_inline(&format!("f{n}")),
            escape(caption)
        );
        self
    }

    /// The whole page.
    pub fn to_html(&self) -> String {
        let mut out = String::with_capacity(self.body.len() + 4096);
        let _ = write!(
            out,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{t}</title>\n<style>{css}</style>\n</head>\n<body>\n<h1>{t}</h1>\n",
            t = escape(&self.title),
            css = CSS.replace("FONT", style::FONT_FAMILY),
        );
        if self.sections.len() > 1 {
            out.push_str("<nav><ol>\n");
            for (i, s) in self.sections.iter().enumerate() {
                let _ = writeln!(out, "<li><a href=\"#s{}\">{}</a></li>", i + 1, escape(s));
            }
            out.push_str("</ol></nav>\n");
        }
        out.push_str(&self.body);
        let _ = write!(
            out,
            "<footer>Written by hyst {}.</footer>\n</body>\n</html>\n",
            env!("CARGO_PKG_VERSION")
        );
        out
    }

    /// Write the page to `path`.
    pub fn write(&self, path: &Path) -> io::Result<()> {
        std::fs::write(path, self.to_html())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Axis, Panel, Series};

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.0123456, 4), "0.01235");
        assert_eq!(significant(-1234.6, 4), "\u{2212}1235");
        assert_eq!(significant(12.0, 4), "12.00");
        assert_eq!(significant(2.5e7, 3), "2.50×10⁷");
        assert_eq!(significant(9.99996e-5, 4), "1.000×10⁻⁴");
        assert_eq!(significant(f64::NAN, 4), "NaN");
        assert_eq!(significant(f64::NEG_INFINITY, 4), "\u{2212}\u{221e}");
    }

    #[test]
    fn rows_must_fill_every_column() {
        let mut t = Table::new(&["model", "NRMSE"]);
        assert!(t.row(vec!["bw".into(), 0.31.into()]).is_ok());
        let e = t.row(vec!["bwbn".into()]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "cells in row 2 of the table (one per column): expected 2, found 1"
        );
    }

    #[test]
    fn numeric_columns_are_right_aligned_and_text_escaped() {
        let mut t = Table::new(&["model", "params", "NRMSE"]);
        t.caption("Ladder <draft>");
        t.row(vec!["bw".into(), 5usize.into(), 0.3141.into()])
            .unwrap()
            .row(vec![
                "bw+pinching".into(),
                9usize.into(),
                Cell::fixed(0.1, 3),
            ])
            .unwrap();
        let mut r = Report::new("Fit & diagnosis");
        r.table(&t);
        let html = r.to_html();
        assert!(html.contains("<title>Fit &amp; diagnosis</title>"));
        assert!(html.contains("Table 1. Ladder &lt;draft&gt;"));
        assert!(html.contains("<th>model</th><th class=\"num\">params</th>"));
        assert!(html
            .contains("<td>bw+pinching</td><td class=\"num\">9</td><td class=\"num\">0.100</td>"));
    }

    #[test]
    fn page_is_self_contained() {
        let mut p = Panel::new(Axis::linear("x", ""), Axis::linear("y", ""));
        p.series(Series::line("a", &[0.0, 1.0], &[0.0, 1.0]).unwrap());
        let mut f = Figure::new(300.0, 200.0);
        f.panel(p);
        let mut r = Report::new("t");
        r.section("One")
            .paragraph("text")
            .section("Two")
            .figure(&f, "c")
            .figure(&f, "d");
        let html = r.to_html();
        for banned in [
            "http:", "https:", "<script", "<link", "src=", "url(http", "@import",
        ] {
            assert!(!html.contains(banned), "page contains {banned}");
        }
        // Two figures, two distinct clip-path ids.
        assert!(html.contains("id=\"f1-p0-clip\"") && html.contains("id=\"f2-p0-clip\""));
        assert!(html.contains("<a href=\"#s2\">Two</a>"));
    }
}
