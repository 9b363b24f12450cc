//! Output of a run: the torque-twist CSV, rebar strains at stations, and
//! legacy VTK files (ParaView) of the concrete and the bars. Every CSV row
//! is flushed when written and every VTK file is written under a temporary
//! name and renamed, so an interrupted run leaves complete files.

use super::backbone;
use super::explicit::{dof, Solver};
use super::material::{BarMaterial, SolidMaterial};
use super::specimen::StationSpec;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// One row of the torque-twist record.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Twist of the top, rad.
    pub twist: f64,
    /// Torque applied at the reference point (reaction of the driven
    /// twist), N m.
    pub torque: f64,
    /// Torque the column's top layer resists with (without the top's own
    /// inertia), N m.
    pub column_torque: f64,
    /// Torque at the fixed base, N m.
    pub base_torque: f64,
    /// Axial force at the reference point (compression negative), N.
    pub axial_force: f64,
    /// Axial displacement of the top, m.
    pub axial_displacement: f64,
    /// Kinetic energy, J.
    pub kinetic: f64,
    /// Internal energy (strain + hourglass), J.
    pub internal: f64,
    /// Hourglass energy, J.
    pub hourglass: f64,
    /// Bulk-viscosity dissipation, J.
    pub viscous: f64,
    /// External work, J.
    pub work: f64,
}

impl Sample {
    /// A sample of a torque-twist curve alone (N m, rad): the three
    /// torques equal, no energies. For tests of what reads curves.
    #[cfg(test)]
    pub(crate) fn on_curve(twist: f64, torque: f64) -> Sample {
        Sample {
            t: 0.0,
            twist,
            torque,
            column_torque: torque,
            base_torque: torque,
            axial_force: 0.0,
            axial_displacement: 0.0,
            kinetic: 0.0,
            internal: 0.0,
            hourglass: 0.0,
            viscous: 0.0,
            work: 0.0,
        }
    }

    /// The sample of the solver's current state.
    pub fn of<M: SolidMaterial, B: BarMaterial>(s: &Solver<M, B>) -> Sample {
        let d = s.top.displacement();
        Sample {
            t: s.t,
            twist: d[dof::RZ],
            torque: s.top.reaction[dof::RZ],
            column_torque: s.top.column[dof::RZ],
            base_torque: s.base_torque(),
            axial_force: s.top.reaction[dof::UZ],
            axial_displacement: d[dof::UZ],
            kinetic: s.energy.kinetic,
            internal: s.energy.internal(),
            hourglass: s.energy.hourglass,
            viscous: s.energy.viscous,
            work: s.energy.work,
        }
    }
}

/// A CSV file written row by row, flushed after every row.
pub struct Csv {
    w: BufWriter<File>,
}

impl Csv {
    /// Creates the file and writes the header.
    pub fn create(path: &Path, header: &[&str]) -> std::io::Result<Csv> {
        let mut w = BufWriter::new(File::create(path)?);
        writeln!(w, "{}", header.join(","))?;
        w.flush()?;
        Ok(Csv { w })
    }

    /// Writes one row.
    pub fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        let s: Vec<String> = values.iter().map(|v| format!("{v:.9e}")).collect();
        writeln!(self.w, "{}", s.join(","))?;
        self.w.flush()
    }
}

/// Header of the torque-twist CSV (SI units but torque in kN m).
pub const TORQUE_TWIST_HEADER: [&str; 12] = [
    "time_s",
    "twist_rad",
    "torque_kNm",
    "column_torque_kNm",
    "base_torque_kNm",
    "axial_force_kN",
    "axial_displacement_mm",
    "kinetic_J",
    "internal_J",
    "hourglass_J",
    "viscous_J",
    "work_J",
];

impl Sample {
    /// The row of the torque-twist CSV.
    pub fn row(&self) -> [f64; 12] {
        [
            self.t,
            self.twist,
            self.torque / 1e3,
            self.column_torque / 1e3,
            self.base_torque / 1e3,
            self.axial_force / 1e3,
            self.axial_displacement * 1e3,
            self.kinetic,
            self.internal,
            self.hourglass,
            self.viscous,
            self.work,
        ]
    }
}

