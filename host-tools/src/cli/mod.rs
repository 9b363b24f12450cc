//! The `hyst` command line: one module per verb.

/// `println!` that hands a failed write (a closed pipe: `hyst fit ... | head`) to the caller
/// with `?` instead of panicking, so that `main` can end quietly.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout(), $($arg)*)?
    }};
}

pub mod columns;
pub mod diagnose;
pub mod discover;
pub mod export;
pub mod fe;
pub mod fit;
pub mod params;
pub mod phm;
pub mod sensitivity;
pub mod simulate;
pub mod table;

use crate::fit::experiment::Between;
use crate::model::{ModelSpec, ParamFile, PHM_MODEL};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// A `--model` value: a Bouc-Wen spec (`bw+pinching`, ...) or the polygonal
/// hysteresis model for torsion (`phm-torsion`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelArg {
    /// A Bouc-Wen model spec.
    Bwbn(ModelSpec),
    /// The PHM of thesis ch. 5.
    Phm,
}

impl FromStr for ModelArg {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> anyhow::Result<Self> {
        if s.trim() == PHM_MODEL {
            return Ok(ModelArg::Phm);
        }
        ModelSpec::parse(s)
            .map(ModelArg::Bwbn)
            .map_err(|e| anyhow::anyhow!("{e} (or `{PHM_MODEL}`)"))
    }
}

/// `--forcing`, for every verb that drives the oscillator with a recorded
/// force.
#[derive(Clone, Copy, Debug, Default, Args)]
pub struct ForcingArgs {
    /// Force-driven records: how the force goes between samples, `linear` or
    /// `cubic` (Hermite through the samples and their rates from eighth-order
    /// central differences: for a band-limited force sampled at a few points
    /// a period; see "Force between samples" in the README). Default: the
    /// parameter file's `fit.forcing` where a verb reads one, else linear.
    #[arg(long = "forcing", value_name = "FORCING", value_enum)]
    pub between: Option<Between>,
}

impl ForcingArgs {
    /// The forcing given on the command line, else the one `file` records
    /// (`fit.forcing`), else none (linear).
    pub fn or_file(self, file: Option<&ParamFile>) -> anyhow::Result<Option<Between>> {
        if self.between.is_some() {
            return Ok(self.between);
        }
        let Some(file) = file else {
            return Ok(None);
        };
        let Some(value) = file.fit.as_ref().and_then(|fit| fit.get("forcing")) else {
            return Ok(None);
        };
        value
            .as_str()
            .and_then(Between::from_name)
            .map(Some)
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "{}: `fit.forcing` is {value}; expected \"linear\" or \"cubic\"",
                    file.at(&["fit", "forcing"])
                )
            })
    }
}

/// Whether two existing paths are one file under two names (a hard link,
/// which `canonicalize` keeps apart: an output through one overwrote its
/// input, found by review).
#[cfg(unix)]
fn one_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether two existing paths are one file under two names (not known off
/// Unix beyond `canonicalize`).
#[cfg(not(unix))]
fn one_file(_: &Path, _: &Path) -> bool {
    false
}

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
    /// Compare a fitted model with its record, see where it fails, name what is missing.
    Diagnose(diagnose::DiagnoseArgs),
    /// Add missing effects one by one until nothing significant is left.
    Discover(discover::DiscoverArgs),
    /// Fit a model to a lab record.
    Fit(fit::FitArgs),
    /// One-at-a-time sensitivity of a fitted model (thesis Table 3.5).
    Sensitivity(sensitivity::SensitivityArgs),
    /// Drive a model with a displacement history; CSV displacement,force,tangent.
    Simulate(simulate::SimulateArgs),
    /// Write the parameter table for the device (binary, Rust or C).
    Export(export::ExportArgs),
    /// Work with binary parameter tables (`check`).
    Table(table::TableArgs),
    /// Explicit finite-element analysis of an RC column under twist.
    Fe(fe::FeArgs),
}

/// Where a verb writes its CSV: the file `path` (created), or standard output.
fn output(path: Option<&Path>) -> anyhow::Result<Box<dyn std::io::Write>> {
    use anyhow::Context;
    Ok(match path {
        Some(p) => Box::new(
            std::fs::File::create(p).with_context(|| format!("{}: cannot create", p.display()))?,
        ),
        None => Box::new(std::io::stdout().lock()),
    })
}

/// Writes `columns` as CSV to the file `path`, or to standard output; a
/// failed write names where (it said "cannot write" alone, found by review).
fn write_csv(path: Option<&Path>, columns: &[(&str, &[f64])]) -> anyhow::Result<()> {
    use anyhow::Context;
    crate::data::write_columns(output(path)?, &[], columns).with_context(|| match path {
        Some(p) => p.display().to_string(),
        None => "standard output".to_string(),
    })
}

