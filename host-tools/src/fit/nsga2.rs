//! NSGA-II, the elitist non-dominated sorting genetic algorithm of Deb, Pratap, Agarwal and
//! Meyarivan (2002), which the thesis uses (section 3.3, after Ortiz et al. 2013) to identify
//! Bouc-Wen-Baber-Noori parameters. Generic over the [`Problem`]; the model objectives live
//! elsewhere.
//!
//! One generation: binary tournaments by the crowded comparison (rank, then crowding distance)
//! pick parents; crossover and mutation make as many children as there are parents (by default
//! none a copy of a parent or of another child: [`Nsga2::eliminate_duplicates`]); the children
//! are evaluated (in parallel); parents and children are merged, sorted into non-dominated
//! fronts under constraint domination (Deb 2000), and the best half survives, the last front
//! admitted being cut by crowding distance.
//!
//! Two encodings: real-coded (simulated binary crossover and polynomial mutation, both bounded,
//! as in Deb's reference code) and binary-coded (the thesis' description: fixed-length bit strings
//! decoded between the bounds, a random cross site, bit-flip mutation).
//!
//! Reproducible: every random draw is made on the calling thread from a seeded xoshiro256**
//! stream, before the evaluations of a generation start, so the result does not depend on the
//! number of threads; it is bit-identical with [`Nsga2::parallel`] on or off.
//!
//! The chosen solution is the thesis' (section 3.4): the point of the first front nearest the
//! origin once each objective is normalised to [0, 1] over the front ([`closest_to_origin`]).
//!
//! ```
//! use hyst::fit::nsga2::{Bounds, Evaluation, Nsga2, Problem};
//!
//! /// Schaffer's problem: minimise x^2 and (x - 2)^2; the Pareto set is 0 <= x <= 2.
//! struct Schaffer([Bounds; 1]);
//!
//! impl Problem for Schaffer {
//!     fn bounds(&self) -> &[Bounds] {
//!         &self.0
//!     }
//!     fn num_objectives(&self) -> usize {
//!         2
//!     }
//!     fn evaluate(&self, x: &[f64]) -> Evaluation {
//!         Evaluation::unconstrained(vec![x[0] * x[0], (x[0] - 2.0).powi(2)])
//!     }
//! }
//!
//! let problem = Schaffer([Bounds::new(-10.0, 10.0)]);
//! let settings = Nsga2 { population: 40, generations: 60, seed: 1, ..Nsga2::default() };
//! let outcome = settings.run(&problem)?;
//! assert_eq!(outcome.evaluations, 40 * 60);
//! assert!(outcome.first_front().iter().all(|s| (-1e-3..=2.001).contains(&s.variables[0])));
//! let knee = outcome.chosen().expect("a feasible front");
//! assert!((knee.variables[0] - 1.0).abs() < 0.1);
//! # Ok::<(), hyst::fit::nsga2::Nsga2Error>(())
//! ```

mod binary_coded;
mod front;
mod ranking;
mod real_coded;
pub mod test_problems;

use std::cmp::Ordering;
use std::collections::HashSet;
use std::fmt;
use std::ops::ControlFlow;

use rayon::prelude::*;

pub use binary_coded::MAX_BITS;
pub use front::{closest_to_origin, write_front_csv};

use crate::random::Rng;
use ranking::{
    constrained_domination, crowded_comparison, crowding_distances, non_dominated_fronts, Ranked,
};

/// The interval a variable lives in, `lower < upper`, both finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Smallest value.
    pub lower: f64,
    /// Largest value.
    pub upper: f64,
}

impl Bounds {
    /// The interval [lower, upper].
    pub const fn new(lower: f64, upper: f64) -> Self {
        Bounds { lower, upper }
    }
}

/// What a problem says of one candidate.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    /// The objectives, all minimised, [`Problem::num_objectives`] of them.
    pub objectives: Vec<f64>,
    /// How far each constraint is violated, [`Problem::num_constraints`] of them: zero or negative
    /// when it holds (pymoo's `G <= 0` convention). For `beta + gamma > 0`, say, `-(beta + gamma)`.
    pub constraint_violations: Vec<f64>,
}

impl Evaluation {
    /// An evaluation with objectives and constraint violations.
    pub fn new(objectives: Vec<f64>, constraint_violations: Vec<f64>) -> Self {
        Evaluation {
            objectives,
            constraint_violations,
        }
    }

