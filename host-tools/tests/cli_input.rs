//! `hyst` on inputs and outputs a user gets wrong or cuts short: a closed pipe, repeated or
//! invalid options, duplicated keys, degenerate records. Each must end in a clear error (or, for
//! a closed pipe, quietly), never in a panic or a result computed from something other than what
//! was asked.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, write};
use std::process::{Command, Output, Stdio};

/// Plain Bouc-Wen parameters.
const BW: &str = r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1}"#;

/// A small displacement-driven record: two cycles of a stiff-then-yielding column.
fn column_record() -> String {
    let mut text = String::from("disp_mm,force_kN\n");
    let mut u = 0.0f64;
    let mut z = 0.0f64;
    for amplitude in [2.0, -2.0, 4.0, -4.0, 0.0] {
        while (amplitude - u).abs() > 1e-9 {
            let du = (amplitude - u).clamp(-0.1, 0.1);
            // Plain Bouc-Wen (n = 1, beta = gamma = 0.5, k0 = 6, alpha = 0.1) by small
            // explicit steps: any hysteretic loop does here.
            z += du * (1.0 - z.abs() * (0.5 * (du * z).signum() + 0.5));
            u += du;
            text += &format!("{u:.4},{:.5}\n", 0.6 * u + 5.4 * z);
        }
    }
    text
}

/// Runs `hyst` with `args`, its standard output a pipe that nobody reads any more.
fn into_closed_pipe(args: &[&str]) -> Output {
    // A pipe whose reading end has gone: `true` held it and has exited.
    let mut reader = Command::new("true")
        .stdin(Stdio::piped())
        .spawn()
        .expect("`true` runs");
    let pipe = reader.stdin.take().expect("a pipe");
    reader.wait().expect("`true` exits");
    Command::new(env!("CARGO_BIN_EXE_hyst"))
        .args(args)
        .stdout(pipe)
        .stderr(Stdio::piped())
        .output()
        .expect("hyst runs")
}

/// `hyst params | head -1` and the like: the reader went away, which is not an error, and
/// certainly not a panic (`println!` panics on a closed pipe; every verb writes with `?`).
#[test]
fn a_closed_pipe_ends_quietly() {
    let data = write("column.csv", &column_record());
    let params = write("bw.json", BW);
    let table = cli::tmp("bw.bin");
    let table = table.to_str().unwrap();
    ok(hyst(&[
        "export", &params, "--format", "bin", "--out", table,
    ]));
    let cases: [&[&str]; 5] = [
        &["params"],
        &["fit", &data, "--method", "lsq"],
        &["fit", &data, "--method", "lsq", "--json"],
        &["table", "check", table],
        &["diagnose", &data, "--candidates", "pinching"],
    ];
    for args in cases {
        let out = into_closed_pipe(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(out.status.success(), "{args:?}: {stderr}");
    }
}

/// A key given twice in a JSON file is refused with its place: `serde_json` alone would keep the
/// last one, and `k0` would silently be 60.
#[test]
fn a_repeated_json_key_is_refused() {
    let history = write("history.csv", "displacement (mm)\n0\n1\n2\n");
    let params = write(
        "repeated.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1, "k0": 60}"#,
    );
    let e = cli::err(hyst(&["simulate", &history, "--params", &params]));
    assert!(
        e.contains("repeated.json:1:") && e.contains("key 'k0' given twice"),
        "{e}"
    );
}
