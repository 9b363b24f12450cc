//! The assembled model: element batches with their constants, layer by
//! layer ([`Layers`]), embedded trusses, lumped nodal masses, the stable
//! time step with optional mass scaling, and the node-to-truss tables that
//! keep the bars' share of the nodal forces deterministic.

use super::hex8::{self, HexBatch};
use super::layers::Layers;
use super::material::{BarMaterial, SolidMaterial};
use super::mesh::Mesh;
use super::rebar::{BarSet, Embedding};
use super::simd::{F4, LANES};
use super::stable_step;

/// Numerical settings of the explicit procedure.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Settings {
    /// Hourglass stiffness scale `s` (1 gives a cubic element the exact
    /// stiffness `G h / 48` of the linearly varying shear strain of
    /// torsion; see [`super::hex8`]).
    pub hourglass_scale: f64,
    /// Linear bulk-viscosity coefficient `b1` (ABAQUS default 0.06).
    pub bulk_linear: f64,
    /// Quadratic bulk-viscosity coefficient `b2` (ABAQUS default 1.2).
    pub bulk_quadratic: f64,
    /// Fraction of the stable step used.
    pub dt_safety: f64,
    /// How the stable step is estimated.
    pub time_step: TimeStep,
    /// Mass scaling: elements whose stable step is below this one get
    /// their density raised to reach it, s.
    pub mass_scaling_dt: Option<f64>,
}

impl Settings {
    /// The stable step's factor for the linear bulk viscosity `b1`:
    /// `sqrt(1 + b1^2) - b1` (ABAQUS/Explicit), the same for the element
    /// and the global estimates.
    pub fn viscous_factor(&self) -> f64 {
        let b1 = self.bulk_linear;
        (1.0 + b1 * b1).sqrt() - b1
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            hourglass_scale: 1.0,
            bulk_linear: 0.06,
            bulk_quadratic: 1.2,
            dt_safety: 0.9,
            time_step: TimeStep::Global,
            mass_scaling_dt: None,
        }
    }
}

/// How the stable time step is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TimeStep {
    /// The smallest of the elements' own bounds: `L_e / c_d` of each
    /// hexahedron (bulk viscosity included) and `L / c` of each truss.
    Element,
    /// The highest frequency of the whole model
    /// ([`super::stable_step`]); ABAQUS/Explicit's global estimate.
    Global,
}

/// Stress and history of one truss.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TrussState<S> {
    /// Axial stress, Pa.
    pub stress: f64,
    /// Accumulated axial strain.
    pub strain: f64,
    /// Material history.
    pub state: S,
}

/// Compressed rows: the contributions to each node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rows<T> {
    /// `start[n]..start[n + 1]` indexes `entries` for node `n`.
    pub start: Vec<u32>,
    /// The contributions, in a fixed order.
    pub entries: Vec<T>,
}

impl<T: Copy> Rows<T> {
    fn build(nodes: usize, items: &[(u32, T)]) -> Rows<T> {
        let mut count = vec![0u32; nodes + 1];
        for (n, _) in items {
            count[*n as usize + 1] += 1;
        }
        for i in 0..nodes {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut entries: Vec<Option<T>> = vec![None; items.len()];
        for (n, t) in items {
            let k = &mut fill[*n as usize];
            entries[*k as usize] = Some(*t);
            *k += 1;
        }
        Rows {
            start: count,
            entries: entries.into_iter().flatten().collect(),
        }
    }

    /// The contributions to node `n`.
    pub fn row(&self, n: usize) -> &[T] {
        &self.entries[self.start[n] as usize..self.start[n + 1] as usize]
    }
}

/// The bars' share of the nodal forces: each truss end's force goes to the
/// nodes of its host hexahedron with the end's interpolation weights.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assembly {
    /// Truss force slots (`2 t + end`) and weights of each node.
    pub truss: Rows<(u32, f64)>,
}

