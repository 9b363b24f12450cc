//! Element layers as the unit of parallel work on the nodal forces.
//!
//! Every mesh is an extrusion ([`super::mesh::Mesh::extrude`]): the
//! hexahedra of element layer `k` have their nodes in node layers `k` and
//! `k + 1`, so two element layers of the same parity share no node. The
//! forces of a layer's hexahedra are therefore added straight into its two
//! node layers, even element layers first, then odd ones, each layer on one
//! thread: no two threads write one node, and every node receives its
//! contributions in one fixed order (its lower or upper element layer
//! first by parity, then batch by batch, lane by lane), whatever the number
//! of threads. An earlier layout wrote every element's eight forces into
//! slots of their own and had each node sum its slots; with the large
//! meshes that array (9.3 MB for H/D(3)) no longer stayed in cache between
//! the two passes, and the node pass waited on its loads (`docs/fe.md`,
//! "Nodal forces by element layers").

use super::hex8::{HexBatch, HexForces};
use super::simd::{F4, LANES};
use rayon::prelude::*;

/// How the batches and nodes of a model fall into layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layers {
    /// Element layers.
    pub count: usize,
    /// Hexahedra in a layer.
    pub elements: usize,
    /// Batches in a layer: the layer's hexahedra in groups of [`LANES`],
    /// the last one padded, so that no batch spans two layers.
    pub batches: usize,
    /// Nodes in a node layer.
    pub nodes: usize,
}

impl Layers {
    /// The layers of `count` element layers of `elements` hexahedra over
    /// node layers of `nodes` nodes.
    pub fn new(count: usize, elements: usize, nodes: usize) -> Self {
        Layers {
            count,
            elements,
            batches: elements.div_ceil(LANES),
            nodes,
        }
    }

    /// The batch and lane of hexahedron `e`.
    pub fn lane_of(&self, e: usize) -> (usize, usize) {
        let (k, i) = (e / self.elements, e % self.elements);
        (k * self.batches + i / LANES, i % LANES)
    }

