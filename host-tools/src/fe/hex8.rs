//! The one-point 8-node hexahedron (the C3D8R of thesis 2.6) with
//! Flanagan-Belytschko stiffness hourglass control, for a batch of
//! [`LANES`] elements.
//!
//! Node order: 1-4 the bottom face counter-clockwise seen from `+z`, 5-8 the
//! top face above them; natural coordinates `(xi, eta, zeta)` of node `a`
//! are [`XI`]. Per step and element (Flanagan and Belytschko 1981):
//!
//! * uniform-gradient vectors `b_ia = dV/dx_ia` (the exact derivative of
//!   the element volume, so `sum_a b_ia x_ja = V delta_ij`: the patch test
//!   holds for any hexahedron), volume `V = sum_a b_xa x_a`;
//! * velocity gradient `L_ij = (1/V) sum_a v_ia b_ja`, strain increment
//!   `deps = dt sym(L)`, spin `W = skew(L)`;
//! * stress rotated by the Jaumann rate, `sigma += dt (W sigma - sigma W)`,
//!   then advanced by the material with `deps`;
//! * bulk viscosity (linear + quadratic, as ABAQUS/Explicit):
//!   `sigma_v = rho L_e (b1 c_d e_v - b2^2 L_e min(e_v, 0)^2)` with
//!   `e_v = tr L`, added to the normal stresses;
//! * nodal forces `f_ia = (sigma_ij + sigma_v delta_ij) b_ja`;
//! * hourglass: shape vectors `gamma_alpha = Gamma_alpha -
//!   (1/V) (Gamma_alpha . x_i) b_i` (orthogonal to every linear field),
//!   mode rates `qdot_i_alpha = v_i . gamma_alpha`, forces
//!   `Q_i_alpha += k dt qdot_i_alpha`, `f_ia += Q_i_alpha gamma_alpha_a`, with
//!   the stiffness `k = s G sum_a |b_a|^2 / (72 V)` (`G` the shear modulus).
//!   Scale `s = 1` gives a cube of side `h` the stiffness `G h / 48`, the
//!   exact energy of the shear strain that varies linearly across an
//!   element in torsion (`u_x = -theta' y z`, whose bilinear part is the
//!   `eta zeta` hourglass mode); pure bending would need `E h / 48`.
//!   Since that stiffness stands for the material's own shear stiffness,
//!   it follows the element's damage (thesis 2.2.1): `k` is scaled by the
//!   lowest [`SolidMaterial::retained_stiffness`] (`1 - d`) the element
//!   has had, and the stored forces by its drop, so `Q = (1 - d) k u` for
//!   the accumulated mode displacement `u`, the secant form of the damaged
//!   material. Taking the lowest value keeps the scale from rising again
//!   when cracks close (the stiffness recovery of the material depends on
//!   the sign of the stress, which varies across an hourglass mode), so
//!   the hourglass energy cannot be created: with the scale never rising,
//!   the work on a mode is at least the energy stored in it.

use super::material::{SolidMaterial, Sym6};
use super::simd::{F4, LANES};

/// Natural coordinates of the eight nodes.
pub const XI: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// The four hourglass base vectors: `eta zeta`, `zeta xi`, `xi eta` and
/// `xi eta zeta` at the nodes.
pub const GAMMA: [[f64; 8]; 4] = [
    [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0],
];

/// Trilinear shape functions at natural coordinates `p`.
pub fn shape(p: [f64; 3]) -> [f64; 8] {
    let mut n = [0.0; 8];
    for (a, n) in n.iter_mut().enumerate() {
        *n = (1.0 + XI[a][0] * p[0]) * (1.0 + XI[a][1] * p[1]) * (1.0 + XI[a][2] * p[2]) / 8.0;
    }
    n
}

