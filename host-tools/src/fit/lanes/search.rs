//! The lane-batched oscillator as NSGA-II's search model for a force-driven plain Bouc-Wen fit.
//!
//! The evolutionary search only compares candidates; the solution it chooses is scored again with
//! the core's error-controlled oscillator ([`Problem::scores`]), and so is every member of the
//! front that `--pareto` writes. So the search may use [`BoucWenLanes`], at one step a sample
//! about 35x cheaper a simulation than the error-controlled [`Sdof`](hysteresis::bwbn::Sdof) on
//! the Bouc-Wen benchmark problem (0.058 ms against 2.1 ms, docs/benchmarks.md), provided it is
//! accurate enough to rank candidates.
//! [`SearchModel::for_problem`] chooses its RK4 steps a sample, doubling from 1 to
//! [`MAX_SUBSTEPS`], as the fewest for which
//!
//! * `h w0 <= 0.5` for the stiffest oscillator the bounds allow (RK4 is stable below 2.8 and its
//!   phase error per step is about `(h w0)^5 / 120`), and
//! * at the start point and fifteen points spread over the bounds (a Halton sequence), the NRMSE
//!   of the prediction is within a quarter of [`SEARCH_TOLERANCE`] of the core's (what the
//!   search compares; the quarter is the margin for the points in between).
//!
//! Otherwise (more steps would cost about as much as the core's adaptive steps), and for every
//! other model or drive, the search uses the core's oscillator, and [`Unsuited`] says why. The
//! force between samples is the problem's, linear or cubic ([`Between`]), as in the core.

use super::{BoucWenLanes, LANES};
use crate::fit::experiment::{Between, Drive};
use crate::fit::forcing::rates;
use crate::fit::objectives::Scores;
use crate::fit::parametrization::Candidate;
use crate::fit::problem::Problem;
use hysteresis::bwbn::{BoucWen, EffectSet};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Largest difference of NRMSE from the core's allowed for the search model at the checked
/// points. The population of a search spreads over more than this until its last generations
/// (on the benchmark problem the best NRMSE of a run is about 1e-3), and the result is scored
/// with the core.
pub const SEARCH_TOLERANCE: f64 = 1e-3;

/// Most RK4 steps a sample. A lane's step costs about 11.6 ns a sample and candidate (0.058 ms
/// for the 5,001 samples of the benchmark record), the core's adaptive Dormand-Prince about
/// 420 ns a sample at its floor of one sub-step a sample (2.1 ms; docs/benchmarks.md), so at
/// 32 steps a candidate costs about what the core's cheapest simulation does, and more steps
/// could cost more than the core.
pub const MAX_SUBSTEPS: usize = 32;

/// How many times the steps a candidate whose fixed-step run was not finite is simulated
/// again with, before the core simulates it. RK4 becomes unstable where the hysteretic spring
/// is stiff (large n and beta at high velocity); shorter steps move that limit. Measured on the
/// Bouc-Wen benchmark record (41,000 samples at 4 steps a sample): 308 of the 1,100 candidates of
/// NSGA-II's first ten generations were not finite, and their core simulations took 64 of the
/// search's 69 CPU seconds (0.1-0.3 s each); at four times the steps, each batch of them costs
/// about 0.11 s and scores as the core does to 2e-6 of NRMSE.
pub const RETRY: usize = 4;

/// Points checked besides the start: one batch of [`LANES`] in all.
const CHECKED: usize = 15;

/// The checked points must be within this share of [`SEARCH_TOLERANCE`]: they sample the bounds,
/// and between them the difference can be larger. Measured on the thesis example at 500 Hz
/// (24 random points): at one step a sample up to 2.0e-3 where eight checked points stayed
/// below 7.5e-4; at two steps (chosen) 3.9e-5 against the sixteen checked points' 4.1e-6.
pub(crate) const MARGIN: f64 = 0.25;

/// The first primes: a Halton sequence's bases, one per free parameter.
const PRIMES: [u32; 8] = [2, 3, 5, 7, 11, 13, 17, 19];

