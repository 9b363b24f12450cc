//! Force–displacement loops and the energy they enclose.

use super::{same_length, same_unit, Painter, Quantity, Signal, Source, TimeBase, Trace};
use crate::report::{Axis, Error, Figure, Panel, Series};

/// Hysteresis loops: measured curves thin and grey underneath, each model
/// as a coloured line on top (thesis Figs 3.3–3.4 draw the same comparison).
///
/// `x` and `y` name the axes, typically displacement and force.
pub fn loop_overlay(traces: &[Trace], x: Quantity, y: Quantity) -> Result<Figure, Error> {
    let mut panel = Panel::new(Axis::linear(x.name, x.unit), Axis::linear(y.name, y.unit));
    let mut painter = Painter::default();
    // Measured first so that models are drawn over them.
    let ordered = traces
        .iter()
        .filter(|t| t.source == Source::Measured)
        .chain(traces.iter().filter(|t| t.source == Source::Model));
    for t in ordered {
        let s = Series::line(t.name, t.x, t.y)?;
        panel.series(painter.paint(s, t.source));
    }
    let mut fig = Figure::new(640.0, 500.0);
    fig.title("Hysteresis loops: measured and model")
        .panel(panel);
    Ok(fig)
}

/// Cumulative dissipated energy over the record, measured against models
/// (thesis §3.5.2, Figs 3.5–3.6). Each model's legend entry states its final
/// energy relative to the first measured curve.
///
/// All curves share one unit and the length of `time`.
pub fn energy_curves(time: TimeBase, curves: &[Signal]) -> Result<Figure, Error> {
    let unit = curves.first().map_or("", |s| s.unit);
    same_unit(curves, unit)?;
    let n = curves.first().map_or(0, |s| s.values.len());
    same_length(curves, n)?;
    let t = time.abscissae(n, "the energy curves")?;
    let tq = time.quantity();
    let mut panel = Panel::new(
        Axis::linear(tq.name, tq.unit),
        Axis::linear("Dissipated energy", unit).include_zero(),
    );
    let mut painter = Painter::default();
    let reference = curves
        .iter()
        .find(|c| c.source == Source::Measured)
        .and_then(|c| last_finite(&t, c.values));
    for c in curves {
        let name = match (c.source, reference, last_finite(&t, c.values)) {
            (Source::Model, Some((_, e_ref)), Some((_, e))) if e_ref != 0.0 => {
                let rel = 100.0 * (e - e_ref) / e_ref.abs();
                format!("{}: {} at the end", c.name, signed_percent(rel))
            }
            _ => c.name.to_string(),
        };
        let s = Series::line(&name, &t, c.values)?;
        panel.series(match c.source {
            Source::Measured => s.measured().width(2.5),
            Source::Model => painter.paint(s, c.source),
        });
    }
    let mut fig = Figure::new(720.0, 420.0);
    fig.title("Cumulative dissipated energy").panel(panel);
    Ok(fig)
}

/// `+4.2%` or `−4.2%`, with a true minus sign.
fn signed_percent(p: f64) -> String {
    format!("{p:+.1}%").replace('-', "\u{2212}")
}

/// The last point of a curve where both coordinates are finite.
fn last_finite(t: &[f64], v: &[f64]) -> Option<(f64, f64)> {
    t.iter()
        .zip(v)
        .rev()
        .find(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_label_states_final_error_against_measured() {
        let measured = [0.0, 1.0, 2.0, 4.0];
        let model = [0.0, 1.0, 2.5, 5.0];
        let fig = energy_curves(
            TimeBase::Index,
            &[
                Signal::measured("measured", "kN·mm", &measured),
                Signal::model("bwbn", "kN·mm", &model),
            ],
        )
        .unwrap();
        let svg = fig.to_svg();
        assert!(svg.contains(">bwbn: +25.0% at the end<"), "{svg}");
    }

    #[test]
    fn energy_curves_refuse_mixed_units_and_lengths() {
        let a = [0.0, 1.0];
        let b = [0.0, 1.0, 2.0];
        let e = energy_curves(
            TimeBase::Index,
            &[Signal::measured("m", "J", &a), Signal::model("p", "kJ", &a)],
        )
        .unwrap_err();
        assert_eq!(e.to_string(), "signal 'p': expected unit 'J', found 'kJ'");
        assert!(energy_curves(
            TimeBase::Index,
            &[Signal::measured("m", "J", &a), Signal::model("p", "J", &b)]
        )
        .is_err());
        let t = [0.0, 0.1, 0.2];
        let e = energy_curves(
            TimeBase::Time {
                values: &t,
                unit: "s",
            },
            &[Signal::measured("m", "J", &a)],
        )
        .unwrap_err();
        assert!(e.to_string().contains("expected 3, found 2"), "{e}");
    }

    #[test]
    fn loops_draw_measured_first_in_grey() {
        let x = [0.0, 1.0, 0.0, -1.0, 0.0];
        let y = [0.0, 1.0, 0.5, -1.0, -0.5];
        let fig = loop_overlay(
            &[Trace::model("bwbn", &x, &y), Trace::measured("lab", &x, &y)],
            Quantity::new("Displacement", "mm"),
            Quantity::new("Force", "kN"),
        )
        .unwrap();
        let svg = fig.to_svg();
        let lab = svg.find("data-name=\"lab\"").unwrap();
        let model = svg.find("data-name=\"bwbn\"").unwrap();
        assert!(lab < model);
        assert!(svg[lab..model].contains("#8c8c8c"));
        assert!(svg[model..].contains("#0072b2"));
    }
}
