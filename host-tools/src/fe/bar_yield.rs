//! The torque against the largest strain of each bar set (thesis Fig. 2.2:
//! in the tests the hoops yield before the longitudinal bars), with each
//! set's yield strain `f_y / E_s` as a line, so that which set yields first,
//! and at what torque, is seen at a glance.

use super::output::Sample;
use crate::report::{Axis, Error, Figure, Panel, Series};

/// The figure: torque (kN m) against the largest axial strain of the
/// longitudinal bars and of the hoops (`strains[i]` of sample `i` starts
/// with those two, `None` for a set without bars), with the
/// yield strains `eps_y` of the two sets as vertical lines.
pub fn figure(
    title: &str,
    samples: &[Sample],
    strains: &[Vec<Option<f64>>],
    eps_y: [f64; 2],
) -> Result<Figure, Error> {
    let mut panel = Panel::new(
        Axis::linear("largest bar strain", "-").include_zero(),
        Axis::linear("torque", "kN m").include_zero(),
    );
    for (set, (name, line)) in [
        ("longitudinal bars", "longitudinal yield"),
        ("hoops", "hoop yield"),
    ]
    .into_iter()
    .enumerate()
    {
        let (x, y): (Vec<f64>, Vec<f64>) = samples
            .iter()
            .zip(strains)
            .filter_map(|(s, e)| {
                e.get(set)
                    .copied()
                    .flatten()
                    .map(|e| (e, s.torque.abs() / 1e3))
            })
            .unzip();
        if !x.is_empty() {
            panel.series(Series::line(name, &x, &y)?.width(2.0).palette(set));
            panel.vline(eps_y[set], &format!("{line} {:.5}", eps_y[set]));
        }
    }
    let mut fig = Figure::new(720.0, 460.0);
    fig.title(title).panel(panel);
    Ok(fig)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both sets drawn against the torque, each with its yield line; a set
    /// without bars is left out.
    #[test]
    fn both_sets_and_their_yield_strains_are_drawn() {
        let samples: Vec<Sample> = (0..=20)
            .map(|i| Sample::on_curve(0.001 * i as f64, 3000.0 * i as f64))
            .collect();
        let strains: Vec<Vec<Option<f64>>> = (0..=20)
            .map(|i| vec![Some(5e-5 * i as f64), Some(1e-4 * i as f64)])
            .collect();
        let svg = figure("TP-91", &samples, &strains, [0.00177, 0.00164])
            .unwrap()
            .to_svg();
        for text in [
            "longitudinal bars",
            "hoops",
            "longitudinal yield 0.00177",
            "hoop yield 0.00164",
            "largest bar strain",
        ] {
            assert!(svg.contains(text), "no '{text}'");
        }
        let no_hoops: Vec<Vec<Option<f64>>> = strains.iter().map(|e| vec![e[0], None]).collect();
        let svg = figure("plain", &samples, &no_hoops, [0.00177, 0.00164])
            .unwrap()
            .to_svg();
        assert!(svg.contains("longitudinal yield") && !svg.contains("hoop yield"));
    }
}
