//! Central-difference explicit dynamics with lumped mass (thesis 2.3):
//!
//! ```text
//! v(n+1/2) = v(n-1/2) + dt M^-1 (f_ext(n) - f_int(n))
//! x(n+1)   = x(n) + dt v(n+1/2)
//! ```
//!
//! The base nodes are fixed; the top nodes move with a rigid body tied to a
//! reference point at the centre of the top face (thesis 2.5), whose six
//! degrees of freedom (three translations, three rotations about global
//! axes) are each either driven by a displacement history or loaded by a
//! force history. The rigid body's mass and inertia are those of its
//! nodes; its rotations are composed exactly (Rodrigues), so the top stays
//! rigid at any twist.
//!
//! Determinism: the hexahedra add their nodal forces layer by layer, in a
//! fixed order ([`super::layers`]), with energies per layer; every node then
//! adds its share of the truss forces in a fixed order. The result does not
//! depend on the number of threads.

use super::hex8::{self, HexEnergy};
use super::history::History;
use super::material::{BarMaterial, SolidMaterial};
use super::model::Model;
use rayon::prelude::*;

/// Nodes per parallel work item.
const NODE_CHUNK: usize = 512;
/// Trusses per parallel work item.
const TRUSS_CHUNK: usize = 256;

/// How one degree of freedom of the top reference point is controlled.
#[derive(Clone, Debug, PartialEq)]
pub enum Control {
    /// A force (N) or moment (N m) history.
    Force(History),
    /// A displacement (m) or rotation (rad) history.
    Motion(History),
}

impl Control {
    /// No load and no restraint.
    pub fn free() -> Control {
        Control::Force(History::constant(0.0))
    }
}

/// Indices of the reference point's degrees of freedom.
pub mod dof {
    /// Translation along x.
    pub const UX: usize = 0;
    /// Translation along y.
    pub const UY: usize = 1;
    /// Translation along the column axis.
    pub const UZ: usize = 2;
    /// Rotation about x.
    pub const RX: usize = 3;
    /// Rotation about y.
    pub const RY: usize = 4;
    /// Rotation about the column axis (twist).
    pub const RZ: usize = 5;
}

/// Energies of the whole model, J (ABAQUS names in brackets).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Energies {
    /// Recoverable and plastic strain energy of concrete and bars (ALLSE +
    /// ALLPD).
    pub strain: f64,
    /// Hourglass energy (ALLAE).
    pub hourglass: f64,
    /// Dissipated by bulk viscosity and by the damping of a preload
    /// ([`Damping`]) (ALLVD).
    pub viscous: f64,
    /// Kinetic energy (ALLKE).
    pub kinetic: f64,
    /// Work of the loads and reactions at the reference point (ALLWK).
    pub work: f64,
}

impl Energies {
    /// Internal energy, strain plus hourglass (ALLIE).
    pub fn internal(&self) -> f64 {
        self.strain + self.hourglass
    }

    /// Energy not accounted for: `work - internal - viscous - kinetic`.
    pub fn imbalance(&self) -> f64 {
        self.work - self.internal() - self.viscous - self.kinetic
    }
}

/// Mass-proportional damping `-alpha m v` on every free node and on the
/// rigid top's force-driven degrees of freedom while `t < until`: the
/// dynamic relaxation of a preload (LS-DYNA's dynamic-relaxation phase),
/// which brings a column to its static state under the axial force in a few
/// periods of its first axial mode when `alpha` is near that mode's critical
/// value `2 omega_1`. Its dissipation is counted in
/// [`Energies::viscous`] (ABAQUS's ALLVD holds damping too).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Damping {
    /// Damping per unit mass, 1/s.
    pub alpha: f64,
    /// End of the damped phase, s.
    pub until: f64,
}

