//! The element contract of [`Element`] (see `src/element.rs`), in every
//! arithmetic, on the all-effects set in the middle of a 4 mm cycle:
//!
//! * a trial never changes the committed state, and every trial starts from
//!   the committed state, not from the previous trial;
//! * revert and then the same trial gives bit-identical results;
//! * non-finite input is refused with [`StepError::NonFiniteInput`], a step
//!   beyond the sub-step budget with [`StepError::ToleranceNotMet`], and
//!   neither changes anything (not even a pending trial);
//! * reset returns to the virgin state, from which the history repeats bit
//!   for bit;
//! * the smallest increment the arithmetic can represent does not stall the
//!   next, ordinary one (the sub-step size carried over from it is far below
//!   the next increment's resolution).

use super::history::{displacement, Set};
use crate::bwbn::{Bwbn, Control, State};
use crate::element::{Element, Response, StepError};
use crate::scalar::{Fixed, Scalar};

/// Point of the history the element is committed at: on the way down from
/// +4 mm, at -2.4 mm, after 4.5 cycles with pinching and degradation active.
const AT: usize = 1930;
/// A trial continuing the same direction (-2.48 mm).
const NEXT: usize = AT + 1;
/// A trial reversing, with an increment of 0.4 mm (-2.0 mm). (The default
/// `f64` control, Dp54 at 1e-9 in at most 64 sub-steps, refuses a single
/// increment larger than about 4.5 mm from the virgin state, or a reversal
/// of more than 1.7 mm (plain) to 3.7 mm (all four) from -4.8 mm in the
/// 8 mm cycles, as `ToleranceNotMet`: callers subdivide large increments.)
const FAR: usize = 1925;

fn bits<S: Scalar>(x: S) -> u64 {
    x.to_f64().to_bits()
}

fn same_response<S: Scalar>(a: Response<S>, b: Response<S>) -> bool {
    bits(a.force) == bits(b.force) && bits(a.tangent) == bits(b.tangent)
}

fn same_state<S: Scalar>(a: &State<S>, b: &State<S>) -> bool {
    a == b && bits(a.u) == bits(b.u) && bits(a.z) == bits(b.z) && bits(a.energy) == bits(b.energy)
}

fn trial<S: Scalar>(el: &mut Bwbn<S>, i: usize) -> Response<S> {
    match el.set_trial(displacement(i)) {
        Ok(r) => r,
        Err(e) => panic!("{}: trial at point {} refused: {}", S::NAME, i, e),
    }
}

/// An element with the history committed up to point `to`.
fn driven<S: Scalar>(to: usize) -> Bwbn<S> {
    let mut el = Bwbn::new(Set::All.params());
    for i in 1..=to {
        trial(&mut el, i);
        el.commit();
    }
    el
}

fn trial_commit_revert<S: Scalar>() {
    let mut el = driven::<S>(AT);
    let committed = *el.committed();
    let r0 = el.response();

    let ra = trial(&mut el, NEXT);
    let trial_a = *el.trial();
    assert!(
        same_state(el.committed(), &committed),
        "{}: a trial changed the committed state",
        S::NAME
    );
    assert!(
        bits(el.displacement()) == bits(committed.u),
        "{}: displacement() follows the trial",
        S::NAME
    );
    assert!(
        !same_state(&trial_a, &committed),
        "{}: the trial did not move",
        S::NAME
    );

    trial(&mut el, FAR);
    assert!(
        same_state(el.committed(), &committed),
        "{}: a second trial changed the committed state",
        S::NAME
    );
    let again = trial(&mut el, NEXT);
    assert!(
        same_response(again, ra) && same_state(el.trial(), &trial_a),
        "{}: a trial depends on the previous trial, not only on the committed state",
        S::NAME
    );

    el.revert();
    assert!(
        same_state(el.trial(), &committed),
        "{}: revert did not restore the trial state",
        S::NAME
    );
    assert!(
        same_response(el.response(), r0),
        "{}: revert did not restore the response",
        S::NAME
    );
    let after_revert = trial(&mut el, NEXT);
    assert!(
        same_response(after_revert, ra) && same_state(el.trial(), &trial_a),
        "{}: revert then the same trial is not bit-identical",
        S::NAME
    );

    el.commit();
    assert!(
        same_state(el.committed(), &trial_a),
        "{}: commit did not accept the trial",
        S::NAME
    );
    assert!(
        bits(el.displacement()) == bits(trial_a.u),
        "{}: displacement() after commit",
        S::NAME
    );
    let same_point = trial(&mut el, NEXT);
    assert!(
        same_response(same_point, ra),
        "{}: a trial at the committed point changed the response",
        S::NAME
    );
}

