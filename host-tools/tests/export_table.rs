//! `hyst export` and `hyst table check` as a user runs them: the binary
//! table, its Rust and C renderings (same bytes; the C header compiles and a
//! C program computes the same CRC-32), the precision report, and the typed
//! errors of `table check` with a non-zero exit.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, stderr, tmp, write};
use std::process::Command;

const ALL_FOUR: &str = r#"{"model": "bwbn", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1,
 "delta_A": 2e-4, "delta_nu": 5e-4, "delta_eta": 5e-4, "zeta0": 0.9, "p": 0.01, "q": 0.1,
 "psi0": 0.2, "delta_psi": 5e-4, "lambda": 0.5, "energy_limit": 2000,
 "units": {"displacement": "mm", "force": "kN"}}"#;

const PHM: &str = r#"{"model": "phm-torsion", "units": {"twist": "deg", "torque": "kN m"},
 "primary": {"positive": [[0.21, 105.0], [1.45, 168.0], [4.0, 172.0], [8.5, 140.0]],
             "negative": [[0.22, 101.0], [1.40, 162.0], [4.0, 165.0], [8.5, 131.0]]},
 "coefficients": {"eq4_a": 0.75}}"#;

/// The bytes of `0x..` literals in a rendered source, in order.
fn hex_bytes(text: &str) -> Vec<u8> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter_map(|w| w.strip_prefix("0x"))
        .filter(|w| w.len() == 2)
        .map(|w| u8::from_str_radix(w, 16).unwrap())
        .collect()
}

