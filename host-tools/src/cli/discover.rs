//! `hyst discover DATA --model SPEC`: the loop: add the strongest
//! significant effect, refit from the previous fit, repeat until nothing
//! significant is left; then the ladder.

use super::diagnose::{
    diagnosis_json, initial_fit, print_diagnosis, unneeded_section, Beyond, Common, Initial,
};
use super::fit::Bar;
use crate::discover::{discover, page, Rung};
use crate::discover::{lag, offset, rate, slip};
use crate::fit::run::Progress;
use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use std::path::PathBuf;

/// Arguments of `hyst discover`.
#[derive(Debug, Args)]
pub struct DiscoverArgs {
    #[command(flatten)]
    pub common: Common,
    /// Write the ladder plot (error falling) as SVG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Runs `hyst discover`.
pub fn run(args: DiscoverArgs) -> Result<()> {
    let quiet = args.common.json;
    let bar = Bar::new(&format!("discover from {}", args.common.model), quiet);
    let Initial {
        problem,
        outcome,
        time,
        monotone,
        options,
    } = initial_fit(&args.common, None, &bar)?;
    bar.status("weighing the candidate effects");
    let discovery = discover(problem, outcome, &options, |step| {
        let top = step.suspects.iter().find(|s| s.significant);
        bar.stage(&format!(
            "{:<40} NRMSE {:.4}  {}",
            step.spec.to_string(),
            step.outcome.scores.nrmse,
            match top {
                Some(s) => format!(
                    "-> adding {} (delta-BIC {:.0})",
                    s.effect.name(),
                    s.bic_of_adding()
                ),
                None => "-> nothing significant left".to_string(),
            }
        ));
    })?;
    let last = discovery.last();
    let mut beyond = Beyond::check(
        &last.problem,
        &last.diagnosis,
        monotone,
        &args.common.read.negate,
    );
    beyond.slip = slip::of_ladder(&discovery, beyond.slip);
    beyond.set_offsets(offset::of_ladder(&discovery));
    if let Some(t) = &time {
        bar.status("refitting with a dashpot");
        beyond.rate = rate::of_ladder(&discovery, t);
    }
    bar.status("realigning the channels");
    beyond.set_lag(lag::of_ladder(&discovery));
    bar.finish();
    if let Some(path) = &args.plot {
        let fig = page::ladder_figure(&discovery.rungs)?;
        std::fs::write(path, fig.to_svg())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    if let Some(path) = &args.common.report {
        let units = page::Units {
            displacement: "mm",
            force: "kN",
        };
        let mut report = page::discovery_page(
            &format!("Discovery on {}", args.common.data.display()),
            &discovery,
            &units,
        )?;
        unneeded_section(&mut report, &discovery.unneeded);
        beyond.section(&mut report);
        report
            .write(path)
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    if args.common.json {
        let mut obj = diagnosis_json(
            &last.problem,
            &last.outcome,
            &last.diagnosis,
            &last.suspects,
            &beyond,
            &discovery.unneeded,
        );
        obj["ladder"] = json!(discovery.rungs);
        outln!("{}", serde_json::to_string_pretty(&obj)?);
    } else {
        outln!(
            "{:<44} {:>6} {:>9} {:>9} {:>10}",
            "model",
            "params",
            "NRMSE",
            "energy",
            "delta-BIC"
        );
        for r in &discovery.rungs {
            let d = r
                .delta_bic
                .map_or_else(|| "-".to_string(), |d| format!("{d:.0}"));
            outln!(
                "{:<44} {:>6} {:>9.4} {:>8.1}% {:>10}",
                r.label(),
                r.params,
                r.nrmse,
                100.0 * r.energy_error,
                d
            );
        }
        outln!("{}\n", summary(&discovery.rungs, last.outcome.scores.nrmse));
        if !discovery.unneeded.is_empty() {
            let names: Vec<&str> = discovery.unneeded.iter().map(|u| u.effect).collect();
            outln!(
                "note: the loop keeps the effects of the model it starts from; the record does not need {} (below): start from a model without {}\n",
                names.join(" and "),
                if names.len() == 1 { "it" } else { "them" }
            );
        }
        print_diagnosis(
            &last.problem,
            &last.outcome,
            &last.diagnosis,
            &last.suspects,
            &beyond,
            &discovery.unneeded,
        )?;
    }
    Ok(())
}

/// The line under the ladder: how far the error fell from the first rung
/// (`rungs`) to the final model's `nrmse`, said as what happened. It read
/// "error fell 1.0x" where nothing was added, and a fall where an effect was
/// added and taken away again, which is the refit's (found by review).
fn summary(rungs: &[Rung], nrmse: f64) -> String {
    let first = rungs.first().map_or(f64::NAN, |r| r.nrmse);
    if rungs.len() <= 1 {
        format!("nothing added: the error stays at {first:.4}")
    } else if rungs.last().is_some_and(|r| r.model == rungs[0].model) {
        format!(
            "no effect kept: the model is the one the loop started from, refitted; the error \
             went from {first:.4} to {nrmse:.4}"
        )
    } else {
        format!(
            "error fell {:.1}x, from {first:.4} to {nrmse:.4}",
            first / nrmse
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rung(model: &str, nrmse: f64, removed: Option<&'static str>) -> Rung {
        Rung {
            model: model.into(),
            params: 5,
            nrmse,
            energy_error: 0.0,
            delta_bic: None,
            removed,
        }
    }

    #[test]
    fn the_summary_says_what_the_ladder_did() {
        assert_eq!(
            summary(&[rung("bw", 0.0251, None)], 0.0251),
            "nothing added: the error stays at 0.0251"
        );
        let back = [
            rung("bw+pinching", 0.0438, None),
            rung("bw+stiffness-degradation+pinching", 0.0252, None),
            rung("bw+pinching", 0.0251, Some("stiffness-degradation")),
        ];
        let said = summary(&back, 0.0251);
        assert!(
            said.starts_with("no effect kept") && said.ends_with("from 0.0438 to 0.0251"),
            "{said}"
        );
        let added = [rung("bw", 0.1402, None), rung("bw+pinching", 0.0217, None)];
        assert_eq!(
            summary(&added, 0.0217),
            "error fell 6.5x, from 0.1402 to 0.0217"
        );
    }
}
