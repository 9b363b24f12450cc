//! Synthetic histories: the OpenSees reference history bit for bit, protocols,
//! and the irregular path's generator, filter and statistics.

use super::data_dir;
use crate::data::history::{BandPass, Normal};
use crate::data::{read, Cycles, Irregular, Protocol, ReadOptions, Shape, Threshold};
use std::f64::consts::PI;

#[test]
fn opensees_reference_history_is_reproduced_bit_for_bit() {
    let file = read(
        data_dir().join("opensees-reference/history.csv"),
        &ReadOptions::default(),
    )
    .unwrap();
    let made = Protocol::opensees_reference().generate().unwrap();
    assert_eq!(made.len(), 3601);
    assert!(made
        .iter()
        .zip(file.input())
        .all(|(a, b)| a.to_bits() == b.to_bits()));
}

#[test]
fn protocols() {
    let p = Protocol::geometric(1.0, 1.4, 6.0, 2, 40).unwrap();
    let amps: Vec<f64> = p
        .amplitudes
        .iter()
        .map(|a| (a * 1e6).round() / 1e6)
        .collect();
    assert_eq!(amps, [1.0, 1.4, 1.96, 2.744, 3.8416, 5.37824]);
    let u = p.generate().unwrap();
    assert_eq!(u.len(), 1 + 6 * 2 * 40);
    let c = Cycles::find(&u, Threshold::default()).unwrap();
    assert_eq!(c.complete_cycles(), 12);
    // Sine cycles: peaks at quarter periods, back to 0 at each cycle's end.
    let s = Protocol {
        amplitudes: vec![2.0],
        cycles_per_amplitude: 2,
        steps_per_cycle: 8,
        shape: Shape::Sine,
    }
    .generate()
    .unwrap();
    assert_eq!(s[2], 2.0);
    assert_eq!(s[6], -2.0);
    assert!(s[8].abs() < 1e-15 && s[16].abs() < 1e-15);
    assert!(Protocol {
        steps_per_cycle: 3,
        ..p.clone()
    }
    .generate()
    .is_err());
    assert!(Protocol {
        amplitudes: vec![f64::NAN],
        ..p.clone()
    }
    .generate()
    .is_err());
    assert!(Protocol::geometric(1.0, 1.0, 6.0, 2, 40).is_err());
}

#[test]
fn normal_deviates_have_unit_variance() {
    let n = 200_000;
    let mut g = Normal::new(42);
    let x: Vec<f64> = (0..n).map(|_| g.sample()).collect();
    let mean = x.iter().sum::<f64>() / n as f64;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let kurt = x.iter().map(|v| (v - mean).powi(4)).sum::<f64>() / n as f64 / (var * var);
    // Five standard errors: sd(mean) = 1/sqrt(n), sd(var) = sqrt(2/n), sd(kurtosis) = sqrt(24/n).
    let nf = n as f64;
    assert!(mean.abs() < 5.0 / nf.sqrt(), "{mean}");
    assert!((var - 1.0).abs() < 5.0 * (2.0 / nf).sqrt(), "{var}");
    assert!((kurt - 3.0).abs() < 5.0 * (24.0 / nf).sqrt(), "{kurt}");
    // The fraction within one sd is erf(1/sqrt 2) = 0.682689...
    let within = x.iter().filter(|v| v.abs() < 1.0).count() as f64 / nf;
    let p = 0.682_689_492;
    assert!(
        (within - p).abs() < 5.0 * (p * (1.0 - p) / nf).sqrt(),
        "{within}"
    );
}

/// Steady-state gain of the band-pass for a sine of frequency `f`, by least
/// squares on whole periods after the transient has died out.
fn measured_gain(band: &BandPass, f: f64, dt: f64) -> f64 {
    let per = (1.0 / (f * dt)).round() as usize;
    let n = per * 400;
    let x: Vec<f64> = (0..n)
        .map(|k| (2.0 * PI * f * k as f64 * dt).sin())
        .collect();
    let y = band.filter(&x);
    let (mut s, mut c) = (0.0, 0.0);
    let tail = n - per * 100;
    for (k, &v) in y.iter().enumerate().skip(tail) {
        let w = 2.0 * PI * f * k as f64 * dt;
        s += v * w.sin();
        c += v * w.cos();
    }
    2.0 * (s * s + c * c).sqrt() / (n - tail) as f64
}

