//! `hyst fe SPECIMEN.toml`: the explicit finite-element analysis of an RC
//! column under axial load and twist (thesis chapter 2).

use super::fit::Bar;
use crate::fe::backbone::{self, PrimaryCurve};
use crate::fe::material::Elastic;
use crate::fe::output;
use crate::fe::run::{run, Progress, RunOptions, Summary};
use crate::fe::section::SHEAR_FLOW_SHARE;
use crate::fe::specimen::{Override, Specimen};
use crate::fit::run::Progress as _;
use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Arguments of `hyst fe`.
#[derive(Debug, Args)]
pub struct FeArgs {
    /// Specimen file (TOML), e.g. `specimens/tp-91.toml`.
    pub specimen: PathBuf,
    /// Directory for `torque_twist.csv`, `torque_twist.svg`, `rebar_strains.csv`,
    /// `rebar_strains.svg`, `section_shear.csv`, `section_shear.svg` and VTK
    /// files.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the PHM primary curve idealised from the computed torque-twist
    /// curve (cracking, yield, peak, deterioration; thesis Fig. 5.2) to
    /// this file, in the format `hyst simulate --model phm-torsion --params`
    /// reads.
    #[arg(long, value_name = "FILE")]
    pub backbone: Option<PathBuf>,
    /// Print the summary as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Elastic concrete and steel instead of concrete damaged plasticity
    /// and yielding steel (thesis 2.2).
    #[arg(long)]
    pub elastic: bool,
    /// Worker threads (overrides the specimen file; at most four for each
    /// hardware thread of the machine).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Element size in mm (overrides the specimen file; at most a quarter of
    /// the section, and at most 5 million elements).
    #[arg(long)]
    pub element_size: Option<f64>,
    /// Replace a value of the specimen file for this run, e.g.
    /// `--set loading.axial_force_kn=320 --set transverse.spacing_mm=94`
    /// (repeatable; the file's checks apply to the changed values).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_override)]
    pub overrides: Vec<(String, String)>,
}

fn parse_override(s: &str) -> Result<(String, String), String> {
    let (key, value) = s.split_once('=').ok_or_else(|| {
        format!("expected KEY=VALUE such as loading.axial_force_kn=320, found `{s}`")
    })?;
    Ok((key.trim().to_string(), value.trim().to_string()))
}

/// Runs the analysis. Ctrl-C stops it after the current step, keeping the
/// files written so far, and still prints the summary.
pub fn run_fe(args: FeArgs) -> anyhow::Result<()> {
    // The two options are overrides too: checked with the file's other values, and named in
    // its errors as given.
    let mut overrides: Vec<Override> = args
        .overrides
        .iter()
        .map(|(k, v)| Override::set(k, v))
        .collect();
    if let Some(h) = args.element_size {
        overrides.push(Override {
            key: "analysis.element_size_mm".into(),
            value: if h.is_nan() {
                "nan".into()
            } else {
                format!("{h:?}")
            },
            given: format!("--element-size {h}"),
        });
    }
    if let Some(t) = args.threads {
        overrides.push(Override {
            key: "analysis.threads".into(),
            value: t.to_string(),
            given: format!("--threads {t}"),
        });
    }
    // One value a key: a second would silently win (found by review).
    for (i, o) in overrides.iter().enumerate() {
        if let Some(first) = overrides[..i].iter().find(|p| p.key == o.key) {
            anyhow::bail!(
                "{} and {} both set `{}`: give it once",
                first.given,
                o.given,
                o.key
            );
        }
    }
    let spec = Specimen::load_with(&args.specimen, &overrides)?;
    for note in spec.notes() {
        eprintln!("note: {note}");
    }
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed))?;
    let bar = ProgressBar::new(1);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} steps {elapsed_precise} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let opts = RunOptions {
        out: args.out.clone(),
    };
    // Where standard error is a log, not a terminal: a plain line every few
    // seconds instead of the bar.
    let log = (!args.json && !std::io::stderr().is_terminal())
        .then(|| Bar::new(&format!("fe {}", args.specimen.display()), false));
    let show = |p: &Progress| {
        // Before any strain there is no internal energy: no ratio to show.
        let ke_ie = if p.ke_ie.is_finite() {
            format!("{:.3}", p.ke_ie)
        } else {
            "-".to_string()
        };
        let state = format!(
            "t = {:.4e} s  T = {:.2} kN m  KE/IE = {ke_ie}",
            p.t, p.torque_knm
        );
        match &log {
            Some(log) => log.status(&format!(
                "step {} of {} ({:.0}%)  {state}",
                p.step,
                p.steps,
                100.0 * p.step as f64 / p.steps.max(1) as f64
            )),
            None => {
                bar.set_length(p.steps);
                bar.set_position(p.step);
                bar.set_message(state);
            }
        }
    };
    let summary = if args.elastic {
        let concrete = Elastic::new(spec.concrete());
        run(&spec, "elastic", concrete, spec.steel(), &opts, &stop, show)?
    } else {
        let concrete = spec.concrete_damaged();
        let steel = spec.steel_yielding();
        run(
            &spec,
            "damaged-plasticity",
            concrete,
            steel,
            &opts,
            &stop,
            show,
        )?
    };
    bar.finish_and_clear();
    let primary = args
        .backbone
        .as_ref()
        .map(|path| write_backbone(&args, &summary, path));
    if args.json {
        let mut v = serde_json::to_value(&summary)?;
        if !args.overrides.is_empty() {
            v["overrides"] = args
                .overrides
                .iter()
                .map(|(k, val)| (k.clone(), serde_json::Value::String(val.clone())))
                .collect::<serde_json::Map<_, _>>()
                .into();
        }
        if let Some(Ok(curve)) = &primary {
            v["primary_curve"] = serde_json::to_value(curve)?;
        }
        outln!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        for (key, value) in &args.overrides {
            outln!("  {key} = {value} (--set)");
        }
        print_summary(&summary)?;
        if let (Some(Ok(curve)), Some(path)) = (&primary, &args.backbone) {
            print_primary(curve, path)?;
        }
    }
    if let Some(Err(e)) = primary {
        return Err(e);
    }
    if summary.interrupted {
        anyhow::bail!(
            "interrupted at step {} (t = {:.4e} s); the files written so far are complete",
            summary.steps,
            summary.time_s
        );
    }
    Ok(())
}