/// Largest `h w0` the steps may have.
const MAX_H_W0: f64 = 0.5;

/// What a search used: shown with the fit's result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchSummary {
    /// RK4 steps a sample.
    pub substeps: usize,
    /// Candidates simulated together.
    pub lanes: usize,
    /// The largest difference of NRMSE from the core at the checked points.
    pub checked_error: f64,
    /// Candidates whose fixed-step run was not finite and that were simulated again with
    /// [`RETRY`] times the steps.
    pub retried: usize,
    /// Of those, the candidates that the core simulated, their fixed-step run not finite again.
    pub by_core: usize,
    /// Batches of lanes simulated, the checks of the step count included.
    pub runs: usize,
}

/// Why a search simulates every candidate with the core's error-controlled oscillator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unsuited {
    /// The lanes hold the plain Bouc-Wen oscillator under an applied force only.
    Model,
    /// The model cannot be built at a corner of the bounds, where the stiffest oscillator is
    /// looked for.
    Corner,
    /// The core cannot simulate the start, against which the steps are checked.
    Start,
    /// No step count up to [`MAX_SUBSTEPS`] met the tolerance: the largest difference of NRMSE
    /// from the core at the checked points with the most steps (infinite where a fixed-step run
    /// was not finite).
    Inaccurate {
        /// The difference with [`MAX_SUBSTEPS`] steps a sample.
        checked_error: f64,
    },
}

impl std::fmt::Display for Unsuited {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the search simulated every candidate with the error-controlled model, because "
        )?;
        match self {
            Unsuited::Model => write!(
                f,
                "the fixed-step search model holds only plain Bouc-Wen under an applied force"
            ),
            Unsuited::Corner => write!(f, "the model cannot be built at a corner of the bounds"),
            Unsuited::Start => write!(f, "the error-controlled model cannot simulate the start"),
            Unsuited::Inaccurate { checked_error } => write!(
                f,
                "RK4 at up to {MAX_SUBSTEPS} steps a sample left the NRMSE at sixteen points of \
                 the bounds up to {checked_error:.1e} from its own (allowed: {:.1e})",
                MARGIN * SEARCH_TOLERANCE
            ),
        }
    }
}

impl std::fmt::Display for SearchSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the search simulated {} candidates at a time by RK4 at {} step{} a sample, whose NRMSE \
             was within {:.1e} of the error-controlled model's at sixteen points of the bounds; the \
             result is scored with the error-controlled model",
            self.lanes,
            self.substeps,
            if self.substeps == 1 { "" } else { "s" },
            self.checked_error
        )?;
        if self.retried > 0 {
            write!(
                f,
                ". {} candidate{} did not stay finite and {} simulated again at {} steps a sample \
                 ({} of them by the error-controlled model, not finite again)",
                self.retried,
                if self.retried == 1 { "" } else { "s" },
                if self.retried == 1 { "was" } else { "were" },
                RETRY * self.substeps,
                self.by_core
            )?;
        }
        Ok(())
    }
}

/// The fixed-step search model of a problem.
#[derive(Clone, Debug)]
pub struct SearchModel {
    /// RK4 steps a sample.
    pub substeps: usize,
    /// The largest difference of NRMSE from the core at the checked points.
    pub checked_error: f64,
    dt: f64,
    mass: f64,
    /// Applied force per unit mass at the samples.
    forcing: Vec<f64>,
    /// Its rates, when it is cubic between samples.
    rates: Option<Vec<f64>>,
    /// Candidates simulated again with more steps, and those simulated by the core.
    retried: Counter,
    by_core: Counter,
    /// Batches of lanes simulated, the checks of the step count included.
    runs: Counter,
}

/// A count shared by the threads of a search.
#[derive(Debug, Default)]
struct Counter(AtomicUsize);

impl Counter {
    fn add(&self, n: usize) {
        self.0.fetch_add(n, Ordering::Relaxed);
    }
    fn get(&self) -> usize {
        self.0.load(Ordering::Relaxed)
    }
}

impl Clone for Counter {
    fn clone(&self) -> Self {
        Counter(AtomicUsize::new(self.get()))
    }
}

