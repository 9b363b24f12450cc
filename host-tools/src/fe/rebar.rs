//! Reinforcing bars as 2-node trusses embedded in the concrete hexahedra
//! (thesis 2.4: perfect bond). Each truss end is an embedded point: its
//! position and velocity follow the host hexahedron's shape functions, and
//! the truss force it carries goes back to the host's nodes with the same
//! weights.

use super::hex8::shape;
use super::mesh::Mesh;

/// A bar's centre line: points joined by straight segments, closed for
/// hoops.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// Points, m.
    pub points: Vec<[f64; 3]>,
    /// Whether the last point joins the first.
    pub closed: bool,
}

/// Bars of one kind (for example the longitudinal bars), with one area and
/// one material.
#[derive(Clone, Debug, PartialEq)]
pub struct BarSet {
    /// Name used in output (`longitudinal`, `transverse`).
    pub name: String,
    /// Bar cross-section area, m^2.
    pub area: f64,
    /// The bars.
    pub bars: Vec<Polyline>,
}

impl BarSet {
    /// Total length of the bars, m.
    pub fn length(&self) -> f64 {
        self.bars
            .iter()
            .map(|b| b.segments().map(|(p, q)| dist(p, q)).sum::<f64>())
            .sum()
    }
}

impl Polyline {
    /// The segments as pairs of points.
    pub fn segments(&self) -> impl Iterator<Item = ([f64; 3], [f64; 3])> + '_ {
        let n = self.points.len();
        let count = if self.closed { n } else { n.saturating_sub(1) };
        (0..count).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }
}

fn dist(p: [f64; 3], q: [f64; 3]) -> f64 {
    ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2)).sqrt()
}

/// A straight vertical bar at `(x, y)` from `z0` to `z1`, in segments of at
/// most `seg`.
pub fn vertical(x: f64, y: f64, z0: f64, z1: f64, seg: f64) -> Polyline {
    let n = (((z1 - z0) / seg).ceil() as usize).max(1);
    Polyline {
        points: (0..=n)
            .map(|i| [x, y, z0 + (z1 - z0) * i as f64 / n as f64])
            .collect(),
        closed: false,
    }
}

/// A helix (spiral) of `radius` and `pitch` from `z0` up to `z1`, in
/// chords of at most `seg`.
pub fn helix(radius: f64, pitch: f64, z0: f64, z1: f64, seg: f64) -> Polyline {
    let turns = (z1 - z0) / pitch;
    let per_turn = (2.0 * std::f64::consts::PI * radius).hypot(pitch);
    let n = ((turns * per_turn / seg).ceil() as usize).max(1);
    Polyline {
        points: (0..=n)
            .map(|i| {
                let s = i as f64 / n as f64;
                let th = 2.0 * std::f64::consts::PI * turns * s;
                [radius * th.cos(), radius * th.sin(), z0 + (z1 - z0) * s]
            })
            .collect(),
        closed: false,
    }
}

/// A closed circular hoop of `radius` at height `z`, in chords of at most
/// `seg`.
pub fn circular_hoop(radius: f64, z: f64, seg: f64) -> Polyline {
    let n = ((2.0 * std::f64::consts::PI * radius / seg).ceil() as usize).max(3);
    Polyline {
        points: (0..n)
            .map(|i| {
                let th = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                [radius * th.cos(), radius * th.sin(), z]
            })
            .collect(),
        closed: true,
    }
}

/// A closed square hoop of centre-line half-width `half` at height `z`, in
/// segments of at most `seg`.
pub fn square_hoop(half: f64, z: f64, seg: f64) -> Polyline {
    let n = ((2.0 * half / seg).ceil() as usize).max(1);
    let corners = [[-half, -half], [half, -half], [half, half], [-half, half]];
    let mut points = Vec::with_capacity(4 * n);
    for c in 0..4 {
        let p = corners[c];
        let q = corners[(c + 1) % 4];
        for i in 0..n {
            let s = i as f64 / n as f64;
            points.push([p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), z]);
        }
    }
    Polyline {
        points,
        closed: true,
    }
}

/// A point tied to a host hexahedron.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmbeddedPoint {
    /// The host's nodes.
    pub hosts: [u32; 8],
    /// Shape-function weights at the point (sum to 1).
    pub weights: [f64; 8],
}

impl EmbeddedPoint {
    /// The nodal field `f` (positions, velocities, displacements)
    /// interpolated to the point with the host's shape functions.
    #[inline(always)]
    pub fn interpolate(&self, f: &[[f64; 3]]) -> [f64; 3] {
        let mut y = [0.0; 3];
        for k in 0..8 {
            let n = self.hosts[k] as usize;
            let w = self.weights[k];
            for i in 0..3 {
                y[i] += w * f[n][i];
            }
        }
        y
    }
}

