//! The data marks: lines, dots, areas, bars, shaded bands, reference
//! lines and annotations, clipped to the plot.

use std::fmt::Write;

use super::axes::{fitted, Layout};
use super::geometry::Rect;
use crate::report::figure::{Anchor, Annotation, Mark, Orientation, Panel, Series};
use crate::report::style::{self, Colour};
use crate::report::xml::escape;

/// Pixel positions of a series' drawable points, `None` at gaps.
pub(super) fn pixels<'a>(
    s: &'a Series,
    ys: &'a [f64],
    l: &'a Layout,
) -> impl Iterator<Item = Option<(f64, f64)>> + 'a {
    s.x.iter()
        .zip(ys)
        .map(move |(&x, &y)| Some((l.xm.px(x)?, l.ym.px(y)?)))
}

pub(super) fn draw_bands(out: &mut String, p: &Panel, l: &Layout) {
    for b in &p.bands {
        let (Some(a), Some(c)) = (l.xm.px(b.from), l.xm.px(b.to)) else {
            continue;
        };
        let (a, c) = (
            a.min(c).clamp(l.plot.x0, l.plot.x1),
            a.max(c).clamp(l.plot.x0, l.plot.x1),
        );
        if c <= a {
            continue;
        }
        let _ = writeln!(
            out,
            "<rect x=\"{a:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"{}\"/>",
            l.plot.y0,
            c - a,
            l.plot.h(),
            style::BAND
        );
        if !b.label.is_empty() && style::text_width(&b.label, style::FONT_SMALL) + 4.0 < c - a {
            let _ = writeln!(
                out,
                "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" fill=\"#777777\">{}</text>",
                (a + c) / 2.0,
                l.plot.y0 + style::FONT_SMALL + 2.0,
                escape(&b.label)
            );
        }
    }
}

/// SVG stroke attributes shared by lines and legend swatches.
pub(super) fn stroke(colour: Colour, width: f64, dash: Option<&str>, opacity: f64) -> String {
    let mut s = format!(
        "stroke=\"{colour}\" stroke-width=\"{width}\" fill=\"none\" stroke-linejoin=\"round\""
    );
    if let Some(d) = dash {
        let _ = write!(s, " stroke-dasharray=\"{}\"", escape(d));
    }
    if opacity < 1.0 {
        let _ = write!(s, " stroke-opacity=\"{opacity}\"");
    }
    s
}

/// A polyline path through the points, broken at gaps; points that round to
/// the previous pixel are dropped.
pub(super) fn polyline(points: impl Iterator<Item = Option<(f64, f64)>>) -> String {
    let mut d = String::new();
    let mut last: Option<(i64, i64)> = None;
    let mut pen_down = false;
    for q in points {
        match q {
            None => pen_down = false,
            Some((x, y)) => {
                let key = ((x * 10.0).round() as i64, (y * 10.0).round() as i64);
                if pen_down && last == Some(key) {
                    continue;
                }
                let _ = write!(d, "{}{x:.1},{y:.1}", if pen_down { "L" } else { "M" });
                last = Some(key);
                pen_down = true;
            }
        }
    }
    d
}

/// Dots as one path of two half-circle arcs each.
pub(super) fn dots(points: impl Iterator<Item = (f64, f64)>, r: f64) -> String {
    let mut d = String::new();
    for (x, y) in points {
        let _ = write!(
            d,
            "M{:.1},{y:.1}a{r},{r} 0 1,0 {:.1},0a{r},{r} 0 1,0 {:.1},0",
            x - r,
            2.0 * r,
            -2.0 * r
        );
    }
    d
}

pub(super) fn draw_series(out: &mut String, s: &Series, l: &Layout) {
    let name = escape(&s.name);
    if s.mark == Mark::Line {
        let d = polyline(pixels(s, &s.y, l));
        if !d.is_empty() {
            let _ = writeln!(
                out,
                "<path class=\"line\" data-name=\"{name}\" d=\"{d}\" {}/>",
                stroke(s.colour, s.width, s.dash.as_deref(), s.opacity)
            );
        }
    }
    if s.radius > 0.0 {
        let d = dots(pixels(s, &s.y, l).flatten(), s.radius);
        if !d.is_empty() {
            let _ = writeln!(
                out,
                "<path class=\"dots\" data-name=\"{name}\" d=\"{d}\" fill=\"{}\" fill-opacity=\"{}\"/>",
                s.colour,
                if s.mark == Mark::Scatter {
                    0.8 * s.opacity
                } else {
                    s.opacity
                }
            );
        }
    }
}

