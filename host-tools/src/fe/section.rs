//! Shear stress across the mid-height cross-section (thesis 2.7.5, Figs 2.9
//! and 2.10) and the thickness of the shear-flow zone.
//!
//! The cut is the layer of hexahedra whose mid-plane is nearest to half the
//! column height. Each element gives its one-point stress at its centroid
//! `(x, y)`; the torsional shear stress is the circumferential component
//! `tau = tau_ztheta = -sin(theta) tau_xz + cos(theta) tau_yz` at the polar
//! angle `theta` of the centroid. It is the shear that resists the torque,
//! `T = sum tau r A` (`r` the centroid radius, `A` the element's area in
//! the section), and, by symmetry, the shear stress along the lines of Fig.
//! 2.10 (parallel to the face towards the edges, across the diagonal along
//! it).
//!
//! **Shear-flow thickness.** The thesis uses the thin-tube idealisation
//! (Bredt; Fig. 2.7: the torque is carried by shear flowing in an outer
//! band, the core does not contribute) but gives no number or rule for the
//! band's thickness. Here it is the thickness `t` of the outer band of the
//! section that carries [`SHEAR_FLOW_SHARE`] (90%) of the section's torque,
//! the depth of a point being its distance to the outer surface (`R - r` for
//! a circle, `b/2 - max(|x|, |y|)` for a square). Each element's share is
//! spread evenly over the depths its corners span. For an elastic circle
//! (`tau = T r / J`) the band carries `1 - (1 - t/R)^4` of the torque, so
//! `t = (1 - 0.1^(1/4)) R = 0.438 R`; a section whose core has cracked or
//! softened has a thinner band.

use super::explicit::Solver;
use super::material::{BarMaterial, SolidMaterial};
use super::mesh::Mesh;
use super::specimen::Shape;
use crate::report::{Axis, Figure, Panel, Series};
use std::fmt::Write as _;
use std::path::Path;

/// The share of the torque the shear-flow band carries: 90%.
pub const SHEAR_FLOW_SHARE: f64 = 0.9;

/// The elements of the mid-height layer and their geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct Cut {
    /// Global element indices.
    pub elements: Vec<usize>,
    /// Centroids `(x, y)` in the section, m.
    pub centroid: Vec<[f64; 2]>,
    /// Areas in the section, m^2.
    pub area: Vec<f64>,
    /// Smallest and largest depth below the outer surface of each
    /// element's corners, m.
    pub depth: Vec<[f64; 2]>,
    /// Height of the cut (mid-plane of the layer), m.
    pub z: f64,
    /// Shape of the section.
    pub shape: Shape,
    /// Radius or half-width of the section, m.
    pub half: f64,
}

/// The shear stresses of a cut at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Circumferential shear stress `tau_ztheta` of each element, Pa.
    pub tau: Vec<f64>,
}

impl Cut {
    /// The layer of `mesh` nearest to mid-height; `size` is the diameter or
    /// width of the section, m.
    pub fn mid_height(mesh: &Mesh, shape: Shape, size: f64) -> Cut {
        let layer = ((mesh.layers as f64 / 2.0 - 0.5).round().max(0.0) as usize)
            .min(mesh.layers.saturating_sub(1));
        let nq = mesh.section.quads.len();
        let half = size / 2.0;
        let depth = |p: [f64; 2]| depth_below_surface(shape, half, p);
        let mut cut = Cut {
            elements: Vec::with_capacity(nq),
            centroid: Vec::with_capacity(nq),
            area: Vec::with_capacity(nq),
            depth: Vec::with_capacity(nq),
            z: (layer as f64 + 0.5) * mesh.dz,
            shape,
            half,
        };
        for (q, quad) in mesh.section.quads.iter().enumerate() {
            let p: Vec<[f64; 2]> = quad
                .iter()
                .map(|&i| mesh.section.nodes[i as usize])
                .collect();
            // Shoelace area and centroid of the quadrilateral.
            let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
            for k in 0..4 {
                let [x0, y0] = p[k];
                let [x1, y1] = p[(k + 1) % 4];
                let w = x0 * y1 - x1 * y0;
                a += w / 2.0;
                cx += (x0 + x1) * w / 6.0;
                cy += (y0 + y1) * w / 6.0;
            }
            let d: Vec<f64> = p.iter().map(|&c| depth(c).max(0.0)).collect();
            cut.elements.push(layer * nq + q);
            cut.centroid.push([cx / a, cy / a]);
            cut.area.push(a);
            cut.depth.push([
                d.iter().copied().fold(f64::INFINITY, f64::min),
                d.iter().copied().fold(0.0, f64::max),
            ]);
        }
        cut
    }

