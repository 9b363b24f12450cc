//! Meshes of 8-node hexahedra for prismatic columns: a quadrilateral mesh
//! of the cross-section (a regular grid for squares, an O-grid for
//! circles) extruded along the column axis `z`, with the base at `z = 0`
//! and the top at `z = height`.

use super::hex8::XI;

/// A quadrilateral mesh of a cross-section, corners counter-clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// Node coordinates `(x, y)`, m.
    pub nodes: Vec<[f64; 2]>,
    /// Quadrilaterals, counter-clockwise.
    pub quads: Vec<[u32; 4]>,
}

impl Section {
    /// A `width` x `width` square centred on the axis with about `h`-sized
    /// square cells.
    pub fn square(width: f64, h: f64) -> Section {
        let n = ((width / h).round() as usize).max(1);
        let mut nodes = Vec::with_capacity((n + 1) * (n + 1));
        for j in 0..=n {
            for i in 0..=n {
                let s = width * (i as f64 / n as f64 - 0.5);
                let t = width * (j as f64 / n as f64 - 0.5);
                nodes.push([s, t]);
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut quads = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Section { nodes, quads }
    }

    /// A circle of `radius` meshed as an O-grid with about `h`-sized
    /// cells: a central block with bulged edges surrounded by a ring of
    /// `4n` cells around and radially graded rows. The block size and
    /// bulge are chosen, from a small fixed set, to minimise the worst
    /// aspect ratio of the hexahedra (with height `h`) among those whose
    /// corner angles stay within 50-130 degrees.
    pub fn circle(radius: f64, h: f64) -> Section {
        let n = ((std::f64::consts::PI * radius / (2.0 * h)).round() as usize).max(2);
        let mut best: Option<(f64, Section)> = None;
        for ai in 0..9 {
            let a_frac = 0.45 + 0.025 * ai as f64;
            for bi in 0..7 {
                let bulge = 0.2 + 0.1 * bi as f64;
                let s = Self::o_grid(radius, n, a_frac, bulge);
                let qual = s.quality(h);
                let q = qual.max_aspect;
                let angles_ok =
                    qual.min_corner_angle_deg >= 50.0 && qual.max_corner_angle_deg <= 130.0;
                if angles_ok && s.quads_positive() && best.as_ref().is_none_or(|(bq, _)| q < *bq) {
                    best = Some((q, s));
                }
            }
        }
        match best {
            Some((_, s)) => s,
            None => Self::o_grid(radius, n, 0.5, 0.5),
        }
    }

    fn o_grid(radius: f64, n: usize, a_frac: f64, bulge: f64) -> Section {
        use std::f64::consts::{FRAC_PI_4, PI, SQRT_2};
        let a = a_frac * radius;
        let mut nodes = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let s = -1.0 + 2.0 * i as f64 / n as f64;
                let t = -1.0 + 2.0 * j as f64 / n as f64;
                let fx = SQRT_2 * s * (1.0 - t * t / 2.0).sqrt();
                let fy = SQRT_2 * t * (1.0 - s * s / 2.0).sqrt();
                nodes.push([
                    a * ((1.0 - bulge) * s + bulge * fx),
                    a * ((1.0 - bulge) * t + bulge * fy),
                ]);
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut quads = Vec::new();
        for j in 0..n {
            for i in 0..n {
                quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        // The block boundary, counter-clockwise from the (-1, -1) corner.
        let mut ring: Vec<u32> = Vec::with_capacity(4 * n);
        ring.extend((0..n).map(|i| id(i, 0)));
        ring.extend((0..n).map(|j| id(n, j)));
        ring.extend((0..n).map(|i| id(n - i, n)));
        ring.extend((0..n).map(|j| id(0, n - j)));
        let m4 = 4 * n;
        // Outer points at uniform angles, corners of the block at the
        // diagonals.
        let outer: Vec<[f64; 2]> = (0..m4)
            .map(|k| {
                let th = -3.0 * FRAC_PI_4 + 2.0 * PI * k as f64 / m4 as f64;
                [radius * th.cos(), radius * th.sin()]
            })
            .collect();
        let spans: Vec<f64> = (0..m4)
            .map(|k| {
                let p = nodes[ring[k] as usize];
                (outer[k][0] - p[0]).hypot(outer[k][1] - p[1])
            })
            .collect();
        let mean = spans.iter().sum::<f64>() / m4 as f64;
        // Rows grow linearly from the block spacing towards the outer
        // spacing; each ray keeps the first row at the block spacing and
        // takes up its own length in the growth.
        let h_in = 2.0 * a / n as f64;
        let h_out = 2.0 * PI * radius / m4 as f64;
        let rows = ((2.0 * mean / (h_in + h_out)).round() as usize).max(1);
        let mut prev = ring.clone();
        let mut frac = vec![0.0; m4];
        for r in 0..rows {
            let mut cur = Vec::with_capacity(m4);
            for (k, &p) in ring.iter().enumerate() {
                let t = spans[k];
                let d0 = h_in.min(t / rows as f64);
                let d1 = 2.0 * t / rows as f64 - d0;
                let d = d0 + (d1 - d0) * (r as f64 + 0.5) / rows as f64;
                frac[k] += d / t;
                let f = if r + 1 == rows { 1.0 } else { frac[k] };
                let pi = nodes[p as usize];
                cur.push(nodes.len() as u32);
                nodes.push([
                    pi[0] + f * (outer[k][0] - pi[0]),
                    pi[1] + f * (outer[k][1] - pi[1]),
                ]);
            }
            for k in 0..m4 {
                let k1 = (k + 1) % m4;
                quads.push([prev[k], cur[k], cur[k1], prev[k1]]);
            }
            prev = cur;
        }
        Section { nodes, quads }
    }

    fn quads_positive(&self) -> bool {
        self.quads.iter().all(|q| {
            (0..4).all(|c| {
                let p0 = self.nodes[q[c] as usize];
                let p1 = self.nodes[q[(c + 1) % 4] as usize];
                let p3 = self.nodes[q[(c + 3) % 4] as usize];
                let cr = (p1[0] - p0[0]) * (p3[1] - p0[1]) - (p1[1] - p0[1]) * (p3[0] - p0[0]);
                cr > 0.0
            })
        })
    }

    /// Area of the section (sum of the quadrilaterals), m^2.
    pub fn area(&self) -> f64 {
        self.quads
            .iter()
            .map(|q| {
                let p: Vec<[f64; 2]> = q.iter().map(|&i| self.nodes[i as usize]).collect();
                0.5 * ((p[2][0] - p[0][0]) * (p[3][1] - p[1][1])
                    - (p[2][1] - p[0][1]) * (p[3][0] - p[1][0]))
            })
            .sum()
    }

    /// Edge lengths and aspect ratios of the hexahedra this section makes
    /// when extruded with layer height `dz`.
    pub fn quality(&self, dz: f64) -> Quality {
        let mut q = Quality {
            min_edge: dz,
            max_edge: dz,
            max_aspect: 1.0,
            min_corner_angle_deg: 180.0,
            max_corner_angle_deg: 0.0,
        };
        for quad in &self.quads {
            let mut lo = dz;
            let mut hi = dz;
            for c in 0..4 {
                let p0 = self.nodes[quad[c] as usize];
                let p1 = self.nodes[quad[(c + 1) % 4] as usize];
                let p3 = self.nodes[quad[(c + 3) % 4] as usize];
                let e = [(p1[0] - p0[0]), (p1[1] - p0[1])];
                let f = [(p3[0] - p0[0]), (p3[1] - p0[1])];
                let le = e[0].hypot(e[1]);
                let lf = f[0].hypot(f[1]);
                lo = lo.min(le);
                hi = hi.max(le);
                let ang = ((e[0] * f[0] + e[1] * f[1]) / (le * lf))
                    .clamp(-1.0, 1.0)
                    .acos();
                q.min_corner_angle_deg = q.min_corner_angle_deg.min(ang.to_degrees());
                q.max_corner_angle_deg = q.max_corner_angle_deg.max(ang.to_degrees());
            }
            q.min_edge = q.min_edge.min(lo);
            q.max_edge = q.max_edge.max(hi);
            q.max_aspect = q.max_aspect.max(hi / lo);
        }
        q
    }

    /// The quadrilateral containing `p` and the natural coordinates of `p`
    /// in it, or `None` outside the section.
    pub fn locate(&self, p: [f64; 2]) -> Option<(usize, [f64; 2])> {
        const TOL: f64 = 1e-9;
        for (k, q) in self.quads.iter().enumerate() {
            let c: Vec<[f64; 2]> = q.iter().map(|&i| self.nodes[i as usize]).collect();
            let (lo_x, hi_x) = c
                .iter()
                .fold((f64::MAX, f64::MIN), |a, v| (a.0.min(v[0]), a.1.max(v[0])));
            let (lo_y, hi_y) = c
                .iter()
                .fold((f64::MAX, f64::MIN), |a, v| (a.0.min(v[1]), a.1.max(v[1])));
            let pad = 1e-9 * (hi_x - lo_x + hi_y - lo_y);
            if p[0] < lo_x - pad || p[0] > hi_x + pad || p[1] < lo_y - pad || p[1] > hi_y + pad {
                continue;
            }
            let r = inverse_bilinear(&c, p);
            if let Some(r) = r {
                if r[0].abs() <= 1.0 + TOL && r[1].abs() <= 1.0 + TOL {
                    return Some((k, [r[0].clamp(-1.0, 1.0), r[1].clamp(-1.0, 1.0)]));
                }
            }
        }
        None
    }
}

/// Natural coordinates of `p` in the quadrilateral `c` by Newton's method.
fn inverse_bilinear(c: &[[f64; 2]], p: [f64; 2]) -> Option<[f64; 2]> {
    let mut r = [0.0f64; 2];
    for _ in 0..30 {
        let mut x = [0.0; 2];
        let mut j = [[0.0; 2]; 2];
        for a in 0..4 {
            let (sa, ta) = (XI[a][0], XI[a][1]);
            let n = 0.25 * (1.0 + sa * r[0]) * (1.0 + ta * r[1]);
            let dn = [0.25 * sa * (1.0 + ta * r[1]), 0.25 * ta * (1.0 + sa * r[0])];
            for i in 0..2 {
                x[i] += n * c[a][i];
                j[i][0] += dn[0] * c[a][i];
                j[i][1] += dn[1] * c[a][i];
            }
        }
        let res = [p[0] - x[0], p[1] - x[1]];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.abs() < 1e-300 {
            return None;
        }
        let d = [
            (j[1][1] * res[0] - j[0][1] * res[1]) / det,
            (j[0][0] * res[1] - j[1][0] * res[0]) / det,
        ];
        r[0] += d[0];
        r[1] += d[1];
        if d[0].abs() + d[1].abs() < 1e-13 {
            return Some(r);
        }
        if r[0].abs() > 10.0 || r[1].abs() > 10.0 {
            return None;
        }
    }
    None
}

/// Edge lengths, aspect ratios and corner angles of a mesh.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Quality {
    /// Shortest edge, m.
    pub min_edge: f64,
    /// Longest edge, m.
    pub max_edge: f64,
    /// Worst ratio of longest to shortest edge of one element.
    pub max_aspect: f64,
    /// Smallest corner angle of the section quadrilaterals, degrees.
    pub min_corner_angle_deg: f64,
    /// Largest corner angle of the section quadrilaterals, degrees.
    pub max_corner_angle_deg: f64,
}

/// A hexahedral mesh of a prismatic column.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// The cross-section it was extruded from.
    pub section: Section,
    /// Node coordinates, m; node `k * section.nodes.len() + p` is section
    /// node `p` at level `k`.
    pub nodes: Vec<[f64; 3]>,
    /// Hexahedra (node order of [`super::hex8`]); element
    /// `k * section.quads.len() + q` is quad `q` in layer `k`.
    pub hexes: Vec<[u32; 8]>,
    /// Number of layers.
    pub layers: usize,
    /// Layer height, m.
    pub dz: f64,
}

impl Mesh {
    /// Extrudes `section` to `height` in layers of about `h`.
    pub fn extrude(section: Section, height: f64, h: f64) -> Mesh {
        let layers = ((height / h).round() as usize).max(1);
        let dz = height / layers as f64;
        let np = section.nodes.len();
        let mut nodes = Vec::with_capacity(np * (layers + 1));
        for k in 0..=layers {
            let z = if k == layers { height } else { k as f64 * dz };
            nodes.extend(section.nodes.iter().map(|p| [p[0], p[1], z]));
        }
        let mut hexes = Vec::with_capacity(section.quads.len() * layers);
        for k in 0..layers {
            let lo = (k * np) as u32;
            let hi = ((k + 1) * np) as u32;
            for q in &section.quads {
                hexes.push([
                    q[0] + lo,
                    q[1] + lo,
                    q[2] + lo,
                    q[3] + lo,
                    q[0] + hi,
                    q[1] + hi,
                    q[2] + hi,
                    q[3] + hi,
                ]);
            }
        }
        Mesh {
            section,
            nodes,
            hexes,
            layers,
            dz,
        }
    }

    /// Column height, m.
    pub fn height(&self) -> f64 {
        self.dz * self.layers as f64
    }

    /// Nodes at `z = 0`.
    pub fn base_nodes(&self) -> std::ops::Range<usize> {
        0..self.section.nodes.len()
    }

    /// Nodes at `z = height`.
    pub fn top_nodes(&self) -> std::ops::Range<usize> {
        let np = self.section.nodes.len();
        self.layers * np..(self.layers + 1) * np
    }

    /// The element containing `p` and the natural coordinates of `p` in
    /// it, or `None` outside the column.
    pub fn locate(&self, p: [f64; 3]) -> Option<(usize, [f64; 3])> {
        let h = self.height();
        if !(p[2] >= -1e-12 * h && p[2] <= h * (1.0 + 1e-12)) {
            return None;
        }
        let k = ((p[2] / self.dz).floor() as usize).min(self.layers - 1);
        let zeta = (2.0 * (p[2] - k as f64 * self.dz) / self.dz - 1.0).clamp(-1.0, 1.0);
        let (q, r) = self.section.locate([p[0], p[1]])?;
        Some((k * self.section.quads.len() + q, [r[0], r[1], zeta]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn square_section_is_a_regular_grid() {
        let s = Section::square(0.4, 0.025);
        assert_eq!(s.quads.len(), 256);
        assert!((s.area() - 0.16).abs() < 1e-15);
        let q = s.quality(0.025);
        assert!((q.max_aspect - 1.0).abs() < 1e-12);
    }

    #[test]
    fn o_grid_covers_the_circle_with_near_unit_aspect() {
        for (r, h) in [
            (0.305, 0.025),
            (0.15, 0.025),
            (0.305, 0.0125),
            (0.305, 0.05),
        ] {
            let s = Section::circle(r, h);
            // The inscribed polygon with 4n sides loses (2 pi / 4n)^2 / 6 of
            // the area, to leading order.
            let n4 = s
                .nodes
                .iter()
                .filter(|p| (p[0].hypot(p[1]) - r).abs() < 1e-12)
                .count() as f64;
            let poly = 0.5 * n4 * r * r * (2.0 * PI / n4).sin();
            assert!(
                (s.area() - poly).abs() < 1e-12 * poly,
                "{} {}",
                s.area(),
                poly
            );
            let q = s.quality(h);
            assert!(q.max_aspect < 1.7, "r {r} h {h}: {q:?}");
            assert!(
                q.min_edge > 0.6 * h && q.max_edge < 1.45 * h,
                "r {r} h {h}: {q:?}"
            );
            assert!(
                q.min_corner_angle_deg >= 50.0 && q.max_corner_angle_deg <= 130.0,
                "{q:?}"
            );
        }
    }

    #[test]
    fn points_are_located_with_their_natural_coordinates() {
        let m = Mesh::extrude(Section::circle(0.3, 0.05), 0.6, 0.05);
        for p in [
            [0.0, 0.0, 0.3],
            [0.21, -0.1, 0.01],
            [-0.25, 0.12, 0.6],
            [0.0, 0.298, 0.0],
        ] {
            let (e, r) = m.locate(p).expect("inside");
            let n = super::super::hex8::shape(r);
            let mut x = [0.0; 3];
            for a in 0..8 {
                for i in 0..3 {
                    x[i] += n[a] * m.nodes[m.hexes[e][a] as usize][i];
                }
            }
            for i in 0..3 {
                assert!((x[i] - p[i]).abs() < 1e-12, "{p:?} -> {x:?}");
            }
        }
        assert!(m.locate([0.31, 0.0, 0.3]).is_none());
        assert!(m.locate([0.0, 0.0, 0.61]).is_none());
    }
}