#[test]
fn export_check_and_renderings_agree() {
    let a = write("a.json", ALL_FOUR);
    let bin = tmp("t.bin");
    let o = ok(hyst(&[
        "export",
        &a,
        &a,
        &a,
        "--format",
        "bin",
        "--scalar",
        "f32",
        "--out",
        bin.to_str().unwrap(),
    ]));
    // The report: f32 within the 1e-4 of peak the core's shared tests prove.
    let report = stderr(&o);
    let worst: f64 = report
        .lines()
        .find_map(|l| l.trim().strip_prefix("worst: "))
        .and_then(|l| l.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(worst > 0.0 && worst < 1e-4, "{report}");
    let bytes = std::fs::read(&bin).unwrap();
    assert_eq!(&bytes[..4], b"HYTB");
    assert_eq!(bytes.len(), 36 + 3 * 18 * 4 + 4);

    let o = ok(hyst(&["table", "check", bin.to_str().unwrap()]));
    let out = String::from_utf8(o.stdout).unwrap();
    assert!(
        out.contains(
            "valid, format 1: BWBN, model bwbn, Zu rule thesis, f32, units mm / kN, 3 elements"
        ),
        "{out}"
    );
    assert_eq!(out.matches("element ").count(), 3);
    assert!(out.contains("energy_limit=2000"));

    let rs = hyst(&["export", &a, &a, &a, "--format", "rust", "--scalar", "f32"]);
    let rs = String::from_utf8(rs.stdout).unwrap();
    assert!(rs.contains(&format!("pub static TABLE: [u8; {}] = [", bytes.len())));
    assert_eq!(hex_bytes(rs.split("= [").nth(1).unwrap()), bytes);

    let c = hyst(&[
        "export", &a, &a, &a, "--format", "c", "--scalar", "f32", "--name", "columns",
    ]);
    let c = String::from_utf8(c.stdout).unwrap();
    assert_eq!(hex_bytes(c.split("= {").nth(1).unwrap()), bytes);
    let header = tmp("columns.h");
    std::fs::write(&header, &c).unwrap();
    // A C program that includes the header and checks the table the way the
    // format document says (CRC-32 of all but the last four bytes).
    let prog = write(
        "check.c",
        r#"#include <stdio.h>
#include "columns.h"
int main(void) {
    uint32_t c = 0xffffffffu;
    for (unsigned i = 0; i < COLUMNS_LEN - 4; i++) {
        c ^= columns[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320u & -(c & 1u));
    }
    c = ~c;
    uint32_t stored = columns[COLUMNS_LEN - 4] | columns[COLUMNS_LEN - 3] << 8
        | columns[COLUMNS_LEN - 2] << 16 | (uint32_t)columns[COLUMNS_LEN - 1] << 24;
    printf("%u %s\n", COLUMNS_LEN, c == stored ? "crc-ok" : "crc-bad");
    return c != stored;
}
"#,
    );
    let exe = tmp("check");
    let cc = Command::new("cc")
        .args([
            "-std=c99",
            "-Wall",
            "-Werror",
            "-o",
            exe.to_str().unwrap(),
            &prog,
        ])
        .output()
        .expect("a C compiler (gcc is on every machine of this project)");
    assert!(cc.status.success(), "{}", stderr(&cc));
    let run = Command::new(&exe).output().unwrap();
    assert_eq!(
        String::from_utf8(run.stdout).unwrap(),
        format!("{} crc-ok\n", bytes.len())
    );
}

#[test]
fn table_check_exits_non_zero_with_the_typed_error() {
    let a = write("b.json", ALL_FOUR);
    let bin = tmp("b.bin");
    assert!(hyst(&[
        "export",
        &a,
        "--format",
        "bin",
        "--scalar",
        "q16",
        "--out",
        bin.to_str().unwrap()
    ])
    .status
    .success());
    let good = std::fs::read(&bin).unwrap();
    let check = |name: &str, bytes: &[u8]| {
        let p = tmp(name);
        std::fs::write(&p, bytes).unwrap();
        let o = hyst(&["table", "check", p.to_str().unwrap()]);
        assert!(!o.status.success(), "{name} accepted");
        assert!(o.stdout.is_empty());
        stderr(&o)
    };
    let mut flipped = good.clone();
    flipped[50] ^= 4;
    assert!(check("flipped.bin", &flipped).contains("table refused: corrupted: stored CRC-32"));
    assert!(check("flipped.bin", &flipped).contains("(Checksum {"));
    assert!(check("cut.bin", &good[..good.len() - 1]).contains("(Truncated {"));
    let mut v2 = good.clone();
    v2[4] = 2;
    assert!(check("v2.bin", &v2)
        .contains("format version 2; this build reads version 1 (UnsupportedVersion(2))"));
    assert!(check("json.bin", ALL_FOUR.as_bytes()).contains("(BadMagic)"));
}

#[test]
fn phm_tables_and_export_errors() {
    let p = write("phm.json", PHM);
    let bin = tmp("phm.bin");
    let o = ok(hyst(&[
        "export",
        &p,
        &p,
        "--format",
        "bin",
        "--scalar",
        "q16",
        "--out",
        bin.to_str().unwrap(),
    ]));
    let report = stderr(&o);
    assert!(report.contains("precision of q16"), "{report}");
    let o = hyst(&["table", "check", bin.to_str().unwrap()]);
    let out = String::from_utf8(o.stdout).unwrap();
    assert!(
        out.contains("PHM, 4 points per curve, q16, units deg / kN m, 2 elements"),
        "{out}"
    );
    assert!(
        out.contains("coefficients (others the thesis'): eq4_a=0.75"),
        "{out}"
    );

    let a = write("c.json", ALL_FOUR);
    let e = stderr(&hyst(&["export", &a, &p, "--format", "bin"]));
    assert!(e.contains("one table holds one model"), "{e}");
    let plain = write(
        "plain.json",
        r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1}"#,
    );
    let e = stderr(&hyst(&["export", &a, &plain, "--format", "bin"]));
    assert!(
        e.contains("model bw differs from") && e.contains("bwbn"),
        "{e}"
    );
    let other = write("n.json", &ALL_FOUR.replace("\"kN\"", "\"N\""));
    let e = stderr(&hyst(&["export", &a, &other, "--format", "bin"]));
    assert!(e.contains("units mm / N differ from"), "{e}");
    // 50 000 kN/mm does not fit Q15.16: refused at export, naming the file.
    let big = write("big.json", &ALL_FOUR.replace("\"k0\": 6", "\"k0\": 50000"));
    let e = stderr(&hyst(&[
        "export", &big, "--format", "bin", "--scalar", "q16",
    ]));
    assert!(
        e.contains("big.json: k0 = 50000 is beyond the range of q16"),
        "{e}"
    );
}

