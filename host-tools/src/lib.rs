//! Host tools for the `hysteresis` crate: reading lab records, simulating,
//! fitting and diagnosing models, and exporting parameter tables. The `hyst`
//! binary is a thin command-line layer over this library.
#![forbid(unsafe_code)]

pub mod cli;
pub mod fe;
pub mod model;