/// A rebar strain station resolved to a truss.
#[derive(Clone, Debug, PartialEq)]
pub struct Station {
    /// Column name.
    pub name: String,
    /// The truss.
    pub truss: usize,
}

/// Finds, for each station, the truss of its bar set whose midpoint is
/// nearest (height difference plus arc length at the bar's radius).
pub fn resolve_stations<M: SolidMaterial, B: BarMaterial>(
    s: &Solver<M, B>,
    stations: &[StationSpec],
) -> Vec<Station> {
    let emb = &s.model.embedding;
    stations
        .iter()
        .filter_map(|st| {
            let set = s.model.bar_names.iter().position(|n| *n == st.set)?;
            let target = st.angle_deg.to_radians();
            emb.trusses
                .iter()
                .enumerate()
                .filter(|(_, t)| t.set as usize == set)
                .map(|(i, t)| {
                    let p = emb.positions[t.ends[0] as usize];
                    let q = emb.positions[t.ends[1] as usize];
                    let m = [
                        (p[0] + q[0]) / 2.0,
                        (p[1] + q[1]) / 2.0,
                        (p[2] + q[2]) / 2.0,
                    ];
                    let r = m[0].hypot(m[1]);
                    let mut da = (m[1].atan2(m[0]) - target).rem_euclid(std::f64::consts::TAU);
                    if da > std::f64::consts::PI {
                        da = std::f64::consts::TAU - da;
                    }
                    ((m[2] - st.z_m).abs() + r * da, i)
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, i)| Station {
                    name: st.name.clone(),
                    truss: i,
                })
        })
        .collect()
}

/// The largest axial strain of the trusses of each named bar set (`None`
/// for a set the model does not have), for the strains against torque of
/// thesis Fig. 2.2.
pub fn largest_bar_strains<M: SolidMaterial, B: BarMaterial>(
    s: &Solver<M, B>,
    sets: &[&str],
) -> Vec<Option<f64>> {
    let m = &s.model;
    sets.iter()
        .map(|name| {
            let set = m.bar_names.iter().position(|n| n == name)?;
            m.embedding
                .trusses
                .iter()
                .zip(&m.truss_state)
                .filter(|(t, _)| t.set as usize == set)
                .map(|(_, st)| st.strain)
                .reduce(f64::max)
        })
        .collect()
}

fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let tmp = path.with_extension("vtk.part");
    {
        let mut w = BufWriter::new(File::create(&tmp)?);
        body(&mut w)?;
        w.flush()?;
    }
    std::fs::rename(&tmp, path)
}

/// The names of the VTK snapshots before their four-digit index: concrete,
/// then bars.
pub const VTK_PREFIXES: [&str; 2] = ["concrete_", "rebar_"];

