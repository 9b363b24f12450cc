//! Model specs (`bw+pinching`) and parameter files.

mod params;
mod spec;

pub use params::{to_json, ParamFile};
pub use spec::{Base, ModelSpec};
