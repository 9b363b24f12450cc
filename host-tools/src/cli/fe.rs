//! `hyst fe SPECIMEN.toml`: the explicit finite-element analysis of an RC
//! column under axial load and twist (thesis chapter 2).

use crate::fe::material::Elastic;
use crate::fe::run::{run, Progress, RunOptions, Summary};
use crate::fe::specimen::Specimen;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Arguments of `hyst fe`.
#[derive(Debug, Args)]
pub struct FeArgs {
    /// Specimen file (TOML), e.g. `specimens/tp-91.toml`.
    pub specimen: PathBuf,
    /// Directory for `torque_twist.csv`, `rebar_strains.csv` and VTK files.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the summary as one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Elastic concrete and steel instead of concrete damaged plasticity
    /// and yielding steel (thesis 2.2).
    #[arg(long)]
    pub elastic: bool,
    /// Worker threads (overrides the specimen file).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Element size in mm (overrides the specimen file).
    #[arg(long)]
    pub element_size: Option<f64>,
}

/// Runs the analysis. Ctrl-C stops it after the current step, keeping the
/// files written so far, and still prints the summary.
pub fn run_fe(args: FeArgs) -> anyhow::Result<()> {
    let spec = Specimen::load(&args.specimen)?;
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
        threads: args.threads,
        element_size_mm: args.element_size,
    };
    let show = |p: &Progress| {
        bar.set_length(p.steps);
        bar.set_position(p.step);
        bar.set_message(format!(
            "t = {:.4e} s  T = {:.2} kN m  KE/IE = {:.3}",
            p.t, p.torque_knm, p.ke_ie
        ));
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
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print_summary(&summary);
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

fn print_summary(s: &Summary) {
    println!(
        "{} ({} materials){}",
        s.specimen,
        s.materials,
        if s.interrupted { ", INTERRUPTED" } else { "" }
    );
    println!(
        "  mesh: {} hexahedra, {} trusses, {} nodes at {} mm (aspect <= {:.2})",
        s.elements, s.trusses, s.nodes, s.element_size_mm, s.mesh.max_aspect
    );
    println!(
        "  time step {:.3e} s (hexahedra {:.3e}, trusses {:.3e}); added mass {:.1} kg ({:.2}%)",
        s.time_step.dt, s.time_step.hex, s.time_step.truss, s.added_mass_kg, s.added_mass_percent
    );
    println!(
        "  {} steps to t = {:.4e} s on {} threads in {:.1} s ({:.0} ns per element-step)",
        s.steps, s.time_s, s.threads, s.wall_s, s.ns_per_element_step
    );
    match s.initial_stiffness {
        Some(k) => println!(
            "  initial stiffness {:.0} kN m/rad ({:.4} x Saint-Venant GJ/L = {:.0})",
            k,
            k / s.saint_venant_stiffness,
            s.saint_venant_stiffness
        ),
        None => println!("  initial stiffness: not enough twist yet"),
    }
    if let Some(t) = s.cracking_torque {
        println!("  cracking torque {t:.2} kN m");
    }
    if let Some(t) = s.peak_torque {
        println!("  peak torque {t:.2} kN m");
    }
    println!("  max torque {:.2} kN m", s.max_torque);
    println!(
        "  KE/IE max {:.4}, hourglass share max {:.4}, energy imbalance max {:.2e}",
        s.max_ke_ie_ratio, s.max_hourglass_share, s.max_energy_imbalance
    );
    if s.quasi_static {
        println!("  quasi-static checks: all hold");
    } else {
        for f in &s.failures {
            println!("  CHECK FAILED: {f}");
        }
    }
    for o in &s.outputs {
        if o.extension().is_some_and(|e| e == "csv") {
            println!("  wrote {}", o.display());
        }
    }
    let vtk = s
        .outputs
        .iter()
        .filter(|o| o.extension().is_some_and(|e| e == "vtk"))
        .count();
    if vtk > 0 {
        println!("  wrote {vtk} VTK files");
    }
}