/// A [`Damping`] over one step of length `dt`, `a = alpha dt / 2`, as the
/// velocity update `m (new - old) / dt = F - alpha m (old + new) / 2` of the
/// free nodes and of the rigid top's force-driven degrees of freedom. With
/// `a = 0` the update is the undamped one to the last bit.
#[derive(Clone, Copy, Debug)]
struct StepDamping {
    a: f64,
    keep: f64,
    scale: f64,
}

impl StepDamping {
    fn new(a: f64) -> Self {
        StepDamping {
            a,
            keep: 1.0 - a,
            scale: 1.0 / (1.0 + a),
        }
    }

    /// The velocity after the step from `old`, with `dv = dt F / m`.
    fn velocity(&self, old: f64, dv: f64) -> f64 {
        (old * self.keep + dv) * self.scale
    }

    /// The energy a mass `m` whose mean velocity over the step has the
    /// square `mean_sq` dissipates in it: `alpha m mean_sq dt`.
    fn dissipated(&self, m: f64, mean_sq: f64) -> f64 {
        2.0 * self.a * m * mean_sq
    }
}

/// The rigid top and its reference point.
#[derive(Clone, Debug)]
pub struct RigidTop {
    nodes: Vec<u32>,
    arms: Vec<[f64; 3]>,
    centre0: [f64; 3],
    centre: [f64; 3],
    rot: [[f64; 3]; 3],
    vel: [f64; 6],
    disp: [f64; 6],
    mass: f64,
    controls: [Control; 6],
    prev_load: [f64; 6],
    /// Load or reaction at the reference point, N and N m, at the last
    /// step.
    pub reaction: [f64; 6],
    /// Resultant of the column's internal forces on the top nodes about the
    /// reference point (what the column resists with), N and N m.
    pub column: [f64; 6],
}

impl RigidTop {
    /// Displacements and rotations of the reference point (m, rad).
    pub fn displacement(&self) -> [f64; 6] {
        self.disp
    }
}

/// The explicit solver.
pub struct Solver<M: SolidMaterial, B: BarMaterial> {
    /// The model being advanced.
    pub model: Model<M, B>,
    /// Current node positions, m.
    pub x: Vec<[f64; 3]>,
    /// Node velocities at the last half step, m/s.
    pub v: Vec<[f64; 3]>,
    /// Internal nodal forces at the last step, N.
    pub f_int: Vec<[f64; 3]>,
    inv_mass: Vec<f64>,
    hex_e: Vec<HexEnergy>,
    truss_f: Vec<[f64; 3]>,
    truss_e: Vec<f64>,
    px: Vec<[f64; 3]>,
    pv: Vec<[f64; 3]>,
    /// Kinetic energy and damping dissipation of each chunk of nodes.
    node_energy: Vec<[f64; 2]>,
    /// The rigid top.
    pub top: RigidTop,
    base: std::ops::Range<usize>,
    /// Time, s.
    pub t: f64,
    /// Steps taken.
    pub steps: u64,
    /// Energies at the last step.
    pub energy: Energies,
    /// Mass-proportional damping of a preload, if any.
    pub damping: Option<Damping>,
    pool: rayon::ThreadPool,
}

