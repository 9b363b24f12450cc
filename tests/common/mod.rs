//! Helpers shared by the host integration tests: reading the reference data in
//! `../shared/data`.
#![allow(dead_code)]

use std::path::PathBuf;

/// Path of a file in the shared data folder.
pub fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(rel)
}

/// Reads a numeric CSV with one header line; returns the header and the rows.
pub fn read_csv(rel: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let path = data(rel);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|v| v.trim().parse::<f64>().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (header, rows)
}

/// The displacement history of the OpenSees reference cases (mm).
pub fn reference_history() -> Vec<f64> {
    read_csv("opensees-reference/history.csv")
        .1
        .iter()
        .map(|r| r[1])
        .collect()
}

/// One OpenSees reference case: (strain, stress) rows.
pub fn reference_case(name: &str) -> Vec<(f64, f64)> {
    read_csv(&format!("opensees-reference/{name}.csv"))
        .1
        .iter()
        .map(|r| (r[1], r[2]))
        .collect()
}
