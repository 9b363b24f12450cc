//! The CSV writer: what it writes reads back to the same bits.

use super::data_dir;
use crate::data::{
    read, read_str, write_columns, write_record, Format, ReadOptions, Record, WriteError,
};

#[test]
fn round_trip_of_a_record_is_bit_exact() {
    for (name, options) in [
        (
            "synthetic/s2_hidden_degradation.csv",
            ReadOptions::default(),
        ),
        (
            "boucwen-benchmark/csv/test_multisine.csv",
            ReadOptions::default().sample_rate(750.0),
        ),
        ("peer-spd-columns/fd/spd_381.csv", ReadOptions::default()),
    ] {
        let r = read(data_dir().join(name), &options).unwrap();
        let mut out = Vec::new();
        write_record(&mut out, &r).unwrap();
        let text = String::from_utf8(out).unwrap();
        for line in text.lines() {
            assert!(!line.ends_with(','), "{name}: trailing comma in '{line}'");
        }
        let back = read_str(
            "back.csv",
            &text,
            Format::Csv,
            &ReadOptions::default().input(r.input_channel()),
        )
        .unwrap();
        let bits = |x: Option<&[f64]>| x.map(|v| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>());
        assert_eq!(bits(back.time()), bits(r.time()), "{name}");
        assert_eq!(bits(back.displacement()), bits(r.displacement()), "{name}");
        assert_eq!(bits(back.force()), bits(r.force()), "{name}");
        assert_eq!(back.comments(), r.comments());
        assert!(back.notices().is_empty(), "{name}: {:?}", back.notices());
    }
}

#[test]
fn header_and_history_layout() {
    let r = Record::from_history("h", vec![0.0, 1.5, -2.25], Some(0.5)).unwrap();
    let mut out = Vec::new();
    write_record(&mut out, &r).unwrap();
    assert_eq!(
        String::from_utf8(out).unwrap(),
        "time (s),displacement (mm)\n0,0\n0.5,1.5\n1,-2.25\n"
    );
}

#[test]
fn refuses_what_the_reader_would_refuse() {
    let a = [1.0, 2.0];
    let b = [1.0];
    let nan = [1.0, f64::NAN];
    let e = |cols: &[(&str, &[f64])]| {
        write_columns(Vec::new(), &[], cols)
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        e(&[("x (mm)", &a), ("y (kN)", &b)]),
        "expected 2 values in column 'y (kN)' like the first column, found 1"
    );
    assert_eq!(
        e(&[("x (mm)", &a), ("y (kN)", &nan)]),
        "expected finite values, found NaN in column 'y (kN)' at sample 1"
    );
    assert_eq!(
        e(&[("x, mm", &a)]),
        "expected a non-empty header without commas, quotes or line breaks, found 'x, mm'"
    );
    assert!(matches!(
        write_columns(Vec::new(), &[], &[("", &a)]),
        Err(WriteError::BadHeader(_))
    ));
}
