//! Where a model misses: residuals by branch and by cycle.

use super::{same_length, Painter, Quantity, Signal};
use crate::report::{style, Axis, Bars, Error, Figure, Panel, Series};

/// Residuals of one record, sample by sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residuals<'a> {
    /// Measured displacement at each sample.
    pub displacement: &'a [f64],
    /// Residual force at each sample (the caller's convention, e.g. model
    /// minus measured).
    pub residual: &'a [f64],
    /// Branch class of each sample, an index into `branch_names`; empty when
    /// samples are not classified.
    pub branch: &'a [usize],
    /// Names of the branch classes (loading, unloading, reloading, …).
    pub branch_names: &'a [&'a str],
    /// First sample of each load cycle, ascending; empty for no cycle bands.
    pub cycle_starts: &'a [usize],
    /// Displacement unit.
    pub displacement_unit: &'a str,
    /// Force unit.
    pub force_unit: &'a str,
}

/// Two panels: residual against displacement, coloured by branch class
/// (where on the loop the model misses), and residual against sample index
/// with every other load cycle shaded and numbered (when it misses).
pub fn residual_map(r: &Residuals) -> Result<Figure, Error> {
    let n = r.residual.len();
    if r.displacement.len() != n {
        return Err(Error::Length {
            what: "displacements of the residual map (one per residual)".into(),
            expected: n,
            found: r.displacement.len(),
        });
    }
    if !r.branch.is_empty() && r.branch.len() != n {
        return Err(Error::Length {
            what: "branch classes of the residual map (one per residual, or none)".into(),
            expected: n,
            found: r.branch.len(),
        });
    }
    if let Some(&b) = r.branch.iter().find(|&&b| b >= r.branch_names.len()) {
        return Err(Error::Index {
            what: "branch class of a residual".into(),
            index: b,
            len: r.branch_names.len(),
        });
    }
    if let Some(&c) = r.cycle_starts.iter().find(|&&c| c >= n) {
        return Err(Error::Index {
            what: "first sample of a cycle".into(),
            index: c,
            len: n,
        });
    }
    if let Some(w) = r.cycle_starts.windows(2).find(|w| w[0] >= w[1]) {
        return Err(Error::Order {
            what: format!("cycle starts ({} then {})", w[0], w[1]),
        });
    }
    let index: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let residual_axis = || Axis::linear("Residual force", r.force_unit);
    let mut by_displacement = Panel::new(
        Axis::linear("Displacement", r.displacement_unit),
        residual_axis(),
    );
    by_displacement
        .title("Residual along the loop")
        .hline(0.0, "");
    let mut by_index = Panel::new(Axis::linear("Sample", ""), residual_axis());
    by_index.title("Residual over the record").hline(0.0, "");
    for (k, w) in r.cycle_starts.iter().enumerate().step_by(2) {
        let end = r.cycle_starts.get(k + 1).copied().unwrap_or(n);
        by_index.band(*w as f64, end as f64, &format!("{}", k + 1));
    }
    // One scatter series per branch class (all samples when unclassified).
    let classes: Vec<(String, Vec<usize>)> = if r.branch.is_empty() {
        vec![("residual".into(), (0..n).collect())]
    } else {
        r.branch_names
            .iter()
            .enumerate()
            .map(|(c, name)| {
                let rows = (0..n).filter(|&i| r.branch[i] == c).collect();
                (name.to_string(), rows)
            })
            .collect()
    };
    for (c, (name, rows)) in classes.iter().enumerate() {
        if rows.is_empty() {
            continue;
        }
        let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let (u, e, t) = (pick(r.displacement), pick(r.residual), pick(&index));
        let colour = style::series(c);
        by_displacement.series(Series::scatter(name, &u, &e)?.colour(colour).markers(2.0));
        by_index.series(Series::scatter("", &t, &e)?.colour(colour).markers(1.6));
    }
    by_index.no_legend();
    let mut fig = Figure::new(1000.0, 430.0);
    fig.title("Residual map")
        .columns(2)
        .panel(by_displacement)
        .panel(by_index);
    Ok(fig)
}

