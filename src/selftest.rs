//! Test bodies shared by the host and the microcontroller.
//!
//! Every case is a plain `fn()` that panics (through `assert!`) when the
//! behaviour it checks is wrong. The host runs them as one unit test; the
//! on-target package `tests/qemu` runs the same table under QEMU on a
//! Cortex-M4F (f32 on the FPU) and a Cortex-M3 (soft float, fixed point), so
//! the numbers the library promises for `f32` and [`Fixed`](crate::Fixed) are
//! checked on the hardware they are meant for.
//!
//! The module exists in `cfg(test)` and with the `selftest` feature. It uses
//! no allocation and no `std`; `f64` appears only as the reference arithmetic
//! (software `f64` on the targets is slow but exact enough).
//!
//! Each model module keeps its own list; [`CASES`] concatenates them. A new
//! module adds its list to `GROUPS` with one line.

/// A named test body: panics on failure.
pub type Case = (&'static str, fn());

/// The per-module case lists, in the order they run.
const GROUPS: &[&[Case]] = &[crate::bwbn::selftest::CASES, crate::phm::selftest::CASES];

/// Every case of the library, in order.
pub const CASES: &[Case] = &ALL;

const ALL: [Case; total(GROUPS)] = concat(GROUPS);

const fn total(groups: &[&[Case]]) -> usize {
    let mut n = 0;
    let mut g = 0;
    while g < groups.len() {
        n += groups[g].len();
        g += 1;
    }
    n
}

const fn concat<const N: usize>(groups: &[&[Case]]) -> [Case; N] {
    let mut out: [Case; N] = [("", placeholder); N];
    let (mut i, mut g) = (0, 0);
    while g < groups.len() {
        let mut c = 0;
        while c < groups[g].len() {
            out[i] = groups[g][c];
            i += 1;
            c += 1;
        }
        g += 1;
    }
    out
}

/// Fills the table before [`concat`] overwrites every slot (`total` sizes it
/// exactly), so it never runs.
fn placeholder() {}

/// Prints a measured value: through `defmt` on the target, to stdout in host
/// unit tests (`cargo test -- --nocapture` shows it), nowhere otherwise.
macro_rules! report {
    ($fmt:literal $(, $arg:expr)* $(,)?) => {{
        #[cfg(feature = "defmt")]
        defmt::println!($fmt $(, $arg)*);
        #[cfg(all(test, not(feature = "defmt")))]
        std::println!($fmt $(, $arg)*);
        #[cfg(not(any(test, feature = "defmt")))]
        let _ = ($($arg,)*);
    }};
}
pub(crate) use report;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shared_case_passes_on_the_host() {
        assert_eq!(CASES.len(), total(GROUPS));
        for (i, (name, case)) in CASES.iter().enumerate() {
            std::println!("case {name} ({}/{})", i + 1, CASES.len());
            case();
        }
    }

    #[test]
    fn case_names_are_unique_and_non_empty() {
        for (i, (a, _)) in CASES.iter().enumerate() {
            assert!(!a.is_empty());
            assert!(
                CASES[i + 1..].iter().all(|(b, _)| a != b),
                "duplicate case {a}"
            );
        }
    }
}
