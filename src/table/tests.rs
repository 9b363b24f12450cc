//! The format against its definition: round trips for random valid sets in
//! every arithmetic, and every kind of bad input refused with its own error.

use super::*;
use crate::bwbn::{BoucWen, BwbnParams, EffectKind, ParamError, Rule, ZuRule};
use crate::phm::{BackboneError, BackboneRule, Coefficients, Direction, PhmError, PhmParams};
use crate::scalar::{Fixed, Scalar};
use proptest::prelude::*;
use std::vec;
use std::vec::Vec;

fn units() -> Units {
    Units::new("mm", "kN").unwrap()
}

fn plain() -> BwbnParams<f64> {
    BwbnParams::plain(BoucWen::new(6.0, 0.2, 1.2, 2.0, -1.0).unwrap())
}

/// The reference set with all four effects and an energy limit.
fn all_four() -> BwbnParams<f64> {
    crate::bwbn::selftest::history::Set::All.params()
}

fn bwbn_table(scalar: ScalarKind, elements: &[BwbnParams<f64>]) -> Vec<u8> {
    let effects = elements[0].effect_set();
    let mut out = vec![0u8; bwbn_len(effects, scalar, elements.len()).unwrap()];
    let n = write_bwbn(&mut out, scalar, &units(), elements).unwrap();
    assert_eq!(n, out.len());
    out
}

fn phm_params() -> PhmParams<f64> {
    PhmParams::new(
        &[[0.21, 105.0], [1.45, 168.0], [4.0, 172.0], [8.5, 140.0]],
        &[[0.22, 101.0], [1.40, 162.0], [4.0, 165.0]],
        Coefficients::thesis(),
    )
    .unwrap()
}

fn phm_table(scalar: ScalarKind, elements: &[PhmParams<f64>]) -> Vec<u8> {
    let mut out = vec![0u8; phm_len(4, scalar, elements.len()).unwrap()];
    let n = write_phm(
        &mut out,
        scalar,
        &Units::new("deg", "kN m").unwrap(),
        elements,
    )
    .unwrap();
    assert_eq!(n, out.len());
    out
}

/// Rewrites the CRC after a deliberate change, so the loader gets past it.
fn fix_crc(t: &mut [u8]) {
    let n = t.len();
    let crc = crc32(&t[..n - 4]);
    t[n - 4..].copy_from_slice(&crc.to_le_bytes());
}

/// What a device holding `p` rounded once into `S` would build.
fn rounded<S: Scalar>(p: &BwbnParams<f64>) -> Result<BwbnParams<S>, ParamError> {
    let limit = p.energy_limit();
    BwbnParams::from_named(p.effect_set(), |name| {
        if name == crate::bwbn::ENERGY_LIMIT {
            Some(if limit == f64::MAX {
                S::MAX
            } else {
                S::from_f64(limit)
            })
        } else {
            p.get(name).map(S::from_f64)
        }
    })
    .map(|q| q.with_zu_rule(p.zu_rule()))
}

