//! One explicit step of an elastic square column (400 mm, 1.35 m, 25 mm
//! hexahedra: 13,824 elements), on one and two threads. Throughput is in
//! elements, so criterion reports time per element-step.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hyst::fe::explicit::{Control, Solver};
use hyst::fe::material::{Elastic, ElasticBar, Isotropic};
use hyst::fe::mesh::{Mesh, Section};
use hyst::fe::model::{Model, Settings};
use hyst::fe::rebar::Embedding;

fn solver(threads: usize) -> Solver<Elastic, ElasticBar> {
    let mesh = Mesh::extrude(Section::square(0.4, 0.025), 1.35, 0.025);
    let mat = Elastic::new(Isotropic {
        e: 25e9,
        nu: 0.2,
        density: 2400.0,
    });
    let model = Model::new(
        mesh,
        mat,
        &[],
        vec![],
        Embedding::default(),
        Settings::default(),
    );
    let mut controls: [Control; 6] = std::array::from_fn(|_| Control::free());
    controls[5] = Control::Motion(hyst::fe::history::History::new(
        vec![(0.0, 0.0), (1e-3, 1e-4)],
        hyst::fe::history::Interpolation::Linear,
    ));
    let mut s = Solver::new(model, controls, threads).expect("a thread pool");
    for _ in 0..20 {
        s.step();
    }
    s
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("fe_elastic_hex_step");
    for threads in [1, 2] {
        let mut s = solver(threads);
        g.throughput(Throughput::Elements(s.model.elements() as u64));
        g.bench_function(format!("{threads}_thread"), |b| b.iter(|| s.step()));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
