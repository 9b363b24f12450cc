//! Comparing models: the ladder of added effects, Pareto fronts of two
//! objectives, and sensitivity to parameters.

use super::{same_unit, Painter, Quantity, Signal};
use crate::report::{style, Anchor, Annotation, Axis, Bars, Error, Figure, Panel, Series};

/// One rung of a model ladder: a model and how well it fits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rung<'a> {
    /// The model (e.g. `bw+pinching`) or the effect the rung adds.
    pub label: &'a str,
    /// Number of fitted parameters.
    pub params: usize,
    /// Normalised RMS error of the fit.
    pub nrmse: f64,
    /// BIC change from the previous rung (negative: better); `None` on the
    /// first rung, which has nothing to compare with.
    pub delta_bic: Option<f64>,
}

/// The error falling as effects are added: NRMSE per rung on a log axis,
/// each point labelled with its parameter count, and below it the BIC change
/// per rung, with an optional reference line at `bic_threshold` (the change
/// the caller calls significant).
pub fn ladder(rungs: &[Rung], bic_threshold: Option<f64>) -> Result<Figure, Error> {
    let labels: Vec<&str> = rungs.iter().map(|r| r.label).collect();
    let at: Vec<f64> = (0..rungs.len()).map(|i| i as f64).collect();
    let nrmse: Vec<f64> = rungs.iter().map(|r| r.nrmse).collect();
    // Room above the highest point for its label: a third of a decade.
    let finite = nrmse.iter().copied().filter(|v| v.is_finite() && *v > 0.0);
    let y = match (finite.clone().reduce(f64::min), finite.reduce(f64::max)) {
        (Some(lo), Some(hi)) => Axis::log("NRMSE", "").limits(lo / 1.6, hi * 2.2),
        _ => Axis::log("NRMSE", ""),
    };
    let mut error = Panel::new(Axis::categories("", &labels), y);
    error.title("Error of each model");
    error.series(Series::line("NRMSE", &at, &nrmse)?.markers(4.0));
    error.no_legend();
    for (i, r) in rungs.iter().enumerate() {
        let plural = if r.params == 1 { "" } else { "s" };
        // Up and to the right: a falling ladder leaves that corner free.
        error.annotate(
            Annotation::new(i as f64, r.nrmse, &format!("{} param{plural}", r.params))
                .anchor(Anchor::Start)
                .offset(8.0, -8.0),
        );
    }
    let bic: Vec<Option<f64>> = rungs.iter().map(|r| r.delta_bic).collect();
    let mut evidence = Panel::new(
        Axis::categories("Model", &labels),
        Axis::linear("\u{0394}BIC to previous", ""),
    );
    evidence.title("Evidence for each added effect");
    evidence.bars(Bars::sparse("\u{0394}BIC", &bic, style::BLUE));
    evidence.hline(0.0, "").no_legend();
    if let Some(t) = bic_threshold {
        evidence.hline(
            t,
            &format!("\u{0394}BIC = {}", crate::report::ticks::plain(t)),
        );
    }
    let title = match (nrmse.first(), nrmse.last()) {
        (Some(&a), Some(&b)) if rungs.len() > 1 && a > 0.0 && b > 0.0 && a.is_finite() => {
            format!(
                "Model ladder: NRMSE falls {:.1}\u{00d7} from first to last rung",
                a / b
            )
        }
        _ => "Model ladder".into(),
    };
    let mut fig = Figure::new(760.0, 640.0);
    fig.title(&title).panel(error).panel(evidence);
    Ok(fig)
}

/// Two objectives of a multi-objective fit (thesis §3.3, NSGA-II).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pareto<'a> {
    /// Objective pairs of all candidates, both minimised.
    pub points: &'a [[f64; 2]],
    /// Index of the candidate chosen, if any.
    pub chosen: Option<usize>,
    /// The first objective.
    pub x: Quantity<'a>,
    /// The second objective.
    pub y: Quantity<'a>,
}

