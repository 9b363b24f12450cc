//! Drawing a [`Figure`] as SVG: layout of panels, axis ranges and ticks,
//! data paths clipped to the plot area, and a legend placed where it hides
//! the least data.

use std::fmt::Write;

use super::figure::{Anchor, Axis, Figure, Mark, Orientation, Panel, Scale, Series};
use super::style::{self, Colour};
use super::ticks::{self, Ticks};
use super::xml::escape;

/// Pixel coordinates are kept inside this box so that a point far outside
/// fixed axis limits cannot produce absurd numbers in the file.
const FAR: f64 = 1e5;

impl Figure {
    /// A standalone SVG document (XML declaration, `xmlns`), for `.svg` files.
    pub fn to_svg(&self) -> String {
        let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        self.render(&mut out, "fig", true);
        out
    }

    /// An `<svg>` element to place inside an HTML page. `id` prefixes every
    /// element id in it, so several figures can share a page; it is reduced
    /// to ASCII letters, digits, `-` and `_`.
    pub fn to_svg_inline(&self, id: &str) -> String {
        let id: String = id
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '_')
            .collect();
        let id = if id.is_empty() { "fig".into() } else { id };
        let mut out = String::new();
        self.render(&mut out, &id, false);
        out
    }

    fn render(&self, out: &mut String, id: &str, standalone: bool) {
        let (w, h) = (self.width, self.height);
        let xmlns = if standalone {
            " xmlns=\"http://www.w3.org/2000/svg\""
        } else {
            ""
        };
        let _ = write!(
            out,
            "<svg{xmlns} width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\" \
             aria-label=\"{t}\" font-family=\"{f}\" font-size=\"{s}\" fill=\"{ink}\">\n",
            t = escape(&self.title),
            f = style::FONT_FAMILY,
            s = style::FONT_SMALL,
            ink = style::INK,
        );
        if !self.title.is_empty() {
            let _ = writeln!(out, "<title>{}</title>", escape(&self.title));
        }
        let _ = writeln!(out, "<rect width=\"{w}\" height=\"{h}\" fill=\"#ffffff\"/>");
        let top = if self.title.is_empty() {
            0.0
        } else {
            let _ = writeln!(
                out,
                "<text x=\"{x}\" y=\"20\" text-anchor=\"middle\" font-size=\"{s}\" \
                 font-weight=\"bold\">{t}</text>",
                x = w / 2.0,
                s = style::FONT_FIGURE,
                t = escape(&self.title),
            );
            28.0
        };
        if self.panels.is_empty() {
            let _ = writeln!(
                out,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{}\">No panels to show</text>",
                w / 2.0,
                (top + h) / 2.0,
                style::WARN
            );
        }
        let columns = self.columns.min(self.panels.len()).max(1);
        let rows = self.panels.len().div_ceil(columns).max(1);
        let (cw, ch) = (w / columns as f64, (h - top) / rows as f64);
        let cell = |i: usize| Rect {
            x0: (i % columns) as f64 * cw,
            y0: top + (i / columns) as f64 * ch,
            x1: (i % columns + 1) as f64 * cw,
            y1: top + (i / columns + 1) as f64 * ch,
        };
        // Plan every panel alone, then again with the margins of its row
        // (top) and column (left, right) so that plot edges line up.
        let alone: Vec<Plan> = (0..self.panels.len())
            .map(|i| plan(&self.panels[i], cell(i), Margins::default()))
            .collect();
        let used: Vec<Margins> = alone.iter().map(|q| q.l.margins).collect();
        for (i, p) in self.panels.iter().enumerate() {
            let min = aligned(&used, columns, i);
            draw_panel(out, &plan(p, cell(i), min), &format!("{id}-p{i}"));
        }
        out.push_str("</svg>\n");
    }
}

/// The margins panel `i` needs to line up with its row (top) and its column
/// (left, right), given the margins each panel used alone.
fn aligned(used: &[Margins], columns: usize, i: usize) -> Margins {
    let mut m = Margins::default();
    for (j, u) in used.iter().enumerate() {
        if j % columns == i % columns {
            m.left = m.left.max(u.left);
            m.right = m.right.max(u.right);
        }
        if j / columns == i / columns {
            m.top = m.top.max(u.top);
        }
    }
    m
}

