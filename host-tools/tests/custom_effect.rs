//! An effect defined outside the library (the slip of
//! `examples/custom_effect/`) plugs into simulation, fitting and diagnosis
//! through the registry, without editing the library.

#[path = "../examples/custom_effect/slip.rs"]
mod slip;

use hyst::discover::{weigh, Diagnosis, WeighOptions};
use hyst::fit::experiment::{Drive, Experiment};
use hyst::fit::problem::Problem;
use hyst::fit::run::{self, Method, Quiet};
use hyst::model::{EffectRef, ModelSpec, ParamFile};
use hysteresis::bwbn::Bwbn;
use hysteresis::Element;
use std::path::Path;
use std::sync::Once;

fn register() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| hyst::model::register(&slip::SlipEffect).unwrap());
}

const TRUTH: [(&str, f64); 7] = [
    ("k0", 20.0),
    ("alpha", 0.03),
    ("n", 1.5),
    ("beta", 0.6),
    ("gamma", 0.4),
    ("slip_depth", 0.8),
    ("slip_width", 0.25),
];

/// A step-wise test of a column whose bars slip, with light noise.
fn slipping_column() -> Experiment {
    register();
    let spec = ModelSpec::parse("bw+slip").unwrap();
    let (params, extras) = spec
        .build(|n| TRUTH.iter().find(|(k, _)| *k == n).map(|(_, v)| *v))
        .unwrap();
    let u = hyst::discover::synthetic::path(hyst::discover::synthetic::Path::StepWise);
    let mut el =
        Bwbn::with_extra(params, &extras, hysteresis::bwbn::Control::default_for()).unwrap();
    let mut gauss = hyst::data::Normal::new(5);
    let mut f = vec![];
    for &ui in &u {
        f.push(el.set_trial(ui).unwrap().force + 0.1 * gauss.sample());
        el.commit();
    }
    Experiment {
        input: u,
        output: f,
        drive: Drive::Displacement,
    }
}

#[test]
fn specs_and_parameter_files_know_the_registered_effect() {
    register();
    let spec = ModelSpec::parse("bwbn+slip").unwrap();
    assert_eq!(spec.to_string(), "bwbn+slip");
    assert!(spec.params().iter().any(|p| p.name == "slip_width"));
    let file = ParamFile::parse(
        Path::new("slip.json"),
        r#"{"model": "bw+slip", "k0": 20, "alpha": 0.03, "n": 1.5, "beta": 0.6, "gamma": 0.4, "slip_depth": 1.5}"#,
    )
    .unwrap();
    let err = file
        .build(file.spec(None).unwrap(), false)
        .unwrap_err()
        .to_string();
    // Placed at the value: column 98 of the one line.
    assert_eq!(err, "slip.json:1:98: slip_depth must lie in [0, 1]");
    assert!(
        hyst::model::register(&slip::SlipEffect).is_err(),
        "a name registers once"
    );
}

#[test]
fn fitting_recovers_the_slip_and_diagnosis_names_it() {
    let exp = slipping_column();
    // Fitting bw+slip recovers the hidden values.
    let with = Problem::new(ModelSpec::parse("bw+slip").unwrap(), exp.clone(), &[]).unwrap();
    let fit = run::fit(&with, Method::Auto, &with.par.default_start(), &Quiet).unwrap();
    // The noise is white, so the fit's own standard errors are the yardstick:
    // each value lies within four of them of the truth, and the data pin every
    // parameter to better than 5%.
    let rel_std = &fit.identifiability.relative_std;
    for (name, truth) in TRUTH {
        let got = fit.values[name];
        let (_, rel) = rel_std.iter().find(|(n, _)| n == name).unwrap();
        let std = rel * got.abs();
        assert!(*rel < 0.05, "{name} is poorly determined: {rel}");
        assert!(
            (got - truth).abs() < 4.0 * std,
            "{name}: {got} vs {truth}, standard error {std}"
        );
    }
    // Starting from bw, the diagnosis names slip as its top significant suspect.
    let bw = Problem::new(ModelSpec::BW, exp, &[]).unwrap();
    let fit = run::fit(&bw, Method::Auto, &bw.par.default_start(), &Quiet).unwrap();
    let d = Diagnosis::new(&bw, &fit).unwrap();
    let suspects = weigh(&bw, &fit, &d, &WeighOptions::default());
    let top = suspects
        .iter()
        .find(|s| s.significant)
        .expect("a significant suspect");
    assert_eq!(
        top.effect,
        EffectRef::from_name("slip").unwrap(),
        "{:?}",
        suspects.iter().map(|s| &s.evidence).collect::<Vec<_>>()
    );
    assert!(fit.scores.nrmse / top.nrmse_with > 3.0);
}