pub(super) fn draw_area(out: &mut String, s: &Series, l: &Layout) {
    // One closed polygon per unbroken run of points.
    let hi: Vec<Option<(f64, f64)>> = pixels(s, &s.y, l).collect();
    let lo: Vec<Option<(f64, f64)>> = pixels(s, &s.y_low, l).collect();
    let mut d = String::new();
    let mut i = 0;
    while i < hi.len() {
        if hi[i].is_none() || lo[i].is_none() {
            i += 1;
            continue;
        }
        let start = i;
        while i < hi.len() && hi[i].is_some() && lo[i].is_some() {
            i += 1;
        }
        let run = hi[start..i]
            .iter()
            .chain(lo[start..i].iter().rev())
            .flatten();
        for (k, (x, y)) in run.enumerate() {
            let _ = write!(d, "{}{x:.1},{y:.1}", if k == 0 { "M" } else { "L" });
        }
        d.push('Z');
    }
    if !d.is_empty() {
        let _ = writeln!(
            out,
            "<path class=\"area\" data-name=\"{}\" d=\"{d}\" fill=\"{}\" fill-opacity=\"{}\" stroke=\"none\"/>",
            escape(&s.name),
            s.colour,
            s.opacity
        );
    }
}

/// Rectangles of every drawable bar, tagged with the index of its bar set.
pub(super) fn bar_rects(p: &Panel, l: &Layout) -> Vec<(usize, Rect)> {
    let n = p.bars.len();
    if n == 0 {
        return Vec::new();
    }
    let unit = (l.xm.px(1.0).unwrap_or(0.0) - l.xm.px(0.0).unwrap_or(0.0)).abs();
    let group = 0.8 * unit;
    let w = group / n as f64;
    let base = if l.ym.log {
        l.plot.y1
    } else {
        l.ym.px(0.0)
            .unwrap_or(l.plot.y1)
            .clamp(l.plot.y0, l.plot.y1)
    };
    let mut rects = Vec::new();
    for (b, bars) in p.bars.iter().enumerate() {
        for (i, &v) in bars.values.iter().enumerate() {
            let (Some(xc), Some(y)) = (l.xm.px(i as f64), v.and_then(|v| l.ym.px(v))) else {
                continue;
            };
            let x0 = xc - group / 2.0 + b as f64 * w;
            rects.push((
                b,
                Rect {
                    x0,
                    y0: y.min(base),
                    x1: x0 + w * 0.92,
                    y1: y.max(base),
                },
            ));
        }
    }
    rects
}

pub(super) fn draw_bars(out: &mut String, p: &Panel, l: &Layout) {
    let rects = bar_rects(p, l);
    for (b, bars) in p.bars.iter().enumerate() {
        let mut d = String::new();
        for (_, r) in rects.iter().filter(|(k, _)| *k == b) {
            let _ = write!(
                d,
                "M{:.1},{:.1}H{:.1}V{:.1}H{:.1}Z",
                r.x0, r.y0, r.x1, r.y1, r.x0
            );
        }
        if !d.is_empty() {
            let _ = writeln!(
                out,
                "<path class=\"bars\" data-name=\"{}\" d=\"{d}\" fill=\"{}\"/>",
                escape(&bars.name),
                bars.colour
            );
        }
    }
}