/// An axis-aligned rectangle in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn w(&self) -> f64 {
        self.x1 - self.x0
    }

    fn h(&self) -> f64 {
        self.y1 - self.y0
    }

    fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }

    fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether the segment `a`–`b` passes through this rectangle
    /// (Liang–Barsky clipping).
    fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// Maps data values on one axis to pixels.
#[derive(Debug, Clone, Copy)]
struct Map {
    lo: f64,
    hi: f64,
    p0: f64,
    p1: f64,
    log: bool,
}

impl Map {
    /// Pixel position of `v`, or `None` where the scale cannot show it.
    fn px(&self, v: f64) -> Option<f64> {
        if !v.is_finite() || (self.log && v <= 0.0) {
            return None;
        }
        let t = if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            // Halves keep `hi - lo` finite near f64::MAX.
            (v / 2.0 - self.lo / 2.0) / (self.hi / 2.0 - self.lo / 2.0)
        };
        Some((self.p0 + t * (self.p1 - self.p0)).clamp(-FAR, FAR))
    }
}

/// Data values the panel puts on each axis, and what could not be shown.
struct Extent {
    xs: Vec<f64>,
    ys: Vec<f64>,
    notes: Vec<String>,
}

/// Gathers every value that should be inside the axis ranges, counting the
/// points that cannot be drawn so that the panel can say so.
fn extent(p: &Panel) -> Extent {
    let xlog = p.x.scale == Scale::Log;
    let ylog = p.y.scale == Scale::Log;
    let ok = |v: f64, log: bool| v.is_finite() && (!log || v > 0.0);
    let mut e = Extent {
        xs: Vec::new(),
        ys: Vec::new(),
        notes: Vec::new(),
    };
    for s in &p.series {
        let (mut non_finite, mut non_positive) = (0usize, 0usize);
        for i in 0..s.x.len() {
            let mut ys = vec![s.y[i]];
            if s.mark == Mark::Area {
                ys.push(s.y_low[i]);
            }
            let vals = std::iter::once((s.x[i], xlog)).chain(ys.iter().map(|&y| (y, ylog)));
            if vals.clone().any(|(v, _)| !v.is_finite()) {
                non_finite += 1;
            } else if vals.clone().any(|(v, log)| !ok(v, log)) {
                non_positive += 1;
            } else {
                e.xs.push(s.x[i]);
                e.ys.extend(ys);
            }
        }
        let name = if s.name.is_empty() {
            String::new()
        } else {
            format!(" of '{}'", s.name)
        };
        if non_finite > 0 {
            e.notes.push(format!(
                "{non_finite} point{} with NaN or infinite values{name} not drawn.",
                plural(non_finite)
            ));
        }
        if non_positive > 0 {
            e.notes.push(format!(
                "{non_positive} point{}{name} at or below zero not drawn on the log axis.",
                plural(non_positive)
            ));
        }
    }
    for b in &p.bars {
        let values = b.values.iter().flatten().copied();
        let skipped = values.clone().filter(|v| !ok(*v, ylog)).count();
        e.ys.extend(values.filter(|v| ok(*v, ylog)));
        if !ylog {
            e.ys.push(0.0);
        }
        if !b.values.is_empty() {
            e.xs.push(-0.5);
            e.xs.push(b.values.len() as f64 - 0.5);
        }
        if skipped > 0 {
            e.notes.push(format!(
                "{skipped} bar{} of '{}' not drawn (not a finite{} value).",
                plural(skipped),
                b.name,
                if ylog { " positive" } else { "" }
            ));
        }
    }
    for r in &p.refs {
        let (vals, log) = match r.orientation {
            Orientation::Horizontal => (&mut e.ys, ylog),
            Orientation::Vertical => (&mut e.xs, xlog),
        };
        if ok(r.value, log) {
            vals.push(r.value);
        }
    }
    for b in &p.bands {
        e.xs.extend([b.from, b.to].into_iter().filter(|v| ok(*v, xlog)));
    }
    for a in &p.annotations {
        if ok(a.x, xlog) && ok(a.y, ylog) {
            e.xs.push(a.x);
            e.ys.push(a.y);
        }
    }
    if !p.x.categories.is_empty() {
        e.xs.push(-0.5);
        e.xs.push(p.x.categories.len() as f64 - 0.5);
    }
    e
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The range an axis shows: fixed limits if valid, else the data's range
/// padded by 4% (not past zero when the data stops at zero), never of zero
/// width. Explains in `notes` what it could not honour.
fn range(axis: &Axis, data: &[f64], notes: &mut Vec<String>) -> (f64, f64) {
    let log = axis.scale == Scale::Log;
    if let Some((lo, hi)) = axis.limits {
        if lo.is_finite() && hi.is_finite() && lo < hi && (!log || lo > 0.0) {
            return (lo, hi);
        }
        notes.push(format!(
            "Limits {lo}..{hi} of axis '{}' not used (expected finite lower < upper{}).",
            axis.label,
            if log { ", lower > 0 on a log axis" } else { "" }
        ));
    }
    let (mut lo, mut hi) = data
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    if axis.include_zero && !log {
        lo = lo.min(0.0);
        hi = hi.max(0.0);
    }
    if lo > hi {
        if !notes.iter().any(|n| n.starts_with("No data")) {
            notes.push("No data to show.".into());
        }
        return if log { (1.0, 10.0) } else { (0.0, 1.0) };
    }
    let magnitude = lo.abs().max(hi.abs());
    if hi / 2.0 - lo / 2.0 <= 0.5e-12 * magnitude {
        let v = lo / 2.0 + hi / 2.0;
        return if log {
            (v / 2.0, v * 2.0)
        } else if v == 0.0 {
            (-1.0, 1.0)
        } else {
            (v - 0.1 * v.abs(), v + 0.1 * v.abs())
        };
    }
    if log {
        let pad = 10f64.powf(0.04 * (hi / lo).log10());
        (lo / pad, hi * pad)
    } else {
        let pad = 0.08 * (hi / 2.0 - lo / 2.0);
        let lo = if lo == 0.0 { 0.0 } else { lo - pad };
        let hi = if hi == 0.0 { 0.0 } else { hi + pad };
        (lo.max(-f64::MAX), hi.min(f64::MAX))
    }
}

/// Ticks for an axis over `lo..hi`: category names, or about `target` numbers.
fn resolve(axis: &Axis, lo: f64, hi: f64, target: usize) -> Ticks {
    if !axis.categories.is_empty() {
        Ticks {
            values: (0..axis.categories.len()).map(|i| i as f64).collect(),
            labels: axis.categories.clone(),
            exponent: 0,
        }
    } else if axis.scale == Scale::Log {
        ticks::log(lo, hi, target)
    } else {
        ticks::linear(lo, hi, target)
    }
}

/// `Force (×10³ kN)`: label, the factored-out power of ten, and the unit.
fn axis_title(axis: &Axis, exponent: i32) -> String {
    let factor = if exponent == 0 {
        String::new()
    } else {
        format!("\u{00d7}10{}", ticks::superscript(exponent))
    };
    let inside = match (factor.is_empty(), axis.unit.is_empty()) {
        (true, true) => return axis.label.clone(),
        (true, false) => axis.unit.clone(),
        (false, true) => factor,
        (false, false) => format!("{factor} {}", axis.unit),
    };
    format!("{} ({inside})", axis.label)
}

fn widest(labels: &[String]) -> f64 {
    labels
        .iter()
        .map(|l| style::text_width(l, style::FONT_SMALL))
        .fold(0.0, f64::max)
}

/// How the x tick labels are set.
#[derive(Debug, Clone, Copy, PartialEq)]
struct XLabels {
    /// Label every `every`-th tick.
    every: usize,
    /// Rotate labels by -35° (long category names).
    rotated: bool,
}

const ROTATION_DEG: f64 = 35.0;

/// Chooses x ticks that fit between pixels `x0` and `x1`: fewer ticks on
/// numeric axes, rotated (and if need be thinned) labels on categorical ones.
fn x_ticks(axis: &Axis, lo: f64, hi: f64, x0: f64, x1: f64) -> (Ticks, XLabels) {
    let map = Map {
        lo,
        hi,
        p0: x0,
        p1: x1,
        log: axis.scale == Scale::Log,
    };
    let mut target = (((x1 - x0) / 90.0) as usize).clamp(2, 12);
    loop {
        let r = resolve(axis, lo, hi, target);
        let px: Vec<f64> = r.values.iter().filter_map(|&v| map.px(v)).collect();
        let spacing = px
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(x1 - x0, f64::min);
        let need = widest(&r.labels) + 10.0;
        if need <= spacing {
            return (
                r,
                XLabels {
                    every: 1,
                    rotated: false,
                },
            );
        }
        if !axis.categories.is_empty() {
            // Rotated labels need only a line height across the slant.
            let row = 1.3 * style::FONT_SMALL / ROTATION_DEG.to_radians().sin();
            let every = (row / spacing.max(1.0)).ceil().max(1.0) as usize;
            return (
                r,
                XLabels {
                    every,
                    rotated: true,
                },
            );
        }
        if target <= 2 {
            let every = (need / spacing.max(1.0)).ceil().max(1.0) as usize;
            return (
                r,
                XLabels {
                    every,
                    rotated: false,
                },
            );
        }
        target -= 1;
    }
}

/// Things on the plot that a legend should not cover, in pixels.
#[derive(Default)]
struct Obstacles {
    segments: Vec<((f64, f64), (f64, f64))>,
    points: Vec<(f64, f64)>,
    boxes: Vec<Rect>,
}

impl Obstacles {
    fn hits(&self, r: &Rect) -> usize {
        self.segments
            .iter()
            .filter(|(a, b)| r.crossed_by(*a, *b))
            .count()
            + self.points.iter().filter(|p| r.contains(**p)).count()
            + 10 * self.boxes.iter().filter(|b| b.overlaps(r)).count()
    }
}

/// A legend entry: swatch kind, colour, dash, name.
struct Entry<'a> {
    mark: Option<Mark>,
    colour: Colour,
    dash: Option<&'a str>,
    radius: f64,
    name: &'a str,
}

