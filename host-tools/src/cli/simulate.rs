//! `hyst simulate HISTORY.csv --model SPEC --params PARAMS.json`: drives the
//! model with a displacement history and writes `displacement,force,tangent`
//! as CSV to standard output (or `--out`), optionally with a plot of the loop.
//! With a PHM file (or `--model phm-torsion`) the history is a twist and the
//! columns are `twist,torque,tangent,n_positive,n_negative` (see
//! [`phm`](super::phm)).

use super::ModelArg;
use crate::data::{self, Channel, ReadOptions};
use crate::model::Extras;
use crate::model::{is_phm, ParamFile, PHM_MODEL};
use crate::report::plots::{loop_overlay, Quantity, Trace};
use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use hysteresis::bwbn::{Bwbn, Control};
use hysteresis::Element;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `hyst simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Displacement history: CSV with a header naming a `displacement` column
    /// (units in parentheses allowed, `#` comment lines allowed). A record
    /// with a force column works too; its force is plotted as measured. For
    /// the PHM: a `twist` column (deg or rad), a `torque` column is plotted.
    pub history: PathBuf,
    /// Model spec (`bw`, `bwbn`, `bw+pinching`, ..., or `phm-torsion`);
    /// defaults to the parameter file's `model`.
    #[arg(long)]
    pub model: Option<ModelArg>,
    /// Parameter file (flat JSON keyed by parameter names; a fit file works;
    /// or a PHM file, `"model": "phm-torsion"`).
    #[arg(long)]
    pub params: PathBuf,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write the force-displacement loop as SVG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// PHM only: print one JSON object (units, peak torque, the columns)
    /// instead of the CSV (which then goes to `--out` only).
    #[arg(long)]
    pub json: bool,
}

/// Whether the file at `path` is JSON declaring `"model": "phm-torsion"`
/// (an unreadable or invalid file is not: its reader reports it).
fn declares_phm(path: &std::path::Path) -> bool {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .is_some_and(|v| is_phm(&v))
}

/// The simulated loop.
pub struct Simulation {
    /// Displacement (mm).
    pub displacement: Vec<f64>,
    /// Force (kN).
    pub force: Vec<f64>,
    /// Tangent (kN/mm).
    pub tangent: Vec<f64>,
    /// Hysteretic energy of the model (kN mm).
    pub energy: Vec<f64>,
}

/// Runs the element over a displacement history.
pub fn simulate(
    params: &hysteresis::bwbn::BwbnParams<f64>,
    extras: &Extras,
    u: &[f64],
) -> Result<Simulation> {
    let mut el = Bwbn::with_extra(*params, extras, Control::default_for());
    let mut s = Simulation {
        displacement: vec![],
        force: vec![],
        tangent: vec![],
        energy: vec![],
    };
    for (i, &ui) in u.iter().enumerate() {
        let r = el
            .set_trial(ui)
            .map_err(|e| anyhow!("step to sample {} (u = {ui} mm): {e}", i + 1))?;
        el.commit();
        s.displacement.push(ui);
        s.force.push(r.force);
        s.tangent.push(r.tangent);
        s.energy.push(el.committed().energy);
    }
    Ok(s)
}

/// Runs `hyst simulate`.
pub fn run(args: SimulateArgs) -> Result<()> {
    let spec = match (args.model, declares_phm(&args.params)) {
        (Some(ModelArg::Phm), _) | (None, true) => return super::phm::simulate(&args),
        (Some(ModelArg::Bwbn(spec)), true) => bail!(
            "{}: a PHM parameter file (model {PHM_MODEL}), but --model {spec}: use --model {PHM_MODEL} or leave --model out",
            args.params.display()
        ),
        (Some(ModelArg::Bwbn(spec)), false) => Some(spec),
        (None, false) => None,
    };
    if args.json {
        bail!("--json is for --model {PHM_MODEL}");
    }
    let file = ParamFile::read(&args.params)?;
    let spec = file.spec(spec)?;
    let (params, extras) = file.build(spec, false)?;
    let record = data::read(
        &args.history,
        &ReadOptions::default().input(Channel::Displacement),
    )?;
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    if record.is_torsion() {
        bail!(
            "{}: a twist/torque record: the Bouc-Wen models take displacement; use a PHM file (--model {PHM_MODEL})",
            args.history.display()
        );
    }
    let u = record
        .displacement()
        .ok_or_else(|| anyhow!("{}: no displacement column", args.history.display()))?;
    let sim = simulate(&params, &extras, u)?;
    let mut out: Box<dyn Write> = match &args.out {
        Some(p) => Box::new(
            std::fs::File::create(p).with_context(|| format!("{}: cannot create", p.display()))?,
        ),
        None => Box::new(std::io::stdout().lock()),
    };
    data::write_columns(
        &mut out,
        &[],
        &[
            ("displacement", &sim.displacement),
            ("force", &sim.force),
            ("tangent", &sim.tangent),
        ],
    )?;
    if let Some(path) = &args.plot {
        let name = spec.to_string();
        let mut traces = vec![];
        if let Some(f) = record.force() {
            traces.push(Trace::measured("measured", u, f));
        }
        traces.push(Trace::model(&name, &sim.displacement, &sim.force));
        let fig = loop_overlay(
            &traces,
            Quantity::new("Displacement", "mm"),
            Quantity::new("Force", "kN"),
        )?;
        std::fs::write(path, fig.to_svg())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    Ok(())
}