pub(super) fn draw_refs(out: &mut String, p: &Panel, l: &Layout) {
    for r in &p.refs {
        let (d, tx, ty, anchor) = match r.orientation {
            Orientation::Horizontal => {
                let Some(y) =
                    l.ym.px(r.value)
                        .filter(|y| *y >= l.plot.y0 && *y <= l.plot.y1)
                else {
                    continue;
                };
                (
                    format!("M{:.1},{y:.1}H{:.1}", l.plot.x0, l.plot.x1),
                    l.plot.x1 - 4.0,
                    y - 4.0,
                    "end",
                )
            }
            Orientation::Vertical => {
                let Some(x) =
                    l.xm.px(r.value)
                        .filter(|x| *x >= l.plot.x0 && *x <= l.plot.x1)
                else {
                    continue;
                };
                (
                    format!("M{x:.1},{:.1}V{:.1}", l.plot.y0, l.plot.y1),
                    x + 4.0,
                    l.plot.y0 + style::FONT_SMALL + 2.0,
                    "start",
                )
            }
        };
        let _ = writeln!(
            out,
            "<path class=\"ref\" d=\"{d}\" stroke=\"#555555\" stroke-width=\"1\" stroke-dasharray=\"5 4\" fill=\"none\"/>"
        );
        if !r.label.is_empty() {
            let _ = writeln!(
                out,
                "<text x=\"{tx:.1}\" y=\"{ty:.1}\" text-anchor=\"{anchor}\" fill=\"#555555\" \
                 stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">{}</text>",
                fitted(&r.label, style::FONT_SMALL, l.plot.w() - 8.0)
            );
        }
    }
}

pub(super) fn anchor_name(a: Anchor) -> &'static str {
    match a {
        Anchor::Start => "start",
        Anchor::Middle => "middle",
        Anchor::End => "end",
    }
}

/// The box an annotation's text takes, moved inside the plot where it
/// would stick out, and the text's anchor point.
pub(super) fn annotation_box(a: &Annotation, l: &Layout) -> Option<(Rect, (f64, f64))> {
    let (x, y) = (l.xm.px(a.x)?, l.ym.px(a.y)?);
    if !l.plot.contains((x, y)) {
        return None;
    }
    let w = style::text_width(&a.text, style::FONT_SMALL).min(l.plot.w() - 4.0);
    let h = style::FONT_SMALL;
    let (mut tx, mut ty) = (x + a.dx, y + a.dy);
    let mut x0 = match a.anchor {
        Anchor::Start => tx,
        Anchor::Middle => tx - w / 2.0,
        Anchor::End => tx - w,
    };
    // Keep the text inside the plot rectangle.
    let shift = (l.plot.x0 + 2.0 - x0).max(0.0) - (x0 + w - l.plot.x1 + 2.0).max(0.0);
    x0 += shift;
    tx += shift;
    if ty - h < l.plot.y0 {
        ty = y + h + 6.0;
    }
    if ty > l.plot.y1 - 2.0 {
        ty = y - 8.0;
    }
    Some((
        Rect {
            x0,
            y0: ty - h,
            x1: x0 + w,
            y1: ty + 3.0,
        },
        (tx, ty),
    ))
}

pub(super) fn draw_annotations(out: &mut String, p: &Panel, l: &Layout) {
    let mut placed: Vec<Rect> = Vec::new();
    for a in &p.annotations {
        let Some((mut r, (tx, mut ty))) = annotation_box(a, l) else {
            continue;
        };
        // Step away from texts already placed: up first, then down.
        let step = style::FONT_SMALL + 3.0;
        for k in [0.0, -1.0, 1.0, -2.0, 2.0, -3.0, 3.0] {
            let moved = Rect {
                y0: r.y0 + k * step,
                y1: r.y1 + k * step,
                ..r
            };
            if !placed.iter().any(|q| q.overlaps(&moved)) {
                r = moved;
                ty += k * step;
                break;
            }
        }
        placed.push(r);
        if a.ring {
            if let (Some(x), Some(y)) = (l.xm.px(a.x), l.ym.px(a.y)) {
                let _ = writeln!(
                    out,
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"7\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>",
                    a.colour
                );
            }
        }
        let _ = writeln!(
            out,
            "<text class=\"annotation\" x=\"{tx:.1}\" y=\"{ty:.1}\" text-anchor=\"{}\" fill=\"{}\" \
             stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">{}</text>",
            anchor_name(a.anchor),
            a.colour,
            fitted(&a.text, style::FONT_SMALL, l.plot.w() - 4.0)
        );
    }
}