const LEGEND_ROW: f64 = 17.0;
const LEGEND_SWATCH: f64 = 22.0;

fn legend_entries(p: &Panel) -> Vec<Entry<'_>> {
    if !p.legend {
        return Vec::new();
    }
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
        })
        .collect();
    v.extend(p.bars.iter().filter(|b| !b.name.is_empty()).map(|b| Entry {
        mark: None,
        colour: b.colour,
        dash: None,
        radius: 0.0,
        name: &b.name,
    }));
    v
}

/// A legend laid out: the swatch position (left, row centre) of each entry
/// and the box around them all.
struct Placed {
    rect: Rect,
    at: Vec<(f64, f64)>,
}

fn entry_width(e: &Entry) -> f64 {
    LEGEND_SWATCH + style::text_width(e.name, style::FONT_SMALL) + 6.0
}

/// Entries one under the other in a box whose top left is `(x, y)`.
fn stacked(entries: &[Entry], x: f64, y: f64) -> Placed {
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
fn in_rows(entries: &[Entry], x: f64, y: f64, width: f64) -> Placed {
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

/// Layout of one panel: plot rectangle, axis maps and ticks.
struct Layout {
    plot: Rect,
    xm: Map,
    ym: Map,
    xt: Ticks,
    yt: Ticks,
    xl: XLabels,
    /// The margins used.
    margins: Margins,
}

/// Height taken below the plot by tick labels, axis title and notes.
fn bottom_margin(notes: usize, rotated_extra: f64) -> f64 {
    style::FONT_SMALL
        + 10.0
        + style::FONT_LABEL
        + 12.0
        + notes as f64 * (style::FONT_SMALL + 4.0)
        + rotated_extra
}

/// Room around the plot: left for the y axis, right and top for a legend
/// (below the panel title), in pixels.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Margins {
    left: f64,
    right: f64,
    top: f64,
}

impl Margins {
    /// Each side at least as wide as in `other`.
    fn max(self, other: Self) -> Self {
        Self {
            left: self.left.max(other.left),
            right: self.right.max(other.right),
            top: self.top.max(other.top),
        }
    }
}

/// Space right of the plot when no legend is there.
const RIGHT_PAD: f64 = 16.0;

/// Lays out a panel in `cell` for the axis ranges `xr` and `yr`, with at
/// least the margins `min` and room for `notes` lines below.
fn layout(
    p: &Panel,
    cell: Rect,
    (xr, yr): ((f64, f64), (f64, f64)),
    notes: usize,
    min: Margins,
) -> Layout {
    let right = min.right.max(RIGHT_PAD);
    let top = cell.y0 + min.top + if p.title.is_empty() { 12.0 } else { 30.0 };
    let mut extra = 0.0;
    let mut left: f64 = min.left;
    // The y tick labels set the left margin, which sets the plot width, which
    // decides whether x labels must rotate, which sets the plot height: two
    // passes settle it.
    let mut pass = || {
        let bottom = bottom_margin(notes, extra);
        let plot_h = (cell.y1 - bottom - top).max(20.0);
        let y = resolve(&p.y, yr.0, yr.1, ((plot_h / 45.0) as usize).clamp(2, 10));
        left = left.max(widest(&y.labels) + 8.0 + style::FONT_LABEL + 14.0);
        let (x0, x1) = (cell.x0 + left, (cell.x1 - right).max(cell.x0 + left + 20.0));
        let (x, xl) = x_ticks(&p.x, xr.0, xr.1, x0, x1);
        let plot = Rect {
            x0,
            y0: top,
            x1,
            y1: top + plot_h,
        };
        let needed = if xl.rotated {
            widest(&x.labels) * ROTATION_DEG.to_radians().sin()
        } else {
            0.0
        };
        let settled = needed <= extra;
        extra = extra.max(needed);
        (plot, x, y, xl, settled)
    };
    let (mut plot, mut xres, mut yres, mut xl, settled) = pass();
    if !settled {
        (plot, xres, yres, xl, _) = pass();
    }
    let xm = Map {
        lo: xr.0,
        hi: xr.1,
        p0: plot.x0,
        p1: plot.x1,
        log: p.x.scale == Scale::Log,
    };
    let ym = Map {
        lo: yr.0,
        hi: yr.1,
        p0: plot.y1,
        p1: plot.y0,
        log: p.y.scale == Scale::Log,
    };
    Layout {
        plot,
        xm,
        ym,
        xt: xres,
        yt: yres,
        xl,
        margins: Margins {
            left,
            right,
            top: min.top,
        },
    }
}

/// Pixel positions of a series' drawable points, `None` at gaps.
fn pixels<'a>(
    s: &'a Series,
    ys: &'a [f64],
    l: &'a Layout,
) -> impl Iterator<Item = Option<(f64, f64)>> + 'a {
    s.x.iter()
        .zip(ys)
        .map(move |(&x, &y)| Some((l.xm.px(x)?, l.ym.px(y)?)))
}

