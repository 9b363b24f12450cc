//! Axes: the data range each axis shows, its ticks, the panel layout that
//! makes room for tick labels, axis titles and notes, and the drawing of
//! axes and grid.

use std::fmt::Write;

use super::geometry::{Map, Rect};
use crate::report::figure::{Axis, Mark, Orientation, Panel, Scale};
use crate::report::style;
use crate::report::ticks::{self, Ticks};
use crate::report::xml::escape;

/// Data values the panel puts on each axis, and what could not be shown.
pub(super) struct Extent {
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
    pub(super) notes: Vec<String>,
}

/// Gathers every value that should be inside the axis ranges, counting the
/// points that cannot be drawn so that the panel can say so.
pub(super) fn extent(p: &Panel) -> Extent {
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

pub(super) fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The range an axis shows: fixed limits if valid, else the data's range
/// padded by 4% (not past zero when the data stops at zero), never of zero
/// width. Explains in `notes` what it could not honour.
pub(super) fn range(axis: &Axis, data: &[f64], notes: &mut Vec<String>) -> (f64, f64) {
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
pub(super) fn resolve(axis: &Axis, lo: f64, hi: f64, target: usize) -> Ticks {
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
pub(super) fn axis_title(axis: &Axis, exponent: i32) -> String {
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

/// `text` shortened with an ellipsis to fit `max` px at `size`, or `None`
/// when it fits as it is.
pub(super) fn truncated(text: &str, size: f64, max: f64) -> Option<String> {
    if style::text_width(text, size) <= max {
        return None;
    }
    let mut cut: String = text.into();
    while !cut.is_empty() && style::text_width(&cut, size) + style::text_width("…", size) > max {
        cut.pop();
    }
    Some(format!("{}…", cut.trim_end()))
}

/// Text content for an SVG `<text>`: `text` escaped, or when wider than
/// `max` px, shortened with an ellipsis and the whole text kept in a
/// `<title>` (shown on hover).
pub(super) fn fitted(text: &str, size: f64, max: f64) -> String {
    match truncated(text, size, max) {
        None => escape(text).into_owned(),
        Some(short) => format!("{}<title>{}</title>", escape(&short), escape(text)),
    }
}

pub(super) fn widest(labels: &[String]) -> f64 {
    labels
        .iter()
        .map(|l| style::text_width(l, style::FONT_SMALL))
        .fold(0.0, f64::max)
}

/// How the x tick labels are set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct XLabels {
    /// Label every `every`-th tick.
    pub(super) every: usize,
    /// Rotate labels by -35° (long category names).
    pub(super) rotated: bool,
    /// Count from one (numbered categories such as cycles: label 1, then
    /// every multiple of `every`) rather than from the first tick.
    pub(super) counted: bool,
}

impl XLabels {
    const ALL: Self = Self {
        every: 1,
        rotated: false,
        counted: false,
    };

    /// Whether tick `k` gets its label.
    pub(super) fn shows(&self, k: usize) -> bool {
        if self.counted {
            k == 0 || (k + 1) % self.every == 0
        } else {
            k % self.every == 0
        }
    }
}

/// The smallest of 1, 2, 5, 10, 20, 50, … that is at least `n`.
fn nice_at_least(n: usize) -> usize {
    let mut step = 1;
    loop {
        for m in [1, 2, 5] {
            if m * step >= n {
                return m * step;
            }
        }
        step *= 10;
    }
}

pub(super) const ROTATION_DEG: f64 = 35.0;

/// Chooses x ticks that fit between pixels `x0` and `x1`: fewer ticks on
/// numeric axes, rotated (and if need be thinned) labels on categorical ones.
pub(super) fn x_ticks(axis: &Axis, lo: f64, hi: f64, x0: f64, x1: f64) -> (Ticks, XLabels) {
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
            return (r, XLabels::ALL);
        }
        let numbered = r.labels.iter().all(|l| l.parse::<f64>().is_ok());
        if !axis.categories.is_empty() && numbered {
            // Cycle numbers: 1, 10, 20, … read better than slanted labels.
            let every = nice_at_least((need / spacing.max(1.0)).ceil() as usize + 1);
            return (
                r,
                XLabels {
                    every,
                    rotated: false,
                    counted: true,
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
                    counted: false,
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
                    counted: false,
                },
            );
        }
        target -= 1;
    }
}

/// Layout of one panel: plot rectangle, axis maps and ticks.
pub(super) struct Layout {
    pub(super) plot: Rect,
    pub(super) xm: Map,
    pub(super) ym: Map,
    pub(super) xt: Ticks,
    pub(super) yt: Ticks,
    pub(super) xl: XLabels,
    /// The margins used.
    pub(super) margins: Margins,
}

/// Height taken below the plot by tick labels, axis title and notes.
pub(super) fn bottom_margin(notes: usize, rotated_extra: f64) -> f64 {
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
pub(super) struct Margins {
    pub(super) left: f64,
    pub(super) right: f64,
    pub(super) top: f64,
}

impl Margins {
    /// Each side at least as wide as in `other`.
    pub(super) fn max(self, other: Self) -> Self {
        Self {
            left: self.left.max(other.left),
            right: self.right.max(other.right),
            top: self.top.max(other.top),
        }
    }
}

/// Space right of the plot when no legend is there.
pub(super) const RIGHT_PAD: f64 = 16.0;

/// Lays out a panel in `cell` for the axis ranges `xr` and `yr`, with at
/// least the margins `min` and room for `notes` lines below.
pub(super) fn layout(
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

pub(super) fn draw_grid(out: &mut String, p: &Panel, l: &Layout) {
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

pub(super) fn draw_axes(out: &mut String, p: &Panel, cell: Rect, l: &Layout) {
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
        let shown = l.xl.shows(k);
        if shown || l.xl.every == 1 || !l.xl.counted {
            let _ = write!(marks, "M{x:.1},{:.1}v4", pl.y1);
        }
        if !shown {
            continue;
        }
        let y = pl.y1 + 6.0 + style::FONT_SMALL;
        if l.xl.rotated {
            // The slant runs left: cut what would pass the panel's left edge.
            let room = (x - cell.x0 - 2.0) / ROTATION_DEG.to_radians().cos();
            let _ = writeln!(
                labels,
                "<text class=\"tick\" x=\"{x:.1}\" y=\"{y:.1}\" text-anchor=\"end\" \
                 transform=\"rotate(-{ROTATION_DEG} {x:.1} {y:.1})\">{}</text>",
                fitted(label, style::FONT_SMALL, room)
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
        fitted(
            &axis_title(&p.x, l.xt.exponent),
            style::FONT_LABEL,
            pl.w().min(2.0 * (cell.x1 - (pl.x0 + pl.x1) / 2.0) - 8.0)
        )
    );
    // At the left edge of the margin, so that aligned panels share it.
    let ylabel_x = pl.x0 - l.margins.left + 6.0 + style::FONT_LABEL / 2.0;
    let ymid = (pl.y0 + pl.y1) / 2.0;
    let _ = writeln!(
        out,
        "<text class=\"axis-label\" x=\"{ylabel_x:.1}\" y=\"{ymid:.1}\" text-anchor=\"middle\" \
         font-size=\"{}\" transform=\"rotate(-90 {ylabel_x:.1} {ymid:.1})\">{}</text>",
        style::FONT_LABEL,
        fitted(&axis_title(&p.y, l.yt.exponent), style::FONT_LABEL, pl.h())
    );
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn axis_titles_carry_the_factored_exponent_and_unit() {
        assert_eq!(
            axis_title(&Axis::linear("Force", "kN"), 3),
            "Force (×10³ kN)"
        );
        assert_eq!(axis_title(&Axis::linear("NRMSE", ""), -3), "NRMSE (×10⁻³)");
        assert_eq!(axis_title(&Axis::linear("NRMSE", ""), 0), "NRMSE");
    }
}
