//! The parts of the structural-control firmware example that are not the
//! control loop: the ADC driver ([`adc`]), the replay device that stands in
//! for the ADC under QEMU ([`replay`]), and the exit path of the QEMU run.
//!
//! See `README.md` beside `Cargo.toml` for what the example does and how to
//! make it your own.
#![no_std]

pub mod adc;
pub mod replay;

// Referenced so that the linker keeps cortex-m's critical-section
// implementation and defmt's global logger.
use cortex_m as _;
use defmt_semihosting as _;

/// Exit code of a panic.
pub const EXIT_PANIC: i32 = 101;

/// Ends the QEMU run with `code` (semihosting `SYS_EXIT_EXTENDED`; on a
/// board without a debugger attached, replace with a reset or a safe state).
pub fn exit(code: i32) -> ! {
    semihosting::process::exit(code)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("{}", defmt::Display2Format(info));
    exit(EXIT_PANIC)
}

#[defmt::panic_handler]
fn defmt_panic() -> ! {
    exit(EXIT_PANIC)
}