impl Assembly {
    /// `f` (the force on node `n` from the hexahedra, [`Layers::add_forces`])
    /// plus node `n`'s share of the truss-end forces in `truss_f`
    /// (`2 t + end`), in the fixed order of its row, so that the sum does
    /// not depend on threads.
    #[inline(always)]
    pub fn with_trusses(&self, f: [f64; 3], truss_f: &[[f64; 3]], n: usize) -> [f64; 3] {
        let mut s = f;
        for &(slot, w) in self.truss.row(n) {
            let g = truss_f[slot as usize];
            s = [s[0] + w * g[0], s[1] + w * g[1], s[2] + w * g[2]];
        }
        s
    }
}

/// Stable time steps before and after mass scaling.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StepLimits {
    /// Smallest stable step of the hexahedra (bulk viscosity included), s.
    pub hex: f64,
    /// Smallest stable step of the truss segments, s.
    pub truss: f64,
    /// Stable step of the whole model from its highest frequency (bulk
    /// viscosity included, after mass scaling), s; `None` with
    /// [`TimeStep::Element`], and when the estimate did not settle (the
    /// element step is used then).
    pub global: Option<f64>,
    /// Lanczos iterations of the global estimate (with
    /// [`TimeStep::Global`], settled or not).
    pub global_iterations: Option<usize>,
    /// The step used: safety times the global step, or times the smallest
    /// element step after mass scaling, s.
    pub dt: f64,
}

/// A model ready for the explicit solver.
pub struct Model<M: SolidMaterial, B: BarMaterial> {
    /// The mesh (reference configuration).
    pub mesh: Mesh,
    /// Concrete.
    pub solid: M,
    /// One material per bar set.
    pub bar_materials: Vec<B>,
    /// Names of the bar sets.
    pub bar_names: Vec<String>,
    /// Hexahedra in batches of [`LANES`], layer by layer ([`Layers`]).
    pub batches: Vec<HexBatch<M::State>>,
    /// How the batches and nodes fall into layers.
    pub layers: Layers,
    /// The embedded bars.
    pub embedding: Embedding,
    /// Truss stresses and histories.
    pub truss_state: Vec<TrussState<B::State>>,
    /// Lumped nodal masses (scaled), kg.
    pub mass: Vec<f64>,
    /// Which element forces each node sums.
    pub assembly: Assembly,
    /// The time steps.
    pub limits: StepLimits,
    /// Physical mass, kg.
    pub physical_mass: f64,
    /// Mass added by mass scaling, kg.
    pub added_mass: f64,
    /// The settings the model was built with.
    pub settings: Settings,
}

