//! The self-contained HTML page of a diagnosis or a discovery run: loops
//! overlaid, force against sample, the residual map, per-cycle errors,
//! energies and peak forces, the suspects and the ladder.

use super::diagnosis::Diagnosis;
use super::ladder::{Discovery, Rung};
use super::suspects::Suspect;
use crate::report::plots::{
    ladder, loop_overlay, per_cycle_bars, residual_map, time_series, Quantity, Residuals,
    Rung as PlotRung, Signal, TimeBase, Trace,
};
use crate::report::{Figure, Report, Table};
use anyhow::Result;

/// Units of the record's displacement and force.
pub struct Units<'a> {
    /// Displacement unit.
    pub displacement: &'a str,
    /// Force unit.
    pub force: &'a str,
}

fn suspects_table(suspects: &[Suspect]) -> Result<Table> {
    let mut t = Table::new(&["Effect", "Significant", "NRMSE with", "ΔBIC", "Evidence"]);
    for s in suspects {
        t.row(vec![
            s.effect.name().into(),
            (if s.significant { "yes" } else { "no" }).into(),
            s.nrmse_with.into(),
            // A whole number, as the text gives it (four digits read "7.000":
            // found by review); none for a model that could not be fitted.
            match s.delta_bic.is_finite() {
                true => (s.delta_bic.round() as i64).into(),
                false => "".into(),
            },
            s.evidence.clone().into(),
        ])?;
    }
    Ok(t)
}

/// Adds the sections of one diagnosed model to `page`.
pub fn diagnosis_sections(
    page: &mut Report,
    model: &str,
    nrmse: f64,
    d: &Diagnosis,
    suspects: &[Suspect],
    units: &Units,
) -> Result<()> {
    let (du, fu) = (units.displacement, units.force);
    let mf = d.model_force();
    let overlay = loop_overlay(
        &[
            Trace::measured("measured", &d.displacement, &d.force),
            Trace::model(model, &d.displacement, mf),
        ],
        Quantity::new("Displacement", du),
        Quantity::new("Force", fu),
    )?;
    let series = time_series(
        TimeBase::Index,
        &[
            Signal::measured("measured", fu, &d.force),
            Signal::model(model, fu, mf),
        ],
    )?;
    let labels = d.segmentation.labels();
    let branch: Vec<usize> = labels.iter().map(|l| l.branch.index()).collect();
    let starts: Vec<usize> = d
        .segmentation
        .cycles()
        .cycles()
        .iter()
        .map(|c| c.from)
        .collect();
    let residual_fig = residual_map(&Residuals {
        displacement: &d.displacement,
        residual: &d.residual,
        branch: &branch,
        branch_names: &["loading", "unloading", "reloading"],
        cycle_starts: &starts,
        displacement_unit: du,
        force_unit: fu,
    })?;
    let rms: Vec<f64> = d.cycles.iter().map(|c| c.rms_error).collect();
    let e_meas: Vec<f64> = d.cycles.iter().map(|c| c.energy_measured).collect();
    let e_model: Vec<f64> = d.cycles.iter().map(|c| c.energy_model).collect();
    let p_meas: Vec<f64> = d
        .cycles
        .iter()
        .map(|c| 0.5 * (c.peak_positive.0 - c.peak_negative.0))
        .collect();
    let p_model: Vec<f64> = d
        .cycles
        .iter()
        .map(|c| 0.5 * (c.peak_positive.1 - c.peak_negative.1))
        .collect();
    let energy_unit = format!("{fu}·{du}");
    let errors = per_cycle_bars(
        Quantity::new("RMS error", fu),
        &[Signal::model(model, fu, &rms)],
    )?;
    let energies = per_cycle_bars(
        Quantity::new("Energy dissipated", &energy_unit),
        &[
            Signal::measured("measured", &energy_unit, &e_meas),
            Signal::model(model, &energy_unit, &e_model),
        ],
    )?;
    let peaks = per_cycle_bars(
        Quantity::new("Peak force (mean of both directions)", fu),
        &[
            Signal::measured("measured", fu, &p_meas),
            Signal::model(model, fu, &p_model),
        ],
    )?;
    page.section(&format!("Model {model}: NRMSE {nrmse:.4}"))
        .paragraph(&format!(
            "Total energy error {:.1}%. Where the model fails, by share of the squared error:",
            100.0 * d.energy_error
        ));
    for p in d.places.iter().take(4) {
        page.paragraph(&format!("• {}.", p.words));
    }
    page.figure(
        &overlay,
        "Force against displacement: measured (grey) and model.",
    )
    .figure(&series, "Force sample by sample.")
    .figure(
        &residual_fig,
        "Residual (model - measured) by branch class and by cycle.",
    )
    .figure(&errors, "RMS error per cycle.")
    .figure(&energies, "Energy dissipated per cycle.")
    .figure(&peaks, "Peak force per cycle.")
    .subsection("Suspects")
    .table(&suspects_table(suspects)?);
    Ok(())
}

