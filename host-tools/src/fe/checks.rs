//! Elastic checks of the solver against closed forms (issue 7): torsion of
//! circular and square columns, axial stiffness with and without bars,
//! cantilever bending, hourglass energy, mesh convergence, and bit-identical
//! results on one and two threads.

use super::explicit::{dof, Control, Solver};
use super::history::{History, Interpolation};
use super::material::{Elastic, ElasticBar, Isotropic};
use super::mesh::{Mesh, Section};
use super::model::{Model, Settings};
use super::quasi_static::{EnergyTrace, Verdict};
use super::rebar::{embed, BarSet};
use std::f64::consts::PI;

const CONCRETE: Isotropic = Isotropic {
    e: 25e9,
    nu: 0.2,
    density: 2400.0,
};

/// What a quasi-static ramp measured.
struct Ramp {
    /// Least-squares slope of reaction against motion over the part of the
    /// ramp beyond 20% of its amplitude.
    stiffness: f64,
    verdict: Verdict,
    /// Base reaction over top reaction at the end.
    base_ratio: f64,
    solver: Solver<Elastic, ElasticBar>,
}

/// Drives degree of freedom `k` of the top by a smooth step to `amp` over
/// `ramp` seconds (then holds for a fifth of that); every other degree of
/// freedom is free.
fn ramp(
    mesh: Mesh,
    mat: Isotropic,
    bars: &[BarSet],
    settings: Settings,
    k: usize,
    amp: f64,
    ramp: f64,
    threads: usize,
) -> Ramp {
    let emb = embed(&mesh, bars).expect("bars inside");
    let steel = vec![
        ElasticBar {
            e: 200e9,
            density: 7800.0
        };
        bars.len()
    ];
    let model = Model::new(mesh, Elastic::new(mat), bars, steel, emb, settings);
    let mut controls: [Control; 6] = std::array::from_fn(|_| Control::free());
    controls[k] = Control::Motion(History::new(
        vec![(0.0, 0.0), (ramp, amp)],
        Interpolation::SmoothStep,
    ));
    let mut s = Solver::new(model, controls, threads);
    let mut trace = EnergyTrace::default();
    let (mut sxy, mut sxx) = (0.0, 0.0);
    while s.t < 1.2 * ramp {
        s.step();
        trace.push(s.t, s.energy);
        let q = s.top.displacement()[k];
        if q.abs() >= 0.2 * amp.abs() {
            sxy += q * s.top.reaction[k];
            sxx += q * q;
        }
    }
    let base = if k == dof::RZ {
        s.base_torque()
    } else if k == dof::UZ {
        s.base_axial()
    } else {
        f64::NAN
    };
    Ramp {
        stiffness: sxy / sxx,
        verdict: trace.verdict(),
        base_ratio: base / s.top.reaction[k],
        solver: s,
    }
}

/// Saint-Venant torsion constant of a square of side `b`: `beta b^4` with
/// `beta = 1/3 - (64 / pi^5) sum tanh((2n-1) pi / 2) / (2n-1)^5`... in its
/// standard series form for a rectangle with `a = b`.
fn square_torsion_constant(b: f64) -> f64 {
    let mut s = 0.0;
    for n in 0..50 {
        let m = (2 * n + 1) as f64;
        s += (m * PI / 2.0).tanh() / m.powi(5);
    }
    b.powi(4) * (1.0 / 3.0 - 64.0 / PI.powi(5) * s)
}

#[test]
fn exploratory_circle() {
    for h in [0.05, 0.025] {
        let r = 0.305;
        let l = 0.25;
        let mesh = Mesh::extrude(Section::circle(r, h), l, h);
        let g = CONCRETE.shear_modulus();
        let k_sv = g * PI * r.powi(4) / 2.0 / l;
        let out = ramp(mesh, CONCRETE, &[], Settings::default(), dof::RZ, 1e-3, 0.01, 2);
        eprintln!(
            "h {h}: K/K_SV {:.5} base {:.5} {:?} dt {:?} el {}",
            out.stiffness / k_sv,
            out.base_ratio,
            out.verdict,
            out.solver.model.limits,
            out.solver.model.elements()
        );
    }
    eprintln!("square beta {}", square_torsion_constant(1.0));
}

#[test]
fn exploratory_square() {
    let b: f64 = 0.4;
    let l = 1.35;
    let k_sv = CONCRETE.shear_modulus() * square_torsion_constant(b) / l;
    for h in [0.05, 0.025] {
        for s in [0.3, 1.0, 3.0] {
            let mesh = Mesh::extrude(Section::square(b, h), l, h);
            let settings = Settings { hourglass_scale: s, ..Settings::default() };
            let out = ramp(mesh, CONCRETE, &[], settings, dof::RZ, 1e-3, 0.02, 2);
            eprintln!(
                "h {h} s {s}: K/K_SV {:.5} base {:.5} ke {:.4} hg {:.4} imb {:.2e}",
                out.stiffness / k_sv,
                out.base_ratio,
                out.verdict.max_ke_ie_ratio, out.verdict.max_hourglass_share, out.verdict.max_imbalance
            );
        }
    }
}
