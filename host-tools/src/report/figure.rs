//! The plot model: a [`Figure`] holds [`Panel`]s laid out in a grid; a panel
//! has two [`Axis`] and the things drawn against them ([`Series`], [`Bars`],
//! reference lines, shaded bands, [`Annotation`]s, notes).
//!
//! Small value types (axes, series, annotations) are built by chaining
//! methods that consume `self`; the containers (panels, figures) are filled
//! through `&mut self` so that loops can add to them. Rendering is in
//! [`super::render`].

use super::style::{self, Colour};
use super::Error;

/// How an axis maps values to length.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Equal steps for equal differences.
    Linear,
    /// Equal steps for equal ratios; values ≤ 0 cannot be shown and are
    /// skipped with a note on the panel.
    Log,
}

/// One axis: what it shows, in which unit, on which scale.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub(crate) label: String,
    pub(crate) unit: String,
    pub(crate) scale: Scale,
    pub(crate) limits: Option<(f64, f64)>,
    pub(crate) categories: Vec<String>,
    pub(crate) include_zero: bool,
}

impl Axis {
    fn with(label: &str, unit: &str, scale: Scale) -> Self {
        Self {
            label: label.into(),
            unit: unit.into(),
            scale,
            limits: None,
            categories: Vec::new(),
            include_zero: false,
        }
    }

    /// A linear axis labelled `label (unit)`; an empty unit shows none.
    pub fn linear(label: &str, unit: &str) -> Self {
        Self::with(label, unit, Scale::Linear)
    }

    /// A log axis labelled `label (unit)`.
    pub fn log(label: &str, unit: &str) -> Self {
        Self::with(label, unit, Scale::Log)
    }

    /// A categorical axis: category `i` sits at position `i` and is labelled
    /// by `names[i]` (bars, the rungs of a model ladder).
    pub fn categories<S: AsRef<str>>(label: &str, names: &[S]) -> Self {
        let mut a = Self::with(label, "", Scale::Linear);
        a.categories = names.iter().map(|s| s.as_ref().to_string()).collect();
        a
    }

    /// Fixed limits instead of the data's range. Limits that are not finite
    /// with `lo < hi` (and `lo > 0` on a log axis) are not used, and the
    /// panel says so in a note.
    pub fn limits(mut self, lo: f64, hi: f64) -> Self {
        self.limits = Some((lo, hi));
        self
    }

    /// Stretch the data range to include zero (linear axes).
    pub fn include_zero(mut self) -> Self {
        self.include_zero = true;
        self
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mark {
    Line,
    Scatter,
    Area,
}

/// A named set of points drawn as a line, as dots, or as a filled area.
///
/// Non-finite points are not drawn: a line breaks at them and the panel
/// carries a note saying how many were skipped.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub(crate) name: String,
    pub(crate) mark: Mark,
    pub(crate) x: Vec<f64>,
    pub(crate) y: Vec<f64>,
    /// Lower edge of an area (empty for lines and dots).
    pub(crate) y_low: Vec<f64>,
    pub(crate) colour: Colour,
    pub(crate) width: f64,
    pub(crate) dash: Option<String>,
    /// Dot radius of scatter series and line markers (0: no markers).
    pub(crate) radius: f64,
    pub(crate) opacity: f64,
}

impl Series {
    fn with(name: &str, mark: Mark, x: &[f64], y: &[f64]) -> Result<Self, Error> {
        if x.len() != y.len() {
            return Err(Error::Length {
                what: format!("y values of series '{name}' (one per x value)"),
                expected: x.len(),
                found: y.len(),
            });
        }
        Ok(Self {
            name: name.into(),
            mark,
            x: x.to_vec(),
            y: y.to_vec(),
            y_low: Vec::new(),
            colour: style::BLUE,
            width: 1.8,
            dash: None,
            radius: if mark == Mark::Scatter { 2.5 } else { 0.0 },
            opacity: 1.0,
        })
    }

    /// A line through `(x[i], y[i])`. An empty name keeps it out of the legend.
    pub fn line(name: &str, x: &[f64], y: &[f64]) -> Result<Self, Error> {
        Self::with(name, Mark::Line, x, y)
    }

    /// Dots at `(x[i], y[i])`.
    pub fn scatter(name: &str, x: &[f64], y: &[f64]) -> Result<Self, Error> {
        Self::with(name, Mark::Scatter, x, y)
    }

