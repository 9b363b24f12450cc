//! Instructions per call of the core's math on Cortex-M4F (and M3) under QEMU.
//!
//! Each [`Case`] runs its body over the 1024 inputs between `bench_start()` and
//! `bench_stop()`; the QEMU plugin in `shared/tools/qemu-insn` counts the
//! instructions in between, and `measure.sh` prints
//! `(case - baseline) / 1024` per case. To add a case (a BWBN step, say), append
//! a `Case` to [`CASES`]: a name and a function of the inputs that returns
//! something derived from every result (so nothing is optimised away).
//!
//! `*_call` cases go through an `#[inline(never)]` function, so constants are
//! reloaded on every call (the cost inside a larger step); the others let the
//! function inline into the loop, as `Scalar::powf` does in the models.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use hysteresis::Scalar;

const N: usize = 1024;

/// The inputs of every case, in RAM: the ranges of `embedded-cost.md`
/// (|z|^n: base in [0.001, 1), exponent in [1, 3); exp: x in [-10, 10)).
pub struct Inputs {
    base: [f32; N],
    expo: [f32; N],
    arg: [f32; N],
    base64: [f64; N],
    expo64: [f64; N],
    arg64: [f64; N],
}

/// One measured case.
pub struct Case {
    /// Printed as `case NAME`; `baseline` is subtracted from the cases after it.
    pub name: &'static str,
    /// Runs the body 1024 times and folds the results into one word.
    pub run: fn(&Inputs) -> u32,
}

#[inline(always)]
fn loop32(a: &[f32; N], b: &[f32; N], f: impl Fn(f32, f32) -> f32) -> u32 {
    let mut acc = 0u32;
    for i in 0..N {
        acc ^= f(black_box(a[i]), black_box(b[i])).to_bits();
    }
    acc
}

#[inline(always)]
fn loop64(a: &[f64; N], b: &[f64; N], f: impl Fn(f64, f64) -> f64) -> u32 {
    let mut acc = 0u64;
    for i in 0..N {
        acc ^= f(black_box(a[i]), black_box(b[i])).to_bits();
    }
    acc as u32 ^ (acc >> 32) as u32
}

#[inline(never)]
fn fast_powf_call(x: f32, y: f32) -> f32 {
    <f32 as Scalar>::powf(x, y)
}

#[inline(never)]
fn fast_expf_call(x: f32) -> f32 {
    Scalar::exp(x)
}

/// The cases, in order. Keep `baseline` first (and add another `baseline` before
/// cases with a different loop skeleton).
pub const CASES: &[Case] = &[
    Case {
        name: "baseline",
        run: |i| loop32(&i.base, &i.expo, |x, _| x),
    },
    Case {
        name: "libm_powf",
        run: |i| loop32(&i.base, &i.expo, libm::powf),
    },
    Case {
        name: "fast_powf",
        run: |i| loop32(&i.base, &i.expo, <f32 as Scalar>::powf),
    },
    Case {
        name: "fast_powf_call",
        run: |i| loop32(&i.base, &i.expo, fast_powf_call),
    },
    Case {
        name: "libm_expf",
        run: |i| loop32(&i.arg, &i.expo, |x, _| libm::expf(x)),
    },
    Case {
        name: "fast_expf",
        run: |i| loop32(&i.arg, &i.expo, |x, _| Scalar::exp(x)),
    },
    Case {
        name: "fast_expf_call",
        run: |i| loop32(&i.arg, &i.expo, |x, _| fast_expf_call(x)),
    },
    Case {
        name: "baseline",
        run: |i| loop64(&i.base64, &i.expo64, |x, _| x),
    },
    Case {
        name: "libm_pow_f64",
        run: |i| loop64(&i.base64, &i.expo64, libm::pow),
    },
    Case {
        name: "fast_pow_f64",
        run: |i| loop64(&i.base64, &i.expo64, <f64 as Scalar>::powf),
    },
    Case {
        name: "libm_exp_f64",
        run: |i| loop64(&i.arg64, &i.expo64, |x, _| libm::exp(x)),
    },
    Case {
        name: "fast_exp_f64",
        run: |i| loop64(&i.arg64, &i.expo64, |x, _| Scalar::exp(x)),
    },
];

/// Marks the start of a measured region (found by name by the QEMU plugin).
#[no_mangle]
#[inline(never)]
pub extern "C" fn bench_start() {
    cortex_m::asm::nop();
}

/// Marks the end of a measured region; a different body from `bench_start` so that
/// the linker cannot fold the two into one address.
#[no_mangle]
#[inline(never)]
pub extern "C" fn bench_stop() {
    cortex_m::asm::nop();
    cortex_m::asm::nop();
}

/// A fixed stream of draws in [0, 1) from integers (LCG, top 24 bits).
struct Draws(u32);
impl Draws {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (self.0 >> 8) as f32 / 16_777_216.0
    }
}

#[entry]
fn main() -> ! {
    let mut d = Draws(12345);
    let mut inputs = Inputs {
        base: [0.0; N],
        expo: [0.0; N],
        arg: [0.0; N],
        base64: [0.0; N],
        expo64: [0.0; N],
        arg64: [0.0; N],
    };
    for k in 0..N {
        inputs.base[k] = 0.001 + 0.999 * d.next();
        inputs.expo[k] = 1.0 + 2.0 * d.next();
        inputs.arg[k] = -10.0 + 20.0 * d.next();
        inputs.base64[k] = inputs.base[k] as f64;
        inputs.expo64[k] = inputs.expo[k] as f64;
        inputs.arg64[k] = inputs.arg[k] as f64;
    }
    let inputs = black_box(&inputs);
    for case in CASES {
        hprintln!("case {}", case.name);
        bench_start();
        let r = (case.run)(inputs);
        bench_stop();
        black_box(r);
    }
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