    /// An evaluation of a problem without constraints.
    pub fn unconstrained(objectives: Vec<f64>) -> Self {
        Self::new(objectives, Vec::new())
    }
}

/// An optimisation problem: bounded variables, objectives to minimise, inequality constraints.
///
/// `evaluate` runs on several threads at once (hence `Sync`) and must be a pure function of `x`
/// for runs to be reproducible.
pub trait Problem: Sync {
    /// The bounds of each variable; their number is the number of variables.
    fn bounds(&self) -> &[Bounds];

    /// The number of objectives (at least one).
    fn num_objectives(&self) -> usize;

    /// The number of inequality constraints.
    fn num_constraints(&self) -> usize {
        0
    }

    /// Evaluates the candidate `x` (within the bounds). An objective that is not finite (a
    /// simulation that blew up, say) or a violation that is NaN marks the candidate invalid: it
    /// ranks as infeasible with an infinite violation and is counted in
    /// [`Outcome::invalid_evaluations`].
    fn evaluate(&self, x: &[f64]) -> Evaluation;

    /// How many candidates [`evaluate_batch`](Self::evaluate_batch) takes at once (1: one at a
    /// time).
    fn batch_size(&self) -> usize {
        1
    }

    /// Evaluates up to [`batch_size`](Self::batch_size) candidates, in their order. The default
    /// calls [`evaluate`](Self::evaluate) on each; a problem that simulates several candidates
    /// together (one per vector lane, [`crate::fit::lanes`]) overrides both. Each result must be
    /// what `evaluate` gives for that candidate alone, whatever its companions, for runs to stay
    /// reproducible.
    fn evaluate_batch(&self, xs: &[&[f64]]) -> Vec<Evaluation> {
        xs.iter().map(|x| self.evaluate(x)).collect()
    }

    /// Names of the variables, for CSV headers: `x1`, `x2`, ... unless overridden.
    fn variable_names(&self) -> Vec<String> {
        (1..=self.bounds().len()).map(|i| format!("x{i}")).collect()
    }

    /// Names of the objectives, for CSV headers: `f1`, `f2`, ... unless overridden.
    fn objective_names(&self) -> Vec<String> {
        (1..=self.num_objectives())
            .map(|i| format!("f{i}"))
            .collect()
    }
}

/// How candidates are represented and varied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Encoding {
    /// Real variables; simulated binary crossover and polynomial mutation, both bounded.
    Real {
        /// SBX distribution index eta_c: large values keep children near their parents.
        crossover_index: f64,
        /// Polynomial-mutation distribution index eta_m: large values make small steps.
        mutation_index: f64,
    },
    /// Bit strings decoded between the bounds (thesis section 3.3).
    Binary {
        /// Bits per variable, 1 to [`MAX_BITS`]: 2^bits equally spaced values per variable.
        bits: u32,
        /// Where the strings are cut.
        crossover: BinaryCrossover,
    },
}

impl Encoding {
    /// Real coding with the distribution indices of Deb et al. (2002): eta_c = eta_m = 20.
    pub const REAL: Encoding = Encoding::Real {
        crossover_index: 20.0,
        mutation_index: 20.0,
    };
}

/// Crossover of bit strings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryCrossover {
    /// One random cross site on the whole string; the bits after it are exchanged (the thesis).
    SinglePoint,
    /// Two random sites; the bits between them are exchanged.
    TwoPoint,
    /// Each variable's string crossed on its own, with the crossover probability, at two random
    /// sites (Deb's reference code; mixes many variables per mating, so it converges faster on
    /// problems of many variables).
    PerVariable,
}

/// The largest population a run takes. The non-dominated sort keeps, for
/// each of parents and children, whom it dominates, which grows with the
/// square of the population: measured peak memory 0.40 GB at 10,000 and
/// 6.0 GB at 40,000 on the thesis example (`hyst fit --method nsga2
/// --generations 1`), and 24 GB at 1,000,000 (an earlier limit).
pub const MAX_POPULATION: usize = 10_000;

