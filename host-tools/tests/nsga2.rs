//! NSGA-II against independent expectations: problems with known Pareto fronts (ZDT1-3, CONSTR,
//! TNK), a single-objective minimum, the knee of a closed-form front, and the reproducibility
//! promises (a seed fixes the result; threads do not change it).
//!
//! The IGD (and GD) limits are 1.5 times the mean IGD (GD) that pymoo 0.6.2's NSGA-II reaches with
//! the same population (100) and generations (250), the same sampled fronts and the same
//! distances, over seeds 1-5 (`benches/baselines/pymoo_test_problems.py`): IGD ZDT1 0.00476,
//! ZDT2 0.00481, ZDT3 0.00518, CONSTR 0.01792, TNK 0.00458; GD CONSTR 0.00358, TNK 0.00095.

use std::ops::ControlFlow;

use hyst::fit::nsga2::test_problems::{
    generational_distance, igd, Constr, Sphere, Tnk, Zdt, ZdtKind,
};
use hyst::fit::nsga2::{
    closest_to_origin, dominates, write_front_csv, BinaryCrossover, Bounds, Encoding, Evaluation,
    Nsga2, Nsga2Error, Outcome, Problem,
};

const PYMOO_MEAN_IGD_ZDT1: f64 = 0.00476;
const PYMOO_MEAN_IGD_ZDT2: f64 = 0.00481;
const PYMOO_MEAN_IGD_ZDT3: f64 = 0.00518;
const PYMOO_MEAN_IGD_CONSTR: f64 = 0.01792;
const PYMOO_MEAN_IGD_TNK: f64 = 0.00458;
const PYMOO_MEAN_GD_CONSTR: f64 = 0.00358;
const PYMOO_MEAN_GD_TNK: f64 = 0.00095;
const MARGIN: f64 = 1.5;

fn feasible_front(outcome: &Outcome) -> Vec<Vec<f64>> {
    outcome
        .first_front()
        .iter()
        .filter(|s| s.is_feasible())
        .map(|s| s.objectives.clone())
        .collect()
}

fn settings(seed: u64) -> Nsga2 {
    Nsga2 {
        seed,
        ..Nsga2::default()
    }
}

/// Runs `problem` for seeds 1-3 and checks the IGD of each feasible first front.
fn assert_igd<P: Problem>(
    name: &str,
    problem: &P,
    encoding: Encoding,
    reference: &[[f64; 2]],
    pymoo_mean: f64,
) {
    for seed in 1..=3 {
        let outcome = Nsga2 {
            encoding,
            ..settings(seed)
        }
        .run(problem)
        .expect("valid settings");
        assert_eq!(outcome.evaluations, 25_000);
        let front = feasible_front(&outcome);
        assert_eq!(
            front.len(),
            100,
            "{name}: the whole population reaches the first front"
        );
        let d = igd(&front, reference);
        let gd = generational_distance(&front, reference);
        eprintln!("{name} seed {seed}: IGD {d:.5} GD {gd:.5} (pymoo mean IGD {pymoo_mean})");
        assert!(
            d < MARGIN * pymoo_mean,
            "{name} seed {seed}: IGD {d} >= {MARGIN} x {pymoo_mean}"
        );
    }
}

#[test]
fn zdt1_real_coded_reaches_the_convex_front() {
    let p = Zdt::new(ZdtKind::Zdt1, 30);
    assert_igd(
        "ZDT1",
        &p,
        Encoding::REAL,
        &p.pareto_front(1000),
        PYMOO_MEAN_IGD_ZDT1,
    );
}

#[test]
fn zdt2_real_coded_reaches_the_concave_front() {
    let p = Zdt::new(ZdtKind::Zdt2, 30);
    assert_igd(
        "ZDT2",
        &p,
        Encoding::REAL,
        &p.pareto_front(1000),
        PYMOO_MEAN_IGD_ZDT2,
    );
}

#[test]
fn zdt3_real_coded_covers_the_five_disconnected_pieces() {
    let p = Zdt::new(ZdtKind::Zdt3, 30);
    assert_igd(
        "ZDT3",
        &p,
        Encoding::REAL,
        &p.pareto_front(1000),
        PYMOO_MEAN_IGD_ZDT3,
    );
}

