//! Tests of the data module against our data sets, malformed inputs and
//! closed-form loops.

mod cycles;
mod errors;
mod files;
mod history;
mod json;
mod write;

use std::path::PathBuf;

/// `../shared/data` as seen from this package.
fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/data")
}

/// Smallest and largest value.
fn range(x: &[f64]) -> (f64, f64) {
    x.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}
