//! Wall time of one bounded least-squares fit of the thesis' Bouc-Wen example (section 4.4:
//! m = 500 kg, k = 6 kN/mm, F(t) = t sin(2 pi t) kN, 10 s at 100 Hz; alpha, beta, gamma, xi
//! and n identified, k known), started at 130 % and at 70 % of the truth. Issue target: at most
//! 10 ms a fit. `host-tools/tests/thesis_bw_example.rs` proves that these fits reach the truth.
//! Side by side: the Jacobian exact (one simulation in dual numbers, what `hyst fit` uses) and
//! by forward differences (one simulation per parameter, on all cores); the exact one with
//! trials simulated apart from their Jacobians (`jacobian_with_trial` off, as before
//! 2026-11-29); and the exact one with the stopping rule used before 2026-11-25 (`x_tol` 1e-10
//! instead of 1e-8).
//!
//!     cargo bench -p hysteresis-host --bench lsq_bw

use criterion::{criterion_group, criterion_main, Criterion};
use hyst::fit::lsq::{self, Options, Residuals};
use hyst::fit::problem::{LeastSquares, Problem};
use hyst::model::ModelSpec;
use std::collections::BTreeMap;
use std::hint::black_box;

#[path = "../tests/support/thesis_bw.rs"]
mod thesis_bw;
use thesis_bw::{record, TRUTH};

fn fit(c: &mut Criterion) {
    let p = Problem::new(ModelSpec::BW, record(), &[("k0".into(), 6.0)]).expect("a problem");
    let (lo, hi) = p.par.bounds();
    let differenced = |x: &[f64]| p.residuals(x);
    let exact = LeastSquares::new(&p);
    let mut group = c.benchmark_group("lsq bw thesis example");
    for factor in [1.3, 0.7] {
        let values: BTreeMap<&str, f64> = TRUTH.iter().map(|(k, v)| (*k, v * factor)).collect();
        let x0 = p.par.normalise(&values);
        let strict = Options {
            x_tol: 1e-10,
            ..Options::default()
        };
        let apart = Options {
            jacobian_with_trial: false,
            ..Options::default()
        };
        let variants: [(&str, &dyn Residuals, Options); 4] = [
            ("exact Jacobian", &exact, Options::default()),
            ("exact Jacobian, trials apart", &exact, apart),
            ("differenced Jacobian", &differenced, Options::default()),
            ("exact Jacobian, x_tol 1e-10", &exact, strict),
        ];
        for (name, f, opts) in variants {
            let s = lsq::minimize(f, &x0, &lo, &hi, opts).expect("a fit");
            eprintln!(
                "start {factor}x, {name}: {} iterations, {} simulations, NRMSE {:.1e}",
                s.iterations,
                s.evaluations,
                s.cost.sqrt()
            );
            group.bench_function(format!("start {factor}x truth, {name}"), |b| {
                b.iter(|| lsq::minimize(f, black_box(&x0), &lo, &hi, opts))
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = fit
}
criterion_main!(benches);
