//! The discovery loop on records with hidden effects (issue 4, point 7):
//! records made by the project's own simulator with each effect alone and in
//! pairs, at two noise levels, along step-wise and irregular paths, and
//! control records with nothing hidden. The tool must name a hidden effect as
//! its top significant suspect, name nothing on the controls, and the error
//! must fall at least 3x once the named effects are added. The two records of
//! `../shared/data/synthetic/` (made by an independent simulator) must pass
//! too.

#[path = "support/shared_records.rs"]
mod shared_records;
use hyst::discover::synthetic::{record, record_with, Noise, Path};
use hyst::discover::{discover, weigh, Diagnosis, Discovery, WeighOptions};
use hyst::fit::experiment::Experiment;
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec};
use hysteresis::bwbn::EffectKind;
use shared_records::shared;

fn fit_bw(exp: Experiment) -> (Problem, hyst::fit::run::Outcome) {
    let problem = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let outcome = run::fit(&problem, Method::Auto, &problem.par.default_start(), &Quiet).unwrap();
    (problem, outcome)
}

/// Fits `bw`, runs the discovery loop from it and returns the first NRMSE,
/// the loop's result and its ladder as text ("model nrmse -> ...").
fn ladder_of(exp: Experiment) -> (f64, Discovery, String) {
    let (problem, outcome) = fit_bw(exp);
    let first = outcome.scores.nrmse;
    let found = discover(problem, outcome, &WeighOptions::default(), |_| {}).unwrap();
    let ladder: Vec<String> = found
        .rungs
        .iter()
        .map(|r| format!("{} {:.4}", r.model, r.nrmse))
        .collect();
    (first, found, ladder.join(" -> "))
}

/// The top significant suspect, if any, and the NRMSE with it.
fn top_suspect(exp: Experiment) -> (Option<(EffectKind, f64)>, f64, String) {
    let (problem, outcome) = fit_bw(exp);
    let d = Diagnosis::new(&problem, &outcome).unwrap();
    let suspects = weigh(&problem, &outcome, &d, &WeighOptions::default());
    let report: Vec<String> = suspects
        .iter()
        .map(|s| {
            format!(
                "{} {} {:.4} {:.0}",
                s.effect.name(),
                s.significant,
                s.nrmse_with,
                s.delta_bic
            )
        })
        .collect();
    let top = suspects.iter().find(|s| s.significant).map(|s| {
        let EffectRef::Builtin(k) = s.effect else {
            panic!("no custom effects registered here")
        };
        (k, s.nrmse_with)
    });
    (top, outcome.scores.nrmse, report.join("; "))
}

const SINGLES: [EffectKind; 4] = [
    EffectKind::Pinching,
    EffectKind::StrengthDegradation,
    EffectKind::StiffnessDegradation,
    EffectKind::Asymmetry,
];

fn conditions() -> Vec<(Path, Noise, &'static str)> {
    vec![
        (Path::StepWise, Noise::LOW, "step-wise, low noise"),
        (Path::StepWise, Noise::HIGH, "step-wise, high noise"),
        (Path::Irregular(7), Noise::LOW, "irregular, low noise"),
        (Path::Irregular(7), Noise::HIGH, "irregular, high noise"),
    ]
}

