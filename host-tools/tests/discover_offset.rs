//! Zero offsets, which no effect of the library models: the diagnosis must
//! name a force offset instead of taking it for asymmetry, name a record that
//! starts away from zero displacement, and stay silent on records with
//! nothing hidden and on real asymmetry.
//!
//! Records: the synthetic base of `hyst::discover::synthetic` (strength about
//! 19 kN, Zu = 1 mm) along its step-wise and irregular paths with high noise
//! (1.5% of the peak force and of Zu), with a constant added to the measured
//! force or to the measured displacement, or with asymmetry hidden.

#[path = "support/cli.rs"]
mod cli;

use cli::{hyst, ok, write_record};
use hyst::discover::displacement_drift;
use hyst::discover::offset::{self, OffsetCheck};
use hyst::discover::synthetic::{record, Noise, Path};
use hyst::discover::{discover, weigh, Diagnosis, WeighOptions};
use hyst::fit::experiment::Experiment;
use hyst::fit::input_noise::monotone;
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec};
use hysteresis::bwbn::EffectKind;

const PATHS: [(Path, &str); 2] = [
    (Path::StepWise, "step-wise"),
    (Path::Irregular(7), "irregular"),
];

/// What [`diagnose`] finds.
struct Found {
    nrmse: f64,
    force: OffsetCheck,
    start: Option<OffsetCheck>,
    /// Asymmetry named among the suspects.
    asymmetry: bool,
    drift: OffsetCheck,
    /// Weighed where a line in the force explains enough of the residual.
    displaced: Option<OffsetCheck>,
}

/// A check that ran and named what it looks for.
fn named(check: &Option<OffsetCheck>) -> bool {
    check.as_ref().is_some_and(|c| c.significant)
}

/// Fits `bw`, weighs the candidates and runs the checks on the one step, as
/// `hyst diagnose` does.
fn diagnose(exp: Experiment) -> Found {
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    let suspects = weigh(&problem, &outcome, &d, &WeighOptions::default());
    let asymmetry = suspects
        .iter()
        .any(|s| s.significant && s.effect.name() == "asymmetry");
    let found = offset::of_fit(&problem, &outcome, &d, &suspects);
    Found {
        nrmse: outcome.scores.nrmse,
        force: found.force.expect("a residual to weigh"),
        start: found.start,
        asymmetry,
        drift: found.drift.expect("a residual to weigh"),
        displaced: found.displacement_drift,
    }
}

/// The checks on the one step of [`diagnose`] with strength degradation the only candidate, so
/// that asymmetry, which holds a constant or a line in the force against itself, is not weighed.
fn without_asymmetry_weighed(exp: Experiment) -> offset::Offsets {
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    let options = WeighOptions {
        candidates: Some(vec![EffectRef::Builtin(EffectKind::StrengthDegradation)]),
        ..WeighOptions::default()
    };
    let suspects = weigh(&problem, &outcome, &d, &options);
    offset::of_fit(&problem, &outcome, &d, &suspects)
}

fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// The `--subtract` option an offset's evidence gives, as `CHANNEL=VALUE`.
fn subtract_option(evidence: &str) -> &str {
    evidence
        .split_once("`--subtract ")
        .and_then(|(_, rest)| rest.split_once('`'))
        .map(|(option, _)| option)
        .unwrap_or_else(|| panic!("no option in: {evidence}"))
}

/// `clean` with a line added to its force, from `first` at the first sample to `last` at the
/// last (fractions of its peak force): a load cell whose zero drifts.
fn drifted(clean: &Experiment, first: f64, last: f64) -> Experiment {
    let p = peak(&clean.output);
    let n = clean.output.len();
    let mut exp = clean.clone();
    exp.output.iter_mut().enumerate().for_each(|(k, f)| {
        *f += p * (first + (last - first) * k as f64 / (n - 1) as f64);
    });
    exp
}