#[test]
fn layout_matches_the_documented_offsets() {
    let t = bwbn_table(ScalarKind::F32, &[plain(), plain(), plain()]);
    assert_eq!(&t[0..4], b"HYTB");
    assert_eq!(u16::from_le_bytes([t[4], t[5]]), 1);
    assert_eq!((t[6], t[7], t[8], t[9]), (1, 2, 0, 0));
    assert_eq!(u16::from_le_bytes([t[10], t[11]]), 3);
    // 5 base parameters + energy_limit, 4 bytes each.
    assert_eq!(u16::from_le_bytes([t[12], t[13]]), 24);
    assert_eq!(&t[14..16], &[0, 0]);
    assert_eq!(
        u32::from_le_bytes(t[16..20].try_into().unwrap()),
        36 + 72 + 4
    );
    assert_eq!(&t[20..28], b"mm\0\0\0\0\0\0");
    assert_eq!(&t[28..36], b"kN\0\0\0\0\0\0");
    // The first record: k0, alpha, n, beta, gamma, no energy limit.
    let f = |i: usize| f32::from_le_bytes(t[36 + 4 * i..40 + 4 * i].try_into().unwrap());
    assert_eq!(
        [f(0), f(1), f(2), f(3), f(4), f(5)],
        [6.0, 0.2, 1.2, 2.0, -1.0, f32::MAX]
    );
    let crc = u32::from_le_bytes(t[108..112].try_into().unwrap());
    assert_eq!(crc, crc32(&t[..108]));

    let all = bwbn_table(ScalarKind::Q16, &[all_four()]);
    assert_eq!(all[8], 0b1111);
    assert_eq!(u16::from_le_bytes([all[12], all[13]]), (17 + 1) * 4);
    let raw = |i: usize| i32::from_le_bytes(all[36 + 4 * i..40 + 4 * i].try_into().unwrap());
    assert_eq!(raw(0), 6 << 16, "k0 = 6 in Q15.16");
    assert_eq!(raw(17), 2000 << 16, "energy_limit = 2000");

    let p = phm_table(ScalarKind::F64, &[phm_params()]);
    assert_eq!((p[6], p[7], p[8], p[9]), (2, 1, 0, 4));
    assert_eq!(&p[20..24], b"deg\0");
    assert_eq!(&p[28..32], b"kN m");
    assert_eq!((p[36], p[37], p[38], p[39]), (4, 3, 0, 0));
    let d = |at: usize| f64::from_le_bytes(p[at..at + 8].try_into().unwrap());
    assert_eq!(d(40), 0.21);
    // The negative curve's fourth slot is unused: zero.
    assert!(p[40 + 64 + 48..40 + 128].iter().all(|&b| b == 0));
    assert_eq!(d(40 + 128), -0.0028, "eq1a_a first among the coefficients");
}

/// The sizes `write_*` fill exactly, and `None` where they do not fit in `usize` (the
/// products overflowed: a panic in debug builds, a wrapped size in release; found by review).
#[test]
fn table_sizes_are_exact_or_none() {
    let one = bwbn_table(ScalarKind::F32, &[plain()]);
    assert_eq!(
        bwbn_len(EffectSet::NONE, ScalarKind::F32, 1),
        Some(one.len())
    );
    let one = phm_table(ScalarKind::F32, &[phm_params()]);
    assert_eq!(phm_len(4, ScalarKind::F32, 1), Some(one.len()));
    assert_eq!(
        bwbn_len(EffectSet::BWBN, ScalarKind::F64, usize::MAX / 8),
        None
    );
    assert_eq!(phm_len(4, ScalarKind::F64, usize::MAX / 8), None);
    assert_eq!(phm_len(usize::MAX / 4, ScalarKind::Q16, 1), None);
    assert_eq!(phm_record_size(usize::MAX, ScalarKind::F64), usize::MAX);
}

#[test]
fn round_trip_in_every_arithmetic() {
    let sets = [all_four(), all_four().with_zu_rule(ZuRule::OpenSees)];
    for set in sets {
        let t = bwbn_table(ScalarKind::F64, &[set, set]);
        let table = BwbnTable::<f64>::load(&t).unwrap();
        assert_eq!(table.iter().collect::<Vec<_>>(), vec![set, set]);
        assert_eq!(table.header().units, units());
        let t = bwbn_table(ScalarKind::F32, &[set]);
        assert_eq!(
            BwbnTable::<f32>::load(&t).unwrap().get(0),
            Some(rounded::<f32>(&set).unwrap())
        );
        let t = bwbn_table(ScalarKind::Q16, &[set]);
        assert_eq!(
            BwbnTable::<Fixed>::load(&t).unwrap().get(0),
            Some(rounded::<Fixed>(&set).unwrap())
        );
    }
    let p = phm_params();
    let t = phm_table(ScalarKind::F64, &[p.clone(), p.clone()]);
    let table = PhmTable::<f64>::load(&t).unwrap();
    assert_eq!(table.len(), 2);
    assert_eq!(table.get(1), Some(p));
    assert_eq!(table.get(2), None);
    assert_eq!(table.header().units.force(), "kN m");
}

