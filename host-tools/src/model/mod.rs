//! Model specs (`bw+pinching`) and parameter files.

mod params;
mod phm_file;
mod spec;

pub use params::{to_json, ParamFile};
pub use phm_file::{is_phm, PhmFile, PHM_MODEL, PHM_POINTS};
pub use spec::{Base, ModelSpec};
