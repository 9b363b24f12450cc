//! A whole analysis of a specimen: build, step to the end of the loading,
//! sample and write output, judge the run, summarise.

use super::backbone;
use super::bar_yield;
use super::explicit::Solver;
use super::material::{BarMaterial, SolidMaterial};
use super::mesh::Quality;
use super::model::{Model, StepLimits};
use super::output::{self, Csv, Sample, Station, TORQUE_TWIST_HEADER};
use super::quasi_static::EnergyTrace;
use super::rebar::embed;
use super::section::{Cut, Profile, Stage, StageSummary};
use super::specimen::Specimen;
use super::torque_twist::{self, Comparison, Marks};
use crate::report::Figure;
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// The most steps a run may take: the specimens of Table 1.1 take 15,000 to 40,000, and 1e8
/// would take days.
pub const MAX_STEPS: u64 = 100_000_000;

/// Choices made on the command line beyond the specimen's values (which
/// `--set`, `--threads` and `--element-size` change when the file is read:
/// [`Specimen::load_with`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunOptions {
    /// Directory for CSV and VTK output (nothing is written without one).
    pub out: Option<PathBuf>,
}

/// What the progress display shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Steps taken.
    pub step: u64,
    /// Steps of the whole run.
    pub steps: u64,
    /// Time, s.
    pub t: f64,
    /// Torque, kN m.
    pub torque_knm: f64,
    /// Kinetic over internal energy now.
    pub ke_ie: f64,
}

/// The summary of a run (`hyst fe --json`).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    /// Specimen name.
    pub specimen: String,
    /// Constitutive models used.
    pub materials: &'static str,
    /// Whether the run was interrupted before the end of the loading.
    pub interrupted: bool,
    /// Whether the run ended before the end of the loading because the
    /// torque fell below `analysis.stop_below_peak` of its peak.
    pub stopped_after_peak: bool,
    /// The fraction of `analysis.stop_below_peak` (none: the whole twist
    /// history was asked for).
    pub stop_below_peak: Option<f64>,
    /// Hexahedra.
    pub elements: usize,
    /// Nodes.
    pub nodes: usize,
    /// Truss elements.
    pub trusses: usize,
    /// Element size, mm.
    pub element_size_mm: f64,
    /// Mesh quality.
    pub mesh: Quality,
    /// Stable steps and the step used.
    pub time_step: StepLimits,
    /// Physical mass, kg.
    pub physical_mass_kg: f64,
    /// Mass added by mass scaling, kg.
    pub added_mass_kg: f64,
    /// Added mass in percent of the physical mass.
    pub added_mass_percent: f64,
    /// Steps taken.
    pub steps: u64,
    /// Time reached, s.
    pub time_s: f64,
    /// Worker threads.
    pub threads: usize,
    /// Initial torsional stiffness, kN m/rad: before cracking when the run
    /// cracks ([`output::cracking`]), else the secant slope between 20% and
    /// 100% of the largest twist.
    pub initial_stiffness: Option<f64>,
    /// Saint-Venant `GJ/L` of the gross concrete section, kN m/rad.
    pub saint_venant_stiffness: f64,
    /// Cracking torque, kN m ([`output::cracking`]; none without cracking).
    pub cracking_torque: Option<f64>,
    /// Peak torque, kN m: the largest torque of a cracked run, if the
    /// torque later fell at least 1% below it (none otherwise).
    pub peak_torque: Option<f64>,
    /// Twist at `peak_torque`, rad.
    pub peak_twist: Option<f64>,
    /// Largest torque reached, kN m.
    pub max_torque: f64,
    /// Shear stress across the mid-height section (thesis Figs 2.9, 2.10)
    /// at cracking ([`backbone::cracking`]), at the peak (as
    /// `peak_torque`) and at the end of the run.
    pub section: Vec<StageSummary>,
    /// Torque when the largest strain of the longitudinal bars first
    /// reached their yield strain, kN m (none if it never did; thesis
    /// Fig. 2.2).
    pub longitudinal_yield_torque: Option<f64>,
    /// The twist at which that happened, rad: before or after
    /// `peak_twist` says whether the bars yield on the way to the peak, as
    /// the tests' hoops do (Fig. 2.2), or only in the collapse.
    pub longitudinal_yield_twist: Option<f64>,
    /// The same for the transverse bars (hoops or spiral).
    pub transverse_yield_torque: Option<f64>,
    /// The twist of the transverse bars' first yield, rad.
    pub transverse_yield_twist: Option<f64>,
    /// Largest kinetic / internal energy ratio in the judged window.
    pub max_ke_ie_ratio: f64,
    /// Largest hourglass share of the internal energy in the window.
    pub max_hourglass_share: f64,
    /// Largest relative energy imbalance in the window.
    pub max_energy_imbalance: f64,
    /// Whether all quasi-static checks hold.
    pub quasi_static: bool,
    /// The checks that failed.
    pub failures: Vec<String>,
    /// The same checks over the run up to the peak torque (none without a
    /// peak): the curve up to the peak, which thesis Table 2.1 compares,
    /// can be quasi-static while the collapse of crushed concrete after it
    /// is not.
    pub checks_to_peak: Option<PeakChecks>,
    /// The cracking and peak torques against thesis Table 2.1, if the
    /// specimen file gives its values (`[reference.table_2_1]`).
    pub table_2_1: Option<Comparison>,
    /// Files written.
    pub outputs: Vec<PathBuf>,
    /// Wall-clock time, s.
    pub wall_s: f64,
    /// Wall-clock time per element and step, ns.
    pub ns_per_element_step: f64,
    /// The torque-twist record as sampled (`torque_twist.csv`).
    #[serde(skip)]
    pub samples: Vec<Sample>,
}