#[test]
fn a_force_offset_is_named_instead_of_the_asymmetry_the_ladder_adds() {
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(clean.clone()).nrmse;
        let f0 = 0.03 * peak(&clean.output);
        let mut exp = clean;
        exp.output.iter_mut().for_each(|f| *f += f0);
        let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
        let outcome =
            run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
        let found = discover(problem, outcome, &WeighOptions::default(), |_| {}).unwrap();
        let offset::Offsets { force, start, .. } = offset::of_ladder(&found);
        let force = force.unwrap();
        assert!(force.significant, "{name}: {}", force.evidence);
        // The ladder takes the offset for asymmetry...
        let asymmetry = force
            .asymmetry_nrmse
            .expect("asymmetry weighed as significant");
        // ...which the one constant beats, down to what the noise leaves.
        assert!(force.nrmse_with < asymmetry, "{name}: {}", force.evidence);
        assert!(
            force.nrmse_with < 1.05 * control,
            "{name}: {} against {control} without the offset",
            force.nrmse_with
        );
        // The constant is found from the residual of the symmetric fit,
        // which leans towards the offset a little (measured: 1% and 13%
        // low): within 20%.
        assert!(
            (force.value - f0).abs() < 0.2 * f0,
            "{name}: found {} for {f0}",
            force.value
        );
        assert!(
            force.evidence.contains("--subtract force="),
            "{}",
            force.evidence
        );
        assert!(start.is_none(), "{name}: {start:?}");
    }
}

#[test]
fn hidden_asymmetry_is_not_taken_for_an_offset() {
    for (path, name) in PATHS {
        let exp = record(&[EffectKind::Asymmetry], path, Noise::HIGH, 1).unwrap();
        let Found {
            force,
            start,
            asymmetry,
            drift,
            displaced,
            ..
        } = diagnose(exp);
        assert!(asymmetry, "{name}: asymmetry not named");
        assert!(!named(&displaced), "{name}: {displaced:?}");
        assert!(!drift.significant, "{name}: {}", drift.evidence);
        assert!(!force.significant, "{name}: {}", force.evidence);
        assert!(
            force.nrmse_with > 2.0 * force.asymmetry_nrmse.unwrap(),
            "{name}: {}",
            force.evidence
        );
        assert!(start.is_none(), "{name}: {start:?}");
    }
}

/// Hidden asymmetry on a record starting 0.5 mm off: the start is named, and its refit leaves
/// the force as measured, since asymmetry refitted from rest explains what a constant or a line
/// in the force would take (found by review: with a constant taken off beside the start, the
/// next run was left a weaker asymmetry, and a start whose refit alone fits worse was named on
/// the strength of the constant). With asymmetry left out of the candidates the constant is not
/// kept either: at rest the refit reads less than half of it (found by review: a constant of
/// 13-14% of the peak force was kept, and the start named beside it).
#[test]
fn hidden_asymmetry_beside_a_start_is_not_taken_for_the_load_cells_zero() {
    for (path, name) in PATHS {
        let mut exp = record(&[EffectKind::Asymmetry], path, Noise::HIGH, 1).unwrap();
        exp.input.iter_mut().for_each(|u| *u += 0.5);
        let unweighed = without_asymmetry_weighed(exp.clone())
            .start
            .expect("the record starts 0.5 mm off");
        println!("{name}, asymmetry not weighed: {}", unweighed.evidence);
        assert!(
            unweighed.with_force.is_none() && unweighed.force_line.is_none(),
            "{name}: {}",
            unweighed.evidence
        );
        assert!(
            unweighed.evidence.contains("kN beside it is not taken off")
                && unweighed.evidence.contains(": at rest, over the first"),
            "{name}: {}",
            unweighed.evidence
        );
        // The start alone fits worse, so nothing is named for it.
        assert!(unweighed.share < 0.0, "{name}: {}", unweighed.evidence);
        assert!(!unweighed.significant, "{name}: {}", unweighed.evidence);

        let Found {
            start,
            asymmetry,
            drift,
            displaced,
            force,
            ..
        } = diagnose(exp);
        let start = start.expect("the record starts 0.5 mm off");
        println!("{name}: {}", start.evidence);
        assert!(asymmetry, "{name}: asymmetry not named");
        assert!(start.significant, "{name}: {}", start.evidence);
        assert!(
            start.with_force.is_none() && start.force_line.is_none(),
            "{name}: {}",
            start.evidence
        );
        assert!(
            start.evidence.contains("Beside asymmetry, the start takes"),
            "{name}: {}",
            start.evidence
        );
        let option = subtract_option(&start.evidence);
        assert!(
            option.starts_with("displacement=") && !option.contains("force"),
            "{name}: {option}"
        );
        assert!(!drift.significant, "{name}: {}", drift.evidence);
        assert!(!force.significant, "{name}: {}", force.evidence);
        assert!(!named(&displaced), "{name}: {displaced:?}");
    }
}

