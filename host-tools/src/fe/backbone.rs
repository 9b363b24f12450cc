//! The primary curve of the polygonal hysteresis model (thesis §5.2.1,
//! Fig. 5.2) idealised from a computed monotonic torque-twist curve, so that
//! `hyst fe --backbone FILE` goes from a column's drawings to the parameter
//! file `hyst simulate --model phm-torsion --params FILE` reads.
//!
//! The thesis takes its primary curve from a monotonic analysis (SMMT, "the
//! envelope of the cyclic load - displacement behavior ... assumed to be
//! identical to the behavior under monotonic loading") and idealises it "as
//! piecewise linear functions representing elastic stiffness, strain
//! hardening, yield plateau, and strength deterioration" (Fig. 5.2), with "a
//! change in slope ... at the cracking point". It does not say how the
//! corner points are read off the curve; the rules here are:
//!
//! * **initial stiffness** `k0` ([`initial_stiffness`]): the least-squares
//!   slope through the origin of the samples whose torque lies between 10%
//!   and 30% of the largest torque, taken before the torque first exceeds
//!   30% (past the start-up of the loading, before cracking);
//! * **cracking** `(T_c / k0, T_c)` ([`cracking`]): `T_c` is the torque of
//!   the last sample before the secant `T / theta` first falls more than
//!   [`CRACKING_DROP`] below `k0`, i.e. the end of the initial linear branch
//!   found by departure from the initial stiffness. The twist is put on the
//!   initial line, so that the PHM's `k_T1 = T_c / theta_c` (§5.2.1) is the
//!   computed initial stiffness;
//! * **peak**: the sample of largest torque. The curve must have passed it:
//!   the torque at the last computed twist is at least [`PEAK_DROP`] below;
//! * **yield**: the end of the strain-hardening branch, the sample between
//!   cracking and peak that maximises the area under the idealised polygon
//!   cracking-yield-peak (equivalently, the one furthest above the chord
//!   from cracking to peak). Where the computed curve is concave the polygon
//!   lies under it, so this is the equal-energy rule restricted to corners
//!   on the curve: the vertex that leaves the least strain energy out. If no
//!   sample lies above the chord (no knee) yield is the peak and the curve
//!   has three points;
//! * **deterioration**: the sample at the last computed twist, so the
//!   idealised curve spans exactly the computed range (beyond it the PHM
//!   holds the last torque; `docs/phm.md`, gap G7).
//!
//! A piecewise-linear curve whose corners are samples gives back its yield,
//! peak and last point exactly, and its cracking point within the error of
//! the departure rule: with a post-cracking slope `k1`, the detected torque
//! exceeds `T_c` by at most `T_c k1 d / ((1 - d) k0 - k1)` (`d` =
//! [`CRACKING_DROP`]) plus one sample's torque increment (0.72% for
//! `k1 = 0.12 k0`; see the tests).

use crate::data::Unit;
use crate::model::{phm_json, PHM_POINTS};
use hysteresis::phm::{Coefficients, PhmParams};
use serde_json::Value;
use std::fmt;

/// How far the secant stiffness may fall below the initial stiffness before
/// the curve counts as cracked: 5%. An explicit run's reaction carries some
/// inertia of the rigid top, which makes its secant fall by 2-3% before
/// cracking (TP-91 at 50 mm: 29,300 to 29,100 kN m/rad against
/// `k0 = 29,800`); the same 5% as the start of `hyst fit --model phm-torsion`
/// ([`crate::fit::phm::idealise`]).
pub const CRACKING_DROP: f64 = 0.05;

/// How far the torque at the last computed twist must lie below the largest
/// torque for the curve to have a peak: 1%, as the `peak_torque` of the
/// `hyst fe` summary.
pub const PEAK_DROP: f64 = 0.01;

/// Samples the idealisation needs at least: the origin's neighbourhood,
/// cracking, yield, peak and a later point.
pub const MIN_SAMPLES: usize = 5;