fn obstacles(p: &Panel, l: &Layout) -> Obstacles {
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
fn least_covered_corner(
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

/// Everything decided about a panel before it is drawn.
struct Plan<'a> {
    p: &'a Panel,
    cell: Rect,
    notes: Vec<String>,
    entries: Vec<Entry<'a>>,
    legend: Option<Placed>,
    l: Layout,
}

/// Ranges, notes, layout and legend place of a panel in `cell`, with at
/// least the margins `min`.
fn plan(p: &Panel, cell: Rect, min: Margins) -> Plan<'_> {
    let ext = extent(p);
    let mut notes = ext.notes;
    let ranges = (
        range(&p.x, &ext.xs, &mut notes),
        range(&p.y, &ext.ys, &mut notes),
    );
    notes.extend(p.notes.iter().cloned());
    let entries = legend_entries(p);
    let mut l = layout(p, cell, ranges, notes.len(), min);
    let mut legend = None;
    if !entries.is_empty() {
        let stack = stacked(&entries, 0.0, 0.0);
        let (w, h) = (stack.rect.w(), stack.rect.h());
        let (corner, hits) = least_covered_corner((w, h), &l.plot, &obstacles(p, &l));
        let row = in_rows(&entries, 0.0, 0.0, l.plot.w());
        let rows = (row.rect.h() / LEGEND_ROW).round();
        legend = Some(if hits == 0 {
            stacked(&entries, corner.0, corner.1)
        } else if rows <= 2.0 {
            // A row or two of entries above the plot costs less than a column.
            let top = row.rect.h() + 4.0;
            let m = min.max(Margins { top, ..min });
            l = layout(p, cell, ranges, notes.len(), m);
            in_rows(&entries, l.plot.x0, l.plot.y0 - top, l.plot.w())
        } else if l.plot.w() - w - 12.0 >= 0.55 * cell.w() {
            let m = min.max(Margins {
                right: w + 24.0,
                ..min
            });
            l = layout(p, cell, ranges, notes.len(), m);
            stacked(&entries, l.plot.x1 + 12.0, l.plot.y0)
        } else {
            stacked(&entries, corner.0, corner.1)
        });
    }
    Plan {
        p,
        cell,
        notes,
        entries,
        legend,
        l,
    }
}

