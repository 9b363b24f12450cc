//! `hyst simulate` and `hyst fit` with `--model phm-torsion`: the polygonal
//! hysteresis model of thesis ch. 5 on torque-twist records.

use super::fit::{monotone_input, Bar, FitArgs};
use super::simulate::SimulateArgs;
use crate::data::{self, Channel, Quantity, Record, Unit};
use crate::fit::phm::{
    amplitudes, breakpoint_starts, first_excursions, fit_envelope, idealise, valid_start,
    PhmOutcome, PhmProblem,
};
use crate::fit::run::Progress;
use crate::model::{phm_json, phm_passivity, simulate_phm, PhmFile, PHM_MODEL, PHM_POINTS};
use crate::report::plots::{loop_overlay, Quantity as Axis, Trace};
use anyhow::{anyhow, bail, Context, Result};
use hysteresis::phm::{Coefficients, Direction, PhmParams};
use serde_json::{json, Map, Value};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The values of `channel` (twist or torque) in `unit`; an error naming the
/// file and the column if the record holds another quantity.
fn channel(record: &Record, channel: Channel, unit: Unit) -> Result<Vec<f64>> {
    let file = record.source().display();
    let want = channel.torsion_quantity();
    let (names, what) = match channel {
        Channel::Displacement => ("twist, rotation or angle", "twist"),
        Channel::Force => ("torque or moment", "torque"),
    };
    let Some(s) = record.series(channel) else {
        bail!(
            "{file}: expected a {what} column (named {names}, or with an {want} unit: {}), found none",
            want.known_symbols()
        );
    };
    if s.unit.quantity() != want {
        bail!(
            "{file}: the PHM needs a {what} column (named {names}, or with an {want} unit: {}), found '{}' in {} (a {} unit)",
            want.known_symbols(),
            s.name,
            s.unit,
            s.unit.quantity()
        );
    }
    Ok(s.values.iter().map(|v| unit.from_canonical(*v)).collect())
}