    /// The region between `low[i]` and `high[i]` over `x[i]`, filled at 25%
    /// opacity unless [`Series::opacity`] says otherwise.
    pub fn area(name: &str, x: &[f64], low: &[f64], high: &[f64]) -> Result<Self, Error> {
        if low.len() != x.len() {
            return Err(Error::Length {
                what: format!("lower edge of area '{name}' (one per x value)"),
                expected: x.len(),
                found: low.len(),
            });
        }
        let mut s = Self::with(name, Mark::Area, x, high)?;
        s.y_low = low.to_vec();
        s.opacity = 0.25;
        Ok(s)
    }

    /// Stroke or fill colour.
    pub fn colour(mut self, c: Colour) -> Self {
        self.colour = c;
        self
    }

    /// Line width in pixels.
    pub fn width(mut self, px: f64) -> Self {
        self.width = px;
        self
    }

    /// An SVG dash pattern such as `"6 3"`.
    pub fn dash(mut self, pattern: &str) -> Self {
        self.dash = Some(pattern.into());
        self
    }

    /// Dot radius for scatter series, or markers on the points of a line.
    pub fn markers(mut self, radius: f64) -> Self {
        self.radius = radius;
        self
    }

    /// Fill or stroke opacity, 0 to 1.
    pub fn opacity(mut self, a: f64) -> Self {
        self.opacity = a;
        self
    }

    /// The `i`-th palette colour with its dash pattern (see [`style::dash`]).
    pub fn palette(mut self, i: usize) -> Self {
        self.colour = style::series(i);
        self.dash = style::dash(i).map(Into::into);
        self
    }

    /// Thin grey: how measured data is drawn under models.
    pub fn measured(self) -> Self {
        self.colour(style::MEASURED).width(1.2)
    }
}

/// One bar per category; all bar sets of a panel stand side by side in each
/// category (grouped bars). Non-finite values get no bar and a note.
#[derive(Debug, Clone, PartialEq)]
pub struct Bars {
    pub(crate) name: String,
    /// `None`: no bar here, and nothing to say about it.
    pub(crate) values: Vec<Option<f64>>,
    pub(crate) colour: Colour,
}

impl Bars {
    /// Bars of height `values[i]` at category `i`.
    pub fn new(name: &str, values: &[f64], colour: Colour) -> Self {
        Self {
            name: name.into(),
            values: values.iter().copied().map(Some).collect(),
            colour,
        }
    }

    /// Bars where some categories have no value by design (the first rung of
    /// a ladder has no BIC change): `None` leaves the slot empty, silently.
    pub fn sparse(name: &str, values: &[Option<f64>], colour: Colour) -> Self {
        Self {
            name: name.into(),
            values: values.to_vec(),
            colour,
        }
    }
}

/// Which way a reference line runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Orientation {
    Horizontal,
    Vertical,
}

/// A dashed line at a fixed value across the whole panel.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RefLine {
    pub(crate) orientation: Orientation,
    pub(crate) value: f64,
    pub(crate) label: String,
}

/// A shaded stretch of the x axis behind the data (a load cycle, say).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Band {
    pub(crate) from: f64,
    pub(crate) to: f64,
    pub(crate) label: String,
}

/// Where a text sits relative to its anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// Text starts at the point.
    Start,
    /// Text is centred on the point.
    Middle,
    /// Text ends at the point.
    End,
}

/// A text at a data point, optionally with a ring marking the point.
#[derive(Debug, Clone, PartialEq)]
pub struct Annotation {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) text: String,
    pub(crate) anchor: Anchor,
    pub(crate) dx: f64,
    pub(crate) dy: f64,
    pub(crate) colour: Colour,
    pub(crate) ring: bool,
}

impl Annotation {
    /// `text` centred 8 px above the point `(x, y)`.
    pub fn new(x: f64, y: f64, text: &str) -> Self {
        Self {
            x,
            y,
            text: text.into(),
            anchor: Anchor::Middle,
            dx: 0.0,
            dy: -8.0,
            colour: style::INK,
            ring: false,
        }
    }

    /// Text alignment relative to the point.
    pub fn anchor(mut self, a: Anchor) -> Self {
        self.anchor = a;
        self
    }

    /// Offset of the text from the point in pixels (+y is down).
    pub fn offset(mut self, dx: f64, dy: f64) -> Self {
        self.dx = dx;
        self.dy = dy;
        self
    }

    /// Text (and ring) colour.
    pub fn colour(mut self, c: Colour) -> Self {
        self.colour = c;
        self
    }