#[test]
fn records_with_nothing_hidden_name_no_offset() {
    for (path, name) in PATHS {
        for seed in [1, 2] {
            let exp = record(&[], path, Noise::HIGH, seed).unwrap();
            let Found {
                force,
                start,
                drift,
                displaced,
                ..
            } = diagnose(exp);
            assert!(!drift.significant, "{name} {seed}: {}", drift.evidence);
            assert!(!named(&displaced), "{name} {seed}: {displaced:?}");
            assert!(
                force.share < offset::MIN_SHARE,
                "{name} {seed}: {}",
                force.evidence
            );
            assert!(!force.significant, "{name} {seed}: {}", force.evidence);
            // The first displacement is noise, 0.015 mm against a peak of 6-8 mm: left out.
            assert!(start.is_none(), "{name} {seed}: {start:?}");
        }
    }
}

#[test]
fn a_record_that_starts_away_from_zero_is_named_and_subtracting_it_restores_the_fit() {
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(clean.clone()).nrmse;
        // Half the yield displacement.
        let mut exp = clean;
        exp.input.iter_mut().for_each(|u| *u += 0.5);
        let Found {
            nrmse,
            start,
            displaced,
            ..
        } = diagnose(exp.clone());
        let start = start.unwrap();
        assert!(start.significant, "{name}: {}", start.evidence);
        // A named start opens the displacement drift's check; its line, from the start, takes
        // up the noise of the first sample and is not named for it.
        assert!(!named(&displaced), "{name}: {displaced:?}");
        assert!(nrmse > 2.0 * control, "{name}: {nrmse} against {control}");
        // Noise of 0.015 mm on the first sample.
        assert!((start.value - 0.5).abs() < 0.06, "{name}: {}", start.value);
        assert!(start.evidence.contains("--subtract displacement="));
        // The check's own refit from rest at the first sample, and what
        // `--subtract` does, give the fit without the offset.
        assert!(
            (start.nrmse_with - control).abs() < 0.02 * control,
            "{name}: {} against {control}",
            start.nrmse_with
        );
        let u0 = exp.input[0];
        exp.input.iter_mut().for_each(|u| *u -= u0);
        let refit = diagnose(exp).nrmse;
        assert!(
            (refit - control).abs() < 0.02 * control,
            "{name}: {refit} against {control}"
        );
    }
}

/// A force offset and a start away from rest together: the model's first jump takes up the
/// constant (a model near its elastic limit turns the jump into a constant z), so the force
/// check alone sees nothing; the start's refit weighs a constant force with it and finds both.
#[test]
fn a_force_offset_hidden_behind_a_start_away_from_rest_is_found_with_it() {
    let clean = record(&[], Path::StepWise, Noise::HIGH, 1).unwrap();
    let f0 = 0.03 * peak(&clean.output);
    let mut exp = clean;
    exp.output.iter_mut().for_each(|f| *f += f0);
    exp.input.iter_mut().for_each(|u| *u += 0.5);
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let found = discover(problem, outcome, &WeighOptions::default(), |_| {}).unwrap();
    let offset::Offsets { force, start, .. } = offset::of_ladder(&found);
    let start = start.unwrap();
    assert!(start.significant, "{}", start.evidence);
    assert!((start.value - 0.5).abs() < 0.06, "{}", start.value);
    let with = start
        .with_force
        .expect("a constant force weighed with the start");
    assert!(
        (with - f0).abs() < 0.2 * f0,
        "{with} for {f0}: {}",
        start.evidence
    );
    assert!(
        start.evidence.contains("--subtract displacement=")
            && start.evidence.contains(" --subtract force="),
        "{}",
        start.evidence
    );
    assert!(!force.unwrap().significant);
}

/// Kunnath's A7 (SPD 351) reads zero force at rest, and its loops are lopsided: a constant
/// fits them as well as asymmetry does (NRMSE 0.263 against 0.267), but an instrument's zero
/// would show from the first sample, where the record reads 0.9 kN of the constant's 6.1.
#[test]
fn a_real_record_that_reads_zero_at_rest_is_not_given_an_offset() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/peer-spd-columns/fd/spd_351.csv"
    );
    let record = hyst::data::read(path, &hyst::data::ReadOptions::default()).unwrap();
    let exp = Experiment::from_record(&record, None).unwrap();
    let force = diagnose(exp).force;
    assert!(force.share > offset::MIN_SHARE, "{}", force.evidence);
    assert!(
        force.nrmse_with <= force.asymmetry_nrmse.unwrap(),
        "{}",
        force.evidence
    );
    assert!(!force.significant, "{}", force.evidence);
    assert!(
        force.evidence.contains("lopsided misfit"),
        "{}",
        force.evidence
    );
}