/// The idealised primary curve of one direction, `[twist, torque]`
/// magnitudes in the units of the curve it was made from.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PrimaryCurve {
    /// Initial stiffness `k0`, torque per twist.
    pub initial_stiffness: f64,
    /// Cracking, on the initial line.
    pub cracking: [f64; 2],
    /// Yield: the end of strain hardening (the peak if the curve has no
    /// knee).
    pub yield_point: [f64; 2],
    /// Peak torque.
    pub peak: [f64; 2],
    /// The last computed point, on the descending branch.
    pub deterioration: [f64; 2],
}

impl PrimaryCurve {
    /// The points in the order the PHM reads them: cracking, yield, peak,
    /// deterioration; the peak is left out when it is the yield point.
    pub fn points(&self) -> Vec<[f64; 2]> {
        let mut p = vec![self.cracking, self.yield_point];
        if self.peak != self.yield_point {
            p.push(self.peak);
        }
        p.push(self.deterioration);
        p
    }

    /// A PHM parameter set with this curve in both directions (the FE
    /// twist is monotonic, the column symmetric) and the thesis' unloading
    /// and reloading coefficients (eqs 1-6, fitted in ch. 5 to the tests;
    /// a monotonic analysis says nothing about them).
    pub fn params(&self) -> Result<PhmParams<f64, PHM_POINTS>, IdealiseError> {
        PhmParams::symmetric(&self.points(), Coefficients::thesis())
            .map_err(|e| IdealiseError::NotAPrimaryCurve(e.to_string()))
    }

    /// The PHM parameter file (`docs/phm.md`; what `hyst simulate --model
    /// phm-torsion --params` reads), the curve being in degrees and kN m;
    /// `source` goes into the file's `fit` object, which the reader skips.
    pub fn phm_file(&self, source: Value) -> Result<Value, IdealiseError> {
        let params = self.params()?;
        Ok(phm_json(
            &params,
            (Unit::Degree, Unit::KilonewtonMetre),
            Some(source),
        ))
    }
}

/// Why a curve has no PHM primary curve.
#[derive(Clone, Debug, PartialEq)]
pub enum IdealiseError {
    /// Fewer than [`MIN_SAMPLES`] samples at increasing twist.
    TooFewSamples {
        /// Samples found.
        found: usize,
    },
    /// No sample between 10% and 30% of the largest torque before the
    /// torque first exceeds 30%, so no initial stiffness.
    NoInitialBranch,
    /// The secant stiffness never falls [`CRACKING_DROP`] below the initial
    /// stiffness before the peak.
    NeverCracks {
        /// The smallest secant up to the peak over the initial stiffness.
        least_secant_ratio: f64,
    },
    /// The torque at the last computed twist is not [`PEAK_DROP`] below the
    /// largest torque.
    NeverPeaks {
        /// Torque at the last twist over the largest torque.
        last_over_peak: f64,
    },
    /// The idealised points break a rule of the PHM's primary curve.
    NotAPrimaryCurve(String),
}

impl fmt::Display for IdealiseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IdealiseError::TooFewSamples { found } => write!(
                f,
                "the torque-twist curve has {found} samples at increasing twist: expected at least {MIN_SAMPLES}"
            ),
            IdealiseError::NoInitialBranch => f.write_str(
                "the torque-twist curve has no sample between 10% and 30% of its largest torque before it first exceeds 30%: expected an initial linear branch to take the initial stiffness from",
            ),
            IdealiseError::NeverCracks { least_secant_ratio } => write!(
                f,
                "the torque-twist curve never cracks before its peak: its secant stiffness falls to {:.1}% of the initial stiffness, expected a fall below {:.0}% (an elastic run, or a twist too small to crack)",
                100.0 * least_secant_ratio,
                100.0 * (1.0 - CRACKING_DROP)
            ),
            IdealiseError::NeverPeaks { last_over_peak } => write!(
                f,
                "the torque-twist curve never peaks: the torque at the last twist is {:.1}% of the largest, expected at most {:.0}% (twist further, past the peak)",
                100.0 * last_over_peak,
                100.0 * (1.0 - PEAK_DROP)
            ),
            IdealiseError::NotAPrimaryCurve(why) => {
                write!(f, "the idealised points are not a PHM primary curve: {why}")
            }
        }
    }
}

