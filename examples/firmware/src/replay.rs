//! What stands in for the hardware under QEMU: a replay of a recorded
//! history through the same embedded-hal traits the real parts implement.
//!
//! * [`ReplayAdc`] implements [`SpiDevice`] and answers the
//!   [`adc`](crate::adc) framing with the codes of a record, at the sample
//!   that the [`ReplayClock`] has reached.
//! * [`ReplayDelay`] implements [`DelayNs`]: it waits on a real delay
//!   (SysTick under QEMU) and advances the clock by the time it was asked to
//!   wait.
//!
//! The clock counts only the delays, not the time the firmware spends
//! computing: a tick of work plus a 1 ms delay reads the next 1 kHz sample,
//! whatever the work cost, so a run is deterministic and the host can
//! compute the same forces. On hardware the ADC samples the real world and a
//! timer paces the loop instead.

use core::cell::Cell;
use core::convert::Infallible;
use embedded_hal::delay::DelayNs;
use embedded_hal::spi::{ErrorType, Operation, SpiDevice};

/// The replay's time, in nanoseconds since the start of the record.
#[derive(Debug, Default)]
pub struct ReplayClock {
    ns: Cell<u64>,
}

impl ReplayClock {
    /// Time zero.
    pub const fn new() -> Self {
        ReplayClock { ns: Cell::new(0) }
    }
    /// The time now.
    pub fn now_ns(&self) -> u64 {
        self.ns.get()
    }
    fn advance(&self, ns: u32) {
        self.ns.set(self.ns.get().saturating_add(ns as u64));
    }
}

/// A [`DelayNs`] that also moves the replay's clock.
pub struct ReplayDelay<'a, D> {
    clock: &'a ReplayClock,
    inner: D,
}

impl<'a, D: DelayNs> ReplayDelay<'a, D> {
    /// Delays with `inner`, advancing `clock`.
    pub fn new(clock: &'a ReplayClock, inner: D) -> Self {
        ReplayDelay { clock, inner }
    }
}

impl<D: DelayNs> DelayNs for ReplayDelay<'_, D> {
    fn delay_ns(&mut self, ns: u32) {
        self.clock.advance(ns);
        self.inner.delay_ns(ns);
    }
}

/// An ADC that plays a record: `channels` codes (u16 little-endian) per
/// sample, one sample every `period_ns` of the replay clock; past the end it
/// holds the last sample.
pub struct ReplayAdc<'a> {
    clock: &'a ReplayClock,
    record: &'a [u8],
    channels: usize,
    period_ns: u64,
    /// The channel the previous frame selected: its result goes out next.
    selected: u8,
}

impl<'a> ReplayAdc<'a> {
    /// A replay of `record` with `channels` channels at one sample per
    /// `period_ns` (a period of 0 holds the first sample).
    pub fn new(clock: &'a ReplayClock, record: &'a [u8], channels: usize, period_ns: u32) -> Self {
        ReplayAdc {
            clock,
            record,
            channels,
            period_ns: period_ns as u64,
            selected: 0,
        }
    }

    /// Samples in the record.
    pub fn samples(&self) -> usize {
        (self.record.len() / 2)
            .checked_div(self.channels)
            .unwrap_or(0)
    }

    /// The code of `channel` at the clock's current sample (mid-scale for a
    /// channel the record does not have).
    fn code(&self, channel: u8) -> u16 {
        let last = self.samples().saturating_sub(1);
        let k = (self.clock.now_ns().checked_div(self.period_ns).unwrap_or(0) as usize).min(last);
        let at = 2 * (k * self.channels + channel as usize);
        match self.record.get(at..at + 2) {
            Some(&[lo, hi]) if (channel as usize) < self.channels => u16::from_le_bytes([lo, hi]),
            _ => 0x8000,
        }
    }

    /// One frame: the result of the previous selection in bytes 2-3, then
    /// the command in bytes 0-1 takes effect.
    fn frame(&mut self, command: &[u8], response: &mut [u8]) {
        let [hi, lo] = self.code(self.selected).to_be_bytes();
        for (r, v) in response.iter_mut().zip([0, 0, hi, lo]) {
            *r = v;
        }
        if let Some(&[c0, c1]) = command.get(..2) {
            let c = u16::from_be_bytes([c0, c1]);
            if c & 0xC000 == 0xC000 && c & 0x03FF == 0 {
                self.selected = ((c >> 10) & 0xF) as u8;
            }
        }
    }
}

impl ErrorType for ReplayAdc<'_> {
    type Error = Infallible;
}

impl SpiDevice for ReplayAdc<'_> {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        for op in operations {
            match op {
                Operation::Transfer(read, write) => self.frame(write, read),
                Operation::TransferInPlace(buf) => {
                    let mut command = [0u8; 2];
                    for (c, b) in command.iter_mut().zip(buf.iter()) {
                        *c = *b;
                    }
                    self.frame(&command, buf)
                }
                Operation::Write(write) => self.frame(write, &mut []),
                Operation::Read(read) => self.frame(&[0, 0], read),
                Operation::DelayNs(_) => {}
            }
        }
        Ok(())
    }
}
