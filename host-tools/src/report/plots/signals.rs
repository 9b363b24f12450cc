//! Signals against time, and the generic x–y plot.

use super::{Painter, Quantity, Signal, Source, TimeBase, Trace};
use crate::report::{Axis, Error, Figure, Panel, Series};

/// Several signals against sample index or time. Signals sharing a unit
/// share a panel; each further unit gets its own panel below, on the same
/// time axis (force over displacement, say). A panel's y axis is named after
/// its first measured signal (else its first signal).
pub fn time_series(time: TimeBase, signals: &[Signal]) -> Result<Figure, Error> {
    let mut units: Vec<&str> = Vec::new();
    for s in signals {
        if !units.contains(&s.unit) {
            units.push(s.unit);
        }
    }
    let tq = time.quantity();
    let mut fig = Figure::new(900.0, 60.0 + 230.0 * units.len().max(1) as f64);
    fig.title("Signals over the record");
    let mut painter = Painter::default();
    for unit in units {
        let group: Vec<&Signal> = signals.iter().filter(|s| s.unit == unit).collect();
        // The axis is named after the measured signal (models are compared
        // with it), else after the first signal.
        let label = group
            .iter()
            .find(|s| s.source == Source::Measured)
            .unwrap_or(&group[0])
            .name;
        let mut panel = Panel::new(Axis::linear(tq.name, tq.unit), Axis::linear(label, unit));
        // Measured first so that models are drawn over them.
        let ordered = group
            .iter()
            .filter(|s| s.source == Source::Measured)
            .chain(group.iter().filter(|s| s.source == Source::Model));
        for s in ordered {
            let t = time.abscissae(s.values.len(), &format!("signal '{}'", s.name))?;
            panel.series(painter.paint(Series::line(s.name, &t, s.values)?, s.source));
        }
        fig.panel(panel);
    }
    Ok(fig)
}

/// A plain x–y line plot of the traces, with a title.
pub fn xy(title: &str, x: Quantity, y: Quantity, traces: &[Trace]) -> Result<Figure, Error> {
    let mut panel = Panel::new(Axis::linear(x.name, x.unit), Axis::linear(y.name, y.unit));
    let mut painter = Painter::default();
    for t in traces {
        panel.series(painter.paint(Series::line(t.name, t.x, t.y)?, t.source));
    }
    let mut fig = Figure::new(640.0, 420.0);
    fig.title(title).panel(panel);
    Ok(fig)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_panel_per_unit() {
        let u = [0.0, 1.0, 2.0];
        let f = [0.0, 5.0, 7.0];
        let g = [0.0, 4.0, 8.0];
        let fig = time_series(
            TimeBase::Index,
            &[
                Signal::measured("Displacement", "mm", &u),
                Signal::measured("Force", "kN", &f),
                Signal::model("bwbn", "kN", &g),
            ],
        )
        .unwrap();
        assert_eq!(fig.panels.len(), 2);
        assert_eq!(fig.panels[0].series.len(), 1);
        assert_eq!(fig.panels[1].series.len(), 2);
        let svg = fig.to_svg();
        assert!(svg.contains(">Displacement (mm)<"));
        assert!(svg.contains(">Force (kN)<"));
        assert!(svg.contains(">Sample<"));
    }

    #[test]
    fn times_must_match_samples() {
        let t = [0.0, 0.01];
        let v = [1.0, 2.0, 3.0];
        let e = time_series(
            TimeBase::Time {
                values: &t,
                unit: "s",
            },
            &[Signal::measured("Force", "kN", &v)],
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "samples of signal 'Force' (one per time value): expected 2, found 3"
        );
    }
}
