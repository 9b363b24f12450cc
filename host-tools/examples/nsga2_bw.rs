//! Our side of the NSGA-II benchmark against pymoo (`benches/baselines/pymoo_bw.py`, whose
//! README states the problem): identify alpha, beta, gamma, xi and n of the thesis' Bouc-Wen
//! example (section 4.4: m = 500 kg, k = 6 kN/mm, F(t) = t sin(2 pi t) kN) from the 5,000
//! displacement samples of `benches/baselines/bw_synthetic.csv`, one objective (the RMS
//! displacement error, mm), constraints beta + gamma > 0 and beta - gamma > 0, search box
//! 50-150 % of the truth, population 100 for 250 generations (25,000 evaluations).
//!
//! The oscillator is `hysteresis::bwbn::Sdof` (error-controlled Dormand-Prince at `--tol`), fed
//! the exact F(t) at each sample, linear in between; `--half-steps` adds the midpoint value, so
//! that the forcing matches the pymoo side's RK4 stages (t, t + dt/2, t + dt) at twice the cost.
//! With `--lanes K` it is `hyst::fit::lanes::BoucWenLanes` instead: sixteen candidates at a time,
//! K fixed RK4 steps a sample, the forcing linear between samples (as `hyst fit` sees a record).
//! The program prints the model's RMS error at the true parameters against the record first
//! (the record is pymoo's own RK4, so this is how far apart the two models are), then the
//! model's throughput. `SIMS_ONLY=N` prints only those, timed over N simulations (50 if N is not
//! a number).
//!
//! ```sh
//! cargo run --release -p hysteresis-host --example nsga2_bw -- [--seeds 1 2 3] [--serial] [--tol 1e-7] [--half-steps] [--lanes K]
//! ```

use hyst::fit::lanes::{BoucWenLanes, LANES};
use hyst::fit::nsga2::{Bounds, Evaluation, Nsga2, Problem};
use hysteresis::bwbn::{BoucWen, BwbnParams, Control, Method, Sdof};
use std::time::Instant;

const MASS: f64 = 5e-4; // 500 kg in kN s^2 / mm
const K: f64 = 6.0;
const DT: f64 = 0.002;
const NAMES: [&str; 5] = ["alpha", "beta", "gamma", "xi", "n"];
const TRUTH: [f64; 5] = [0.2, 2.0, -1.0, 0.05, 1.2];

fn forcing(t: f64) -> f64 {
    t * (2.0 * std::f64::consts::PI * t).sin()
}

/// The displacement samples after t = 0 (5,000 of them), read with the
/// project's reader; the time column must be the 2 ms grid from 0.
fn record() -> Vec<f64> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../benches/baselines/bw_synthetic.csv"
    );
    let record = hyst::data::read(path, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let time = record.time().expect("a time column");
    for (i, t) in time.iter().enumerate() {
        assert!(
            (t - i as f64 * DT).abs() < 1e-9,
            "{path}: sample {} is not at t = {} s",
            i + 1,
            i as f64 * DT
        );
    }
    record.displacement().expect("a displacement column")[1..].to_vec()
}

struct BwIdentification {
    measured: Vec<f64>,
    bounds: Vec<Bounds>,
    control: Control<f64>,
    half_steps: bool,
    /// RK4 steps a sample of the lane-batched model, if it is used.
    lanes: Option<usize>,
    /// F(t)/m at the samples, t = 0 included.
    forcing: Vec<f64>,
}

impl BwIdentification {
    /// RMS displacement error (mm) of the parameters `x`, or `None` when they cannot be
    /// simulated (rejected or the integration gave up).
    fn rms(&self, x: &[f64]) -> Option<f64> {
        let base = BoucWen::new(K, x[0], x[4], x[1], x[2]).ok()?;
        let mut osc = Sdof::from_physical(BwbnParams::plain(base), MASS, x[3])
            .ok()?
            .with_control(self.control)
            .unwrap();
        let mut sum = 0.0;
        for (i, u_meas) in self.measured.iter().enumerate() {
            let t = i as f64 * DT;
            if self.half_steps {
                osc.step(0.5 * DT, forcing(t + 0.5 * DT) / MASS).ok()?;
            }
            let h = if self.half_steps { 0.5 * DT } else { DT };
            let u = osc.step(h, forcing(t + DT) / MASS).ok()?.u;
            sum += (u - u_meas) * (u - u_meas);
        }
        Some((sum / self.measured.len() as f64).sqrt())
    }

    /// RMS displacement errors (mm) of up to [`LANES`] candidates simulated together, RK4 with
    /// `substeps` steps a sample; `None` where a candidate cannot be simulated.
    fn rms_lanes(&self, xs: &[&[f64]], substeps: usize) -> Vec<Option<f64>> {
        let bases: Vec<Option<(BoucWen<f64>, f64)>> = xs
            .iter()
            .map(|x| {
                let base = BoucWen::new(K / MASS, x[0], x[4], x[1], x[2]).ok()?;
                Some((base, x[3]))
            })
            .collect();
        let valid: Vec<(BoucWen<f64>, f64)> = bases.iter().flatten().copied().collect();
        let Some(lanes) = BoucWenLanes::new(&valid) else {
            return vec![None; xs.len()];
        };
        let mut sse = [0.0; LANES];
        let mut i = 0;
        lanes.simulate(&self.forcing, None, DT, substeps, |s| {
            if i > 0 {
                for (l, e) in sse.iter_mut().enumerate() {
                    let d = f64::from(s.u[l]) - self.measured[i - 1];
                    *e = d.mul_add(d, *e);
                }
            }
            i += 1;
        });
        let mut lane = 0;
        bases
            .iter()
            .map(|b| {
                b.as_ref()?;
                let rms = (sse[lane] / self.measured.len() as f64).sqrt();
                lane += 1;
                rms.is_finite().then_some(rms)
            })
            .collect()
    }

