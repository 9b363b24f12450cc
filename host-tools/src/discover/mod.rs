//! The model-discovery loop: compare a model with measurements, see where it
//! fails, learn which physical effect is missing, add it, watch the error
//! fall.
//!
//! * [`Diagnosis`]: the fitted model lined up with its record: residuals by
//!   cycle, half-cycle and branch class, energy and peak force per cycle, and
//!   the places where it fails in words ([`diagnosis`]).
//! * [`signature`]: what each missing effect leaves in the residual.
//! * [`suspects`]: every candidate effect added and refitted, ranked by
//!   delta-BIC, significant or not, with a sentence of evidence.
//! * [`rate`]: rate dependence, which no effect of the library models: the
//!   model refitted with a dashpot beside it, so that the diagnosis names it
//!   rather than blaming an effect it has.
//! * [`slip`]: slip or a gap, a plateau of zero force on reversal, which no
//!   effect of the library models either and which pinching only resembles.
//! * [`offset`]: instruments that do not read zero at zero (a force offset, a
//!   record that starts away from zero displacement), which asymmetry and
//!   pinching can stand in for.
//! * [`displacement_drift`]: a displacement zero that drifts along the test,
//!   told apart from a drifting load cell.
//! * [`lag`]: force and displacement read out of step, which stiffness
//!   degradation and pinching can stand in for.
//! * [`ladder`]: the loop, adding the strongest significant effect until none
//!   is left.
//! * [`grown`]: a model with effects fitted by growing it from its base, as
//!   the ladder does, where a direct fit leaves an effect in a corner.
//! * [`synthetic`]: lab-like records with hidden effects for testing all of
//!   it.

pub mod diagnosis;
pub mod displacement_drift;
pub mod grown;
pub mod ladder;
pub mod lag;
pub mod offset;
pub mod page;
pub mod rate;
pub mod signature;
pub mod slip;
pub mod suspects;
pub mod synthetic;

pub use diagnosis::{CycleStats, Diagnosis, Place};
pub use ladder::{discover, Discovery, Rung, Step};
pub use suspects::{weigh, Suspect, WeighOptions};