    /// Depth of element `i`'s centroid below the outer surface, m.
    pub fn centroid_depth(&self, i: usize) -> f64 {
        depth_below_surface(self.shape, self.half, self.centroid[i])
    }

    /// Centroid radius of element `i` of the cut, m.
    pub fn radius(&self, i: usize) -> f64 {
        self.centroid[i][0].hypot(self.centroid[i][1])
    }

    /// The circumferential shear stresses of the solver's current state.
    pub fn profile<M: SolidMaterial, B: BarMaterial>(&self, s: &Solver<M, B>) -> Profile {
        let batches = &s.model.batches;
        let tau = self
            .elements
            .iter()
            .zip(&self.centroid)
            .map(|(&e, &[x, y])| {
                let (b, l) = s.model.layers.lane_of(e);
                let b = &batches[b];
                // Stress components: xx, yy, zz, xy, yz, zx.
                let (tyz, txz) = (b.stress[4].0[l], b.stress[5].0[l]);
                let r = x.hypot(y);
                if r > 0.0 {
                    (x * tyz - y * txz) / r
                } else {
                    0.0
                }
            })
            .collect();
        Profile { tau }
    }

    /// The torque the shear stresses resist, `sum tau r A`, N m.
    pub fn torque(&self, p: &Profile) -> f64 {
        (0..self.elements.len())
            .map(|i| p.tau[i] * self.radius(i) * self.area[i])
            .sum()
    }

    /// The thickness of the outer band carrying `share` of the section's
    /// torque (module docs), m; `None` if the section carries no torque.
    pub fn shear_flow_thickness(&self, p: &Profile, share: f64) -> Option<f64> {
        let parts: Vec<f64> = (0..self.elements.len())
            .map(|i| p.tau[i] * self.radius(i) * self.area[i])
            .collect();
        let total: f64 = parts.iter().sum();
        if !(total.abs() > 0.0) {
            return None;
        }
        // The torque carried above depth t, piecewise linear in t between
        // the depths where an element starts or ends.
        let carried = |t: f64| -> f64 {
            parts
                .iter()
                .zip(&self.depth)
                .map(|(&part, &[lo, hi])| {
                    let f = if hi > lo {
                        ((t - lo) / (hi - lo)).clamp(0.0, 1.0)
                    } else if t >= lo {
                        1.0
                    } else {
                        0.0
                    };
                    part * f
                })
                .sum::<f64>()
                / total
        };
        let mut knots: Vec<f64> = self.depth.iter().flatten().copied().collect();
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        let mut prev = (0.0, 0.0);
        for &t in &knots {
            let c = carried(t);
            if c >= share {
                let (t0, c0) = prev;
                return Some(if c > c0 {
                    t0 + (t - t0) * (share - c0) / (c - c0)
                } else {
                    t
                });
            }
            prev = (t, c);
        }
        knots.last().copied()
    }
}

/// Distance of `p` to the surface of a circle of radius `half` or a square
/// of half-width `half`, m.
fn depth_below_surface(shape: Shape, half: f64, p: [f64; 2]) -> f64 {
    match shape {
        Shape::Circular => half - p[0].hypot(p[1]),
        Shape::Square => half - p[0].abs().max(p[1].abs()),
    }
}

/// The profile of one instant of a run, with what identifies it.
#[derive(Clone, Debug, PartialEq)]
pub struct Stage<'a> {
    /// `cracking`, `peak` or `end`.
    pub name: &'static str,
    /// Time, s.
    pub t: f64,
    /// Twist, rad.
    pub twist: f64,
    /// Torque at the reference point, N m.
    pub torque: f64,
    /// The shear stresses.
    pub profile: &'a Profile,
}

/// What the summary of a run says about one stage.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StageSummary {
    /// `cracking`, `peak` or `end`.
    pub stage: &'static str,
    /// Time, s.
    pub time_s: f64,
    /// Torque at the reference point, kN m.
    pub torque_knm: f64,
    /// Torque the cut's shear stresses resist, `sum tau r A`, kN m.
    pub section_torque_knm: f64,
    /// Largest circumferential shear stress of the cut, MPa.
    pub max_shear_mpa: f64,
    /// Thickness of the band carrying [`SHEAR_FLOW_SHARE`] of the cut's
    /// torque, mm.
    pub shear_flow_thickness_mm: Option<f64>,
}