#[test]
fn bad_input_gets_its_own_error() {
    let good = bwbn_table(ScalarKind::F32, &[plain()]);
    let load = |b: &[u8]| BwbnTable::<f32>::load(b).map(|t| t.len());
    assert_eq!(load(&good), Ok(1));

    // Truncated anywhere.
    for cut in 0..good.len() {
        let e = load(&good[..cut]).unwrap_err();
        assert!(
            matches!(e, TableError::Truncated { found, .. } if found == cut),
            "{cut}: {e}"
        );
    }
    // Trailing bytes (a table copied into a larger buffer must be cut to
    // its declared length).
    let mut long = good.clone();
    long.push(0xff);
    assert_eq!(
        load(&long),
        Err(TableError::TrailingBytes {
            declared: good.len(),
            found: good.len() + 1
        })
    );
    // Any single flipped bit is caught (CRC-32 detects every one; a flip in
    // magic, version or length is caught before the CRC).
    for byte in 0..good.len() {
        for bit in 0..8 {
            let mut t = good.clone();
            t[byte] ^= 1 << bit;
            assert!(load(&t).is_err(), "bit {bit} of byte {byte}");
        }
    }
    let mut t = good.clone();
    t[40] ^= 0x10;
    assert!(
        matches!(load(&t), Err(TableError::Checksum { stored, computed }) if stored != computed)
    );
    let mut t = good.clone();
    t[0] = b'X';
    assert_eq!(load(&t), Err(TableError::BadMagic));
    let mut t = good.clone();
    t[4] = 2;
    fix_crc(&mut t);
    assert_eq!(load(&t), Err(TableError::UnsupportedVersion(2)));

    // Wrong arithmetic or model for the caller.
    assert_eq!(
        BwbnTable::<f64>::load(&good).map(|t| t.len()),
        Err(TableError::WrongScalar {
            expected: ScalarKind::F64,
            found: ScalarKind::F32
        })
    );
    assert_eq!(
        PhmTable::<f32>::load(&good).map(|t| t.len()),
        Err(TableError::WrongModel {
            expected: ModelKind::Phm,
            found: ModelKind::Bwbn
        })
    );

    // Header fields, each with a valid CRC.
    let patched = |at: usize, v: u8| {
        let mut t = good.clone();
        t[at] = v;
        fix_crc(&mut t);
        load(&t)
    };
    assert_eq!(patched(6, 9), Err(TableError::UnknownModel(9)));
    assert_eq!(patched(7, 0), Err(TableError::UnknownScalar(0)));
    assert_eq!(patched(8, 0x40), Err(TableError::UnknownEffects(0x40)));
    assert_eq!(patched(9, 2), Err(TableError::BadOption(2)));
    assert_eq!(
        patched(14, 1),
        Err(TableError::ReservedNotZero { offset: 14 })
    );
    assert_eq!(patched(21, 0x07), Err(TableError::BadUnits));
    assert_eq!(
        patched(23, b'x'),
        Err(TableError::BadUnits),
        "text after NUL padding"
    );
    assert_eq!(
        patched(8, 0b1000),
        Err(TableError::RecordSize {
            expected: 4 * 12,
            found: 24
        })
    );
    assert_eq!(patched(10, 0), Err(TableError::NoElements));
    assert_eq!(
        patched(10, 2),
        Err(TableError::LengthMismatch {
            expected: 36 + 48 + 4,
            declared: 64
        })
    );

    // Out of range: alpha = 1.5 in element 0, with a valid CRC.
    let mut t = good.clone();
    t[40..44].copy_from_slice(&1.5f32.to_le_bytes());
    fix_crc(&mut t);
    assert_eq!(
        load(&t),
        Err(TableError::Bwbn {
            element: 0,
            error: ParamError {
                field: "alpha",
                rule: Rule::NotAFraction
            }
        })
    );
    assert_eq!(
        load(&t).unwrap_err().to_string(),
        "element 0: alpha must lie in [0, 1]"
    );
    // NaN anywhere is refused by the parameter set.
    let mut t = good.clone();
    t[36..40].copy_from_slice(&f32::NAN.to_le_bytes());
    fix_crc(&mut t);
    assert!(matches!(
        load(&t),
        Err(TableError::Bwbn {
            element: 0,
            error: ParamError { field: "k0", .. }
        })
    ));
}

