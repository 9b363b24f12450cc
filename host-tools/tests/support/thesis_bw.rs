//! The Bouc-Wen identification example of thesis section 4.4 (after Ortiz et
//! al. 2013): m = 500 kg, k = 6 kN/mm, F(t) = t sin(2 pi t) kN, true
//! alpha = 0.2, beta = 2, gamma = -1, xi = 0.05, n = 1.2; 10 s at 100 Hz.
//! Shared by the tests that fit it (`thesis_bw_example.rs`, `exact_jacobian.rs`,
//! `force_driven_cli.rs`, `force_between_samples.rs`) and `benches/lsq_bw.rs`.

use hyst::fit::experiment::{Between, Drive, Experiment};
use hysteresis::bwbn::{BoucWen, BwbnParams, Control, Method, Sdof};

/// 500 kg in kN s^2 / mm.
pub const MASS: f64 = 5e-4;

/// The identified parameters and their true values (k0 = 6 is known).
pub const TRUTH: [(&str, f64); 5] = [
    ("alpha", 0.2),
    ("beta", 2.0),
    ("gamma", -1.0),
    ("xi", 0.05),
    ("n", 1.2),
];

/// The record: the force and the displacement of the true oscillator,
/// integrated far more tightly than any fit does.
pub fn record() -> Experiment {
    let dt = 0.01;
    let force: Vec<f64> = (0..=1000)
        .map(|i| {
            let t = i as f64 * dt;
            t * (2.0 * std::f64::consts::PI * t).sin()
        })
        .collect();
    let base = BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).expect("valid truth");
    let tight = Control {
        method: Method::Dp54,
        tol: 1e-11,
        max_substeps: 5000,
    };
    let mut osc = Sdof::from_physical(BwbnParams::plain(base), MASS, 0.05)
        .expect("valid truth")
        .with_control(tight)
        .unwrap();
    let mut u = vec![0.0];
    for f in &force[1..] {
        u.push(osc.step(dt, f / MASS).expect("the truth simulates").u);
    }
    Experiment {
        input: force,
        output: u,
        drive: Drive::Force {
            dt,
            mass: MASS,
            between: Between::Linear,
        },
    }
}
