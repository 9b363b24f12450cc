//! The legend: its entries, where it goes (an empty corner of the plot,
//! else a row above it, else a column beside it), and how it is drawn.

use std::fmt::Write;

use super::axes::{fitted, truncated, Layout};
use super::geometry::Rect;
use super::marks::{annotation_box, bar_rects, pixels, stroke};
use crate::report::figure::{Mark, Panel};
use crate::report::style::{self, Colour};

/// Things on the plot that a legend should not cover, in pixels.
#[derive(Default)]
pub(super) struct Obstacles {
    pub(super) segments: Vec<((f64, f64), (f64, f64))>,
    pub(super) points: Vec<(f64, f64)>,
    pub(super) boxes: Vec<Rect>,
}

impl Obstacles {
    pub(super) fn hits(&self, r: &Rect) -> usize {
        self.segments
            .iter()
            .filter(|(a, b)| r.crossed_by(*a, *b))
            .count()
            + self.points.iter().filter(|p| r.contains(**p)).count()
            + 10 * self.boxes.iter().filter(|b| b.overlaps(r)).count()
    }
}

/// A legend entry: swatch kind, colour, dash, name (shortened to `label`
/// when too long).
pub(super) struct Entry<'a> {
    pub(super) mark: Option<Mark>,
    pub(super) colour: Colour,
    pub(super) dash: Option<&'a str>,
    pub(super) radius: f64,
    pub(super) name: &'a str,
    pub(super) label: String,
}

pub(super) const LEGEND_ROW: f64 = 17.0;

pub(super) const LEGEND_SWATCH: f64 = 22.0;

/// The legend entries of a panel, names cut to `max` px.
pub(super) fn legend_entries(p: &Panel, max: f64) -> Vec<Entry<'_>> {
    if !p.legend {
        return Vec::new();
    }
    let label = |name: &str| truncated(name, style::FONT_SMALL, max).unwrap_or_else(|| name.into());
    let mut v: Vec<Entry> = p
        .series
        .iter()
        .filter(|s| !s.name.is_empty())
        .map(|s| Entry {
            mark: Some(s.mark),
            colour: s.colour,
            dash: s.dash.as_deref(),
            radius: s.radius,
            name: &s.name,
            label: label(&s.name),
        })
        .collect();
    v.extend(p.bars.iter().filter(|b| !b.name.is_empty()).map(|b| Entry {
        mark: None,
        colour: b.colour,
        dash: None,
        radius: 0.0,
        name: &b.name,
        label: label(&b.name),
    }));
    v
}

/// A legend laid out: the swatch position (left, row centre) of each entry
/// and the box around them all.
pub(super) struct Placed {
    pub(super) rect: Rect,
    pub(super) at: Vec<(f64, f64)>,
}

pub(super) fn entry_width(e: &Entry) -> f64 {
    LEGEND_SWATCH + style::text_width(&e.label, style::FONT_SMALL) + 6.0
}

/// Entries one under the other in a box whose top left is `(x, y)`.
pub(super) fn stacked(entries: &[Entry], x: f64, y: f64) -> Placed {
    let w = entries.iter().map(entry_width).fold(0.0, f64::max) + 12.0;
    Placed {
        rect: Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + entries.len() as f64 * LEGEND_ROW + 8.0,
        },
        at: (0..entries.len())
            .map(|i| (x + 6.0, y + 4.0 + (i as f64 + 0.5) * LEGEND_ROW))
            .collect(),
    }
}

/// Entries side by side from `(x, y)`, wrapping to a new row at `width`.
pub(super) fn in_rows(entries: &[Entry], x: f64, y: f64, width: f64) -> Placed {
    let (mut cx, mut row, mut right) = (x, 0.0, x);
    let mut at = Vec::new();
    for e in entries {
        let w = entry_width(e);
        if cx > x && cx + w > x + width {
            cx = x;
            row += 1.0;
        }
        at.push((cx, y + (row + 0.5) * LEGEND_ROW));
        cx += w + 12.0;
        right = f64::max(right, cx - 12.0);
    }
    Placed {
        rect: Rect {
            x0: x,
            y0: y,
            x1: right,
            y1: y + (row + 1.0) * LEGEND_ROW,
        },
        at,
    }
}

