//! The optimiser's own cost, without a model: NSGA-II on ZDT1 (30 variables, evaluation a few
//! nanoseconds), population 100. `initial population` is sampling, evaluating and sorting 100
//! members; `250 generations` is a whole run of 25,000 evaluations, so
//! (250 generations - initial population) / 249 is the cost of one generation: tournaments,
//! crossover, mutation, duplicate check, non-dominated sorting and crowding of 200 members.
//!
//!     cargo bench -p hysteresis-host --bench nsga2

use criterion::{criterion_group, criterion_main, Criterion};
use hyst::fit::nsga2::test_problems::{Zdt, ZdtKind};
use hyst::fit::nsga2::Nsga2;
use std::hint::black_box;

fn zdt1(c: &mut Criterion) {
    let problem = Zdt::new(ZdtKind::Zdt1, 30);
    let mut group = c.benchmark_group("nsga2 zdt1 pop 100");
    for generations in [1, 250] {
        let settings = Nsga2 {
            generations,
            parallel: false,
            seed: 1,
            ..Nsga2::default()
        };
        let name = if generations == 1 {
            "initial population".to_owned()
        } else {
            format!("{generations} generations")
        };
        group.bench_function(name, |b| {
            b.iter(|| settings.run(black_box(&problem)).expect("valid settings"))
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = zdt1
}
criterion_main!(benches);
