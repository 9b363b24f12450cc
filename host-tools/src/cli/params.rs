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

/// Prints the parameter table, each column as wide as its widest entry
/// (symbols such as `ν₀` are counted in characters, not bytes).
pub fn run(args: ParamsArgs) -> anyhow::Result<()> {
    let params = args.model.params();
    let rows: Vec<[String; 4]> = params
        .iter()
        .map(|s| {
            [
                s.name.to_string(),
                s.symbol.to_string(),
                s.equation.to_string(),
                s.off.to_string(),
            ]
        })
        .collect();
    let header = ["name", "symbol", "eq.", "off"].map(str::to_string);
    let width = |c: usize| {
        rows.iter()
            .chain([&header])
            .map(|r| r[c].chars().count())
            .max()
            .unwrap_or(0)
    };
    let widths = [width(0), width(1), width(2), width(3)];
    let line = |r: &[String; 4], doc: &str| {
        let pad = |c: usize| " ".repeat(widths[c] - r[c].chars().count());
        format!(
            "{}{}  {}{}  {}{}  {}{}  {doc}",
            r[0],
            pad(0),
            r[1],
            pad(1),
            r[2],
            pad(2),
            pad(3),
            r[3]
        )
    };
    outln!("{}", line(&header, "description"));
    for (r, s) in rows.iter().zip(&params) {
        outln!("{}", line(r, s.doc));
    }
    Ok(())
}