/// The shared record s2 (an independent simulator, degradation hidden) starts at 0.18 mm, 0.18%
/// of its peak, so its start is weighed; with 3% of its peak force taken off every sample the
/// offset is the force's, not the start's (a start refitted with a constant force was named
/// for it, the constant doing the work: found by review).
#[test]
fn a_force_offset_on_a_record_starting_near_zero_is_the_forces() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/synthetic/s2_hidden_degradation.csv"
    );
    let record = hyst::data::read(path, &hyst::data::ReadOptions::default()).unwrap();
    let mut exp = Experiment::from_record(&record, None).unwrap();
    let f0 = -0.03 * peak(&exp.output);
    exp.output.iter_mut().for_each(|f| *f += f0);
    let Found {
        force,
        start,
        drift,
        ..
    } = diagnose(exp);
    // A constant is the force offset's, not a drift's.
    assert!(!drift.significant, "{}", drift.evidence);
    let start = start.expect("a first displacement of 0.18% of the peak is weighed");
    assert!(!start.significant, "{}", start.evidence);
    assert!(force.significant, "{}", force.evidence);
    // Measured -19.1 for -17.5: the mean residual carries the model's own lopsided misfit.
    assert!(
        (force.value - f0).abs() < 0.2 * f0.abs(),
        "{} for {f0}",
        force.value
    );
}

/// A load cell whose zero drifts along the test (found by review: 1% of the peak force over the
/// record was added to `bw` as asymmetry at delta-BIC -485): the line is named, its size found;
/// a hidden strength degradation, whose peaks fall in both directions, is not taken for one.
#[test]
fn a_drifting_force_zero_is_named_and_degradation_is_not_taken_for_one() {
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(clean.clone()).nrmse;
        let total = 0.03 * peak(&clean.output);
        let Found {
            nrmse,
            force,
            drift,
            displaced,
            ..
        } = diagnose(drifted(&clean, 0.0, 0.03));
        // The load cell's line, not the displacement's.
        let displaced = displaced.expect("a line in the force weighs the displacement's");
        assert!(!displaced.significant, "{name}: {}", displaced.evidence);
        println!(
            "{name}: bw {nrmse:.4}, control {control:.4}: {}",
            drift.evidence
        );
        assert!(drift.significant, "{name}: {}", drift.evidence);
        assert!(
            (drift.value - total).abs() < 0.2 * total,
            "{name}: found {} for {total}",
            drift.value
        );
        assert!(
            drift.nrmse_with < 1.1 * control,
            "{name}: {} against {control}",
            drift.nrmse_with
        );
        // The constant alone does not explain it: no force offset named.
        assert!(!force.significant, "{name}: {}", force.evidence);

        let exp = record(&[EffectKind::StrengthDegradation], path, Noise::HIGH, 1).unwrap();
        let Found {
            drift, displaced, ..
        } = diagnose(exp);
        assert!(!drift.significant, "{name}: {}", drift.evidence);
        assert!(!named(&displaced), "{name}: {displaced:?}");

        // Without asymmetry weighed nothing holds a line against real asymmetry (found by
        // review: `--candidates` leaving it out named a drift of 11% of the peak).
        let exp = record(&[EffectKind::Asymmetry], path, Noise::HIGH, 1).unwrap();
        let drift = without_asymmetry_weighed(exp).drift.unwrap();
        println!("{name}, asymmetry not weighed: {}", drift.evidence);
        assert!(!drift.significant, "{name}: {}", drift.evidence);
    }
}