#[test]
fn constr_real_coded_follows_the_active_constraint() {
    assert_igd(
        "CONSTR",
        &Constr::default(),
        Encoding::REAL,
        &Constr::pareto_front(1000),
        PYMOO_MEAN_IGD_CONSTR,
    );
}

#[test]
fn tnk_real_coded_follows_the_wavy_constraint_boundary() {
    assert_igd(
        "TNK",
        &Tnk::default(),
        Encoding::REAL,
        &Tnk::pareto_front(20_001),
        PYMOO_MEAN_IGD_TNK,
    );
}

const BINARY_PER_VARIABLE: Encoding = Encoding::Binary {
    bits: 30,
    crossover: BinaryCrossover::PerVariable,
};

#[test]
fn zdt1_binary_coded_reaches_the_front() {
    let p = Zdt::new(ZdtKind::Zdt1, 30);
    assert_igd(
        "ZDT1 binary",
        &p,
        BINARY_PER_VARIABLE,
        &p.pareto_front(1000),
        PYMOO_MEAN_IGD_ZDT1,
    );
}

#[test]
fn zdt2_binary_coded_reaches_the_front() {
    let p = Zdt::new(ZdtKind::Zdt2, 30);
    assert_igd(
        "ZDT2 binary",
        &p,
        BINARY_PER_VARIABLE,
        &p.pareto_front(1000),
        PYMOO_MEAN_IGD_ZDT2,
    );
}

/// Runs `problem` for seeds 1-3 and checks that the feasible first front lies on the Pareto
/// front (GD), without asking it to cover the whole front.
fn assert_gd<P: Problem>(
    name: &str,
    problem: &P,
    encoding: Encoding,
    reference: &[[f64; 2]],
    pymoo_mean: f64,
) {
    for seed in 1..=3 {
        let outcome = Nsga2 {
            encoding,
            ..settings(seed)
        }
        .run(problem)
        .expect("valid settings");
        let front = feasible_front(&outcome);
        assert!(
            front.len() >= 50,
            "{name}: {} feasible first-front members",
            front.len()
        );
        let d = igd(&front, reference);
        let gd = generational_distance(&front, reference);
        eprintln!("{name} seed {seed}: IGD {d:.5} GD {gd:.5} (pymoo mean GD {pymoo_mean})");
        assert!(
            gd < MARGIN * pymoo_mean,
            "{name} seed {seed}: GD {gd} >= {MARGIN} x {pymoo_mean}"
        );
    }
}

// The binary-coded variants converge onto the constrained fronts about as closely as pymoo's
// real-coded NSGA-II (GD) but cover them less well: on TNK they measured IGD 0.008-0.058, missing
// the short end pieces of the front where the wavy boundary meets the circle. Only GD is asserted.

#[test]
fn tnk_binary_single_point_the_thesis_variant_converges_onto_the_constraint_boundary() {
    let thesis = Encoding::Binary {
        bits: 20,
        crossover: BinaryCrossover::SinglePoint,
    };
    assert_gd(
        "TNK binary single-point",
        &Tnk::default(),
        thesis,
        &Tnk::pareto_front(20_001),
        PYMOO_MEAN_GD_TNK,
    );
}

#[test]
fn constr_binary_two_point_converges_onto_the_active_constraint() {
    let two_point = Encoding::Binary {
        bits: 20,
        crossover: BinaryCrossover::TwoPoint,
    };
    assert_gd(
        "CONSTR binary two-point",
        &Constr::default(),
        two_point,
        &Constr::pareto_front(1000),
        PYMOO_MEAN_GD_CONSTR,
    );
}

#[test]
fn eliminating_duplicates_keeps_every_member_distinct() {
    // Bit strings breed copies: without elimination, TNK at 20 bits a variable measured about
    // half of its final population duplicated.
    let thesis = Encoding::Binary {
        bits: 20,
        crossover: BinaryCrossover::SinglePoint,
    };
    let distinct = |eliminate_duplicates| {
        let outcome = Nsga2 {
            generations: 100,
            encoding: thesis,
            eliminate_duplicates,
            ..settings(1)
        }
        .run(&Tnk::default())
        .expect("valid settings");
        let mut keys: Vec<Vec<u64>> = outcome
            .population
            .iter()
            .map(|s| s.variables.iter().map(|v| v.to_bits()).collect())
            .collect();
        keys.sort_unstable();
        keys.dedup();
        keys.len()
    };
    assert_eq!(distinct(true), 100);
    assert!(distinct(false) < 90);
}

