//! `hyst table check FILE`: verifies a binary parameter table with the
//! device's loader (`hysteresis::table`) and lists its elements; exits
//! non-zero with the loader's typed error on bad input.

use crate::export::{self, Listing};
use anyhow::{anyhow, Context, Result};
use clap::{Args, Subcommand};
use std::path::PathBuf;

/// Arguments of `hyst table`.
#[derive(Debug, Args)]
pub struct TableArgs {
    /// What to do with a table.
    #[command(subcommand)]
    pub command: TableCommand,
}

/// The `hyst table` subcommands.
#[derive(Debug, Subcommand)]
pub enum TableCommand {
    /// Verify a binary table (as `hyst export --format bin` writes it) and
    /// list its elements.
    Check {
        /// The table.
        file: PathBuf,
    },
}

/// Runs `hyst table`.
pub fn run(args: TableArgs) -> Result<()> {
    match args.command {
        TableCommand::Check { file } => check(&file),
    }
}

fn check(file: &PathBuf) -> Result<()> {
    let bytes = std::fs::read(file).with_context(|| format!("{}: cannot read", file.display()))?;
    let (header, listing) = export::verify(&bytes)
        .map_err(|e| anyhow!("{}: table refused: {e} ({e:?})", file.display()))?;
    outln!("{}: valid, {}", file.display(), export::describe(&header));
    let num = |x: f64| format!("{x}");
    match listing {
        Listing::Bwbn(elements) => {
            for (i, e) in elements.iter().enumerate() {
                let mut parts: Vec<String> = e
                    .values
                    .iter()
                    .map(|(n, v)| format!("{n}={}", num(*v)))
                    .collect();
                parts.push(match e.energy_limit {
                    Some(l) => format!("energy_limit={}", num(l)),
                    None => "energy_limit=none".into(),
                });
                outln!("  element {i}: {}", parts.join(" "));
            }
        }
        Listing::Phm(elements) => {
            let curve = |c: &[[f64; 2]]| {
                c.iter()
                    .map(|[x, y]| format!("({}, {})", num(*x), num(*y)))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            for (i, e) in elements.iter().enumerate() {
                outln!("  element {i}: positive {}", curve(&e.positive));
                outln!("             negative {}", curve(&e.negative));
                if e.coefficients.is_empty() {
                    outln!("             coefficients: the thesis' values");
                } else {
                    let c: Vec<String> = e
                        .coefficients
                        .iter()
                        .map(|(n, v)| format!("{n}={}", num(*v)))
                        .collect();
                    outln!(
                        "             coefficients (others the thesis'): {}",
                        c.join(" ")
                    );
                }
            }
        }
    }
    Ok(())
}