/// The quasi-static checks ([`super::quasi_static`]) of a run up to its
/// peak torque.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PeakChecks {
    /// Time of the peak, s: the end of the judged window.
    pub t_peak: f64,
    /// Largest kinetic / internal energy ratio up to the peak.
    pub max_ke_ie_ratio: f64,
    /// Largest hourglass share of the internal energy up to the peak.
    pub max_hourglass_share: f64,
    /// Largest relative energy imbalance up to the peak.
    pub max_energy_imbalance: f64,
    /// Whether all checks hold up to the peak.
    pub quasi_static: bool,
    /// The checks that failed up to the peak.
    pub failures: Vec<String>,
}

/// Whether the last sample's torque lies below `fraction` of the largest
/// torque so far, and the run cracked ([`output::cracking`]) before that
/// largest torque: the rule of `analysis.stop_below_peak`. The cracking
/// condition keeps the noise of the start of a run, when the largest torque
/// is still tiny, from ending it; a fraction of 0 never holds.
fn fallen_below_peak(samples: &[Sample], fraction: f64) -> bool {
    let (Some(last), Some((peak_at, peak))) = (samples.last(), output::largest_torque(samples))
    else {
        return false;
    };
    last.torque.abs() < fraction * peak
        && output::cracking(samples).is_some_and(|(_, c)| c < peak_at)
}

/// The files a run with `--out` writes into its folder, besides the VTK
/// snapshots ([`output::VTK_PREFIXES`]).
const TORQUE_TWIST_CSV: &str = "torque_twist.csv";
const TORQUE_TWIST_SVG: &str = "torque_twist.svg";
const REBAR_STRAINS_CSV: &str = "rebar_strains.csv";
const REBAR_STRAINS_SVG: &str = "rebar_strains.svg";
const SECTION_SHEAR_CSV: &str = "section_shear.csv";
const SECTION_SHEAR_SVG: &str = "section_shear.svg";

/// Whether a run with `--out` writes a file of this name into its folder
/// (the curves, bar strains, section shear and the VTK snapshots), so that
/// no other output may take it.
pub fn writes_into_out(name: &str) -> bool {
    let snapshot = |prefix: &str| {
        name.strip_prefix(prefix)
            .and_then(|r| r.strip_suffix(".vtk"))
            .is_some_and(|n| n.len() >= 4 && n.bytes().all(|b| b.is_ascii_digit()))
    };
    [
        TORQUE_TWIST_CSV,
        TORQUE_TWIST_SVG,
        REBAR_STRAINS_CSV,
        REBAR_STRAINS_SVG,
        SECTION_SHEAR_CSV,
        SECTION_SHEAR_SVG,
    ]
    .contains(&name)
        || output::VTK_PREFIXES.iter().any(|p| snapshot(p))
}