/// The settings of one NSGA-II run.
#[derive(Clone, Debug, PartialEq)]
pub struct Nsga2 {
    /// Parents per generation, and children per generation (2 to
    /// [`MAX_POPULATION`]).
    pub population: usize,
    /// Generations, counting the random initial population as the first (as Deb's reference
    /// code and pymoo do): a run makes `population * generations` evaluations unless stopped.
    pub generations: usize,
    /// Probability that a pair of parents is crossed (otherwise the children are copies of
    /// them), or that a variable is, with [`BinaryCrossover::PerVariable`].
    pub crossover_probability: f64,
    /// Probability that a variable (real coding) or a bit (binary coding) mutates; `None` for one
    /// over the number of variables or bits, so one mutation per child on average.
    pub mutation_probability: Option<f64>,
    /// Representation and operators.
    pub encoding: Encoding,
    /// Mate again when a child is identical to a parent or to an earlier child of its
    /// generation, so that no evaluation is spent on a copy and copies do not crowd the front
    /// (pymoo's default; Deb's 2002 algorithm keeps duplicates). After 100 matings per child
    /// without enough distinct children (a tiny search space), duplicates are accepted.
    pub eliminate_duplicates: bool,
    /// Seed of the random stream: equal settings and seed give bit-identical results.
    pub seed: u64,
    /// Evaluate each generation's children on rayon's thread pool (the current one, so a
    /// caller may install a pool of its own size). Does not change the result.
    pub parallel: bool,
}

impl Default for Nsga2 {
    /// Population 100, 250 generations, crossover probability 0.9, one mutation per child,
    /// real coding with eta_c = eta_m = 20, duplicates eliminated, seed 0, parallel.
    fn default() -> Self {
        Nsga2 {
            population: 100,
            generations: 250,
            crossover_probability: 0.9,
            mutation_probability: None,
            encoding: Encoding::REAL,
            eliminate_duplicates: true,
            seed: 0,
            parallel: true,
        }
    }
}

/// A member of a population.
#[derive(Clone, Debug, PartialEq)]
pub struct Individual {
    /// Its variables (decoded, in binary coding).
    pub variables: Vec<f64>,
    /// Its objectives as evaluated.
    pub objectives: Vec<f64>,
    /// Its constraint violations as evaluated.
    pub constraint_violations: Vec<f64>,
    /// Sum of the positive violations; 0 when feasible; infinite when the evaluation was invalid.
    pub total_violation: f64,
    /// Its front in the last sort, 0 for the first (non-dominated) front.
    pub rank: usize,
    /// Its crowding distance within that front (infinite at the front's extremes).
    pub crowding: f64,
    /// The bit strings it decodes from (binary coding; empty in real coding).
    genome: Vec<u64>,
}

impl Individual {
    /// Satisfies every constraint.
    pub fn is_feasible(&self) -> bool {
        self.total_violation == 0.0
    }

    fn new(candidate: Candidate, evaluation: Evaluation) -> Self {
        let valid = evaluation.objectives.iter().all(|f| f.is_finite())
            && !evaluation.constraint_violations.iter().any(|g| g.is_nan());
        let total_violation = if valid {
            evaluation
                .constraint_violations
                .iter()
                .map(|&g| g.max(0.0))
                .sum()
        } else {
            f64::INFINITY
        };
        Individual {
            variables: candidate.variables,
            objectives: evaluation.objectives,
            constraint_violations: evaluation.constraint_violations,
            total_violation,
            rank: 0,
            crowding: 0.0,
            genome: candidate.genome,
        }
    }

    /// The evaluation gave finite objectives and no NaN violation.
    fn is_valid(&self) -> bool {
        self.objectives.iter().all(|f| f.is_finite())
            && !self.constraint_violations.iter().any(|g| g.is_nan())
    }
}

impl Ranked for Individual {
    fn objectives(&self) -> &[f64] {
        &self.objectives
    }
    fn total_violation(&self) -> f64 {
        self.total_violation
    }
}

/// The state after one generation, handed to the callback of [`Nsga2::run_with`].
#[derive(Clone, Copy, Debug)]
pub struct Generation<'a> {
    /// 1 for the initial population, up to [`Nsga2::generations`].
    pub index: usize,
    /// Evaluations so far.
    pub evaluations: usize,
    /// Evaluations so far that returned a non-finite objective or a NaN violation.
    pub invalid_evaluations: usize,
    /// The surviving population.
    pub population: &'a [Individual],
}