/// Candidates as grey dots, the non-dominated front joined as a line, and
/// the chosen candidate ringed.
pub fn pareto_front(p: &Pareto) -> Result<Figure, Error> {
    if let Some(c) = p.chosen.filter(|&c| c >= p.points.len()) {
        return Err(Error::Index {
            what: "chosen candidate of the Pareto front".into(),
            index: c,
            len: p.points.len(),
        });
    }
    let front = non_dominated(p.points);
    let (dx, dy): (Vec<f64>, Vec<f64>) = p
        .points
        .iter()
        .enumerate()
        .filter(|(i, _)| !front.contains(i))
        .map(|(_, q)| (q[0], q[1]))
        .unzip();
    let (fx, fy): (Vec<f64>, Vec<f64>) = front
        .iter()
        .map(|&i| (p.points[i][0], p.points[i][1]))
        .unzip();
    let mut panel = Panel::new(
        Axis::linear(p.x.name, p.x.unit),
        Axis::linear(p.y.name, p.y.unit),
    );
    if !dx.is_empty() {
        panel.series(Series::scatter("dominated", &dx, &dy)?.colour(style::MEASURED));
    }
    panel.series(Series::line("Pareto front", &fx, &fy)?.markers(3.5));
    if let Some(c) = p.chosen {
        let [x, y] = p.points[c];
        panel.series(
            Series::scatter("chosen", &[x], &[y])?
                .colour(style::VERMILLION)
                .markers(5.0),
        );
        panel.annotate(
            Annotation::new(x, y, "chosen")
                .offset(10.0, -10.0)
                .anchor(Anchor::Start)
                .colour(style::VERMILLION)
                .ring(),
        );
    }
    let mut fig = Figure::new(640.0, 460.0);
    fig.title("Pareto front of the two objectives").panel(panel);
    Ok(fig)
}

/// Indices of the points no other point beats in both coordinates (both
/// minimised), ordered by the first coordinate. Non-finite points are never
/// on the front.
fn non_dominated(points: &[[f64; 2]]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].iter().all(|v| v.is_finite()))
        .collect();
    idx.sort_by(|&a, &b| {
        points[a][0]
            .total_cmp(&points[b][0])
            .then(points[a][1].total_cmp(&points[b][1]))
    });
    let mut front = Vec::new();
    let mut best_y = f64::INFINITY;
    for i in idx {
        if points[i][1] < best_y {
            best_y = points[i][1];
            front.push(i);
        }
    }
    front
}

/// RMS error against a relative change of each parameter (thesis §3.5.3,
/// Eq. 3.24, Fig. 3.7): one curve per parameter over the changes in
/// `change_percent` (typically −50 … +50).
pub fn sensitivity(
    change_percent: &[f64],
    error_name: &str,
    curves: &[Signal],
) -> Result<Figure, Error> {
    let unit = curves.first().map_or("", |s| s.unit);
    same_unit(curves, unit)?;
    let mut panel = Panel::new(
        Axis::linear("Parameter change", "%"),
        Axis::linear(error_name, unit).include_zero(),
    );
    panel.vline(0.0, "");
    let mut painter = Painter::default();
    for c in curves {
        let s = Series::line(c.name, change_percent, c.values)?.markers(2.5);
        panel.series(painter.paint(s, c.source));
    }
    let mut fig = Figure::new(720.0, 460.0);
    fig.title("Sensitivity of the model to its parameters")
        .panel(panel);
    Ok(fig)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_keeps_exactly_the_non_dominated_points() {
        let pts = [
            [1.0, 5.0],
            [2.0, 3.0],
            [2.5, 4.0], // dominated by [2, 3]
            [3.0, 1.0],
            [f64::NAN, 0.0],
            [4.0, 1.0], // dominated by [3, 1]
        ];
        assert_eq!(non_dominated(&pts), [0, 1, 3]);
    }

    #[test]
    fn chosen_index_must_exist() {
        let pts = [[1.0, 2.0]];
        let p = Pareto {
            points: &pts,
            chosen: Some(1),
            x: Quantity::new("Force error", ""),
            y: Quantity::new("Energy error", ""),
        };
        let e = pareto_front(&p).unwrap_err();
        assert_eq!(
            e.to_string(),
            "chosen candidate of the Pareto front: index 1 is out of range (there are 1)"
        );
    }

    #[test]
    fn ladder_title_states_the_fall_and_first_rung_has_no_bic_bar() {
        let rungs = [
            Rung {
                label: "bw",
                params: 5,
                nrmse: 0.30,
                delta_bic: None,
            },
            Rung {
                label: "+pinching",
                params: 9,
                nrmse: 0.10,
                delta_bic: Some(-420.0),
            },
        ];
        let fig = ladder(&rungs, Some(-10.0)).unwrap();
        let svg = fig.to_svg();
        assert!(svg.contains("NRMSE falls 3.0\u{00d7}"), "{svg}");
        assert!(svg.contains(">5 params<") && svg.contains(">9 params<"));
        // One bar only (one rectangle in the bar path), and no note about it.
        let bars = svg.split("class=\"bars\"").nth(1).unwrap();
        let d = bars
            .split("d=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        assert_eq!(d.matches('Z').count(), 1, "{d}");
        assert!(!svg.contains("Note:"));
    }

    #[test]
    fn sensitivity_curves_must_match_changes() {
        let change = [-50.0, 0.0, 50.0];
        let e = [3.0, 0.0];
        let err =
            sensitivity(&change, "RMS error", &[Signal::model("alpha", "mm", &e)]).unwrap_err();
        assert!(err.to_string().contains("'alpha'"), "{err}");
    }
}