impl Cut {
    /// The summary of a stage.
    pub fn summarise(&self, st: &Stage) -> StageSummary {
        StageSummary {
            stage: st.name,
            time_s: st.t,
            torque_knm: st.torque / 1e3,
            section_torque_knm: self.torque(st.profile) / 1e3,
            max_shear_mpa: st.profile.tau.iter().fold(0.0f64, |m, t| m.max(t.abs())) / 1e6,
            shear_flow_thickness_mm: self
                .shear_flow_thickness(st.profile, SHEAR_FLOW_SHARE)
                .map(|t| t * 1e3),
        }
    }

    /// Writes the CSV of the stages: one row per element of the cut
    /// (`x_mm, y_mm, r_mm, depth_mm, area_mm2`, then `tau_STAGE_MPa` for each
    /// stage), after `#` lines naming each stage's time, twist, torques and
    /// shear-flow thickness.
    pub fn write_csv(&self, stages: &[Stage], path: &Path) -> std::io::Result<()> {
        let mut w = String::new();
        let _ = writeln!(
            w,
            "# hyst fe: circumferential shear stress tau_ztheta across the section at z = {:.4} m (thesis Figs 2.9, 2.10)",
            self.z
        );
        for st in stages {
            let s = self.summarise(st);
            let _ = writeln!(
                w,
                "# {}: t = {:.6e} s, twist = {:.6e} rad, torque = {:.4} kN m, section torque = {:.4} kN m, shear-flow thickness ({:.0}% of the torque) = {} mm",
                st.name,
                st.t,
                st.twist,
                s.torque_knm,
                s.section_torque_knm,
                100.0 * SHEAR_FLOW_SHARE,
                s.shear_flow_thickness_mm
                    .map_or("none".to_string(), |t| format!("{t:.2}"))
            );
        }
        w.push_str("x_mm,y_mm,r_mm,depth_mm,area_mm2");
        for st in stages {
            let _ = write!(w, ",tau_{}_MPa", st.name);
        }
        w.push('\n');
        for i in 0..self.elements.len() {
            let [x, y] = self.centroid[i];
            let _ = write!(
                w,
                "{:.4},{:.4},{:.4},{:.4},{:.4}",
                x * 1e3,
                y * 1e3,
                self.radius(i) * 1e3,
                self.centroid_depth(i) * 1e3,
                self.area[i] * 1e6
            );
            for st in stages {
                let _ = write!(w, ",{:.6e}", st.profile.tau[i] / 1e6);
            }
            w.push('\n');
        }
        std::fs::write(path, w)
    }

    /// The figure of the stages: shear stress against the distance from
    /// the axis, for every element of a circular cut (Fig. 2.9), along the
    /// face axis (`x`) and the diagonal (`(x + y) / sqrt 2`) of a square one
    /// (Fig. 2.10).
    pub fn figure(&self, title: &str, stages: &[Stage]) -> Result<Figure, crate::report::Error> {
        type Position = fn([f64; 2]) -> f64;
        let lines: Vec<(&str, Vec<usize>, Position)> = match self.shape {
            Shape::Circular => vec![(
                "radial direction (every element)",
                (0..self.elements.len()).collect(),
                |[x, y]| x.hypot(y),
            )],
            Shape::Square => {
                let [edge, diagonal] = square_lines(self);
                vec![
                    ("towards the middle of a face", edge, |[x, _]| x),
                    ("along the diagonal", diagonal, |[x, y]| {
                        (x + y) / std::f64::consts::SQRT_2
                    }),
                ]
            }
        };
        let mut fig = Figure::new(560.0 * lines.len() as f64, 400.0);
        fig.title(title).columns(lines.len());
        for (name, idx, position) in lines {
            let mut panel = Panel::new(
                Axis::linear("distance from the axis", "mm").include_zero(),
                Axis::linear("shear stress", "MPa").include_zero(),
            );
            panel.title(name);
            for (k, st) in stages.iter().enumerate() {
                let x: Vec<f64> = idx
                    .iter()
                    .map(|&i| position(self.centroid[i]) * 1e3)
                    .collect();
                let y: Vec<f64> = idx.iter().map(|&i| st.profile.tau[i] / 1e6).collect();
                let label = format!("{} ({:.1} kN m)", st.name, st.torque / 1e3);
                let series = match self.shape {
                    Shape::Circular => Series::scatter(&label, &x, &y)?.markers(2.5),
                    Shape::Square => Series::line(&label, &x, &y)?.markers(3.0),
                };
                panel.series(series.palette(k));
            }
            fig.panel(panel);
        }
        Ok(fig)
    }
}

