//! The work `∫ T dθ` an element takes in along a twist path: the energy
//! balance of a cycle (dissipated when positive, returned when negative).

use super::Phm;
use crate::element::{Element, StepError};

/// Work `∫ T dθ` from the committed twist to `to`, committing steps of at
/// most `h` (the element ends committed at `to`). The PHM's torque is
/// piecewise linear in the twist, so a step whose midpoint is off its chord
/// is split there until the trapezoid rule is exact (to `1e-13` of the
/// torques, or a step of `1e-9`); the result does not depend on `h` beyond
/// rounding. A step that fails stops the walk with its error (the element
/// keeps what was committed before it).
///
/// ```
/// use hysteresis::phm::{work_along, Coefficients, Phm, PhmParams};
///
/// let p = PhmParams::<f64>::symmetric(&[[1.0, 10.0], [5.0, 20.0], [10.0, 20.0]], Coefficients::thesis())
///     .unwrap();
/// let mut el: Phm<f64> = Phm::new(p);
/// // Elastic to 0.5: the work is k θ² / 2 = 10 * 0.25 / 2.
/// let w = work_along(&mut el, 0.5, 0.1).unwrap();
/// assert!((w - 1.25).abs() < 1e-12);
/// // A full cycle to ±8 dissipates.
/// let cycle = [8.0, -8.0, 0.0].iter().map(|&x| work_along(&mut el, x, 0.1).unwrap()).sum::<f64>();
/// assert!(cycle > 0.0);
/// ```
pub fn work_along<const N: usize, const M: usize>(
    el: &mut Phm<f64, N, M>,
    to: f64,
    h: f64,
) -> Result<f64, StepError> {
    fn piece<const N: usize, const M: usize>(
        el: &mut Phm<f64, N, M>,
        b: f64,
    ) -> Result<f64, StepError> {
        let (a, ta) = (el.displacement(), el.response().force);
        let mid = 0.5 * (a + b);
        let tm = el.set_trial(mid)?.force;
        let tb = el.set_trial(b)?.force;
        if (tm - 0.5 * (ta + tb)).abs() <= 1e-13 * (1.0 + ta.abs() + tb.abs())
            || (b - a).abs() < 1e-9
        {
            el.commit();
            return Ok(0.5 * (ta + tb) * (b - a));
        }
        el.revert();
        Ok(piece(el, mid)? + piece(el, b)?)
    }
    if !(to.is_finite() && h > 0.0) {
        return Err(StepError::NonFiniteInput);
    }
    let mut w = 0.0;
    while el.displacement() != to {
        let x0 = el.displacement();
        let step = if (to - x0).abs() <= h {
            to
        } else {
            x0 + h * (to - x0).signum()
        };
        w += piece(el, step)?;
    }
    Ok(w)
}

/// The work over a cycle through `corners` (from the first through the
/// others back to the first), repeated until the element's state after a
/// repetition (torque and tangent, what it follows, the rule memory, the
/// branch and the depth of the inner-cycle memory) is the one after the
/// repetition before: that closed cycle's work,
/// or `None` if the state has not repeated within `repeats` repetitions (or
/// `corners` is empty). The element is first taken to `corners[0]`, whose
/// work is not counted; steps as in [`work_along`].
pub fn closed_cycle_work<const N: usize, const M: usize>(
    el: &mut Phm<f64, N, M>,
    corners: &[f64],
    h: f64,
    repeats: usize,
) -> Result<Option<f64>, StepError> {
    let Some(&first) = corners.first() else {
        return Ok(None);
    };
    work_along(el, first, h)?;
    let state = |e: &Phm<f64, N, M>| {
        (
            e.response(),
            e.committed().kind(),
            *e.levels(),
            *e.branch(),
            e.memory_depth(),
        )
    };
    let mut before = state(el);
    for _ in 0..repeats {
        let mut w = 0.0;
        for &x in corners[1..].iter().chain(&corners[..1]) {
            w += work_along(el, x, h)?;
        }
        let after = state(el);
        if after == before {
            return Ok(Some(w));
        }
        before = after;
    }
    Ok(None)
}