impl<M: SolidMaterial, B: BarMaterial> Solver<M, B> {
    /// A solver at rest at `t = 0`, running on `threads` threads; an error
    /// if the system cannot start them (never fewer threads than asked).
    pub fn new(
        model: Model<M, B>,
        controls: [Control; 6],
        threads: usize,
    ) -> Result<Self, rayon::ThreadPoolBuildError> {
        let n = model.mesh.nodes.len();
        let x = model.mesh.nodes.clone();
        let mut inv_mass: Vec<f64> = model.mass.iter().map(|m| 1.0 / m).collect();
        let base = model.mesh.base_nodes();
        for i in base.clone() {
            inv_mass[i] = 0.0;
        }
        let top_nodes: Vec<u32> = model.mesh.top_nodes().map(|i| i as u32).collect();
        for &i in &top_nodes {
            inv_mass[i as usize] = 0.0;
        }
        let centre = [0.0, 0.0, model.mesh.height()];
        let arms = top_nodes
            .iter()
            .map(|&i| sub(x[i as usize], centre))
            .collect();
        let mass = top_nodes.iter().map(|&i| model.mass[i as usize]).sum();
        let nt = model.embedding.trusses.len();
        let np = model.embedding.points.len();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .build()?;
        Ok(Solver {
            hex_e: vec![HexEnergy::default(); model.layers.count],
            truss_f: vec![[0.0; 3]; 2 * nt],
            truss_e: vec![0.0; nt.div_ceil(TRUSS_CHUNK)],
            px: model.embedding.positions.clone(),
            pv: vec![[0.0; 3]; np],
            node_energy: vec![[0.0; 2]; n.div_ceil(NODE_CHUNK)],
            v: vec![[0.0; 3]; n],
            f_int: vec![[0.0; 3]; n],
            x,
            inv_mass,
            top: RigidTop {
                nodes: top_nodes,
                arms,
                centre0: centre,
                centre,
                rot: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                vel: [0.0; 6],
                disp: [0.0; 6],
                mass,
                controls,
                prev_load: [0.0; 6],
                reaction: [0.0; 6],
                column: [0.0; 6],
            },
            base,
            model,
            t: 0.0,
            steps: 0,
            energy: Energies::default(),
            damping: None,
            pool,
        })
    }