/// A zero 3% of the peak force off at the start that drifts back to zero by the end: the drift
/// is named, and the force offset, which a constant alone would also pass, is not named beside
/// it (found by review: both named, and giving both options took the constant off twice, since
/// offsets for one channel add up). Forces a hundred thousand times smaller (a record in N read
/// as kN) get the same verdict and an option that still holds the line (at 4 decimals it printed
/// `force=0.0000..0.0000`, which took nothing off).
#[test]
fn a_zero_drifting_back_is_named_once_and_small_forces_keep_their_digits() {
    let clean = record(&[], Path::StepWise, Noise::HIGH, 1).unwrap();
    let total = 0.03 * peak(&clean.output);
    let exp = drifted(&clean, 0.03, 0.0);
    let mut small = exp.clone();
    small.output.iter_mut().for_each(|f| *f *= 1e-5);
    for (exp, scale) in [(exp, 1.0), (small, 1e-5)] {
        let Found { force, drift, .. } = diagnose(exp);
        assert!(drift.significant, "{scale}: {}", drift.evidence);
        assert!(!force.significant, "{scale}: {}", force.evidence);
        assert!(
            force
                .evidence
                .contains("the force drift (below) takes off a line"),
            "{scale}: {}",
            force.evidence
        );
        let [first, last] = drift.line.unwrap();
        assert!(
            (first - total * scale).abs() < 0.2 * total * scale && last.abs() < 0.2 * total * scale,
            "{scale}: {first}..{last} for {}..0",
            total * scale
        );
        // The option as printed, read back: its first end within 1e-4 of the line's.
        let option = subtract_option(&drift.evidence);
        let printed: hyst::data::Baseline = option.strip_prefix("force=").unwrap().parse().unwrap();
        assert!(
            (printed.first - first).abs() < 1e-4 * first.abs(),
            "{scale}: `{option}` for {first}..{last}"
        );
    }
}

/// The user's loop on a drifting instrument: `discover` on `exp` (the record `clean` with a
/// drift added) names the drift as `check`, whose evidence gives the option that takes the line
/// off `channel`; run again with that option as printed, the ladder stays at `bw`, nothing is
/// named, and the error is the record's without the drift. The record is written as `file`,
/// which tests running at once must not share.
fn the_option_takes_it_off(
    file: &str,
    clean: &Experiment,
    exp: &Experiment,
    check: &str,
    channel: &str,
) {
    let discover = |path: &str, extra: &[&str]| -> serde_json::Value {
        let args = [&["discover", path, "--model", "bw", "--json"], extra].concat();
        serde_json::from_slice(&ok(hyst(&args)).stdout).unwrap()
    };
    let ladder = |v: &serde_json::Value| -> Vec<String> {
        v["ladder"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["model"].as_str().unwrap().to_string())
            .collect()
    };
    let control = discover(&write_record(&format!("un{file}.csv"), clean), &[]);
    assert_eq!(ladder(&control), ["bw"], "{control}");
    let path = write_record(&format!("{file}.csv"), exp);
    let found = discover(&path, &[]);
    let drift = &found[check];
    assert_eq!(drift["significant"], true, "{drift}");
    let evidence = drift["evidence"].as_str().unwrap();
    let option = subtract_option(evidence);
    assert!(
        option.starts_with(&format!("{channel}=")) && option.contains(".."),
        "{option}"
    );

    // One option a channel, each after its own `--subtract`.
    let options: Vec<&str> = option
        .split(" --subtract ")
        .flat_map(|o| ["--subtract", o])
        .collect();
    let again = discover(&path, &options);
    println!(
        "ladder {:?} -> {:?} with --subtract {option}; NRMSE {} -> {}, clean {}",
        ladder(&found),
        ladder(&again),
        found["nrmse"],
        again["nrmse"],
        control["nrmse"]
    );
    assert_eq!(ladder(&again), ["bw"], "{again}");
    for check in [
        "force_offset",
        "force_drift",
        "displacement_drift",
        "start_offset",
        "channel_lag",
    ] {
        assert_ne!(
            again[check]["significant"], true,
            "{check}: {}",
            again[check]
        );
    }
    let (after, clean) = (
        again["nrmse"].as_f64().unwrap(),
        control["nrmse"].as_f64().unwrap(),
    );
    assert!(
        (after - clean).abs() < 0.02 * clean,
        "{after} against {clean}"
    );
}

/// The loop on a load cell drifting 3% of the peak force over the test: named beside the
/// asymmetry the ladder adds, taken off by its option.
#[test]
fn the_option_a_named_drift_gives_takes_it_off() {
    let clean = record(&[], Path::StepWise, Noise::HIGH, 1).unwrap();
    let exp = drifted(&clean, 0.0, 0.03);
    the_option_takes_it_off("force_drift", &clean, &exp, "force_drift", "force");
}

