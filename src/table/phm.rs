//! PHM records: the point counts of the two primary curves, then `P` point
//! slots per curve (`P` = the header's points per curve; unused slots are
//! zero), then the rule coefficients in the order of
//! [`SPECS`](crate::phm::SPECS).
//!
//! ```text
//! 0        1 points of the positive curve (2..=P)
//! 1        1 points of the negative curve (2..=P)
//! 2        2 reserved (0)
//! 4        P x [twist, torque], positive curve
//! 4+2Pw    P x [twist, torque], negative curve
//! 4+4Pw    30 coefficients
//! ```

use super::{ModelKind, ScalarKind, Table, TableError, TableScalar};
use crate::phm::{
    BackboneError, BackboneRule, Coefficients, Direction, PhmError, PhmParams, SPECS,
};
use core::marker::PhantomData;
use heapless::Vec;

/// The most points per primary curve a table holds (a [`Phm`](crate::phm::Phm)
/// keeps its segment in a `u8`).
pub(super) const MAX_POINTS: u8 = 254;
/// Bytes before the point slots.
const COUNTS: usize = 4;

/// Bytes of one PHM record with `points` slots per curve in `scalar` (`usize::MAX` for a
/// `points` so large that the size does not fit).
pub fn phm_record_size(points: usize, scalar: ScalarKind) -> usize {
    points
        .saturating_mul(4)
        .saturating_add(SPECS.len())
        .saturating_mul(scalar.width())
        .saturating_add(COUNTS)
}

/// A verified table of PHM parameter sets in the arithmetic `S` with room
/// for `N` points per primary curve: every element passed
/// [`PhmParams::new`]'s validation when the table was loaded.
#[derive(Clone, Copy, Debug)]
pub struct PhmTable<'a, S, const N: usize = 8> {
    table: Table<'a>,
    _scalar: PhantomData<S>,
}

impl<'a, S: TableScalar, const N: usize> PhmTable<'a, S, N> {
    /// Parses and verifies `bytes` (see the [module docs](super)).
    pub fn load(bytes: &'a [u8]) -> Result<Self, TableError> {
        Table::parse(bytes)?.phm()
    }

    pub(super) fn verify(table: Table<'a>) -> Result<Self, TableError> {
        table.expect(ModelKind::Phm, S::KIND)?;
        let t = PhmTable {
            table,
            _scalar: PhantomData,
        };
        for i in 0..t.len() {
            t.decode(i)?;
        }
        Ok(t)
    }

    fn decode(&self, i: usize) -> Result<PhmParams<S, N>, TableError> {
        let h = self.table.header();
        let element = i as u16;
        let rec = self.table.record(i).ok_or(TableError::Truncated {
            needed: h.len as usize,
            found: self.table.bytes.len(),
        })?;
        let slots = h.option as usize;
        let width = S::KIND.width();
        let (counts, values) = rec
            .split_at_checked(COUNTS)
            .ok_or(TableError::RecordReserved { element })?;
        if counts.get(2..4) != Some(&[0, 0]) {
            return Err(TableError::RecordReserved { element });
        }
        let mut curves: [Vec<[S; 2], N>; 2] = [Vec::new(), Vec::new()];
        for (c, direction) in [Direction::Positive, Direction::Negative]
            .into_iter()
            .enumerate()
        {
            let count = counts.get(c).copied().unwrap_or(0);
            let bad = TableError::PointCount {
                element,
                direction,
                count,
            };
            if count as usize > slots {
                return Err(bad);
            }
            let curve = values
                .get(c * 2 * slots * width..(c + 1) * 2 * slots * width)
                .ok_or(bad)?;
            let (used, unused) = curve
                .split_at_checked(2 * count as usize * width)
                .ok_or(bad)?;
            if unused.iter().any(|&b| b != 0) {
                return Err(bad);
            }
            if count as usize > N {
                return Err(TableError::Phm {
                    element,
                    error: PhmError::Backbone(BackboneError {
                        direction,
                        point: count as usize,
                        rule: BackboneRule::TooManyPoints,
                    }),
                });
            }
            for p in used.chunks_exact(2 * width) {
                let (x, y) = (S::read(p), p.get(width..).and_then(S::read));
                if let (Some(x), Some(y)) = (x, y) {
                    // count <= N was checked: the push cannot fail.
                    let _ = curves[c].push([x, y]);
                }
            }
        }
        let mut k = [S::ZERO; SPECS.len()];
        let coefficients = values.get(4 * slots * width..).unwrap_or(&[]);
        for (v, bytes) in k.iter_mut().zip(coefficients.chunks_exact(width)) {
            *v = S::read(bytes).unwrap_or(S::ZERO);
        }
        PhmParams::new(&curves[0], &curves[1], Coefficients(k))
            .map_err(|error| TableError::Phm { element, error })
    }

    /// The header (units, points per curve, count).
    pub fn header(&self) -> &super::Header {
        self.table.header()
    }

    /// The number of elements (at least 1).
    pub fn len(&self) -> usize {
        self.table.header().count as usize
    }

    /// Always false: a table holds at least one element.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The parameters of element `i`, `None` if `i >= len()` (decoding
    /// repeats what [`load`](Self::load) verified, so it succeeds for every
    /// `i < len()`).
    pub fn get(&self, i: usize) -> Option<PhmParams<S, N>> {
        self.decode(i).ok()
    }

    /// The parameters of every element, in order.
    pub fn iter(&self) -> impl Iterator<Item = PhmParams<S, N>> + 'a {
        let t = *self;
        (0..t.len()).filter_map(move |i| t.get(i))
    }
}
