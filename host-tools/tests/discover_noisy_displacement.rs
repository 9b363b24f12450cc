//! Noise in the imposed displacement: the reversals it makes must not become
//! a physical effect.
//!
//! The records come from a simulator written here, apart from the core: BWBN
//! in dz/du form integrated by classical Runge-Kutta at 40 steps a sample,
//! hysteretic energy normalised by k Zu0^2, along sine cycles of 5 to 100 mm
//! (two at each amplitude, 100 samples a cycle), with the noise of
//! `../shared/data/synthetic/`: 0.2 mm on the displacement and 1% of the peak
//! on the force. Strong stiffness degradation behind that noise was named
//! together with a strength degradation that is not there (delta-BIC -28, on
//! five seeds of five) before the loader made such a displacement monotone
//! between the test's reversals (`hyst::fit::input_noise`).

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, stderr, write};
use serde_json::Value;

/// Samples per cycle, and the cycles' amplitudes (mm), two cycles each.
const PER_CYCLE: usize = 100;
const AMPLITUDES: [f64; 8] = [5.0, 10.0, 20.0, 30.0, 40.0, 60.0, 80.0, 100.0];

/// A standard normal stream (Box-Muller on xorshift).
struct Normal(u64);

impl Normal {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn sample(&mut self) -> f64 {
        let (a, b) = (self.uniform(), self.uniform());
        (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
    }
}

/// What the simulator hides, and along which cycles.
#[derive(Clone, Copy)]
struct Hidden {
    /// Stiffness degradation per unit of normalised energy.
    delta_eta: f64,
    /// Pinching (zeta0 0.9, p 0.5, q 0.1, psi 0.2, lambda 0.3, the width
    /// in units of Zu0).
    pinching: bool,
    /// Triangular cycles instead of sine ones.
    triangular: bool,
}

const SINE: Hidden = Hidden {
    delta_eta: 0.0,
    pinching: false,
    triangular: false,
};

/// The record as CSV, with noise `(displacement mm, force fraction of
/// peak)`.
fn record(hidden: Hidden, noise: (f64, f64), seed: u64) -> String {
    let (k, alpha, n, beta, gamma) = (50.0, 0.05, 1.5, 0.02, 0.0116);
    let zu0 = (1.0f64 / (beta + gamma)).powf(1.0 / n);
    let mut u = vec![0.0];
    for a in AMPLITUDES {
        for _ in 0..2 {
            for i in 1..=PER_CYCLE {
                let t = i as f64 / PER_CYCLE as f64;
                u.push(
                    a * if !hidden.triangular {
                        (2.0 * std::f64::consts::PI * t).sin()
                    } else if t <= 0.25 {
                        4.0 * t
                    } else if t <= 0.75 {
                        2.0 - 4.0 * t
                    } else {
                        4.0 * t - 4.0
                    },
                );
            }
        }
    }
    let zeta0 = if hidden.pinching { 0.9 } else { 0.0 };
    // (dz/du, de/du) along an increment of sign `s`.
    let rate = |z: f64, e: f64, s: f64| {
        let sg = if s * z >= 0.0 { 1.0 } else { -1.0 };
        let zeta1 = zeta0 * (1.0 - (-0.5 * e).exp());
        let zeta2 = 0.2 * zu0 * (0.3 + zeta1);
        let h = 1.0 - zeta1 * (-(z * s - 0.1 * zu0).powi(2) / (zeta2 * zeta2)).exp();
        let dz = h * (1.0 - z.abs().powf(n) * (beta * sg + gamma)) / (1.0 + hidden.delta_eta * e);
        (dz, (1.0 - alpha) * k * z / (k * zu0 * zu0))
    };
    let (mut z, mut e) = (0.0f64, 0.0f64);
    let mut f = vec![0.0];
    for w in u.windows(2) {
        let h = (w[1] - w[0]) / 40.0;
        let s = h.signum();
        for _ in 0..40 {
            let k1 = rate(z, e, s);
            let k2 = rate(z + 0.5 * h * k1.0, e + 0.5 * h * k1.1, s);
            let k3 = rate(z + 0.5 * h * k2.0, e + 0.5 * h * k2.1, s);
            let k4 = rate(z + h * k3.0, e + h * k3.1, s);
            z += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            e += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        f.push(alpha * k * w[1] + (1.0 - alpha) * k * z);
    }
    let peak = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut g = Normal(0x9e37_79b9_7f4a_7c15 ^ seed);
    let mut text = String::from("time (s),displacement (mm),force (kN)\n");
    for (i, (ui, fi)) in u.iter().zip(&f).enumerate() {
        let um = ui + noise.0 * g.sample();
        let fm = fi + noise.1 * peak * g.sample();
        text += &format!("{:.3},{um:.5},{fm:.5}\n", 0.6 * i as f64);
    }
    text
}

/// `hyst VERB FILE --model bw --json ARGS`, parsed, and its stderr.
fn run(verb: &str, file: &str, args: &[&str]) -> (Value, String) {
    let mut all = vec![verb, file, "--model", "bw", "--json"];
    all.extend_from_slice(args);
    let o = ok(hyst(&all));
    let json = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    (json, stderr(&o))
}

/// The test's reversals: a peak and a trough a cycle.
const REVERSALS: u64 = 2 * 2 * AMPLITUDES.len() as u64;

/// Named alone on every record. Before the loader made the displacement
/// monotone, all five named strength degradation too; with the monotone
/// displacement but each reversal taken from its one sample, seed 0 still
/// did (delta-BIC -12.5 against the threshold of 10, NRMSE 0.02192 ->
/// 0.02174). Placing the reversals from the samples around them took the
/// fit to 0.02096 and the extra effect away (measured on seeds 0-9: alone on
/// all ten).
#[test]
fn stiffness_degradation_behind_a_noisy_displacement_is_named_alone() {
    for seed in 0..5 {
        let file = write(
            &format!("stiffness-{seed}.csv"),
            &record(
                Hidden {
                    delta_eta: 0.02,
                    ..SINE
                },
                (0.2, 0.01),
                seed,
            ),
        );
        let (json, err) = run("discover", &file, &[]);
        assert_eq!(
            json["model"], "bw+stiffness-degradation",
            "seed {seed}: {:#}",
            json["ladder"]
        );
        let noise = &json["displacement_noise"];
        assert_eq!(noise["kept_reversals"], REVERSALS, "seed {seed}: {noise}");
        // Sine cycles: rounded corners, each placed by its parabola.
        assert_eq!(noise["corner_shape"], "parabola", "seed {seed}: {noise}");
        assert_eq!(
            noise["refined_reversals"], REVERSALS,
            "seed {seed}: {noise}"
        );
        let sd = noise["noise"].as_f64().unwrap();
        assert!((sd / 0.2 - 1.0).abs() < 0.1, "seed {seed}: noise {sd}");
        assert!(
            err.contains("made monotone between the 32 reversals"),
            "{err}"
        );
    }
}

/// Seed 16 named asymmetry at delta-BIC -19 before its signature gated (the
/// peak ratio within the cycles' scatter of the model's).
#[test]
fn nothing_is_named_behind_a_noisy_displacement_when_nothing_is_missing() {
    for seed in [10, 11, 16] {
        let file = write(
            &format!("control-{seed}.csv"),
            &record(SINE, (0.2, 0.01), seed),
        );
        let (json, _) = run("discover", &file, &[]);
        assert_eq!(json["model"], "bw", "seed {seed}: {:#}", json["ladder"]);
        let suspects = json["suspects"].as_array().unwrap();
        assert!(
            suspects.iter().all(|s| s["significant"] == false),
            "seed {seed}: {suspects:#?}"
        );
    }
}

#[test]
fn a_displacement_whose_reversals_are_the_tests_is_read_as_measured() {
    // Force noise only: the displacement's reversals are all the test's.
    let file = write(
        "clean.csv",
        &record(
            Hidden {
                delta_eta: 0.02,
                ..SINE
            },
            (0.0, 0.01),
            1,
        ),
    );
    let (json, err) = run("fit", &file, &[]);
    assert_eq!(json["displacement_noise"], Value::Null, "{err}");
    assert!(!err.contains("monotone"), "{err}");
    // A real column test (Lehman and Moehle 415).
    let column = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/peer-spd-columns/fd/spd_369.csv"
    );
    let (json, err) = run("fit", column, &[]);
    assert_eq!(json["displacement_noise"], Value::Null, "{err}");
}

#[test]
fn raw_displacement_keeps_the_measurement_and_the_fit_file_says_what_was_done() {
    let file = write("noisy.csv", &record(SINE, (0.2, 0.01), 3));
    let (json, err) = run("fit", &file, &["--raw-displacement"]);
    assert_eq!(json["displacement_noise"], Value::Null);
    assert!(!err.contains("monotone"), "{err}");
    let raw = json["nrmse"].as_f64().unwrap();
    let out = cli::tmp("noisy-fit.json");
    let (json, _) = run("fit", &file, &["--out", out.to_str().unwrap()]);
    // The noise the model no longer sees is error it no longer makes.
    let monotone = json["nrmse"].as_f64().unwrap();
    assert!(monotone < 0.9 * raw, "{monotone} against {raw}");
    let saved: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(
        saved["fit"]["displacement_noise"]["kept_reversals"],
        REVERSALS
    );
}

const TRIANGLES: Hidden = Hidden {
    triangular: true,
    ..SINE
};

/// Triangular cycles turn sharply, so the one noisy sample at each reversal
/// sets where the model turns. Taken as measured, a chance imbalance between
/// peaks and troughs read as asymmetry: on seed 5 at delta-BIC below -10
/// (measured while this was built; seeds 0-19: on 2 with the reversals as
/// measured, on 1, seed 16, with them placed from their neighbours). On seed
/// 16 the asymmetry fit (NRMSE 0.0240 to 0.0235, delta-BIC -36) took the
/// offsets the placed reversals leave on the branches, with unequal strength
/// and stiffness whose effects on the peaks cancel: the peak ratio is 1.008x
/// the model's cycle by cycle, at t = 1.9 (seeds 0-59 and 20 sine records:
/// asymmetry named on 3 before its signature gated, on none since).
#[test]
fn triangular_cycles_with_nothing_missing_name_nothing() {
    for seed in [5, 6, 16] {
        let file = write(
            &format!("triangles-{seed}.csv"),
            &record(TRIANGLES, (0.2, 0.01), seed),
        );
        let (json, _) = run("discover", &file, &[]);
        assert_eq!(json["model"], "bw", "seed {seed}: {:#}", json["ladder"]);
        let noise = &json["displacement_noise"];
        assert_eq!(noise["corner_shape"], "hinge", "seed {seed}: {noise}");
    }
}

/// Pinching is found alone. On seed 2 the pinching model refitted from the
/// plain one stalled (NRMSE 0.167 where 0.025 is reachable), which made
/// stiffness degradation look indispensable beside it, until each single
/// was also refitted from the pair that holds it (measured while this was
/// built: seeds 0-29, a second effect beside pinching on 3 before, on 2
/// after, both asymmetry at delta-BIC -11.5 and -12.6).
#[test]
fn pinching_behind_triangular_cycles_is_named_alone() {
    for seed in [1, 2] {
        let file = write(
            &format!("pinching-{seed}.csv"),
            &record(
                Hidden {
                    pinching: true,
                    ..TRIANGLES
                },
                (0.2, 0.01),
                seed,
            ),
        );
        let (json, _) = run("discover", &file, &[]);
        assert_eq!(
            json["model"], "bw+pinching",
            "seed {seed}: {:#}",
            json["ladder"]
        );
    }
}