/// Coefficients of a nodal field in the isoparametric basis,
/// `p = p0 + xi e1 + eta e2 + zeta e3 + eta zeta h1 + zeta xi h2 + xi eta h3
/// + xi eta zeta h4`, returned as `[e1, e2, e3, h1, h2, h3, h4]`; each is
/// `(1/8) sum_a c(a) p_a` for its sign pattern `c`, by butterflies.
#[inline(always)]
fn coefficients(p: &[F4; 8]) -> [F4; 7] {
    let s: [F4; 4] = std::array::from_fn(|a| p[a] + p[a + 4]);
    let d: [F4; 4] = std::array::from_fn(|a| p[a + 4] - p[a]);
    let k = 0.125;
    let (su, sw) = (s[2] - s[0], s[1] - s[3]);
    let (du, dw) = (d[2] - d[0], d[1] - d[3]);
    let (s02, s13) = (s[0] + s[2], s[1] + s[3]);
    let (d02, d13) = (d[0] + d[2], d[1] + d[3]);
    [
        (su + sw) * k,
        (su - sw) * k,
        (d02 + d13) * k,
        (du - dw) * k,
        (du + dw) * k,
        (s02 - s13) * k,
        (d02 - d13) * k,
    ]
}

/// Nodal values `f_a = sum_k c_k(a) f[k]` from coefficients ordered as in
/// [`coefficients`] (the transpose of that map, without the 1/8).
#[inline(always)]
fn expand(f: &[F4; 7]) -> [F4; 8] {
    let (a1, a2) = (f[0] - f[1], f[0] + f[1]);
    let (c1, c2) = (f[4] - f[3], f[4] + f[3]);
    // Corners (xi, eta) = (-,-), (+,-), (+,+), (-,+).
    let a = [f[5] - a2, a1 - f[5], a2 + f[5], -a1 - f[5]];
    let c = [
        f[2] - c2 + f[6],
        f[2] + c1 - f[6],
        f[2] + c2 + f[6],
        f[2] - c1 - f[6],
    ];
    [
        a[0] - c[0],
        a[1] - c[1],
        a[2] - c[2],
        a[3] - c[3],
        a[0] + c[0],
        a[1] + c[1],
        a[2] + c[2],
        a[3] + c[3],
    ]
}

type V3 = [F4; 3];

#[inline(always)]
fn cross4(a: V3, b: V3) -> V3 {
    [
        a[1].mul_add(b[2], -(a[2] * b[1])),
        a[2].mul_add(b[0], -(a[0] * b[2])),
        a[0].mul_add(b[1], -(a[1] * b[0])),
    ]
}

#[inline(always)]
fn lin(a: V3, fa: f64, b: V3, fb: f64) -> V3 {
    std::array::from_fn(|i| a[i].mul_add(F4::splat(fa), b[i] * fb))
}

/// Coefficient vectors `[e1, e2, e3, h1, h2, h3, h4]` of the geometry, the
/// derivatives `G_k = dV/d(coefficient k)` of the volume for the first six
/// (`h4` does not change the volume), and the volume.
///
/// With the coefficients, `V = 8 [e1.(e2 x e3) + (e1.(h3 x h2) +
/// e2.(h1 x h3) + e3.(h2 x h1)) / 3]` exactly (the integral of det J over
/// the cube), so `b_a = dV/dx_a = (1/8) sum_k c_k(a) G_k`: the uniform
/// gradient of Flanagan and Belytschko (1981) without forming it per node.
#[inline(always)]
fn geometry(x: &[[F4; 8]; 3]) -> ([V3; 7], [V3; 6], F4) {
    let cx = [
        coefficients(&x[0]),
        coefficients(&x[1]),
        coefficients(&x[2]),
    ];
    let c: [V3; 7] = std::array::from_fn(|k| [cx[0][k], cx[1][k], cx[2][k]]);
    let (e1, e2, e3, h1, h2, h3) = (c[0], c[1], c[2], c[3], c[4], c[5]);
    let t = 8.0 / 3.0;
    let g = [
        lin(cross4(e2, e3), 8.0, cross4(h3, h2), t),
        lin(cross4(e3, e1), 8.0, cross4(h1, h3), t),
        lin(cross4(e1, e2), 8.0, cross4(h2, h1), t),
        lin(cross4(h3, e2), t, cross4(e3, h2), t),
        lin(cross4(e1, h3), t, cross4(h1, e3), t),
        lin(cross4(h2, e1), t, cross4(e2, h1), t),
    ];
    let mut v = F4::ZERO;
    for k in 0..6 {
        v = c[k][0].mul_add(g[k][0], v);
    }
    (c, g, v)
}

/// Uniform-gradient vectors `b[i][a] = dV/dx_ia` and volumes of a batch.
pub fn gradients(x: &[[F4; 8]; 3]) -> ([[F4; 8]; 3], F4) {
    let (_, g, v) = geometry(x);
    let b = std::array::from_fn(|i| {
        let mut f = [F4::ZERO; 7];
        for k in 0..6 {
            f[k] = g[k][i] * 0.125;
        }
        expand(&f)
    });
    (b, v)
}