#[test]
fn the_precision_history_takes_the_read_options() {
    // One history, 0 -> 6 -> -6 -> 6 mm in 0.1 mm steps, written twice: in mm
    // under a header the reader knows, and in cm under a bare `D` column next
    // to a force-like `V` that the reader has to be told to ignore.
    let mut u = vec![0.0f64];
    for target in [6.0, -6.0, 6.0] {
        while (u[u.len() - 1] - target).abs() > 1e-9 {
            let last = u[u.len() - 1];
            u.push(last + 0.1 * (target - last).signum());
        }
    }
    let mm: String = u.iter().map(|v| format!("{v:.4}\n")).collect();
    let cm: String = u.iter().map(|v| format!("{:.5},1\n", v / 10.0)).collect();
    let in_mm = write("h-mm.csv", &format!("displacement (mm)\n{mm}"));
    let in_cm = write("h-cm.csv", &format!("D,V\n{cm}"));
    let a = write("h.json", ALL_FOUR);
    let export = |history: &str, read: &[&str]| {
        let mut args = vec!["export", &a, "--format", "bin", "--scalar", "q16"];
        args.extend(["--history", history]);
        args.extend(read);
        let report = stderr(&ok(hyst(&args)));
        report
            .lines()
            .find_map(|l| l.trim().strip_prefix("worst: ").map(str::to_string))
            .unwrap_or_else(|| panic!("no precision line: {report}"))
    };
    let reference = export(&in_mm, &[]);
    let told = export(&in_cm, &["--displacement", "D:cm", "--ignore", "V"]);
    assert_eq!(told, reference);
    // Not told, the bare columns are refused rather than guessed, before a
    // table is written.
    let out = tmp("untold.bin");
    let out_arg = out.to_str().unwrap();
    let args = ["export", &a, "--format", "bin", "--scalar", "q16"];
    let o = hyst(&[&args[..], &["--history", &in_cm, "--out", out_arg]].concat());
    assert!(!o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--displacement COLUMN"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists(), "a table was written for a failed export");
}

/// A force-driven fit (`hyst fit --mass`) holds the test's mass and damping besides the
/// hysteretic spring: exported, its table is the spring's alone, byte for byte the table of the
/// same file without `m` and `xi`, and a note says what was left out.
#[test]
fn a_force_driven_fit_exports_its_spring_and_says_so() {
    let spring = r#"{"model": "bw", "k0": 6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1,
 "units": {"displacement": "mm", "force": "kN"}}"#;
    let fitted = write(
        "dynamic.json",
        &spring.replace("\"gamma\": -1,", "\"gamma\": -1, \"xi\": 0.05, \"m\": 500,"),
    );
    let spring = write("spring.json", spring);
    let table = |file: &str, name: &str| {
        let out = tmp(name);
        let o = ok(hyst(&[
            "export",
            file,
            "--format",
            "bin",
            "--out",
            out.to_str().unwrap(),
        ]));
        (std::fs::read(&out).unwrap(), stderr(&o))
    };
    let (dynamic, note) = table(&fitted, "dynamic.bin");
    let (plain, quiet) = table(&spring, "spring.bin");
    assert_eq!(dynamic, plain);
    assert!(
        note.contains("dynamic.json: m and xi belong to the oscillator of the force-driven test"),
        "{note}"
    );
    assert!(!quiet.contains("note:"), "{quiet}");
}

/// A precision report over a history the device cannot follow is no report:
/// a ramp past Q15.16's range (32,768 mm) stops the q16 element, and the
/// export fails naming it, the table written, instead of printing the error
/// of the points before as the worst (found by review: "worst: 6.10e-5").
/// And a table that cannot be written to standard output is an error.
#[test]
fn a_history_beyond_the_devices_range_fails_the_precision_report() {
    let fit = write(
        "ramp-fit.json",
        r#"{"model": "bw", "k0": 0.6, "alpha": 0.2, "n": 1.2, "beta": 2, "gamma": -1,
 "units": {"displacement": "mm", "force": "kN"}}"#,
    );
    let ramp: String = (0..=330).map(|i| format!("{}\n", 100 * i)).collect();
    let history = write("ramp.csv", &format!("displacement (mm)\n{ramp}"));
    let out = tmp("ramp.bin");
    let args = ["export", &fit, "--format", "bin", "--scalar", "q16"];
    let o = hyst(
        &[
            &args[..],
            &["--history", &history, "--out", out.to_str().unwrap()],
        ]
        .concat(),
    );
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains("in q16 the device cannot follow this history (element 0 after 327 points)"),
        "{e}"
    );
    assert!(!e.contains("worst:"), "{e}");
    assert!(out.exists(), "the table is written before the report");
    // The same history in f32 is followed to the end.
    let o = ok(hyst(
        &[
            &args[..4],
            &[
                "--scalar",
                "f32",
                "--history",
                &history,
                "--out",
                out.to_str().unwrap(),
            ],
        ]
        .concat(),
    ));
    assert!(stderr(&o).contains("worst: "), "{}", stderr(&o));

    let full = std::fs::File::create("/dev/full").expect("/dev/full on Linux");
    let o = Command::new(env!("CARGO_BIN_EXE_hyst"))
        .args(["export", &fit, "--format", "bin"])
        .stdout(full)
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("standard output: cannot write the table"),
        "{}",
        stderr(&o)
    );
}
