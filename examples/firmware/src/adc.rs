//! A driver for an 8-channel, 16-bit SPI ADC with the command framing of the
//! TI ADS8688 family, written against embedded-hal 1.0's
//! [`SpiDevice`](embedded_hal::spi::SpiDevice) so that it runs on any HAL (and
//! on the replay device under QEMU).
//!
//! Framing (ADS8688 datasheet, "manual channel select"): each frame is 32
//! clocks with chip select held low. The host sends a 16-bit command in the
//! first half (`0xC000 | ch << 10` selects channel `ch`, `0x0000` repeats the
//! last selection); the device shifts out, in the second half, the result
//! of the conversion the *previous* frame selected. A scan of n channels is
//! therefore n + 1 frames.
//!
//! Codes are straight binary: for a bipolar range ±R, code 32768 is 0 and
//! one code is R / 32768.

use embedded_hal::spi::SpiDevice;

/// Channels of the device.
pub const CHANNELS: u8 = 8;
/// The command that repeats the last channel selection.
pub const NO_OP: u16 = 0x0000;

/// The command selecting `channel` (manual mode).
pub const fn manual(channel: u8) -> u16 {
    0xC000 | (channel as u16) << 10
}

/// Why a scan failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub enum Error<E> {
    /// The SPI bus or device failed.
    Spi(E),
    /// A channel number is not below [`CHANNELS`].
    Channel(u8),
    /// The output slice does not have one slot per channel asked for.
    Length,
}

/// The ADC on an SPI device (bus + chip select, from the HAL).
pub struct Ads8688<SPI> {
    spi: SPI,
}

impl<SPI: SpiDevice> Ads8688<SPI> {
    /// The driver for the device on `spi`.
    pub fn new(spi: SPI) -> Self {
        Ads8688 { spi }
    }

    /// Gives the SPI device back.
    pub fn release(self) -> SPI {
        self.spi
    }

    /// One 32-clock frame: sends `command`, returns the result shifted out.
    fn frame(&mut self, command: u16) -> Result<u16, Error<SPI::Error>> {
        let [hi, lo] = command.to_be_bytes();
        let mut read = [0u8; 4];
        self.spi
            .transfer(&mut read, &[hi, lo, 0, 0])
            .map_err(Error::Spi)?;
        Ok(u16::from_be_bytes([read[2], read[3]]))
    }

    /// Converts `channels` in order and writes their codes to `out` (one
    /// slot per channel): n + 1 frames, each result one frame late.
    pub fn scan(&mut self, channels: &[u8], out: &mut [u16]) -> Result<(), Error<SPI::Error>> {
        if channels.len() != out.len() {
            return Err(Error::Length);
        }
        if let Some(&c) = channels.iter().find(|&&c| c >= CHANNELS) {
            return Err(Error::Channel(c));
        }
        let mut previous: Option<&mut u16> = None;
        for (&c, slot) in channels.iter().zip(out.iter_mut()) {
            let r = self.frame(manual(c))?;
            if let Some(p) = previous {
                *p = r;
            }
            previous = Some(slot);
        }
        if let Some(p) = previous {
            *p = self.frame(NO_OP)?;
        }
        Ok(())
    }
}