/// Elements of a square section's cut along the two lines of thesis Fig.
/// 2.10 in the first quadrant: the row nearest the `+x` half-axis, towards
/// the middle of a face ("towards the edges"), and the elements nearest the
/// `x = y` diagonal, each sorted by distance from the axis. Centroids more
/// than a quarter of the nearest element's distance further from the line
/// than it are left out.
pub fn square_lines(cut: &Cut) -> [Vec<usize>; 2] {
    let pick = |off: &dyn Fn([f64; 2]) -> f64| {
        let mut idx: Vec<usize> = (0..cut.elements.len())
            .filter(|&i| cut.centroid[i][0] > 0.0 && cut.centroid[i][1] >= 0.0)
            .collect();
        let best = idx
            .iter()
            .map(|&i| off(cut.centroid[i]))
            .fold(f64::INFINITY, f64::min);
        idx.retain(|&i| off(cut.centroid[i]) <= best * 1.25 + 1e-12);
        idx.sort_by(|&a, &b| cut.radius(a).total_cmp(&cut.radius(b)));
        idx
    };
    let edge = pick(&|[_, y]: [f64; 2]| y.abs());
    let diagonal = pick(&|[x, y]: [f64; 2]| (x - y).abs() / std::f64::consts::SQRT_2);
    [edge, diagonal]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::Section;

    fn profile_of(cut: &Cut, f: impl Fn(f64) -> f64) -> Profile {
        Profile {
            tau: (0..cut.elements.len()).map(|i| f(cut.radius(i))).collect(),
        }
    }

    #[test]
    fn the_cut_is_the_middle_layer_and_tiles_the_section() {
        let mesh = Mesh::extrude(Section::circle(0.15, 0.03), 0.4, 0.05);
        let cut = Cut::mid_height(&mesh, Shape::Circular, 0.3);
        assert_eq!(mesh.layers, 8);
        assert!((cut.z - 0.225).abs() < 1e-12, "{}", cut.z);
        assert_eq!(cut.elements[0], 4 * mesh.section.quads.len());
        let a: f64 = cut.area.iter().sum();
        assert!((a - mesh.section.area()).abs() < 1e-12 * a);
        assert!(cut
            .depth
            .iter()
            .all(|d| d[0] >= 0.0 && d[1] <= 0.15 + 1e-12));
    }

    #[test]
    fn an_elastic_circle_has_the_closed_form_band() {
        // tau = c r: the band carrying 90% is (1 - 0.1^(1/4)) R = 0.4377 R
        // on the exact circle. The O-grid's elements spread their share
        // evenly over their depth range, which moves the band's edge by
        // less than half an element's depth (R / 20 here).
        let r = 0.3;
        let mesh = Mesh::extrude(Section::circle(r, r / 10.0), 0.1, 0.05);
        let cut = Cut::mid_height(&mesh, Shape::Circular, 2.0 * r);
        let t = cut
            .shear_flow_thickness(&profile_of(&cut, |x| 1e6 * x), SHEAR_FLOW_SHARE)
            .expect("torque");
        let exact = (1.0 - 0.1f64.powf(0.25)) * r;
        assert!((t - exact).abs() < 0.05 * r, "{t} vs {exact}");
        // Uniform stress on a square (the fully plastic limit): the band of
        // depth t carries 1 - (1 - 2t/b)^3 of the torque (T ~ a^3 for a
        // square of half-width a), so 90% at t = (1 - 0.1^(1/3)) b/2.
        let b = 0.4;
        let mesh = Mesh::extrude(Section::square(b, b / 16.0), 0.1, 0.05);
        let cut = Cut::mid_height(&mesh, Shape::Square, b);
        let t = cut
            .shear_flow_thickness(&profile_of(&cut, |_| 1e6), SHEAR_FLOW_SHARE)
            .expect("torque");
        let exact = (1.0 - 0.1f64.powf(1.0 / 3.0)) * b / 2.0;
        assert!((t - exact).abs() < 0.5 * b / 16.0, "{t} vs {exact}");
        assert!(cut
            .shear_flow_thickness(&profile_of(&cut, |_| 0.0), 0.9)
            .is_none());
    }

    #[test]
    fn square_lines_run_along_the_face_axis_and_the_diagonal() {
        let b = 0.4;
        let mesh = Mesh::extrude(Section::square(b, b / 8.0), 0.1, 0.05);
        let cut = Cut::mid_height(&mesh, Shape::Square, b);
        let [edge, diagonal] = square_lines(&cut);
        assert_eq!(edge.len(), 4);
        assert!(edge
            .iter()
            .all(|&i| (cut.centroid[i][1] - b / 16.0).abs() < 1e-12));
        assert_eq!(diagonal.len(), 4);
        for &i in &diagonal {
            let [x, y] = cut.centroid[i];
            assert!((x - y).abs() < 1e-12);
        }
    }
}
