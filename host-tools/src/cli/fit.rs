//! `hyst fit DATA --model SPEC`: parameters of a model from a lab record.

use super::columns::ReadArgs;
use super::{ForcingArgs, ModelArg};
use crate::data;
use crate::discover::grown;
use crate::fit::experiment::{Between, Drive, Experiment, Prediction, SimError};
use crate::fit::input_noise::{self, Monotone};
use crate::fit::nsga2::{BinaryCrossover, Encoding, Nsga2};
use crate::fit::objectives::{self, Scores};
use crate::fit::problem::Problem;
use crate::fit::run::{self, Evolution, Method, Outcome, Progress};
use crate::model::{to_json, ParamFile};
use anyhow::{anyhow, bail, Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// Arguments of `hyst fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// The lab record (CSV or JSON; see the data formats in the README).
    pub data: PathBuf,
    /// Model spec: `bw` or `bwbn`, then `+effect` terms; or `phm-torsion`
    /// (a twist/torque record; see `docs/phm.md`).
    #[arg(long, default_value = "bw")]
    pub model: ModelArg,
    /// Start from this parameter file (a fit's `--out`, or written by hand; default: the
    /// model's default start). It may hold a smaller model (a `bw` fit to start `bw+pinching`):
    /// what it lacks starts at the default. For `phm-torsion`, a PHM parameter file (default: a
    /// primary curve idealised from the record's envelope and the thesis' coefficients).
    #[arg(long)]
    pub params: Option<PathBuf>,
    /// Search method: lsq, homotopy (force-driven records), nsga2 or auto (least squares from
    /// eight starts; for force-driven `bw`, screened with the fixed-step model first).
    #[arg(long, default_value = "auto")]
    pub method: String,
    /// Hold a parameter at a value (physical units), e.g. `--fix beta=2`;
    /// repeatable.
    #[arg(long = "fix", value_parser = parse_fix)]
    pub fix: Vec<(String, f64)>,
    /// Mass in kg, for force-driven records.
    #[arg(long, allow_negative_numbers = true)]
    pub mass: Option<f64>,
    #[command(flatten)]
    pub forcing: ForcingArgs,
    #[command(flatten)]
    pub read: ReadArgs,
    /// Write the fitted parameters (a parameter file) here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print one JSON object instead of the text summary.
    #[arg(long)]
    pub json: bool,
    /// NSGA-II: population size [default: 100].
    #[arg(long)]
    pub population: Option<usize>,
    /// NSGA-II: generations (counting the initial population) [default: 100].
    #[arg(long)]
    pub generations: Option<usize>,
    /// NSGA-II: seed of the random stream (runs are reproducible) [default: 1].
    #[arg(long)]
    pub seed: Option<u64>,
    /// NSGA-II: bits per variable for the binary-coded variant the thesis
    /// describes (default: real-coded, SBX and polynomial mutation).
    #[arg(long)]
    pub bits: Option<u32>,
    /// NSGA-II: write the final Pareto front (parameters and the four
    /// objectives) as CSV.
    #[arg(long)]
    pub pareto: Option<PathBuf>,
    /// NSGA-II: refine the chosen solution by bounded least squares on the
    /// NRMSE (method `nsga2+lsq`); the summary gives both errors.
    #[arg(long)]
    pub polish: bool,
}

impl FitArgs {
    /// The evolutionary settings of these arguments.
    pub fn evolution(&self) -> Evolution {
        let encoding = match self.bits {
            Some(bits) => Encoding::Binary {
                bits,
                crossover: BinaryCrossover::SinglePoint,
            },
            None => Encoding::REAL,
        };
        Evolution {
            nsga2: Nsga2 {
                population: self.population.unwrap_or(100),
                generations: self.generations.unwrap_or(100),
                seed: self.seed.unwrap_or(1),
                encoding,
                ..Nsga2::default()
            },
            front_csv: self.pareto.clone(),
            polish: self.polish,
        }
    }
}

