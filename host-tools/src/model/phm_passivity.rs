//! Does a PHM parameter set return energy over closed cycles? A search, run
//! after a fit: the element's rules are passive for the thesis' coefficients
//! in every cycle the core's tests search, but a fit may move the
//! coefficients where they are not (`docs/phm.md`, "Open points": with every
//! coefficient scaled by 0.7-1.3, 313 of 5,209 closed cycles returned
//! energy).
//!
//! A cycle is closed when the element's state repeats: random histories
//! within a twist span, then a cycle through two or three random twists
//! driven until its end state (torque, branch, rule memory) is the one of the
//! repetition before. The work `∮ T dθ` over such a cycle is the energy the
//! element takes in; a negative one is returned.

use super::PHM_POINTS;
use crate::random::Rng;
use hysteresis::phm::{closed_cycle_work, Direction, Phm, PhmParams};
use hysteresis::Element;
use serde::Serialize;

/// The element the search drives (the default memory of 16 entries).
type Element16 = Phm<f64, PHM_POINTS, 16>;

/// A closed cycle that returns energy.
#[derive(Clone, Debug, Serialize)]
pub struct Returning {
    /// The twists driven before the cycle (from the virgin state).
    pub history: Vec<f64>,
    /// The cycle's twists, from the first back to it.
    pub cycle: Vec<f64>,
    /// `∮ T dθ` over one repetition (negative).
    pub work: f64,
}

/// The result of [`search`].
#[derive(Clone, Debug, Serialize)]
pub struct Passivity {
    /// Closed cycles found (cycles whose state did not repeat within six
    /// repetitions are not counted).
    pub cycles: usize,
    /// How many of them return energy.
    pub returning_energy: usize,
    /// The cycle returning the most energy, if any.
    pub worst: Option<Returning>,
}

/// Searches `draws` random closed cycles within twists `[-span, span]`
/// (seeded, so the same on every run). A cycle returns energy when its work
/// is below `-1e-9` of the peak torque times `span`.
pub fn search(
    params: &PhmParams<f64, PHM_POINTS>,
    span: f64,
    draws: usize,
    seed: u64,
) -> Passivity {
    let peak = [Direction::Positive, Direction::Negative]
        .iter()
        .flat_map(|&d| params.primary(d).points().iter().map(|p| p[1]))
        .fold(0.0f64, f64::max);
    let h = span / 100.0;
    let mut rng = Rng::seed_from_u64(seed);
    let twist = |rng: &mut Rng| (2.0 * rng.uniform() - 1.0) * span;
    let mut out = Passivity {
        cycles: 0,
        returning_energy: 0,
        worst: None,
    };
    for _ in 0..draws {
        let mut el = Element16::new(params.clone());
        let history: Vec<f64> = (0..rng.below(5)).map(|_| twist(&mut rng)).collect();
        let corners: Vec<f64> = (0..2 + rng.below(2)).map(|_| twist(&mut rng)).collect();
        let Some(closed) = closed_cycle(&mut el, &history, &corners, h) else {
            continue;
        };
        out.cycles += 1;
        if closed < -1e-9 * peak * span {
            out.returning_energy += 1;
            if out.worst.as_ref().is_none_or(|w| closed < w.work) {
                out.worst = Some(Returning {
                    history,
                    cycle: corners,
                    work: closed,
                });
            }
        }
    }
    out
}

/// Drives `el` through `history` (10 steps a leg), then repeats the cycle
/// through `corners` until the state repeats; the work over that last
/// repetition, or `None` if it did not close within six (or a step failed).
fn closed_cycle(el: &mut Element16, history: &[f64], corners: &[f64], h: f64) -> Option<f64> {
    for &x in history {
        let from = el.displacement();
        for i in 1..=10 {
            el.set_trial(from + (x - from) * f64::from(i) / 10.0).ok()?;
            el.commit();
        }
    }
    closed_cycle_work(el, corners, h, 6).ok().flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hysteresis::phm::Coefficients;

    fn column(scale_eq1a_b: f64) -> PhmParams<f64, PHM_POINTS> {
        let c = Coefficients::thesis();
        let c = Coefficients::from_named(|n| {
            c.get(n)
                .map(|v| if n == "eq1a_b" { v * scale_eq1a_b } else { v })
        })
        .unwrap();
        let pts = [[1.35, 14.59], [6.68, 20.48], [12.01, 20.74], [20.37, 16.18]];
        PhmParams::symmetric(&pts, c).unwrap()
    }

    /// A column (a random curve of a search) with the thesis' coefficients
    /// returns no energy in any cycle found; with eq. 1a's intercept at 0.7
    /// of its value (the first unloading point then lies before the reversal
    /// instead of 5 % past it, so the unloading starts flatter than `k_T1`)
    /// some cycles do. (Of the first ten random curves of that search, nine
    /// returned energy in 2 to 5 of about 61 closed cycles with that
    /// coefficient, none with the thesis' values.)
    #[test]
    fn the_thesis_column_is_passive_and_a_flatter_unloading_is_not() {
        let thesis = search(&column(1.0), 26.0, 400, 7);
        assert!(thesis.cycles > 50, "{thesis:?}");
        assert_eq!(thesis.returning_energy, 0, "{thesis:?}");
        let flat = search(&column(0.7), 26.0, 400, 7);
        eprintln!("{flat:?}");
        assert!(flat.returning_energy > 0, "{flat:?}");
        let worst = flat.worst.unwrap();
        assert!(worst.work < 0.0);
    }
}