impl Command {
    /// The files the command reads, and those it writes with the option that names each (an
    /// `fe --out` folder is created, and the files in it are the run's own).
    fn files(&self) -> (Vec<&Path>, Vec<(&'static str, &Path)>) {
        let mut inputs: Vec<&Path> = Vec::new();
        let mut outputs: Vec<(&'static str, &Path)> = Vec::new();
        fn out<'a>(
            o: &mut Vec<(&'static str, &'a Path)>,
            flag: &'static str,
            p: &'a Option<PathBuf>,
        ) {
            o.extend(p.as_deref().map(|p| (flag, p)));
        }
        match self {
            Command::Diagnose(a) => {
                inputs.push(&a.common.data);
                inputs.extend(a.params.as_deref());
                out(&mut outputs, "--report", &a.common.report);
            }
            Command::Discover(a) => {
                inputs.push(&a.common.data);
                out(&mut outputs, "--report", &a.common.report);
                out(&mut outputs, "--plot", &a.plot);
            }
            Command::Fit(a) => {
                inputs.push(&a.data);
                inputs.extend(a.params.as_deref());
                out(&mut outputs, "--out", &a.out);
                out(&mut outputs, "--pareto", &a.pareto);
            }
            Command::Sensitivity(a) => {
                inputs.extend([a.data.as_path(), a.params.as_path()]);
                out(&mut outputs, "--plot", &a.plot);
            }
            Command::Simulate(a) => {
                inputs.extend([a.history.as_path(), a.params.as_path()]);
                out(&mut outputs, "--out", &a.out);
                out(&mut outputs, "--plot", &a.plot);
            }
            Command::Export(a) => {
                inputs.extend(a.fits.iter().map(PathBuf::as_path));
                inputs.extend(a.history.as_deref());
                out(&mut outputs, "--out", &a.out);
            }
            Command::Fe(a) => {
                inputs.push(&a.specimen);
                out(&mut outputs, "--backbone", &a.backbone);
            }
            Command::Params(_) | Command::Table(_) => {}
        }
        (inputs, outputs)
    }

    /// Refuses, before any work, an output that is one of the inputs or another output (the
    /// only copy of a lab record was overwritten by a typo: found by review) or whose folder
    /// does not exist (the result of a long run was lost at the end), or that is a folder.
    /// `hyst fe --out` names a folder the run makes: the folder above it must exist, and
    /// `--backbone` may not take the name of a file the run writes there (it replaced
    /// `torque_twist.csv`: found by review).
    fn check_outputs(&self) -> anyhow::Result<()> {
        let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
            (Ok(ca), Ok(cb)) => ca == cb || one_file(a, b),
            _ => a == b,
        };
        let folder_exists = |flag: &str, p: &Path| {
            let folder = p.parent().filter(|d| !d.as_os_str().is_empty());
            match folder.filter(|d| !d.is_dir()) {
                Some(d) => Err(anyhow::anyhow!(
                    "{flag} {}: the folder {} does not exist",
                    p.display(),
                    d.display()
                )),
                None => Ok(()),
            }
        };
        let (inputs, outputs) = self.files();
        for (k, &(flag, p)) in outputs.iter().enumerate() {
            if let Some(input) = inputs.iter().find(|i| same(p, i)) {
                anyhow::bail!(
                    "{flag} {}: that is the input {}, which would be overwritten; choose another path",
                    p.display(),
                    input.display()
                );
            }
            if let Some(&(other, _)) = outputs[..k].iter().find(|(_, q)| same(p, q)) {
                anyhow::bail!(
                    "{flag} {}: {other} writes the same file; choose another path",
                    p.display()
                );
            }
            folder_exists(flag, p)?;
            // Found by review: the work was done and then lost at the write.
            if p.is_dir() {
                anyhow::bail!("{flag} {}: that is a folder; give a file name", p.display());
            }
        }
        if let Command::Fe(a) = self {
            if let Some(out) = &a.out {
                // The run makes its folder, not the folders above it.
                folder_exists("--out", out)?;
                if out.exists() && !out.is_dir() {
                    anyhow::bail!("--out {}: expected a folder, found a file", out.display());
                }
                let taken = |p: &Path| {
                    let folder = p.parent().filter(|d| !d.as_os_str().is_empty());
                    folder.is_some_and(|d| same(d, out))
                        && p.file_name()
                            .and_then(|n| n.to_str())
                            .is_some_and(crate::fe::run::writes_into_out)
                };
                if let Some(b) = a.backbone.as_deref().filter(|b| taken(b)) {
                    anyhow::bail!(
                        "--backbone {}: the run writes that file into --out {}; choose another name",
                        b.display(),
                        out.display()
                    );
                }
            }
        }
        Ok(())
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    cli.command.check_outputs()?;
    match cli.command {
        Command::Diagnose(a) => diagnose::run(a),
        Command::Discover(a) => discover::run(a),
        Command::Fit(a) => fit::run(a),
        Command::Params(a) => params::run(a),
        Command::Sensitivity(a) => sensitivity::run(a),
        Command::Simulate(a) => simulate::run(a),
        Command::Export(a) => export::run(a),
        Command::Table(a) => table::run(a),
        Command::Fe(a) => fe::run_fe(a),
    }
}