#[test]
fn sphere_single_objective_reaches_the_minimum_at_the_origin() {
    for encoding in [
        Encoding::REAL,
        Encoding::Binary {
            bits: 24,
            crossover: BinaryCrossover::PerVariable,
        },
    ] {
        let outcome = Nsga2 {
            population: 50,
            generations: 200,
            encoding,
            ..settings(1)
        }
        .run(&Sphere::new(10))
        .expect("valid settings");
        let best = outcome.best_objectives().expect("unconstrained")[0];
        eprintln!("sphere {encoding:?}: best {best:e}");
        // The population starts near E[sum x^2] = 10 x 5.12^2 / 3 = 87.4.
        assert!(best < 1.0e-3, "{encoding:?}: best {best}");
        let chosen = outcome.chosen().expect("feasible");
        assert_eq!(
            chosen.objectives[0], best,
            "one objective: the chosen one is the best"
        );
    }
}

#[test]
fn the_chosen_solution_of_zdt1_is_the_knee_of_its_normalised_front() {
    // The normalised front is (f1, 1 - sqrt(f1)); with s = sqrt(f1) the squared distance to the
    // origin is s^4 + (1 - s)^2, least where 4 s^3 - 2 (1 - s) = 0, i.e. 2 s^3 + s - 1 = 0:
    // s = 0.5898, f1 = 0.3478.
    let s = {
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if 2.0 * mid * mid * mid + mid - 1.0 > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    };
    let knee_f1 = s * s;
    assert!((knee_f1 - 0.3478).abs() < 1e-4);
    let outcome = settings(4)
        .run(&Zdt::new(ZdtKind::Zdt1, 30))
        .expect("valid settings");
    let chosen = outcome.chosen().expect("feasible");
    // 100 points spread over f1 in [0, 1]: neighbours about 0.01-0.02 apart near the knee.
    assert!(
        (chosen.objectives[0] - knee_f1).abs() < 0.03,
        "chosen {:?}",
        chosen.objectives
    );
    // And it is what closest_to_origin picks from the front's objectives.
    let front = outcome.first_front();
    let i = closest_to_origin(front.iter().map(|s| s.objectives.as_slice())).expect("non-empty");
    assert_eq!(front[i].objectives, chosen.objectives);
}

#[test]
fn first_front_members_are_dominated_by_no_member() {
    let outcome = Nsga2 {
        generations: 40,
        ..settings(2)
    }
    .run(&Constr::default())
    .expect("valid settings");
    let front = outcome.first_front();
    assert!(!front.is_empty());
    for a in &front {
        assert!(outcome.population.iter().all(|b| !dominates(b, a)));
    }
    for b in outcome.population.iter().filter(|s| s.rank > 0) {
        assert!(
            outcome.population.iter().any(|a| dominates(a, b)),
            "a later-front member is dominated"
        );
    }
}

/// Every number of an outcome, as bits.
fn fingerprint(outcome: &Outcome) -> Vec<u64> {
    let mut bits = vec![outcome.generations as u64, outcome.evaluations as u64];
    for s in &outcome.population {
        let numbers = s
            .variables
            .iter()
            .chain(&s.objectives)
            .chain(&s.constraint_violations)
            .chain([&s.total_violation, &s.crowding]);
        bits.extend(numbers.map(|v| v.to_bits()));
        bits.push(s.rank as u64);
    }
    bits
}

#[test]
fn a_seed_fixes_the_result_and_another_seed_changes_it() {
    let p = Tnk::default();
    let run = |seed| {
        Nsga2 {
            generations: 60,
            ..settings(seed)
        }
        .run(&p)
        .expect("valid settings")
    };
    assert_eq!(fingerprint(&run(7)), fingerprint(&run(7)));
    assert_ne!(fingerprint(&run(7)), fingerprint(&run(8)));
}

/// ZDT1 whose evaluation takes a time that depends on `x`, so that threads finish out of order.
struct UnevenZdt1(Zdt);

