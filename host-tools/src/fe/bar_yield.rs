//! The torque against the largest strain of each bar set (thesis Fig. 2.2:
//! in the tests the hoops yield before the longitudinal bars), with each
//! set's yield strain `f_y / E_s` as a line, so that which set yields first,
//! and at what torque, is seen at a glance.

use super::output::{self, Sample};
use crate::report::{Axis, Error, Figure, Panel, Series};

/// The figure: torque (kN m) against the largest axial strain of the
/// longitudinal bars and of the hoops (`strains[i]` of sample `i` starts
/// with those two, `None` for a set without bars), with the yield strains
/// `eps_y` of the two sets as vertical lines. The curves end where the
/// torque has fallen below 80 % of its peak: in the collapse after it the
/// hoop strains grow tenfold (to 0.03 on H/D(6)) and would squeeze the
/// yielding near the peak, which the figure is for, into a corner.
pub fn figure(
    title: &str,
    samples: &[Sample],
    strains: &[Vec<Option<f64>>],
    eps_y: [f64; 2],
) -> Result<Figure, Error> {
    let (end, peak) = cut(samples);
    let torque: Vec<f64> = samples.iter().map(|s| s.torque.abs() / 1e3).collect();
    let mut panel = Panel::new(
        Axis::linear("largest bar strain", "-").include_zero(),
        Axis::linear("torque", "kN m").include_zero(),
    );
    // Two yield strains a few per cent apart (H/D(6): 0.00229 and 0.00231)
    // would print their labels over each other: one label then names both.
    let close = (eps_y[0] - eps_y[1]).abs() < 0.1 * eps_y[0].max(eps_y[1]);
    let mut drawn = [false; 2];
    for (set, name) in ["longitudinal bars", "hoops"].into_iter().enumerate() {
        let (x, y): (Vec<f64>, Vec<f64>) = strains[..end.min(strains.len())]
            .iter()
            .zip(&torque)
            .filter_map(|(e, &t)| e.get(set).copied().flatten().map(|e| (e, t)))
            .unzip();
        if !x.is_empty() {
            panel.series(Series::line(name, &x, &y)?.width(2.0).palette(set));
            drawn[set] = true;
        }
    }
    let label = |set: usize| {
        let name = ["longitudinal yield", "hoop yield"][set];
        format!("{name} {:.5}", eps_y[set])
    };
    match drawn {
        [true, true] if close => {
            panel.vline(eps_y[0], &format!("{}, {}", label(0), label(1)));
            panel.vline(eps_y[1], "");
        }
        _ => {
            for set in (0..2).filter(|&s| drawn[s]) {
                panel.vline(eps_y[set], &label(set));
            }
        }
    }
    if end < torque.len() {
        panel.note(&format!(
            "up to the torque falling below 80 % of its peak ({:.1} kN m)",
            peak / 1e3
        ));
    }
    let mut fig = Figure::new(720.0, 460.0);
    fig.title(title).panel(panel);
    Ok(fig)
}

/// The number of samples drawn (those before the first after the peak
/// below 80 % of it) and the peak torque, N m.
fn cut(samples: &[Sample]) -> (usize, f64) {
    let Some((peak_at, peak)) = output::largest_torque(samples) else {
        return (0, 0.0);
    };
    let end = (peak_at..samples.len())
        .find(|&i| samples[i].torque.abs() < 0.8 * peak)
        .unwrap_or(samples.len());
    (end, peak)
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
        // Yield strains 1% apart share one label.
        let svg = figure("close", &samples, &strains, [0.00231, 0.00229])
            .unwrap()
            .to_svg();
        assert!(svg.contains("longitudinal yield 0.00231, hoop yield 0.00229"));
    }

    /// The curves end where the torque falls below 80 % of its peak, and a
    /// note says so.
    #[test]
    fn the_collapse_after_the_peak_is_cut() {
        // Up to 60 kN m at sample 10, then down by 5 kN m a sample: 45 kN m
        // (75 %) at sample 13 is the first below 48; the dip to 40 % before
        // the peak does not count.
        let torque: Vec<f64> = (0..=16)
            .map(|i| match i {
                3 => 7.0,
                0..=10 => 6.0 * i as f64,
                _ => 60.0 - 5.0 * (i - 10) as f64,
            })
            .collect();
        let samples: Vec<Sample> = (0..=16)
            .map(|i| Sample::on_curve(0.001 * i as f64, 1e3 * torque[i]))
            .collect();
        assert_eq!(cut(&samples), (13, 60e3));
        assert_eq!(cut(&samples[..12]), (12, 60e3));
        let strains: Vec<Vec<Option<f64>>> = (0..=16)
            .map(|i| vec![Some(1e-4 * i as f64), Some(1e-4 * i as f64)])
            .collect();
        let svg = figure("cut", &samples, &strains, [0.00177, 0.00164])
            .unwrap()
            .to_svg();
        assert!(svg.contains("up to the torque falling below 80 % of its peak (60.0 kN m)"));
        let svg = figure("whole", &samples[..12], &strains[..12], [0.00177, 0.00164])
            .unwrap()
            .to_svg();
        assert!(!svg.contains("below 80 %"));
    }
}
