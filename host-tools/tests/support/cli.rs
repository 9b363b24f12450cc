//! Running `hyst` as a user does, for the command-line tests: the binary, its
//! output, and a scratch folder per test file.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `hyst` with `args` and returns what it did, success or not.
pub fn hyst(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hyst"))
        .args(args)
        .output()
        .expect("hyst runs")
}

/// What `o` wrote to stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `o`, after asserting that it succeeded (its stderr is the failure message).
pub fn ok(o: Output) -> Output {
    assert!(o.status.success(), "{}", stderr(&o));
    o
}

/// The stderr of `o`, after asserting that it failed.
pub fn err(o: Output) -> String {
    assert!(!o.status.success(), "expected a failure");
    stderr(&o)
}

/// `name` in this test file's scratch folder (one per test binary and run).
pub fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "hyst-{}-{}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Writes `text` to `name` in the scratch folder; returns the path as an
/// argument for `hyst`.
pub fn write(name: &str, text: &str) -> String {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// Writes a displacement-driven record (`input` mm, `output` kN) as the CSV
/// `name` in the scratch folder; returns the path as an argument for `hyst`.
pub fn write_record(name: &str, exp: &hyst::fit::experiment::Experiment) -> String {
    let rows: String = exp
        .input
        .iter()
        .zip(&exp.output)
        .map(|(u, f)| format!("{u},{f}\n"))
        .collect();
    write(name, &format!("displacement (mm),force (kN)\n{rows}"))
}