/// Idealises the run's torque-twist curve (in deg and kN m) and writes the
/// PHM file.
fn write_backbone(
    args: &FeArgs,
    summary: &Summary,
    path: &std::path::Path,
) -> anyhow::Result<PrimaryCurve> {
    let curve: Vec<[f64; 2]> = output::torque_twist(&summary.samples)
        .iter()
        .map(|&[x, t]| [x.to_degrees(), t / 1e3])
        .collect();
    let primary = backbone::idealise(&curve).with_context(|| {
        format!(
            "--backbone {}: no PHM primary curve from {}{}",
            path.display(),
            args.specimen.display(),
            if args.out.is_some() {
                " (the other outputs are written)"
            } else {
                ""
            }
        )
    })?;
    let source = serde_json::json!({
        "method": "idealised from hyst fe (docs/fe.md, PHM primary curve)",
        "specimen": args.specimen.display().to_string(),
        "materials": summary.materials,
        "element_size_mm": summary.element_size_mm,
        "interrupted": summary.interrupted,
        "stopped_after_peak": summary.stopped_after_peak,
        "quasi_static": summary.quasi_static,
        "quasi_static_to_peak": summary.checks_to_peak.as_ref().map(|c| c.quasi_static),
        "initial_stiffness_kNm_per_deg": primary.initial_stiffness,
        "coefficients": "the thesis' (ch. 5): a monotonic analysis does not give them",
    });
    let file = primary.phm_file(source)?;
    std::fs::write(path, serde_json::to_string_pretty(&file)? + "\n")
        .with_context(|| format!("--backbone {}: cannot write", path.display()))?;
    Ok(primary)
}

fn print_primary(c: &PrimaryCurve, path: &std::path::Path) -> std::io::Result<()> {
    outln!(
        "  PHM primary curve (deg, kN m), written to {}:",
        path.display()
    );
    for (name, p) in [
        ("cracking", c.cracking),
        ("yield", c.yield_point),
        ("peak", c.peak),
        ("deterioration", c.deterioration),
    ] {
        outln!("    {name:<13} ({:.5}, {:.2})", p[0], p[1]);
    }
    Ok(())
}

