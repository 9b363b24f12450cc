//! BWBN records: the values of [`BwbnParams::for_each`] in its order (base
//! parameters, then each effect's, in the order of [`specs`]), then
//! `energy_limit` (the arithmetic's largest value for "no limit").

use super::{ModelKind, ScalarKind, Table, TableError, TableScalar};
use crate::bwbn::{specs, BwbnParams, EffectSet, ZuRule, ENERGY_LIMIT};
use core::marker::PhantomData;

/// Bytes of one BWBN record with the effects `effects` in `scalar`.
pub fn bwbn_record_size(effects: EffectSet, scalar: ScalarKind) -> usize {
    (specs(effects).count() + 1) * scalar.width()
}

/// A verified table of BWBN parameter sets in the arithmetic `S`: every
/// element passed [`BwbnParams::from_named`]'s validation when the table was
/// loaded. Borrows the table's bytes; an element is decoded from them when
/// asked for.
#[derive(Clone, Copy, Debug)]
pub struct BwbnTable<'a, S> {
    table: Table<'a>,
    _scalar: PhantomData<S>,
}

impl<'a, S: TableScalar> BwbnTable<'a, S> {
    /// Parses and verifies `bytes` (see the [module docs](super)): a table
    /// of BWBN elements in `S`, each a valid parameter set, or the first
    /// reason it is not.
    pub fn load(bytes: &'a [u8]) -> Result<Self, TableError> {
        Table::parse(bytes)?.bwbn()
    }

    pub(super) fn verify(table: Table<'a>) -> Result<Self, TableError> {
        table.expect(ModelKind::Bwbn, S::KIND)?;
        let t = BwbnTable {
            table,
            _scalar: PhantomData,
        };
        for i in 0..t.len() {
            t.decode(i)?;
        }
        Ok(t)
    }

    fn decode(&self, i: usize) -> Result<BwbnParams<S>, TableError> {
        let h = self.table.header();
        let rec = self.table.record(i).ok_or(TableError::Truncated {
            needed: h.len as usize,
            found: self.table.bytes.len(),
        })?;
        let width = S::KIND.width();
        let value = |k: usize| rec.get(k * width..).and_then(S::read);
        let n = specs(h.effects).count();
        let p = BwbnParams::from_named(h.effects, |name| {
            if name == ENERGY_LIMIT {
                value(n)
            } else {
                specs(h.effects)
                    .position(|s| s.name == name)
                    .and_then(value)
            }
        })
        .map_err(|error| TableError::Bwbn {
            element: i as u16,
            error,
        })?;
        Ok(if h.option == 1 {
            p.with_zu_rule(ZuRule::OpenSees)
        } else {
            p
        })
    }

    /// The header (units, effects, count).
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

    /// The parameters of element `i`, `None` if `i >= len()`.
    ///
    /// Decoding repeats what [`load`](Self::load) verified, on the same
    /// bytes, so it succeeds for every `i < len()`.
    pub fn get(&self, i: usize) -> Option<BwbnParams<S>> {
        self.decode(i).ok()
    }

    /// The parameters of every element, in order.
    pub fn iter(&self) -> impl Iterator<Item = BwbnParams<S>> + 'a {
        let t = *self;
        (0..t.len()).filter_map(move |i| t.get(i))
    }
}