/// Per-element constants and history of a batch of hexahedra.
#[derive(Clone, Debug)]
pub struct HexBatch<S> {
    /// Global node numbers, `nodes[a][lane]`.
    pub nodes: [[u32; LANES]; 8],
    /// Number of real elements in the batch (the rest repeat the last one
    /// and are masked out).
    pub len: usize,
    /// Cauchy stress, Pa.
    pub stress: Sym6,
    /// Accumulated strain (sum of the increments), for output.
    pub strain: Sym6,
    /// Hourglass generalised forces `Q[i][alpha]`, N.
    pub hg: [[F4; 4]; 3],
    /// Hourglass stiffness `k`, N/m, of the undamaged element.
    pub hg_k: F4,
    /// Fraction of `hg_k` in use: the lowest
    /// [`SolidMaterial::retained_stiffness`] the element has had.
    pub hg_keep: F4,
    /// Characteristic length `V / A_max`, m.
    pub char_len: F4,
    /// Linear bulk-viscosity coefficient `b1 rho c_d L_e`, Pa s.
    pub bv1: F4,
    /// Quadratic bulk-viscosity coefficient `b2^2 rho L_e^2`, Pa s^2.
    pub bv2: F4,
    /// 1 for real lanes, 0 for padding.
    pub mask: F4,
    /// Material history per lane.
    pub state: [S; LANES],
}

/// Energy increments of one step of a batch, J.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HexEnergy {
    /// Strain energy (`sigma : deps V`, trapezoidal).
    pub internal: f64,
    /// Hourglass (artificial) energy.
    pub hourglass: f64,
    /// Dissipated by bulk viscosity.
    pub viscous: f64,
}

/// Nodal internal forces of a batch, `f[i][a]`.
pub type HexForces = [[F4; 8]; 3];

/// Gathers the coordinates of a batch from a node array.
#[inline(always)]
pub fn gather(nodes: &[[u32; LANES]; 8], src: &[[f64; 3]]) -> [[F4; 8]; 3] {
    let mut out = [[F4::ZERO; 8]; 3];
    for a in 0..8 {
        for l in 0..LANES {
            let p = src[nodes[a][l] as usize];
            out[0][a].0[l] = p[0];
            out[1][a].0[l] = p[1];
            out[2][a].0[l] = p[2];
        }
    }
    out
}