impl std::error::Error for IdealiseError {}

/// The samples at a new largest twist, as `[twist, torque]` in the
/// direction of the last sample's twist (magnitudes for a negative twist),
/// starting after the origin.
pub fn envelope(curve: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let sign = match curve.last() {
        Some(p) if p[0] < 0.0 => -1.0,
        _ => 1.0,
    };
    let mut far = 0.0;
    let mut env = vec![];
    for &[x, t] in curve {
        let (x, t) = (sign * x, sign * t);
        if x > far {
            far = x;
            env.push([x, t]);
        }
    }
    env
}

/// The initial stiffness (rule above) and the index of the first sample
/// whose torque magnitude exceeds 30% of the largest; `None` without such
/// samples.
pub fn initial_stiffness(curve: &[[f64; 2]]) -> Option<(f64, usize)> {
    let top = curve.iter().fold(0.0f64, |m, p| m.max(p[1].abs()));
    let rise = curve.iter().position(|p| p[1].abs() > 0.3 * top)?;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for &[x, t] in &curve[..rise] {
        if t.abs() >= 0.1 * top {
            sxy += x * t;
            sxx += x * x;
        }
    }
    (sxx > 0.0).then(|| (sxy / sxx, rise))
}

/// The initial stiffness and the index of the cracking sample (rule above):
/// the last sample before the secant first falls [`CRACKING_DROP`] below
/// the initial stiffness, searched up to index `until` (inclusive).
pub fn cracking(curve: &[[f64; 2]], until: usize) -> Result<(f64, usize), IdealiseError> {
    let (k0, rise) = initial_stiffness(curve).ok_or(IdealiseError::NoInitialBranch)?;
    let secant = |i: usize| curve[i][1] / curve[i][0] / k0;
    let end = until.min(curve.len() - 1);
    match (rise..=end).find(|&i| secant(i) < 1.0 - CRACKING_DROP) {
        Some(i) if i > 0 => Ok((k0, i - 1)),
        _ => Err(IdealiseError::NeverCracks {
            least_secant_ratio: (rise..=end).map(secant).fold(f64::INFINITY, f64::min),
        }),
    }
}

