//! Elastic checks of the solver against closed forms (issue 7): torsion of
//! circular and square columns, axial stiffness with and without bars,
//! cantilever bending, hourglass energy, mesh convergence, and bit-identical
//! results on one and two threads.

use super::explicit::{dof, Control, Damping, Energies, Solver};
use super::history::{History, Interpolation};
use super::material::{Elastic, ElasticBar, Isotropic};
use super::mesh::{Mesh, Section};
use super::model::{Model, Settings, TimeStep};
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
#[allow(clippy::too_many_arguments)]
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
    let mut s = Solver::new(model, controls, threads).expect("a thread pool");
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
/// `beta = 1/3 - (64 / pi^5) sum_n tanh((2n-1) pi / 2) / (2n-1)^5` (the
/// series for a rectangle with equal sides; `beta = 0.1406`).
fn square_torsion_constant(b: f64) -> f64 {
    let mut s = 0.0;
    for n in 0..50 {
        let m = (2 * n + 1) as f64;
        s += (m * PI / 2.0).tanh() / m.powi(5);
    }
    b.powi(4) * (1.0 / 3.0 - 64.0 / PI.powi(5) * s)
}

fn circle_ksv(r: f64, l: f64) -> f64 {
    CONCRETE.shear_modulus() * PI * r.powi(4) / 2.0 / l
}

fn assert_quasi_static(v: &Verdict) {
    assert!(v.failures().is_empty(), "{:?}", v.failures());
}

#[test]
fn circular_column_torsion_matches_saint_venant() {
    let (r, l, h) = (0.305, 0.25, 0.025);
    let mesh = Mesh::extrude(Section::circle(r, h), l, h);
    let out = ramp(
        mesh,
        CONCRETE,
        &[],
        Settings::default(),
        dof::RZ,
        1e-3,
        0.01,
        2,
    );
    let ratio = out.stiffness / circle_ksv(r, l);
    eprintln!("circle 25 mm: K/(GJ/L) = {ratio:.5}, {:?}", out.verdict);
    assert!((ratio - 1.0).abs() < 0.01, "K / (GJ/L) = {ratio}");
    assert!(out.verdict.max_hourglass_share < 0.05);
    assert_quasi_static(&out.verdict);
    // The base resists what the top applies.
    assert!((out.base_ratio - 1.0).abs() < 1e-3, "{}", out.base_ratio);
}

#[test]
fn square_column_torsion_is_saint_venant_stiffened_by_warping_restraint() {
    // TP-91's section and effective height; the fixed base and rigid top
    // restrain warping, which stiffens the column a little (about 1.01
    // K_SV at this slenderness, issue 7).
    let (b, l, h) = (0.4, 1.35, 0.025);
    let k_sv = CONCRETE.shear_modulus() * square_torsion_constant(b) / l;
    let mesh = Mesh::extrude(Section::square(b, h), l, h);
    let out = ramp(
        mesh,
        CONCRETE,
        &[],
        Settings::default(),
        dof::RZ,
        1e-3,
        0.02,
        2,
    );
    let ratio = out.stiffness / k_sv;
    eprintln!("square 25 mm: K/K_SV = {ratio:.5}, {:?}", out.verdict);
    assert!((1.0..1.02).contains(&ratio), "K / K_SV = {ratio}");
    assert!(out.verdict.final_hourglass_share < 0.05);
    assert_quasi_static(&out.verdict);
}

#[test]
fn axial_stiffness_with_embedded_bars_is_the_transformed_section() {
    // nu = 0: no Poisson restraint at the ends, so a uniform strain is
    // exact and K = (Ec Ag + Es As) / L (bars embedded without removing
    // concrete, as ABAQUS' embedded elements).
    let (b, l, h) = (0.2, 0.4, 0.025);
    let mat = Isotropic {
        nu: 0.0,
        ..CONCRETE
    };
    let d: f64 = 0.016;
    let area = PI * d * d / 4.0;
    let c = b / 2.0 - 0.04;
    let bars = BarSet {
        name: "longitudinal".into(),
        area,
        bars: [(-c, -c), (c, -c), (c, c), (-c, c)]
            .iter()
            .map(|&(x, y)| super::rebar::vertical(x, y, 0.0, l, h))
            .collect(),
    };
    let mesh = Mesh::extrude(Section::square(b, h), l, h);
    let out = ramp(
        mesh,
        mat,
        &[bars],
        Settings::default(),
        dof::UZ,
        -2e-5,
        0.004,
        2,
    );
    let k = (mat.e * b * b + 200e9 * 4.0 * area) / l;
    eprintln!(
        "axial: K/K_exact = {:.6}, base/top {:.6}",
        out.stiffness / k,
        out.base_ratio
    );
    assert!(
        (out.stiffness / k - 1.0).abs() < 2e-3,
        "{}",
        out.stiffness / k
    );
    let strain = out.solver.model.truss_state[0].strain;
    assert!(
        (strain / (-2e-5 / l) - 1.0).abs() < 2e-3,
        "bar strain {strain}"
    );
    assert!((out.base_ratio - 1.0).abs() < 2e-3);
    assert_quasi_static(&out.verdict);
}

