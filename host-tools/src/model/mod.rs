//! Model specs (`bw+pinching`), custom effects and parameter files.

pub mod custom;
mod params;
mod phm_file;
pub mod phm_passivity;
mod spec;

pub use custom::{register, CustomEffect, Extras};
pub use params::{to_json, ParamFile};
pub use phm_file::{is_phm, phm_json, simulate_phm, PhmFile, PhmRun, PHM_MODEL, PHM_POINTS};
pub use spec::{Base, EffectRef, ModelSpec};