impl Generation<'_> {
    /// The smallest value of each objective over the feasible members, `None` if none is feasible.
    pub fn best_objectives(&self) -> Option<Vec<f64>> {
        best_objectives(self.population)
    }

    /// The number of members in the first front.
    pub fn first_front_len(&self) -> usize {
        self.population.iter().filter(|s| s.rank == 0).count()
    }

    /// The number of feasible members.
    pub fn feasible(&self) -> usize {
        self.population.iter().filter(|s| s.is_feasible()).count()
    }
}

fn best_objectives(population: &[Individual]) -> Option<Vec<f64>> {
    let mut feasible = population.iter().filter(|s| s.is_feasible());
    let mut best = feasible.next()?.objectives.clone();
    for s in feasible {
        for (b, &f) in best.iter_mut().zip(&s.objectives) {
            *b = b.min(f);
        }
    }
    Some(best)
}

/// The result of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The final population, with ranks and crowding distances of the last sort.
    pub population: Vec<Individual>,
    /// Generations made (fewer than asked when stopped early).
    pub generations: usize,
    /// Evaluations made.
    pub evaluations: usize,
    /// Evaluations that returned a non-finite objective or a NaN violation.
    pub invalid_evaluations: usize,
    /// The callback stopped the run before the last generation.
    pub stopped_early: bool,
}

impl Outcome {
    /// The first front of the final population (duplicates included, in population order). It is
    /// the Pareto front found when any member is feasible; otherwise it holds the members of
    /// least violation.
    pub fn first_front(&self) -> Vec<&Individual> {
        self.population.iter().filter(|s| s.rank == 0).collect()
    }

    /// The thesis' choice of one solution (section 3.4): the member of the first front nearest
    /// the origin with every objective normalised to [0, 1] over the front. `None` when no member
    /// is feasible.
    pub fn chosen(&self) -> Option<&Individual> {
        let front: Vec<&Individual> = self
            .first_front()
            .into_iter()
            .filter(|s| s.is_feasible())
            .collect();
        closest_to_origin(front.iter().map(|s| s.objectives.as_slice())).map(|i| front[i])
    }

    /// The smallest value of each objective over the feasible members.
    pub fn best_objectives(&self) -> Option<Vec<f64>> {
        best_objectives(&self.population)
    }
}

/// Why a run could not start or go on.
#[derive(Clone, Debug, PartialEq)]
pub enum Nsga2Error {
    /// A setting out of its range.
    Setting {
        /// The field of [`Nsga2`] or [`Encoding`].
        name: &'static str,
        /// Its value.
        value: String,
        /// What it must be.
        expected: &'static str,
    },
    /// The problem has no variables.
    NoVariables,
    /// The problem has no objectives.
    NoObjectives,
    /// A variable's bounds are not finite with lower < upper (a fixed parameter must be taken
    /// out of the problem rather than given equal bounds).
    Bounds {
        /// Index of the variable (from 0).
        variable: usize,
        /// Its lower bound.
        lower: f64,
        /// Its upper bound.
        upper: f64,
    },
    /// `evaluate` returned the wrong number of objectives or constraints.
    EvaluationShape {
        /// The candidate evaluated.
        variables: Vec<f64>,
        /// Objectives returned and expected.
        objectives: (usize, usize),
        /// Constraint violations returned and expected.
        constraints: (usize, usize),
    },
    /// `evaluate_batch` returned more or fewer evaluations than it was given candidates.
    BatchLength {
        /// Candidates of the generation.
        candidates: usize,
        /// Evaluations returned for them.
        evaluations: usize,
    },
}

impl fmt::Display for Nsga2Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Nsga2Error::Setting { name, value, expected } => {
                write!(f, "NSGA-II setting `{name}` = {value}: expected {expected}")
            }
            Nsga2Error::NoVariables => f.write_str("the problem has no variables to optimise"),
            Nsga2Error::NoObjectives => f.write_str("the problem has no objectives"),
            Nsga2Error::Bounds { variable, lower, upper } => write!(
                f,
                "bounds of variable {variable} are [{lower}, {upper}]: expected finite bounds with lower < upper"
            ),
            Nsga2Error::EvaluationShape {
                variables,
                objectives,
                constraints,
            } => write!(
                f,
                "evaluating {variables:?} returned {} objectives and {} constraint violations: expected {} and {}",
                objectives.0, constraints.0, objectives.1, constraints.1
            ),
            Nsga2Error::BatchLength {
                candidates,
                evaluations,
            } => write!(
                f,
                "evaluate_batch returned {evaluations} evaluations for {candidates} candidates: expected one each"
            ),
        }
    }
}

