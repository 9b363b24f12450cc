//! The loading of the OpenSees reference cases (`../shared/data/opensees-reference`)
//! and the parameter sets they were run with, generated in code so that the
//! target needs no data files.
//!
//! History: 3 triangular cycles 0 -> +A -> 0 -> -A -> 0 at each of A = 0.5, 1,
//! 2, 4, 6, 8 mm, 200 steps a cycle, 3601 points starting at 0
//! (`history.csv`; a host test checks that the two agree bit for bit).
//! Parameters (kN, mm): alpha 0.2, k0 6, n 1.2, beta 2, gamma -1.

use crate::bwbn::{BoucWen, BwbnParams, EffectKind, EffectSet};
use crate::scalar::{Fixed, Scalar};

/// Number of points of the history.
pub const POINTS: usize = 3601;
const STEPS_PER_CYCLE: usize = 200;
const CYCLES_PER_AMPLITUDE: usize = 3;
/// Points per amplitude: the history returns to 0 after each block of
/// closed cycles.
pub const BLOCK: usize = STEPS_PER_CYCLE * CYCLES_PER_AMPLITUDE;
/// Amplitudes in units of 0.01 mm per quarter-cycle step: A = 0.5 mm is
/// 50 quarter-cycle steps of 0.01 mm.
const AMPLITUDE_HALF_MM: [i32; 6] = [1, 2, 4, 8, 12, 16];

/// The displacement (mm) at point `i` of the history, `i < POINTS`:
/// `A * t / 50` with `t` the position on the triangle wave (-50..=50),
/// computed as one rounded division `(2A t) / 100` in the arithmetic `S`.
pub fn displacement<S: Scalar>(i: usize) -> S {
    let amplitude = AMPLITUDE_HALF_MM[i.saturating_sub(1) / BLOCK];
    let k = (i % STEPS_PER_CYCLE) as i32;
    let tri = match k {
        0..=50 => k,
        51..=150 => 100 - k,
        _ => k - 200,
    };
    S::ratio(amplitude * tri, 100)
}

/// Checks the generated history: 3601 points, starting and ending at 0, a
/// peak of +-A on every cycle, steps of A/50.
pub fn shape() {
    let amplitudes = [0.5, 1.0, 2.0, 4.0, 6.0, 8.0];
    assert!(displacement::<f64>(0) == 0.0 && displacement::<f64>(POINTS - 1) == 0.0);
    for (b, a) in amplitudes.iter().enumerate() {
        for c in 0..CYCLES_PER_AMPLITUDE {
            let start = (b * CYCLES_PER_AMPLITUDE + c) * STEPS_PER_CYCLE;
            let peak = |k: usize| displacement::<f64>(start + k);
            assert!(
                peak(50) == *a && peak(150) == -*a && peak(100) == 0.0,
                "cycle {} of {} mm",
                c,
                a
            );
            for k in 1..=STEPS_PER_CYCLE {
                let du = Scalar::abs(peak(k) - peak(k - 1));
                assert!(
                    Scalar::abs(du - a / 50.0) < 1e-12,
                    "step {} of cycle {} of {} mm",
                    k,
                    c,
                    a
                );
            }
        }
    }
}

/// Base parameters of every reference case.
const BASE: [(&str, f64); 5] = [
    ("k0", 6.0),
    ("alpha", 0.2),
    ("n", 1.2),
    ("beta", 2.0),
    ("gamma", -1.0),
];

/// The degradation rates of OpenSees' `BoucWen_degrade` case (per kN mm).
const DEGRADATION: [(&str, f64); 3] = [("delta_A", 2e-4), ("delta_nu", 5e-4), ("delta_eta", 5e-4)];

/// The pinching parameters of OpenSees' `BWBN_pinch` case.
const PINCHING: [(&str, f64); 6] = [
    ("zeta0", 0.9),
    ("p", 0.01),
    ("q", 0.1),
    ("psi0", 0.2),
    ("delta_psi", 5e-4),
    ("lambda", 0.5),
];

