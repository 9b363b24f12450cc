//! The torque-twist curve of a run set against the measured torques (thesis
//! Fig. 2.1 and Table 2.1): where the computed curve cracks and peaks, the
//! test's cracking and ultimate torques as reference lines, the thesis's
//! ABAQUS values in a note (their lines would crowd the test's), and the
//! part of the run after the peak shaded when the quasi-static checks fail
//! there but hold up to the peak.

use super::output::Sample;
use super::specimen::TorqueReference;
use crate::report::{Anchor, Annotation, Axis, Error, Figure, Panel, Series};

/// How a computed torque compares with Table 2.1, kN m.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// The values the run is compared with.
    pub reference: TorqueReference,
    /// `(computed - test) / test` of the cracking torque, if the run
    /// cracked.
    pub cracking_error: Option<f64>,
    /// `(computed - test) / test` of the peak torque, if the run peaked.
    pub peak_error: Option<f64>,
}

impl Comparison {
    /// Compares computed cracking and peak torques (kN m) with `reference`.
    pub fn new(reference: TorqueReference, cracking: Option<f64>, peak: Option<f64>) -> Self {
        Comparison {
            reference,
            cracking_error: cracking.map(|c| c / reference.test_cracking_knm - 1.0),
            peak_error: peak.map(|p| p / reference.test_peak_knm - 1.0),
        }
    }
}

/// What the figure marks on the computed curve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Marks {
    /// Index of the sample the cracking torque is read from.
    pub cracking: Option<usize>,
    /// Index of the peak sample.
    pub peak: Option<usize>,
    /// The quasi-static checks hold up to the peak and fail over the whole
    /// run: the part after the peak is shaded as not quasi-static.
    pub fails_after_peak: bool,
}

/// The figure: torque (kN m) against twist (rad) of `samples`, with the
/// marks and, if given, the torques of Table 2.1 as horizontal lines.
pub fn figure(
    title: &str,
    samples: &[Sample],
    marks: Marks,
    reference: Option<&TorqueReference>,
) -> Result<Figure, Error> {
    let twist: Vec<f64> = samples.iter().map(|s| s.twist).collect();
    let torque: Vec<f64> = samples.iter().map(|s| s.torque / 1e3).collect();
    // Head room above the highest of the curve and the two ultimate
    // torques of Table 2.1, so that the reference lines' labels stay clear
    // of the shaded band's label at the top.
    let refs = reference.map_or(0.0, |r| r.test_peak_knm.max(r.thesis_fe_peak_knm));
    let top = torque.iter().fold(refs, |m, &t| m.max(t));
    let bottom = torque.iter().fold(0.0f64, |m, &t| m.min(t));
    let mut y = Axis::linear("torque", "kN m").include_zero();
    if top > 0.0 && top.is_finite() && bottom.is_finite() {
        y = y.limits(bottom * 1.05, top * 1.15);
    }
    let mut panel = Panel::new(Axis::linear("twist", "rad").include_zero(), y);
    panel.series(Series::line("computed", &twist, &torque)?.width(2.0));
    if let Some(r) = reference {
        panel
            .hline(
                r.test_cracking_knm,
                &format!("test cracking {:.1}", r.test_cracking_knm),
            )
            .hline(
                r.test_peak_knm,
                &format!("test ultimate {:.1}", r.test_peak_knm),
            );
        panel.note(&format!(
            "Table 2.1, kN m: test cracking {:.1}, ultimate {:.1}; thesis FE cracking {:.1}, ultimate {:.1}",
            r.test_cracking_knm, r.test_peak_knm, r.thesis_fe_cracking_knm, r.thesis_fe_peak_knm
        ));
    }
    for (i, name) in [(marks.cracking, "cracking"), (marks.peak, "peak")] {
        if let Some(i) = i.filter(|&i| i < samples.len()) {
            panel.annotate(
                Annotation::new(twist[i], torque[i], &format!("{name} {:.1}", torque[i]))
                    .anchor(Anchor::Start)
                    .offset(8.0, 14.0)
                    .ring(),
            );
        }
    }
    if let (true, Some(p)) = (marks.fails_after_peak, marks.peak) {
        if let Some(&end) = twist.last() {
            if p < samples.len() && end > twist[p] {
                panel.band(twist[p], end, "after the peak: not quasi-static");
            }
        }
    }
    let mut fig = Figure::new(720.0, 460.0);
    fig.title(title).panel(panel);
    Ok(fig)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(twist: f64, torque_knm: f64) -> Sample {
        Sample::on_curve(twist, torque_knm * 1e3)
    }

    const TP91: TorqueReference = TorqueReference {
        test_cracking_knm: 60.7,
        test_peak_knm: 76.6,
        thesis_fe_cracking_knm: 62.9,
        thesis_fe_peak_knm: 82.0,
    };

    #[test]
    fn errors_are_relative_to_the_test() {
        let c = Comparison::new(TP91, Some(42.49), Some(61.28));
        assert!((c.cracking_error.unwrap() - (42.49 / 60.7 - 1.0)).abs() < 1e-15);
        assert!((c.peak_error.unwrap() + 0.2).abs() < 1e-12);
        let none = Comparison::new(TP91, None, None);
        assert_eq!((none.cracking_error, none.peak_error), (None, None));
    }

    #[test]
    fn the_figure_shows_the_curve_the_marks_and_table_2_1() {
        let samples: Vec<Sample> = (0..=40)
            .map(|i| {
                let th = 0.002 * i as f64;
                sample(
                    th,
                    (30_000.0 * th).min(59.0 + 500.0 * th) - 2e4 * (th - 0.05).max(0.0),
                )
            })
            .collect();
        let marks = Marks {
            cracking: Some(1),
            peak: Some(25),
            fails_after_peak: true,
        };
        let svg = figure("TP-91", &samples, marks, Some(&TP91))
            .unwrap()
            .to_svg();
        for text in [
            "test cracking 60.7",
            "test ultimate 76.6",
            "thesis FE cracking 62.9, ultimate 82.0",
            &format!("peak {:.1}", samples[25].torque / 1e3),
            "cracking 60.0",
            "after the peak: not quasi-static",
        ] {
            assert!(svg.contains(text), "no '{text}' in the figure");
        }
        let plain = figure("TP-91", &samples, Marks::default(), None)
            .unwrap()
            .to_svg();
        assert!(!plain.contains("test cracking") && !plain.contains("after the peak"));
    }
}