impl std::error::Error for Nsga2Error {}

/// A child before evaluation.
struct Candidate {
    variables: Vec<f64>,
    genome: Vec<u64>,
}

/// How many matings per child may be spent looking for distinct children before duplicates are
/// accepted (pymoo's limit too).
const MATINGS_PER_CHILD: usize = 100;

/// What makes two members the same: their bit strings, or the bits of their real variables.
fn identity(variables: &[f64], genome: &[u64]) -> Vec<u64> {
    if genome.is_empty() {
        variables.iter().map(|v| v.to_bits()).collect()
    } else {
        genome.to_vec()
    }
}

/// The variation operators with every setting resolved.
struct Variation<'a> {
    bounds: &'a [Bounds],
    eliminate_duplicates: bool,
    crossover_probability: f64,
    mutation_probability: f64,
    encoding: Encoding,
}

impl Variation<'_> {
    fn random(&self, rng: &mut Rng) -> Candidate {
        match self.encoding {
            Encoding::Real { .. } => Candidate {
                variables: self
                    .bounds
                    .iter()
                    .map(|b| b.lower + (b.upper - b.lower) * rng.uniform())
                    .collect(),
                genome: Vec::new(),
            },
            Encoding::Binary { bits, .. } => {
                let genome = self
                    .bounds
                    .iter()
                    .map(|_| binary_coded::random_word(bits, rng))
                    .collect();
                self.decoded(genome, bits)
            }
        }
    }

    fn decoded(&self, genome: Vec<u64>, bits: u32) -> Candidate {
        let variables = genome
            .iter()
            .zip(self.bounds)
            .map(|(&w, &b)| binary_coded::decode(w, bits, b))
            .collect();
        Candidate { variables, genome }
    }

    /// Two children of `a` and `b`.
    fn mate(&self, a: &Individual, b: &Individual, rng: &mut Rng) -> [Candidate; 2] {
        match self.encoding {
            Encoding::Real {
                crossover_index,
                mutation_index,
            } => {
                let (mut x, mut y) = (a.variables.clone(), b.variables.clone());
                if rng.chance(self.crossover_probability) {
                    real_coded::sbx(&mut x, &mut y, self.bounds, crossover_index, rng);
                }
                for child in [&mut x, &mut y] {
                    real_coded::polynomial_mutation(
                        child,
                        self.bounds,
                        self.mutation_probability,
                        mutation_index,
                        rng,
                    );
                }
                [x, y].map(|variables| Candidate {
                    variables,
                    genome: Vec::new(),
                })
            }
            Encoding::Binary { bits, crossover } => {
                let (mut x, mut y) = (a.genome.clone(), b.genome.clone());
                binary_coded::crossover(
                    &mut x,
                    &mut y,
                    bits,
                    crossover,
                    self.crossover_probability,
                    rng,
                );
                for child in [&mut x, &mut y] {
                    binary_coded::bit_flip(child, bits, self.mutation_probability, rng);
                }
                [x, y].map(|genome| self.decoded(genome, bits))
            }
        }
    }

    /// `count` children of `parents`, each parent chosen by a binary tournament. Contestants are
    /// drawn without replacement from a shuffled order of the population, reshuffled when spent,
    /// so every member enters the same number of tournaments, give or take one (Deb's scheme).
    fn offspring(&self, parents: &[Individual], count: usize, rng: &mut Rng) -> Vec<Candidate> {
        let mut order: Vec<usize> = (0..parents.len()).collect();
        let mut next = order.len();
        let mut tournament = |rng: &mut Rng| -> usize {
            if next + 2 > order.len() {
                rng.shuffle(&mut order);
                next = 0;
            }
            let (i, j) = (order[next], order[next + 1]);
            next += 2;
            let (a, b) = (&parents[i], &parents[j]);
            match crowded_comparison(a.rank, a.crowding, b.rank, b.crowding) {
                Ordering::Less => i,
                Ordering::Greater => j,
                Ordering::Equal => {
                    if rng.chance(0.5) {
                        i
                    } else {
                        j
                    }
                }
            }
        };
        let mut seen: HashSet<Vec<u64>> = HashSet::new();
        if self.eliminate_duplicates {
            seen.extend(parents.iter().map(|p| identity(&p.variables, &p.genome)));
        }
        let patience = MATINGS_PER_CHILD * count;
        let mut matings = 0;
        let mut children = Vec::with_capacity(count);
        while children.len() < count {
            let a = tournament(rng);
            let b = tournament(rng);
            matings += 1;
            for child in self.mate(&parents[a], &parents[b], rng) {
                let accept = !self.eliminate_duplicates
                    || matings > patience
                    || seen.insert(identity(&child.variables, &child.genome));
                if accept && children.len() < count {
                    children.push(child);
                }
            }
        }
        children
    }
}

