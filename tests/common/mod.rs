//! Helpers shared by the host integration tests: reading the reference data in
//! `../shared/data`.
#![allow(dead_code)]

use hysteresis::bwbn::{BwbnParams, EffectSet};
use hysteresis::Scalar;
use std::path::PathBuf;

/// The parameters of the OpenSees reference cases (`cases.json`) with the
/// effects of `set` switched on: k0 6, alpha 0.2, n 1.2, beta 2, gamma -1,
/// the degradation of `BoucWen_degrade` and the pinching of `BWBN_pinch`.
/// Degradation: A = A0 - dA e, nu = 1 + dnu e, eta = 1 + deta e. A reaches
/// zero at e = 5000 kN*mm, so the set is only valid below that (energy limit
/// 4500); the reference history reaches 785 kN*mm.
pub fn reference_params(set: EffectSet) -> BwbnParams<f64> {
    reference_params_in(set)
}

/// [`reference_params`] in the arithmetic `S` (each value rounded once).
pub fn reference_params_in<S: Scalar>(set: EffectSet) -> BwbnParams<S> {
    const VALUES: [(&str, f64); 15] = [
        ("k0", 6.0),
        ("alpha", 0.2),
        ("n", 1.2),
        ("beta", 2.0),
        ("gamma", -1.0),
        ("delta_A", 2e-4),
        ("delta_nu", 5e-4),
        ("delta_eta", 5e-4),
        ("energy_limit", 4500.0),
        ("zeta0", 0.9),
        ("p", 0.01),
        ("q", 0.1),
        ("psi0", 0.2),
        ("delta_psi", 5e-4),
        ("lambda", 0.5),
    ];
    BwbnParams::from_named(set, |name| {
        VALUES
            .iter()
            .find(|(k, _)| *k == name)
            .map(|(_, v)| S::from_f64(*v))
    })
    .expect("valid reference parameters")
}

/// Path of a file in the shared data folder.
pub fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(rel)
}

/// Reads a numeric CSV with one header line; returns the header and the rows.
pub fn read_csv(rel: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let path = data(rel);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|v| v.trim().parse::<f64>().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (header, rows)
}

/// The displacement history of the OpenSees reference cases (mm).
pub fn reference_history() -> Vec<f64> {
    read_csv("opensees-reference/history.csv")
        .1
        .iter()
        .map(|r| r[1])
        .collect()
}

/// One OpenSees reference case: (strain, stress) rows.
pub fn reference_case(name: &str) -> Vec<(f64, f64)> {
    read_csv(&format!("opensees-reference/{name}.csv"))
        .1
        .iter()
        .map(|r| (r[1], r[2]))
        .collect()
}

/// In-place radix-2 complex FFT (`inverse` scales by 1/n). Length must be a
/// power of two. Used to interpolate band-limited periodic test signals.
pub fn fft(re: &mut [f64], im: &mut [f64], inverse: bool) {
    let n = re.len();
    assert!(n.is_power_of_two() && im.len() == n);
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let ang = sign * 2.0 * std::f64::consts::PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (ang * k as f64).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let (tr, ti) = (re[b] * c - im[b] * s, re[b] * s + im[b] * c);
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
            }
        }
        len <<= 1;
    }
    if inverse {
        for v in re.iter_mut().chain(im.iter_mut()) {
            *v /= n as f64;
        }
    }
}

/// Band-limited interpolation of one period of a periodic real signal by an
/// integer factor (zero-padding its spectrum).
pub fn interpolate_periodic(x: &[f64], factor: usize) -> Vec<f64> {
    let n = x.len();
    let m = n * factor;
    let (mut re, mut im) = (x.to_vec(), vec![0.0; n]);
    fft(&mut re, &mut im, false);
    let (mut zr, mut zi) = (vec![0.0; m], vec![0.0; m]);
    for k in 0..n / 2 {
        zr[k] = re[k];
        zi[k] = im[k];
        if k > 0 {
            zr[m - k] = re[n - k];
            zi[m - k] = im[n - k];
        }
    }
    // split the Nyquist bin between +n/2 and -n/2
    zr[n / 2] = re[n / 2] / 2.0;
    zr[m - n / 2] = re[n / 2] / 2.0;
    fft(&mut zr, &mut zi, true);
    zr.iter().map(|v| v * factor as f64).collect()
}

/// Band-limited rate of one period of a periodic real signal sampled every
/// `dt` (its spectrum times `i w`; the Nyquist bin, whose rate is not defined
/// by the samples, is dropped).
pub fn rate_periodic(x: &[f64], dt: f64) -> Vec<f64> {
    let n = x.len();
    let (mut re, mut im) = (x.to_vec(), vec![0.0; n]);
    fft(&mut re, &mut im, false);
    let w1 = 2.0 * std::f64::consts::PI / (n as f64 * dt);
    for k in 0..n {
        let w = if k < n / 2 {
            k as f64 * w1
        } else if k > n / 2 {
            -((n - k) as f64) * w1
        } else {
            0.0
        };
        (re[k], im[k]) = (-w * im[k], w * re[k]);
    }
    fft(&mut re, &mut im, true);
    re
}