/// Parses `name=value`.
pub fn parse_fix(s: &str) -> Result<(String, f64), String> {
    let (n, v) = s
        .split_once('=')
        .ok_or_else(|| format!("expected name=value, got `{s}`"))?;
    let v: f64 = v
        .trim()
        .parse()
        .map_err(|_| format!("`{v}` in `{s}` is not a number"))?;
    if !v.is_finite() {
        return Err(format!("`{s}`: the value is not a finite number"));
    }
    Ok((n.trim().to_string(), v))
}

/// Progress on standard error with the best error so far: a spinner on a
/// terminal; where standard error is a file or a pipe (a batch job's log),
/// plain lines instead, each stamped with the time since the start: every
/// stage, and the status at most every [`LOG_EVERY`] seconds.
pub struct Bar {
    pb: ProgressBar,
    log: Option<Log>,
}

/// The plain-line side of [`Bar`].
struct Log {
    prefix: String,
    start: Instant,
    /// When the last status line was written, and whether a stage line
    /// followed it (then the next status is news and is written at once).
    last: Mutex<(Option<Instant>, bool)>,
}

/// Seconds between two status lines of a [`Bar`] writing to a log.
pub const LOG_EVERY: u64 = 10;

/// What a line of a [`Log`] says.
#[derive(Clone, Copy, PartialEq)]
enum Line {
    /// A stage: always written.
    Stage,
    /// A status: written when a stage came since the last status line, or
    /// after [`LOG_EVERY`] seconds.
    Status,
    /// A better error: written after [`LOG_EVERY`] seconds.
    Improved,
}

impl Log {
    fn line(&self, message: &str, kind: Line) {
        let now = Instant::now();
        let Ok(mut last) = self.last.lock() else {
            return;
        };
        if kind == Line::Stage {
            last.1 = true;
        } else {
            let recent = last
                .0
                .is_some_and(|t| now.duration_since(t).as_secs() < LOG_EVERY);
            let news = kind == Line::Status && last.1;
            if recent && !news {
                return;
            }
            *last = (Some(now), false);
        }
        eprintln!(
            "{} [{} s] {message}",
            self.prefix,
            now.duration_since(self.start).as_secs()
        );
    }
}

impl Bar {
    /// A spinner labelled `what`, hidden when `quiet`.
    pub fn new(what: &str, quiet: bool) -> Bar {
        let terminal = std::io::stderr().is_terminal();
        let pb = if quiet || !terminal {
            ProgressBar::hidden()
        } else {
            ProgressBar::new_spinner()
        };
        pb.set_style(
            ProgressStyle::with_template("{spinner} {elapsed:>4} {prefix} {msg}")
                .expect("valid template"),
        );
        pb.set_prefix(what.to_string());
        pb.enable_steady_tick(std::time::Duration::from_millis(120));
        let log = (!quiet && !terminal).then(|| Log {
            prefix: what.to_string(),
            start: Instant::now(),
            last: Mutex::new((None, true)),
        });
        Bar { pb, log }
    }
    /// A note on standard error, written above a spinning bar rather than
    /// through it.
    pub fn note(&self, message: &str) {
        self.pb.suspend(|| eprintln!("note: {message}"));
    }
    /// Removes the bar.
    pub fn finish(&self) {
        self.pb.finish_and_clear();
    }
}

impl Progress for Bar {
    fn improved(&self, evaluations: usize, nrmse: f64) {
        let message = format!("{evaluations} simulations, best NRMSE {nrmse:.4e}");
        match &self.log {
            Some(log) => log.line(&message, Line::Improved),
            None => self.pb.set_message(message),
        }
    }
    fn stage(&self, message: &str) {
        match &self.log {
            Some(log) => log.line(message, Line::Stage),
            None => self.pb.println(format!("  {message}")),
        }
    }
    fn status(&self, message: &str) {
        match &self.log {
            Some(log) => log.line(message, Line::Status),
            None => self.pb.set_message(message.to_string()),
        }
    }
}

