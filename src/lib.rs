//! Hysteresis models of reinforced-concrete members as element state for
//! controllers.
//!
//! * [`bwbn`]: the Bouc-Wen-Baber-Noori smooth model (thesis ch. 3) with its
//!   effects switchable, as a displacement-driven [`Element`] and as a
//!   force-driven oscillator.
//! * [`phm`]: the polygonal hysteresis model of RC columns under cyclic
//!   torsion (thesis ch. 5), a twist-driven [`Element`] with the same API.
//! * [`table`]: parameter tables from the host to the device: a versioned,
//!   CRC-checked byte format and its verifying, zero-copy loader.
//! * [`scalar`]: the arithmetic the models are generic over: `f64` on the
//!   host, `f32` on Cortex-M4F, [`Fixed`] (Q15.16) on FPU-less parts.
//!
//! The crate is `no_std`, never allocates, never panics on input, and bounds
//! the work of every step: parameter sets are validated when they are built,
//! non-finite input is refused, and a step that cannot meet its accuracy
//! within its budget returns a [`StepError`] and leaves the state unchanged.
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
// Negated comparisons are how this crate treats NaN as a failure: `!(r <= tol)`
// is true for NaN, `r > tol` is not.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

#[cfg(feature = "std")]
extern crate std;

pub mod bwbn;
mod element;
pub mod phm;
pub mod scalar;
#[cfg(any(test, feature = "selftest"))]
pub mod selftest;
pub mod table;

pub use element::{Element, Response, StepError};
pub use scalar::{Fixed, Scalar};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
