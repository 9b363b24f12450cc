//! `x^y` and `e^x`: libm, std (glibc on Linux) and this crate's `Scalar`
//! implementations (`src/scalar/fastmath`), side by side.
//!
//! Inputs are the models' domain: `x` log-uniform in [1e-3, 1.5) and `y` in
//! [0.5, 5) for the powers (|z|^n with z normalised near 1), `x` in [-10, 10) for
//! the exponentials. Two measures per function:
//!
//! * `throughput`: independent calls over a table of 1024 inputs (what a batch of
//!   elements costs);
//! * `latency`: each call's argument depends on the previous result (through an
//!   integer AND with a zero the compiler cannot see), as in the stages of one
//!   Runge-Kutta step.
//!
//! Run with `cargo bench --bench math`.

use criterion::{criterion_group, criterion_main, Criterion};
use hysteresis::Scalar;
use std::hint::black_box;

const N: usize = 1024;

/// SplitMix64 draws in [0, 1).
fn draws(seed: u64) -> impl Iterator<Item = f64> {
    let mut s = seed;
    core::iter::from_fn(move || {
        s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        Some(((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64)
    })
}

struct Inputs {
    base: Vec<f64>,
    expo: Vec<f64>,
    arg: Vec<f64>,
}

fn inputs() -> Inputs {
    let mut d = draws(7);
    let mut next = move || d.next().unwrap_or(0.5);
    let base = (0..N).map(|_| 10f64.powf(-3.0 + 3.176 * next())).collect();
    let expo = (0..N).map(|_| 0.5 + 4.5 * next()).collect();
    let arg = (0..N).map(|_| -10.0 + 20.0 * next()).collect();
    Inputs { base, expo, arg }
}

/// Moving a float through its bits (for the latency chain).
trait Bits: Copy + 'static {
    fn bits(self) -> u64;
    fn from_bits(b: u64) -> Self;
}
impl Bits for f64 {
    fn bits(self) -> u64 {
        self.to_bits()
    }
    fn from_bits(b: u64) -> Self {
        f64::from_bits(b)
    }
}
impl Bits for f32 {
    fn bits(self) -> u64 {
        self.to_bits() as u64
    }
    fn from_bits(b: u64) -> Self {
        f32::from_bits(b as u32)
    }
}

/// Throughput and latency of one binary function `f` on the tables.
fn bench2<T: Bits>(
    c: &mut Criterion,
    group: &str,
    name: &str,
    xs: &[T],
    ys: &[T],
    f: impl Fn(T, T) -> T,
) {
    let mut g = c.benchmark_group(group);
    let mut i = 0;
    g.bench_function(format!("{name}/throughput"), |b| {
        b.iter(|| {
            i = (i + 1) % N;
            f(black_box(xs[i]), black_box(ys[i]))
        })
    });
    let zero = black_box(0u64);
    let mut prev = xs[0];
    g.bench_function(format!("{name}/latency"), |b| {
        b.iter(|| {
            i = (i + 1) % N;
            let x = T::from_bits(xs[i].bits() | (prev.bits() & zero));
            prev = f(x, ys[i]);
            prev
        })
    });
    g.finish();
}

fn math(c: &mut Criterion) {
    let inp = inputs();
    let ones = vec![0.0f64; N];
    let (b32, e32, a32): (Vec<f32>, Vec<f32>, Vec<f32>) = (
        inp.base.iter().map(|&v| v as f32).collect(),
        inp.expo.iter().map(|&v| v as f32).collect(),
        inp.arg.iter().map(|&v| v as f32).collect(),
    );
    let ones32 = vec![0.0f32; N];

    let (b, e, a) = (&inp.base, &inp.expo, &inp.arg);
    bench2(c, "f64 pow", "libm", b, e, libm::pow);
    bench2(c, "f64 pow", "std", b, e, f64::powf);
    bench2(c, "f64 pow", "fastmath", b, e, <f64 as Scalar>::powf);

    bench2(c, "f64 exp", "libm", a, &ones, |x, _| libm::exp(x));
    bench2(c, "f64 exp", "std", a, &ones, |x, _| x.exp());
    bench2(c, "f64 exp", "fastmath", a, &ones, |x, _| Scalar::exp(x));

    bench2(c, "f32 powf", "libm", &b32, &e32, libm::powf);
    bench2(c, "f32 powf", "std", &b32, &e32, f32::powf);
    bench2(c, "f32 powf", "fastmath", &b32, &e32, <f32 as Scalar>::powf);

    bench2(c, "f32 expf", "libm", &a32, &ones32, |x, _| libm::expf(x));
    bench2(c, "f32 expf", "std", &a32, &ones32, |x, _| x.exp());
    bench2(c, "f32 expf", "fastmath", &a32, &ones32, |x, _| {
        Scalar::exp(x)
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(300))
        .measurement_time(std::time::Duration::from_secs(1));
    targets = math
}
criterion_main!(benches);
