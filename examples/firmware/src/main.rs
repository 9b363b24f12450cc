//! The structural-control firmware example (see `README.md`): four BWBN
//! column elements loaded from a parameter table in flash, driven at 1 kHz
//! by displacements read through an SPI ADC, their forces checked at the
//! end against the host's f64 simulation of the same record.
#![no_std]
#![no_main]

mod table;

use embedded_hal::delay::DelayNs;
use hysteresis::bwbn::Bwbn;
use hysteresis::table::BwbnTable;
use hysteresis::Element;
use hysteresis_firmware_example::adc::Ads8688;
use hysteresis_firmware_example::exit;
use hysteresis_firmware_example::replay::{ReplayAdc, ReplayClock, ReplayDelay};
use table::TABLE;

/// ADC channel of each column, in table order.
const CHANNELS: [u8; 4] = [0, 1, 2, 3];
/// Control period: 1 kHz.
const PERIOD_NS: u32 = 1_000_000;
/// Core clock of mps2-an386 (SysTick counts it).
const CORE_HZ: u32 = 25_000_000;
/// One ADC code in mm: ±10 mm over 16 bits (exact in f32).
const MM_PER_CODE: f32 = 10.0 / 32768.0;
/// The recorded displacements, as the ADC's codes (host-made, see README).
static RECORD: &[u8] = include_bytes!("../data/record.bin");
/// The host's f64 forces for the same codes, rounded to f32 (kN).
static REFERENCE: &[u8] = include_bytes!("../data/reference.bin");
/// The f32 bound the core's shared tests prove on the reference history:
/// force error at most 1e-4 of the peak force, against f64.
const F32_BOUND: f32 = 1e-4;
/// Elements this firmware has room for.
const MAX_ELEMENTS: usize = 8;

/// Displacement (mm) of a straight-binary bipolar code.
fn displacement(code: u16) -> f32 {
    (code as i32 - 32768) as f32 * MM_PER_CODE
}

/// The host's force for sample `k`, element `i`.
fn reference(k: usize, i: usize) -> f32 {
    let at = 4 * (k * CHANNELS.len() + i);
    match REFERENCE.get(at..at + 4) {
        Some(&[a, b, c, d]) => f32::from_le_bytes([a, b, c, d]),
        _ => f32::NAN,
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    let Some(cp) = cortex_m::Peripherals::take() else {
        exit(1)
    };
    let clock = ReplayClock::new();
    let mut delay = ReplayDelay::new(&clock, cortex_m::delay::Delay::new(cp.SYST, CORE_HZ));
    let spi = ReplayAdc::new(&clock, RECORD, CHANNELS.len(), PERIOD_NS);
    let samples = spi.samples();
    let mut adc = Ads8688::new(spi);

    // Nothing runs on a table that does not verify completely.
    let table = match BwbnTable::<f32>::load(&TABLE) {
        Ok(t) => t,
        Err(e) => {
            defmt::error!("parameter table refused: {}", e);
            exit(1)
        }
    };
    let units = table.header().units;
    defmt::info!(
        "table: {} BWBN elements (effects {=u8:#x}), f32, {=str} / {=str}",
        table.len(),
        table.header().effects.bits(),
        units.displacement(),
        units.force()
    );
    if table.len() != CHANNELS.len() || table.len() > MAX_ELEMENTS {
        defmt::error!("{} elements for {} channels", table.len(), CHANNELS.len());
        exit(1)
    }
    let mut elements: heapless::Vec<Bwbn<f32>, MAX_ELEMENTS> = heapless::Vec::new();
    for p in table.iter() {
        // The length was checked above: no push fails.
        let _ = elements.push(Bwbn::new(p));
    }
    defmt::info!(
        "{} elements of {} bytes of state each",
        elements.len(),
        core::mem::size_of::<Bwbn<f32>>()
    );

    let mut codes = [0u16; CHANNELS.len()];
    let mut peak = [0f32; CHANNELS.len()];
    let mut error = [0f32; CHANNELS.len()];
    for k in 0..samples {
        if let Err(e) = adc.scan(&CHANNELS, &mut codes) {
            defmt::error!("tick {}: ADC: {}", k, e);
            exit(1)
        }
        let columns = elements
            .iter_mut()
            .zip(&codes)
            .zip(peak.iter_mut().zip(&mut error));
        for (i, ((el, &code), (peak, error))) in columns.enumerate() {
            let u = displacement(code);
            let force = match el.set_trial(u) {
                Ok(r) => r.force,
                Err(e) => {
                    defmt::error!("tick {}, element {}: u = {} mm refused: {}", k, i, u, e);
                    exit(1)
                }
            };
            el.commit();
            let want = reference(k, i);
            *peak = peak.max(want.abs());
            *error = error.max((force - want).abs());
        }
        // Every block of three cycles, at the positive peak of its second.
        if k % 600 == 250 {
            let mut f = [0f32; CHANNELS.len()];
            for (f, e) in f.iter_mut().zip(&elements) {
                *f = e.response().force;
            }
            defmt::info!(
                "t = {} ms: u0 = {} mm, forces {} kN",
                k,
                displacement(codes[0]),
                f.as_slice()
            );
        }
        delay.delay_ns(PERIOD_NS);
    }

    let mut failed = 0;
    for (i, (peak, error)) in peak.iter().zip(&error).enumerate() {
        let rel = error / peak;
        let ok = rel <= F32_BOUND;
        defmt::println!(
            "element {}: peak {} kN, max |F - F_host| {} kN = {} of peak (bound {}) ... {=str}",
            i,
            peak,
            error,
            rel,
            F32_BOUND,
            if ok { "ok" } else { "FAILED" }
        );
        failed += !ok as usize;
    }
    defmt::println!(
        "{} ticks of {} elements at 1 kHz; {} passed, {} failed",
        samples,
        elements.len(),
        elements.len() - failed,
        failed
    );
    exit(if failed == 0 { 0 } else { 1 })
}