fn draw_panel(out: &mut String, plan: &Plan, id: &str) {
    let Plan {
        p,
        cell,
        notes,
        entries,
        legend,
        l,
    } = plan;
    let (p, cell, l) = (*p, *cell, l);
    let _ = writeln!(out, "<g class=\"panel\">");
    if !p.title.is_empty() {
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"{}\" font-weight=\"bold\">{}</text>",
            l.plot.x0,
            cell.y0 + 18.0,
            style::FONT_TITLE,
            escape(&p.title)
        );
    }
    let _ = writeln!(
        out,
        "<clipPath id=\"{id}-clip\"><rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\"/></clipPath>",
        l.plot.x0,
        l.plot.y0,
        l.plot.w(),
        l.plot.h()
    );
    draw_bands(out, p, &l);
    draw_grid(out, p, &l);
    let _ = writeln!(out, "<g clip-path=\"url(#{id}-clip)\">");
    for s in p.series.iter().filter(|s| s.mark == Mark::Area) {
        draw_area(out, s, &l);
    }
    draw_bars(out, p, &l);
    for s in p.series.iter().filter(|s| s.mark != Mark::Area) {
        draw_series(out, s, &l);
    }
    out.push_str("</g>\n");
    draw_refs(out, p, &l);
    draw_axes(out, p, &l);
    draw_annotations(out, p, &l);
    if let Some(placed) = legend {
        draw_legend(out, entries, placed);
    }
    let mut y = cell.y1 - 6.0 - (notes.len() as f64 - 1.0) * (style::FONT_SMALL + 4.0);
    for n in notes.iter() {
        let _ = writeln!(
            out,
            "<text class=\"note\" x=\"{:.1}\" y=\"{y:.1}\" fill=\"{}\">Note: {}</text>",
            cell.x0 + 8.0,
            style::WARN,
            escape(n)
        );
        y += style::FONT_SMALL + 4.0;
    }
    out.push_str("</g>\n");
}

