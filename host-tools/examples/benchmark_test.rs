//! Simulates the two official test sets of the Bouc-Wen benchmark (Noel and
//! Schoukens 2016) with a force-driven fit and prints the benchmark's figure
//! of merit, the RMSE of the displacement in metres (PROVENANCE.md, eq. 6).
//! `hyst simulate` runs a force-driven record from rest; this example adds what the test sets
//! need beyond that: warm-up periods for the steady-state multisine and its band-limited input.
//!
//! ```text
//! hyst fit ../shared/data/boucwen-benchmark/csv/train_multisine_forgione.csv \
//!     --model bw --mass 2 --sample-rate 750 --out bw-benchmark.json
//! cargo run --release -p hysteresis-host --example benchmark_test -- bw-benchmark.json
//! ```
//!
//! The simulation runs at the data's 750 Hz (x1), with the force linear
//! between samples and with it cubic (`hyst fit --forcing cubic`), and, for
//! the periodic multisine, also on the input interpolated band-limited x16
//! (12 kHz, as the project's test of the true model does). The multisine test file is one
//! steady-state period of a periodic input: two periods of warm-up precede
//! the scored one. The sine sweep starts from rest and is simulated as is.
//! The benchmark's true parameters go through the same path as a reference:
//! what this discretisation alone costs.

// The band-limited interpolation the root crate's test of the true model uses.
#[path = "../../tests/common/mod.rs"]
mod common;

use common::interpolate_periodic;
use hyst::fit::experiment::{Between, Drive, Experiment};
use hyst::model::{Extras, ParamFile};
use hysteresis::bwbn::{BoucWen, BwbnParams, Control};
use std::path::PathBuf;

const FS: f64 = 750.0;

/// `u_N,y_m` columns, as kN and mm.
fn read(path: &PathBuf) -> (Vec<f64>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(
        lines.next().map(str::trim),
        Some("u_N,y_m"),
        "{}",
        path.display()
    );
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut it = l.split(',').map(|v| v.trim().parse::<f64>().unwrap());
            (it.next().unwrap() * 1e-3, it.next().unwrap() * 1e3)
        })
        .unzip()
}

/// RMSE in metres of the model on a test set; `warmup` periods of the input
/// are run first when the record is one period of a periodic input. With
/// `factor > 1` the (periodic) input is interpolated band-limited by that
/// factor and the model runs at `factor * 750` Hz; `between` is the force
/// between the (interpolated) samples.
#[allow(clippy::too_many_arguments)]
fn rmse_m(
    params: &BwbnParams<f64>,
    extras: &Extras,
    xi: f64,
    mass_kg: f64,
    u: &[f64],
    y: &[f64],
    warmup: usize,
    factor: usize,
    between: Between,
) -> Result<f64, String> {
    let n = u.len();
    let fine = if factor > 1 {
        interpolate_periodic(u, factor)
    } else {
        u.to_vec()
    };
    let m = fine.len();
    let input: Vec<f64> = fine
        .iter()
        .copied()
        .cycle()
        .take(m * (warmup + 1))
        .collect();
    let exp = Experiment {
        output: vec![0.0; input.len()],
        input,
        drive: Drive::Force {
            dt: 1.0 / (FS * factor as f64),
            mass: mass_kg * 1e-6,
            between,
        },
    };
    let pred = exp
        .simulate(params, extras, xi, Control::default_for())
        .map_err(|e| e.to_string())?;
    let sim = pred.output[m * warmup..].iter().step_by(factor);
    let se: f64 = sim.zip(y).map(|(a, b)| (a - b).powi(2)).sum();
    Ok((se / n as f64).sqrt() * 1e-3)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let fit = PathBuf::from(
        args.next()
            .expect("usage: benchmark_test FIT.json [CSV_DIR]"),
    );
    let dir = PathBuf::from(
        args.next()
            .unwrap_or_else(|| "../shared/data/boucwen-benchmark/csv".into()),
    );
    let file = ParamFile::read(&fit).unwrap_or_else(|e| panic!("{e:#}"));
    let spec = file.spec(None).unwrap_or_else(|e| panic!("{e:#}"));
    let (params, extras) = file.build(spec, true).unwrap_or_else(|e| panic!("{e:#}"));
    let xi = file.values.get("xi").copied().unwrap_or(0.0);
    let mass = file
        .values
        .get("m")
        .copied()
        .expect("the fit file has no mass m");

    // The true model in mm, kN: k0 = kL + a = 1e5 N/m = 0.1 kN/mm, alpha 0.5,
    // beta = b g = 800 /m = 0.8 /mm, gamma = b d = -1100 /m = -1.1 /mm, n 1;
    // xi = c / (2 sqrt(k0 m)).
    let truth = BwbnParams::plain(BoucWen::new(0.1, 0.5, 1.0, 0.8, -1.1).unwrap());
    let xi_true = 10.0 / (2.0 * (1e5f64 * 2.0).sqrt());
    let none = Extras::default();

    println!(
        "fit {} (model {spec}, m {mass} kg, xi {xi:.5e})",
        fit.display()
    );
    println!(
        "test set                          samples  rms(y) m    RMSE fit m  RMSE truth m (same path)"
    );
    for (name, warmup, factor, between) in [
        ("test_multisine.csv", 2, 1, Between::Linear),
        ("test_multisine.csv", 2, 1, Between::Cubic),
        ("test_multisine.csv", 2, 16, Between::Linear),
        ("test_sinesweep.csv", 0, 1, Between::Linear),
        ("test_sinesweep.csv", 0, 1, Between::Cubic),
    ] {
        let (u, y) = read(&dir.join(name));
        let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len() as f64).sqrt() * 1e-3;
        let fitted = rmse_m(&params, &extras, xi, mass, &u, &y, warmup, factor, between);
        let true_ = rmse_m(&truth, &none, xi_true, 2.0, &u, &y, warmup, factor, between);
        let name = format!("{name} x{factor} {between}");
        let show = |r: &Result<f64, String>| match r {
            Ok(v) => format!("{v:.3e}"),
            Err(e) => format!("failed: {e}"),
        };
        println!(
            "{name:<31} {:>7}  {rms:.3e}   {}   {}",
            y.len(),
            show(&fitted),
            show(&true_)
        );
    }
}
