//! `hyst params --model SPEC`: the parameters of a model, with their thesis
//! symbols, equations, off values and documentation.

use crate::model::ModelSpec;
use clap::Args;

/// Arguments of `hyst params`.
#[derive(Debug, Args)]
pub struct ParamsArgs {
    /// Model spec, e.g. `bw+pinching` or `bwbn`.
    #[arg(long, default_value = "bwbn")]
    pub model: ModelSpec,
}

/// Prints the parameter table.
pub fn run(args: ParamsArgs) -> anyhow::Result<()> {
    outln!(
        "{:<10} {:<6} {:<5} {:>6}  description",
        "name",
        "symbol",
        "eq.",
        "off"
    );
    for s in args.model.params() {
        outln!(
            "{:<10} {:<6} {:<5} {:>6}  {}",
            s.name,
            s.symbol,
            s.equation,
            s.off,
            s.doc
        );
    }
    Ok(())
}
