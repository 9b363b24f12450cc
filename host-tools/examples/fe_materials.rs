//! The figure of `docs/fe.md`, "Materials (part 2)": uniaxial stress paths
//! of TP-91's concrete damaged plasticity and of its longitudinal steel,
//! with the laws they are built from dashed.
//!
//! Run from the repository root:
//! `cargo run --release -p hysteresis-host --example fe_materials`
//! (writes `docs/fe-materials.svg`).

use hyst::fe::concrete::{CdpState, ConcreteDamagedPlasticity, ConcreteParams};
use hyst::fe::material::{BarMaterial, Isotropic};
use hyst::fe::steel::HardeningSteel;
use hyst::report::{Axis, Figure, Panel, Series};
use std::path::PathBuf;

const FC: f64 = 28.3e6;
const STEPS: usize = 400;

/// Uniaxial stress along x through the strain `targets`; returns
/// (strain in mm/m, stress in MPa).
fn concrete_path(mat: &ConcreteDamagedPlasticity, targets: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (mut state, mut stress, mut eps) = (CdpState::default(), [0.0; 6], 0.0);
    let (mut x, mut y) = (vec![0.0], vec![0.0]);
    for &target in targets {
        let de = (target - eps) / STEPS as f64;
        for _ in 0..STEPS {
            let d = mat
                .step_with_free_stress(
                    &mut state,
                    &mut stress,
                    [de, 0.0, 0.0, 0.0, 0.0, 0.0],
                    &[1, 2],
                )
                .expect("uniaxial step");
            eps += d[0];
            x.push(eps * 1e3);
            y.push(stress[0] / 1e6);
        }
    }
    (x, y)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let elastic = Isotropic {
        e: 4700.0 * 28.3f64.sqrt() * 1e6,
        nu: 0.2,
        density: 2400.0,
    };
    let mat = ConcreteDamagedPlasticity::new(ConcreteParams::thesis(elastic, FC));
    let (e, ft, eps0) = (elastic.e, 0.1 * FC, mat.peak_strain());
    let eps_cr = ft / e;

    let mut fig = Figure::new(1050.0, 380.0);
    fig.title("TP-91 materials, uniaxial stress paths (compression negative)");
    fig.columns(3);

    let (x, y) = concrete_path(&mat, &[10.0 * eps_cr, 8.0 * eps_cr, 20.0 * eps_cr]);
    let law_x: Vec<f64> = (0..=200)
        .map(|i| eps_cr * (1.0 + 19.0 * i as f64 / 200.0))
        .collect();
    let law_y: Vec<f64> = law_x
        .iter()
        .map(|&s| ft * (eps_cr / s).powf(0.4) / 1e6)
        .collect();
    let law_x: Vec<f64> = law_x.iter().map(|s| s * 1e3).collect();
    let mut tension = Panel::new(
        Axis::linear("strain", "mm/m"),
        Axis::linear("stress", "MPa"),
    );
    tension.title("Concrete: crack, close, reopen");
    tension.series(Series::line("model", &x, &y)?);
    tension.series(
        Series::line("Greene (2006)", &law_x, &law_y)?
            .dash("5 4")
            .palette(1),
    );
    fig.panel(tension);

    let (x, y) = concrete_path(&mat, &[-1.5 * eps0, -1.1 * eps0, 2.0 * eps_cr, -1.9 * eps0]);
    let vc_x: Vec<f64> = (0..=200).map(|i| -1.9 * eps0 * i as f64 / 200.0).collect();
    let vc_y: Vec<f64> = vc_x
        .iter()
        .map(|&s| {
            let eta = -s / eps0;
            if -s * e <= 0.3 * FC {
                s * e / 1e6
            } else {
                -FC * (2.0 * eta - eta * eta) / 1e6
            }
        })
        .collect();
    let vc_x: Vec<f64> = vc_x.iter().map(|s| s * 1e3).collect();
    let mut compression = Panel::new(
        Axis::linear("strain", "mm/m"),
        Axis::linear("stress", "MPa"),
    );
    compression.title("Concrete: crush, unload, pull, crush");
    compression.series(Series::line("model", &x, &y)?);
    compression.series(
        Series::line("Vecchio-Collins", &vc_x, &vc_y)?
            .dash("5 4")
            .palette(1),
    );
    fig.panel(compression);

    let steel = HardeningSteel::thesis(354e6);
    let (mut p, mut s, mut eps) = (0.0, 0.0, 0.0);
    let (mut x, mut y) = (vec![0.0], vec![0.0]);
    for target in [0.02, -0.01, 0.03] {
        let de = (target - eps) / STEPS as f64;
        for _ in 0..STEPS {
            steel.update(&mut p, de, &mut s);
            eps += de;
            x.push(eps * 1e3);
            y.push(s / 1e6);
        }
    }
    let mut bar = Panel::new(
        Axis::linear("strain", "mm/m"),
        Axis::linear("stress", "MPa"),
    );
    bar.title("Steel: f_y = 354 MPa, H = 0.01 E");
    bar.series(Series::line("model", &x, &y)?);
    fig.panel(bar);

    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/fe-materials.svg");
    std::fs::write(&out, fig.to_svg())?;
    println!("wrote {}", out.display());
    Ok(())
}