impl Nsga2 {
    /// Runs to the last generation.
    pub fn run<P: Problem + ?Sized>(&self, problem: &P) -> Result<Outcome, Nsga2Error> {
        self.run_with(problem, |_| ControlFlow::Continue(()))
    }

    /// Runs, calling `on_generation` after each generation (the initial population included);
    /// the run stops early when it returns `ControlFlow::Break`.
    pub fn run_with<P, F>(&self, problem: &P, mut on_generation: F) -> Result<Outcome, Nsga2Error>
    where
        P: Problem + ?Sized,
        F: FnMut(&Generation<'_>) -> ControlFlow<()>,
    {
        let variation = self.variation(problem)?;
        let n = self.population;
        let mut rng = Rng::seed_from_u64(self.seed);

        let initial: Vec<Candidate> = (0..n).map(|_| variation.random(&mut rng)).collect();
        let mut population = self.evaluate(problem, initial)?;
        let mut invalid = population.iter().filter(|s| !s.is_valid()).count();
        population = survivors(population, n);
        let (mut generation, mut evaluations) = (1, n);
        let mut stop = on_generation(&Generation {
            index: generation,
            evaluations,
            invalid_evaluations: invalid,
            population: &population,
        })
        .is_break();

        while !stop && generation < self.generations {
            let children = variation.offspring(&population, n, &mut rng);
            let children = self.evaluate(problem, children)?;
            invalid += children.iter().filter(|s| !s.is_valid()).count();
            evaluations += children.len();
            population.extend(children);
            population = survivors(population, n);
            generation += 1;
            stop = on_generation(&Generation {
                index: generation,
                evaluations,
                invalid_evaluations: invalid,
                population: &population,
            })
            .is_break();
        }

        Ok(Outcome {
            population,
            generations: generation,
            evaluations,
            invalid_evaluations: invalid,
            stopped_early: generation < self.generations,
        })
    }

    /// Checks the settings against the problem.
    fn variation<'a, P: Problem + ?Sized>(
        &self,
        problem: &'a P,
    ) -> Result<Variation<'a>, Nsga2Error> {
        let setting = |name, value: String, expected| {
            Err(Nsga2Error::Setting {
                name,
                value,
                expected,
            })
        };
        let probability = |p: f64| (0.0..=1.0).contains(&p);
        if !(2..=MAX_POPULATION).contains(&self.population) {
            return setting("population", self.population.to_string(), "2 to 10,000");
        }
        if self.generations < 1 {
            return setting("generations", self.generations.to_string(), "at least 1");
        }
        if !probability(self.crossover_probability) {
            return setting(
                "crossover_probability",
                self.crossover_probability.to_string(),
                "a probability in [0, 1]",
            );
        }
        if let Some(p) = self.mutation_probability.filter(|&p| !probability(p)) {
            return setting(
                "mutation_probability",
                p.to_string(),
                "a probability in [0, 1]",
            );
        }
        let bounds = problem.bounds();
        if bounds.is_empty() {
            return Err(Nsga2Error::NoVariables);
        }
        if problem.num_objectives() == 0 {
            return Err(Nsga2Error::NoObjectives);
        }
        for (variable, b) in bounds.iter().enumerate() {
            if !(b.lower.is_finite() && b.upper.is_finite() && b.lower < b.upper) {
                return Err(Nsga2Error::Bounds {
                    variable,
                    lower: b.lower,
                    upper: b.upper,
                });
            }
        }
        let genes = match self.encoding {
            Encoding::Real {
                crossover_index,
                mutation_index,
            } => {
                for (name, eta) in [
                    ("crossover_index", crossover_index),
                    ("mutation_index", mutation_index),
                ] {
                    if !(eta.is_finite() && eta >= 0.0) {
                        return setting(name, eta.to_string(), "a finite distribution index >= 0");
                    }
                }
                bounds.len()
            }
            Encoding::Binary { bits, .. } => {
                if !(1..=MAX_BITS).contains(&bits) {
                    return setting("bits", bits.to_string(), "1 to 52 bits per variable");
                }
                bounds.len() * bits as usize
            }
        };
        Ok(Variation {
            bounds,
            crossover_probability: self.crossover_probability,
            mutation_probability: self.mutation_probability.unwrap_or(1.0 / genes as f64),
            encoding: self.encoding,
            eliminate_duplicates: self.eliminate_duplicates,
        })
    }

    /// Evaluates `candidates`, in parallel when asked; the order of the results is theirs.
    fn evaluate<P: Problem + ?Sized>(
        &self,
        problem: &P,
        candidates: Vec<Candidate>,
    ) -> Result<Vec<Individual>, Nsga2Error> {
        let batch = |chunk: &[Candidate]| {
            let xs: Vec<&[f64]> = chunk.iter().map(|c| c.variables.as_slice()).collect();
            problem.evaluate_batch(&xs)
        };
        let size = problem.batch_size().max(1);
        let evaluations: Vec<Evaluation> = if self.parallel {
            candidates.par_chunks(size).flat_map_iter(batch).collect()
        } else {
            candidates.chunks(size).flat_map(batch).collect()
        };
        if evaluations.len() != candidates.len() {
            return Err(Nsga2Error::BatchLength {
                candidates: candidates.len(),
                evaluations: evaluations.len(),
            });
        }
        let (m, k) = (problem.num_objectives(), problem.num_constraints());
        candidates
            .into_iter()
            .zip(evaluations)
            .map(|(c, e)| {
                if e.objectives.len() != m || e.constraint_violations.len() != k {
                    return Err(Nsga2Error::EvaluationShape {
                        variables: c.variables,
                        objectives: (e.objectives.len(), m),
                        constraints: (e.constraint_violations.len(), k),
                    });
                }
                Ok(Individual::new(c, e))
            })
            .collect()
    }
}