/// The mass (kg) of a force-driven model: `--mass` if given, else the
/// parameter file's `m`. A value that is not a positive number is an error
/// that says where it came from.
pub fn mass_of(given: Option<f64>, file: Option<&ParamFile>) -> Result<Option<f64>> {
    // Simulating a fitted spring with another mass is a fair question, but the
    // answer must say it is not the file's oscillator (found by review).
    if let (Some(m), Some(f)) = (given, file) {
        if let Some(&fm) = f.values.get("m").filter(|&&fm| fm != m) {
            eprintln!(
                "note: --mass {m} kg replaces the mass of {} ({fm} kg)",
                f.at(&["m"])
            );
        }
    }
    let (mass, source) = match (given, file) {
        (Some(m), _) => (m, "--mass".to_string()),
        (None, Some(f)) => match f.values.get("m") {
            Some(&m) => (m, f.at(&["m"])),
            None => return Ok(None),
        },
        (None, None) => return Ok(None),
    };
    if !(mass.is_finite() && mass > 0.0) {
        bail!("{source}: the mass must be a positive number of kg, got {mass}");
    }
    Ok(Some(mass))
}

/// The values of the parameter file `file` as a point of `problem` (the
/// record `data` with the file's model) and the model's prediction there,
/// which checks that it can be simulated: a rejected value names its place
/// in the file, a failed step its sample. A force-driven fit needs the
/// file's `xi` unless it is fixed: no damping is made up.
pub fn given_point(
    file: &ParamFile,
    problem: &Problem,
    data: &Path,
) -> Result<(Vec<f64>, Prediction)> {
    let (built, _) = file.build(problem.par.spec, problem.par.dynamic)?;
    // A `--fix` that contradicts the file: the fixed value was simulated, the file's dropped
    // without a word (`diagnose --params fit.json --fix beta=2` evaluated a mixture).
    for (name, fixed) in &problem.par.fixed {
        let given = file.values.get(*name).copied().or_else(|| built.get(name));
        if let Some(given) = given.filter(|g| g != fixed) {
            bail!(
                "--fix {name}={fixed} contradicts {}: {name} = {given} there; drop the --fix or change the file",
                file.at(&[name])
            );
        }
    }
    if problem.par.names().contains(&"xi") && !file.values.contains_key("xi") {
        bail!(
            "{}: no `xi` (viscous damping ratio): a force-driven record needs the parameters of a force-driven fit",
            file.path.display()
        );
    }
    let values: BTreeMap<&str, f64> = file.values.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    let x = problem.par.normalise(&values);
    let prediction = simulated(&x, file, problem, data)?;
    Ok((x, prediction))
}

