//! Writing tables (the host's `hyst export`; usable on a device too: no
//! allocation, the caller provides the buffer).

use super::bwbn::bwbn_record_size;
use super::phm::{phm_record_size, MAX_POINTS};
use super::{
    crc32, ModelKind, ScalarKind, Units, WriteError, CRC_LEN, HEADER_LEN, MAGIC, UNIT_LEN, VERSION,
};
use crate::bwbn::{BwbnParams, EffectSet, ZuRule};
use crate::phm::{Direction, PhmParams};
use crate::scalar::Scalar;

/// Bytes of a BWBN table of `count` elements, `None` if that does not fit in `usize`.
pub fn bwbn_len(effects: EffectSet, scalar: ScalarKind, count: usize) -> Option<usize> {
    table_len(count, bwbn_record_size(effects, scalar))
}

/// Bytes of a PHM table of `count` elements with `points` slots per curve, `None` if that
/// does not fit in `usize`.
pub fn phm_len(points: usize, scalar: ScalarKind, count: usize) -> Option<usize> {
    table_len(count, phm_record_size(points, scalar))
}

/// Header, `count` records of `record` bytes and the CRC.
fn table_len(count: usize, record: usize) -> Option<usize> {
    count.checked_mul(record)?.checked_add(HEADER_LEN + CRC_LEN)
}

/// The parts every table shares.
struct Layout {
    model: ModelKind,
    scalar: ScalarKind,
    effects: u8,
    option: u8,
    count: usize,
    record: usize,
}

/// Checks the size, writes the header, lets `record` fill each record, then
/// the CRC. Returns the table's length.
fn write(
    out: &mut [u8],
    l: &Layout,
    units: &Units,
    mut record: impl FnMut(usize, &mut [u8]),
) -> Result<usize, WriteError> {
    if l.count == 0 {
        return Err(WriteError::NoElements);
    }
    if l.count > u16::MAX as usize {
        return Err(WriteError::TooManyElements(l.count));
    }
    let len = HEADER_LEN + l.count * l.record + CRC_LEN;
    if out.len() < len {
        return Err(WriteError::BufferTooSmall {
            needed: len,
            found: out.len(),
        });
    }
    let out = &mut out[..len];
    out.fill(0);
    out[0..4].copy_from_slice(&MAGIC);
    out[4..6].copy_from_slice(&VERSION.to_le_bytes());
    out[6] = l.model as u8;
    out[7] = l.scalar as u8;
    out[8] = l.effects;
    out[9] = l.option;
    out[10..12].copy_from_slice(&(l.count as u16).to_le_bytes());
    out[12..14].copy_from_slice(&(l.record as u16).to_le_bytes());
    out[16..20].copy_from_slice(&(len as u32).to_le_bytes());
    let d = units.displacement().as_bytes();
    out[20..20 + d.len()].copy_from_slice(d);
    let f = units.force().as_bytes();
    out[20 + UNIT_LEN..20 + UNIT_LEN + f.len()].copy_from_slice(f);
    for (i, r) in out[HEADER_LEN..len - CRC_LEN]
        .chunks_exact_mut(l.record)
        .enumerate()
    {
        record(i, r);
    }
    let crc = crc32(&out[..len - CRC_LEN]);
    out[len - CRC_LEN..].copy_from_slice(&crc.to_le_bytes());
    Ok(len)
}

/// Writes a table of the BWBN parameter sets `elements` (computed in any
/// arithmetic `T`), each value rounded once into `scalar`, into `out`.
/// Returns the table's length. All elements must share one effect set and
/// Zu rule.
///
/// Values that do not fit `scalar` (beyond ±32768 for Q15.16, beyond f32's
/// range) are written saturated or infinite, and loading the table then
/// refuses them, naming element and parameter: verify what you write
/// (`hyst export` does, with the device's loader).
pub fn write_bwbn<T: Scalar>(
    out: &mut [u8],
    scalar: ScalarKind,
    units: &Units,
    elements: &[BwbnParams<T>],
) -> Result<usize, WriteError> {
    let first = elements.first().ok_or(WriteError::NoElements)?;
    let effects = first.effect_set();
    let zu = first.zu_rule();
    if let Some(element) = elements
        .iter()
        .position(|p| p.effect_set() != effects || p.zu_rule() != zu)
    {
        return Err(WriteError::Mixed { element });
    }
    let layout = Layout {
        model: ModelKind::Bwbn,
        scalar,
        effects: effects.bits(),
        option: (zu == ZuRule::OpenSees) as u8,
        count: elements.len(),
        record: bwbn_record_size(effects, scalar),
    };
    let w = scalar.width();
    write(out, &layout, units, |i, rec| {
        let p = &elements[i];
        let mut slots = rec.chunks_exact_mut(w);
        p.for_each(|_, v| {
            if let Some(s) = slots.next() {
                scalar.write(v.to_f64(), false, s);
            }
        });
        if let Some(s) = slots.next() {
            let limit = p.energy_limit();
            scalar.write(limit.to_f64(), limit == T::MAX, s);
        }
    })
}

/// Writes a table of the PHM parameter sets `elements` (computed in any
/// arithmetic `T`), each value rounded once into `scalar`, into `out`, with
/// as many point slots per curve as the longest curve has. Returns the
/// table's length.
pub fn write_phm<T: Scalar, const N: usize>(
    out: &mut [u8],
    scalar: ScalarKind,
    units: &Units,
    elements: &[PhmParams<T, N>],
) -> Result<usize, WriteError> {
    let curves = |p: &PhmParams<T, N>| {
        [Direction::Positive, Direction::Negative].map(|d| p.primary(d).points().len())
    };
    let slots = elements
        .iter()
        .flat_map(curves)
        .max()
        .ok_or(WriteError::NoElements)?;
    if slots > MAX_POINTS as usize {
        let element = elements
            .iter()
            .position(|p| curves(p).iter().any(|&n| n > MAX_POINTS as usize))
            .unwrap_or(0);
        return Err(WriteError::Mixed { element });
    }
    let layout = Layout {
        model: ModelKind::Phm,
        scalar,
        effects: 0,
        option: slots as u8,
        count: elements.len(),
        record: phm_record_size(slots, scalar),
    };
    let w = scalar.width();
    write(out, &layout, units, |i, rec| {
        let p = &elements[i];
        let (counts, values) = rec.split_at_mut(4);
        let mut curve_slots = values.chunks_exact_mut(2 * slots * w);
        for (c, d) in [Direction::Positive, Direction::Negative]
            .into_iter()
            .enumerate()
        {
            let points = p.primary(d).points();
            counts[c] = points.len() as u8;
            if let Some(curve) = curve_slots.next() {
                for (xy, s) in points.iter().flatten().zip(curve.chunks_exact_mut(w)) {
                    scalar.write(xy.to_f64(), false, s);
                }
            }
        }
        let coefficients = &mut values[4 * slots * w..];
        let mut slots = coefficients.chunks_exact_mut(w);
        p.coefficients().for_each(|_, v| {
            if let Some(s) = slots.next() {
                scalar.write(v.to_f64(), false, s);
            }
        });
    })
}