impl SearchModel {
    /// The search model for `problem`, if it is a force-driven plain Bouc-Wen fit without custom
    /// effects and a step count up to [`MAX_SUBSTEPS`] meets the rules of the module.
    pub fn for_problem(problem: &Problem) -> Result<Self, Unsuited> {
        let Drive::Force { dt, mass, between } = problem.exp.drive else {
            return Err(Unsuited::Model);
        };
        let (lo, hi) = problem.par.bounds();
        let plain =
            |c: &Candidate| c.params.effect_set() == EffectSet::NONE && c.extras.0.is_empty();
        if problem
            .params(&problem.par.default_start())
            .is_some_and(|c| !plain(&c))
        {
            return Err(Unsuited::Model);
        }
        let mut stiffest = 0.0f64;
        for x in [&lo, &hi] {
            let c = problem.params(x).ok_or(Unsuited::Corner)?;
            if !plain(&c) {
                return Err(Unsuited::Model);
            }
            stiffest = stiffest.max(c.params.base().k0 / mass);
        }
        // Plain Bouc-Wen has six parameters at most, one Halton base each.
        if lo.len() > PRIMES.len() {
            return Err(Unsuited::Model);
        }
        let points = checked_points(problem);
        // The core's NRMSE where it can simulate (its sub-step budget may run out at extreme
        // points); the start must be among them.
        let references: Vec<(&[f64], f64)> = points
            .iter()
            .filter_map(|x| Some((x.as_slice(), problem.scores(x)?.nrmse)))
            .collect();
        if references.first().map(|r| r.0) != Some(points[0].as_slice()) {
            return Err(Unsuited::Start);
        }
        let xs: Vec<&[f64]> = references.iter().map(|r| r.0).collect();
        let mut model = SearchModel {
            substeps: 1,
            checked_error: 0.0,
            dt,
            mass,
            forcing: problem.exp.input.iter().map(|f| f / mass).collect(),
            rates: None,
            retried: Counter::default(),
            by_core: Counter::default(),
            runs: Counter::default(),
        };
        if between == Between::Cubic {
            model.rates = Some(rates(&model.forcing, dt));
        }
        let mut checked_error = f64::INFINITY;
        while model.substeps <= MAX_SUBSTEPS {
            if dt / model.substeps as f64 * stiffest.sqrt() <= MAX_H_W0 {
                // The fixed-step runs alone: a run that blows up fails the check here (more
                // steps are tried), where the search would hand it to the core.
                let worst = xs
                    .chunks(LANES)
                    .flat_map(|chunk| model.simulate(problem, chunk, model.substeps))
                    .zip(&references)
                    .map(|(s, r)| s.map_or(f64::INFINITY, |s| (s.nrmse - r.1).abs()))
                    .fold(0.0f64, f64::max);
                if worst <= MARGIN * SEARCH_TOLERANCE {
                    model.checked_error = worst;
                    return Ok(model);
                }
                checked_error = worst;
            }
            model.substeps *= 2;
        }
        Err(Unsuited::Inaccurate { checked_error })
    }

    /// What to report about this model.
    pub fn summary(&self) -> SearchSummary {
        SearchSummary {
            substeps: self.substeps,
            lanes: LANES,
            checked_error: self.checked_error,
            retried: self.retried.get(),
            by_core: self.by_core.get(),
            runs: self.runs.get(),
        }
    }

    /// Scores at up to [`LANES`] points, simulated together. Where a point's
    /// fixed-step simulation is not finite (RK4 is unstable for a stiff enough hysteretic
    /// spring: large n and beta at high velocity), those points are simulated again together
    /// with [`RETRY`] times the steps (more accurate than the checked step count, not less),
    /// and where that is not finite either, the core simulates them, so that the search never
    /// discards a candidate the core can simulate. `None` where none can.
    pub fn scores(&self, problem: &Problem, xs: &[&[f64]]) -> Vec<Option<Scores>> {
        let mut scores = self.simulate(problem, xs, self.substeps);
        let failed: Vec<usize> = (0..xs.len())
            .filter(|&i| scores[i].is_none() && problem.params(xs[i]).is_some())
            .collect();
        if failed.is_empty() {
            return scores;
        }
        self.retried.add(failed.len());
        let again: Vec<&[f64]> = failed.iter().map(|&i| xs[i]).collect();
        let more = self.simulate(problem, &again, RETRY * self.substeps);
        for (&i, s) in failed.iter().zip(more) {
            scores[i] = s.or_else(|| {
                self.by_core.add(1);
                problem.scores(xs[i])
            });
        }
        scores
    }