#[test]
fn nothing_is_returned_from_a_table_with_one_bad_element() {
    let mut t = bwbn_table(ScalarKind::F64, &[plain(), plain(), plain()]);
    // Element 2's k0 = -1.
    let at = 36 + 2 * 48;
    t[at..at + 8].copy_from_slice(&(-1.0f64).to_le_bytes());
    fix_crc(&mut t);
    assert_eq!(
        BwbnTable::<f64>::load(&t).map(|t| t.len()),
        Err(TableError::Bwbn {
            element: 2,
            error: ParamError {
                field: "k0",
                rule: Rule::NotPositive
            }
        })
    );
}

#[test]
fn phm_records_are_checked() {
    let good = phm_table(ScalarKind::F32, &[phm_params()]);
    let load = |b: &[u8]| PhmTable::<f32>::load(b).map(|t| t.len());
    assert_eq!(load(&good), Ok(1));
    let patched = |at: usize, v: u8| {
        let mut t = good.clone();
        t[at] = v;
        fix_crc(&mut t);
        load(&t)
    };
    assert_eq!(
        patched(38, 1),
        Err(TableError::RecordReserved { element: 0 })
    );
    assert_eq!(
        patched(36, 5),
        Err(TableError::PointCount {
            element: 0,
            direction: Direction::Positive,
            count: 5
        })
    );
    // Three points stored, the fourth slot not zero.
    let slot = 40 + 32 + 3 * 8;
    assert_eq!(
        patched(slot, 1),
        Err(TableError::PointCount {
            element: 0,
            direction: Direction::Negative,
            count: 3
        })
    );
    let mut one_point = good.clone();
    one_point[37] = 1;
    one_point[72 + 8..72 + 24].fill(0);
    fix_crc(&mut one_point);
    assert_eq!(
        load(&one_point),
        Err(TableError::Phm {
            element: 0,
            error: PhmError::Backbone(BackboneError {
                direction: Direction::Negative,
                point: 1,
                rule: BackboneRule::TooFewPoints
            })
        })
    );
    assert_eq!(patched(9, 1), Err(TableError::BadOption(1)));
    // A PHM type with room for 3 points per curve cannot take a 4-point curve.
    assert_eq!(
        PhmTable::<f32, 3>::load(&good).map(|t| t.len()),
        Err(TableError::Phm {
            element: 0,
            error: PhmError::Backbone(BackboneError {
                direction: Direction::Positive,
                point: 4,
                rule: BackboneRule::TooManyPoints
            })
        })
    );
    // The cycle band (last coefficient) must be a fraction.
    let mut t = good.clone();
    let n = t.len();
    t[n - 8..n - 4].copy_from_slice(&1.5f32.to_le_bytes());
    fix_crc(&mut t);
    assert!(matches!(
        load(&t),
        Err(TableError::Phm {
            element: 0,
            error: PhmError::Coefficient(_)
        })
    ));
}