/// Elitist survival (Deb et al. 2002, section III-C): the `n` best of `merged` by front, the last
/// front admitted cut by crowding distance (largest first, ties in population order), each
/// survivor carrying the rank and crowding distance of this sort. Survivors keep their order.
fn survivors(merged: Vec<Individual>, n: usize) -> Vec<Individual> {
    let mut keep = vec![false; merged.len()];
    let mut rank_crowding = vec![(0usize, 0.0f64); merged.len()];
    let mut kept = 0;
    for (rank, front) in non_dominated_fronts(&merged).into_iter().enumerate() {
        if kept >= n {
            break;
        }
        let distance = crowding_distances(&merged, &front);
        for (k, &i) in front.iter().enumerate() {
            rank_crowding[i] = (rank, distance[k]);
        }
        let mut order: Vec<usize> = (0..front.len()).collect();
        if kept + front.len() > n {
            order.sort_by(|&x, &y| distance[y].total_cmp(&distance[x]));
            order.truncate(n - kept);
        }
        for k in order {
            keep[front[k]] = true;
        }
        kept = kept.saturating_add(front.len()).min(n);
    }
    merged
        .into_iter()
        .zip(keep)
        .zip(rank_crowding)
        .filter(|((_, keep), _)| *keep)
        .map(|((mut s, _), (rank, crowding))| {
            s.rank = rank;
            s.crowding = crowding;
            s
        })
        .collect()
}

/// Whether `a` constraint-dominates `b` (Deb 2000): feasible beats infeasible, the smaller total
/// violation beats the larger, and between feasible members Pareto domination decides.
pub fn dominates(a: &Individual, b: &Individual) -> bool {
    constrained_domination(a, b) == Ordering::Less
}

#[cfg(test)]
mod tests;
