//! A sample report with every plot kind, on data made here: a degrading
//! Bouc–Wen column under a stepped cyclic displacement history ("measured",
//! with a little deterministic noise), and three models that leave out
//! degradation effects. Shared by the screenshot test and the
//! `report_gallery` example.

use hyst::report::plots::{
    energy_curves, ladder, loop_overlay, pareto_front, per_cycle_bars, residual_map, sensitivity,
    time_series, xy, Pareto, Quantity, Residuals, Rung, Signal, TimeBase, Trace,
};
use hyst::report::{Cell, Figure, Report, Table};

/// Samples per load cycle.
pub const PER_CYCLE: usize = 200;
/// Displacement amplitude of each cycle (mm).
pub const AMPLITUDES: [f64; 8] = [2.0, 2.0, 4.0, 4.0, 6.0, 6.0, 8.0, 8.0];

/// Bouc–Wen with energy-driven strength (ν) and stiffness (η) degradation
/// (thesis Eqs 3.5–3.7, without pinching), displacement-driven.
#[derive(Debug, Clone, Copy)]
pub struct BoucWen {
    pub k: f64,
    pub alpha: f64,
    pub a: f64,
    pub beta: f64,
    pub gamma: f64,
    pub n: f64,
    pub delta_nu: f64,
    pub delta_eta: f64,
}

pub const TRUTH: BoucWen = BoucWen {
    k: 10.0,
    alpha: 0.1,
    a: 1.0,
    beta: 0.15,
    gamma: 0.10,
    n: 2.0,
    delta_nu: 0.004,
    delta_eta: 0.003,
};

impl BoucWen {
    /// Restoring force (kN) along the displacement path `u` (mm).
    pub fn force(&self, u: &[f64]) -> Vec<f64> {
        let (mut z, mut e, mut prev) = (0.0_f64, 0.0_f64, u.first().copied().unwrap_or(0.0));
        let mut f = Vec::with_capacity(u.len());
        for &ui in u {
            const SUB: usize = 20;
            let du = (ui - prev) / SUB as f64;
            for _ in 0..SUB {
                let nu = 1.0 + self.delta_nu * e;
                let eta = 1.0 + self.delta_eta * e;
                let s = (du * z).signum();
                let dz = (self.a - nu * z.abs().powf(self.n) * (self.beta * s + self.gamma)) / eta;
                e += z * du;
                z += dz * du;
            }
            prev = ui;
            f.push(self.alpha * self.k * ui + (1.0 - self.alpha) * self.k * z);
        }
        f
    }
}

/// The stepped cyclic displacement history (mm).
pub fn displacement() -> Vec<f64> {
    let mut u = Vec::new();
    for amp in AMPLITUDES {
        for i in 0..PER_CYCLE {
            let t = i as f64 / PER_CYCLE as f64;
            u.push(amp * (2.0 * std::f64::consts::PI * t).sin());
        }
    }
    u
}

/// Deterministic noise in [-0.5, 0.5) (a linear congruential generator).
fn noise(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
}

/// Dissipated energy per cycle, ∮ F du by the trapezoid rule.
fn energy_per_cycle(u: &[f64], f: &[f64]) -> Vec<f64> {
    cumulative_energy(u, f)
        .chunks(PER_CYCLE)
        .scan(0.0, |start, c| {
            let end = *c.last().unwrap();
            let e = end - *start;
            *start = end;
            Some(e)
        })
        .collect()
}

fn cumulative_energy(u: &[f64], f: &[f64]) -> Vec<f64> {
    let mut e = vec![0.0];
    for i in 1..u.len() {
        e.push(e[i - 1] + 0.5 * (f[i] + f[i - 1]) * (u[i] - u[i - 1]));
    }
    e
}

fn rms(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
}