/// The start of a fit from the parameter file `file` (`hyst fit --params`): the default start
/// with the file's values in place of its own. The file may hold a smaller model (a `bw` fit to
/// start `bw+pinching` from): the parameters of effects it lacks start where the default start
/// has them (switched off), and a note says which. A force-driven fit needs the file's `xi`
/// unless it is fixed, as [`given_point`] does: no damping is made up. A `--fix` replaces the
/// file's value with a note. A value outside this record's search range is refused with the
/// range, not clamped into it; one beyond an end by no more than 1e-9 of the range's width (a
/// fit stopped at that end, written out and scaled back: one unit in the last place on about a
/// sixth of records, found by review) starts at the end.
pub fn start_point(file: &ParamFile, problem: &Problem, data: &Path) -> Result<Vec<f64>> {
    let par = &problem.par;
    if let Err(e) = file.build(par.spec, par.dynamic) {
        match file.model.filter(|m| *m != par.spec) {
            Some(model) => bail!(
                "{} holds parameters of model {model}, which --model {} lacks: give --model {model} \
                 (or a model with more effects)",
                file.path.display(),
                par.spec
            ),
            None => return Err(e),
        }
    }
    if par.names().contains(&"xi") && !file.values.contains_key("xi") {
        bail!(
            "{}: no `xi` (viscous damping ratio): a force-driven fit starts from the parameters of \
             a force-driven fit, or give the damping with --fix xi=VALUE",
            file.path.display()
        );
    }
    for (name, fixed) in &par.fixed {
        if let Some(given) = file.values.get(*name).filter(|g| *g != fixed) {
            eprintln!(
                "note: --fix {name}={fixed} replaces {name} = {given} of {}",
                file.at(&[name])
            );
        }
    }
    let default = par.default_start();
    let mut values = par.physical(&default);
    let names = par.names();
    let mut missing = vec![];
    for name in &names {
        match file.values.get(*name) {
            Some(&v) => {
                values.insert(name, v);
            }
            None => missing.push(*name),
        }
    }
    if !missing.is_empty() {
        eprintln!(
            "note: {} has no {}: {} switched off, where the default start has {}",
            file.path.display(),
            missing.join(", "),
            if missing.len() == 1 {
                "it starts"
            } else {
                "they start"
            },
            if missing.len() == 1 { "it" } else { "them" },
        );
    }
    let mut x = par.normalise(&values);
    let (lo, hi) = par.bounds();
    for (i, name) in names.iter().enumerate() {
        let slack = 1e-9 * (hi[i] - lo[i]);
        if !(lo[i] - slack..=hi[i] + slack).contains(&x[i]) {
            let end = |v: f64| {
                let mut at = x.clone();
                at[i] = v;
                par.physical(&at)[name]
            };
            bail!(
                "{}: {name} = {} lies outside the search range of this record, {:.4e} to {:.4e} \
                 (mm, kN; the range scales with the record's displacement and force): start inside \
                 it, or hold the value with --fix {name}={}",
                file.at(&[name]),
                values[name],
                end(lo[i]),
                end(hi[i]),
                values[name]
            );
        }
        x[i] = x[i].clamp(lo[i], hi[i]);
    }
    // The file's set with the `--fix` values: a fix that breaks it is named as the cause, not
    // the record's scales (found by review: `--fix beta=1` against the file's gamma = -1).
    if !par.fixed.is_empty() {
        if let Err(e) = par.build(&x) {
            let fixes: Vec<String> = par.fixed.iter().map(|(k, v)| format!("{k}={v}")).collect();
            bail!(
                "{} with --fix {}: not a valid set: {e}",
                file.path.display(),
                fixes.join(" --fix ")
            );
        }
    }
    simulated(&x, file, problem, data)?;
    Ok(x)
}

/// The prediction of `problem` at `x`, the values of `file`: a set that fails names the file
/// and, for a failed step, the record's sample.
fn simulated(x: &[f64], file: &ParamFile, problem: &Problem, data: &Path) -> Result<Prediction> {
    match problem.try_predict(x) {
        Ok(p) => Ok(p),
        // The file's values passed `build` above: what fails here is the set scaled to the
        // record (`n = 1000` overflowed beta's scale, and the file's finite beta was blamed as
        // "not finite": found by review).
        Err(SimError::Params(e)) => bail!(
            "{}: valid as written, but not once scaled to the displacement and force of {}: {e}",
            file.at(&[e.field]),
            data.display()
        ),
        Err(e @ SimError::Step(..)) => bail!(
            "{}: the parameters of {} cannot be simulated on this record: {e}",
            data.display(),
            file.path.display()
        ),
    }
}

/// Reads a record for fitting.
pub fn load(
    path: &PathBuf,
    read: &ReadArgs,
    mass: Option<f64>,
    forcing: Option<Between>,
) -> Result<Experiment> {
    load_timed(path, read, mass, forcing).map(|l| l.exp)
}

