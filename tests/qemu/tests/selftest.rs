//! The library's shared test cases (`hysteresis::selftest::CASES`), the same
//! bodies the host runs, on the target under QEMU.
#![no_std]
#![no_main]

#[cortex_m_rt::entry]
fn main() -> ! {
    hysteresis_qemu::run(hysteresis::selftest::CASES)
}
