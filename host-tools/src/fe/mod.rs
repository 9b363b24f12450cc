//! An explicit finite-element solver for reinforced-concrete columns under
//! torsion and axial load (thesis chapter 2). See `docs/fe.md` for the
//! formulation, the checks and the measured numbers.
//!
//! * [`specimen`]: specimen files (TOML) of circular and square columns.
//! * [`mesh`], [`rebar`]: hexahedral meshes and embedded bars.
//! * [`hex8`], [`material`]: the one-point hexahedron with hourglass
//!   control, and the material traits with the elastic materials.
//! * [`concrete`], [`steel`]: concrete damaged plasticity and hardening
//!   steel (thesis 2.2), tested at the material point.
//! * [`model`], [`explicit`]: assembly, time step, mass scaling, the
//!   central-difference solver with the rigid top; [`layers`]: nodal forces
//!   by element layers; [`stable_step`]: the global stable step from the
//!   model's highest frequency.
//! * [`quasi_static`], [`output`], [`run`]: energy checks, CSV and VTK
//!   output, a whole analysis.
//! * [`section`]: shear stress across the mid-height section (thesis Figs
//!   2.9, 2.10) and the shear-flow thickness.
//! * [`backbone`]: the PHM primary curve (thesis Fig. 5.2) idealised from
//!   the computed torque-twist curve.
//! * [`torque_twist`]: the computed curve against the torques of thesis
//!   Table 2.1 (Fig. 2.1), as a figure and as relative errors.
// Negated comparisons treat NaN as a failure (`!(x > 0.0)` is true for NaN),
// as in the core crate. Kernels index several arrays with one index, which
// reads like the equations; iterators would hide that.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]
pub mod backbone;
pub mod bar_yield;
#[cfg(test)]
mod checks;
pub mod concrete;
pub mod explicit;
pub mod hex8;
pub mod history;
pub mod layers;
pub mod material;
pub mod mesh;
pub mod model;
pub mod output;
pub mod quasi_static;
pub mod rebar;
pub mod run;
pub mod section;
pub mod simd;
pub mod specimen;
pub mod stable_step;
pub mod steel;
pub mod torque_twist;