/// A record read for fitting.
pub struct Loaded {
    /// What the model is driven with and scored against.
    pub exp: Experiment,
    /// The sample times, if the record has them.
    pub time: Option<Vec<f64>>,
    /// What was done to a noisy displacement ([`input_noise::monotone`]).
    pub monotone: Option<Monotone>,
}

/// Reads a record for fitting, with its sample times if it has any.
pub fn load_timed(
    path: &PathBuf,
    read: &ReadArgs,
    mass: Option<f64>,
    forcing: Option<Between>,
) -> Result<Loaded> {
    let mut opts = read.options();
    // A mass means the oscillator of eq. 3.3: the force is the input, also
    // in records whose columns would default to a displacement input.
    if mass.is_some() {
        opts = opts.input(data::Channel::Force);
    }
    let record = data::read(path, &opts)?;
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    let time = record.time().map(<[f64]>::to_vec);
    let mut exp = Experiment::from_record(&record, mass)?;
    if let Some(between) = forcing {
        exp = exp.with_forcing(between)?;
    }
    if exp.drive == Drive::Displacement {
        if let Some(words) =
            objectives::gives_out_energy(exp.displacement(), exp.force(), &read.negate)
        {
            eprintln!("note: {}: {words}", path.display());
        }
    }
    let monotone = match exp.drive {
        Drive::Displacement => monotone_input(path, &mut exp.input, read, "displacement", "mm"),
        Drive::Force { .. } => None,
    };
    Ok(Loaded {
        exp,
        time,
        monotone,
    })
}

/// Makes `values`, the `quantity` (displacement, twist) of the record at
/// `path`, monotone between the test's reversals where its noise makes most of
/// them ([`input_noise::monotone`]), unless `--raw-displacement` is given; says
/// so in a note.
pub fn monotone_input(
    path: &std::path::Path,
    values: &mut Vec<f64>,
    read: &ReadArgs,
    quantity: &str,
    unit: &str,
) -> Option<Monotone> {
    if read.raw_displacement {
        return None;
    }
    let (v, m) = input_noise::monotone(values)?;
    eprintln!("note: {}: {}", path.display(), m.describe(quantity, unit));
    *values = v;
    Some(m)
}

/// Where `--polish` started: the scores of the set NSGA-II chose.
fn polished_from(chosen: &Scores) -> Value {
    json!({
        "method": "nsga2",
        "nrmse": chosen.nrmse,
        "ortiz": chosen.ortiz,
    })
}

/// How the force goes between samples, for a force-driven problem.
fn forcing(problem: &Problem) -> Option<Between> {
    match problem.exp.drive {
        Drive::Force { between, .. } => Some(between),
        Drive::Displacement => None,
    }
}

/// The fit as a parameter file with its `fit` metadata.
pub fn fit_json(
    problem: &Problem,
    outcome: &Outcome,
    data: &std::path::Path,
    seconds: f64,
    monotone: Option<&Monotone>,
) -> Result<Value> {
    let candidate = problem
        .par
        .build(&outcome.x)
        .map_err(|e| anyhow!("fitted set rejected: {e}"))?;
    let mut extra = vec![];
    if let Drive::Force { mass, .. } = problem.exp.drive {
        extra.push(("xi", candidate.xi));
        extra.push(("m", mass * 1e6));
    }
    let limit = Some(candidate.params.energy_limit());
    let mut meta = json!({
        "data": data.display().to_string(),
        "method": outcome.method,
        "nrmse": outcome.scores.nrmse,
        "ortiz": outcome.scores.ortiz,
        "simulations": outcome.evaluations,
        "seconds": seconds,
        "identifiability": outcome.identifiability,
    });
    if let Some(between) = forcing(problem) {
        meta["forcing"] = json!(between.name());
    }
    if !outcome.at_bounds.is_empty() {
        meta["at_bounds"] = json!(outcome.at_bounds);
    }
    if let Some(chosen) = &outcome.polished_from {
        meta["polished_from"] = polished_from(chosen);
    }
    if let Some(m) = monotone {
        meta["displacement_noise"] = json!(m);
    }
    Ok(to_json(
        problem.par.spec,
        &outcome.values,
        limit,
        &extra,
        Some(("mm", "kN")),
        Some(meta),
    ))
}

