//! `hyst params --model SPEC`: the parameters of a model, with their thesis
//! symbols, equations, off values and documentation; for `phm-torsion`, the
//! keys of a PHM file and the rule coefficients of thesis ch. 5 with the
//! thesis' values.

use super::ModelArg;
use crate::model::{ModelSpec, PHM_MODEL, PHM_POINTS};
use clap::Args;
use hysteresis::phm::SPECS;

/// Arguments of `hyst params`.
#[derive(Debug, Args)]
pub struct ParamsArgs {
    /// Model spec, e.g. `bw+pinching` or `bwbn`, or `phm-torsion`.
    #[arg(long, default_value = "bwbn")]
    pub model: ModelArg,
}

/// Prints the parameter table.
pub fn run(args: ParamsArgs) -> anyhow::Result<()> {
    match args.model {
        ModelArg::Bwbn(spec) => print_bwbn(spec),
        ModelArg::Phm => print_phm(),
    }
}

fn print_bwbn(spec: ModelSpec) -> anyhow::Result<()> {
    let rows = spec
        .params()
        .iter()
        .map(|s| {
            (
                [
                    s.name.to_string(),
                    s.symbol.to_string(),
                    s.equation.to_string(),
                    s.off.to_string(),
                ],
                s.doc,
            )
        })
        .collect();
    print_table(["name", "symbol", "eq.", "off"], rows)
}

fn print_phm() -> anyhow::Result<()> {
    outln!("A {PHM_MODEL} file (JSON) holds:");
    outln!("  primary.positive  [[twist, torque], ...]: the primary curve, at most {PHM_POINTS} points, twist rising from zero (cracking, yield, peak, deterioration)");
    outln!("  primary.negative  the same for negative twist; left out, the column is symmetric");
    outln!("  units             {{\"twist\": ..., \"torque\": ...}}, default deg and kN m");
    outln!("  coefficients      the rule coefficients below by name; one left out keeps the thesis' value");
    outln!("  memory            16, the inner-cycle depth the host uses (optional)");
    outln!();
    let rows = SPECS
        .iter()
        .map(|s| {
            (
                [
                    s.name.to_string(),
                    s.equation.to_string(),
                    (f64::from(s.thesis.0) / f64::from(s.thesis.1)).to_string(),
                ],
                s.doc,
            )
        })
        .collect();
    print_table(["name", "eq.", "thesis"], rows)
}

/// Prints `rows` under `header` and before their description, each column as
/// wide as its widest entry (symbols such as `ν₀` are counted in characters,
/// not bytes), the last one aligned right.
fn print_table<const N: usize>(
    header: [&str; N],
    rows: Vec<([String; N], &str)>,
) -> anyhow::Result<()> {
    let header = header.map(str::to_string);
    let widths: [usize; N] = std::array::from_fn(|c| {
        rows.iter()
            .map(|(r, _)| r)
            .chain([&header])
            .map(|r| r[c].chars().count())
            .max()
            .unwrap_or(0)
    });
    let line = |r: &[String; N], doc: &str| {
        let mut text = String::new();
        for (c, cell) in r.iter().enumerate() {
            let pad = " ".repeat(widths[c] - cell.chars().count());
            if c + 1 == N {
                text += &format!("{pad}{cell}  ");
            } else {
                text += &format!("{cell}{pad}  ");
            }
        }
        text + doc
    };
    outln!("{}", line(&header, "description"));
    for (r, doc) in &rows {
        outln!("{}", line(r, doc));
    }
    Ok(())
}