#[test]
fn cantilever_bending_matches_timoshenko() {
    // Fixed base, lateral displacement of the rigid top, top rotations
    // free: tip stiffness 1 / (L^3 / 3EI + L / (kappa G A)) with Cowper's
    // kappa = 10 (1 + nu) / (12 + 11 nu) for a rectangle. The fixed base
    // also restrains the Poisson contraction, which 3D elasticity has and
    // beam theory has not: a few parts per thousand at L / b = 5.
    let (b, l, h): (f64, f64, f64) = (0.2, 1.0, 0.025);
    let e = CONCRETE.e;
    let nu = CONCRETE.nu;
    let i = b.powi(4) / 12.0;
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let k = 1.0 / (l.powi(3) / (3.0 * e * i) + l / (kappa * CONCRETE.shear_modulus() * b * b));
    let mesh = Mesh::extrude(Section::square(b, h), l, h);
    let out = ramp(
        mesh,
        CONCRETE,
        &[],
        Settings::default(),
        dof::UX,
        1e-4,
        0.08,
        2,
    );
    let ratio = out.stiffness / k;
    eprintln!("cantilever: K/K_Timoshenko = {ratio:.5}, {:?}", out.verdict);
    assert!((ratio - 1.0).abs() < 0.02, "K / K_Timoshenko = {ratio}");
    assert!(out.verdict.final_hourglass_share < 0.05);
    assert_quasi_static(&out.verdict);
}

#[test]
fn patch_test_linear_field_gives_uniform_stress_and_no_interior_force() {
    let mut mesh = Mesh::extrude(Section::square(0.3, 0.1), 0.3, 0.1);
    // Move the interior nodes off the grid.
    let interior: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&n| {
            let p = mesh.nodes[n];
            p[0].abs() < 0.149 && p[1].abs() < 0.149 && p[2] > 0.001 && p[2] < 0.299
        })
        .collect();
    assert_eq!(interior.len(), 8);
    for (k, &n) in interior.iter().enumerate() {
        let w = 0.02 * (k as f64 + 1.0);
        mesh.nodes[n][0] += w * (k as f64).sin();
        mesh.nodes[n][1] -= 0.6 * w * (k as f64).cos();
        mesh.nodes[n][2] += 0.4 * w;
    }
    let model = Model::new(
        mesh,
        Elastic::new(CONCRETE),
        &[],
        Vec::<ElasticBar>::new(),
        Default::default(),
        Settings {
            bulk_linear: 0.0,
            bulk_quadratic: 0.0,
            ..Settings::default()
        },
    );
    let dt = model.dt();
    let mut s =
        Solver::new(model, std::array::from_fn(|_| Control::free()), 1).expect("a thread pool");
    let a = [
        [1e-4, 2e-5, -3e-5],
        [4e-5, -2e-4, 1e-5],
        [-1e-5, 3e-5, 5e-5],
    ];
    for n in 0..s.v.len() {
        let x = s.x[n];
        s.v[n] = std::array::from_fn(|i| (a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2]) / dt);
    }
    s.step();
    let (l, m) = CONCRETE.lame();
    let tr = a[0][0] + a[1][1] + a[2][2];
    let want = [
        l * tr + 2.0 * m * a[0][0],
        l * tr + 2.0 * m * a[1][1],
        l * tr + 2.0 * m * a[2][2],
        m * (a[0][1] + a[1][0]),
        m * (a[1][2] + a[2][1]),
        m * (a[2][0] + a[0][2]),
    ];
    for bt in &s.model.batches {
        for lane in 0..bt.len {
            for c in 0..6 {
                let got = bt.stress[c].0[lane];
                assert!(
                    (got - want[c]).abs() < 1e-9 * 1e6,
                    "component {c}: {got} vs {}",
                    want[c]
                );
            }
            for al in 0..4 {
                for i in 0..3 {
                    assert!(bt.hg[i][al].0[lane].abs() < 1e-6);
                }
            }
        }
    }
    let scale = s.f_int.iter().fold(0.0f64, |m, f| {
        m.max(f[0].abs().max(f[1].abs()).max(f[2].abs()))
    });
    for &n in &interior {
        for i in 0..3 {
            assert!(
                s.f_int[n][i].abs() < 1e-10 * scale,
                "node {n}: {:?}",
                s.f_int[n]
            );
        }
    }
}