/// Runs `hyst fit`.
pub fn run(args: FitArgs) -> Result<()> {
    let model = match args.model {
        ModelArg::Phm => return super::phm::fit(&args),
        ModelArg::Bwbn(spec) => spec,
    };
    let start = args.params.as_deref().map(ParamFile::read).transpose()?;
    let method: Method = args.method.parse()?;
    if start.is_some() && method == Method::Nsga2 {
        bail!(
            "--params gives least squares and homotopy their start; NSGA-II draws its population \
             over the whole search range and would not use it: use --method lsq, homotopy or auto"
        );
    }
    let mass = mass_of(args.mass, start.as_ref())?;
    let between = args.forcing.or_file(start.as_ref())?;
    let loaded = load_timed(&args.data, &args.read, mass, between)?;
    let monotone = loaded.monotone;
    let problem = Problem::new(model, loaded.exp, &args.fix)
        .with_context(|| args.data.display().to_string())?;
    if problem.dim() == 0 {
        bail!("every parameter of {model} is fixed: nothing to fit");
    }
    let x0 = match &start {
        Some(file) => start_point(file, &problem, &args.data)?,
        None => problem.par.default_start(),
    };
    let bar = Bar::new(&format!("fit {} ({method})", model), args.json);
    let t0 = Instant::now();
    if args.pareto.is_some() && method != Method::Nsga2 {
        bail!("--pareto writes the NSGA-II front: use it with --method nsga2");
    }
    if args.polish && method != Method::Nsga2 {
        bail!("--polish refines the solution NSGA-II chose: use it with --method nsga2");
    }
    let evolutionary = [
        ("--population", args.population.is_some()),
        ("--generations", args.generations.is_some()),
        ("--seed", args.seed.is_some()),
        ("--bits", args.bits.is_some()),
    ];
    if let Some((flag, _)) = evolutionary.iter().find(|(_, given)| *given) {
        if method != Method::Nsga2 {
            bail!("{flag} is a setting of NSGA-II, which method {method} does not run: use it with --method nsga2");
        }
    }
    let outcome = run::fit_with(&problem, method, &x0, &args.evolution(), &bar)
        .with_context(|| args.data.display().to_string())?;
    bar.finish();
    let seconds = t0.elapsed().as_secs_f64();
    let mut file = fit_json(&problem, &outcome, &args.data, seconds, monotone.as_ref())?;
    if let Some(start) = &start {
        file["fit"]["start"] = json!(start.path.display().to_string());
    }
    args.read.record_into(&mut file["fit"]);
    if let Some(out) = &args.out {
        std::fs::write(out, serde_json::to_string_pretty(&file)? + "\n")
            .with_context(|| format!("{}: cannot write", out.display()))?;
    }
    if args.json {
        let mut obj = json!({
            "model": model.to_string(),
            "nrmse": outcome.scores.nrmse,
            "ortiz": outcome.scores.ortiz,
            "method": outcome.method,
            "simulations": outcome.evaluations,
            "seconds": seconds,
            "identifiability": outcome.identifiability,
            "identifiability_summary": outcome.identifiability.summary(),
            "search_model": outcome.search.map(|s| match s {
                Ok(s) => json!({
                    "method": "rk4",
                    "steps_per_sample": s.substeps,
                    "lanes": s.lanes,
                    "checked_error": s.checked_error,
                    "retried": s.retried,
                    "by_core": s.by_core,
                    "lane_runs": s.runs,
                }),
                Err(why) => json!({ "method": "core", "reason": why.to_string() }),
            }),
            "screening": outcome.screening.map(|s| json!({
                "method": "rk4",
                "steps_per_sample": s.model.substeps,
                "lanes": s.model.lanes,
                "lane_runs": s.model.runs,
                "checked_error": s.model.checked_error,
                "starts": s.starts,
                "refined": s.refined,
            })),
            "polished_from": outcome.polished_from.as_ref().map(polished_from),
            "forcing": forcing(&problem).map(Between::name),
            "at_bounds": outcome.at_bounds,
            "displacement_noise": monotone,
        });
        obj["params"] = file
            .as_object()
            .map(|m| {
                m.iter()
                    .filter(|(k, _)| !["model", "units", "fit"].contains(&k.as_str()))
                    .map(|(k, v)| (k.clone(), v.clone()))
                    .collect::<serde_json::Map<_, _>>()
            })
            .into();
        outln!("{}", serde_json::to_string_pretty(&obj)?);
    } else {
        outln!(
            "model {}  method {}  NRMSE {:.4e}  ({} simulations, {seconds:.2} s)",
            model,
            outcome.method,
            outcome.scores.nrmse,
            outcome.evaluations
        );
        if let Some(between) = forcing(&problem) {
            outln!("  force {between} between samples");
        }
        for (name, v) in &outcome.values {
            let fixed = if problem.par.fixed.contains_key(name) {
                "  (fixed)"
            } else {
                ""
            };
            outln!("  {name:<10} {v:>14.6e}{fixed}");
        }
        outln!("{}", outcome.identifiability.summary());
        for at in &outcome.at_bounds {
            outln!("Note: {at}.");
        }
        let cornered = grown::cornered(&problem, &outcome);
        if !cornered.is_empty() {
            outln!(
                "Note: a fit can stall with an effect's parameters at the ends of their ranges \
                 ({}): `hyst diagnose` and `hyst discover` then also grow the model from its base, \
                 adding one effect at a time to the fit before, and keep the better fit.",
                cornered.join(", ")
            );
        }
        if let Some(chosen) = &outcome.polished_from {
            outln!(
                "NSGA-II chose a set with NRMSE {:.4e}; least squares from there reached {:.4e}.",
                chosen.nrmse,
                outcome.scores.nrmse
            );
        }
        if let Some(screening) = &outcome.screening {
            outln!("Note: {screening}.");
        }
        match &outcome.search {
            Some(Ok(lanes)) => outln!("Note: {lanes}."),
            Some(Err(core)) => outln!("Note: {core}."),
            None => {}
        }
        if let Some(out) = &args.out {
            outln!("parameters written to {}", out.display());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ModelSpec;

    /// A start at an end of k0's range, nudged beyond it by far less than 1e-9 of the range's
    /// width (as a stopped fit written out and scaled back lands), starts at that end; a value
    /// well beyond is refused with the range.
    #[test]
    fn a_start_at_an_end_of_its_range_is_taken_and_one_beyond_it_refused() {
        let record = PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../benches/baselines/bw_synthetic.csv"
        ));
        let exp = load(&record, &ReadArgs::default(), Some(500.0), None).unwrap();
        let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
        let (_, hi) = problem.par.bounds();
        let k = problem.par.names().iter().position(|n| *n == "k0").unwrap();
        let mut x = problem.par.default_start();
        x[k] = hi[k];
        let end = problem.par.physical(&x)["k0"];
        let file = |k0: f64| {
            let text = format!(
                r#"{{"model": "bw", "k0": {k0:?}, "alpha": 0.2, "n": 1.5, "beta": 0.5, "gamma": 0.5, "xi": 0.05}}"#
            );
            ParamFile::parse(Path::new("start.json"), &text).unwrap()
        };
        let at = start_point(&file(end * (1.0 + 1e-13)), &problem, &record).unwrap();
        assert_eq!(at[k], hi[k]);
        let e = start_point(&file(end * (1.0 + 1e-6)), &problem, &record).unwrap_err();
        assert!(
            e.to_string().contains("lies outside the search range"),
            "{e}"
        );
    }
}