fn print_summary(s: &Summary) -> std::io::Result<()> {
    outln!(
        "{} ({} materials){}",
        s.specimen,
        s.materials,
        if s.interrupted { ", INTERRUPTED" } else { "" }
    );
    outln!(
        "  mesh: {} hexahedra, {} trusses, {} nodes at {} mm (aspect <= {:.2})",
        s.elements,
        s.trusses,
        s.nodes,
        s.element_size_mm,
        s.mesh.max_aspect
    );
    let limit = match (s.time_step.global, s.time_step.global_iterations) {
        (Some(g), Some(it)) => {
            format!("whole model {g:.3e} from its highest frequency ({it} Lanczos iterations); ")
        }
        (None, Some(it)) => format!(
            "the whole model's highest frequency had not settled after {it} Lanczos iterations, so the elements' step is used; "
        ),
        _ => String::new(),
    };
    outln!(
        "  time step {:.3e} s ({limit}elements alone: hexahedra {:.3e}, trusses {:.3e}); added mass {:.1} kg ({:.2}%)",
        s.time_step.dt,
        s.time_step.hex,
        s.time_step.truss,
        s.added_mass_kg,
        s.added_mass_percent
    );
    outln!(
        "  {} steps to t = {:.4e} s on {} threads in {:.1} s ({:.0} ns per element-step){}",
        s.steps,
        s.time_s,
        s.threads,
        s.wall_s,
        s.ns_per_element_step,
        match s.stop_below_peak {
            Some(f) if s.stopped_after_peak => format!(
                "; ended there: the torque fell below {f} of its peak (analysis.stop_below_peak)"
            ),
            _ => String::new(),
        }
    );
    match s.initial_stiffness {
        Some(k) => outln!(
            "  initial stiffness {:.0} kN m/rad ({:.4} x Saint-Venant GJ/L = {:.0})",
            k,
            k / s.saint_venant_stiffness,
            s.saint_venant_stiffness
        ),
        None => outln!("  initial stiffness: not enough twist yet"),
    }
    if let Some(t) = s.cracking_torque {
        outln!("  cracking torque {t:.2} kN m");
    }
    if let Some(t) = s.peak_torque {
        outln!("  peak torque {t:.2} kN m");
    }
    outln!("  max torque {:.2} kN m", s.max_torque);
    if let Some(c) = &s.table_2_1 {
        let r = &c.reference;
        let here =
            |e: Option<f64>| e.map_or("not reached".into(), |e| format!("{:+.1}%", 100.0 * e));
        outln!(
            "  thesis Table 2.1: cracking, test {:.1} kN m (here {}), thesis FE {:.1}; ultimate, test {:.1} kN m (here {}), thesis FE {:.1}",
            r.test_cracking_knm,
            here(c.cracking_error),
            r.thesis_fe_cracking_knm,
            r.test_peak_knm,
            here(c.peak_error),
            r.thesis_fe_peak_knm
        );
    }
    for (set, t, twist) in [
        (
            "transverse",
            s.transverse_yield_torque,
            s.transverse_yield_twist,
        ),
        (
            "longitudinal",
            s.longitudinal_yield_torque,
            s.longitudinal_yield_twist,
        ),
    ] {
        match (t, twist) {
            (Some(t), Some(th)) => {
                let when = match s.peak_twist {
                    Some(p) if th <= p => format!(", before the peak (at {p:.4} rad)"),
                    Some(p) => format!(", after the peak (at {p:.4} rad)"),
                    None => String::new(),
                };
                outln!("  {set} bars first yield at {t:.2} kN m, twist {th:.4} rad{when}");
            }
            _ => outln!("  {set} bars do not yield"),
        }
    }
    for st in &s.section {
        outln!(
            "  section at {}: torque {:.2} kN m (section {:.2}), max shear {:.2} MPa, shear-flow thickness ({:.0}% of the torque) {}",
            st.stage,
            st.torque_knm,
            st.section_torque_knm,
            st.max_shear_mpa,
            100.0 * SHEAR_FLOW_SHARE,
            st.shear_flow_thickness_mm
                .map_or("none".to_string(), |t| format!("{t:.1} mm"))
        );
    }
    outln!(
        "  KE/IE max {:.4}, hourglass share max {:.4}, energy imbalance max {:.2e}",
        s.max_ke_ie_ratio,
        s.max_hourglass_share,
        s.max_energy_imbalance
    );
    if let Some(c) = &s.checks_to_peak {
        outln!(
            "  up to the peak (t = {:.4e} s): KE/IE max {:.4}, hourglass share max {:.4}, energy imbalance max {:.2e}",
            c.t_peak, c.max_ke_ie_ratio, c.max_hourglass_share, c.max_energy_imbalance
        );
        if c.quasi_static {
            outln!("  quasi-static checks up to the peak: all hold");
        }
        for f in &c.failures {
            outln!("  CHECK FAILED up to the peak: {f}");
        }
    }
    if s.quasi_static {
        outln!("  quasi-static checks over the whole run: all hold");
    } else {
        for f in &s.failures {
            outln!("  CHECK FAILED over the whole run: {f}");
        }
    }
    for o in &s.outputs {
        if o.extension().is_some_and(|e| e == "csv" || e == "svg") {
            outln!("  wrote {}", o.display());
        }
    }
    let vtk = s
        .outputs
        .iter()
        .filter(|o| o.extension().is_some_and(|e| e == "vtk"))
        .count();
    if vtk > 0 {
        outln!("  wrote {vtk} VTK files");
    }
    Ok(())
}