/// The loop on a displacement transducer drifting 0.5 mm over the test: named (the ladder
/// adds asymmetry for it, measured), taken off by its option.
#[test]
fn the_option_a_named_displacement_drift_gives_takes_it_off() {
    let clean = record(&[], Path::StepWise, Noise::HIGH, 1).unwrap();
    let exp = displaced(&clean, 0.0, 0.5);
    the_option_takes_it_off(
        "displacement_drift",
        &clean,
        &exp,
        "displacement_drift",
        "displacement",
    );
}

/// `clean` with a line added to its displacement, from `first` at the first sample to `last` at
/// the last (mm): a displacement transducer whose zero drifts.
fn displaced(clean: &Experiment, first: f64, last: f64) -> Experiment {
    let n = clean.input.len();
    let mut exp = clean.clone();
    exp.input.iter_mut().enumerate().for_each(|(k, u)| {
        *u += first + (last - first) * k as f64 / (n - 1) as f64;
    });
    exp
}

/// `exp` as the loader reads it: a noisy displacement made monotone between the test's reversals
/// (raw, the noise biases an irregular path's line by +0.1..+0.28 mm).
fn loaded(mut exp: Experiment) -> Experiment {
    if let Some((u, _)) = monotone(&exp.input) {
        exp.input = u;
    }
    exp
}

/// A displacement transducer whose zero drifts 0.5 mm over the test (half the base's yield
/// displacement, 6-8% of the peak) leaves a residual a line in the force follows too (found by
/// review: named a load cell's drift, whose option left part of it). The line in the
/// displacement is named, its size found, the fit back at the record's without it; the force
/// drift is not named beside it, nor the start away from rest that the noise on the first
/// sample gives the irregular path (0.016 mm; refitted with a constant force it took up part of
/// the drift and was named for it).
///
/// The displacement is made monotone between the test's reversals, as the loader does with a
/// noisy displacement: raw, the noise (1.5% of the yield displacement) biases the irregular
/// path's line by 0.1-0.28 mm (seeds 1-3, measured; the step-wise path's by up to 0.035).
#[test]
fn a_drifting_displacement_zero_is_named_as_the_transducers_not_the_load_cells() {
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(loaded(clean.clone())).nrmse;
        let Found {
            nrmse,
            force,
            drift,
            displaced,
            start,
            ..
        } = diagnose(loaded(displaced(&clean, 0.0, 0.5)));
        let displaced = displaced.expect("a line in the force weighs the displacement's");
        println!(
            "{name}: bw {nrmse:.4}, control {control:.4}: {}",
            displaced.evidence
        );
        assert!(displaced.significant, "{name}: {}", displaced.evidence);
        let [first, last] = displaced.line.unwrap();
        // Within a fifth of the line's size at both ends.
        assert!(
            first.abs() < 0.1 && (last - 0.5).abs() < 0.1,
            "{name}: {first}..{last} for 0..0.5"
        );
        assert!(
            displaced.nrmse_with < 1.05 * control,
            "{name}: {} against {control}",
            displaced.nrmse_with
        );
        assert!(
            subtract_option(&displaced.evidence).starts_with("displacement="),
            "{name}: {}",
            displaced.evidence
        );
        // Nothing else is off, and the estimate takes nothing off the force.
        assert_eq!(
            (displaced.with_force, displaced.force_line),
            (None, None),
            "{name}: {}",
            displaced.evidence
        );
        assert!(!drift.significant, "{name}: {}", drift.evidence);
        assert!(
            drift.evidence.contains("a line in the displacement"),
            "{name}: {}",
            drift.evidence
        );
        assert!(!force.significant, "{name}: {}", force.evidence);
        assert!(!named(&start), "{name}: {start:?}");
    }
}

/// A line that runs beyond a quarter of the peak displacement is not a drift whatever its BIC:
/// on PEER SPD 302 (`bw`) the estimate runs to 17.3 mm, 48% of the peak (found by review: such
/// lines were printed as drifts' sizes, up to 113% of the peak), and says it means nothing.
#[test]
fn a_line_running_beyond_a_quarter_of_the_peak_is_not_taken_for_a_drift() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/peer-spd-columns/fd/spd_302.csv"
    );
    let record = hyst::data::read(path, &hyst::data::ReadOptions::default()).unwrap();
    let exp = Experiment::from_record(&record, None).unwrap();
    let peak_u = peak(&exp.input);
    let displaced = diagnose(exp)
        .displaced
        .expect("a line in the force weighs the displacement's");
    let [first, last] = displaced.line.unwrap();
    let reach = first.abs().max(last.abs()) / peak_u;
    println!("{reach:.3}: {}", displaced.evidence);
    assert!(reach > displacement_drift::RUNS_OFF, "{reach}");
    assert!(!displaced.significant, "{}", displaced.evidence);
    assert!(
        displaced.evidence.contains("stands in for another misfit"),
        "{}",
        displaced.evidence
    );
}

