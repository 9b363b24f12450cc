//! An explicit finite-element solver for reinforced-concrete columns under
//! torsion and axial load (thesis chapter 2).
#[cfg(test)]
mod checks;
pub mod explicit;
pub mod hex8;
pub mod history;
pub mod material;
pub mod mesh;
pub mod model;
pub mod output;
pub mod quasi_static;
pub mod rebar;
pub mod run;
pub mod simd;
pub mod specimen;