/// Grouped bars per load cycle: each signal holds one value per cycle
/// (an error, a dissipated energy, a peak force), measured grey beside the
/// models in colour. All signals need the same number of cycles.
pub fn per_cycle_bars(quantity: Quantity, signals: &[Signal]) -> Result<Figure, Error> {
    let cycles = signals.first().map_or(0, |s| s.values.len());
    same_length(signals, cycles)?;
    let names: Vec<String> = (1..=cycles).map(|c| c.to_string()).collect();
    let mut panel = Panel::new(
        Axis::categories("Cycle", &names),
        Axis::linear(quantity.name, quantity.unit),
    );
    let mut painter = Painter::default();
    for s in signals {
        panel.bars(Bars::new(s.name, s.values, painter.colour(s.source)));
    }
    let mut fig = Figure::new(900.0, 380.0);
    fig.title(&format!("{} per cycle", quantity.name))
        .panel(panel);
    Ok(fig)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample<'a>(u: &'a [f64], e: &'a [f64], b: &'a [usize], c: &'a [usize]) -> Residuals<'a> {
        Residuals {
            displacement: u,
            residual: e,
            branch: b,
            branch_names: &["loading", "unloading"],
            cycle_starts: c,
            displacement_unit: "mm",
            force_unit: "kN",
        }
    }

    #[test]
    fn residual_map_checks_its_inputs() {
        let u = [0.0, 1.0, 2.0, 1.0];
        let e = [0.1, -0.2, 0.3, 0.0];
        assert!(residual_map(&sample(&u, &e, &[0, 0, 1, 1], &[0, 2])).is_ok());
        assert!(residual_map(&sample(&u, &e, &[], &[])).is_ok());
        let err = residual_map(&sample(&u, &e, &[0, 2, 1, 1], &[])).unwrap_err();
        assert_eq!(
            err.to_string(),
            "branch class of a residual: index 2 is out of range (there are 2)"
        );
        assert!(residual_map(&sample(&u, &e, &[0, 1], &[])).is_err());
        assert!(residual_map(&sample(&u[..3], &e, &[], &[])).is_err());
        assert!(residual_map(&sample(&u, &e, &[], &[0, 4])).is_err());
        let err = residual_map(&sample(&u, &e, &[], &[2, 1])).unwrap_err();
        assert_eq!(err.to_string(), "cycle starts (2 then 1) must ascend");
    }

    #[test]
    fn residual_map_colours_each_branch_and_shades_alternate_cycles() {
        let u = [0.0, 1.0, 2.0, 1.0, 0.0, -1.0];
        let e = [0.1, -0.2, 0.3, 0.0, 0.1, 0.2];
        let svg = residual_map(&sample(&u, &e, &[0, 0, 1, 1, 0, 1], &[0, 2, 4]))
            .unwrap()
            .to_svg();
        assert!(svg.contains("data-name=\"loading\""));
        assert!(svg.contains("data-name=\"unloading\""));
        // Cycles 1 and 3 are shaded, cycle 2 is not.
        assert_eq!(svg.matches(&format!("fill=\"{}\"", style::BAND)).count(), 2);
    }

    #[test]
    fn bars_need_one_value_per_cycle_in_every_signal() {
        let a = [1.0, 2.0, 3.0];
        let b = [1.0, 2.0];
        let q = Quantity::new("Energy", "kN·mm");
        assert!(per_cycle_bars(q, &[Signal::measured("lab", "kN·mm", &a)]).is_ok());
        let e = per_cycle_bars(
            q,
            &[
                Signal::measured("lab", "kN·mm", &a),
                Signal::model("bw", "kN·mm", &b),
            ],
        )
        .unwrap_err();
        assert_eq!(e.to_string(), "values of 'bw': expected 3, found 2");
    }
}