/// Idealises a monotonic torque-twist curve (`[twist, torque]` samples in
/// order, any consistent units) into the PHM primary curve (rules in the
/// [module docs](self)).
pub fn idealise(curve: &[[f64; 2]]) -> Result<PrimaryCurve, IdealiseError> {
    let env = envelope(curve);
    if env.len() < MIN_SAMPLES {
        return Err(IdealiseError::TooFewSamples { found: env.len() });
    }
    let p = (0..env.len())
        .max_by(|&a, &b| env[a][1].total_cmp(&env[b][1]))
        .unwrap_or(0);
    let (k0, c) = cracking(&env, p)?;
    let last = env.len() - 1;
    let tp = env[p][1];
    let last_over_peak = env[last][1] / tp;
    if !(last_over_peak < 1.0 - PEAK_DROP) {
        return Err(IdealiseError::NeverPeaks { last_over_peak });
    }
    let tc = env[c][1];
    let cracking = [tc / k0, tc];
    let above = |i: usize| {
        let k = (tp - tc) / (env[p][0] - cracking[0]);
        env[i][1] - (tc + k * (env[i][0] - cracking[0]))
    };
    let y = (c + 1..p)
        .filter(|&i| above(i) > 0.0)
        .max_by(|&a, &b| above(a).total_cmp(&above(b)))
        .unwrap_or(p);
    let curve = PrimaryCurve {
        initial_stiffness: k0,
        cracking,
        yield_point: env[y],
        peak: env[p],
        deterioration: env[last],
    };
    curve.params()?;
    Ok(curve)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Samples every `step` of the piecewise-linear curve through the
    /// origin and `corners`.
    fn polyline(corners: &[[f64; 2]], step: f64) -> Vec<[f64; 2]> {
        let end = corners[corners.len() - 1][0];
        let n = (end / step).round() as usize;
        (0..=n)
            .map(|i| {
                let x = i as f64 * step;
                let mut prev = [0.0, 0.0];
                for &c in corners {
                    if x <= c[0] + 1e-12 {
                        return [
                            x,
                            prev[1] + (c[1] - prev[1]) * (x - prev[0]) / (c[0] - prev[0]),
                        ];
                    }
                    prev = c;
                }
                [x, prev[1]]
            })
            .collect()
    }

    /// The primary curve of `tests/phm_cli.rs` (deg, kN m): `k0 = 500`,
    /// post-cracking slope 60 = 0.12 `k0`, plateau 4, deterioration.
    const CORNERS: [[f64; 2]; 4] = [[0.2, 100.0], [1.2, 160.0], [4.2, 172.0], [7.5, 150.0]];

    #[test]
    fn a_piecewise_linear_curve_gives_back_its_corners() {
        let got = idealise(&polyline(&CORNERS, 0.01)).expect("idealised");
        assert!((got.initial_stiffness - 500.0).abs() < 1e-9);
        // Cracking: secant >= 0.95 k0 up to 0.2 (k0 - k1) / (0.95 k0 - k1)
        // = 0.21205, so the sample at 0.21; torque 100.6 (+0.6%, within the
        // bound 100 * 60 * 0.05 / (475 - 60) = 0.72 plus one step's 0.6).
        assert!((got.cracking[1] - 100.6).abs() < 1e-9, "{:?}", got.cracking);
        assert!((got.cracking[0] - 100.6 / 500.0).abs() < 1e-12);
        assert!(got.cracking[1] - 100.0 <= 100.0 * 60.0 * 0.05 / (475.0 - 60.0) + 0.6);
        for (a, b) in [
            (got.yield_point, CORNERS[1]),
            (got.peak, CORNERS[2]),
            (got.deterioration, CORNERS[3]),
        ] {
            assert!(
                (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9,
                "{a:?} vs {b:?}"
            );
        }
        assert_eq!(got.points().len(), 4);
    }

    #[test]
    fn corners_between_samples_are_found_within_one_step() {
        // Corners off the 0.013 grid; each point within one step in twist
        // and the torque change over one step.
        let step = 0.013;
        let got = idealise(&polyline(&CORNERS, step)).expect("idealised");
        let slope: [f64; 4] = [500.0, 60.0, 4.0, 22.0 / 3.3];
        for (i, (a, b)) in [
            (got.yield_point, CORNERS[1]),
            (got.peak, CORNERS[2]),
            (got.deterioration, CORNERS[3]),
        ]
        .into_iter()
        .enumerate()
        {
            assert!((a[0] - b[0]).abs() <= step, "{a:?} vs {b:?}");
            assert!(
                (a[1] - b[1]).abs() <= step * slope[i].max(slope[i + 1]),
                "{a:?} vs {b:?}"
            );
        }
        assert!((got.cracking[1] - 100.0).abs() <= 0.72 + step * 60.0);
    }

    #[test]
    fn a_ripple_moves_the_corners_no_further_than_it_can() {
        // A ripple of amplitude a = 0.5% of the torque, as the inertia of an
        // explicit run leaves on its curve. A corner between slopes s1 > s2
        // can move by at most 2 a T_max / min(s1 - s_chord, s_chord - s2)
        // in twist: yield 2 (0.86) / (17.5 - 4) = 0.13, peak (slopes 4 and
        // -6.7 about a flat top) 2 (0.86) / 4 = 0.43. Torques stay within
        // 2% (the ripple plus the slope over the shift).
        let curve: Vec<[f64; 2]> = polyline(&CORNERS, 0.01)
            .into_iter()
            .enumerate()
            .map(|(i, [x, t])| [x, t * (1.0 + 0.005 * (i as f64 * 0.7).sin())])
            .collect();
        let got = idealise(&curve).expect("idealised");
        for (a, b, dx) in [
            (got.cracking, CORNERS[0], 0.01),
            (got.yield_point, CORNERS[1], 0.13),
            (got.peak, CORNERS[2], 0.43),
            (got.deterioration, CORNERS[3], 1e-9),
        ] {
            assert!((a[1] / b[1] - 1.0).abs() < 0.02, "{a:?} vs {b:?}");
            assert!((a[0] - b[0]).abs() <= dx, "{a:?} vs {b:?}");
        }
    }

    #[test]
    fn negative_twist_gives_magnitudes_and_no_knee_gives_three_points() {
        // Straight hardening from cracking to the peak: yield is the peak.
        let corners = [[1.0, 10.0], [5.0, 14.0], [6.0, 12.0]];
        let curve: Vec<[f64; 2]> = polyline(&corners, 0.05)
            .into_iter()
            .map(|[x, t]| [-x, -t])
            .collect();
        let got = idealise(&curve).expect("idealised");
        assert_eq!(got.yield_point, got.peak);
        let pts = got.points();
        assert_eq!(pts.len(), 3);
        assert!((pts[1][0] - 5.0).abs() < 1e-9 && (pts[1][1] - 14.0).abs() < 1e-9);
        assert!((pts[2][0] - 6.0).abs() < 1e-9);
        got.params().expect("a valid PHM curve");
    }

    #[test]
    fn curves_without_cracking_or_peak_are_refused_with_what_was_expected() {
        // An elastic run.
        let linear = polyline(&[[10.0, 50.0]], 0.1);
        let e = idealise(&linear).unwrap_err();
        let IdealiseError::NeverCracks { least_secant_ratio } = e else {
            panic!("{e:?}");
        };
        assert!((least_secant_ratio - 1.0).abs() < 1e-9);
        assert!(
            e.to_string().contains("never cracks before its peak"),
            "{e}"
        );
        assert!(e.to_string().contains("expected a fall below 95%"), "{e}");
        // Linear up, then down: a peak but no cracking before it.
        let brittle = polyline(&[[10.0, 50.0], [11.0, 20.0]], 0.1);
        let e = idealise(&brittle).unwrap_err();
        assert!(matches!(e, IdealiseError::NeverCracks { .. }), "{e:?}");
        // Cracks and hardens but never turns down.
        let hardening = polyline(&[[1.0, 10.0], [5.0, 14.0]], 0.05);
        let e = idealise(&hardening).unwrap_err();
        assert_eq!(
            e,
            IdealiseError::NeverPeaks {
                last_over_peak: 1.0
            }
        );
        assert!(e.to_string().contains("never peaks"), "{e}");
        assert!(e.to_string().contains("expected at most 99%"), "{e}");
        let e = idealise(&[[0.0, 0.0], [1.0, 1.0], [2.0, 1.5]]).unwrap_err();
        assert_eq!(e, IdealiseError::TooFewSamples { found: 2 });
        assert!(e.to_string().contains("expected at least 5"), "{e}");
        assert!(idealise(&[]).is_err());
        let nan = vec![[f64::NAN, 1.0]; 10];
        assert!(idealise(&nan).is_err());
    }

    #[test]
    fn the_file_is_what_the_phm_reader_reads() {
        let got = idealise(&polyline(&CORNERS, 0.01)).expect("idealised");
        let v = got
            .phm_file(serde_json::json!({"method": "test"}))
            .expect("file");
        let f = crate::model::PhmFile::from_value(std::path::Path::new("t.json"), &v)
            .expect("a PHM file");
        assert_eq!(f.params, got.params().expect("params"));
        assert_eq!(v["units"]["twist"], "deg");
    }
}