#[test]
fn writer_refuses_what_a_table_cannot_hold() {
    let mut buf = [0u8; 4096];
    let u = units();
    assert_eq!(
        write_bwbn::<f64>(&mut buf, ScalarKind::F32, &u, &[]),
        Err(WriteError::NoElements)
    );
    assert_eq!(
        write_bwbn(&mut buf, ScalarKind::F32, &u, &[plain(), all_four()]),
        Err(WriteError::Mixed { element: 1 })
    );
    assert_eq!(
        write_bwbn(
            &mut buf,
            ScalarKind::F32,
            &u,
            &[all_four(), all_four().with_zu_rule(ZuRule::OpenSees)]
        ),
        Err(WriteError::Mixed { element: 1 })
    );
    assert_eq!(
        write_bwbn(&mut buf[..50], ScalarKind::F32, &u, &[plain()]),
        Err(WriteError::BufferTooSmall {
            needed: 64,
            found: 50
        })
    );
    assert!(Units::new("millimetre", "kN").is_none());
    assert!(Units::new("mm", "k\u{e9}N").is_none());
    assert_eq!(Units::new("", "").unwrap().displacement(), "");
}

#[test]
fn values_a_q16_cannot_hold_are_refused_on_load_with_their_name() {
    let big = BwbnParams::plain(BoucWen::new(50_000.0, 0.2, 1.2, 2.0, -1.0).unwrap());
    let t = bwbn_table(ScalarKind::Q16, &[big]);
    assert_eq!(
        BwbnTable::<Fixed>::load(&t).map(|t| t.len()),
        Err(TableError::Bwbn {
            element: 0,
            error: ParamError {
                field: "k0",
                rule: Rule::NotFinite
            }
        })
    );
}

/// A random parameter set with the effects `bits`, values drawn from each
/// parameter's fitting range.
fn bwbn_set(
    bits: u8,
    unit: Vec<f64>,
    limit: Option<f64>,
    opensees: bool,
) -> Option<BwbnParams<f64>> {
    let effects = EffectSet::from_bits(bits & EffectSet::ALL.bits())?;
    let specs: Vec<_> = crate::bwbn::specs(effects).collect();
    let p = BwbnParams::from_named(effects, |name| {
        if name == crate::bwbn::ENERGY_LIMIT {
            return limit;
        }
        let i = specs.iter().position(|s| s.name == name)?;
        let (lo, hi) = specs[i].fit_range;
        Some(lo as f64 + (hi - lo) as f64 * unit[i])
    })
    .ok()?;
    Some(if opensees && effects.contains(EffectKind::Pinching) {
        p.with_zu_rule(ZuRule::OpenSees)
    } else {
        p
    })
}