    /// The fixed-step scores alone: `None` where a point's parameters are rejected or its
    /// simulation is not finite. Each lane's samples go straight into its objectives
    /// ([`Target::running`](crate::fit::objectives::Target::running)); no prediction is stored.
    fn simulate(&self, problem: &Problem, xs: &[&[f64]], substeps: usize) -> Vec<Option<Scores>> {
        let mut running = problem.target.running::<LANES>();
        // The energy input of a force-driven model is the applied force over its displacement.
        let mut applied = problem.exp.input.iter();
        let valid = self.run(problem, xs, substeps, |u| {
            if let Some(&f) = applied.next() {
                running.push(u, u, &[f; LANES]);
            }
        });
        let mut lanes_out = running.scores().into_iter();
        valid
            .iter()
            .map(|&ok| {
                // An output that is not finite makes the squared error not finite.
                ok.then(|| lanes_out.next())
                    .flatten()
                    .filter(|s| s.nrmse.is_finite())
            })
            .collect()
    }

    /// Least-squares residuals (those of [`Problem::residuals`]: prediction error over
    /// `RMS(measured) sqrt(samples)`) at up to [`LANES`] points, simulated together at the
    /// model's step count: `None` where a point's parameters are rejected or a residual is not
    /// finite.
    pub fn residuals(&self, problem: &Problem, xs: &[&[f64]]) -> Vec<Option<Vec<f64>>> {
        let scale = problem.target.residual_scale();
        let measured = &problem.target.output;
        let mut lanes = vec![Vec::with_capacity(measured.len()); xs.len()];
        let mut sample = 0;
        let valid = self.run(problem, xs, self.substeps, |u| {
            if let Some(y) = measured.get(sample) {
                for (r, u) in lanes.iter_mut().zip(u) {
                    r.push((u - y) * scale);
                }
            }
            sample += 1;
        });
        let mut lanes = lanes.into_iter();
        valid
            .iter()
            .map(|&ok| {
                ok.then(|| lanes.next())
                    .flatten()
                    .filter(|r| r.iter().all(|v| v.is_finite()))
            })
            .collect()
    }

    /// Simulates the points `xs` together (up to [`LANES`]) and hands `sink` the
    /// displacement of every lane at each sample, the first lanes holding the valid points in
    /// order. Returns which points were valid (their parameters could be built).
    fn run(
        &self,
        problem: &Problem,
        xs: &[&[f64]],
        substeps: usize,
        mut sink: impl FnMut(&[f64; LANES]),
    ) -> Vec<bool> {
        let sets: Vec<Option<(BoucWen<f64>, f64)>> = xs
            .iter()
            .map(|x| {
                let c = problem.params(x)?;
                let per_mass = c.params.per_unit_mass(self.mass).ok()?;
                Some((*per_mass.base(), c.xi))
            })
            .collect();
        let valid: Vec<(BoucWen<f64>, f64)> = sets.iter().flatten().copied().collect();
        let Some(lanes) = BoucWenLanes::new(&valid) else {
            return vec![false; xs.len()];
        };
        self.runs.add(1);
        lanes.simulate(
            &self.forcing,
            self.rates.as_deref(),
            self.dt,
            substeps,
            |s| sink(&s.u.map(f64::from)),
        );
        sets.iter().map(Option::is_some).collect()
    }
}

