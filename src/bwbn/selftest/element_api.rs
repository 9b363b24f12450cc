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
//!   for bit.

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
    let mut el = el.with_control(control);
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