/// Advances a batch by one step: strain increment from the velocities
/// `v` (at `t - dt/2`) on the geometry `x` (at `t`), stress update, nodal
/// internal forces into `f`. Returns the (masked) energy increments. (The
/// forces are written in place: returned by value, their 768 bytes were
/// copied once more per batch, 1.2% of a run's instructions.)
#[inline(always)]
pub fn step<M: SolidMaterial>(
    batch: &mut HexBatch<M::State>,
    mat: &M,
    x_all: &[[f64; 3]],
    v_all: &[[f64; 3]],
    dt: f64,
    f: &mut HexForces,
) -> HexEnergy {
    let x = gather(&batch.nodes, x_all);
    let v = gather(&batch.nodes, v_all);
    let (cx, g, vol) = geometry(&x);
    let inv_v = F4::splat(1.0) / vol;
    let vc = [
        coefficients(&v[0]),
        coefficients(&v[1]),
        coefficients(&v[2]),
    ];

    // Velocity gradient L_ij = (1/V) sum_a v_ia b_ja = (1/V) sum_k vc_ki G_kj.
    let mut l = [[F4::ZERO; 3]; 3];
    for (i, li) in l.iter_mut().enumerate() {
        for (j, lij) in li.iter_mut().enumerate() {
            let mut s = F4::ZERO;
            for k in 0..6 {
                s = vc[i][k].mul_add(g[k][j], s);
            }
            *lij = s * inv_v;
        }
    }
    let half_dt = 0.5 * dt;
    let deps: Sym6 = [
        l[0][0] * dt,
        l[1][1] * dt,
        l[2][2] * dt,
        (l[0][1] + l[1][0]) * half_dt,
        (l[1][2] + l[2][1]) * half_dt,
        (l[2][0] + l[0][2]) * half_dt,
    ];
    let wxy = (l[0][1] - l[1][0]) * half_dt;
    let wyz = (l[1][2] - l[2][1]) * half_dt;
    let wzx = (l[2][0] - l[0][2]) * half_dt;

    // Jaumann rotation: sigma += W sigma - sigma W (W already times dt).
    let s = batch.stress;
    let (sxx, syy, szz, sxy, syz, szx) = (s[0], s[1], s[2], s[3], s[4], s[5]);
    let ms = |a: F4, b: F4, c: F4, d: F4| a.mul_add(b, -(c * d));
    let a00 = ms(wxy, sxy, wzx, szx);
    let a11 = ms(wyz, syz, wxy, sxy);
    let a22 = ms(wzx, szx, wyz, syz);
    let a01 = ms(wxy, syy, wzx, syz);
    let a10 = ms(wyz, szx, wxy, sxx);
    let a12 = ms(wyz, szz, wxy, szx);
    let a21 = ms(wzx, sxy, wyz, syy);
    let a20 = ms(wzx, sxx, wyz, sxy);
    let a02 = ms(wxy, syz, wzx, szz);
    let rotated: Sym6 = [
        sxx + a00 + a00,
        syy + a11 + a11,
        szz + a22 + a22,
        sxy + a01 + a10,
        syz + a12 + a21,
        szx + a20 + a02,
    ];
    let mut new = rotated;
    mat.update(&mut batch.state, &deps, batch.char_len, &mut new);

    // Strain energy, trapezoidal in stress.
    let mut w = F4::ZERO;
    for i in 0..6 {
        let f = if i < 3 { 0.5 } else { 1.0 };
        w = ((rotated[i] + new[i]) * f).mul_add(deps[i], w);
    }
    for i in 0..6 {
        batch.strain[i] += deps[i];
    }
    batch.stress = new;

    // Bulk viscosity.
    let ev = l[0][0] + l[1][1] + l[2][2];
    let evn = ev.min0();
    let sv = batch.bv1.mul_add(ev, -(batch.bv2 * evn * evn));

    // Hourglass control. Gamma_alpha . x_j = 8 h_alpha_j; the mode rates
    // are q_i_alpha = v_i . gamma_alpha = 8 vh_alpha_i - sum_j s_alpha_j L_ij.
    let mut hg_work = F4::ZERO;
    let keep = batch.hg_keep.min(mat.retained_stiffness(&batch.state));
    let relax = keep / batch.hg_keep;
    batch.hg_keep = keep;
    let kdt = batch.hg_k * keep * dt;
    let s_al: [V3; 4] = std::array::from_fn(|al| std::array::from_fn(|j| cx[3 + al][j] * 8.0));
    for i in 0..3 {
        for al in 0..4 {
            let proj =
                s_al[al][0].mul_add(l[i][0], s_al[al][1].mul_add(l[i][1], s_al[al][2] * l[i][2]));
            let q = vc[i][3 + al].mul_add(F4::splat(8.0), -proj);
            let old = batch.hg[i][al];
            let upd = kdt.mul_add(q, old * relax);
            batch.hg[i][al] = upd;
            hg_work = ((old + upd) * half_dt).mul_add(q, hg_work);
        }
    }

    // Forces f_ia = sigma~_ij b_ja + Q_i_alpha Gamma_alpha_a, with
    // sigma~ = sigma + sigma_v I - (1/V) Q s, expanded from coefficients.
    let sig = [
        [new[0] + sv, new[3], new[5]],
        [new[3], new[1] + sv, new[4]],
        [new[5], new[4], new[2] + sv],
    ];
    for i in 0..3 {
        let q = &batch.hg[i];
        let st: [F4; 3] = std::array::from_fn(|j| {
            let qs = q[0].mul_add(
                s_al[0][j],
                q[1].mul_add(s_al[1][j], q[2].mul_add(s_al[2][j], q[3] * s_al[3][j])),
            );
            (-qs).mul_add(inv_v, sig[i][j])
        });
        let mut fk = [F4::ZERO; 7];
        for k in 0..6 {
            fk[k] = st[0].mul_add(g[k][0], st[1].mul_add(g[k][1], st[2] * g[k][2])) * 0.125;
        }
        for al in 0..4 {
            fk[3 + al] += q[al];
        }
        f[i] = expand(&fk);
    }

    HexEnergy {
        internal: (w * vol * batch.mask).sum(),
        hourglass: (hg_work * batch.mask).sum(),
        viscous: (sv * ev * vol * batch.mask).sum() * dt,
    }
}

