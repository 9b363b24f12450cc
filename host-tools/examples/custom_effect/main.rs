//! `hyst` with one more physical effect, defined here and not in the library.
//!
//! ```sh
//! cargo run --release -p hysteresis-host --example custom_effect -- params --model bw+slip
//! cargo run --release -p hysteresis-host --example custom_effect -- discover DATA.csv --model bw
//! ```
//!
//! Registering the effect is the only step: every verb then knows `slip`
//! (`simulate`, `fit`, `diagnose`, `discover`, which weighs it as a suspect).

mod slip;

use clap::Parser;

fn main() {
    if let Err(e) = hyst::model::register(&slip::SlipEffect) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
    if let Err(e) = hyst::cli::run(hyst::cli::Cli::parse()) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