    /// Advances one time step.
    pub fn step(&mut self) {
        let dt = self.model.dt();
        let Solver {
            model,
            x,
            v,
            f_int,
            inv_mass,
            hex_e,
            truss_f,
            truss_e,
            px,
            pv,
            node_energy,
            pool,
            ..
        } = self;
        let (x, v) = (&*x, &*v);
        let (de, dtr) = pool.install(|| {
            // Embedded points follow their hosts.
            let points = &model.embedding.points;
            px.par_iter_mut()
                .zip(pv.par_iter_mut())
                .zip(points.par_iter())
                .with_min_len(256)
                .for_each(|((px, pv), pt)| {
                    *px = pt.interpolate(x);
                    *pv = pt.interpolate(v);
                });

            // Hexahedra, their forces added to the nodes layer by layer.
            let mat = &model.solid;
            model.layers.add_forces(
                &mut model.batches,
                f_int,
                hex_e,
                |b, acc: &mut HexEnergy, forces| {
                    let en = hex8::step(b, mat, x, v, dt, forces);
                    acc.internal += en.internal;
                    acc.hourglass += en.hourglass;
                    acc.viscous += en.viscous;
                },
            );

            // Trusses.
            let trusses = &model.embedding.trusses;
            let mats = &model.bar_materials;
            let (px, pv) = (&*px, &*pv);
            model
                .truss_state
                .par_chunks_mut(TRUSS_CHUNK)
                .zip(trusses.par_chunks(TRUSS_CHUNK))
                .zip(truss_f.par_chunks_mut(2 * TRUSS_CHUNK))
                .zip(truss_e.par_iter_mut())
                .for_each(|(((st, tr), f), e)| {
                    let mut acc = 0.0;
                    for ((s, t), f) in st.iter_mut().zip(tr).zip(f.chunks_mut(2)) {
                        let (p, q) = (t.ends[0] as usize, t.ends[1] as usize);
                        let d = sub(px[q], px[p]);
                        let len = dot(d, d).sqrt();
                        let dir = [d[0] / len, d[1] / len, d[2] / len];
                        let deps = dot(dir, sub(pv[q], pv[p])) / len * dt;
                        let old = s.stress;
                        mats[t.set as usize].update(&mut s.state, deps, &mut s.stress);
                        s.strain += deps;
                        acc += 0.5 * (old + s.stress) * deps * t.area * t.length;
                        let n = s.stress * t.area;
                        f[0] = [-n * dir[0], -n * dir[1], -n * dir[2]];
                        f[1] = [n * dir[0], n * dir[1], n * dir[2]];
                    }
                    *e = acc;
                });

            let de = hex_e.iter().fold(HexEnergy::default(), |a, e| HexEnergy {
                internal: a.internal + e.internal,
                hourglass: a.hourglass + e.hourglass,
                viscous: a.viscous + e.viscous,
            });
            let dtr: f64 = truss_e.iter().sum();
            (de, dtr)
        });
        let damping = StepDamping::new(match self.damping {
            Some(d) if self.t < d.until => 0.5 * d.alpha * dt,
            _ => 0.0,
        });
        let (xm, vm) = (&mut self.x, &mut self.v);
        let (truss_f, assembly, mass) = (&*truss_f, &model.assembly, &model.mass);
        pool.install(|| {
            xm.par_chunks_mut(NODE_CHUNK)
                .zip(vm.par_chunks_mut(NODE_CHUNK))
                .zip(f_int.par_chunks_mut(NODE_CHUNK))
                .zip(node_energy.par_iter_mut())
                .enumerate()
                .for_each(|(c, (((xs, vs), fs), out))| {
                    let (mut acc, mut dis) = (0.0, 0.0);
                    for (k, ((xn, vn), fi)) in xs.iter_mut().zip(vs.iter_mut()).zip(fs).enumerate()
                    {
                        let n = c * NODE_CHUNK + k;
                        // The bars' share of the nodal forces, added here
                        // rather than in a pass of its own over the nodes.
                        let f = assembly.with_trusses(*fi, truss_f, n);
                        *fi = f;
                        let im = inv_mass[n];
                        if im == 0.0 {
                            continue;
                        }
                        let old = *vn;
                        let new = [
                            damping.velocity(old[0], -(dt * im * f[0])),
                            damping.velocity(old[1], -(dt * im * f[1])),
                            damping.velocity(old[2], -(dt * im * f[2])),
                        ];
                        let avg = [
                            0.5 * (old[0] + new[0]),
                            0.5 * (old[1] + new[1]),
                            0.5 * (old[2] + new[2]),
                        ];
                        let mean_sq = dot(avg, avg);
                        acc += 0.5 * mass[n] * mean_sq;
                        dis += damping.dissipated(mass[n], mean_sq);
                        *vn = new;
                        *xn = [
                            xn[0] + dt * new[0],
                            xn[1] + dt * new[1],
                            xn[2] + dt * new[2],
                        ];
                    }
                    *out = [acc, dis];
                });
        });
        let ke_nodes: f64 = node_energy.iter().map(|k| k[0]).sum();
        let damped: f64 = node_energy.iter().map(|k| k[1]).sum();
        let (ke_top, work, damped_top) = self.advance_top(dt, damping);
        self.energy.strain += de.internal + dtr;
        self.energy.hourglass += de.hourglass;
        self.energy.viscous += de.viscous + damped + damped_top;
        self.energy.kinetic = ke_nodes + ke_top;
        self.energy.work += work;
        self.t += dt;
        self.steps += 1;
    }