impl Problem for UnevenZdt1 {
    fn bounds(&self) -> &[Bounds] {
        self.0.bounds()
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let spins = (x[0] * 20_000.0) as u64;
        let mut acc = 0u64;
        for i in 0..spins {
            acc = std::hint::black_box(acc.wrapping_add(i));
        }
        std::hint::black_box(acc);
        self.0.evaluate(x)
    }
}

#[test]
fn threads_do_not_change_the_result() {
    let p = UnevenZdt1(Zdt::new(ZdtKind::Zdt1, 30));
    for encoding in [Encoding::REAL, BINARY_PER_VARIABLE] {
        let base = Nsga2 {
            generations: 30,
            encoding,
            ..settings(3)
        };
        let sequential = Nsga2 {
            parallel: false,
            ..base.clone()
        }
        .run(&p)
        .expect("valid settings");
        for threads in [1, 2, 4, 7] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            let parallel = pool.install(|| base.run(&p)).expect("valid settings");
            assert_eq!(
                fingerprint(&parallel),
                fingerprint(&sequential),
                "{threads} threads, {encoding:?}"
            );
        }
    }
}

/// ZDT1 evaluated `size` candidates at a time, recording the batch lengths it was given (or, with
/// `short`, dropping the last evaluation of each batch).
struct BatchedZdt1 {
    zdt: Zdt,
    size: usize,
    short: bool,
    seen: std::sync::Mutex<Vec<usize>>,
}

impl Problem for BatchedZdt1 {
    fn bounds(&self) -> &[Bounds] {
        self.zdt.bounds()
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, _: &[f64]) -> Evaluation {
        unreachable!("every evaluation goes through evaluate_batch")
    }
    fn batch_size(&self) -> usize {
        self.size
    }
    fn evaluate_batch(&self, xs: &[&[f64]]) -> Vec<Evaluation> {
        self.seen.lock().unwrap().push(xs.len());
        let mut out: Vec<Evaluation> = xs.iter().map(|x| self.zdt.evaluate(x)).collect();
        if self.short {
            out.pop();
        }
        out
    }
}

#[test]
fn batches_change_nothing_but_how_candidates_are_handed_over() {
    let zdt = Zdt::new(ZdtKind::Zdt1, 30);
    let run = |parallel| Nsga2 {
        generations: 30,
        parallel,
        ..settings(3)
    };
    let one_by_one = run(false).run(&zdt).expect("valid settings");
    for parallel in [false, true] {
        let batched = BatchedZdt1 {
            zdt: Zdt::new(ZdtKind::Zdt1, 30),
            size: 8,
            short: false,
            seen: Default::default(),
        };
        let outcome = run(parallel).run(&batched).expect("valid settings");
        assert_eq!(fingerprint(&outcome), fingerprint(&one_by_one));
        let seen = batched.seen.into_inner().unwrap();
        // 30 generations of 100 candidates (the first one included): 12 batches of 8 and one
        // of 4 each.
        assert_eq!(outcome.evaluations, 3_000);
        assert_eq!(seen.len(), 30 * 13, "{parallel}");
        assert!(seen.iter().all(|&n| n == 8 || n == 4));
        assert_eq!(seen.iter().sum::<usize>(), 3_000);
    }
    let short = BatchedZdt1 {
        zdt,
        size: 8,
        short: true,
        seen: Default::default(),
    };
    let err = run(false).run(&short).expect_err("a batch came back short");
    assert_eq!(
        err,
        Nsga2Error::BatchLength {
            candidates: 100,
            evaluations: 87
        }
    );
    assert!(err.to_string().contains("expected one each"), "{err}");
}