    /// Draw a ring around the point.
    pub fn ring(mut self) -> Self {
        self.ring = true;
        self
    }
}

/// One plot area with its axes and contents.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    pub(crate) title: String,
    pub(crate) x: Axis,
    pub(crate) y: Axis,
    pub(crate) series: Vec<Series>,
    pub(crate) bars: Vec<Bars>,
    pub(crate) refs: Vec<RefLine>,
    pub(crate) bands: Vec<Band>,
    pub(crate) annotations: Vec<Annotation>,
    pub(crate) notes: Vec<String>,
    pub(crate) legend: bool,
}

impl Panel {
    /// An empty panel over the axes `x` and `y`, with a legend.
    pub fn new(x: Axis, y: Axis) -> Self {
        Self {
            title: String::new(),
            x,
            y,
            series: Vec::new(),
            bars: Vec::new(),
            refs: Vec::new(),
            bands: Vec::new(),
            annotations: Vec::new(),
            notes: Vec::new(),
            legend: true,
        }
    }

    /// Title above the panel.
    pub fn title(&mut self, t: &str) -> &mut Self {
        self.title = t.into();
        self
    }

    /// Add a line, scatter or area series (drawn in the order added, areas first).
    pub fn series(&mut self, s: Series) -> &mut Self {
        self.series.push(s);
        self
    }

    /// Add a set of bars.
    pub fn bars(&mut self, b: Bars) -> &mut Self {
        self.bars.push(b);
        self
    }

    /// A horizontal reference line at `y` (label may be empty).
    pub fn hline(&mut self, y: f64, label: &str) -> &mut Self {
        self.refs.push(RefLine {
            orientation: Orientation::Horizontal,
            value: y,
            label: label.into(),
        });
        self
    }

    /// A vertical reference line at `x`.
    pub fn vline(&mut self, x: f64, label: &str) -> &mut Self {
        self.refs.push(RefLine {
            orientation: Orientation::Vertical,
            value: x,
            label: label.into(),
        });
        self
    }

    /// Shade `from..to` on the x axis, with a label at the top if it fits.
    pub fn band(&mut self, from: f64, to: f64, label: &str) -> &mut Self {
        self.bands.push(Band {
            from,
            to,
            label: label.into(),
        });
        self
    }

    /// Add a text at a data point.
    pub fn annotate(&mut self, a: Annotation) -> &mut Self {
        self.annotations.push(a);
        self
    }

    /// A note printed under the panel (data caveats).
    pub fn note(&mut self, text: &str) -> &mut Self {
        self.notes.push(text.into());
        self
    }

    /// Leave the legend out.
    pub fn no_legend(&mut self) -> &mut Self {
        self.legend = false;
        self
    }
}

/// A picture of one or more panels in a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub(crate) title: String,
    pub(crate) width: f64,
    pub(crate) height: f64,
    pub(crate) columns: usize,
    pub(crate) panels: Vec<Panel>,
}

impl Figure {
    /// An empty figure of `width` × `height` pixels (each at least 100),
    /// panels stacked in one column.
    pub fn new(width: f64, height: f64) -> Self {
        let size = |v: f64| if v.is_finite() { v.max(100.0) } else { 100.0 };
        Self {
            title: String::new(),
            width: size(width),
            height: size(height),
            columns: 1,
            panels: Vec::new(),
        }
    }

    /// Title across the top.
    pub fn title(&mut self, t: &str) -> &mut Self {
        self.title = t.into();
        self
    }

    /// Panels per row (at least 1).
    pub fn columns(&mut self, n: usize) -> &mut Self {
        self.columns = n.max(1);
        self
    }

    /// Add a panel (row by row).
    pub fn panel(&mut self, p: Panel) -> &mut Self {
        self.panels.push(p);
        self
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (f64, f64) {
        (self.width, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mismatched_lengths_are_refused_with_both_counts() {
        let e = Series::line("model", &[1.0, 2.0], &[1.0]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "y values of series 'model' (one per x value): expected 2, found 1"
        );
        assert!(Series::area("band", &[1.0], &[], &[1.0]).is_err());
        assert!(Series::area("band", &[1.0], &[0.0], &[]).is_err());
    }

    #[test]
    fn figure_size_is_sane_for_any_input() {
        assert_eq!(Figure::new(f64::NAN, -5.0).size(), (100.0, 100.0));
        assert_eq!(Figure::new(800.0, 600.0).size(), (800.0, 600.0));
    }
}