    /// Moves the rigid top: resultants, reference-point dynamics (with
    /// `damping` in its force-driven degrees of freedom),
    /// exact rigid positions of the top nodes. Returns the kinetic energy of
    /// the top nodes, the work increment at the reference point and the
    /// energy the damping dissipated.
    fn advance_top(&mut self, dt: f64, damping: StepDamping) -> (f64, f64, f64) {
        let top = &mut self.top;
        let mut col = [0.0; 6];
        let mut inertia = [0.0; 3];
        for &n in &top.nodes {
            let n = n as usize;
            let r = sub(self.x[n], top.centre);
            let f = self.f_int[n];
            let m = cross(r, f);
            for i in 0..3 {
                col[i] += f[i];
                col[3 + i] += m[i];
            }
            let mass = self.model.mass[n];
            inertia[0] += mass * (r[1] * r[1] + r[2] * r[2]);
            inertia[1] += mass * (r[0] * r[0] + r[2] * r[2]);
            inertia[2] += mass * (r[0] * r[0] + r[1] * r[1]);
        }
        let (mut work, mut damped) = (0.0, 0.0);
        for k in 0..6 {
            let mk = if k < 3 { top.mass } else { inertia[k - 3] };
            let (vel, load) = match &top.controls[k] {
                Control::Force(h) => {
                    let g = h.value(self.t);
                    let vel = damping.velocity(top.vel[k], dt * (g - col[k]) / mk);
                    let avg = 0.5 * (top.vel[k] + vel);
                    damped += damping.dissipated(mk, avg * avg);
                    (vel, g)
                }
                Control::Motion(h) => {
                    let vel = (h.value(self.t + dt) - top.disp[k]) / dt;
                    (vel, mk * (vel - top.vel[k]) / dt + col[k])
                }
            };
            work += 0.5 * (top.prev_load[k] + load) * dt * top.vel[k];
            top.prev_load[k] = load;
            top.reaction[k] = load;
            top.vel[k] = vel;
            top.disp[k] += dt * vel;
        }
        top.column = col;
        for i in 0..3 {
            top.centre[i] = top.centre0[i] + top.disp[i];
        }
        let inc = rotation([dt * top.vel[3], dt * top.vel[4], dt * top.vel[5]]);
        top.rot = matmul(inc, top.rot);
        let mut ke = 0.0;
        for (&n, arm) in top.nodes.iter().zip(&top.arms) {
            let n = n as usize;
            let r = matvec(top.rot, *arm);
            let xn = [
                top.centre[0] + r[0],
                top.centre[1] + r[1],
                top.centre[2] + r[2],
            ];
            let old = self.v[n];
            let new = [
                (xn[0] - self.x[n][0]) / dt,
                (xn[1] - self.x[n][1]) / dt,
                (xn[2] - self.x[n][2]) / dt,
            ];
            let avg = [
                0.5 * (old[0] + new[0]),
                0.5 * (old[1] + new[1]),
                0.5 * (old[2] + new[2]),
            ];
            ke += 0.5 * self.model.mass[n] * dot(avg, avg);
            self.v[n] = new;
            self.x[n] = xn;
        }
        (ke, work, damped)
    }

    /// Current positions of the embedded bar points (as of the last
    /// step's start), m.
    pub fn bar_points(&self) -> &[[f64; 3]] {
        &self.px
    }

    /// The torque the fixed base resists with (equal to the applied torque
    /// in equilibrium), N m.
    pub fn base_torque(&self) -> f64 {
        let mut t = 0.0;
        for n in self.base.clone() {
            let f = self.f_int[n];
            let x = self.x[n];
            t -= x[0] * f[1] - x[1] * f[0];
        }
        t
    }

    /// The axial force at the base, signed as the load at the top (equal
    /// to it in equilibrium), N.
    pub fn base_axial(&self) -> f64 {
        -self.base.clone().map(|n| self.f_int[n][2]).sum::<f64>()
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn matvec(m: [[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn matmul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

/// The rotation matrix of a rotation vector (Rodrigues' formula).
fn rotation(w: [f64; 3]) -> [[f64; 3]; 3] {
    let th = dot(w, w).sqrt();
    if th == 0.0 {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let k = [w[0] / th, w[1] / th, w[2] / th];
    let (s, c) = th.sin_cos();
    let t = 1.0 - c;
    [
        [
            c + t * k[0] * k[0],
            t * k[0] * k[1] - s * k[2],
            t * k[0] * k[2] + s * k[1],
        ],
        [
            t * k[1] * k[0] + s * k[2],
            c + t * k[1] * k[1],
            t * k[1] * k[2] - s * k[0],
        ],
        [
            t * k[2] * k[0] - s * k[1],
            t * k[2] * k[1] + s * k[0],
            c + t * k[2] * k[2],
        ],
    ]
}
