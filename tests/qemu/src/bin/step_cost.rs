//! Instructions per step of the BWBN element on the reference history, for
//! each arithmetic and integration tolerance (`step-cost.sh` counts them
//! exactly with the `qemu-insn` plugin; not run by `scripts/test`).
//!
//! Each case steps a fresh element over the 3600 increments of the history
//! between the markers `bench_start` and `bench_stop`, after printing `case
//! NAME`; `step-cost.sh` divides the count by 3600. The default cases (and
//! plain Bouc-Wen by Bogacki-Shampine) then run once more with the markers
//! around every single step, for the worst step.
#![no_std]
#![no_main]

use core::hint::black_box;
use hysteresis::bwbn::selftest::history::{displacement, Set, POINTS};
use hysteresis::bwbn::{Bwbn, Control, Method};
use hysteresis::phm::{Coefficients, Phm, PhmParams};
use hysteresis::{Element, Fixed, Scalar};

/// Start marker: the plugin counts from its first instruction.
#[no_mangle]
#[inline(never)]
pub extern "C" fn bench_start() {
    cortex_m::asm::nop();
}

/// Stop marker (a different body, so the linker cannot fold the two).
#[no_mangle]
#[inline(never)]
pub extern "C" fn bench_stop() {
    cortex_m::asm::nop();
    cortex_m::asm::nop();
}

fn case<S: Scalar>(name: &str, set: Set, control: Control<S>) {
    let mut el = Bwbn::<S>::new(black_box(set.params_q16()))
        .with_control(control)
        .unwrap();
    defmt::println!("case {}/{}/{}", set.name(), S::NAME, name);
    bench_start();
    for i in 1..POINTS {
        if el.set_trial(black_box(displacement::<S>(i))).is_err() {
            defmt::panic!("point {} refused", i);
        }
        el.commit();
    }
    bench_stop();
}

/// The same history with the markers around each step, one `case NAME/step`
/// line per step: `step-cost.sh` reports the mean and the worst step.
fn per_step<S: Scalar>(set: Set, label: &str, control: Control<S>) {
    let mut el = Bwbn::<S>::new(black_box(set.params_q16()))
        .with_control(control)
        .unwrap();
    for i in 1..POINTS {
        defmt::println!("case {}/{}/{}", set.name(), S::NAME, label);
        bench_start();
        let ok = el.set_trial(black_box(displacement::<S>(i))).is_ok();
        el.commit();
        bench_stop();
        if !ok {
            defmt::panic!("point {} refused", i);
        }
    }
}

/// The PHM on the same history (as twist), on the primary curve of
/// OpenSees' `Pinching4` reference cases: (1, 5), (3, 6.3), (6, 6.5), (10, 5).
fn phm<S: Scalar>() {
    let p = |x: i32, y10: i32| [S::from_i32(x), S::ratio(y10, 10)];
    let Ok(params) = PhmParams::<S, 4>::symmetric(
        &[p(1, 50), p(3, 63), p(6, 65), p(10, 50)],
        Coefficients::thesis(),
    ) else {
        defmt::panic!("PHM parameters refused")
    };
    let mut el: Phm<S, 4, 16> = Phm::new(black_box(params));
    defmt::println!("case phm/{}/default", S::NAME);
    let mut acc = S::ZERO;
    bench_start();
    for i in 1..POINTS {
        match el.set_trial(black_box(displacement::<S>(i))) {
            Ok(r) => acc += r.force,
            Err(_) => defmt::panic!("point {} refused", i),
        }
        el.commit();
    }
    bench_stop();
    black_box(acc);
}

/// The history loop alone (the displacement of each point and a sum), whose
/// count `step-cost.sh` subtracts from the PHM's.
fn history_loop<S: Scalar>() {
    defmt::println!("case history/{}/loop", S::NAME);
    let mut acc = S::ZERO;
    bench_start();
    for i in 1..POINTS {
        acc += black_box(displacement::<S>(i));
    }
    bench_stop();
    black_box(acc);
}

fn bs32<S: Scalar>(tol: f32) -> Control<S> {
    Control {
        method: Method::Bs32,
        tol: S::lit(tol),
        ..Control::default_for()
    }
}

fn series<S: Scalar>(tol: f32) -> Control<S> {
    Control {
        method: Method::Series,
        tol: S::lit(tol),
        ..Control::default_for()
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    // Plain Bouc-Wen is summed as series by default; Bogacki-Shampine is
    // its default before and the pair every effect integrates by in f32 and
    // fixed point.
    case::<f32>("series-1e-4", Set::Plain, series(1e-4));
    case::<f32>("bs32-1e-5", Set::Plain, bs32(1e-5));
    case::<Fixed>("bs32-2e-4", Set::Plain, bs32(2e-4));
    for set in [Set::Plain, Set::All] {
        case::<f32>("default", set, Control::default_for());
        case::<f32>("tol-3e-5", set, bs32(3e-5));
        case::<f32>("tol-1e-4", set, bs32(1e-4));
        case::<Fixed>("default", set, Control::default_for());
        case::<Fixed>("tol-5e-4", set, bs32(5e-4));
    }
    history_loop::<f32>();
    history_loop::<Fixed>();
    phm::<f32>();
    phm::<Fixed>();
    per_step::<f32>(Set::All, "step", Control::default_for());
    per_step::<Fixed>(Set::All, "step", Control::default_for());
    per_step::<f32>(Set::Plain, "step", Control::default_for());
    per_step::<f32>(Set::Plain, "bs32-step", bs32(1e-5));
    per_step::<Fixed>(Set::Plain, "step", Control::default_for());
    per_step::<Fixed>(Set::Plain, "bs32-step", bs32(2e-4));
    hysteresis_qemu::exit(0)
}
