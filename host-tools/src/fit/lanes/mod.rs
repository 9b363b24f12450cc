//! Simulating several candidate parameter sets at once, one per vector lane, for the
//! evolutionary search (thesis ch. 3): NSGA-II evaluates a hundred candidates a generation, all
//! on the same record, so the same arithmetic runs for each of them in lockstep. The same
//! batches give the residuals and a differenced Jacobian for screening the starts of a
//! multi-start least-squares fit ([`least_squares`]).
//!
//! [`BoucWenLanes`] is the plain Bouc-Wen oscillator of thesis eqs 3.3-3.4 and 3.13, per unit
//! mass, for [`LANES`] parameter sets, integrated by the classic fourth-order Runge-Kutta method
//! with a fixed number of steps per sample: no error control, so its error is measured where it
//! is used ([`search`] checks it against the core's error-controlled
//! [`Sdof`](hysteresis::bwbn::Sdof) before a search, and the search's result is scored with the
//! core). Its `|z|^n` comes from [`math`], whose polynomials vectorise where the core's
//! table-driven `pow` cannot.

pub mod bouc_wen;
pub mod least_squares;
pub mod math;
pub mod search;

pub use bouc_wen::{BoucWenLanes, LaneState};
pub use least_squares::LaneResiduals;
pub use search::{SearchModel, SearchSummary, Unsuited, MAX_SUBSTEPS};

/// Parameter sets simulated together: two AVX2 registers of eight `f32`, enough independent work
/// to hide the latency of the polynomial chains.
pub const LANES: usize = 16;

/// One value per lane, in single precision: with compensated sums its rounding stays within a few
/// `f32` epsilons of peak over a record (see [`bouc_wen`]), far below the fixed-step error the
/// search model is checked for, and it puts twice the lanes in a register.
pub type Lanes = [f32; LANES];