#[test]
fn each_hidden_effect_is_named_and_adding_it_cuts_the_error_threefold() {
    let mut failures = vec![];
    for kind in SINGLES {
        for (i, (path, noise, what)) in conditions().into_iter().enumerate() {
            let exp = record(&[kind], path, noise, 100 + i as u64).unwrap();
            let (top, nrmse, report) = top_suspect(exp);
            eprintln!("{} / {what}: bw {nrmse:.4}; {report}", kind.name());
            match top {
                Some((k, with)) if k == kind && nrmse / with >= 3.0 => {}
                other => failures.push(format!(
                    "{} / {what}: top {other:?}, bw {nrmse:.4}; {report}",
                    kind.name()
                )),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn control_records_get_no_significant_suspect() {
    let mut failures = vec![];
    for (i, (path, noise, what)) in conditions().into_iter().enumerate() {
        let exp = record(&[], path, noise, 200 + i as u64).unwrap();
        let (top, nrmse, report) = top_suspect(exp);
        eprintln!("control / {what}: bw {nrmse:.4}; {report}");
        if let Some(t) = top {
            failures.push(format!("control / {what}: invented {t:?}; {report}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn pairs_of_hidden_effects_are_found_by_the_loop() {
    let mut failures = vec![];
    for (a, i) in SINGLES.iter().zip(0..) {
        for b in &SINGLES[i + 1..] {
            let exp = record(&[*a, *b], Path::StepWise, Noise::LOW, 300 + i as u64).unwrap();
            let (first, found, ladder) = ladder_of(exp);
            eprintln!("{} + {}: {ladder}", a.name(), b.name());
            let last = found.last();
            let spec = last.spec;
            let named_first = found.steps.get(1).map(|s| s.spec);
            let first_ok =
                named_first.is_some_and(|s| s.effects.contains(*a) || s.effects.contains(*b));
            if !(first_ok && first / last.outcome.scores.nrmse >= 3.0) {
                failures.push(format!(
                    "{} + {}: {ladder} (final {spec})",
                    a.name(),
                    b.name()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_shared_synthetic_records_pass() {
    // s1 hides pinching.
    let (top, nrmse, report) = top_suspect(shared("s1_hidden_pinching.csv"));
    let (k, with) = top.unwrap_or_else(|| panic!("s1: nothing named; {report}"));
    assert_eq!(k, EffectKind::Pinching, "s1: {report}");
    assert!(nrmse / with >= 3.0, "s1: {nrmse} -> {with}");
    // s2 hides strength and stiffness degradation: the loop adds both.
    let (first, found, ladder) = ladder_of(shared("s2_hidden_degradation.csv"));
    let effects = found.last().spec.effects;
    assert!(
        effects.contains(EffectKind::StrengthDegradation),
        "s2: {ladder}"
    );
    assert!(
        effects.contains(EffectKind::StiffnessDegradation),
        "s2: {ladder}"
    );
    assert!(!effects.contains(EffectKind::Pinching), "s2: {ladder}");
    assert!(
        first / found.last().outcome.scores.nrmse >= 3.0,
        "s2: {ladder}"
    );
    // Each rung's BIC change is that of its own step, recomputed from the two rungs' NRMSE and
    // parameters at the sample size the effect was weighed at. On s2 the second rung showed
    // -3987, the cost of removing that effect from the best pair, for a step of -1368.
    for (i, rung) in found.rungs.iter().enumerate().skip(1) {
        let before = &found.rungs[i - 1];
        let weighed = found.steps[i - 1]
            .suspects
            .iter()
            .find(|s| s.significant)
            .expect("a rung was added for a significant suspect");
        let n = weighed.n_eff;
        let step = n * (rung.nrmse / before.nrmse).powi(2).ln()
            + (rung.params - before.params) as f64 * n.ln();
        let shown = rung.delta_bic.unwrap();
        assert!(
            (shown - step).abs() <= 1e-9 * step.abs(),
            "s2 rung {i}: {shown} against {step}; {ladder}"
        );
    }
}

/// Pinching that grows over the test, as in RC columns: the hidden
/// pinching with `p` = 0.0018 and 0.0006 per kN mm, half developed after
/// 385 and 1,155 kN mm of hysteretic energy (the plain base takes in about
/// 2,700 kN mm along the step-wise path).
/// It shows near zero force in the late cycles only, so the residual's
/// pinching signature over the whole record misses it; adding pinching still
/// takes the error to the noise. Before the best fit could overrule the
/// signature (`DECISIVE_FIT`), stiffness degradation was named instead on
/// 5 of these 6 records, the noise-free one with p = 0.0018 included (NRMSE
/// 0.047 with it, 2e-8 with pinching).
#[test]
fn pinching_that_grows_over_the_test_is_named_alone() {
    let noises = [
        (
            Noise {
                displacement: 0.0,
                force: 0.0,
            },
            "no noise",
        ),
        (Noise::LOW, "low noise"),
        (Noise::HIGH, "high noise"),
    ];
    let mut failures = vec![];
    for (i, p) in [0.0018, 0.0006].into_iter().enumerate() {
        for (j, (noise, what)) in noises.iter().enumerate() {
            let exp = record_with(
                &[EffectKind::Pinching],
                &[("p", p)],
                Path::StepWise,
                *noise,
                400 + 3 * i as u64 + j as u64,
            )
            .unwrap();
            let (_, found, ladder) = ladder_of(exp);
            eprintln!("p = {p} / {what}: {ladder}");
            if found.last().spec.to_string() != "bw+pinching" {
                failures.push(format!("p = {p} / {what}: {ladder}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same pinching (p = 0.0018) beside strength and stiffness
/// degradation: the loop ends with all three (before: stiffness and
/// strength degradation only, at NRMSE 0.059, pinching vetoed).
#[test]
fn pinching_that_grows_beside_degradation_is_named_too() {
    let exp = record_with(
        &[
            EffectKind::Pinching,
            EffectKind::StrengthDegradation,
            EffectKind::StiffnessDegradation,
        ],
        &[("p", 0.0018)],
        Path::StepWise,
        Noise::LOW,
        410,
    )
    .unwrap();
    let (first, found, ladder) = ladder_of(exp);
    let last = found.last();
    for kind in [
        EffectKind::Pinching,
        EffectKind::StrengthDegradation,
        EffectKind::StiffnessDegradation,
    ] {
        assert!(last.spec.effects.contains(kind), "{ladder}");
    }
    assert!(first / last.outcome.scores.nrmse >= 3.0, "{ladder}");
}

/// Weak pinching with a wide band (zeta0 0.2, psi0 0.75) at 2% force noise: its pattern near
/// zero force is below pinching's gate (the band lowers the stiffness everywhere), and stiffness
/// degradation, which has no gate, was named in its place on 12 of 18 such records (seeds 1-6,
/// zeta0 0.15-0.25; found by review on the core's simulator, 4 of 18 there). Pinching alone
/// fits them decisively better (a BIC 35-59 lower here), so stiffness degradation is held back,
/// and where pinching's best fit has at most `DECISIVE_FIT` (0.95) of the NRMSE of the best
/// without it, pinching is named on its fit: seed 2 (0.94). Seed 4 (0.95, just above) names
/// neither, and the evidence says which fits best. Both named stiffness degradation before.
#[test]
fn weak_pinching_is_named_on_its_fit_or_not_at_all() {
    let values = [
        ("zeta0", 0.2),
        ("p", 0.002),
        ("q", 0.1),
        ("psi0", 0.75),
        ("delta_psi", 0.0),
        ("lambda", 0.5),
    ];
    let noise = Noise {
        displacement: 0.0,
        force: 0.02,
    };
    for seed in [2u64, 4] {
        let exp = record_with(
            &[EffectKind::Pinching],
            &values,
            Path::StepWise,
            noise,
            seed,
        )
        .unwrap();
        let (problem, outcome) = fit_bw(exp);
        let d = Diagnosis::new(&problem, &outcome).unwrap();
        let suspects = weigh(&problem, &outcome, &d, &WeighOptions::default());
        let named: Vec<&str> = suspects
            .iter()
            .filter(|s| s.significant)
            .map(|s| s.effect.name())
            .collect();
        if seed == 2 {
            let pinching = suspects
                .iter()
                .find(|s| s.effect == EffectRef::Builtin(EffectKind::Pinching))
                .unwrap();
            assert_eq!(named, ["pinching"], "seed {seed}: {}", pinching.evidence);
            assert!(
                pinching
                    .evidence
                    .contains("so it is weighed on its fit all the same"),
                "seed {seed}: {}",
                pinching.evidence
            );
            continue;
        }
        assert!(named.is_empty(), "seed {seed}: {named:?}");
        let stiffness = suspects
            .iter()
            .find(|s| s.effect == EffectRef::Builtin(EffectKind::StiffnessDegradation))
            .unwrap();
        eprintln!("seed {seed}: {}", stiffness.evidence);
        // It would have been named on its own evidence: in the best model the gate leaves,
        // its removal costs more than 10.
        assert!(
            stiffness.delta_bic < -10.0,
            "seed {seed}: {}",
            stiffness.evidence
        );
        assert!(
            stiffness.evidence.contains("But pinching alone, held back"),
            "seed {seed}: {}",
            stiffness.evidence
        );
    }
}
