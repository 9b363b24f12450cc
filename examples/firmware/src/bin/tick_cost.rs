//! The budget of the example: instructions to verify the parameter table and
//! build its elements, and per control tick for 1, 8 and 64 elements, each
//! counted exactly between the markers `bench_start` and `bench_stop` by the
//! `qemu-insn` plugin (`tick-cost.sh`; not run by `scripts/test`).
//!
//! Every measured case prints `case NAME COUNT` and then makes COUNT
//! start/stop pairs; `baseline` is the markers alone. A tick is: take one
//! ADC code per element from the record (the SPI transfer itself is
//! hardware time, not counted), convert it to mm, `set_trial` + `commit`.
#![no_std]
#![no_main]

#[path = "../table.rs"]
mod table;
#[path = "../table64.rs"]
mod table64;

use core::hint::black_box;
use hysteresis::bwbn::Bwbn;
use hysteresis::table::BwbnTable;
use hysteresis::Element;
use hysteresis_firmware_example::exit;

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

static RECORD: &[u8] = include_bytes!("../../data/record.bin");
const CHANNELS: usize = 4;
const MM_PER_CODE: f32 = 10.0 / 32768.0;
const MAX: usize = 64;

fn code(k: usize, channel: usize) -> u16 {
    let at = 2 * (k * CHANNELS + channel);
    match RECORD.get(at..at + 2) {
        Some(&[lo, hi]) => u16::from_le_bytes([lo, hi]),
        _ => 0x8000,
    }
}

fn load(name: &str, bytes: &'static [u8]) -> BwbnTable<'static, f32> {
    defmt::println!("case load/{} 1", name);
    bench_start();
    let t = BwbnTable::<f32>::load(black_box(bytes));
    bench_stop();
    match t {
        Ok(t) => t,
        Err(e) => defmt::panic!("{}", e),
    }
}

fn build(t: &BwbnTable<'static, f32>, n: usize) -> heapless::Vec<Bwbn<f32>, MAX> {
    defmt::println!("case build/{} 1", n);
    bench_start();
    let v = t.iter().take(n).map(Bwbn::new).collect();
    bench_stop();
    v
}

fn ticks(elements: &mut [Bwbn<f32>]) {
    let samples = RECORD.len() / (2 * CHANNELS);
    defmt::println!("case tick/{} {}", elements.len(), samples - 1);
    for k in 1..samples {
        bench_start();
        for (i, el) in elements.iter_mut().enumerate() {
            let u = (code(k, i % CHANNELS) as i32 - 32768) as f32 * MM_PER_CODE;
            if el.set_trial(black_box(u)).is_err() {
                defmt::panic!("tick {} element {} refused", k, i);
            }
            el.commit();
        }
        bench_stop();
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    defmt::println!("case baseline 100");
    for _ in 0..100 {
        bench_start();
        bench_stop();
    }
    let four = load("4", &table::TABLE);
    let t64 = load("64", &table64::TABLE);
    let _ = build(&four, 4);
    for n in [1, 8, 64] {
        let mut elements = build(&t64, n);
        ticks(&mut elements);
    }
    exit(0)
}