#[test]
fn torsion_converges_with_mesh_refinement() {
    // A circle of 300 mm, 200 mm high: the error against GJ/L shrinks with
    // every halving of the element size.
    let (r, l) = (0.15, 0.2);
    let mut errors = Vec::new();
    for h in [0.05, 0.025, 0.0125] {
        let mesh = Mesh::extrude(Section::circle(r, h), l, h);
        let out = ramp(
            mesh,
            CONCRETE,
            &[],
            Settings::default(),
            dof::RZ,
            1e-3,
            0.005,
            2,
        );
        let err = out.stiffness / circle_ksv(r, l) - 1.0;
        eprintln!(
            "h = {:.4} m: {} elements, K/(GJ/L) - 1 = {err:+.5}, hourglass share {:.4}",
            h,
            out.solver.model.elements(),
            out.verdict.final_hourglass_share
        );
        assert_quasi_static(&out.verdict);
        errors.push(err.abs());
    }
    assert!(errors[1] < errors[0] && errors[2] < errors[1], "{errors:?}");
    assert!(errors[2] < 0.005, "{errors:?}");
}

#[test]
fn one_and_two_threads_give_bit_identical_results() {
    let (r, l, h) = (0.2, 0.3, 0.05);
    let mesh = Mesh::extrude(Section::circle(r, h), l, h);
    let sets = vec![
        BarSet {
            name: "longitudinal".into(),
            area: 2e-4,
            bars: (0..8)
                .map(|k| {
                    let th = k as f64 * PI / 4.0;
                    super::rebar::vertical(0.15 * th.cos(), 0.15 * th.sin(), 0.0, l, 0.025)
                })
                .collect(),
        },
        BarSet {
            name: "transverse".into(),
            area: 1e-4,
            bars: vec![super::rebar::helix(0.16, 0.05, 0.0, l, 0.025)],
        },
    ];
    let run = |threads| {
        let emb = embed(&mesh, &sets).expect("inside");
        let steel = vec![
            ElasticBar {
                e: 200e9,
                density: 7800.0
            };
            2
        ];
        let model = Model::new(
            mesh.clone(),
            Elastic::new(CONCRETE),
            &sets,
            steel,
            emb,
            Settings::default(),
        );
        let mut controls: [Control; 6] = std::array::from_fn(|_| Control::free());
        controls[dof::RZ] = Control::Motion(History::new(
            vec![(0.0, 0.0), (2e-3, 1e-3)],
            Interpolation::SmoothStep,
        ));
        controls[dof::UZ] = Control::Force(History::new(
            vec![(0.0, 0.0), (1e-3, -1e5)],
            Interpolation::SmoothStep,
        ));
        let mut s = Solver::new(model, controls, threads).expect("a thread pool");
        for _ in 0..300 {
            s.step();
        }
        s
    };
    let (a, b) = (run(1), run(2));
    assert!(a.energy.strain > 0.0);
    let bits = |v: &[[f64; 3]]| {
        v.iter()
            .flat_map(|p| p.map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&a.x), bits(&b.x));
    assert_eq!(bits(&a.v), bits(&b.v));
    assert_eq!(a.energy.strain.to_bits(), b.energy.strain.to_bits());
    assert_eq!(
        a.top.reaction[dof::RZ].to_bits(),
        b.top.reaction[dof::RZ].to_bits()
    );
    for (x, y) in a.model.truss_state.iter().zip(&b.model.truss_state) {
        assert_eq!(x.stress.to_bits(), y.stress.to_bits());
    }
}