fn check_round_trip<S: TableScalar>(elements: &[BwbnParams<f64>]) -> Result<(), TestCaseError> {
    let t = bwbn_table(S::KIND, elements);
    let expected: Result<Vec<_>, TableError> = elements
        .iter()
        .enumerate()
        .map(|(i, p)| {
            rounded::<S>(p).map_err(|error| TableError::Bwbn {
                element: i as u16,
                error,
            })
        })
        .collect();
    let loaded = BwbnTable::<S>::load(&t).map(|t| t.iter().collect::<Vec<_>>());
    prop_assert_eq!(loaded, expected);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Host-encode, device-decode: for random valid sets with random effects,
    /// every arithmetic loads exactly the set that rounding each value once
    /// into it gives, or, if the rounding breaks a rule (a small rate that
    /// Q15.16 rounds to zero), refuses the table naming the element and
    /// parameter the set itself names.
    #[test]
    fn bwbn_round_trip(
        bits in 0u8..32,
        unit in prop::collection::vec(0.0f64..1.0, 20),
        limit in prop::option::of(10.0f64..1e4),
        opensees in any::<bool>(),
        count in 1usize..5,
    ) {
        let set = bwbn_set(bits, unit, limit, opensees);
        prop_assume!(set.is_some());
        let elements = vec![set.unwrap(); count];
        check_round_trip::<f64>(&elements)?;
        check_round_trip::<f32>(&elements)?;
        check_round_trip::<Fixed>(&elements)?;
    }

    /// The same for PHM: random primary curves and coefficients.
    #[test]
    fn phm_round_trip(
        dx in prop::collection::vec(0.05f64..3.0, 2..7),
        k1 in 1.0f64..50.0,
        fall in 0.0f64..0.5,
        neg_scale in 0.5f64..1.5,
        scale in prop::collection::vec(-1.0f64..3.0, crate::phm::SPECS.len()),
    ) {
        let mut pts = Vec::new();
        let (mut x, mut t) = (0.0, 0.0);
        for (i, d) in dx.iter().enumerate() {
            let k = match i { 0 => k1, 1 => 0.2 * k1, _ => -fall * k1 };
            x += d;
            t = (t + k * d).max(0.3 * t);
            pts.push([x, t]);
        }
        let neg: Vec<[f64; 2]> = pts.iter().map(|p| [p[0] * neg_scale, p[1]]).collect();
        let mut c = Coefficients::<f64>::thesis();
        for (v, s) in c.0.iter_mut().zip(&scale) {
            *v *= s;
        }
        let band = crate::phm::rules::idx::CYCLE_BAND;
        c.0[band] = c.0[band].abs().min(1.0);
        let p = PhmParams::<f64>::new(&pts, &neg[..neg.len().clamp(2, 3)], c);
        prop_assume!(p.is_ok());
        let p = p.unwrap();
        fn expect<S: TableScalar>(p: &PhmParams<f64>) -> Result<PhmParams<S>, PhmError> {
            let r = |c: &[[f64; 2]]| c.iter().map(|q| q.map(S::from_f64)).collect::<Vec<_>>();
            let mut k = Coefficients::<S>::thesis();
            for (v, &x) in k.0.iter_mut().zip(p.coefficients().0.iter()) {
                *v = S::from_f64(x);
            }
            PhmParams::new(
                &r(p.primary(Direction::Positive).points()),
                &r(p.primary(Direction::Negative).points()),
                k,
            )
        }
        fn check<S: TableScalar>(p: &PhmParams<f64>) -> Result<(), TestCaseError> {
            let mut out = vec![0u8; phm_len(8, S::KIND, 2).unwrap()];
            let n = write_phm(&mut out, S::KIND, &Units::default(), &[p.clone(), p.clone()]).unwrap();
            let loaded = PhmTable::<S>::load(&out[..n]).map(|t| t.iter().collect::<Vec<_>>());
            let want = expect::<S>(p).map(|q| vec![q.clone(), q]).map_err(|error| TableError::Phm { element: 0, error });
            prop_assert_eq!(loaded, want);
            Ok(())
        }
        check::<f64>(&p)?;
        check::<f32>(&p)?;
        check::<Fixed>(&p)?;
    }

    /// Random bytes, and random changes to a valid table (with the CRC
    /// rewritten, so the header and record checks are reached): never a
    /// panic, and a table that loads decodes every element it counts.
    #[test]
    fn arbitrary_bytes_never_panic(
        noise in prop::collection::vec(any::<u8>(), 0..200),
        edits in prop::collection::vec((0usize..200, any::<u8>()), 0..6),
        model in 0usize..2,
    ) {
        let _ = Table::parse(&noise);
        let mut t = if model == 0 {
            bwbn_table(ScalarKind::F32, &[all_four(), all_four()])
        } else {
            phm_table(ScalarKind::F32, &[phm_params()])
        };
        let n = t.len();
        for (at, v) in edits {
            t[at % (n - 4)] = v;
        }
        fix_crc(&mut t);
        if let Ok(b) = BwbnTable::<f32>::load(&t) {
            prop_assert_eq!(b.iter().count(), b.len());
        }
        if let Ok(p) = PhmTable::<f32>::load(&t) {
            prop_assert_eq!(p.iter().count(), p.len());
        }
    }
}