/// Checks that `el` still holds `committed`, the pending trial `pending`
/// and its response `response` after a refused step.
fn unchanged<S: Scalar>(
    el: &Bwbn<S>,
    committed: &State<S>,
    pending: &State<S>,
    response: Response<S>,
    what: &str,
) {
    assert!(
        same_state(el.committed(), committed),
        "{}: {} changed the committed state",
        S::NAME,
        what
    );
    assert!(
        same_state(el.trial(), pending),
        "{}: {} changed the pending trial",
        S::NAME,
        what
    );
    assert!(
        same_response(el.response(), response),
        "{}: {} changed the response",
        S::NAME,
        what
    );
}

fn refused_steps_change_nothing<S: Scalar>() {
    let mut el = driven::<S>(AT);
    let ra = trial(&mut el, NEXT);
    let (committed, pending) = (*el.committed(), *el.trial());
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let bad = S::from_f64(bad);
        assert!(!bad.is_finite(), "{}: test input is finite", S::NAME);
        assert!(
            el.set_trial(bad) == Err(StepError::NonFiniteInput),
            "{}: non-finite input not refused as such",
            S::NAME
        );
        unchanged(&el, &committed, &pending, ra, "non-finite input");
    }
    // A budget of 2 sub-steps cannot cover a 6.4 mm reversal: the step is
    // refused for its tolerance, and nothing changes either.
    let control = Control {
        max_substeps: 2,
        ..*el.control()
    };
    let mut el = el.with_control(control).unwrap();
    assert!(
        el.set_trial(S::from_i32(4)) == Err(StepError::ToleranceNotMet),
        "{}: a step beyond the sub-step budget was not refused",
        S::NAME
    );
    unchanged(&el, &committed, &pending, ra, "a step beyond the budget");
    el.commit();
    assert!(
        same_state(el.committed(), &pending),
        "{}: the pending trial was lost",
        S::NAME
    );
}

fn reset_returns_to_virgin<S: Scalar>() {
    let mut el = driven::<S>(AT);
    el.reset();
    let mut fresh = Bwbn::<S>::new(Set::All.params());
    assert!(
        same_state(el.committed(), fresh.committed()),
        "{}: reset committed state",
        S::NAME
    );
    assert!(
        same_state(el.trial(), fresh.trial()),
        "{}: reset trial state",
        S::NAME
    );
    assert!(
        same_response(el.response(), fresh.response()),
        "{}: reset response",
        S::NAME
    );
    assert!(
        el.committed().u == S::ZERO
            && el.committed().z == S::ZERO
            && el.committed().energy == S::ZERO
    );
    for i in 1..=600 {
        let (a, b) = (trial(&mut el, i), trial(&mut fresh, i));
        assert!(
            same_response(a, b),
            "{}: after reset, point {} differs",
            S::NAME,
            i
        );
        el.commit();
        fresh.commit();
    }
}

/// From the virgin state, one step of the smallest representable increment
/// (`EPSILON`: 2.2e-16 mm in `f64`, 1.2e-7 mm in `f32`, one Q15.16 step)
/// and then a step to 1 mm gives the force of a single step to 1 mm, to the
/// arithmetic's accuracy bound of the reference history. (The sub-step
/// size carried over from the tiny step, at most five times it, was once
/// tried first and was already below the 1 mm step's smallest allowed
/// sub-step, 16 `EPSILON` of its length, so the step was refused.)
fn tiny_then_ordinary<S: Scalar>(bound: f64) {
    let params = Set::All.params();
    let mut direct = Bwbn::<S>::new(params);
    let mut via_tiny = Bwbn::<S>::new(params);
    let target = S::ONE;
    let expected = direct.set_trial(target);
    let tiny = via_tiny.set_trial(S::EPSILON);
    via_tiny.commit();
    let got = via_tiny.set_trial(target);
    match (expected, tiny, got) {
        (Ok(a), Ok(_), Ok(b)) => {
            let (a, b) = (a.force.to_f64(), b.force.to_f64());
            assert!(
                (a - b).abs() <= bound * a.abs(),
                "{}: force at 1 mm {} after a tiny step, {} directly",
                S::NAME,
                b,
                a
            );
        }
        other => panic!("{}: steps refused: {:?}", S::NAME, other),
    }
}

/// A tiny increment does not stall the next one.
pub fn tiny_increment() {
    tiny_then_ordinary::<f64>(1e-6);
    tiny_then_ordinary::<f32>(super::accuracy::F32_BOUND);
    tiny_then_ordinary::<Fixed>(super::accuracy::FIXED_BOUND);
}

/// Trials never change the committed state; revert + same trial is
/// bit-identical.
pub fn trial_commit_revert_all() {
    trial_commit_revert::<f64>();
    trial_commit_revert::<f32>();
    trial_commit_revert::<Fixed>();
}

/// NaN and infinities, and a step beyond the sub-step budget, are refused
/// and change nothing.
pub fn refused_steps() {
    refused_steps_change_nothing::<f64>();
    refused_steps_change_nothing::<f32>();
    refused_steps_change_nothing::<Fixed>();
}

/// Reset gives the virgin element back.
pub fn reset() {
    reset_returns_to_virgin::<f64>();
    reset_returns_to_virgin::<f32>();
    reset_returns_to_virgin::<Fixed>();
}
