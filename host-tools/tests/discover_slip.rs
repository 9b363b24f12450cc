//! Slip, the other effect the library does not model: the diagnosis must name
//! a plateau of zero force on reversal where the record has one, read its
//! length, and stay silent on records without one, including those whose
//! missing effect is pinching, the library effect slip resembles.
//!
//! Records: the synthetic base of `hyst::discover::synthetic` behind a gap
//! (`record_with_gap`) or with a hidden library effect (`record`), along the
//! step-wise and the earthquake-like paths, at both noise levels; and the
//! shared records of `../shared/data/synthetic/` (an independent simulator).

#[path = "support/cli.rs"]
mod cli;
#[path = "support/shared_records.rs"]
mod shared_records;
use cli::{hyst, ok, write_record};
use hyst::discover::slip::{self, SlipCheck};
use hyst::discover::synthetic::{record, record_with_gap, Noise, Path};
use hyst::discover::{Diagnosis, Discovery, Step};
use hyst::fit::experiment::Experiment;
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec};
use hysteresis::bwbn::EffectKind;
use shared_records::shared;

/// Fits `bw` to `exp` as `hyst diagnose` does and runs the slip check.
fn check(exp: Experiment) -> SlipCheck {
    check_with(ModelSpec::BW, exp)
}

fn check_with(spec: ModelSpec, exp: Experiment) -> SlipCheck {
    let problem = Problem::new(spec, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    slip::check(&d, &problem.exp.drive).expect("half-cycles where the force changes sign")
}

const PATHS: [Path; 2] = [Path::StepWise, Path::Irregular(1)];

#[test]
fn a_gap_is_named_and_its_length_read() {
    for gap in [0.5, 1.0] {
        for (which, noise, seed) in [
            (Path::StepWise, Noise::LOW, 1),
            (Path::StepWise, Noise::HIGH, 2),
            (Path::Irregular(1), Noise::LOW, 3),
            (Path::Irregular(2), Noise::HIGH, 4),
        ] {
            let c = check(record_with_gap(gap, which, noise, seed).unwrap());
            println!("gap {gap} {which:?} {noise:?}: {c:?}");
            assert!(
                c.significant,
                "gap {gap}, {which:?}, {noise:?}: {}",
                c.evidence
            );
            // The plateau is the slider crossing the gap: 2 gap long, less
            // the samples where noise lifts the force out of the band.
            assert!(
                (0.8 * 2.0 * gap..=1.1 * 2.0 * gap).contains(&c.plateau),
                "gap {gap}, {which:?}, {noise:?}: plateau {} against {}",
                c.plateau,
                2.0 * gap
            );
        }
    }
}

#[test]
fn no_gap_no_slip() {
    for which in PATHS {
        for (noise, seed) in [(Noise::LOW, 5), (Noise::HIGH, 6)] {
            let c = check(record_with_gap(0.0, which, noise, seed).unwrap());
            println!("no gap {which:?} {noise:?}: {c:?}");
            assert!(!c.significant, "{which:?}, {noise:?}: {}", c.evidence);
        }
    }
}

#[test]
fn hidden_library_effects_are_not_taken_for_slip() {
    for kind in [
        EffectKind::Pinching,
        EffectKind::StrengthDegradation,
        EffectKind::StiffnessDegradation,
        EffectKind::Asymmetry,
    ] {
        for which in PATHS {
            let c = check(record(&[kind], which, Noise::HIGH, 7).unwrap());
            println!("{kind:?} {which:?}: {c:?}");
            assert!(!c.significant, "{kind:?}, {which:?}: {}", c.evidence);
        }
    }
}

#[test]
fn the_shared_synthetic_records_have_no_slip() {
    for name in ["s1_hidden_pinching.csv", "s2_hidden_degradation.csv"] {
        let c = check(shared(name));
        println!("{name}: {c:?}");
        assert!(!c.significant, "{name}: {}", c.evidence);
    }
    // With the missing effect added, the model's band is the measured one.
    let pinched = ModelSpec::BW.with(EffectRef::Builtin(EffectKind::Pinching));
    let c = check_with(pinched, shared("s1_hidden_pinching.csv"));
    println!("s1 with pinching: {c:?}");
    assert!(!c.significant && c.excess.abs() < 0.01, "{}", c.evidence);
}

#[test]
fn hyst_diagnose_names_the_gap_in_text_and_json() {
    let exp = record_with_gap(0.5, Path::StepWise, Noise::LOW, 8).unwrap();
    let csv = write_record("gap.csv", &exp);
    let args = [
        "diagnose",
        &csv,
        "--model",
        "bw",
        "--candidates",
        "pinching",
    ];
    let text = String::from_utf8(ok(hyst(&args)).stdout).unwrap();
    assert!(
        text.contains("beyond the library's effects:")
            && text
                .lines()
                .any(|l| l.trim() == "slip or gap               SIGNIFICANT"),
        "{text}"
    );
    let json = ok(hyst(&[&args[..], &["--json"]].concat())).stdout;
    let v: serde_json::Value = serde_json::from_slice(&json).unwrap();
    assert_eq!(
        v["slip"]["significant"],
        serde_json::Value::Bool(true),
        "{v}"
    );
    let plateau = v["slip"]["plateau"].as_f64().unwrap();
    assert!((0.8..=1.1).contains(&plateau), "{plateau}");
}

/// Sampled coarsely around zero force (the step-wise path's 60 samples a
/// cycle against a stiffness of 20 kN/mm), the force passes through the
/// band in one or two samples. The evidence says so, instead of a band of
/// 0 mm and a flatness of 0 (found by review).
#[test]
fn a_crossing_between_samples_is_called_too_coarse_to_tell() {
    let clean = Noise {
        displacement: 0.0,
        force: 0.0,
    };
    let c = check(record(&[], Path::StepWise, clean, 9).unwrap());
    println!("{c:?}");
    assert!(!c.significant);
    assert!(
        c.evidence
            .contains("half-cycles the measured force passes from -10% to +10% of its peak in fewer than three samples"),
        "{}",
        c.evidence
    );
    // A gap is resolved and measured as before.
    let c = check(record_with_gap(0.5, Path::StepWise, clean, 9).unwrap());
    assert!(
        c.significant && c.evidence.contains("flatness"),
        "{}",
        c.evidence
    );
}

/// A ladder that added effects which take the plateau's error (pinching narrows the loop around
/// zero force) no longer shows the gap on its final model; the first model's finding stands
/// then, naming the effects that stand in for the gap. On the fastener record c54o6 of
/// `cfs-fastener-peterman2014` (4 minutes, so not here) `hyst diagnose` found slip on `bw` and
/// `hyst discover`, which checked only its final model with four effects, reported none.
#[test]
fn a_gap_found_on_the_first_model_stands_when_the_ladder_papers_over_it() {
    let exp = record_with_gap(1.0, Path::StepWise, Noise::LOW, 10).unwrap();
    let step = |spec: ModelSpec| {
        let problem = Problem::new(spec, exp.clone(), &[]).unwrap();
        let outcome =
            run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
        Step::diagnosed(problem, outcome).unwrap()
    };
    let pinched = ModelSpec::BW.with(EffectRef::Builtin(EffectKind::Pinching));
    let ladder = Discovery {
        rungs: vec![],
        steps: vec![step(ModelSpec::BW), step(pinched)],
        unneeded: vec![],
    };
    let last = ladder.last();
    let on_last = slip::check(&last.diagnosis, &last.problem.exp.drive);
    println!("on bw+pinching: {on_last:?}");
    let on_last = on_last.unwrap();
    let kept = slip::of_ladder(&ladder, Some(on_last.clone())).unwrap();
    assert!(kept.significant, "{}", kept.evidence);
    // Pinching takes the plateau down to 1.46 of the measured 1.87 mm, an excess of 6.7% of
    // the half-cycle against the 7% the check needs (measured while this was built).
    assert!(!on_last.significant, "{}", on_last.evidence);
    assert!(
        kept.evidence.starts_with("On the first model, bw: In ")
            && kept.evidence.ends_with(
                "The effects added since (pinching) narrow the loop around zero force and take the plateau's error, so on the final model the check no longer shows it, but none of them holds the force at zero over a band: they stand in for the gap."
            ),
        "{}",
        kept.evidence
    );
    // A final model that still shows it keeps its own check.
    let first = slip::check(&ladder.steps[0].diagnosis, &exp.drive).unwrap();
    assert_eq!(slip::of_ladder(&ladder, Some(first.clone())), Some(first));
    // A ladder of one model keeps its check.
    let one = Discovery {
        rungs: vec![],
        steps: vec![step(ModelSpec::BW)],
        unneeded: vec![],
    };
    assert_eq!(slip::of_ladder(&one, None), None);
}