/// All figures of the sample report, with their captions.
pub fn figures() -> Vec<(&'static str, Figure, String)> {
    let u = displacement();
    let mut seed = 7;
    let truth = TRUTH.force(&u);
    let measured: Vec<f64> = truth.iter().map(|f| f + 0.6 * noise(&mut seed)).collect();
    let models = [
        (
            "bw",
            BoucWen {
                delta_nu: 0.0,
                delta_eta: 0.0,
                ..TRUTH
            },
            6,
        ),
        (
            "bw+strength",
            BoucWen {
                delta_eta: 0.0,
                ..TRUTH
            },
            7,
        ),
        ("bw+strength+stiffness", TRUTH, 8),
    ];
    let predicted: Vec<Vec<f64>> = models.iter().map(|(_, m, _)| m.force(&u)).collect();
    let range = measured.iter().cloned().fold(f64::MIN, f64::max)
        - measured.iter().cloned().fold(f64::MAX, f64::min);
    let n = u.len() as f64;
    let bic = |p: &[f64], k: usize| {
        let rss: f64 = p.iter().zip(&measured).map(|(a, b)| (a - b).powi(2)).sum();
        n * (rss / n).ln() + k as f64 * n.ln()
    };
    let mut out = Vec::new();
    let disp = Quantity::new("Displacement", "mm");
    let force = Quantity::new("Force", "kN");

    out.push((
        "loops",
        loop_overlay(
            &[
                Trace::measured("measured", &u, &measured),
                Trace::model("bw", &u, &predicted[0]),
                Trace::model("bw+strength", &u, &predicted[1]),
            ],
            disp,
            force,
        )
        .unwrap(),
        "Loops: the plain Bouc–Wen model keeps its strength while the specimen loses it.".into(),
    ));

    // A few dropped samples, as a data logger may leave them.
    let mut with_dropouts = measured.clone();
    for i in [400, 401, 950] {
        with_dropouts[i] = f64::NAN;
    }
    out.push((
        "time-series",
        time_series(
            TimeBase::Index,
            &[
                Signal::measured("Displacement", "mm", &u),
                Signal::measured("Force", "kN", &with_dropouts),
                Signal::model("bw", "kN", &predicted[0]),
            ],
        )
        .unwrap(),
        "Signals over the record (three dropped samples are reported, not hidden).".into(),
    ));

    let residual: Vec<f64> = predicted[0]
        .iter()
        .zip(&measured)
        .map(|(p, m)| p - m)
        .collect();
    let fmax = measured.iter().fold(0.0_f64, |a, f| a.max(f.abs()));
    let branch: Vec<usize> = (0..u.len())
        .map(|i| {
            let du = if i == 0 { u[1] - u[0] } else { u[i] - u[i - 1] };
            if measured[i].abs() < 0.2 * fmax {
                2
            } else if u[i] * du > 0.0 {
                0
            } else {
                1
            }
        })
        .collect();
    let starts: Vec<usize> = (0..AMPLITUDES.len()).map(|c| c * PER_CYCLE).collect();
    out.push((
        "residual-map",
        residual_map(&Residuals {
            displacement: &u,
            residual: &residual,
            branch: &branch,
            branch_names: &["loading", "unloading", "near zero force"],
            cycle_starts: &starts,
            displacement_unit: "mm",
            force_unit: "kN",
        })
        .unwrap(),
        "Residual of the plain model, by branch and by cycle.".into(),
    ));

    let e_meas = energy_per_cycle(&u, &measured);
    let e_bw = energy_per_cycle(&u, &predicted[0]);
    let e_full = energy_per_cycle(&u, &predicted[2]);
    out.push((
        "per-cycle",
        per_cycle_bars(
            Quantity::new("Dissipated energy", "kN·mm"),
            &[
                Signal::measured("measured", "kN·mm", &e_meas),
                Signal::model("bw", "kN·mm", &e_bw),
                Signal::model("bw+strength+stiffness", "kN·mm", &e_full),
            ],
        )
        .unwrap(),
        "Energy dissipated in each cycle.".into(),
    ));

    let rungs: Vec<Rung> = models
        .iter()
        .enumerate()
        .map(|(i, (name, _, k))| Rung {
            label: name,
            params: *k,
            nrmse: rms(&predicted[i], &measured) / range,
            delta_bic: (i > 0)
                .then(|| bic(&predicted[i], *k) - bic(&predicted[i - 1], models[i - 1].2)),
        })
        .collect();
    out.push((
        "ladder",
        ladder(&rungs, Some(-10.0)).unwrap(),
        "The ladder of models: each added effect lowers the error; ΔBIC weighs it against the added parameters.".into(),
    ));

    let t: Vec<f64> = (0..u.len()).map(|i| i as f64 * 0.05).collect();
    let ce_meas = cumulative_energy(&u, &measured);
    let ce_bw = cumulative_energy(&u, &predicted[0]);
    let ce_str = cumulative_energy(&u, &predicted[1]);
    out.push((
        "energy",
        energy_curves(
            TimeBase::Time {
                values: &t,
                unit: "s",
            },
            &[
                Signal::measured("measured", "kN·mm", &ce_meas),
                Signal::model("bw", "kN·mm", &ce_bw),
                Signal::model("bw+strength", "kN·mm", &ce_str),
            ],
        )
        .unwrap(),
        "Cumulative dissipated energy.".into(),
    ));

    let mut seed = 11;
    let points: Vec<[f64; 2]> = (0..80)
        .map(|i| {
            let x = 0.05 + 0.9 * (i as f64 + 0.5) / 80.0;
            let lift = if i % 3 == 0 {
                0.0
            } else {
                0.3 * (noise(&mut seed) + 0.5)
            };
            [x, 0.02 / x + lift * 0.2]
        })
        .collect();
    let chosen = points
        .iter()
        .enumerate()
        .filter(|(i, _)| i % 3 == 0)
        .min_by(|a, b| (a.1[0] + a.1[1]).total_cmp(&(b.1[0] + b.1[1])))
        .map(|(i, _)| i);
    out.push((
        "pareto",
        pareto_front(&Pareto {
            points: &points,
            chosen,
            x: Quantity::new("Force NRMSE", ""),
            y: Quantity::new("Energy error", ""),
        })
        .unwrap(),
        "Candidates of a two-objective fit and the one chosen.".into(),
    ));

    let change: Vec<f64> = (-5..=5).map(|k| k as f64 * 10.0).collect();
    type Knob = fn(&mut BoucWen, f64);
    let knobs: [(&str, Knob); 5] = [
        ("α", |m, s| m.alpha *= s),
        ("β", |m, s| m.beta *= s),
        ("γ", |m, s| m.gamma *= s),
        ("n", |m, s| m.n *= s),
        ("A", |m, s| m.a *= s),
    ];
    let curves: Vec<(&str, Vec<f64>)> = knobs
        .iter()
        .map(|(name, knob)| {
            let e = change
                .iter()
                .map(|c| {
                    let mut m = TRUTH;
                    knob(&mut m, 1.0 + c / 100.0);
                    rms(&m.force(&u), &truth)
                })
                .collect();
            (*name, e)
        })
        .collect();
    let signals: Vec<Signal> = curves
        .iter()
        .map(|(n, e)| Signal::model(n, "kN", e))
        .collect();
    out.push((
        "sensitivity",
        sensitivity(&change, "RMS error", &signals).unwrap(),
        "RMS force error when one parameter moves from −50% to +50% (cf. thesis Fig. 3.7).".into(),
    ));

    // The first cycle at each amplitude: the backbone of the loops.
    let first = |f: &[f64]| -> Vec<f64> {
        f.chunks(PER_CYCLE)
            .step_by(2)
            .map(|c| c.iter().fold(0.0_f64, |a, v| a.max(*v)))
            .collect()
    };
    let amplitudes: Vec<f64> = AMPLITUDES.iter().step_by(2).copied().collect();
    let (p_meas, p_bw) = (first(&measured), first(&predicted[0]));
    out.push((
        "xy",
        xy(
            "Backbone: peak force against amplitude",
            Quantity::new("Amplitude", "mm"),
            force,
            &[
                Trace::measured("measured", &amplitudes, &p_meas),
                Trace::model("bw", &amplitudes, &p_bw),
            ],
        )
        .unwrap(),
        "Peak force of the first cycle at each amplitude (the backbone).".into(),
    ));
    out
}