/// The start and [`CHECKED`] points of a Halton sequence over the bounds.
fn checked_points(problem: &Problem) -> Vec<Vec<f64>> {
    let (lo, hi) = problem.par.bounds();
    let mut points = vec![problem.par.default_start()];
    points.extend((1..=CHECKED as u32).map(|i| {
        lo.iter()
            .zip(&hi)
            .zip(PRIMES)
            .map(|((l, h), base)| l + (h - l) * radical_inverse(i, base))
            .collect()
    }));
    points
}

/// The `i`-th element of van der Corput's sequence in `base`: `i`'s digits mirrored behind the
/// point, in (0, 1).
fn radical_inverse(mut i: u32, base: u32) -> f64 {
    let (mut value, mut scale) = (0.0, 1.0);
    while i > 0 {
        scale /= base as f64;
        value += (i % base) as f64 * scale;
        i /= base;
    }
    value
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::fit::experiment::Experiment;
    use crate::model::ModelSpec;
    use std::collections::BTreeMap;
    use std::f64::consts::PI;

    const MASS: f64 = 5e-4;
    pub(crate) const TRUTH: [(&str, f64); 5] = [
        ("alpha", 0.2),
        ("beta", 2.0),
        ("gamma", -1.0),
        ("xi", 0.05),
        ("n", 1.2),
    ];

    /// The thesis' example (sec. 4.4) at `rate_hz`: F = t sin(2 pi t) kN on 500 kg with
    /// k = 6 kN/mm (fixed), the displacement predicted by the core at the true parameters.
    pub(crate) fn problem(spec: ModelSpec, rate_hz: f64) -> Problem {
        problem_between(spec, rate_hz, Between::Linear)
    }

    /// [`problem`] with the force `between` samples as given.
    fn problem_between(spec: ModelSpec, rate_hz: f64, between: Between) -> Problem {
        let thesis = |t: f64| t * (2.0 * PI * t).sin();
        problem_under(spec, rate_hz, between, thesis, 10.0)
    }

    /// Four sines up to 20 Hz, next to the oscillator's 17.4 Hz: the record of
    /// `tests/force_between_samples.rs`.
    fn band_limited(t: f64) -> f64 {
        [
            (2.0, 4.0, 0.0),
            (6.0, 3.0, 1.0),
            (13.0, 3.0, 2.0),
            (20.0, 6.0, 3.0),
        ]
        .iter()
        .map(|(f, a, p)| a * (2.0 * PI * f * t + p).sin())
        .sum()
    }

    /// The thesis' oscillator under `force` (kN) for `seconds`.
    fn problem_under(
        spec: ModelSpec,
        rate_hz: f64,
        between: Between,
        force: impl Fn(f64) -> f64,
        seconds: f64,
    ) -> Problem {
        let dt = 1.0 / rate_hz;
        let input: Vec<f64> = (0..=(seconds * rate_hz) as usize)
            .map(|i| force(i as f64 * dt))
            .collect();
        // A placeholder output (it must vary to make a problem), replaced by the truth's
        // prediction below.
        let exp = Experiment {
            output: input.clone(),
            input,
            drive: Drive::Force {
                dt,
                mass: MASS,
                between,
            },
        };
        let fixed = [("k0".to_string(), 6.0)];
        let p = Problem::new(spec, exp, &fixed).unwrap();
        let truth: BTreeMap<&str, f64> = TRUTH.into_iter().collect();
        let output = p.predict(&p.par.normalise(&truth)).unwrap().output;
        Problem::new(
            spec,
            Experiment {
                output,
                ..p.exp.clone()
            },
            &fixed,
        )
        .unwrap()
    }

    /// The NRMSE of the search model and of the core at `x`; `None` where the core cannot
    /// simulate `x` (its sub-step budget runs out).
    fn compare(model: &SearchModel, p: &Problem, x: &[f64]) -> Option<(f64, f64)> {
        let core = p.scores(x)?.nrmse;
        let fast = model
            .scores(p, &[x])
            .remove(0)
            .expect("scores where the core has them");
        Some((fast.nrmse, core))
    }

    /// The step count is the smallest that passes: with half as many steps, the NRMSE at one of
    /// the checked points is further from the core's than the tolerance, or `h w0` is too large.
    ///
    /// Near resonance (the band-limited record at 200 Hz) more steps are needed than under the
    /// thesis' slow forcing. On the record of `tests/force_between_samples.rs` (measured with
    /// `hyst fit`), a checked point (n 2.9, beta + gamma -0.02) was not finite at 2 steps a
    /// sample, 4e-2 off at 4 and 4.7e-4 off at 8, so while the steps stopped at 8 the search
    /// used the core: 7.2 s for NSGA-II's defaults, against 0.53 s with the lanes at 16.
    #[test]
    fn the_fewest_steps_that_meet_the_tolerance() {
        let band = || problem_under(ModelSpec::BW, 200.0, Between::Cubic, band_limited, 2.0);
        for (rate, p) in [
            (100.0, problem(ModelSpec::BW, 100.0)),
            (500.0, problem(ModelSpec::BW, 500.0)),
            (200.0, band()),
        ] {
            let model = SearchModel::for_problem(&p).expect("a search model");
            // The rule's measure: the fixed-step run alone, a blow-up failing it.
            let worst = |m: &SearchModel| {
                checked_points(&p)
                    .iter()
                    .filter_map(|x| {
                        let core = p.scores(x)?.nrmse;
                        let fast = m.simulate(&p, &[x], m.substeps).remove(0);
                        let fast = fast.map_or(f64::INFINITY, |s| s.nrmse);
                        Some((fast - core).abs())
                    })
                    .fold(0.0f64, f64::max)
            };
            assert!(model.checked_error <= MARGIN * SEARCH_TOLERANCE);
            assert_eq!(worst(&model), model.checked_error);
            if model.substeps > 1 {
                let half = SearchModel {
                    substeps: model.substeps / 2,
                    ..model.clone()
                };
                let w0 = (6.0 / MASS).sqrt();
                assert!(
                    worst(&half) > MARGIN * SEARCH_TOLERANCE
                        || w0 / rate / half.substeps as f64 > MAX_H_W0,
                    "{rate} Hz: {} steps would do",
                    half.substeps
                );
            }
            eprintln!(
                "{rate} Hz: {} steps, checked {:e}",
                model.substeps, model.checked_error
            );
        }
    }

    #[test]
    fn van_der_corput() {
        let two: Vec<f64> = (1..=4).map(|i| radical_inverse(i, 2)).collect();
        assert_eq!(two, [0.5, 0.25, 0.75, 0.125]);
        let three: Vec<f64> = (1..=4).map(|i| radical_inverse(i, 3)).collect();
        assert_eq!(
            three,
            [1.0 / 3.0, 2.0 / 3.0, 1.0 / 9.0, 1.0 / 9.0 + 1.0 / 3.0]
        );
    }

    /// Where it matters, between the checked points: at random points of the bounds, the search
    /// model's NRMSE is within the tolerance of the core's, so it ranks candidates as the core
    /// would wherever their errors differ by more. (At some extreme points, such as n = 3.1 with
    /// alpha = 0.014, the core's sub-step budget runs out, where the search model still gives a
    /// finite answer; those are skipped, and counted.) The same with the force cubic between
    /// samples, in both models.
    #[test]
    fn random_candidates_score_as_with_the_core() {
        for (rate, p) in [
            (
                100.0,
                problem_between(ModelSpec::BW, 100.0, Between::Linear),
            ),
            (
                500.0,
                problem_between(ModelSpec::BW, 500.0, Between::Linear),
            ),
            (100.0, problem_between(ModelSpec::BW, 100.0, Between::Cubic)),
            (
                200.0,
                problem_under(ModelSpec::BW, 200.0, Between::Cubic, band_limited, 2.0),
            ),
        ] {
            let model = SearchModel::for_problem(&p).expect("a search model");
            let (lo, hi) = p.par.bounds();
            let mut seed = 0x9e37_79b9_7f4a_7c15u64;
            let (mut worst, mut compared) = (0.0f64, 0);
            for _ in 0..24 {
                let x: Vec<f64> = lo
                    .iter()
                    .zip(&hi)
                    .map(|(l, h)| {
                        seed ^= seed << 13;
                        seed ^= seed >> 7;
                        seed ^= seed << 17;
                        l + (h - l) * (seed >> 11) as f64 / (1u64 << 53) as f64
                    })
                    .collect();
                if let Some((fast, core)) = compare(&model, &p, &x) {
                    worst = worst.max((fast - core).abs());
                    compared += 1;
                }
            }
            assert!(compared >= 20, "{rate} Hz: {compared} of 24");
            assert!(
                worst <= SEARCH_TOLERANCE,
                "{rate} Hz: NRMSE off by {worst:e}"
            );
            eprintln!(
                "{rate} Hz: {} steps, {compared} compared, worst {worst:e}",
                model.substeps
            );
        }
    }

    /// A candidate whose fixed-step run is not finite is simulated again with [`RETRY`] times
    /// the steps, which scores it about as the core does, and the summary counts it.
    ///
    /// About: such a candidate is stiff, and the first one found is at the edge of the
    /// retry's stability, where RK4 is stable but not accurate to the search's tolerance. It
    /// scores 29.85 against the core's 29.4108266 (1.5%; at 16 and 64 times the steps
    /// 29.4108271 and 29.4108270). The search only has to rank it far below candidates within
    /// the search's tolerance of a fit (a good fit's NRMSE is about 1e-3), which 2% does. (Until
    /// the core's oscillator landed its sub-steps on v = 0 and z = 0 it was itself 1.5% off here,
    /// and agreed with the retry to 1e-3.)
    #[test]
    fn a_candidate_that_blows_up_is_simulated_again_with_more_steps() {
        let p = problem(ModelSpec::BW, 100.0);
        let model = SearchModel::for_problem(&p).expect("a search model");
        let (lo, hi) = p.par.bounds();
        let more = SearchModel {
            substeps: RETRY * model.substeps,
            ..model.clone()
        };
        let alone = |m: &SearchModel, x: &[f64]| m.simulate(&p, &[x], m.substeps).remove(0);
        // Halton points past the checked ones, until one blows up at the chosen steps and not
        // at the retry's.
        let x = (CHECKED as u32 + 1..2000)
            .map(|i| {
                lo.iter()
                    .zip(&hi)
                    .zip(PRIMES)
                    .map(|((l, h), base)| l + (h - l) * radical_inverse(i, base))
                    .collect::<Vec<f64>>()
            })
            .find(|x| {
                p.scores(x).is_some() && alone(&model, x).is_none() && alone(&more, x).is_some()
            })
            .expect("a point where the chosen steps blow up and the retry's do not");
        let retried = alone(&more, &x).unwrap().nrmse;
        let scored = model.scores(&p, &[&x]).remove(0).unwrap().nrmse;
        assert_eq!(scored, retried);
        let core = p.scores(&x).unwrap().nrmse;
        assert!(
            (retried - core).abs() <= 0.02 * core && core > 1e3 * SEARCH_TOLERANCE,
            "{retried} against the core's {core}"
        );
        let summary = model.summary();
        assert_eq!((summary.retried, summary.by_core), (1, 0));
        eprintln!(
            "{:?}: {retried} against the core's {core}",
            p.par.physical(&x)
        );
    }

    #[test]
    fn only_force_driven_plain_bouc_wen() {
        let p = problem(ModelSpec::BW, 100.0);
        assert!(SearchModel::for_problem(&p).is_ok());
        let pinched: ModelSpec = "bw+pinching".parse().unwrap();
        assert_eq!(
            SearchModel::for_problem(&problem(pinched, 100.0)).unwrap_err(),
            Unsuited::Model
        );
        let quasi_static = Problem::new(
            ModelSpec::BW,
            Experiment {
                drive: Drive::Displacement,
                ..p.exp.clone()
            },
            &[],
        )
        .unwrap();
        assert_eq!(
            SearchModel::for_problem(&quasi_static).unwrap_err(),
            Unsuited::Model
        );
    }
}
