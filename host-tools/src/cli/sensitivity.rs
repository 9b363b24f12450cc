//! `hyst sensitivity DATA --params FIT.json`: one-at-a-time sensitivity of
//! the fitted model (thesis section 3.5.3, Table 3.5, Fig. 3.7).

use super::columns::ReadArgs;
use super::fit::{given_point, load, mass_of};
use super::ForcingArgs;
use crate::fit::problem::Problem;
use crate::fit::sensitivity;
use crate::model::{ModelSpec, ParamFile};
use crate::report::plots::{sensitivity as plot, Signal};
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `hyst sensitivity`.
#[derive(Debug, Args)]
pub struct SensitivityArgs {
    /// The record the model is run on (its input drives the model).
    pub data: PathBuf,
    /// The parameter or fit file.
    #[arg(long)]
    pub params: PathBuf,
    /// Model spec; defaults to the parameter file's.
    #[arg(long)]
    pub model: Option<ModelSpec>,
    /// Mass in kg, for force-driven records (default: the `m` of the parameter file, if any).
    #[arg(long, allow_negative_numbers = true)]
    pub mass: Option<f64>,
    #[command(flatten)]
    pub forcing: ForcingArgs,
    #[command(flatten)]
    pub read: ReadArgs,
    /// Changes from -50% to +50% in this many steps.
    #[arg(long, default_value_t = 11)]
    pub levels: usize,
    /// Write the curves as SVG (thesis Fig. 3.7).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `hyst sensitivity`.
pub fn run(args: SensitivityArgs) -> Result<()> {
    let file = ParamFile::read(&args.params)?;
    for note in args.read.unrepeated(&file) {
        eprintln!("note: {note}");
    }
    let spec = file.spec(args.model)?;
    let forcing = args.forcing.or_file(Some(&file))?;
    // A fit of the oscillator carries its mass (kg), as `simulate` reads it.
    let mass = mass_of(args.mass, Some(&file))?;
    let exp = load(&args.data, &args.read, mass, forcing)?;
    let problem = Problem::new(spec, exp, &[]).with_context(|| args.data.display().to_string())?;
    let (x, nominal) = given_point(&file, &problem, &args.data)?;
    let sweeps = sensitivity::analyse(&problem, &x, &nominal.output, args.levels)?;
    if let Some(path) = &args.plot {
        let change: Vec<f64> = sweeps
            .first()
            .map(|s| s.changes.iter().map(|c| 100.0 * c).collect())
            .unwrap_or_default();
        let curves: Vec<Signal> = sweeps
            .iter()
            .map(|s| Signal::model(&s.name, "", &s.errors))
            .collect();
        let fig = plot(&change, "e, eq. 3.24", &curves)?;
        std::fs::write(path, fig.to_svg())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    let mut ranked: Vec<_> = sweeps.iter().collect();
    ranked.sort_by_key(|s| s.rank);
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&ranked)?);
    } else {
        outln!(
            "{:<12} {:>14} {:>18} {:>5} {:>14}",
            "parameter",
            "value",
            "max e (eq. 3.25)",
            "rank",
            "not simulated"
        );
        for s in &ranked {
            outln!(
                "{:<12} {:>14.6e} {:>18.6e} {:>5} {:>14}",
                format!("{}{}", s.name, if s.of_range { "*" } else { "" }),
                s.nominal,
                s.max_error,
                s.rank,
                format!("{} of {}", s.not_simulated, s.changes.len())
            );
        }
        if ranked.iter().any(|s| s.of_range) {
            outln!("* zero: swept over -50%..+50% of its fitting range instead of its value");
        }
        if ranked.iter().any(|s| s.not_simulated > 0) {
            outln!(
                "not simulated: changes that made the set invalid or a step fail; max e is over the others"
            );
        }
    }
    Ok(())
}