/// The sample report: every figure, a table and some text.
pub fn report() -> Report {
    let mut r = Report::new("Sample report: a degrading column against three models");
    r.section("Summary").paragraph(
        "A synthetic column (Bouc–Wen with strength and stiffness degradation, 8 cycles at \
         2 to 8 mm) compared with models that leave effects out. Every plot kind of the report \
         module appears once.",
    );
    let mut t = Table::new(&[
        "Model",
        "Parameters",
        "RMS error to the true force (kN)",
        "Note",
    ]);
    t.caption("Models compared.");
    for (name, k, note) in [
        ("bw", 6usize, "no degradation"),
        ("bw+strength", 7, "strength degradation"),
        ("bw+strength+stiffness", 8, "the model that made the data"),
    ] {
        let u = displacement();
        let m = match name {
            "bw" => BoucWen {
                delta_nu: 0.0,
                delta_eta: 0.0,
                ..TRUTH
            },
            "bw+strength" => BoucWen {
                delta_eta: 0.0,
                ..TRUTH
            },
            _ => TRUTH,
        };
        let truth = TRUTH.force(&u);
        let f = m.force(&u);
        t.row(vec![
            name.into(),
            k.into(),
            Cell::fixed(rms(&f, &truth), 3),
            note.into(),
        ])
        .unwrap();
    }
    r.table(&t);
    let mut section = "";
    for (id, fig, caption) in figures() {
        let heading = match id {
            "loops" | "time-series" => "Model and measurement",
            "residual-map" | "per-cycle" => "Where the model fails",
            "ladder" | "energy" => "Adding effects",
            _ => "Fitting",
        };
        if heading != section {
            r.section(heading);
            section = heading;
        }
        r.figure(&fig, &caption);
    }
    r
}