/// Writes `concrete_NNNN.vtk` (hexahedra: displacement and velocity at
/// nodes; stress, strain and the material's history fields per element)
/// and `rebar_NNNN.vtk` (trusses: axial strain and stress) into `dir`.
pub fn write_vtk<M: SolidMaterial, B: BarMaterial>(
    s: &Solver<M, B>,
    dir: &Path,
    index: usize,
) -> std::io::Result<[PathBuf; 2]> {
    let m = &s.model;
    let conc = dir.join(format!("{}{index:04}.vtk", VTK_PREFIXES[0]));
    write_atomically(&conc, |w| {
        writeln!(w, "# vtk DataFile Version 3.0")?;
        writeln!(w, "hyst fe: concrete at t = {:.6e} s", s.t)?;
        writeln!(w, "ASCII\nDATASET UNSTRUCTURED_GRID")?;
        writeln!(w, "POINTS {} double", m.mesh.nodes.len())?;
        for p in &m.mesh.nodes {
            writeln!(w, "{:.6e} {:.6e} {:.6e}", p[0], p[1], p[2])?;
        }
        let n = m.mesh.hexes.len();
        writeln!(w, "CELLS {n} {}", 9 * n)?;
        for h in &m.mesh.hexes {
            writeln!(
                w,
                "8 {} {} {} {} {} {} {} {}",
                h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7]
            )?;
        }
        writeln!(w, "CELL_TYPES {n}")?;
        for _ in 0..n {
            writeln!(w, "12")?;
        }
        writeln!(w, "POINT_DATA {}", m.mesh.nodes.len())?;
        writeln!(w, "VECTORS displacement double")?;
        for (x, x0) in s.x.iter().zip(&m.mesh.nodes) {
            writeln!(
                w,
                "{:.6e} {:.6e} {:.6e}",
                x[0] - x0[0],
                x[1] - x0[1],
                x[2] - x0[2]
            )?;
        }
        writeln!(w, "VECTORS velocity double")?;
        for v in &s.v {
            writeln!(w, "{:.6e} {:.6e} {:.6e}", v[0], v[1], v[2])?;
        }
        writeln!(w, "CELL_DATA {n}")?;
        for (name, strain) in [("stress", false), ("strain", true)] {
            writeln!(w, "TENSORS {name} double")?;
            for b in &m.batches {
                for l in 0..b.len {
                    let c = if strain { &b.strain } else { &b.stress };
                    let t = [
                        c[0].0[l], c[1].0[l], c[2].0[l], c[3].0[l], c[4].0[l], c[5].0[l],
                    ];
                    writeln!(w, "{:.6e} {:.6e} {:.6e}", t[0], t[3], t[5])?;
                    writeln!(w, "{:.6e} {:.6e} {:.6e}", t[3], t[1], t[4])?;
                    writeln!(w, "{:.6e} {:.6e} {:.6e}", t[5], t[4], t[2])?;
                }
            }
        }
        let names = m.solid.field_names();
        if !names.is_empty() {
            let mut vals = Vec::with_capacity(names.len());
            let mut cols: Vec<Vec<f64>> = vec![Vec::with_capacity(n); names.len()];
            for b in &m.batches {
                for st in &b.state[..b.len] {
                    vals.clear();
                    m.solid.fields(st, &mut vals);
                    for (c, v) in cols.iter_mut().zip(&vals) {
                        c.push(*v);
                    }
                }
            }
            for (name, col) in names.iter().zip(&cols) {
                writeln!(w, "SCALARS {name} double 1\nLOOKUP_TABLE default")?;
                for v in col {
                    writeln!(w, "{v:.6e}")?;
                }
            }
        }
        Ok(())
    })?;
    let bars = dir.join(format!("{}{index:04}.vtk", VTK_PREFIXES[1]));
    let emb = &m.embedding;
    write_atomically(&bars, |w| {
        writeln!(w, "# vtk DataFile Version 3.0")?;
        writeln!(w, "hyst fe: bars at t = {:.6e} s", s.t)?;
        writeln!(w, "ASCII\nDATASET UNSTRUCTURED_GRID")?;
        writeln!(w, "POINTS {} double", emb.positions.len())?;
        for p in &emb.positions {
            writeln!(w, "{:.6e} {:.6e} {:.6e}", p[0], p[1], p[2])?;
        }
        let n = emb.trusses.len();
        writeln!(w, "CELLS {n} {}", 3 * n)?;
        for t in &emb.trusses {
            writeln!(w, "2 {} {}", t.ends[0], t.ends[1])?;
        }
        writeln!(w, "CELL_TYPES {n}")?;
        for _ in 0..n {
            writeln!(w, "3")?;
        }
        writeln!(w, "POINT_DATA {}", emb.positions.len())?;
        writeln!(w, "VECTORS displacement double")?;
        for (x, x0) in s.bar_points().iter().zip(&emb.positions) {
            writeln!(
                w,
                "{:.6e} {:.6e} {:.6e}",
                x[0] - x0[0],
                x[1] - x0[1],
                x[2] - x0[2]
            )?;
        }
        writeln!(w, "CELL_DATA {n}")?;
        writeln!(w, "SCALARS axial_strain double 1\nLOOKUP_TABLE default")?;
        for t in &m.truss_state {
            writeln!(w, "{:.6e}", t.strain)?;
        }
        writeln!(w, "SCALARS axial_stress double 1\nLOOKUP_TABLE default")?;
        for t in &m.truss_state {
            writeln!(w, "{:.6e}", t.stress)?;
        }
        writeln!(w, "SCALARS bar_set int 1\nLOOKUP_TABLE default")?;
        for t in &emb.trusses {
            writeln!(w, "{}", t.set)?;
        }
        Ok(())
    })?;
    Ok([conc, bars])
}

