//! `x^y` and `e^x` for `f64` and `f32`, written for the hysteresis models.
//!
//! The BWBN rate needs `|z|^n` in every right-hand-side evaluation and pinching
//! two `e^x`; with `libm` those calls were most of the cost of a step. These
//! versions are `no_std`, safe, branch only on rare inputs, and carry their error
//! bounds as tested constants:
//!
//! * [`f64`](self::f64): table-driven (two tables of 256 bytes), `pow` with the
//!   `y e` part of `y log2 x` kept exact so that the error does not grow with the
//!   size of the result's logarithm; about 1 ulp for `exp`, 2-3 ulp for `pow` on
//!   the models' domain.
//! * [`f32`](self::f32): no tables, no `f64`, written for instruction count on a
//!   Cortex-M4F (see `benches/firmware`); a few ulp.
//!
//! The polynomial coefficients and tables come from `remez.py` in this folder.
//! Special values follow C99 for `x >= 0` (see [`f64::pow`](self::f64::pow)).

pub(crate) mod f32;
// With `std` the `f64` impl uses the standard library; the tests still check this one.
#[cfg(any(test, not(feature = "std")))]
pub(crate) mod f64;