#[test]
fn mass_scaling_lifts_the_bar_step_and_reports_the_added_mass() {
    let (b, l, h) = (0.2, 0.3, 0.025);
    let mesh = Mesh::extrude(Section::square(b, h), l, h);
    let bars = vec![BarSet {
        name: "longitudinal".into(),
        area: 2e-4,
        bars: vec![super::rebar::vertical(0.05, 0.05, 0.0, l, h)],
    }];
    let steel = ElasticBar {
        e: 200e9,
        density: 7800.0,
    };
    let build = |settings| {
        let emb = embed(&mesh, &bars).expect("inside");
        Model::new(
            mesh.clone(),
            Elastic::new(CONCRETE),
            &bars,
            vec![steel],
            emb,
            settings,
        )
    };
    // Mass scaling acts on the elements' own steps; measured here on the
    // element-by-element estimate.
    let element = Settings {
        time_step: TimeStep::Element,
        ..Settings::default()
    };
    let plain = build(element);
    // The 25 mm bar segments set the step, below the concrete's.
    assert!(plain.limits.truss < plain.limits.hex);
    assert_eq!(plain.added_mass, 0.0);
    assert!((plain.dt() - 0.9 * plain.limits.truss).abs() < 1e-18);
    let target = plain.limits.hex;
    let scaled = build(Settings {
        mass_scaling_dt: Some(target),
        ..element
    });
    assert!((scaled.dt() - 0.9 * target).abs() < 1e-15 * target);
    let c = (200e9f64 / 7800.0).sqrt();
    let want: f64 = scaled
        .embedding
        .trusses
        .iter()
        .map(|t| 7800.0 * t.area * t.length * ((target * c / t.length).powi(2) - 1.0))
        .sum();
    assert!(
        (scaled.added_mass - want).abs() < 1e-9 * want,
        "{} vs {want}",
        scaled.added_mass
    );
    let total: f64 = scaled.mass.iter().sum();
    assert!((total - scaled.physical_mass - scaled.added_mass).abs() < 1e-9 * total);
}

/// An axial force on a column brought on by a smooth step over `ramp` and
/// held to `end`, with the preload damping `damping`: the top's axial
/// displacement and the energies at `end`.
fn axial_preload(ramp: f64, end: f64, damping: Option<Damping>) -> ([f64; 6], Energies) {
    let mesh = Mesh::extrude(Section::square(0.2, 0.05), 0.6, 0.05);
    let model: Model<Elastic, ElasticBar> = Model::new(
        mesh,
        Elastic::new(CONCRETE),
        &[],
        vec![],
        Default::default(),
        Settings::default(),
    );
    let mut controls: [Control; 6] = std::array::from_fn(|_| Control::free());
    controls[dof::UZ] = Control::Force(History::new(
        vec![(0.0, 0.0), (ramp, -1e6)],
        Interpolation::SmoothStep,
    ));
    controls[dof::RZ] = Control::Motion(History::constant(0.0));
    let mut s = Solver::new(model, controls, 1).expect("a thread pool");
    s.damping = damping;
    while s.t < end {
        s.step();
    }
    (s.top.displacement(), s.energy)
}

#[test]
fn a_damped_preload_reaches_the_static_state_in_a_few_axial_periods() {
    // First axial mode of the fixed-free column: T1 = 4 L / c.
    let (l, c) = (0.6, (CONCRETE.e / CONCRETE.density).sqrt());
    let t1 = 4.0 * l / c;
    let omega = 2.0 * PI / t1;
    // The static state: an undamped ramp over 30 periods (its residual
    // vibration, about 60 / (omega T)^3 of the displacement, is 1e-6).
    let (slow, e_slow) = axial_preload(30.0 * t1, 30.0 * t1, None);
    // Over 1.5 periods and held one more: undamped, the residual vibration
    // is percents; critically damped, the state is within 0.1%.
    let (fast, _) = axial_preload(1.5 * t1, 2.5 * t1, None);
    let damping = Damping {
        alpha: 2.0 * omega,
        until: 2.5 * t1,
    };
    let (relaxed, e) = axial_preload(1.5 * t1, 2.5 * t1, Some(damping));
    let off = |u: [f64; 6]| (u[dof::UZ] / slow[dof::UZ] - 1.0).abs();
    assert!(off(relaxed) < 2e-3, "relaxed: {}", off(relaxed));
    assert!(off(fast) > 5.0 * off(relaxed), "undamped: {}", off(fast));
    // The kinetic energy is nearly gone, and the damping's dissipation is
    // counted: the balance closes as in the slow run.
    assert!(e.kinetic < 1e-3 * e.internal(), "{e:?}");
    assert!(e.viscous > 0.1 * e.internal(), "{e:?}");
    assert!(e.imbalance().abs() < 1e-3 * e.work, "{e:?}");
    assert!(e_slow.imbalance().abs() < 1e-3 * e_slow.work, "{e_slow:?}");
}
