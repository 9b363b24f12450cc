//! Model specs (`bw+pinching`), custom effects and parameter files.

pub mod custom;
mod params;
mod spec;

pub use custom::{register, CustomEffect, Extras};
pub use params::{to_json, ParamFile};
pub use spec::{Base, EffectRef, ModelSpec};