/// A truss between two embedded points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Truss {
    /// Indices of the end points.
    pub ends: [u32; 2],
    /// Cross-section area, m^2.
    pub area: f64,
    /// Initial length, m.
    pub length: f64,
    /// Index of the bar set (and its material).
    pub set: u16,
}

/// The embedded bars of a model.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Embedding {
    /// Embedded points.
    pub points: Vec<EmbeddedPoint>,
    /// Initial positions of the points, m.
    pub positions: Vec<[f64; 3]>,
    /// Trusses.
    pub trusses: Vec<Truss>,
}

/// Why a bar could not be embedded.
#[derive(Clone, Debug, PartialEq)]
pub struct OutsideConcrete {
    /// The bar set.
    pub set: String,
    /// The point outside the concrete, m.
    pub point: [f64; 3],
}

impl std::fmt::Display for OutsideConcrete {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "a {} bar point at ({:.4}, {:.4}, {:.4}) m lies outside the concrete",
            self.set, self.point[0], self.point[1], self.point[2]
        )
    }
}

impl std::error::Error for OutsideConcrete {}

/// Embeds the bar sets in the mesh: every polyline point becomes an
/// embedded point, every segment a truss.
pub fn embed(mesh: &Mesh, sets: &[BarSet]) -> Result<Embedding, OutsideConcrete> {
    let mut emb = Embedding::default();
    for (si, set) in sets.iter().enumerate() {
        for bar in &set.bars {
            let first = emb.points.len() as u32;
            for &p in &bar.points {
                let (e, r) = mesh.locate(p).ok_or_else(|| OutsideConcrete {
                    set: set.name.clone(),
                    point: p,
                })?;
                emb.points.push(EmbeddedPoint {
                    hosts: mesh.hexes[e],
                    weights: shape(r),
                });
                emb.positions.push(p);
            }
            let n = bar.points.len() as u32;
            for (i, (p, q)) in bar.segments().enumerate() {
                let i = i as u32;
                emb.trusses.push(Truss {
                    ends: [first + i, first + (i + 1) % n],
                    area: set.area,
                    length: dist(p, q),
                    set: si as u16,
                });
            }
        }
    }
    Ok(emb)
}

#[cfg(test)]
mod tests {
    use super::super::mesh::Section;
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn helix_length_and_pitch() {
        let h = helix(0.27, 0.07, 0.0, 0.7, 0.025);
        let set = BarSet {
            name: "t".into(),
            area: 1.0,
            bars: vec![h.clone()],
        };
        let exact = 10.0 * (2.0 * PI * 0.27f64).hypot(0.07);
        // Chords are shorter than the arc by (theta^2/24) of their length.
        assert!((set.length() - exact).abs() < 2e-3 * exact);
        assert!(h.segments().all(|(p, q)| dist(p, q) <= 0.025));
        assert_eq!(h.points.last().map(|p| p[2]), Some(0.7));
    }

    #[test]
    fn hoops_are_closed() {
        let c = circular_hoop(0.2, 0.1, 0.02);
        assert_eq!(c.segments().count(), c.points.len());
        let s = square_hoop(0.17, 0.1, 0.025);
        let l: f64 = s.segments().map(|(p, q)| dist(p, q)).sum();
        assert!((l - 8.0 * 0.17).abs() < 1e-12);
    }

    #[test]
    fn embedded_points_reproduce_their_positions() {
        let mesh = Mesh::extrude(Section::circle(0.3, 0.05), 0.5, 0.05);
        let sets = vec![
            BarSet {
                name: "longitudinal".into(),
                area: 3e-4,
                bars: vec![vertical(0.2, 0.1, 0.0, 0.5, 0.05)],
            },
            BarSet {
                name: "transverse".into(),
                area: 1e-4,
                bars: vec![helix(0.25, 0.1, 0.0, 0.5, 0.05)],
            },
        ];
        let emb = embed(&mesh, &sets).expect("inside");
        for (pt, x) in emb.points.iter().zip(&emb.positions) {
            let y = pt.interpolate(&mesh.nodes);
            assert!((0..3).all(|i| (y[i] - x[i]).abs() < 1e-12));
            assert!((pt.weights.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        }
        let outside = vec![BarSet {
            name: "longitudinal".into(),
            area: 3e-4,
            bars: vec![vertical(0.31, 0.0, 0.0, 0.5, 0.05)],
        }];
        assert!(embed(&mesh, &outside).is_err());
    }
}
