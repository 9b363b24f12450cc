//! The subject of `profile/profile.sh`: one all-four-effects `f32` element
//! (default control, the parameters `step_cost` uses) over the reference
//! history, and nothing else.
#![no_std]
#![no_main]

use core::hint::black_box;
use hysteresis::bwbn::selftest::history::{displacement, Set, POINTS};
use hysteresis::bwbn::Bwbn;
use hysteresis::Element;

#[cortex_m_rt::entry]
fn main() -> ! {
    let mut el = Bwbn::<f32>::new(black_box(Set::All.params_q16()));
    for i in 1..POINTS {
        if el.set_trial(black_box(displacement::<f32>(i))).is_err() {
            defmt::panic!("point {} refused", i);
        }
        el.commit();
    }
    hysteresis_qemu::exit(0)
}