fn draw_bands(out: &mut String, p: &Panel, l: &Layout) {
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

fn draw_grid(out: &mut String, p: &Panel, l: &Layout) {
    let mut d = String::new();
    if p.x.categories.is_empty() {
        for &v in &l.xt.values {
            if let Some(x) = l.xm.px(v) {
                let _ = write!(d, "M{x:.1},{:.1}V{:.1}", l.plot.y0, l.plot.y1);
            }
        }
    }
    for &v in &l.yt.values {
        if let Some(y) = l.ym.px(v) {
            let _ = write!(d, "M{:.1},{y:.1}H{:.1}", l.plot.x0, l.plot.x1);
        }
    }
    if !d.is_empty() {
        let _ = writeln!(
            out,
            "<path class=\"grid\" d=\"{d}\" stroke=\"{}\" stroke-width=\"1\" fill=\"none\"/>",
            style::GRID
        );
    }
}

/// SVG stroke attributes shared by lines and legend swatches.
fn stroke(colour: Colour, width: f64, dash: Option<&str>, opacity: f64) -> String {
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
fn polyline(points: impl Iterator<Item = Option<(f64, f64)>>) -> String {
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
fn dots(points: impl Iterator<Item = (f64, f64)>, r: f64) -> String {
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

fn draw_series(out: &mut String, s: &Series, l: &Layout) {
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

fn draw_area(out: &mut String, s: &Series, l: &Layout) {
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
fn bar_rects(p: &Panel, l: &Layout) -> Vec<(usize, Rect)> {
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

fn draw_bars(out: &mut String, p: &Panel, l: &Layout) {
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

fn draw_refs(out: &mut String, p: &Panel, l: &Layout) {
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
                "<text x=\"{tx:.1}\" y=\"{ty:.1}\" text-anchor=\"{anchor}\" fill=\"#555555\">{}</text>",
                escape(&r.label)
            );
        }
    }
}

fn anchor_name(a: Anchor) -> &'static str {
    match a {
        Anchor::Start => "start",
        Anchor::Middle => "middle",
        Anchor::End => "end",
    }
}

/// The box an annotation's text takes, moved inside the plot where it
/// would stick out, and the text's anchor point.
fn annotation_box(a: &super::figure::Annotation, l: &Layout) -> Option<(Rect, (f64, f64))> {
    let (x, y) = (l.xm.px(a.x)?, l.ym.px(a.y)?);
    if !l.plot.contains((x, y)) {
        return None;
    }
    let w = style::text_width(&a.text, style::FONT_SMALL);
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

fn draw_annotations(out: &mut String, p: &Panel, l: &Layout) {
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
            escape(&a.text)
        );
    }
}

fn draw_axes(out: &mut String, p: &Panel, l: &Layout) {
    let pl = &l.plot;
    let _ = writeln!(
        out,
        "<path class=\"axis\" d=\"M{:.1},{:.1}V{:.1}H{:.1}\" stroke=\"{}\" stroke-width=\"1\" fill=\"none\"/>",
        pl.x0,
        pl.y0,
        pl.y1,
        pl.x1,
        style::INK
    );
    // Ticks and labels.
    let mut marks = String::new();
    let mut labels = String::new();
    for (k, (&v, label)) in l.xt.values.iter().zip(&l.xt.labels).enumerate() {
        let Some(x) = l.xm.px(v) else { continue };
        let _ = write!(marks, "M{x:.1},{:.1}v4", pl.y1);
        if k % l.xl.every != 0 {
            continue;
        }
        let y = pl.y1 + 6.0 + style::FONT_SMALL;
        if l.xl.rotated {
            let _ = writeln!(
                labels,
                "<text class=\"tick\" x=\"{x:.1}\" y=\"{y:.1}\" text-anchor=\"end\" \
                 transform=\"rotate(-{ROTATION_DEG} {x:.1} {y:.1})\">{}</text>",
                escape(label)
            );
        } else {
            let _ = writeln!(
                labels,
                "<text class=\"tick\" x=\"{x:.1}\" y=\"{y:.1}\" text-anchor=\"middle\">{}</text>",
                escape(label)
            );
        }
    }
    for (&v, label) in l.yt.values.iter().zip(&l.yt.labels) {
        let Some(y) = l.ym.px(v) else { continue };
        let _ = write!(marks, "M{:.1},{y:.1}h-4", pl.x0);
        let _ = writeln!(
            labels,
            "<text class=\"tick\" x=\"{:.1}\" y=\"{y:.1}\" dy=\"0.35em\" text-anchor=\"end\">{}</text>",
            pl.x0 - 6.0,
            escape(label)
        );
    }
    let _ = writeln!(
        out,
        "<path class=\"ticks\" d=\"{marks}\" stroke=\"{}\" stroke-width=\"1\"/>",
        style::INK
    );
    out.push_str(&labels);
    // Axis titles.
    let x_extra = if l.xl.rotated {
        widest(&l.xt.labels) * ROTATION_DEG.to_radians().sin()
    } else {
        0.0
    };
    let _ = writeln!(
        out,
        "<text class=\"axis-label\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>",
        (pl.x0 + pl.x1) / 2.0,
        pl.y1 + 8.0 + style::FONT_SMALL + x_extra + style::FONT_LABEL + 6.0,
        style::FONT_LABEL,
        escape(&axis_title(&p.x, l.xt.exponent))
    );
    // At the left edge of the margin, so that aligned panels share it.
    let ylabel_x = pl.x0 - l.margins.left + 6.0 + style::FONT_LABEL / 2.0;
    let ymid = (pl.y0 + pl.y1) / 2.0;
    let _ = writeln!(
        out,
        "<text class=\"axis-label\" x=\"{ylabel_x:.1}\" y=\"{ymid:.1}\" text-anchor=\"middle\" \
         font-size=\"{}\" transform=\"rotate(-90 {ylabel_x:.1} {ymid:.1})\">{}</text>",
        style::FONT_LABEL,
        escape(&axis_title(&p.y, l.yt.exponent))
    );
}

fn draw_legend(out: &mut String, entries: &[Entry], placed: &Placed) {
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
            escape(e.name)
        );
    }
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    const CELL: Rect = Rect {
        x0: 0.0,
        y0: 0.0,
        x1: 640.0,
        y1: 480.0,
    };

    fn panel_with(series: Vec<Series>) -> Panel {
        let mut p = Panel::new(Axis::linear("u", "mm"), Axis::linear("F", "kN"));
        for s in series {
            p.series(s);
        }
        p
    }

    #[test]
    fn legend_avoids_a_loop_in_the_first_and_third_quadrants() {
        // An ellipse tilted along the diagonal, as a hysteresis loop is.
        let t: Vec<f64> = (0..400)
            .map(|i| i as f64 / 400.0 * std::f64::consts::TAU)
            .collect();
        let u: Vec<f64> = t.iter().map(|t| t.cos()).collect();
        let f: Vec<f64> = t.iter().map(|t| t.cos() + 0.3 * t.sin()).collect();
        let p = panel_with(vec![
            Series::line("measured", &u, &f).unwrap(),
            Series::line("model with a long name", &u, &f).unwrap(),
        ]);
        let plan = plan(&p, CELL, Margins::default());
        let legend = plan.legend.as_ref().expect("a legend");
        assert!(
            plan.l.plot.contains((legend.rect.x0, legend.rect.y0)),
            "legend inside the plot"
        );
        assert_eq!(obstacles(&p, &plan.l).hits(&legend.rect), 0);
    }

    #[test]
    fn legend_moves_above_data_that_fills_every_corner() {
        let mut seed = 1u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (x, y): (Vec<f64>, Vec<f64>) = (0..3000).map(|_| (next(), next())).unzip();
        let p = panel_with(vec![Series::scatter("noise", &x, &y).unwrap()]);
        let plan = plan(&p, CELL, Margins::default());
        let legend = plan.legend.as_ref().expect("a legend");
        assert!(legend.rect.y1 <= plan.l.plot.y0, "legend above the plot");
        assert!(plan.l.margins.top > 0.0);
    }

    #[test]
    fn ranges_pad_data_but_not_past_zero_and_never_collapse() {
        let mut notes = Vec::new();
        let lin = Axis::linear("x", "");
        assert_eq!(range(&lin, &[0.0, 10.0], &mut notes), (0.0, 10.4));
        assert_eq!(range(&lin, &[5.0, 5.0], &mut notes), (4.5, 5.5));
        assert_eq!(range(&lin, &[0.0], &mut notes), (-1.0, 1.0));
        let (lo, hi) = range(&lin, &[-f64::MAX, f64::MAX], &mut notes);
        assert!(lo.is_finite() && hi.is_finite() && lo < hi);
        assert!(notes.is_empty());
        assert_eq!(range(&lin, &[], &mut notes), (0.0, 1.0));
        assert_eq!(notes, ["No data to show."]);
        let log = Axis::log("y", "");
        let (lo, hi) = range(&log, &[0.01, 1.0], &mut notes);
        assert!((lo.log10() + 2.08).abs() < 1e-12 && (hi.log10() - 0.08).abs() < 1e-12);
    }

    #[test]
    fn bad_limits_are_reported_not_used() {
        let mut notes = Vec::new();
        let a = Axis::log("NRMSE", "").limits(0.0, 1.0);
        assert_eq!(
            range(&a, &[0.1, 0.5], &mut notes).1,
            0.5 * 10f64.powf(0.04 * 5f64.log10())
        );
        assert_eq!(notes.len(), 1);
        assert!(notes[0].contains("NRMSE"), "{notes:?}");
        let a = Axis::linear("x", "").limits(2.0, 1.0);
        range(&a, &[0.1, 0.5], &mut notes);
        assert_eq!(notes.len(), 2);
    }

    #[test]
    fn segment_crossing_is_exact_at_the_edges() {
        let r = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 10.0,
            y1: 10.0,
        };
        assert!(r.crossed_by((-5.0, 5.0), (15.0, 5.0)));
        assert!(r.crossed_by((5.0, 5.0), (6.0, 6.0)));
        assert!(!r.crossed_by((-5.0, -1.0), (15.0, -1.0)));
        assert!(!r.crossed_by((11.0, -5.0), (20.0, 5.0)));
        assert!(r.crossed_by((-1.0, 9.0), (1.0, 11.0)));
    }

    #[test]
    fn axis_titles_carry_the_factored_exponent_and_unit() {
        assert_eq!(
            axis_title(&Axis::linear("Force", "kN"), 3),
            "Force (×10³ kN)"
        );
        assert_eq!(axis_title(&Axis::linear("NRMSE", ""), -3), "NRMSE (×10⁻³)");
        assert_eq!(axis_title(&Axis::linear("NRMSE", ""), 0), "NRMSE");
    }
}