/// A displacement drift of 0.5 mm beside a load cell's offset of 3% of the peak force, or beside
/// its drift of -2% over the test: named as a displacement drift whose line is estimated together
/// with what the force needs beside it, and the two together fit as well as the clean record
/// (each line estimated alone, a force offset beside the drift was named a force drift, and the
/// displacement's line came out with the wrong sign: found by review). The split between the
/// two is not sharp, since a line in the displacement and one in the force leave alike
/// residuals over part of a test (seeds 1-3: the displacement's line ended at 0.31-0.64 mm, and
/// beside the irregular path's drift of seed 1 a constant force of a third of the drift's end
/// was chosen), so the displacement's line is held to a factor of two and the force's part to
/// its sign at the last sample.
#[test]
fn a_displacement_drift_beside_a_load_cells_offset_or_drift_is_estimated_with_it() {
    let within_two = |estimate: f64, truth: f64| (0.5..=2.0).contains(&(estimate / truth));
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(loaded(clean.clone())).nrmse;
        let p = peak(&clean.output);
        for (first, last, kind) in [(0.03, 0.03, "offset"), (0.0, -0.02, "drift")] {
            let Found {
                nrmse,
                force,
                drift,
                displaced,
                start,
                ..
            } = diagnose(loaded(displaced(&drifted(&clean, first, last), 0.0, 0.5)));
            let dd = displaced.expect("a line in the force weighs the displacement's");
            println!(
                "{name}, force {kind}: bw {nrmse:.4}, control {control:.4}: {}",
                dd.evidence
            );
            assert!(dd.significant, "{name}, {kind}: {}", dd.evidence);
            let [a, b] = dd.line.unwrap();
            assert!(
                a.abs() < 0.1 && within_two(b, 0.5),
                "{name}, {kind}: {a}..{b} for 0..0.5"
            );
            let at_last = match (dd.with_force, dd.force_line) {
                (Some(c), None) => c,
                (None, Some([_, l])) => l,
                other => panic!("{name}, {kind}: {other:?}: {}", dd.evidence),
            };
            assert!(
                at_last * last > 0.0,
                "{name}, {kind}: force {at_last} at the last sample for {}",
                p * last
            );
            assert!(
                dd.nrmse_with < 1.05 * control,
                "{name}, {kind}: {} against {control}",
                dd.nrmse_with
            );
            let option = subtract_option(&dd.evidence);
            assert!(
                option.starts_with("displacement=") && option.contains(" --subtract force="),
                "{name}, {kind}: {option}"
            );
            for check in [&force, &drift] {
                assert!(!check.significant, "{name}, {kind}: {}", check.evidence);
            }
            assert!(!named(&start), "{name}, {kind}: {start:?}");
        }
    }
}

/// A displacement zero that drifts from 0.5 mm back to 0 over the test, alone and beside a load
/// cell's offset of 3% of the peak: the start dominates the residual, so a line in the force
/// explains too little to open the displacement drift's check, which the named start now opens
/// (found by review: a drift from 1.5 mm back to 0 beside a force drift was named a start, and
/// the line was not weighed). Estimated from the start, the line is named, holds the start at
/// its first end, and the start yields to it. On the irregular path; on the step-wise path the
/// drift beside the offset is told from a start with a constant force by less than the slope
/// must add, and the start is named (README).
#[test]
fn a_drift_from_a_start_away_from_rest_is_weighed_against_the_start() {
    let clean = record(&[], Path::Irregular(7), Noise::HIGH, 1).unwrap();
    let control = diagnose(loaded(clean.clone())).nrmse;
    for (force, kind) in [(0.0, "alone"), (0.03, "beside a force offset")] {
        let exp = displaced(&drifted(&clean, force, force), 0.5, 0.0);
        let Found {
            nrmse,
            displaced,
            start,
            drift,
            ..
        } = diagnose(loaded(exp));
        let dd = displaced.expect("a named start opens the check");
        println!(
            "{kind}: bw {nrmse:.4}, control {control:.4}: {}",
            dd.evidence
        );
        assert!(dd.significant, "{kind}: {}", dd.evidence);
        let [a, b] = dd.line.unwrap();
        assert!(
            (a - 0.5).abs() < 0.1 && b.abs() < 0.1,
            "{kind}: {a}..{b} for 0.5..0"
        );
        assert_eq!(
            dd.with_force.is_some(),
            force > 0.0,
            "{kind}: {}",
            dd.evidence
        );
        assert!(
            dd.nrmse_with < 1.05 * control,
            "{kind}: {} against {control}",
            dd.nrmse_with
        );
        let start = start.expect("the record starts 0.5 mm off");
        assert!(!start.significant, "{kind}: {}", start.evidence);
        assert!(
            start.evidence.contains("its first end holds the start"),
            "{kind}: {}",
            start.evidence
        );
        assert!(!drift.significant, "{kind}: {}", drift.evidence);
    }
}