/// The ladder figure: NRMSE and BIC change of each rung, labelled with
/// [`Rung::label`], the significance threshold marked (the page's figure
/// and `hyst discover --plot`).
pub fn ladder_figure(rungs: &[Rung]) -> Result<Figure> {
    let labels: Vec<String> = rungs.iter().map(Rung::label).collect();
    let plot_rungs: Vec<PlotRung> = rungs
        .iter()
        .zip(&labels)
        .map(|(r, label)| PlotRung {
            label,
            params: r.params,
            nrmse: r.nrmse,
            delta_bic: r.delta_bic,
        })
        .collect();
    Ok(ladder(&plot_rungs, Some(super::suspects::SIGNIFICANT_BIC))?)
}

/// The ladder figure and table.
pub fn ladder_section(page: &mut Report, rungs: &[Rung]) -> Result<()> {
    let fig = ladder_figure(rungs)?;
    let mut t = Table::new(&["Model", "Parameters", "NRMSE", "Energy error", "ΔBIC"]);
    for r in rungs {
        t.row(vec![
            r.label().into(),
            r.params.into(),
            r.nrmse.into(),
            r.energy_error.into(),
            r.delta_bic
                .map_or_else(|| "".to_string(), |d| format!("{d:.0}"))
                .into(),
        ])?;
    }
    page.section("The error falling")
        .figure(
            &fig,
            "NRMSE as effects are added (and taken away, marked -effect, where the final model did not need one), and the BIC change of each step.",
        )
        .table(&t);
    Ok(())
}

/// The page of a discovery run.
pub fn discovery_page(title: &str, discovery: &Discovery, units: &Units) -> Result<Report> {
    let mut page = Report::new(title);
    ladder_section(&mut page, &discovery.rungs)?;
    before_and_after(&mut page, discovery, units)?;
    for step in &discovery.steps {
        let name = step.spec.to_string();
        diagnosis_sections(
            &mut page,
            &name,
            step.outcome.scores.nrmse,
            &step.diagnosis,
            &step.suspects,
            units,
        )?;
    }
    Ok(page)
}

/// The first and the final model over the measured loops, and the RMS error
/// of every rung cycle by cycle: where the added effects took the error away.
fn before_and_after(page: &mut Report, discovery: &Discovery, units: &Units) -> Result<()> {
    let (Some(first), Some(last)) = (discovery.steps.first(), discovery.steps.last()) else {
        return Ok(());
    };
    if discovery.steps.len() < 2 {
        return Ok(());
    }
    let (du, fu) = (units.displacement, units.force);
    let names: Vec<String> = discovery.steps.iter().map(|s| s.spec.to_string()).collect();
    let d0 = &first.diagnosis;
    let overlay = loop_overlay(
        &[
            Trace::measured("measured", &d0.displacement, &d0.force),
            Trace::model(&names[0], &d0.displacement, d0.model_force()),
            Trace::model(
                &names[names.len() - 1],
                &last.diagnosis.displacement,
                last.diagnosis.model_force(),
            ),
        ],
        Quantity::new("Displacement", du),
        Quantity::new("Force", fu),
    )?;
    let rms: Vec<Vec<f64>> = discovery
        .steps
        .iter()
        .map(|s| s.diagnosis.cycles.iter().map(|c| c.rms_error).collect())
        .collect();
    let signals: Vec<Signal> = names
        .iter()
        .zip(&rms)
        .map(|(n, r)| Signal::model(n, fu, r))
        .collect();
    let errors = per_cycle_bars(Quantity::new("RMS error", fu), &signals)?;
    page.section("Before and after")
        .figure(
            &overlay,
            "Force against displacement: measured (grey), the first model and the final one.",
        )
        .figure(&errors, "RMS error per cycle of every model on the ladder.");
    Ok(())
}