/// Volume, characteristic length `V / A_max` and `sum_a |b_a|^2` of one
/// hexahedron in its reference configuration.
pub fn measures(x: &[[f64; 3]; 8]) -> (f64, f64, f64) {
    let mut xs = [[F4::ZERO; 8]; 3];
    for a in 0..8 {
        for i in 0..3 {
            xs[i][a] = F4::splat(x[a][i]);
        }
    }
    let (b, v) = gradients(&xs);
    let mut bb = 0.0;
    for bi in &b {
        for ba in bi {
            bb += ba.0[0] * ba.0[0];
        }
    }
    const FACES: [[usize; 4]; 6] = [
        [0, 1, 2, 3],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    let mut amax: f64 = 0.0;
    for f in FACES {
        let d1 = sub(x[f[2]], x[f[0]]);
        let d2 = sub(x[f[3]], x[f[1]]);
        let c = cross(d1, d2);
        amax = amax.max(0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt());
    }
    (v.0[0], v.0[0] / amax, bb)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::super::material::{Elastic, Isotropic};
    use super::*;

    /// [`step`] with its forces returned.
    fn run<M: SolidMaterial>(
        batch: &mut HexBatch<M::State>,
        mat: &M,
        x: &[[f64; 3]],
        v: &[[f64; 3]],
        dt: f64,
    ) -> (HexForces, HexEnergy) {
        let mut f = [[F4::ZERO; 8]; 3];
        let e = step(batch, mat, x, v, dt, &mut f);
        (f, e)
    }

    /// A distorted hexahedron (no two faces parallel).
    fn distorted() -> [[f64; 3]; 8] {
        let mut x = [[0.0; 3]; 8];
        let wobble = [
            [0.03, -0.02, 0.01],
            [-0.04, 0.05, 0.02],
            [0.06, 0.01, -0.03],
            [-0.02, -0.05, 0.04],
            [0.05, 0.03, -0.02],
            [-0.01, -0.04, 0.06],
            [0.02, 0.06, 0.03],
            [-0.06, 0.02, -0.05],
        ];
        for a in 0..8 {
            for i in 0..3 {
                x[a][i] = 0.5 * XI[a][i] + wobble[a][i] + [0.3, -0.2, 1.0][i];
            }
        }
        x
    }

    /// Exact volume by 2x2x2 Gauss quadrature of det J (det J is at most
    /// quadratic in each natural coordinate, so this is exact).
    fn volume_gauss(x: &[[f64; 3]; 8]) -> f64 {
        let g = 1.0 / 3f64.sqrt();
        let mut vol = 0.0;
        for p in [
            [-g, -g, -g],
            [g, -g, -g],
            [g, g, -g],
            [-g, g, -g],
            [-g, -g, g],
            [g, -g, g],
            [g, g, g],
            [-g, g, g],
        ] {
            let mut j = [[0.0; 3]; 3];
            for a in 0..8 {
                let dn = [
                    XI[a][0] * (1.0 + XI[a][1] * p[1]) * (1.0 + XI[a][2] * p[2]) / 8.0,
                    XI[a][1] * (1.0 + XI[a][0] * p[0]) * (1.0 + XI[a][2] * p[2]) / 8.0,
                    XI[a][2] * (1.0 + XI[a][0] * p[0]) * (1.0 + XI[a][1] * p[1]) / 8.0,
                ];
                for r in 0..3 {
                    for c in 0..3 {
                        j[r][c] += dn[r] * x[a][c];
                    }
                }
            }
            let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
            vol += det;
        }
        vol
    }

    fn lanes(x: &[[f64; 3]; 8]) -> [[F4; 8]; 3] {
        let mut xs = [[F4::ZERO; 8]; 3];
        for a in 0..8 {
            for i in 0..3 {
                xs[i][a] = F4::splat(x[a][i]);
            }
        }
        xs
    }

    #[test]
    fn gradients_are_the_derivative_of_the_exact_volume() {
        let x = distorted();
        let (b, v) = gradients(&lanes(&x));
        let v_exact = volume_gauss(&x);
        assert!(
            (v.0[0] - v_exact).abs() < 1e-14 * v_exact,
            "{} {}",
            v.0[0],
            v_exact
        );
        let h = 1e-6;
        for a in 0..8 {
            for i in 0..3 {
                let mut xp = x;
                let mut xm = x;
                xp[a][i] += h;
                xm[a][i] -= h;
                let fd = (volume_gauss(&xp) - volume_gauss(&xm)) / (2.0 * h);
                assert!(
                    (b[i][a].0[0] - fd).abs() < 1e-8,
                    "b[{i}][{a}] {} vs {fd}",
                    b[i][a].0[0]
                );
            }
        }
    }

    #[test]
    fn gradients_reproduce_linear_fields() {
        let x = distorted();
        let (b, v) = gradients(&lanes(&x));
        for i in 0..3 {
            let s: f64 = (0..8).map(|a| b[i][a].0[0]).sum();
            assert!(s.abs() < 1e-15);
            for j in 0..3 {
                let m: f64 = (0..8).map(|a| b[i][a].0[0] * x[a][j]).sum();
                let want = if i == j { v.0[0] } else { 0.0 };
                assert!((m - want).abs() < 1e-15, "{i}{j}: {m} vs {want}");
            }
        }
    }

    #[test]
    fn cube_measures() {
        let mut x = [[0.0; 3]; 8];
        for a in 0..8 {
            for i in 0..3 {
                x[a][i] = 0.05 * (XI[a][i] + 1.0);
            }
        }
        let (v, le, bb) = measures(&x);
        assert!((v - 1e-3).abs() < 1e-16);
        assert!((le - 0.1).abs() < 1e-15);
        // b_ia = +-h^2/4, so sum |b|^2 = 24 h^4 / 16.
        assert!((bb - 1.5e-4).abs() < 1e-18);
    }

    fn batch_of(x: &[[f64; 3]; 8], hg_k: f64) -> HexBatch<()> {
        let mut nodes = [[0u32; LANES]; 8];
        for (a, n) in nodes.iter_mut().enumerate() {
            *n = [a as u32; LANES];
        }
        let (_, le, _) = measures(x);
        HexBatch {
            nodes,
            len: LANES,
            stress: [F4::ZERO; 6],
            strain: [F4::ZERO; 6],
            hg: [[F4::ZERO; 4]; 3],
            hg_k: F4::splat(hg_k),
            hg_keep: F4::splat(1.0),
            char_len: F4::splat(le),
            bv1: F4::ZERO,
            bv2: F4::ZERO,
            mask: F4([1.0, 0.0, 0.0, 0.0]),
            state: [(); LANES],
        }
    }

    #[test]
    fn rigid_rotation_leaves_a_stressed_element_in_equilibrium() {
        // A stress state rotated rigidly stays a rotated stress state with
        // the same invariants, and creates no hourglass force.
        let x = distorted();
        let mat = Elastic::new(Isotropic {
            e: 30e9,
            nu: 0.2,
            density: 2400.0,
        });
        let mut bt = batch_of(&x, 1e9);
        bt.stress[2] = F4::splat(-2e6);
        let w = 0.01;
        let v: Vec<[f64; 3]> = x.iter().map(|p| [-w * p[1], w * p[0], 0.0]).collect();
        let (f, e) = run(&mut bt, &mat, &x, &v, 1e-3);
        assert!((bt.stress[2].0[0] + 2e6).abs() < 1e-6);
        assert!(bt.stress[0].0[0].abs() < 1e-6 && bt.stress[3].0[0].abs() < 1e-6);
        assert!(e.internal.abs() < 1e-12 && e.hourglass.abs() < 1e-20);
        for a in 0..8 {
            assert!(f[0][a].0[0].abs() < 1e-6 && f[1][a].0[0].abs() < 1e-6);
        }
    }

    #[test]
    fn shear_stress_rotates_with_the_spin() {
        // sigma_xz under a spin about z turns into sigma_yz: d(sigma_yz) =
        // w dt sigma_xz (Jaumann rate).
        let x = distorted();
        let mat = Elastic::new(Isotropic {
            e: 30e9,
            nu: 0.2,
            density: 2400.0,
        });
        let mut bt = batch_of(&x, 0.0);
        bt.stress[5] = F4::splat(1e6);
        let w = 0.02;
        let dt = 1e-3;
        let v: Vec<[f64; 3]> = x.iter().map(|p| [-w * p[1], w * p[0], 0.0]).collect();
        run(&mut bt, &mat, &x, &v, dt);
        assert!((bt.stress[4].0[0] - w * dt * 1e6).abs() < 1e-6);
        assert!((bt.stress[5].0[0] - 1e6).abs() < 1e-6);
    }

    #[test]
    fn hourglass_mode_is_resisted_and_linear_fields_are_not() {
        let mut x = [[0.0; 3]; 8];
        for a in 0..8 {
            for i in 0..3 {
                x[a][i] = 0.5 * XI[a][i];
            }
        }
        let mat = Elastic::new(Isotropic {
            e: 30e9,
            nu: 0.2,
            density: 2400.0,
        });
        let mut bt = batch_of(&x, 1e8);
        // u_x = c eta zeta: no mean strain, pure hourglass.
        let v: Vec<[f64; 3]> = (0..8).map(|a| [GAMMA[0][a], 0.0, 0.0]).collect();
        let (f, e) = run(&mut bt, &mat, &x, &v, 1e-6);
        for s in bt.stress {
            assert!(s.0[0].abs() < 1e-9);
        }
        // Q = k dt q with q = sum v gamma = 8; f = Q gamma.
        let q = 1e8 * 1e-6 * 8.0;
        for a in 0..8 {
            assert!((f[0][a].0[0] - q * GAMMA[0][a]).abs() < 1e-9);
        }
        assert!((e.hourglass - 0.5 * q * 8.0 * 1e-6).abs() < 1e-12);
    }

    /// Elastic, with a retained stiffness set by each update: a stand-in
    /// for a damaging material.
    struct Softened {
        elastic: Elastic,
        keep: f64,
    }

    impl SolidMaterial for Softened {
        type State = f64;

        fn initial(&self) -> Isotropic {
            self.elastic.initial()
        }

        fn update(&self, state: &mut [f64; LANES], deps: &Sym6, h: F4, stress: &mut Sym6) {
            self.elastic.update(&mut [(); LANES], deps, h, stress);
            *state = [self.keep; LANES];
        }

        fn retained_stiffness(&self, state: &[f64; LANES]) -> F4 {
            F4(*state)
        }
    }

    #[test]
    fn hourglass_stiffness_follows_the_lowest_retained_stiffness() {
        // Q = keep k u: the hourglass force is the secant force of the
        // damaged element, for the accumulated mode displacement u.
        let mut x = [[0.0; 3]; 8];
        for a in 0..8 {
            for i in 0..3 {
                x[a][i] = 0.5 * XI[a][i];
            }
        }
        let elastic = Elastic::new(Isotropic {
            e: 30e9,
            nu: 0.2,
            density: 2400.0,
        });
        let mut bt: HexBatch<f64> = HexBatch {
            nodes: batch_of(&x, 0.0).nodes,
            len: LANES,
            stress: [F4::ZERO; 6],
            strain: [F4::ZERO; 6],
            hg: [[F4::ZERO; 4]; 3],
            hg_k: F4::splat(1e8),
            hg_keep: F4::splat(1.0),
            char_len: F4::splat(1.0),
            bv1: F4::ZERO,
            bv2: F4::ZERO,
            mask: F4([1.0, 0.0, 0.0, 0.0]),
            state: [0.0; LANES],
        };
        let dt = 1e-6;
        let moving: Vec<[f64; 3]> = (0..8).map(|a| [GAMMA[0][a], 0.0, 0.0]).collect();
        let still = vec![[0.0; 3]; 8];
        let q1 = 1e8 * dt * 8.0;
        let mut hourglass = 0.0;
        // (keep of the material, mode moving?, expected Q / q1)
        for (keep, v, expected) in [
            (1.0, &moving, 1.0),
            (0.5, &still, 0.5),
            (1.0, &still, 0.5),
            (0.5, &moving, 1.0),
            (0.25, &still, 0.5),
        ] {
            let mat = Softened { elastic, keep };
            let (f, e) = run(&mut bt, &mat, &x, v, dt);
            hourglass += e.hourglass;
            let q = bt.hg[0][0].0[0];
            assert!((q - expected * q1).abs() < 1e-12 * q1, "{q} vs {expected}");
            for a in 0..8 {
                assert!((f[0][a].0[0] - q * GAMMA[0][a]).abs() < 1e-9);
            }
        }
        assert_eq!(bt.hg_keep.0[0], 0.25);
        // Work done on the mode: q1 over dt 8, then (q1/2 + q1)/2 over dt 8.
        let work = 0.5 * q1 * 8.0 * dt + 0.75 * q1 * 8.0 * dt;
        assert!((hourglass - work).abs() < 1e-12 * work);
    }

    #[test]
    fn coefficients_use_the_hourglass_base_vectors() {
        let p: [F4; 8] = std::array::from_fn(|a| F4::splat((a * a) as f64 + 0.5 * a as f64));
        let c = coefficients(&p);
        for (al, g) in GAMMA.iter().enumerate() {
            let dot: f64 = (0..8).map(|a| g[a] * p[a].0[0]).sum();
            assert!((c[3 + al].0[0] - dot / 8.0).abs() < 1e-14);
        }
        for k in 0..3 {
            let dot: f64 = (0..8).map(|a| XI[a][k] * p[a].0[0]).sum();
            assert!((c[k].0[0] - dot / 8.0).abs() < 1e-14);
        }
        // expand is the transpose: sum_a f_a p_a = sum_k F_k (8 c_k).
        let fk: [F4; 7] = std::array::from_fn(|k| F4::splat(1.0 + k as f64));
        let f = expand(&fk);
        let lhs: f64 = (0..8).map(|a| f[a].0[0] * p[a].0[0]).sum();
        let rhs: f64 = (0..7).map(|k| fk[k].0[0] * 8.0 * c[k].0[0]).sum();
        assert!((lhs - rhs).abs() < 1e-10);
    }

    #[test]
    fn forces_match_the_flanagan_belytschko_formulas() {
        // Reference: gamma = Gamma - (1/V)(Gamma . x_i) b_i, q = v . gamma,
        // f = sigma b + Q gamma, on a distorted element with arbitrary
        // velocities and a prior stress and hourglass state.
        let x = distorted();
        let mat = Elastic::new(Isotropic {
            e: 30e9,
            nu: 0.2,
            density: 2400.0,
        });
        let mut bt = batch_of(&x, 3e8);
        bt.stress = [1e6, -2e6, 0.5e6, 0.3e6, -0.1e6, 0.2e6].map(F4::splat);
        for i in 0..3 {
            for al in 0..4 {
                bt.hg[i][al] = F4::splat(100.0 * (i as f64 + 1.0) - 37.0 * al as f64);
            }
        }
        let v: Vec<[f64; 3]> = (0..8)
            .map(|a| {
                [
                    0.1 * (a as f64).sin(),
                    0.2 * (a as f64 * 1.3).cos(),
                    -0.05 * a as f64,
                ]
            })
            .collect();
        let dt = 1e-6;
        let q0 = bt.hg;
        let (b, vol) = gradients(&lanes(&x));
        let vol = vol.0[0];
        let (f, _) = run(&mut bt, &mat, &x, &v, dt);
        let mut gam = [[0.0; 8]; 4];
        for al in 0..4 {
            for a in 0..8 {
                let mut proj = 0.0;
                for i in 0..3 {
                    let gx: f64 = (0..8).map(|c| GAMMA[al][c] * x[c][i]).sum();
                    proj += b[i][a].0[0] * gx;
                }
                gam[al][a] = GAMMA[al][a] - proj / vol;
            }
        }
        let s = bt.stress.map(|c| c.0[0]);
        let sig = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
        for i in 0..3 {
            let mut q_new = [0.0; 4];
            for al in 0..4 {
                let q: f64 = (0..8).map(|a| v[a][i] * gam[al][a]).sum();
                q_new[al] = q0[i][al].0[0] + 3e8 * dt * q;
                assert!((bt.hg[i][al].0[0] - q_new[al]).abs() < 1e-9 * q_new[al].abs().max(1.0));
            }
            for a in 0..8 {
                let mut r = 0.0;
                for j in 0..3 {
                    r += sig[i][j] * b[j][a].0[0];
                }
                for al in 0..4 {
                    r += q_new[al] * gam[al][a];
                }
                assert!(
                    (f[i][a].0[0] - r).abs() < 1e-9 * r.abs().max(1.0),
                    "f[{i}][{a}]"
                );
            }
        }
    }
}