/// Least-squares slope through the origin of torque against twist over the
/// samples whose twist lies within `[lo, hi]` of the largest twist reached.
pub fn secant_stiffness(samples: &[Sample], lo: f64, hi: f64) -> Option<f64> {
    let top = samples.iter().fold(0.0f64, |m, s| m.max(s.twist.abs()));
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for s in samples {
        let a = s.twist.abs();
        if top > 0.0 && a >= lo * top && a <= hi * top {
            sxy += s.twist * s.torque;
            sxx += s.twist * s.twist;
        }
    }
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Initial stiffness and cracking torque of an inelastic run. The initial
/// stiffness is [`backbone::initial_stiffness`]: the least-squares slope
/// through the origin of torque against twist over the samples whose torque
/// lies between 10% and 30% of the largest torque, taken before the torque
/// first exceeds 30% (before cracking, past the start-up of the loading,
/// not on the descending branch); the cracking torque is the torque of the
/// first later sample whose secant stiffness `T / theta` is 10% below it.
/// Returns the initial stiffness and the index of that sample; `None` when
/// the secant never drops that far (an elastic run) or there are too few
/// samples.
pub fn cracking(samples: &[Sample]) -> Option<(f64, usize)> {
    let (k0, rise) = backbone::initial_stiffness(&torque_twist(samples))?;
    (rise..samples.len())
        .find(|&i| (samples[i].torque / samples[i].twist).abs() < 0.9 * k0.abs())
        .map(|i| (k0, i))
}

/// The index of the sample with the largest torque magnitude (the first if
/// several) and that magnitude, N m; `None` without samples.
pub fn largest_torque(samples: &[Sample]) -> Option<(usize, f64)> {
    let max = samples.iter().fold(0.0f64, |a, x| a.max(x.torque.abs()));
    let at = samples.iter().position(|x| x.torque.abs() == max)?;
    Some((at, max))
}

/// The `[twist, torque]` pairs of the samples.
pub fn torque_twist(samples: &[Sample]) -> Vec<[f64; 2]> {
    samples.iter().map(|s| [s.twist, s.torque]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(twist: f64, torque: f64) -> Sample {
        Sample::on_curve(twist, torque)
    }

    /// Bilinear: 2e7 N m/rad to 1e5 N m at 0.005 rad, then 1e6 N m/rad.
    fn bilinear(th: f64) -> f64 {
        if th <= 0.005 {
            2e7 * th
        } else {
            1e5 + 1e6 * (th - 0.005)
        }
    }

    #[test]
    fn secant_stiffness_uses_its_window() {
        let s: Vec<Sample> = (0..=10)
            .map(|i| {
                let th = i as f64 * 0.001;
                sample(th, bilinear(th))
            })
            .collect();
        let k = secant_stiffness(&s, 0.1, 0.5).expect("samples");
        assert!((k - 2e7).abs() < 1e-6);
        assert!(secant_stiffness(&[], 0.1, 0.5).is_none());
    }

    #[test]
    fn cracking_is_where_the_secant_falls_below_the_initial_stiffness() {
        // The bilinear curve and a descending branch through 10-30% of the
        // peak, which must not enter the initial stiffness.
        let mut s: Vec<Sample> = (0..=100)
            .map(|i| {
                let th = i as f64 * 0.0002;
                sample(th, bilinear(th))
            })
            .collect();
        s.extend((1..=10).map(|i| sample(0.02 + 0.001 * i as f64, 1.15e5 - 1e4 * i as f64)));
        let (k0, i) = cracking(&s).expect("cracks");
        let tc = s[i].torque;
        assert!((k0 - 2e7).abs() < 1e-6);
        // Secant 1e5 (1 + 10 (th - 0.005)) / th < 1.8e7 first at th = 0.0056.
        assert!((tc - (1e5 + 1e6 * 0.0006)).abs() < 1e-6, "{tc}");
        let linear: Vec<Sample> = (0..=10).map(|i| sample(i as f64, 3.0 * i as f64)).collect();
        assert!(cracking(&linear).is_none());
    }
}