#[test]
fn band_pass_gain_matches_the_bilinear_closed_form() {
    // |H| = 1 / sqrt(1 + Q^2 (W - 1/W)^2) with W = tan(pi f dt) / tan(pi f0 dt).
    let (f0, q, dt) = (2.0, 3.0, 0.01);
    let band = BandPass::new(f0, q, dt);
    for f in [0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0] {
        let w = (PI * f * dt).tan() / (PI * f0 * dt).tan();
        let exact = 1.0 / (1.0 + q * q * (w - 1.0 / w).powi(2)).sqrt();
        let g = measured_gain(&band, f, dt);
        assert!(
            (g - exact).abs() < 2e-3 * exact.max(0.01),
            "f = {f}: {g} vs {exact}"
        );
    }
}

#[test]
fn irregular_path_is_reproducible_scaled_and_narrow_band() {
    let p = Irregular {
        samples: 40_001,
        dt: 0.01,
        frequency_hz: 1.5,
        q: 2.0,
        peak: 25.0,
        peak_time_fraction: 0.3,
        seed: 11,
    };
    let u = p.generate().unwrap();
    assert_eq!(u, p.generate().unwrap());
    assert_ne!(
        u,
        Irregular {
            seed: 12,
            ..p.clone()
        }
        .generate()
        .unwrap()
    );
    assert_eq!(u.iter().fold(0.0f64, |m, v| m.max(v.abs())), 25.0);
    assert_eq!((u[0], u[40_000]), (0.0, 0.0));
    // Upcrossings of zero: the envelope does not move them, so their rate is
    // that of the filtered noise, which Rice's formula gives from the filter's
    // closed-form gain: sqrt(∫ f² |H|⁴ df / ∫ |H|⁴ df) (1.12 f0 for q = 2 in
    // the analog limit). Over 400 s about 670 upcrossings are expected.
    let gain2 = |f: f64| {
        let w = (PI * f * 0.01).tan() / (PI * 1.5 * 0.01).tan();
        1.0 / (1.0 + 4.0 * (w - 1.0 / w).powi(2))
    };
    let (mut m0, mut m2) = (0.0, 0.0);
    for k in 1..50_000 {
        let f = 50.0 * k as f64 / 50_000.0;
        let s = gain2(f).powi(2);
        m0 += s;
        m2 += f * f * s;
    }
    let rice = (m2 / m0).sqrt();
    assert!((rice / 1.5 - 1.118).abs() < 0.01, "{rice}");
    let ups = u.windows(2).filter(|w| w[0] < 0.0 && w[1] >= 0.0).count() as f64;
    let rate = ups / 400.0;
    assert!((rate / rice - 1.0).abs() < 0.08, "{rate} Hz vs {rice} Hz");
    // The envelope: the strong phase is near 30 % of the duration, quiet at the ends.
    let rms =
        |a: usize, b: usize| (u[a..b].iter().map(|v| v * v).sum::<f64>() / (b - a) as f64).sqrt();
    let (start, strong, end) = (rms(0, 2000), rms(10_000, 14_000), rms(38_000, 40_000));
    assert!(
        strong > 5.0 * start && strong > 5.0 * end,
        "{start} {strong} {end}"
    );
    // Bad parameters are refused.
    assert!(Irregular {
        frequency_hz: 50.0,
        ..p.clone()
    }
    .generate()
    .is_err());
    assert!(Irregular {
        peak: 0.0,
        ..p.clone()
    }
    .generate()
    .is_err());
    assert!(Irregular {
        samples: 2,
        ..p.clone()
    }
    .generate()
    .is_err());
    assert!(Irregular {
        peak_time_fraction: 0.95,
        ..p
    }
    .generate()
    .is_err());
}