impl<M: SolidMaterial, B: BarMaterial> Model<M, B> {
    /// Builds the model; `bar_sets[i]` uses `bar_materials[i]`.
    pub fn new(
        mesh: Mesh,
        solid: M,
        bar_sets: &[BarSet],
        bar_materials: Vec<B>,
        embedding: Embedding,
        settings: Settings,
    ) -> Self {
        let props = solid.initial();
        let c = props.wave_speed();
        let g = props.shear_modulus();
        let rho = props.density;
        let b1 = settings.bulk_linear;
        let visc = settings.viscous_factor();
        let target = settings.mass_scaling_dt.unwrap_or(0.0);
        let n_nodes = mesh.nodes.len();
        let mut mass = vec![0.0; n_nodes];
        let mut physical = 0.0;
        let mut added = 0.0;
        let mut dt_hex = f64::INFINITY;
        let mut dt_min = f64::INFINITY;
        let per_layer = mesh.section.quads.len();
        let layers = Layers::new(mesh.layers, per_layer, mesh.section.nodes.len());
        let mut batches = Vec::with_capacity(layers.count * layers.batches);
        for chunk in mesh
            .hexes
            .chunks(per_layer)
            .flat_map(|layer| layer.chunks(LANES))
        {
            let mut nodes = [[0u32; LANES]; 8];
            let mut hg_k = F4::ZERO;
            let mut le = F4::ZERO;
            let mut bv1 = F4::ZERO;
            let mut bv2 = F4::ZERO;
            let mut mask = F4::ZERO;
            for l in 0..LANES {
                let real = l < chunk.len();
                let hex = chunk[l.min(chunk.len() - 1)];
                for a in 0..8 {
                    nodes[a][l] = hex[a];
                }
                let xs: [[f64; 3]; 8] = std::array::from_fn(|a| mesh.nodes[hex[a] as usize]);
                let (vol, len, bb) = hex8::measures(&xs);
                hg_k.0[l] = settings.hourglass_scale * g * bb / (72.0 * vol);
                le.0[l] = len;
                bv1.0[l] = b1 * rho * c * len;
                bv2.0[l] = settings.bulk_quadratic.powi(2) * rho * len * len;
                if real {
                    mask.0[l] = 1.0;
                    let dt_e = len / c * visc;
                    dt_hex = dt_hex.min(dt_e);
                    let scale = if dt_e < target {
                        (target / dt_e).powi(2)
                    } else {
                        1.0
                    };
                    dt_min = dt_min.min(dt_e * scale.sqrt());
                    let m = rho * vol;
                    physical += m;
                    added += m * (scale - 1.0);
                    for &n in &hex {
                        mass[n as usize] += m * scale / 8.0;
                    }
                }
            }
            batches.push(HexBatch {
                nodes,
                len: chunk.len(),
                stress: [F4::ZERO; 6],
                strain: [F4::ZERO; 6],
                hg: [[F4::ZERO; 4]; 3],
                hg_k,
                hg_keep: F4::splat(1.0),
                char_len: le,
                bv1,
                bv2,
                mask,
                state: Default::default(),
            });
        }
        let mut dt_truss = f64::INFINITY;
        for t in &embedding.trusses {
            let mat = &bar_materials[t.set as usize];
            let cs = (mat.modulus() / mat.density()).sqrt();
            let dt_e = t.length / cs;
            dt_truss = dt_truss.min(dt_e);
            let scale = if dt_e < target {
                (target / dt_e).powi(2)
            } else {
                1.0
            };
            dt_min = dt_min.min(dt_e * scale.sqrt());
            let m = mat.density() * t.area * t.length;
            physical += m;
            added += m * (scale - 1.0);
            for &p in &t.ends {
                let pt = &embedding.points[p as usize];
                for a in 0..8 {
                    mass[pt.hosts[a] as usize] += 0.5 * m * scale * pt.weights[a];
                }
            }
        }
        let mut truss_items = Vec::new();
        for (t, tr) in embedding.trusses.iter().enumerate() {
            for (end, &p) in tr.ends.iter().enumerate() {
                let pt = &embedding.points[p as usize];
                for a in 0..8 {
                    if pt.weights[a] != 0.0 {
                        truss_items.push((pt.hosts[a], ((2 * t + end) as u32, pt.weights[a])));
                    }
                }
            }
        }
        let truss_state = vec![TrussState::default(); embedding.trusses.len()];
        let mut model = Model {
            assembly: Assembly {
                truss: Rows::build(n_nodes, &truss_items),
            },
            layers,
            mesh,
            solid,
            bar_materials,
            bar_names: bar_sets.iter().map(|s| s.name.clone()).collect(),
            batches,
            embedding,
            truss_state,
            mass,
            limits: StepLimits {
                hex: dt_hex,
                truss: dt_truss,
                global: None,
                global_iterations: None,
                dt: settings.dt_safety * dt_min,
            },
            physical_mass: physical,
            added_mass: added,
            settings,
        };
        if settings.time_step == TimeStep::Global {
            model.take_global_step(stable_step::MAX_ITERATIONS);
        }
        model
    }

    /// Replaces the element step by the global one
    /// (`dt_safety (2 / omega_max)(sqrt(1 + b1^2) - b1)`) when the Lanczos
    /// estimate settles within `max_iterations`; otherwise keeps the
    /// element step and records only the iterations taken.
    pub(super) fn take_global_step(&mut self, max_iterations: usize) {
        match stable_step::highest_frequency(self, max_iterations) {
            Ok(f) => {
                let dt = 2.0 / f.omega_max * self.settings.viscous_factor();
                self.limits.global = Some(dt);
                self.limits.global_iterations = Some(f.iterations);
                self.limits.dt = self.settings.dt_safety * dt;
            }
            Err(e) => {
                self.limits.global = None;
                self.limits.global_iterations = Some(e.iterations);
            }
        }
    }

    /// The time step, s.
    pub fn dt(&self) -> f64 {
        self.limits.dt
    }

    /// Number of hexahedra.
    pub fn elements(&self) -> usize {
        self.mesh.hexes.len()
    }
}