/// A start 0.5 mm away from rest beside a load cell drifting 2% of the peak force: the force's
/// line opens the displacement drift's check, and the line estimated with a line in the force
/// fitted better than the start's refit when that kept no more than a constant force (a BIC
/// change 250-800 below the start's, measured), though nothing drifts (found by review: such
/// lines of 0.01-0.16 mm were named drifts). Held at one value with the same part of the force,
/// the line's slope adds nothing significant, and the start stays named, now with the load
/// cell's line beside it.
#[test]
fn a_start_beside_a_load_cells_drift_is_not_taken_for_a_displacement_drift() {
    for (path, name) in PATHS {
        let clean = record(&[], path, Noise::HIGH, 1).unwrap();
        let control = diagnose(loaded(clean.clone())).nrmse;
        let Found {
            displaced,
            start,
            drift,
            ..
        } = diagnose(loaded(displaced(&drifted(&clean, 0.0, 0.02), 0.5, 0.5)));
        let start = start.expect("the record starts 0.5 mm off");
        assert!(start.significant, "{name}: {}", start.evidence);
        assert!(!drift.significant, "{name}: {}", drift.evidence);
        // The start's refit keeps the load cell's drift beside it, and its
        // option takes both off (the loop below). The line is fitted to what
        // the refit leaves, not refitted with it: measured 2.2% for 2% on the
        // irregular path, within a fifth; 1.6% on the step-wise path, whose
        // growing amplitude lets the refit's parameters follow part of a
        // drift (asymmetry refitted from rest there reaches 0.0275 against
        // the line's 0.0274), within a quarter.
        let [a, b] = start.force_line.expect("a line in the force");
        let p = peak(&clean.output);
        let within = if path == Path::StepWise { 0.25 } else { 0.2 };
        assert!(
            ((b - a) / p - 0.02).abs() < within * 0.02,
            "{name}: {a}..{b} of {p}"
        );
        assert!(
            (start.nrmse_with - control).abs() < 0.05 * control,
            "{name}: {} against {control}",
            start.nrmse_with
        );
        assert!(subtract_option(&start.evidence).contains("--subtract force="));
        let dd = displaced.expect("a line in the force opens the check");
        println!("{name}: {}", dd.evidence);
        assert!(!dd.significant, "{name}: {}", dd.evidence);
        assert!(
            dd.evidence.contains("held at one value there"),
            "{name}: {}",
            dd.evidence
        );
    }
}

/// The loop on the step-wise record with both: `--subtract` as printed takes both off.
#[test]
fn the_option_a_displacement_drift_beside_a_force_offset_gives_takes_both_off() {
    let clean = record(&[], Path::StepWise, Noise::HIGH, 1).unwrap();
    let exp = displaced(&drifted(&clean, 0.03, 0.03), 0.0, 0.5);
    the_option_takes_it_off(
        "displacement_and_force_offset",
        &clean,
        &exp,
        "displacement_drift",
        "displacement",
    );
}

/// The loop on a record starting 0.5 mm off beside a load cell drifting 2% of the peak force
/// (found by review: the start's option took off a constant force, and the drift was named only
/// on the next run): the start's option as printed takes both off.
#[test]
fn the_option_a_start_beside_a_load_cells_drift_gives_takes_both_off() {
    let clean = record(&[], Path::Irregular(7), Noise::HIGH, 1).unwrap();
    let exp = displaced(&drifted(&clean, 0.0, 0.02), 0.5, 0.5);
    the_option_takes_it_off(
        "start_and_force_drift",
        &clean,
        &exp,
        "start_offset",
        "displacement",
    );
}
