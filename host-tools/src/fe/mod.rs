//! An explicit finite-element solver for reinforced-concrete columns under
//! torsion and axial load (thesis chapter 2).
pub mod hex8;
pub mod history;
pub mod material;
pub mod mesh;
pub mod rebar;
pub mod simd;
