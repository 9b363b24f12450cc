//! Support for the on-target tests: defmt logging over semihosting, exit codes
//! QEMU hands back to cargo, and the plain test harness.
//!
//! Exit codes (semihosting `SYS_EXIT_EXTENDED`, passed through by
//! `qemu-run.sh`): 0 every case passed, 101 a panic (failed assertion),
//! 102 a HardFault; a hung firmware is stopped by the runner's timeout (124).
#![no_std]

use core::cell::Cell;
use critical_section::Mutex;

// Referenced so that the linker keeps cortex-m's critical-section
// implementation and defmt's global logger.
use cortex_m as _;
use defmt_semihosting as _;

/// Exit code of a panic (a failed case).
pub const EXIT_PANIC: i32 = 101;
/// Exit code of a HardFault.
pub const EXIT_FAULT: i32 = 102;

pub use hysteresis::selftest::Case;

/// A running case: name, index, number of cases.
type Running = (&'static str, usize, usize);

/// The case running now, for the panic handler.
static CURRENT: Mutex<Cell<Option<Running>>> = Mutex::new(Cell::new(None));

/// Which CPU the firmware was built for.
const CPU: &str = if cfg!(target_abi = "eabihf") {
    "Cortex-M4F, mps2-an386, hard float"
} else {
    "Cortex-M3, mps2-an385, soft float"
};

/// Ends the QEMU run with `code`.
pub fn exit(code: i32) -> ! {
    semihosting::process::exit(code)
}

/// Runs `cases` in order, printing `test NAME (i/n) ... ok` after each and
/// `N passed, 0 failed` at the end, then exits 0. A failing case panics: the
/// panic handler prints the failure and exits [`EXIT_PANIC`], so the later
/// cases do not run (there is no unwinding).
pub fn run(cases: &[Case]) -> ! {
    let n = cases.len();
    defmt::println!("running {} cases on {}", n, CPU);
    for (i, (name, case)) in cases.iter().enumerate() {
        critical_section::with(|cs| CURRENT.borrow(cs).set(Some((name, i, n))));
        case();
        defmt::println!("test {} ({}/{}) ... ok", name, i + 1, n);
    }
    critical_section::with(|cs| CURRENT.borrow(cs).set(None));
    defmt::println!("{} passed, 0 failed", n);
    exit(0)
}

/// Reports the failed case, if a harness was running one, and exits.
fn fail() -> ! {
    if let Some((name, i, n)) = critical_section::with(|cs| CURRENT.borrow(cs).get()) {
        defmt::println!("test {} ({}/{}) ... FAILED", name, i + 1, n);
        defmt::println!("{} passed, 1 failed, {} not run", i, n - i - 1);
    }
    exit(EXIT_PANIC)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("{}", defmt::Display2Format(info));
    fail()
}

#[defmt::panic_handler]
fn defmt_panic() -> ! {
    fail()
}

#[cortex_m_rt::exception]
unsafe fn HardFault(frame: &cortex_m_rt::ExceptionFrame) -> ! {
    defmt::error!("HardFault at PC {=u32:#010x}", frame.pc());
    exit(EXIT_FAULT)
}
