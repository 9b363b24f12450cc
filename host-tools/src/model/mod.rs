//! Model specs (`bw+pinching`) and parameter files.

mod spec;

pub use spec::{Base, ModelSpec};
