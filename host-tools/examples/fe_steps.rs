//! Runs a given number of explicit steps of the elastic square column of
//! the `fe_step` benchmark, for instruction counts under callgrind:
//!
//! ```text
//! valgrind --tool=callgrind target/release/examples/fe_steps 20 1
//! ```
//!
//! The difference between two step counts divided by the extra
//! element-steps is the per-element-step instruction count without setup.

use hyst::fe::explicit::{Control, Solver};
use hyst::fe::history::{History, Interpolation};
use hyst::fe::material::{Elastic, Isotropic};
use hyst::fe::mesh::{Mesh, Section};
use hyst::fe::model::{Model, Settings};
use hyst::fe::rebar::Embedding;

fn main() {
    let mut args = std::env::args().skip(1);
    let steps: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let threads: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let mesh = Mesh::extrude(Section::square(0.4, 0.025), 1.35, 0.025);
    let mat = Elastic::new(Isotropic {
        e: 25e9,
        nu: 0.2,
        density: 2400.0,
    });
    let model = Model::<_, hyst::fe::material::ElasticBar>::new(
        mesh,
        mat,
        &[],
        vec![],
        Embedding::default(),
        Settings::default(),
    );
    let mut controls: [Control; 6] = std::array::from_fn(|_| Control::free());
    controls[5] = Control::Motion(History::new(
        vec![(0.0, 0.0), (1e-3, 1e-4)],
        Interpolation::Linear,
    ));
    let mut s = Solver::new(model, controls, threads).expect("a thread pool");
    let start = std::time::Instant::now();
    for _ in 0..steps {
        s.step();
    }
    let el = s.model.elements() as f64 * steps as f64;
    println!(
        "{} elements, {steps} steps, {threads} threads: {:.1} ns per element-step, torque {:.6e} N m",
        s.model.elements(),
        start.elapsed().as_secs_f64() * 1e9 / el,
        s.top.reaction[5]
    );
}
