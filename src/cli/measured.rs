//! `pipearm compare` and `pipearm fit`: a run set against a rig's measured file, and parameters
//! fitted to it.

use std::path::Path;

use anyhow::{Context, Result, bail};
use pipearm::record::{Ending, Recorded, save_recording};
use pipearm::scenario::Scenario;

/// `pipearm compare`: the measured file is read and checked before the run; nothing is written
/// unless the comparison completes.
pub fn compare_command(
    path: &Path,
    measured: &Path,
    options: pipearm::compare::CompareOptions,
    out: &Path,
) -> Result<()> {
    let scenario = super::overrides::Overrides { model: options.fidelity, ..Default::default() }.load(path)?;
    let measured = pipearm::measured::read(measured)?;
    let compiled = scenario.compile(options.fidelity)?;
    let model: &pipearm::model::Model = &compiled.model;
    let defs = pipearm::run::measurable_channels(model);
    note_renamed(&measured, &defs);
    let compared = pipearm::compare::compare(&compiled, &measured, &options)?;
    print!("{}", pipearm::compare::table(&compared.comparison));
    let overlay =
        pipearm::compare::overlay::measured_chunks(&measured, &compared.columns, &compared.comparison, &defs)?;
    let ending = Ending::Finished(&compared.summary);
    let recorded = Recorded { series: &compared.series, ending, overlay: &overlay };
    let rrd = out.join(format!("{}.compare.rrd", model.name));
    save_recording(&rrd, &recorded, None)?;
    let json = out.join(format!("{}.compare.json", model.name));
    pipearm::compare::write_json(&json, &compared.comparison)?;
    println!("wrote {} and {}", json.display(), rrd.display());
    Ok(())
}

/// `pipearm fit`: the fitted values with their intervals; the report and the fitted scenario.
pub fn fit_command(
    path: &Path,
    measured: &Path,
    keys: &[String],
    (settings, shift): (pipearm::fit::RunSettings, bool),
    out: &Path,
) -> Result<()> {
    if let Some(step) = settings.step_s
        && !(step.is_finite() && step > 0.0 && step <= 0.1)
    {
        bail!("--step = {step}: allowed 0 < step <= 0.1 s");
    }
    let scenario = Scenario::load(path)?;
    let measured = pipearm::measured::read(measured)?;
    note_renamed(&measured, &pipearm::run::measurable_channels(&scenario.model));
    let signals = pipearm::fit::signals_of(&measured, &scenario.model)?;
    let problem = pipearm::fit::Problem::new(&scenario, keys, settings)?;
    pipearm::export::check_folder(out).context("--out")?;
    let report = pipearm::fit::fit(&problem, &signals, shift, &pipearm::fit::lm::LmOptions::default())?;
    println!("{:<32} {:>14} {:>14} {:>31}", "key", "scenario", "fitted", "95 % interval");
    for p in &report.parameters {
        let [lo, hi] = p.interval_95;
        println!("{:<32} {:>14.6e} {:>14.6e} {:>14.6e} .. {:>14.6e}", p.key, p.initial, p.value, lo, hi);
    }
    println!(
        "shift {:.4} s, RMS residual over peak {:.4} -> {:.4}, {} runs, converged: {}",
        report.shift_s, report.rms_residual[0], report.rms_residual[1], report.evaluations, report.converged
    );
    let values: Vec<f64> = report.parameters.iter().map(|p| p.value).collect();
    let text = problem.scenario_text(&values, out)?;
    let name = &scenario.model.name;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let json = out.join(format!("{name}.fit.json"));
    std::fs::write(&json, serde_json::to_string_pretty(&report)?)
        .with_context(|| format!("writing {}", json.display()))?;
    let fitted = out.join(format!("{name}.fitted.toml"));
    std::fs::write(&fitted, text).with_context(|| format!("writing {}", fitted.display()))?;
    println!("wrote {} and {}", json.display(), fitted.display());
    Ok(())
}

/// A note for each measured column named in a former spelling, read under the signal's name.
fn note_renamed(measured: &pipearm::measured::Measured, defs: &[pipearm::channel::Channel]) {
    let known: Vec<pipearm::measured::Known> = defs.iter().map(pipearm::measured::Known::from).collect();
    for (written, read) in measured.renamed(&known) {
        println!(
            "note: the column `{written}` is read as `{read}` (the pair's name, as the summary gives it: write it so)"
        );
    }
}
