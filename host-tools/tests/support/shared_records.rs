//! The records of `../shared/data/synthetic/` (made by an independent
//! simulator, each hiding one effect), for the discovery tests.

use hyst::fit::experiment::Experiment;

/// The shared synthetic record `name`, displacement-driven.
pub fn shared(name: &str) -> Experiment {
    let path = format!(
        "{}/../../shared/data/synthetic/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let rec = hyst::data::read(&path, &Default::default()).unwrap();
    Experiment::from_record(&rec, None).unwrap()
}
