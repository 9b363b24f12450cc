//! Drawing a [`Figure`] as SVG: panels planned alone, then again aligned
//! with their row and column; axis ranges and ticks ([`axes`]); data marks
//! clipped to the plot ([`marks`]); a legend placed where it hides the least
//! data ([`legend`]).

mod axes;
mod geometry;
mod legend;
mod marks;

use std::fmt::Write;

use super::figure::{Figure, Mark, Panel};
use super::style;
use super::xml::escape;
use axes::{draw_axes, draw_grid, extent, fitted, layout, range, Layout, Margins};
use geometry::Rect;
use legend::{
    draw_legend, in_rows, least_covered_corner, legend_entries, obstacles, stacked, Entry, Placed,
    LEGEND_ROW,
};
use marks::{draw_annotations, draw_area, draw_bands, draw_bars, draw_refs, draw_series};

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
        let _ = writeln!(
            out,
            "<svg{xmlns} width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\" \
             aria-label=\"{t}\" font-family=\"{f}\" font-size=\"{s}\" fill=\"{ink}\">",
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
                t = fitted(&self.title, style::FONT_FIGURE, w - 16.0),
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
    let entries = legend_entries(p, (0.45 * cell.w()).max(100.0));
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
            fitted(&p.title, style::FONT_TITLE, cell.x1 - l.plot.x0 - 4.0)
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
    draw_bands(out, p, l);
    draw_grid(out, p, l);
    let _ = writeln!(out, "<g clip-path=\"url(#{id}-clip)\">");
    for s in p.series.iter().filter(|s| s.mark == Mark::Area) {
        draw_area(out, s, l);
    }
    draw_bars(out, p, l);
    for s in p.series.iter().filter(|s| s.mark != Mark::Area) {
        draw_series(out, s, l);
    }
    out.push_str("</g>\n");
    draw_refs(out, p, l);
    draw_axes(out, p, cell, l);
    draw_annotations(out, p, l);
    if let Some(placed) = legend {
        draw_legend(out, entries, placed);
    }
    let mut y = cell.y1 - 6.0 - (notes.len() as f64 - 1.0) * (style::FONT_SMALL + 4.0);
    for n in notes.iter() {
        let _ = writeln!(
            out,
            "<text class=\"note\" x=\"{:.1}\" y=\"{y:.1}\" fill=\"{}\">{}</text>",
            cell.x0 + 8.0,
            style::WARN,
            fitted(&format!("Note: {n}"), style::FONT_SMALL, cell.w() - 16.0)
        );
        y += style::FONT_SMALL + 4.0;
    }
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Axis, Series};

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
}