    /// Sets `f` to the sum of the nodal forces `element` writes into its
    /// third argument for every batch (`f[n]` is the force on node `n`), in
    /// the fixed order of the module docs, and `energy[k]` to what
    /// `element` adds, through its second argument, for the batches of
    /// layer `k` (from `E::default()`).
    pub fn add_forces<S, E>(
        &self,
        batches: &mut [HexBatch<S>],
        f: &mut [[f64; 3]],
        energy: &mut [E],
        element: impl Fn(&mut HexBatch<S>, &mut E, &mut HexForces) + Sync,
    ) where
        S: Send,
        E: Send + Default,
    {
        debug_assert_eq!(batches.len(), self.count * self.batches);
        debug_assert_eq!(f.len(), (self.count + 1) * self.nodes);
        debug_assert_eq!(energy.len(), self.count);
        energy.fill_with(E::default);
        for parity in 0..2 {
            batches[parity * self.batches..]
                .par_chunks_mut(2 * self.batches)
                .zip(f[parity * self.nodes..].par_chunks_mut(2 * self.nodes))
                .zip(energy[parity..].par_chunks_mut(2))
                .enumerate()
                .for_each(|(i, ((pair, nodes), e))| {
                    let lower = parity + 2 * i;
                    let base = lower * self.nodes;
                    // A node layer is zeroed by the first element layer to
                    // reach it, while the layer's nodes are about to be in
                    // cache anyway: the even element layers reach all but
                    // the top node layer of an even count, which only the
                    // last element layer, an odd one, reaches.
                    if parity == 0 {
                        nodes.fill([0.0; 3]);
                    } else if lower + 1 == self.count {
                        nodes[self.nodes..].fill([0.0; 3]);
                    }
                    let mut forces = [[F4::ZERO; 8]; 3];
                    for b in &mut pair[..self.batches] {
                        element(b, &mut e[0], &mut forces);
                        for l in 0..b.len {
                            for a in 0..8 {
                                let g = &mut nodes[b.nodes[a][l] as usize - base];
                                for c in 0..3 {
                                    g[c] += forces[c][a].0[l];
                                }
                            }
                        }
                    }
                });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A batch whose lanes are the given hexahedra (node lists), the last
    /// one repeated as padding.
    fn batch(hexes: &[[u32; 8]]) -> HexBatch<()> {
        HexBatch {
            nodes: std::array::from_fn(|a| {
                std::array::from_fn(|l| hexes[l.min(hexes.len() - 1)][a])
            }),
            len: hexes.len(),
            stress: [F4::ZERO; 6],
            strain: [F4::ZERO; 6],
            hg: [[F4::ZERO; 4]; 3],
            hg_k: F4::ZERO,
            hg_keep: F4::splat(1.0),
            char_len: F4::ZERO,
            bv1: F4::ZERO,
            bv2: F4::ZERO,
            mask: F4::ZERO,
            state: [(); LANES],
        }
    }

    /// Three and four layers (an odd and an even count: the top node layer
    /// is zeroed by an even or an odd element layer) of a strip of five
    /// square cells (12 nodes a layer, the last batch of each layer
    /// padded): every node gets the sum of the forces its hexahedra give
    /// it, counted independently per element, the padding adds nothing,
    /// each layer's energy is its own, and one thread and two give the
    /// same bits.
    #[test]
    fn every_node_gets_its_elements_forces_once() {
        for layers in [3, 4] {
            forces_of(layers);
        }
    }

    fn forces_of(layers: usize) {
        let cells = 5;
        let np = 2 * (cells + 1);
        let hexes: Vec<[u32; 8]> = (0..layers)
            .flat_map(|k| {
                (0..cells).map(move |c| {
                    let q = [c, c + 1, cells + 2 + c, cells + 1 + c];
                    let lo = k * np;
                    let hi = (k + 1) * np;
                    std::array::from_fn(|a| (if a < 4 { q[a] + lo } else { q[a - 4] + hi }) as u32)
                })
            })
            .collect();
        let lay = Layers::new(layers, cells, np);
        assert_eq!(lay.batches, 2);
        let make = || -> Vec<HexBatch<()>> {
            hexes
                .chunks(cells)
                .flat_map(|layer| layer.chunks(LANES).map(batch).collect::<Vec<_>>())
                .collect()
        };
        // Element e gives node a the force (e + 1) * [1, 10, 100] * (a + 1).
        let element_of = |b: &HexBatch<()>, l: usize| {
            hexes
                .iter()
                .position(|h| (0..8).all(|a| h[a] == b.nodes[a][l]))
                .unwrap()
        };
        let element = |b: &mut HexBatch<()>, e: &mut f64, f: &mut HexForces| {
            for l in 0..LANES {
                let id = element_of(b, l) as f64 + 1.0;
                for a in 0..8 {
                    for c in 0..3 {
                        f[c][a].0[l] = id * 10f64.powi(c as i32) * (a as f64 + 1.0);
                    }
                }
                if l < b.len {
                    *e += id;
                }
            }
        };
        let mut want = vec![[0.0; 3]; (layers + 1) * np];
        for (e, h) in hexes.iter().enumerate() {
            for (a, &n) in h.iter().enumerate() {
                for c in 0..3 {
                    want[n as usize][c] +=
                        (e as f64 + 1.0) * 10f64.powi(c as i32) * (a as f64 + 1.0);
                }
            }
        }
        let mut results = Vec::new();
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut batches = make();
            let mut f = vec![[f64::NAN; 3]; (layers + 1) * np];
            let mut energy = vec![f64::NAN; layers];
            pool.install(|| lay.add_forces(&mut batches, &mut f, &mut energy, element));
            assert_eq!(f, want);
            // Layer k holds elements 5k + 1 ..= 5k + 5.
            let sums: Vec<f64> = (0..layers)
                .map(|k| (1..=cells).map(|i| (cells * k + i) as f64).sum())
                .collect();
            assert_eq!(energy, sums);
            results.push(f);
        }
        assert_eq!(results[0], results[1]);
        for e in [0, 4, 5, 14] {
            let (b, l) = lay.lane_of(e);
            let batches = make();
            assert_eq!(element_of(&batches[b], l), e);
        }
    }
}
