//! The data of the structural-control firmware example
//! (`examples/firmware`) is what the host tools make of its parameter files:
//! the tables are `hyst export --format rust` of `params/column-*.json`, and
//! the replayed record and the f64 reference forces are computed here. This
//! test regenerates all of it and fails if a committed file differs; run it
//! with `HYST_REGENERATE=1` to rewrite them:
//!
//! ```text
//! HYST_REGENERATE=1 cargo test -p hysteresis-host --test firmware_example
//! ```
//!
//! The record: the OpenSees reference loading history (3 triangular cycles at
//! 0.5, 1, 2, 4, 6, 8 mm, 200 steps a cycle, 3601 points), scaled for each
//! column by its storey factor, sampled by a 16-bit bipolar ADC with a
//! ±10 mm range (straight binary, 32768 = 0 mm). The reference forces are
//! the f64 fits driven by exactly the displacements those codes stand for.

use hyst::export::precision::protocol;
use hyst::model::ParamFile;
use hysteresis::bwbn::Bwbn;
use hysteresis::Element;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Storey factors of the four columns (channel k reads column k).
const FACTORS: [f64; 4] = [1.0, 0.8, 0.6, 1.1];
/// ADC range: ±10 mm over 16 bits; one code is 10 * 2^-15 mm (exact in f32).
const FULL_SCALE_MM: f64 = 10.0;
/// Copies of the four columns in the 64-element table of the budget bin.
const COPIES_64: usize = 16;

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/firmware")
}

fn columns() -> Vec<String> {
    (1..=4).map(|i| format!("params/column-{i}.json")).collect()
}

fn export_rust(files: &[String]) -> Vec<u8> {
    let o = Command::new(env!("CARGO_BIN_EXE_hyst"))
        .current_dir(example())
        .arg("export")
        .args(files)
        .args(["--format", "rust", "--scalar", "f32"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o.stdout
}

fn code(u_mm: f64) -> u16 {
    let c = (u_mm / FULL_SCALE_MM * 32768.0).round() + 32768.0;
    assert!(
        (0.0..=65535.0).contains(&c),
        "{u_mm} mm is outside the ADC's range"
    );
    c as u16
}

fn displacement(code: u16) -> f64 {
    (code as f64 - 32768.0) * (FULL_SCALE_MM / 32768.0)
}

/// `record.bin`: per sample, the four channels' codes (u16 LE);
/// `reference.bin`: per sample, the four columns' f64 forces rounded to f32
/// (LE).
fn record_and_reference() -> (Vec<u8>, Vec<u8>) {
    let history = protocol(1.0);
    let mut elements: Vec<Bwbn<f64>> = columns()
        .iter()
        .map(|f| {
            let file = ParamFile::read(example().join(f)).unwrap();
            Bwbn::new(file.build(file.spec(None).unwrap(), false).unwrap().0)
        })
        .collect();
    let (mut record, mut reference) = (vec![], vec![]);
    for (k, &u) in history.iter().enumerate() {
        for (el, factor) in elements.iter_mut().zip(FACTORS) {
            let c = code(u * factor);
            record.extend_from_slice(&c.to_le_bytes());
            let r = el
                .set_trial(displacement(c))
                .unwrap_or_else(|e| panic!("sample {k}: {e}"));
            el.commit();
            reference.extend_from_slice(&(r.force as f32).to_le_bytes());
        }
    }
    (record, reference)
}

#[test]
fn committed_example_data_is_what_the_host_tools_make() {
    let (record, reference) = record_and_reference();
    let mut files64 = vec![];
    for _ in 0..COPIES_64 {
        files64.extend(columns());
    }
    let generated = [
        ("src/table.rs", export_rust(&columns())),
        ("src/table64.rs", export_rust(&files64)),
        ("data/record.bin", record),
        ("data/reference.bin", reference),
    ];
    let regenerate = std::env::var_os("HYST_REGENERATE").is_some();
    for (name, bytes) in generated {
        let path = example().join(name);
        if regenerate {
            std::fs::write(&path, &bytes).unwrap();
        }
        let committed = std::fs::read(&path).unwrap_or_default();
        assert!(
            committed == bytes,
            "{} is not what the host tools make of the parameter files; regenerate with \
             HYST_REGENERATE=1 cargo test -p hysteresis-host --test firmware_example",
            path.display()
        );
    }
}

#[test]
fn adc_codes_stand_for_the_history() {
    assert_eq!(code(0.0), 32768);
    assert_eq!(displacement(code(8.8)), 28836.0 * 10.0 / 32768.0);
    for u in [-8.8, -0.01, 0.0, 0.3, 8.8] {
        assert!((displacement(code(u)) - u).abs() <= FULL_SCALE_MM / 65536.0);
    }
}
