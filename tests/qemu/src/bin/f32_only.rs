//! Firmware that steps only an `f32` BWBN element (all four effects) over the
//! reference history. Its release ELF must contain no double-precision
//! soft-float routine (`__aeabi_d*`): `scripts/test` checks that no `f64`
//! reaches `f32` firmware, on the Cortex-M4F and on the Cortex-M3.
#![no_std]
#![no_main]

use core::hint::black_box;
use hysteresis::bwbn::selftest::history::{displacement, POINTS};
use hysteresis::bwbn::{Bwbn, BwbnParams, EffectSet};
use hysteresis::{Element, Scalar};

/// The all-effects reference parameters as `f32` literals, hidden from the
/// optimiser so that the model is not evaluated at compile time.
fn param(name: &str) -> Option<f32> {
    let v = match name {
        "k0" => 6.0,
        "alpha" => 0.2,
        "n" => 1.2,
        "beta" => 2.0,
        "gamma" => -1.0,
        "delta_A" => 2e-4,
        "delta_nu" => 5e-4,
        "delta_eta" => 5e-4,
        "zeta0" => 0.9,
        "p" => 0.01,
        "q" => 0.1,
        "psi0" => 0.2,
        "delta_psi" => 5e-4,
        "lambda" => 0.5,
        "energy_limit" => 2000.0,
        _ => return None,
    };
    Some(black_box(v))
}

#[cortex_m_rt::entry]
fn main() -> ! {
    let Ok(params) = BwbnParams::<f32>::from_named(EffectSet::BWBN, param) else {
        defmt::panic!("invalid parameters")
    };
    let mut el = Bwbn::new(params);
    let mut peak = 0.0f32;
    for i in 1..POINTS {
        match el.set_trial(black_box(displacement::<f32>(i))) {
            Ok(r) => {
                el.commit();
                peak = peak.max(Scalar::abs(r.force));
            }
            Err(e) => defmt::panic!("point {}: {}", i, e),
        }
    }
    defmt::println!(
        "f32 BWBN: {} points, peak force {=f32} kN, final z {=f32}",
        POINTS,
        peak,
        el.committed().z
    );
    hysteresis_qemu::exit(0)
}