/// The energy range (kN mm) the degrading sets are validated for: A = 1 -
/// 2e-4 e stays above 0.6. A step beyond it is refused, so the accuracy
/// cases, which commit every point, also check that the history stays inside.
pub const ENERGY_LIMIT: f64 = 2000.0;

/// One of the reference parameter sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Set {
    /// Plain Bouc-Wen.
    Plain,
    /// A, strength and stiffness degradation.
    Degrading,
    /// Pinching.
    Pinching,
    /// All four effects: the thesis' BWBN model.
    All,
}

impl Set {
    /// Every set, in the order the reports list them.
    pub const ALL: [Set; 4] = [Set::Plain, Set::Degrading, Set::Pinching, Set::All];

    /// Short name for reports.
    pub const fn name(self) -> &'static str {
        match self {
            Set::Plain => "plain",
            Set::Degrading => "degrading",
            Set::Pinching => "pinching",
            Set::All => "all-four",
        }
    }

    /// The effects that are on.
    pub fn effects(self) -> EffectSet {
        let degrading = EffectSet::NONE
            .with(EffectKind::ADegradation)
            .with(EffectKind::StrengthDegradation)
            .with(EffectKind::StiffnessDegradation);
        match self {
            Set::Plain => EffectSet::NONE,
            Set::Degrading => degrading,
            Set::Pinching => EffectSet::NONE.with(EffectKind::Pinching),
            Set::All => EffectSet::BWBN,
        }
    }

    /// The value of parameter `name` in this set, in `f64`.
    pub fn value(self, name: &str) -> Option<f64> {
        let degrading = matches!(self, Set::Degrading | Set::All);
        let pinching = matches!(self, Set::Pinching | Set::All);
        let find = |list: &[(&str, f64)]| list.iter().find(|(n, _)| *n == name).map(|p| p.1);
        find(&BASE)
            .or(if degrading { find(&DEGRADATION) } else { None })
            .or(if pinching { find(&PINCHING) } else { None })
            .or(if degrading && name == crate::bwbn::ENERGY_LIMIT {
                Some(ENERGY_LIMIT)
            } else {
                None
            })
    }

    /// The validated parameter set in arithmetic `S`, each value rounded
    /// once from its decimal `f64`.
    pub fn params<S: Scalar>(self) -> BwbnParams<S> {
        BwbnParams::from_named(self.effects(), |name| self.value(name).map(S::from_f64))
            .expect("the reference sets are valid")
    }

    /// The parameter set in `S` with every value first rounded to Q15.16:
    /// the values a fixed-point element holds, exact in `f32` and `f64` as
    /// well, so that elements in different arithmetics run the same model.
    pub fn params_q16<S: Scalar>(self) -> BwbnParams<S> {
        BwbnParams::from_named(self.effects(), |name| {
            self.value(name)
                .map(|v| S::from_f64(Fixed::from_f64(v).to_f64()))
        })
        .expect("the reference sets are valid")
    }
}

/// The plain base model in `S`.
pub fn base<S: Scalar>() -> BoucWen<S> {
    let v = BASE.map(|(_, v)| S::from_f64(v));
    BoucWen::new(v[0], v[1], v[2], v[3], v[4]).expect("the reference base parameters are valid")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn history_matches_the_opensees_reference_file_bit_for_bit() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/data/opensees-reference/history.csv");
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut rows = 0;
        for (line_no, line) in text.lines().enumerate().skip(1) {
            let mut cols = line.split(',');
            let step: usize = cols.next().unwrap().parse().unwrap();
            let u: f64 = cols.next().unwrap().parse().unwrap();
            assert_eq!(
                step,
                rows,
                "{}:{}: step number",
                path.display(),
                line_no + 1
            );
            let ours = displacement::<f64>(step);
            assert_eq!(
                ours.to_bits(),
                u.to_bits(),
                "{}:{}: step {step}: file {u:?}, generated {ours:?}",
                path.display(),
                line_no + 1
            );
            rows += 1;
        }
        assert_eq!(rows, POINTS);
    }
}
