//! Tests of the run loop's pieces that the public API does not show: survival and settings.

use super::*;

fn member(objectives: &[f64], violation: f64) -> Individual {
    Individual {
        variables: vec![objectives[0]],
        objectives: objectives.to_vec(),
        constraint_violations: vec![violation],
        total_violation: violation,
        rank: 99,
        crowding: -1.0,
        genome: Vec::new(),
    }
}

#[test]
fn survival_keeps_whole_fronts_then_the_least_crowded_of_the_last() {
    // Front 0: (0,4) (1,3) (2,2) (3,1) (4,0) with (1,3) and (2,2) and (3,1) interior.
    // Front 1: (1,4) (4,1) and (2.5, 2.5). Infeasible: one.
    let merged = vec![
        member(&[2.0, 2.0], 0.0),
        member(&[1.0, 4.0], 0.0),
        member(&[9.0, 9.0], 1.0),
        member(&[0.0, 4.0], 0.0),
        member(&[2.5, 2.5], 0.0),
        member(&[4.0, 0.0], 0.0),
        member(&[1.0, 3.0], 0.0),
        member(&[4.0, 1.0], 0.0),
        member(&[3.0, 1.0], 0.0),
    ];
    // n = 7: the five of front 0, then two of front 1's three: its extremes (1,4) and (4,1) have
    // infinite crowding distance, (2.5, 2.5) a finite one.
    let kept = survivors(merged, 7);
    let points: Vec<(Vec<f64>, usize)> = kept
        .iter()
        .map(|s| (s.objectives.clone(), s.rank))
        .collect();
    assert_eq!(
        points,
        vec![
            (vec![2.0, 2.0], 0),
            (vec![1.0, 4.0], 1),
            (vec![0.0, 4.0], 0),
            (vec![4.0, 0.0], 0),
            (vec![1.0, 3.0], 0),
            (vec![4.0, 1.0], 1),
            (vec![3.0, 1.0], 0),
        ]
    );
    // Crowding in front 0, ranges 4 and 4: (1,3): (2-0)/4 + (4-2)/4 = 1; (2,2): 2/4 + 2/4 = 1.
    assert_eq!(kept[0].crowding, 1.0);
    assert_eq!(kept[4].crowding, 1.0);
    assert_eq!(kept[2].crowding, f64::INFINITY);
}

#[test]
fn survival_of_a_population_no_larger_than_n_keeps_everyone_ranked() {
    let merged = vec![
        member(&[1.0, 1.0], 0.0),
        member(&[2.0, 2.0], 0.0),
        member(&[0.0, 0.0], 3.0),
    ];
    let kept = survivors(merged, 3);
    assert_eq!(
        kept.iter().map(|s| s.rank).collect::<Vec<_>>(),
        vec![0, 1, 2]
    );
}

#[test]
fn invalid_evaluations_rank_as_infinitely_violated() {
    let c = || Candidate {
        variables: vec![0.5],
        genome: Vec::new(),
    };
    let nan = Individual::new(c(), Evaluation::unconstrained(vec![f64::NAN, 1.0]));
    assert_eq!(nan.total_violation, f64::INFINITY);
    assert!(!nan.is_valid() && !nan.is_feasible());
    let nan_violation = Individual::new(c(), Evaluation::new(vec![1.0], vec![f64::NAN]));
    assert_eq!(nan_violation.total_violation, f64::INFINITY);
    let ok = Individual::new(c(), Evaluation::new(vec![1.0], vec![-2.0, 0.5, 0.25]));
    assert!(ok.is_valid());
    assert_eq!(ok.total_violation, 0.75, "only positive violations count");
}

struct Flat;

const UNIT: [Bounds; 1] = [Bounds::new(0.0, 1.0)];

impl Problem for Flat {
    fn bounds(&self) -> &[Bounds] {
        &UNIT
    }
    fn num_objectives(&self) -> usize {
        1
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::unconstrained(vec![x[0]])
    }
}

#[test]
fn settings_out_of_range_are_refused_by_name() {
    let bad = [
        (
            Nsga2 {
                population: 1,
                ..Nsga2::default()
            },
            "population",
        ),
        (
            Nsga2 {
                generations: 0,
                ..Nsga2::default()
            },
            "generations",
        ),
        (
            Nsga2 {
                crossover_probability: 1.5,
                ..Nsga2::default()
            },
            "crossover_probability",
        ),
        (
            Nsga2 {
                mutation_probability: Some(f64::NAN),
                ..Nsga2::default()
            },
            "mutation_probability",
        ),
        (
            Nsga2 {
                encoding: Encoding::Real {
                    crossover_index: -1.0,
                    mutation_index: 20.0,
                },
                ..Nsga2::default()
            },
            "crossover_index",
        ),
        (
            Nsga2 {
                encoding: Encoding::Binary {
                    bits: 53,
                    crossover: BinaryCrossover::SinglePoint,
                },
                ..Nsga2::default()
            },
            "bits",
        ),
    ];
    for (settings, field) in bad {
        match settings.run(&Flat) {
            Err(Nsga2Error::Setting { name, .. }) => assert_eq!(name, field),
            other => panic!("{field}: {other:?}"),
        }
    }
}
