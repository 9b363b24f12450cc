//! Host tools for the `hysteresis` crate: reading lab records, simulating,
//! fitting and diagnosing models, and exporting parameter tables. The `hyst`
//! binary is a thin command-line layer over this library.
#![forbid(unsafe_code)]

pub mod cli;
pub mod data;
pub mod discover;
pub mod export;
pub mod fe;
pub mod fit;
pub mod model;
mod random;
pub mod report;
