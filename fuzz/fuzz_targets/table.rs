//! The table loader on arbitrary bytes: it must never panic, and a table it
//! accepts must give as many elements as it counts, each of which builds an
//! element that steps without panicking.
//!
//! The first byte chooses how the rest is used: with bit 0 set, the last four
//! bytes are replaced by the CRC-32 of the others before loading, so the
//! fuzzer gets past the checksum and explores the header and record checks
//! and the models' validation; otherwise the bytes are loaded as they are.
#![no_main]

use hysteresis::bwbn::Bwbn;
use hysteresis::phm::Phm;
use hysteresis::table::{crc32, BwbnTable, PhmTable, Table, TableScalar};
use hysteresis::{Element, Fixed, Scalar};
use libfuzzer_sys::fuzz_target;

/// A few steps out and back: enough to run the element's code on the
/// loaded values, bounded in time.
fn drive<S: Scalar, E: Element<S>>(mut el: E) {
    for k in [1, 3, -2, 0] {
        if el.set_trial(S::from_i32(k)).is_ok() {
            el.commit();
        }
    }
}

fn bwbn<S: TableScalar>(bytes: &[u8]) {
    if let Ok(t) = BwbnTable::<S>::load(bytes) {
        assert_eq!(t.iter().count(), t.len());
        for p in t.iter().take(4) {
            drive(Bwbn::new(p));
        }
    }
}

fn phm<S: TableScalar>(bytes: &[u8]) {
    if let Ok(t) = PhmTable::<S, 8>::load(bytes) {
        assert_eq!(t.iter().count(), t.len());
        for p in t.iter().take(4) {
            drive(Phm::<S, 8, 4>::new(p));
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut buf = rest.to_vec();
    if mode & 1 == 1 && buf.len() >= 4 {
        let n = buf.len() - 4;
        let crc = crc32(&buf[..n]);
        buf[n..].copy_from_slice(&crc.to_le_bytes());
    }
    if Table::parse(&buf).is_err() {
        return;
    }
    bwbn::<f64>(&buf);
    bwbn::<f32>(&buf);
    bwbn::<Fixed>(&buf);
    phm::<f64>(&buf);
    phm::<f32>(&buf);
    phm::<Fixed>(&buf);
});
