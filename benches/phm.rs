//! Host speed of the PHM element: steps per second on the OpenSees reference
//! history (3601 twist steps, 36 triangular cycles up to 8 mm, 72 reversals),
//! in each arithmetic. OpenSees' `Pinching4` takes about 0.24 us a step on
//! this kind of machine (see `../shared/data/opensees-reference/README.md`).
//!
//! `cargo bench --bench phm`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hysteresis::phm::{Coefficients, Phm, PhmParams};
use hysteresis::{Element, Fixed, Scalar};
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;

fn bench_arithmetic<S: Scalar>(c: &mut Criterion, h: &[f64]) {
    let p = |x: f64, y: f64| [S::from_f64(x), S::from_f64(y)];
    // The Pinching4 reference cases' primary curve.
    let params = PhmParams::<S, 4>::symmetric(
        &[p(1.0, 5.0), p(3.0, 6.3), p(6.0, 6.5), p(10.0, 5.0)],
        Coefficients::thesis(),
    )
    .unwrap();
    let twists: Vec<S> = h.iter().map(|&x| S::from_f64(x)).collect();
    let mut group = c.benchmark_group("phm_reference_history");
    group.throughput(Throughput::Elements(twists.len() as u64));
    group.bench_with_input(
        BenchmarkId::from_parameter(S::NAME),
        &twists,
        |b, twists| {
            b.iter(|| {
                let mut el: Phm<S, 4, 16> = Phm::new(params.clone());
                let mut acc = S::ZERO;
                for &x in twists {
                    acc += el.set_trial(black_box(x)).unwrap().force;
                    el.commit();
                }
                black_box(acc)
            })
        },
    );
    group.finish();
}

fn benches(c: &mut Criterion) {
    let h = common::reference_history();
    bench_arithmetic::<f64>(c, &h);
    bench_arithmetic::<f32>(c, &h);
    bench_arithmetic::<Fixed>(c, &h);
}

criterion_group!(phm, benches);
criterion_main!(phm);