/// Runs `hyst simulate --model phm-torsion`.
pub fn simulate(args: &SimulateArgs) -> Result<()> {
    for (given, name) in [
        (args.mass.is_some(), "--mass"),
        (args.forcing.between.is_some(), "--forcing"),
    ] {
        if given {
            bail!("{name} is for the force-driven Bouc-Wen oscillator; the PHM is driven by twist");
        }
    }
    let file = PhmFile::read(&args.params)?;
    let (tu, mu) = file.data_units;
    let record = data::read(
        &args.history,
        &args.read.options().input(Channel::Displacement),
    )?;
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    let twist = channel(&record, Channel::Displacement, tu)?;
    let run = simulate_phm(&file.params, &twist)
        .map_err(|e| anyhow!("{}: {e}", args.history.display()))?;
    let (x_head, t_head) = (format!("twist ({tu})"), format!("torque ({mu})"));
    let columns: [(&str, &[f64]); 5] = [
        (&x_head, &run.twist),
        (&t_head, &run.torque),
        ("tangent", &run.tangent),
        ("n_positive", &run.cycles[0]),
        ("n_negative", &run.cycles[1]),
    ];
    if args.json {
        let obj = json!({
            "model": PHM_MODEL,
            "params": args.params.display().to_string(),
            "history": args.history.display().to_string(),
            "units": { "twist": tu.symbol(), "torque": mu.symbol() },
            "samples": run.twist.len(),
            "peak_torque": run.torque.iter().fold(0.0f64, |m, t| m.max(t.abs())),
            "forgotten": run.forgotten,
            "columns": columns.iter().map(|(h, v)| (h.to_string(), json!(v))).collect::<Map<_, _>>(),
        });
        writeln!(std::io::stdout().lock(), "{}", serde_json::to_string(&obj)?)?;
        if let Some(p) = &args.out {
            super::write_csv(Some(p), &columns)?;
        }
    } else {
        super::write_csv(args.out.as_deref(), &columns)?;
    }
    if run.forgotten > 0 {
        eprintln!(
            "note: {} remembered branches were dropped (inner cycles nested deeper than 8; docs/phm.md G8)",
            run.forgotten
        );
    }
    if let Some(path) = &args.plot {
        let mut traces = vec![];
        let measured = match record.quantity(Channel::Force) {
            Some(Quantity::Torque) => Some(channel(&record, Channel::Force, mu)?),
            _ => None,
        };
        if let Some(t) = &measured {
            traces.push(Trace::measured("measured", &twist, t));
        }
        traces.push(Trace::model(PHM_MODEL, &run.twist, &run.torque));
        let fig = loop_overlay(
            &traces,
            Axis::new("Twist", tu.symbol()),
            Axis::new("Torque", mu.symbol()),
        )?;
        std::fs::write(path, fig.to_svg())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    Ok(())
}

/// The start of a fit without a start file: each direction's primary curve
/// idealised from the record's envelope, the thesis' coefficients.
fn idealised_start(
    file: &Path,
    twist: &[f64],
    torque: &[f64],
) -> Result<PhmParams<f64, PHM_POINTS>> {
    let mut curves = vec![];
    for (sign, side) in [(1.0, "positive"), (-1.0, "negative")] {
        let env = first_excursions(twist, torque, sign);
        let pts = idealise(&env).ok_or_else(|| {
            anyhow!(
                "{}: the {side} direction has {} samples at a new largest twist with torque of the same sign, and needs at least 3 that go past cracking to idealise a primary curve: give a start file with --params START.json",
                file.display(),
                env.len()
            )
        })?;
        curves.push(fit_envelope(&env, &valid_start(&pts)));
    }
    PhmParams::new(&curves[0], &curves[1], Coefficients::thesis())
        .map_err(|e| anyhow!("{}: the idealised start is not valid: {e}", file.display()))
}

/// Runs `hyst fit --model phm-torsion`.
pub fn fit(args: &FitArgs) -> Result<()> {
    for (given, name) in [
        (args.mass.is_some(), "--mass"),
        (args.forcing.between.is_some(), "--forcing"),
        (args.pareto.is_some(), "--pareto"),
        (args.bits.is_some(), "--bits"),
        (args.polish, "--polish"),
    ] {
        if given {
            bail!("{name} is for the Bouc-Wen fits; the PHM fit takes a twist-driven record");
        }
    }
    if !["auto", "lsq"].contains(&args.method.as_str()) {
        bail!(
            "--method {}: the PHM is fitted by bounded least squares (lsq)",
            args.method
        );
    }
    let start_file = args.params.as_deref().map(PhmFile::read).transpose()?;
    let (tu, mu) = start_file
        .as_ref()
        .map_or((Unit::Degree, Unit::KilonewtonMetre), |f| f.data_units);
    let record = data::read(&args.data, &args.read.options())?;
    for n in record.notices() {
        eprintln!("note: {n}");
    }
    let mut twist = channel(&record, Channel::Displacement, tu)?;
    let torque = channel(&record, Channel::Force, mu)?;
    let monotone = monotone_input(&args.data, &mut twist, &args.read, "twist", tu.symbol());
    let units = [tu.symbol(), mu.symbol()];
    let start = match &start_file {
        Some(f) => f.params.clone(),
        None => idealised_start(&args.data, &twist, &torque)?,
    };
    let problem = PhmProblem::new(&twist, &torque, units, &start, &args.fix)?;
    // Without a start file, the idealised start's breakpoints may lie on the
    // wrong side of an amplitude of the record, which a local fit cannot
    // cross: other starts put each on the other sides (`breakpoint_starts`).
    // Starts that `--fix` makes equal to the first are dropped.
    let mut starts = vec![(None, problem)];
    if start_file.is_none() {
        let amps = [amplitudes(&twist, 1.0), amplitudes(&twist, -1.0)];
        for (what, p) in breakpoint_starts(&start, [&amps[0], &amps[1]]) {
            let moved = PhmProblem::new(&twist, &torque, units, &p, &args.fix)?;
            if moved.free_start() != starts[0].1.free_start() {
                starts.push((Some(what), moved));
            }
        }
    }
    let bar = Bar::new(&format!("fit {PHM_MODEL} (lsq)"), args.json);
    let t0 = Instant::now();
    let n_starts = starts.len();
    let mut best: Option<(Option<String>, PhmProblem, PhmOutcome)> = None;
    let mut simulations = 0;
    for (k, (what, problem)) in starts.into_iter().enumerate() {
        if n_starts > 1 {
            let from = what.as_deref().unwrap_or("idealised from the envelope");
            bar.stage(&format!("start {} of {n_starts}: {from}", k + 1));
        }
        let outcome = match problem.solve(|i, nrmse| bar.improved(i, nrmse)) {
            Ok(o) => o,
            // The first start is the one a user would expect to work.
            Err(e) if k == 0 => return Err(e),
            Err(_) => continue,
        };
        simulations += outcome.evaluations;
        if best.as_ref().is_none_or(|b| outcome.nrmse < b.2.nrmse) {
            best = Some((what, problem, outcome));
        }
    }
    let seconds = t0.elapsed().as_secs_f64();
    let (moved, problem, outcome) = best.expect("the first start's fit succeeded");
    // A fit may move the coefficients where closed cycles return energy
    // (docs/phm.md, "Open points"): search the fitted set within the record's
    // twist range and say so.
    let span = twist.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    bar.stage("passivity: searching closed cycles of the fitted model");
    let passivity = phm_passivity::search(&outcome.params, span, 1000, 1);
    bar.finish();
    let start_text = match (&args.params, &moved) {
        (Some(p), _) => p.display().to_string(),
        (None, None) if n_starts == 1 => "idealised from the envelope".to_string(),
        (None, None) => format!("idealised from the envelope (best of {n_starts} starts)"),
        (None, Some(m)) => {
            format!("idealised from the envelope, then {m} (best of {n_starts} starts)")
        }
    };
    let points_std = |d: usize| json!(outcome.point_std[d]);
    let std: Map<String, Value> = outcome
        .std
        .iter()
        .map(|(n, s)| (n.clone(), json!(s)))
        .collect();
    let mut meta = json!({
        "data": args.data.display().to_string(),
        "method": "lsq",
        "start": start_text,
        "starts": n_starts,
        "nrmse": outcome.nrmse,
        "iterations": outcome.iterations,
        "simulations": simulations,
        "seconds": seconds,
        "std": std,
        "primary_std": { "positive": points_std(0), "negative": points_std(1) },
        "fixed": problem.vars.iter().filter(|v| v.fixed).map(|v| json!([v.name, v.start])).collect::<Vec<_>>(),
        "identifiability": outcome.identifiability,
        "displacement_noise": monotone,
        "passivity": passivity,
    });
    args.read.record_into(&mut meta);
    if let Some(w) = &passivity.worst {
        eprintln!(
            "warning: the fitted model returns energy in {} of {} closed cycles searched within the record's twist range (worst: {:.4} {mu}*{tu} a cycle through {:?} after {:?}); its coefficients lie where the PHM's rules are not passive (docs/phm.md, \"Open points\")",
            passivity.returning_energy, passivity.cycles, w.work, w.cycle, w.history
        );
    }
    let file = phm_json(&outcome.params, (tu, mu), Some(meta.clone()));
    if let Some(out) = &args.out {
        std::fs::write(out, serde_json::to_string_pretty(&file)? + "\n")
            .with_context(|| format!("{}: cannot write", out.display()))?;
    }
    if args.json {
        let params: Map<String, Value> = ["primary", "coefficients"]
            .iter()
            .map(|k| (k.to_string(), file[*k].clone()))
            .collect();
        let obj = json!({
            "model": PHM_MODEL,
            "nrmse": outcome.nrmse,
            "params": params,
            "units": file["units"],
            "std": meta["std"],
            "primary_std": meta["primary_std"],
            "start": start_text,
            "starts": n_starts,
            "iterations": outcome.iterations,
            "simulations": simulations,
            "seconds": seconds,
            "identifiability": outcome.identifiability,
            "identifiability_summary": outcome.identifiability.summary(),
            "passivity": meta["passivity"],
        });
        outln!("{}", serde_json::to_string_pretty(&obj)?);
        return Ok(());
    }
    outln!(
        "model {PHM_MODEL}  method lsq  NRMSE {:.4e}  ({} iterations, {simulations} simulations over {n_starts} starts, {seconds:.2} s)",
        outcome.nrmse, outcome.iterations
    );
    outln!("  start: {start_text}");
    outln!(
        "  passivity: {} of {} closed cycles searched return energy",
        passivity.returning_energy,
        passivity.cycles
    );
    for (d, dir) in [Direction::Positive, Direction::Negative]
        .into_iter()
        .enumerate()
    {
        outln!(
            "  primary curve, {} (twist {tu}, torque {mu}, +- standard error):",
            ["positive", "negative"][d]
        );
        for (p, s) in outcome
            .params
            .primary(dir)
            .points()
            .iter()
            .zip(&outcome.point_std[d])
        {
            outln!(
                "    ({:.5} +- {:.2e}, {:.4} +- {:.2e})",
                p[0],
                s[0],
                p[1],
                s[1]
            );
        }
    }
    let base: usize = outcome.params.primary(Direction::Positive).points().len() * 2
        + outcome.params.primary(Direction::Negative).points().len() * 2;
    for v in &problem.vars[base..] {
        let value = outcome
            .params
            .coefficients()
            .get(&v.name)
            .unwrap_or(v.start);
        let note = match outcome.std.iter().find(|(n, _)| n == &v.name) {
            Some((_, s)) => format!("+- {s:.2e}"),
            None => "(fixed)".to_string(),
        };
        outln!("  {:<10} {value:>12.5}  {note}", v.name);
    }
    outln!("{}", outcome.identifiability.summary());
    if let Some(out) = &args.out {
        outln!("parameters written to {}", out.display());
    }
    Ok(())
}