pub(super) fn obstacles(p: &Panel, l: &Layout) -> Obstacles {
    let mut o = Obstacles::default();
    for s in &p.series {
        let mut prev = None;
        for q in pixels(s, &s.y, l) {
            if s.mark == Mark::Scatter {
                o.points.extend(q);
            } else if let (Some(a), Some(b)) = (prev, q) {
                o.segments.push((a, b));
            }
            prev = q;
        }
        if s.mark == Mark::Area {
            let mut prev = None;
            for q in pixels(s, &s.y_low, l) {
                if let (Some(a), Some(b)) = (prev, q) {
                    o.segments.push((a, b));
                }
                prev = q;
            }
        }
    }
    for (b, rect) in bar_rects(p, l) {
        if b < p.bars.len() {
            o.boxes.push(rect);
        }
    }
    for a in &p.annotations {
        if let Some((r, _)) = annotation_box(a, l) {
            o.boxes.push(r);
        }
    }
    o
}

/// The top-left point of the inside corner where a legend box of `size`
/// covers the least data, and how much it covers there.
pub(super) fn least_covered_corner(
    size: (f64, f64),
    plot: &Rect,
    obstacles: &Obstacles,
) -> ((f64, f64), usize) {
    let (w, h) = size;
    let m = 6.0;
    [
        (plot.x0 + m, plot.y0 + m),
        (plot.x1 - m - w, plot.y0 + m),
        (plot.x0 + m, plot.y1 - m - h),
        (plot.x1 - m - w, plot.y1 - m - h),
    ]
    .into_iter()
    .map(|(x, y)| {
        let grown = Rect {
            x0: x - 3.0,
            y0: y - 3.0,
            x1: x + w + 3.0,
            y1: y + h + 3.0,
        };
        ((x, y), obstacles.hits(&grown))
    })
    .min_by_key(|(_, hits)| *hits)
    .unwrap_or(((plot.x0, plot.y0), 0))
}

pub(super) fn draw_legend(out: &mut String, entries: &[Entry], placed: &Placed) {
    let r = placed.rect;
    let _ = writeln!(
        out,
        "<g class=\"legend\"><rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" \
         fill=\"#ffffff\" fill-opacity=\"0.9\" stroke=\"{}\"/>",
        r.x0,
        r.y0,
        r.w(),
        r.h(),
        if placed.at.len() > 1 && placed.at[1].1 == placed.at[0].1 {
            "none"
        } else {
            "#cccccc"
        }
    );
    for (e, &(x0, y)) in entries.iter().zip(&placed.at) {
        let x1 = x0 + LEGEND_SWATCH - 4.0;
        match e.mark {
            Some(Mark::Line) => {
                let _ = writeln!(
                    out,
                    "<path d=\"M{x0:.1},{y:.1}H{x1:.1}\" {}/>",
                    stroke(e.colour, 2.0, e.dash, 1.0)
                );
                if e.radius > 0.0 {
                    let _ = writeln!(
                        out,
                        "<circle cx=\"{:.1}\" cy=\"{y:.1}\" r=\"{}\" fill=\"{}\"/>",
                        (x0 + x1) / 2.0,
                        e.radius.min(4.0),
                        e.colour
                    );
                }
            }
            Some(Mark::Scatter) => {
                let _ = writeln!(
                    out,
                    "<circle cx=\"{:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"{}\"/>",
                    (x0 + x1) / 2.0,
                    e.colour
                );
            }
            Some(Mark::Area) | None => {
                let opacity = if e.mark.is_some() { 0.35 } else { 1.0 };
                let _ = writeln!(
                    out,
                    "<rect x=\"{x0:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"10\" fill=\"{}\" fill-opacity=\"{opacity}\"/>",
                    y - 5.0,
                    x1 - x0,
                    e.colour
                );
            }
        }
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{y:.1}\" dy=\"0.35em\">{}</text>",
            x0 + LEGEND_SWATCH,
            fitted(
                e.name,
                style::FONT_SMALL,
                style::text_width(&e.label, style::FONT_SMALL)
            )
        );
    }
    out.push_str("</g>\n");
}
