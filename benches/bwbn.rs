//! Host speed of the BWBN element in f64: steps per second on the OpenSees
//! reference history (3601 displacement steps, 200 a cycle, 18 cycles up to
//! 8 mm), for plain Bouc-Wen, pinching only (OpenSees' `BWBN`) and all four
//! thesis effects, each with the default integrator (plain Bouc-Wen summed as
//! series, `Method::Series`: force within 4.6e-11 of peak of the converged
//! answer, `tests/bwbn_series.rs`; with an effect on, Dormand-Prince 5(4):
//! within 1e-6, `tests/bwbn_opensees.rs`) and with OpenSees' own scheme (one
//! backward-Euler step per increment); plain Bouc-Wen also with Dormand-Prince,
//! its default before `Series`, and summed as series at 1e-6, the loosest
//! tolerance that keeps the accuracy (1.8e-7 of peak against 1e-6).
//!
//! `cargo bench --bench bwbn`; `benches/bwbn-vs-opensees.sh` runs it beside
//! openseespy on the same history.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hysteresis::bwbn::{Bwbn, BwbnParams, Control, EffectKind, EffectSet, Method, ZuRule};
use hysteresis::Element;
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;

/// The reference cases' parameters (`cases.json`) with the effects of `set`,
/// Zu by OpenSees' rule.
fn params(set: EffectSet) -> BwbnParams<f64> {
    common::reference_params(set).with_zu_rule(ZuRule::OpenSees)
}

fn bench(c: &mut Criterion) {
    let h = common::reference_history();
    let pinching = EffectSet::NONE.with(EffectKind::Pinching);
    let cases = [
        ("bw", EffectSet::NONE),
        ("bw+pinching", pinching),
        ("bwbn (all four)", EffectSet::BWBN),
    ];
    let dp54 = Control {
        method: Method::Dp54,
        ..Control::default_for()
    };
    let schemes = [
        ("default", Control::default_for()),
        ("dp54", dp54),
        ("opensees-scheme", Control::opensees(1e-8, 100)),
        // The loosest tolerance of `Series` within 1e-6 of peak force on this
        // history (1.8e-7, `tests/bwbn_series.rs`); plain Bouc-Wen only.
        (
            "series-1e-6",
            Control {
                tol: 1e-6,
                ..Control::default_for()
            },
        ),
    ];
    let mut group = c.benchmark_group("bwbn_reference_history_f64");
    group.throughput(Throughput::Elements(h.len() as u64));
    for (name, set) in cases {
        let p = params(set);
        for (scheme, control) in schemes {
            // With an effect on, `Series` at any tolerance is Dormand-Prince:
            // only the default and OpenSees' scheme are run.
            if control != Control::default_for()
                && control.method != Method::BackwardEuler
                && set != EffectSet::NONE
            {
                continue;
            }
            group.bench_with_input(BenchmarkId::new(name, scheme), &h, |b, h| {
                b.iter(|| {
                    let mut el = Bwbn::with_extra(p, (), control).unwrap();
                    let mut acc = 0.0;
                    for &u in h {
                        acc += el.set_trial(black_box(u)).expect("step").force;
                        el.commit();
                    }
                    acc
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