    /// The model's RMS error at `x` with the chosen integrator.
    fn rms_any(&self, x: &[f64]) -> Option<f64> {
        match self.lanes {
            Some(k) => self.rms_lanes(&[x], k)[0],
            None => self.rms(x),
        }
    }
}

fn evaluation(x: &[f64], rms: Option<f64>) -> Evaluation {
    let (beta, gamma) = (x[1], x[2]);
    let violations = vec![(-(beta + gamma)).max(0.0), (-(beta - gamma)).max(0.0)];
    Evaluation::new(vec![rms.unwrap_or(f64::INFINITY)], violations)
}

impl Problem for BwIdentification {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        1
    }
    fn num_constraints(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        evaluation(x, self.rms_any(x))
    }
    fn batch_size(&self) -> usize {
        if self.lanes.is_some() {
            LANES
        } else {
            1
        }
    }
    fn evaluate_batch(&self, xs: &[&[f64]]) -> Vec<Evaluation> {
        match self.lanes {
            Some(k) => xs
                .iter()
                .zip(self.rms_lanes(xs, k))
                .map(|(x, rms)| evaluation(x, rms))
                .collect(),
            None => xs.iter().map(|x| self.evaluate(x)).collect(),
        }
    }
    fn variable_names(&self) -> Vec<String> {
        NAMES.iter().map(|s| s.to_string()).collect()
    }
}

fn main() {
    let mut seeds = vec![];
    let mut parallel = true;
    let mut tol = 1e-7;
    let mut half_steps = false;
    let mut lanes = None;
    let mut args = std::env::args().skip(1).peekable();
    while let Some(a) = args.next() {
        match a.as_str() {
            "--serial" => parallel = false,
            "--half-steps" => half_steps = true,
            "--lanes" => {
                lanes = Some(
                    args.next()
                        .and_then(|v| v.parse().ok())
                        .expect("--lanes takes a number of RK4 steps a sample"),
                )
            }
            "--tol" => {
                tol = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .expect("--tol takes a number")
            }
            "--seeds" => {
                while let Some(s) = args.peek().and_then(|v| v.parse::<u64>().ok()) {
                    seeds.push(s);
                    args.next();
                }
            }
            other => panic!(
                "unknown argument {other}: expected --seeds N.., --serial, --tol X, --half-steps, --lanes K"
            ),
        }
    }
    if seeds.is_empty() {
        seeds.push(1);
    }
    let bounds = TRUTH
        .iter()
        .map(|&v| {
            let (a, b) = (0.5 * v, 1.5 * v);
            Bounds {
                lower: a.min(b),
                upper: a.max(b),
            }
        })
        .collect();
    let measured = record();
    let forcing = (0..=measured.len())
        .map(|i| forcing(i as f64 * DT) / MASS)
        .collect();
    let problem = BwIdentification {
        measured,
        bounds,
        control: Control {
            method: Method::Dp54,
            tol,
            max_substeps: 1000,
        },
        half_steps,
        lanes,
        forcing,
    };
    let floor = problem.rms_any(&TRUTH).expect("the truth simulates");
    let start = Instant::now();
    let sims_only = std::env::var_os("SIMS_ONLY")
        .map(|v| v.to_str().and_then(|s| s.parse().ok()).unwrap_or(50));
    let sims = sims_only.unwrap_or(200);
    let xs: Vec<Vec<f64>> = (0..sims)
        .map(|i| {
            let f = 0.9 + 0.2 * i as f64 / sims as f64;
            TRUTH.iter().map(|v| v * f).collect()
        })
        .collect();
    for chunk in xs.chunks(problem.batch_size()) {
        let refs: Vec<&[f64]> = chunk.iter().map(|x| x.as_slice()).collect();
        std::hint::black_box(problem.evaluate_batch(&refs));
    }
    let per_sim = start.elapsed().as_secs_f64() / sims as f64;
    let model = match lanes {
        Some(k) => format!("{LANES} lanes, RK4 at {k} step(s) a sample"),
        None => format!("Dp54 at tol {tol:e}"),
    };
    println!(
        "model: {model}; RMS error at the truth {floor:.2e} mm; {:.3} ms a simulation ({:.0}/s, one thread)",
        1e3 * per_sim,
        1.0 / per_sim
    );
    if sims_only.is_some() {
        return;
    }
    for seed in seeds {
        let settings = Nsga2 {
            seed,
            parallel,
            ..Nsga2::default()
        };
        let start = Instant::now();
        let outcome = settings.run(&problem).expect("valid settings");
        let wall = start.elapsed().as_secs_f64();
        let best = outcome
            .population
            .iter()
            .filter(|m| m.is_feasible())
            .min_by(|a, b| a.objectives[0].total_cmp(&b.objectives[0]))
            .expect("a feasible member");
        let errors: Vec<String> = best
            .variables
            .iter()
            .zip(TRUTH)
            .zip(NAMES)
            .map(|((v, t), n)| format!("{n} {:+.2}%", 100.0 * (v - t) / t.abs()))
            .collect();
        println!(
            "seed {seed}, {}: {wall:.1} s, {} evaluations, {:.0}/s; RMS error {:.2e} mm; {}",
            if parallel { "parallel" } else { "one thread" },
            outcome.evaluations,
            outcome.evaluations as f64 / wall,
            best.objectives[0],
            errors.join(", ")
        );
    }
}
