//! How each arithmetic is stored in a table: little-endian IEEE 754 binary64
//! or binary32, or the raw `i32` of a Q15.16 [`Fixed`].

use super::ScalarKind;
use crate::scalar::{Fixed, Scalar};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for f32 {}
    impl Sealed for crate::scalar::Fixed {}
}

/// A [`Scalar`] with a table encoding: the three arithmetics of the crate.
/// Sealed: the table format names exactly these.
pub trait TableScalar: Scalar + sealed::Sealed {
    /// Its code in the table header.
    const KIND: ScalarKind;
    /// Decodes the value at the start of `bytes` (`None` if `bytes` is
    /// shorter than [`ScalarKind::width`]).
    fn read(bytes: &[u8]) -> Option<Self>;
}

fn array<const W: usize>(bytes: &[u8]) -> Option<[u8; W]> {
    bytes.get(..W)?.try_into().ok()
}

impl TableScalar for f64 {
    const KIND: ScalarKind = ScalarKind::F64;
    #[inline]
    fn read(bytes: &[u8]) -> Option<Self> {
        array(bytes).map(f64::from_le_bytes)
    }
}

impl TableScalar for f32 {
    const KIND: ScalarKind = ScalarKind::F32;
    #[inline]
    fn read(bytes: &[u8]) -> Option<Self> {
        array(bytes).map(f32::from_le_bytes)
    }
}

impl TableScalar for Fixed {
    const KIND: ScalarKind = ScalarKind::Q16;
    #[inline]
    fn read(bytes: &[u8]) -> Option<Self> {
        array(bytes).map(|b| Fixed::from_raw(i32::from_le_bytes(b)))
    }
}

impl ScalarKind {
    /// Bytes per value.
    pub const fn width(self) -> usize {
        match self {
            ScalarKind::F64 => 8,
            ScalarKind::F32 | ScalarKind::Q16 => 4,
        }
    }

    /// Writes `x` rounded once into this arithmetic (as [`Scalar::from_f64`]
    /// does: out-of-range values become infinite or saturate, which the
    /// loader then refuses as not finite) at the start of `out`, which must
    /// hold [`width`](Self::width) bytes. `max` writes the arithmetic's
    /// largest finite value instead (the "no limit" of `energy_limit`).
    pub(crate) fn write(self, x: f64, max: bool, out: &mut [u8]) {
        match self {
            ScalarKind::F64 => {
                let v = if max { f64::MAX } else { x };
                out[..8].copy_from_slice(&v.to_le_bytes())
            }
            ScalarKind::F32 => {
                let v = if max { f32::MAX } else { f32::from_f64(x) };
                out[..4].copy_from_slice(&v.to_le_bytes())
            }
            ScalarKind::Q16 => {
                let v = if max { Fixed::MAX } else { Fixed::from_f64(x) };
                out[..4].copy_from_slice(&v.to_raw().to_le_bytes())
            }
        }
    }
}