#[test]
fn the_callback_sees_every_generation_and_can_stop_the_run() {
    let p = Zdt::new(ZdtKind::Zdt2, 10);
    let s = Nsga2 {
        population: 20,
        generations: 30,
        ..settings(5)
    };
    let mut seen = Vec::new();
    let full = s
        .run_with(&p, |g| {
            seen.push((g.index, g.evaluations, g.population.len()));
            assert!(g.first_front_len() >= 1 && g.feasible() == 20);
            ControlFlow::Continue(())
        })
        .expect("valid settings");
    assert_eq!(seen, (1..=30).map(|i| (i, 20 * i, 20)).collect::<Vec<_>>());
    assert!(!full.stopped_early);

    let mut best_f2 = Vec::new();
    let stopped = s
        .run_with(&p, |g| {
            best_f2.push(g.best_objectives().expect("unconstrained")[1]);
            if g.index == 10 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .expect("valid settings");
    assert_eq!((stopped.generations, stopped.evaluations), (10, 200));
    assert!(stopped.stopped_early);
    // Elitism: the best value of each objective never gets worse.
    assert!(best_f2.windows(2).all(|w| w[1] <= w[0]), "{best_f2:?}");
    // The stopped run is the full run's prefix: same draws, same first ten generations.
    let ten = Nsga2 {
        generations: 10,
        ..s
    }
    .run(&p)
    .expect("valid settings");
    assert_eq!(fingerprint(&ten)[2..], fingerprint(&stopped)[2..]);
}

#[test]
fn the_front_as_csv_reads_back_to_the_same_numbers() {
    let p = Constr::default();
    let outcome = Nsga2 {
        generations: 20,
        ..settings(6)
    }
    .run(&p)
    .expect("valid settings");
    let front = outcome.first_front();
    let mut out = Vec::new();
    write_front_csv(&mut out, &p, &front).expect("write to memory");
    let text = String::from_utf8(out).expect("utf-8");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x1,x2,f1,f2,constraint_violation"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect())
        .collect();
    assert_eq!(rows.len(), front.len());
    for (row, s) in rows.iter().zip(&front) {
        let expected: Vec<f64> = s
            .variables
            .iter()
            .chain(&s.objectives)
            .chain([&s.total_violation])
            .copied()
            .collect();
        assert_eq!(row, &expected);
    }
}

/// A problem that blows up (NaN) on part of its domain, and returns the wrong shape on demand.
struct Fragile {
    bounds: [Bounds; 1],
    wrong_shape: bool,
}

impl Problem for Fragile {
    fn bounds(&self) -> &[Bounds] {
        &self.bounds
    }
    fn num_objectives(&self) -> usize {
        2
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        if self.wrong_shape {
            return Evaluation::unconstrained(vec![x[0]]);
        }
        let f = if x[0] > 3.0 { f64::NAN } else { x[0] * x[0] };
        Evaluation::unconstrained(vec![f, (x[0] - 2.0).powi(2)])
    }
}

#[test]
fn blown_up_evaluations_are_counted_and_never_chosen() {
    let p = Fragile {
        bounds: [Bounds::new(-5.0, 5.0)],
        wrong_shape: false,
    };
    let outcome = Nsga2 {
        population: 40,
        generations: 40,
        ..settings(9)
    }
    .run(&p)
    .expect("valid settings");
    // About a fifth of the initial population lies in (3, 5].
    assert!(outcome.invalid_evaluations > 0);
    let front = outcome.first_front();
    assert!(front
        .iter()
        .all(|s| s.is_feasible() && s.variables[0] <= 3.0));
    let chosen = outcome.chosen().expect("feasible");
    assert!(
        (chosen.variables[0] - 1.0).abs() < 0.15,
        "{:?}",
        chosen.variables
    );
}

#[test]
fn wrong_shapes_and_bad_bounds_are_errors_not_panics() {
    let wrong = Fragile {
        bounds: [Bounds::new(-5.0, 5.0)],
        wrong_shape: true,
    };
    match settings(1).run(&wrong) {
        Err(Nsga2Error::EvaluationShape {
            objectives,
            constraints,
            ..
        }) => {
            assert_eq!((objectives, constraints), ((1, 2), (0, 0)));
        }
        other => panic!("{other:?}"),
    }
    for bounds in [
        Bounds::new(1.0, 1.0),
        Bounds::new(2.0, 1.0),
        Bounds::new(0.0, f64::INFINITY),
    ] {
        let p = Fragile {
            bounds: [bounds],
            wrong_shape: false,
        };
        let err = settings(1).run(&p).expect_err("bad bounds");
        assert_eq!(
            err,
            Nsga2Error::Bounds {
                variable: 0,
                lower: bounds.lower,
                upper: bounds.upper
            }
        );
        assert!(err.to_string().contains("lower < upper"));
    }
}