/// Writes `fig` as `name` in the run's folder `dir`; returns its path.
fn write_svg(dir: &Path, name: &str, fig: &Figure) -> anyhow::Result<PathBuf> {
    let svg = dir.join(name);
    std::fs::write(&svg, fig.to_svg()).with_context(|| format!("writing {}", svg.display()))?;
    Ok(svg)
}

/// The bar sets whose largest strains `rebar_strains.csv` reports, in its
/// column order.
const BAR_SETS: [&str; 2] = ["longitudinal", "transverse"];

/// Runs a specimen with the given materials until the end of its loading
/// or until `stop` is set; `progress` is called about every 0.2% of the
/// run.
///
/// A run longer than [`MAX_STEPS`] is refused before it starts.
pub fn run<M: SolidMaterial, B: BarMaterial>(
    spec: &Specimen,
    materials: &'static str,
    solid: M,
    bars: Vec<B>,
    opts: &RunOptions,
    stop: &AtomicBool,
    mut progress: impl FnMut(&Progress),
) -> anyhow::Result<Summary> {
    // Checked against the machine's threads when the file was read.
    let threads = spec.analysis.threads.unwrap_or(2);
    let mesh = spec.mesh();
    let quality = mesh.section.quality(mesh.dz);
    let sets = spec.bar_sets();
    let emb =
        embed(&mesh, &sets).with_context(|| format!("embedding the bars of {}", spec.name))?;
    let model = Model::new(mesh, solid, &sets, bars, emb, spec.settings());
    let dt = model.dt();
    let end = spec.end_time();
    let ratio = end / dt;
    // Absurd but positive inputs (a twist history ending at 1e300 s, a density of 1e-300) gave
    // more steps than `u64` holds, and a run that never ended without a word (found by review).
    anyhow::ensure!(
        ratio.is_finite() && ratio <= MAX_STEPS as f64,
        "{}: the run would take {ratio:.3e} steps of {dt:.3e} s to the end of its history at \
         {end:.3e} s, more than the {MAX_STEPS:.0e} a run may take: check `loading.twist` and \
         the material values",
        spec.name
    );
    let steps = ratio.ceil() as u64;
    let every = (steps / spec.output.samples as u64).max(1);
    let vtk_every = spec
        .output
        .vtk_every_s
        .map(|v| ((v / dt).round() as u64).max(1));
    let mut s = Solver::new(model, spec.controls(), threads)
        .with_context(|| format!("starting {threads} worker threads"))?;
    s.damping = spec.preload_damping();
    let stations = output::resolve_stations(&s, &spec.output.rebar_station);
    let cut = Cut::mid_height(
        &s.model.mesh,
        spec.section.shape,
        spec.section.size_mm / 1e3,
    );

    let mut outputs = Vec::new();
    let mut files = None;
    if let Some(dir) = &opts.out {
        if !dir.is_dir() {
            std::fs::create_dir(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        let tt = dir.join(TORQUE_TWIST_CSV);
        let rb = dir.join(REBAR_STRAINS_CSV);
        let csv = Csv::create(&tt, &TORQUE_TWIST_HEADER)
            .with_context(|| format!("creating {}", tt.display()))?;
        let mut header = vec![
            "time_s",
            "twist_rad",
            "torque_kNm",
            "max_longitudinal_strain",
            "max_transverse_strain",
        ];
        header.extend(stations.iter().map(|st: &Station| st.name.as_str()));
        let rcsv =
            Csv::create(&rb, &header).with_context(|| format!("creating {}", rb.display()))?;
        outputs.push(tt);
        outputs.push(rb);
        files = Some((dir.clone(), csv, rcsv));
    }
    let mut vtk_index = 0;
    let write_row = |s: &Solver<M, B>,
                     files: &mut Option<(PathBuf, Csv, Csv)>,
                     rec: &mut Record|
     -> anyhow::Result<()> {
        let smp = Sample::of(s);
        let bars = output::largest_bar_strains(s, &BAR_SETS);
        rec.samples.push(smp);
        rec.profiles.push(cut.profile(s));
        rec.bar_strains.push(bars.clone());
        if let Some((_, csv, rcsv)) = files {
            csv.row(&smp.row())?;
            let mut r = vec![smp.t, smp.twist, smp.torque / 1e3];
            r.extend(bars.iter().map(|v| v.unwrap_or(f64::NAN)));
            r.extend(
                stations
                    .iter()
                    .map(|st| s.model.truss_state[st.truss].strain),
            );
            rcsv.row(&r)?;
        }
        Ok(())
    };
    let mut write_vtk = |s: &Solver<M, B>,
                         files: &Option<(PathBuf, Csv, Csv)>,
                         outputs: &mut Vec<PathBuf>|
     -> anyhow::Result<()> {
        if let Some((dir, _, _)) = files {
            outputs.extend(output::write_vtk(s, dir, vtk_index)?);
            vtk_index += 1;
        }
        Ok(())
    };

    let mut rec = Record::default();
    let mut trace = EnergyTrace::default();
    write_row(&s, &mut files, &mut rec)?;
    if vtk_every.is_some() {
        write_vtk(&s, &files, &mut outputs)?;
    }
    let report = (steps / 500).max(1);
    let start = Instant::now();
    let mut interrupted = false;
    let mut stopped_after_peak = false;
    while s.steps < steps {
        if stop.load(Ordering::Relaxed) {
            interrupted = true;
            break;
        }
        s.step();
        // An unstable run (a stiffness or force far beyond the specimen's, e.g. an axial
        // force that crushes the column at once) ends with an error, not with NaN results.
        let torque = s.top.reaction[super::explicit::dof::RZ];
        anyhow::ensure!(
            s.energy.kinetic.is_finite() && torque.is_finite(),
            "{}: the run diverged at t = {:.6} s (step {} of {steps}): the kinetic energy or the torque is no longer finite",
            spec.name,
            s.t,
            s.steps
        );
        trace.push(s.t, s.energy);
        if s.steps % every == 0 || s.steps == steps {
            write_row(&s, &mut files, &mut rec)?;
            if let Some(f) = spec.analysis.stop_below_peak {
                if fallen_below_peak(&rec.samples, f) {
                    stopped_after_peak = true;
                    break;
                }
            }
        }
        if vtk_every.is_some_and(|v| s.steps % v == 0) {
            write_vtk(&s, &files, &mut outputs)?;
        }
        if s.steps % report == 0 {
            progress(&Progress {
                step: s.steps,
                steps,
                t: s.t,
                torque_knm: s.top.reaction[super::explicit::dof::RZ] / 1e3,
                ke_ie: s.energy.kinetic / s.energy.internal(),
            });
        }
    }
    let wall = start.elapsed().as_secs_f64();
    if interrupted {
        write_row(&s, &mut files, &mut rec)?;
    }
    let samples = &rec.samples;
    let verdict = trace.verdict();
    let cracking = output::cracking(samples);
    let largest = output::largest_torque(samples);
    let max_torque = largest.map_or(0.0, |(_, t)| t);
    let peak_at = largest.map(|(i, _)| i);
    let passed_peak = peak_at.is_some_and(|i| {
        samples[i + 1..]
            .iter()
            .any(|x| x.torque.abs() < 0.99 * max_torque)
    });
    let peak_torque = (cracking.is_some() && passed_peak).then_some(max_torque / 1e3);
    // The sample of `peak_torque`: none unless the run cracked and peaked.
    let peak_sample = peak_at.filter(|_| peak_torque.is_some());
    let pairs = output::torque_twist(samples);
    let mut stage_at = vec![];
    if let Some(p) = peak_at {
        if let Ok((_, c)) = backbone::cracking(&pairs, p) {
            stage_at.push(("cracking", c));
        }
    }
    if let Some(p) = peak_sample {
        stage_at.push(("peak", p));
    }
    stage_at.push(("end", samples.len() - 1));
    let stages: Vec<Stage> = stage_at
        .iter()
        .map(|&(name, i)| Stage {
            name,
            t: samples[i].t,
            twist: samples[i].twist,
            torque: samples[i].torque,
            profile: &rec.profiles[i],
        })
        .collect();
    if let Some((dir, _, _)) = &files {
        let csv = dir.join(SECTION_SHEAR_CSV);
        cut.write_csv(&stages, &csv)
            .with_context(|| format!("writing {}", csv.display()))?;
        outputs.push(csv);
        let title = format!("{}: shear stress at z = {:.3} m", spec.name, cut.z);
        outputs.push(write_svg(
            dir,
            SECTION_SHEAR_SVG,
            &cut.figure(&title, &stages)?,
        )?);
    }
    let yield_strain = |mpa: f64| mpa / spec.steel.elastic_modulus_mpa;
    let first_yield = |set: usize, eps_y: f64| {
        rec.bar_strains
            .iter()
            .position(|b| b[set].is_some_and(|e| e >= eps_y))
            .map(|i| &samples[i])
    };
    let eps_y = [
        yield_strain(spec.longitudinal.yield_mpa),
        yield_strain(spec.transverse.yield_mpa),
    ];
    let longitudinal_yield = first_yield(0, eps_y[0]);
    let transverse_yield = first_yield(1, eps_y[1]);
    if let Some((dir, _, _)) = &files {
        let title = format!("{}: torque against the largest bar strains", spec.name);
        let fig = bar_yield::figure(&title, samples, &rec.bar_strains, eps_y)?;
        outputs.push(write_svg(dir, REBAR_STRAINS_SVG, &fig)?);
    }
    let failures = verdict.failures();
    let cracking_torque = cracking.map(|(_, i)| samples[i].torque.abs() / 1e3);
    let table_2_1 = spec
        .reference
        .table_2_1
        .map(|r| Comparison::new(r, cracking_torque, peak_torque));
    let checks_to_peak = peak_sample.map(|p| {
        let t_peak = samples[p].t;
        let v = trace.verdict_until(t_peak);
        let failures = v.failures();
        PeakChecks {
            t_peak,
            max_ke_ie_ratio: v.max_ke_ie_ratio,
            max_hourglass_share: v.max_hourglass_share,
            max_energy_imbalance: v.max_imbalance,
            quasi_static: failures.is_empty(),
            failures,
        }
    });
    if let Some((dir, _, _)) = &files {
        let marks = Marks {
            cracking: cracking.map(|(_, i)| i),
            peak: peak_sample,
            fails_after_peak: !failures.is_empty()
                && checks_to_peak.as_ref().is_some_and(|c| c.quasi_static),
        };
        let title = format!(
            "{}: torque against twist at {} mm elements",
            spec.name, spec.analysis.element_size_mm
        );
        let fig = torque_twist::figure(&title, samples, marks, spec.reference.table_2_1.as_ref())?;
        outputs.push(write_svg(dir, TORQUE_TWIST_SVG, &fig)?);
    }
    let m = &s.model;
    Ok(Summary {
        specimen: spec.name.clone(),
        materials,
        interrupted,
        stopped_after_peak,
        stop_below_peak: spec.analysis.stop_below_peak,
        elements: m.elements(),
        nodes: m.mesh.nodes.len(),
        trusses: m.embedding.trusses.len(),
        element_size_mm: spec.analysis.element_size_mm,
        mesh: quality,
        time_step: m.limits,
        physical_mass_kg: m.physical_mass,
        added_mass_kg: m.added_mass,
        added_mass_percent: 100.0 * m.added_mass / m.physical_mass,
        steps: s.steps,
        time_s: s.t,
        threads,
        initial_stiffness: match cracking {
            Some((k0, _)) => Some(k0 / 1e3),
            None => output::secant_stiffness(samples, 0.2, 1.0).map(|k| k / 1e3),
        },
        saint_venant_stiffness: spec.saint_venant_stiffness() / 1e3,
        cracking_torque,
        peak_torque,
        peak_twist: peak_sample.map(|p| samples[p].twist.abs()),
        max_torque: max_torque / 1e3,
        section: stages.iter().map(|st| cut.summarise(st)).collect(),
        longitudinal_yield_torque: longitudinal_yield.map(|x| x.torque.abs() / 1e3),
        longitudinal_yield_twist: longitudinal_yield.map(|x| x.twist.abs()),
        transverse_yield_torque: transverse_yield.map(|x| x.torque.abs() / 1e3),
        transverse_yield_twist: transverse_yield.map(|x| x.twist.abs()),
        max_ke_ie_ratio: verdict.max_ke_ie_ratio,
        max_hourglass_share: verdict.max_hourglass_share,
        max_energy_imbalance: verdict.max_imbalance,
        quasi_static: failures.is_empty(),
        failures,
        checks_to_peak,
        table_2_1,
        outputs,
        wall_s: wall,
        ns_per_element_step: wall * 1e9 / (s.steps.max(1) as f64 * m.elements() as f64),
        samples: rec.samples,
    })
}

/// What a run keeps of each sample.
#[derive(Default)]
struct Record {
    samples: Vec<Sample>,
    /// Shear stresses across the mid-height section.
    profiles: Vec<Profile>,
    /// Largest strain of each of [`BAR_SETS`].
    bar_strains: Vec<Vec<Option<f64>>>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::material::Elastic;
    use crate::fe::specimen::Override;
    use std::path::Path;

    /// A short plain-looking circular column: D = 300 mm, L = 0.3 m, thin
    /// bars (a spiral of 6 mm at 300 mm hardly stiffens torsion), no axial
    /// force, twisted by 0.001 rad.
    const SMALL_CIRCLE: &str = r#"
name = "small circle"
source = "test"
[section]
shape = "circular"
size_mm = 300.0
clear_cover_mm = 25.0
[column]
height_m = 0.3
[concrete]
fc_mpa = 30.0
poisson = 0.2
density_kg_m3 = 2400.0
[longitudinal]
count = 6
bar_diameter_mm = 6.0
yield_mpa = 400.0
[transverse]
kind = "spiral"
bar_diameter_mm = 6.0
spacing_mm = 300.0
yield_mpa = 400.0
[steel]
elastic_modulus_mpa = 200000.0
density_kg_m3 = 7800.0
[loading]
axial_force_kn = 0.0
axial_ramp_s = 0.002
twist = [[0.0, 0.0], [0.01, 0.001]]
interpolation = "smooth-step"
[analysis]
element_size_mm = 25.0
hourglass_scale = 1.0
bulk_viscosity = [0.06, 1.2]
dt_safety = 0.9
threads = 1
[output]
samples = 50
[reference]
longitudinal_ratio_pct = 0.24
transverse_ratio_pct = 0.16
[assumed]
"#;

    #[test]
    fn an_elastic_circle_has_shear_stress_growing_linearly_with_radius() {
        // Saint-Venant torsion of a circle: tau = G theta r / L, the same
        // at every height (no warping). A one-point hexahedron's stress is
        // the mean of the linear strain field over it, i.e. its value at
        // the centroid, so each element's stress is G theta r_c / L up to
        // the O-grid's departure from a circle and the dynamics of the
        // run (the twist rate is zero at the end of a smooth step).
        let spec = Specimen::parse(SMALL_CIRCLE, Path::new("small.toml")).expect("specimen");
        let dir = std::env::temp_dir().join(format!("hyst-fe-section-{}", std::process::id()));
        let opts = RunOptions {
            out: Some(dir.clone()),
        };
        let s = run(
            &spec,
            "elastic",
            Elastic::new(spec.concrete()),
            spec.steel(),
            &opts,
            &AtomicBool::new(false),
            |_| {},
        )
        .expect("run");
        let end = s.section.last().expect("the end stage");
        assert_eq!(end.stage, "end");
        assert_eq!(s.section.len(), 1, "no cracking, no peak");
        let iso = spec.concrete();
        let g = iso.e / (2.0 * (1.0 + iso.nu));
        let theta = s.samples.last().expect("samples").twist;
        let text = std::fs::read_to_string(dir.join("section_shear.csv")).expect("csv");
        let mut worst: f64 = 0.0;
        let mut rows = 0;
        let tau_max = g * theta * 0.15 / 0.3;
        for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
            let v: Vec<f64> = line
                .split(',')
                .map(|x| x.parse().expect("number"))
                .collect();
            let expected = g * theta * v[2] / 1e3 / 0.3;
            worst = worst.max((v[5] * 1e6 - expected).abs() / tau_max);
            rows += 1;
        }
        assert!(rows > 50, "{rows}");
        assert!(worst < 0.01, "largest error {worst} of tau_max");
        // The stresses resist the torque but for the part of each element's
        // own polar moment, `A h^2 / 6` of a square `h` x `h` cell, which
        // the one-point element carries in its hourglass modes: a share
        // `h^2 / (3 R^2)` = 0.9% of `J`; less than 2% in all.
        let ratio = end.section_torque_knm / end.torque_knm;
        assert!(ratio < 1.0 && ratio > 0.98, "{ratio}");
        // The band carrying 90%: 0.438 R on the exact circle, within half
        // an element's depth (12.5 mm) on the mesh.
        let t = end.shear_flow_thickness_mm.expect("thickness");
        let exact = (1.0 - 0.1f64.powf(0.25)) * 150.0;
        assert!((t - exact).abs() < 12.5, "{t} vs {exact}");
        std::fs::remove_dir_all(&dir).ok();
    }

    /// `stop_below_peak`'s rule, sample by sample, on a curve of the shape
    /// of the specimens' (linear to cracking at 0.01 rad, hardening to a
    /// peak of 150 at 0.06 rad, then falling) after a start whose small
    /// torques rise and fall before any twist: it holds from the first
    /// sample below half the peak on, and at no sample before.
    #[test]
    fn the_stop_rule_holds_from_the_first_sample_below_the_fraction_after_cracking() {
        let torque = |th: f64| {
            if th <= 0.01 {
                1e4 * th
            } else if th <= 0.06 {
                100.0 + 1e3 * (th - 0.01)
            } else {
                150.0 - 1e4 * (th - 0.06)
            }
        };
        let mut samples = vec![
            Sample::on_curve(0.0, 0.0),
            Sample::on_curve(0.0, 2.0),
            Sample::on_curve(0.0, 0.5),
        ];
        assert!(!fallen_below_peak(&samples, 0.5), "noise before the twist");
        let mut first = None;
        for i in 1..=80 {
            let th = 0.001 * i as f64;
            samples.push(Sample::on_curve(th, torque(th)));
            let expected = th > 0.06 && torque(th) < 75.0;
            assert_eq!(fallen_below_peak(&samples, 0.5), expected, "at {th} rad");
            if expected && first.is_none() {
                first = Some(th);
            }
        }
        assert_eq!(first, Some(0.001 * 68.0));
    }

    /// A run that unloads without cracking (an elastic curve going back
    /// down its loading line) is never stopped: the rule is for a fall
    /// after a peak, not for unloading.
    #[test]
    fn the_stop_rule_leaves_an_uncracked_run_alone() {
        let mut samples = vec![Sample::on_curve(0.0, 0.0)];
        for i in (1..=20).chain((1..20).rev()) {
            let th = 0.001 * i as f64;
            samples.push(Sample::on_curve(th, 1e4 * th));
            assert!(!fallen_below_peak(&samples, 0.5), "at {th} rad");
        }
    }

    /// A run stopped by `analysis.stop_below_peak` is the whole run cut
    /// short: an explicit step depends only on the steps before it, so
    /// every sample up to the stop is the whole run's, bit for bit. It ends
    /// at the first sample below the fraction of the peak and says why.
    #[test]
    fn a_run_stopped_below_its_peak_is_the_whole_run_cut_short() {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-92.toml");
        let coarse = |stop: &str| {
            [
                Override::set("analysis.threads", "1"),
                Override::set("analysis.element_size_mm", "50.0"),
                Override::set("analysis.stop_below_peak", stop),
            ]
        };
        let go = |sets: &[Override]| {
            let spec = Specimen::load_with(&p, sets).expect("specimen");
            let s = run(
                &spec,
                "damaged-plasticity",
                spec.concrete_damaged(),
                spec.steel_yielding(),
                &RunOptions::default(),
                &AtomicBool::new(false),
                |_| {},
            )
            .expect("run");
            (s, spec.end_time())
        };
        let (whole, end) = go(&coarse("0"));
        let (cut, _) = go(&coarse("0.5"));
        assert!(!whole.stopped_after_peak && whole.time_s >= end);
        assert!(cut.stopped_after_peak && !cut.interrupted && cut.time_s < end);
        assert_eq!(
            (whole.stop_below_peak, cut.stop_below_peak),
            (Some(0.0), Some(0.5))
        );
        let n = cut.samples.len();
        assert!(n < whole.samples.len(), "{n} samples");
        assert!(cut.samples[..] == whole.samples[..n]);
        assert_eq!(cut.cracking_torque, whole.cracking_torque);
        assert_eq!(cut.peak_torque, whole.peak_torque);
        let peak = cut.peak_torque.expect("a peak") * 1e3;
        let at = cut
            .samples
            .iter()
            .position(|x| x.torque.abs() * 1e-3 == cut.max_torque);
        let after = &cut.samples[at.expect("the peak sample")..];
        assert!(after[after.len() - 1].torque.abs() < 0.5 * peak);
        assert!(after[..after.len() - 1]
            .iter()
            .all(|x| x.torque.abs() >= 0.5 * peak));
    }

    #[test]
    fn an_interrupted_run_keeps_complete_files_and_says_so() {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../specimens/tp-92.toml");
        let coarse = [
            Override::set("analysis.threads", "1"),
            Override::set("analysis.element_size_mm", "100.0"),
        ];
        let spec = Specimen::load_with(&p, &coarse).expect("specimen");
        let dir = std::env::temp_dir().join(format!("hyst-fe-interrupt-{}", std::process::id()));
        let opts = RunOptions {
            out: Some(dir.clone()),
        };
        let stop = AtomicBool::new(false);
        let mut calls = 0;
        let s = run(
            &spec,
            "elastic",
            Elastic::new(spec.concrete()),
            spec.steel(),
            &opts,
            &stop,
            |p| {
                calls += 1;
                if p.step * 3 > p.steps {
                    stop.store(true, Ordering::Relaxed);
                }
            },
        )
        .expect("run");
        assert!(s.interrupted && calls > 0);
        assert!(s.time_s < spec.end_time());
        let csv = std::fs::read_to_string(dir.join("torque_twist.csv")).expect("csv");
        let rows: Vec<&str> = csv.lines().collect();
        assert!(rows.len() > 10);
        assert!(rows
            .iter()
            .all(|r| r.split(',').count() == TORQUE_TWIST_HEADER.len()));
        let last: Vec<f64> = rows[rows.len() - 1]
            .split(',')
            .map(|v| v.parse().expect("number"))
            .collect();
        assert!(
            (last[0] - s.time_s).abs() < 1e-8 * s.time_s,
            "{} vs {}",
            last[0],
            s.time_s
        );
        let vtk: Vec<_> = s
            .outputs
            .iter()
            .filter(|o| o.extension().is_some_and(|e| e == "vtk"))
            .collect();
        assert!(vtk.len() >= 2);
        for f in vtk {
            let text = std::fs::read_to_string(f).expect("vtk");
            assert!(text.starts_with("# vtk DataFile Version 3.0"));
            assert!(text.contains("CELL_DATA"));
        }
        assert!(std::fs::read_dir(&dir).expect("dir").all(|e| !e
            .expect("entry")
            .path()
            .to_string_lossy()
            .ends_with(".part")));
        std::fs::remove_dir_all(&dir).ok();
    }
}
