//! Firmware that steps only a fixed-point (Q15.16) BWBN element (all four
//! effects) over the reference history, for FPU-less parts. Its release ELF
//! for the Cortex-M3 must contain no floating-point soft-float routine
//! (`__aeabi_f*`, `__aeabi_d*`): `scripts/test` checks it.
#![no_std]
#![no_main]

use core::hint::black_box;
use hysteresis::bwbn::selftest::history::{displacement, POINTS};
use hysteresis::bwbn::{Bwbn, BwbnParams, EffectSet};
use hysteresis::{Element, Fixed, Scalar};

/// `x` rounded to Q15.16 at compile time (the firmware gets its parameters
/// as raw fixed-point numbers, as it would from flash or a host link).
const fn q16(x: f32) -> Fixed {
    let v = x * 65536.0;
    Fixed::from_raw(if v >= 0.0 { v + 0.5 } else { v - 0.5 } as i32)
}

/// The all-effects reference parameters.
const PARAMS: [(&str, Fixed); 15] = [
    ("k0", q16(6.0)),
    ("alpha", q16(0.2)),
    ("n", q16(1.2)),
    ("beta", q16(2.0)),
    ("gamma", q16(-1.0)),
    ("delta_A", q16(2e-4)),
    ("delta_nu", q16(5e-4)),
    ("delta_eta", q16(5e-4)),
    ("zeta0", q16(0.9)),
    ("p", q16(0.01)),
    ("q", q16(0.1)),
    ("psi0", q16(0.2)),
    ("delta_psi", q16(5e-4)),
    ("lambda", q16(0.5)),
    ("energy_limit", q16(2000.0)),
];

/// Looks a parameter up, hidden from the optimiser so that the model is not
/// evaluated at compile time.
fn param(name: &str) -> Option<Fixed> {
    PARAMS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, v)| black_box(*v))
}

#[cortex_m_rt::entry]
fn main() -> ! {
    let Ok(params) = BwbnParams::<Fixed>::from_named(EffectSet::BWBN, param) else {
        defmt::panic!("invalid parameters")
    };
    let mut el = Bwbn::new(params);
    let mut peak = Fixed::ZERO;
    for i in 1..POINTS {
        match el.set_trial(black_box(displacement::<Fixed>(i))) {
            Ok(r) => {
                el.commit();
                peak = Scalar::max(peak, r.force.abs());
            }
            Err(e) => defmt::panic!("point {}: {}", i, e),
        }
    }
    defmt::println!(
        "fixed BWBN: {} points, peak force {=i32} / 65536 kN, final z {=i32} / 65536",
        POINTS,
        peak.to_raw(),
        el.committed().z.to_raw()
    );
    hysteresis_qemu::exit(0)
}
