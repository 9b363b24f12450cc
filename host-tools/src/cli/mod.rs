//! The `hyst` command line: one module per verb.

pub mod fe;
pub mod params;

use clap::{Parser, Subcommand};

/// hyst: hysteresis models of RC members, from the lab bench to the controller.
#[derive(Debug, Parser)]
#[command(name = "hyst", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The verbs.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the parameters of a model.
    Params(params::ParamsArgs),
    /// Explicit finite-element analysis of an RC column under twist.
    Fe(fe::FeArgs),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Params(a) => params::run(a),
        Command::Fe(a) => fe::run_fe(a),
    }
}
