//! The BWBN cases of the shared test table ([`crate::selftest`]).
//!
//! * [`history`]: the OpenSees reference history and parameter sets, in code;
//! * [`accuracy`]: `f32` and fixed point against `f64` on that history, and
//!   the energy balance over its closed cycles;
//! * [`element_api`]: trial/commit/revert, refused input, reset;
//! * [`limits`]: closed forms the model must reproduce.

pub mod accuracy;
pub mod element_api;
pub mod history;
pub mod limits;

use crate::selftest::Case;

/// The BWBN cases.
pub const CASES: &[Case] = &[
    ("bwbn::history_has_the_reference_shape", history::shape),
    ("bwbn::reference_history::plain", accuracy::plain),
    (
        "bwbn::reference_history::plain_other_methods",
        accuracy::plain_other_methods,
    ),
    ("bwbn::reference_history::degrading", accuracy::degrading),
    ("bwbn::reference_history::pinching", accuracy::pinching),
    ("bwbn::reference_history::all_four", accuracy::all_four),
    (
        "bwbn::element::trial_commit_revert",
        element_api::trial_commit_revert_all,
    ),
    (
        "bwbn::element::refused_steps_change_nothing",
        element_api::refused_steps,
    ),
    ("bwbn::element::reset", element_api::reset),
    (
        "bwbn::element::tiny_increment_does_not_stall",
        element_api::tiny_increment,
    ),
    (
        "bwbn::limits::alpha_one_is_linear_elastic",
        limits::alpha_one_is_linear_elastic,
    ),
    ("bwbn::limits::z_tends_to_zu", limits::z_tends_to_zu),
    ("bwbn::limits::n_one_closed_form", limits::n_one_closed_form),
    (
        "bwbn::limits::small_zu_every_arithmetic",
        limits::small_zu_every_arithmetic,
    ),
];
