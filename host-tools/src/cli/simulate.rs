//! `hyst simulate HISTORY.csv --model SPEC --params PARAMS.json`: drives the
//! model with a displacement history and writes `displacement,force,tangent`
//! as CSV to standard output (or `--out`), optionally with a plot of the loop.
//! With a PHM file (or `--model phm-torsion`) the history is a twist and the
//! columns are `twist,torque,tangent,n_positive,n_negative` (see
//! [`phm`](super::phm)).

use super::columns::ReadArgs;
use super::fit::mass_of;
use super::{ForcingArgs, ModelArg};
use crate::data::{self, Channel};
use crate::fit::experiment::SimError;
use crate::model::Extras;
use crate::model::{is_phm, ParamFile, PHM_MODEL};
use crate::report::plots::{loop_overlay, Quantity, Trace};
use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use hysteresis::bwbn::{Bwbn, Control};
use hysteresis::Element;
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
    /// Drive by force (the oscillator of thesis eq. 3.3, as `hyst fit --mass`
    /// fits it): the history's force column is the input and the
    /// displacement is predicted. The mass in kg; when left out, a fit
    /// file's `m` is used (such a file also selects the force drive).
    #[arg(long, allow_negative_numbers = true)]
    pub mass: Option<f64>,
    #[command(flatten)]
    pub forcing: ForcingArgs,
    #[command(flatten)]
    pub read: ReadArgs,
    /// PHM only: print one JSON object (units, peak torque, the columns)
    /// instead of the CSV (which then goes to `--out` only).
    #[arg(long)]
    pub json: bool,
}

/// Whether the file at `path` is JSON declaring `"model": "phm-torsion"`
/// (an unreadable or invalid file is not: its reader reports it).
fn declares_phm(path: &std::path::Path) -> bool {
    crate::data::read_text(path)
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
    let mut el = Bwbn::with_extra(*params, extras, Control::default_for())?;
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
    let file = ParamFile::read(&args.params)?;
    if args.json {
        bail!("--json is for --model {PHM_MODEL}");
    }
    let spec = file.spec(spec)?;
    for note in file
        .switched_off(spec)
        .into_iter()
        .chain(args.read.unrepeated(&file))
    {
        eprintln!("note: {note}");
    }
    let mut opts = args.read.options();
    // A mass, or a fit of the oscillator (its file carries `m`), means the
    // force drives.
    if args.mass.is_some() || file.values.contains_key("m") {
        opts = opts.input(Channel::Force);
    }
    let record = data::read(&args.history, &opts)?;
    if record.input_channel() == Channel::Force && !record.is_torsion() {
        return forced(&args, &file, spec, &record);
    }
    if args.forcing.between.is_some() {
        bail!(
            "{}: --forcing is for force-driven records (give --mass, or a fit file with `m`); this one is driven by displacement",
            args.history.display()
        );
    }
    let record = data::read(&args.history, &opts.input(Channel::Displacement))?;
    let (params, extras) = file.build(spec, false)?;
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    if record.is_torsion() {
        bail!(
            "{}: {}: a twist/torque record, which the Bouc-Wen models do not take: use a PHM file (--model {PHM_MODEL}), or give the column a length or force unit (--force COLUMN:kN)",
            args.history.display(),
            record.channels_in_words()
        );
    }
    let u = record
        .displacement()
        .ok_or_else(|| anyhow!("{}: no displacement column", args.history.display()))?;
    let sim =
        simulate(&params, &extras, u).map_err(|e| anyhow!("{}: {e}", args.history.display()))?;
    super::write_csv(
        args.out.as_deref(),
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

/// `hyst simulate` driven by force: writes `time,force,displacement` (the
/// predicted displacement) and, when the record has one, reports the RMS
/// error against the measured displacement.
fn forced(
    args: &SimulateArgs,
    file: &ParamFile,
    spec: crate::model::ModelSpec,
    record: &data::Record,
) -> Result<()> {
    let src = args.history.display();
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    let Some(mass) = mass_of(args.mass, Some(file))? else {
        bail!(
            "{src}: the record is driven by force, so the oscillator needs its mass: give --mass KG (or an `m` in {})",
            file.path.display()
        )
    };
    let xi = *file.values.get("xi").ok_or_else(|| {
        anyhow!(
            "{}: no `xi` (viscous damping ratio): a force-driven simulation needs the parameters of a force-driven fit",
            file.path.display()
        )
    })?;
    let (params, extras) = file.build(spec, true)?;
    let dt = crate::fit::experiment::uniform_step(record)?;
    let force = record
        .force()
        .ok_or_else(|| anyhow!("{src}: no force column to drive the oscillator"))?;
    let measured = record.displacement();
    // Judged as `fit` judged it, by the record's secant stiffness, so that a
    // fit's own file is not refused (with the file's k0, 6 against a secant
    // of 2.3, a mass `fit` took was refused here: found by review); by k0
    // where the record has no displacement.
    crate::fit::experiment::check_mass(
        &src,
        mass,
        force,
        measured,
        Some((params.base().k0, &file.at(&["k0"]))),
        dt,
    )?;
    let exp = crate::fit::experiment::Experiment {
        input: force.to_vec(),
        output: measured.map_or_else(|| vec![0.0; force.len()], <[f64]>::to_vec),
        drive: crate::fit::experiment::Drive::Force {
            dt,
            mass: mass * 1e-6,
            between: args.forcing.or_file(Some(file))?.unwrap_or_default(),
        },
    };
    // A rejected set is the parameter file's fault, a failed step the record's.
    let sim = exp
        .simulate(&params, &extras, xi, Control::default_for())
        .map_err(|e| match e {
            SimError::Params(p) => anyhow!("{}: {e}", file.at(&[p.field])),
            SimError::Step(..) => anyhow!("{src}: {e}"),
        })?;
    let time: Vec<f64> = (0..force.len()).map(|i| i as f64 * dt).collect();
    super::write_csv(
        args.out.as_deref(),
        &[
            ("time", &time),
            ("force", force),
            ("displacement", &sim.displacement),
        ],
    )?;
    if let Some(u) = measured {
        let n = u.len() as f64;
        let rms = |v: &mut dyn Iterator<Item = f64>| (v.map(|x| x * x).sum::<f64>() / n).sqrt();
        let err = rms(&mut u.iter().zip(&sim.displacement).map(|(a, b)| a - b));
        let scale = rms(&mut u.iter().copied());
        eprintln!(
            "displacement RMS error {err:.4e} mm ({:.4e} m), {:.3}% of the measured RMS {scale:.4e} mm",
            err * 1e-3,
            100.0 * err / scale
        );
    }
    if let Some(path) = &args.plot {
        let name = spec.to_string();
        let mut traces = vec![];
        if let Some(u) = measured {
            traces.push(Trace::measured("measured", u, force));
        }
        traces.push(Trace::model(&name, &sim.displacement, force));
        let fig = loop_overlay(
            &traces,
            Quantity::new("Displacement", "mm"),
            Quantity::new("Applied force", "kN"),
        )?;
        std::fs::write(path, fig.to_svg())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    Ok(())
}
