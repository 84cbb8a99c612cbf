//! Regression baselines on what a dampener takes: per contact pair the peak force, its time,
//! the impulse and the impact count; the run's largest tip deflection, its residual vibration's
//! frequency and log decrement and the peak drive torque, each with a tolerance; and the settings
//! it was blessed under (model, integrator, contact method, step). `pipearm check` compares a run
//! with its baseline and fails on a changed setting; `--bless` rewrites it.
//!
//! How the default tolerances were chosen is measured in `docs/regression.md`.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::run::RunSummary;

/// Errors reading or writing a baseline.
#[derive(Debug, Error)]
pub enum BaselineError {
    /// No baseline file.
    #[error("{path}: no baseline for scenario `{scenario}`: create it with `pipearm check {scenario_path} --bless`")]
    Missing { path: PathBuf, scenario: String, scenario_path: String },
    /// Unreadable or malformed.
    #[error("{path}: malformed baseline: {message}; rewrite it with `pipearm check {scenario_path} --bless`")]
    Malformed { path: PathBuf, message: String, scenario_path: String },
    /// Cannot write.
    #[error("{path}: cannot write: {message}")]
    Write { path: PathBuf, message: String },
}

/// One checked quantity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Quantity {
    /// `<pair>.peak_force_n`, `max_tip_deflection_m`, ...
    pub name: String,
    /// Baseline value (SI unit in the name).
    pub value: f64,
    /// Allowed relative change.
    pub relative_tolerance: f64,
    /// Allowed absolute change (in the quantity's unit); a change passes if within either.
    pub absolute_tolerance: f64,
}

/// A scenario's baseline file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Baseline {
    /// pipearm version that wrote it.
    pub pipearm_version: String,
    /// Scenario name.
    pub scenario: String,
    /// Model fidelity of the run.
    pub model: String,
    /// Time step of the run, s.
    pub step_s: f64,
    /// Contact method.
    pub contact_method: String,
    /// Integrator, as a scenario names it with its parameters (empty in a baseline blessed before
    /// it was recorded: any run then differs from it until blessed again).
    #[serde(default)]
    pub integrator: String,
    /// The quantities.
    #[serde(rename = "quantity")]
    pub quantities: Vec<Quantity>,
}

/// Default tolerances (relative, absolute) of each kind of quantity (docs/regression.md).
pub fn default_tolerance(name: &str) -> (f64, f64) {
    match name.rsplit('.').next().unwrap_or(name) {
        "peak_force_n" => (0.02, 1.0),
        "peak_time_s" => (0.0, 0.005),
        "impulse_n_s" => (0.03, 0.01),
        "impact_count" => (0.0, 1.0),
        "max_tip_deflection_m" => (0.01, 1e-5),
        "frequency_hz" => (0.01, 0.0),
        "log_decrement" => (0.10, 0.002),
        "peak_drive_torque_n_m" => (0.02, 1.0),
        "peak_stress_pa" => (0.02, 1e4),
        "utilisation" => (0.02, 1e-4),
        "damage_per_lift" => (0.10, 1e-15),
        "min_angle_deg" | "max_angle_deg" => (0.02, 0.01),
        "residual_swing_deg" => (0.05, 0.002),
        _ => (0.02, 0.0),
    }
}

/// The checked quantities of a run, by name.
pub fn quantities_of(summary: &RunSummary) -> Vec<(String, f64)> {
    let mut q = Vec::new();
    for p in &summary.pairs {
        q.push((format!("{}.peak_force_n", p.pair), p.peak_force_n));
        q.push((format!("{}.peak_time_s", p.pair), if p.peak_time_s.is_finite() { p.peak_time_s } else { 0.0 }));
        q.push((format!("{}.impulse_n_s", p.pair), p.impulse_n_s));
        q.push((format!("{}.impact_count", p.pair), p.impact_count as f64));
    }
    q.push(("max_tip_deflection_m".into(), summary.max_tip_deflection_m));
    // The decay and the drive's peak where the run has them (a residual that does not oscillate
    // has no frequency; an actuated hub reports its torque in the actuator's summary).
    let optional = [
        ("residual.frequency_hz", summary.residual.frequency_hz),
        ("residual.log_decrement", summary.residual.log_decrement),
        ("peak_drive_torque_n_m", summary.peak_drive_torque_n_m),
    ];
    q.extend(optional.into_iter().filter(|(_, v)| v.is_finite()).map(|(n, v)| (n.to_string(), v)));
    if let Some(head) = &summary.head {
        q.push(("head.min_angle_deg".into(), head.min_angle_deg));
        q.push(("head.max_angle_deg".into(), head.max_angle_deg));
        q.push(("head.residual_swing_deg".into(), head.residual_swing_deg));
    }
    q.extend(sign_off_quantities(summary));
    q
}

/// The sign-off's checked quantities, where the run has them: the peak stress and utilisation,
/// the pivot's and the cylinder pin's peak force, the fatigue damage of the lift.
fn sign_off_quantities(summary: &RunSummary) -> Vec<(String, f64)> {
    let Some(signed) = &summary.sign_off else { return Vec::new() };
    let (stress, pins) = (&signed.stress, &signed.pins);
    let mut q = vec![("stress.peak_stress_pa".into(), stress.peak_stress_pa)];
    q.extend(stress.utilisation.map(|u| ("stress.utilisation".into(), u)));
    q.push(("pins.pivot.peak_force_n".into(), pins.pivot.peak_force_n));
    q.extend(pins.cylinder.as_ref().map(|c| ("pins.cylinder.peak_force_n".into(), c.peak_force_n)));
    q.extend(signed.fatigue.damage_per_lift.map(|d| ("fatigue.damage_per_lift".into(), d)));
    q
}

/// A setting a run differs from its baseline in: its value in the baseline and now.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SettingChange {
    /// `model`, `integrator`, `contact_method` or `step_s`.
    pub setting: &'static str,
    /// As blessed.
    pub baseline: String,
    /// As run.
    pub now: String,
}

/// The settings (model, integrator, contact method, step) in which a run differs from the ones
/// its baseline was blessed under: a baseline is a claim about one configuration, so a change of
/// configuration fails the check until it is blessed.
pub fn setting_changes(baseline: &Baseline, summary: &RunSummary) -> Vec<SettingChange> {
    [
        ("model", baseline.model.clone(), summary.model.clone()),
        ("integrator", baseline.integrator.clone(), summary.integrator.clone()),
        ("contact_method", baseline.contact_method.clone(), summary.contact_method.clone()),
        ("step_s", baseline.step_s.to_string(), summary.step_s.to_string()),
    ]
    .into_iter()
    .filter(|(_, was, now)| was != now)
    .map(|(setting, baseline, now)| SettingChange { setting, baseline, now })
    .collect()
}

/// One row of a comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Quantity.
    pub name: String,
    /// Baseline value (NaN: not in the baseline).
    pub baseline: f64,
    /// This run's value (NaN: not produced any more).
    pub now: f64,
    /// Relative change (now − baseline)/|baseline|.
    pub change: f64,
    /// Tolerance as written: relative and absolute.
    pub tolerance: (f64, f64),
    /// Within tolerance.
    pub pass: bool,
}

/// Compares a run with its baseline, quantity by quantity (a quantity missing on either side
/// fails).
pub fn compare(baseline: &Baseline, summary: &RunSummary) -> Vec<Row> {
    let now = quantities_of(summary);
    let mut rows: Vec<Row> = baseline
        .quantities
        .iter()
        .map(|b| {
            let value = now.iter().find(|(n, _)| *n == b.name).map_or(f64::NAN, |(_, v)| *v);
            let diff = (value - b.value).abs();
            let pass = diff <= b.absolute_tolerance || diff <= b.relative_tolerance * b.value.abs();
            Row {
                name: b.name.clone(),
                baseline: b.value,
                now: value,
                change: (value - b.value) / b.value.abs(),
                tolerance: (b.relative_tolerance, b.absolute_tolerance),
                pass: pass && value.is_finite(),
            }
        })
        .collect();
    for (name, value) in now.iter().filter(|(n, _)| !baseline.quantities.iter().any(|b| &b.name == n)) {
        rows.push(Row {
            name: name.clone(),
            baseline: f64::NAN,
            now: *value,
            change: f64::NAN,
            tolerance: default_tolerance(name),
            pass: false,
        });
    }
    rows
}

/// The baseline a run would bless: its quantities with the tolerances of `previous` where it
/// has the quantity, the defaults otherwise.
pub fn blessed(summary: &RunSummary, previous: Option<&Baseline>) -> Baseline {
    let quantities = quantities_of(summary)
        .into_iter()
        .map(|(name, value)| {
            let kept = previous.and_then(|p| p.quantities.iter().find(|q| q.name == name));
            let (relative_tolerance, absolute_tolerance) =
                kept.map_or_else(|| default_tolerance(&name), |q| (q.relative_tolerance, q.absolute_tolerance));
            Quantity { name, value, relative_tolerance, absolute_tolerance }
        })
        .collect();
    Baseline {
        pipearm_version: env!("CARGO_PKG_VERSION").into(),
        scenario: summary.scenario.clone(),
        model: summary.model.clone(),
        step_s: summary.step_s,
        contact_method: summary.contact_method.clone(),
        integrator: summary.integrator.clone(),
        quantities,
    }
}

/// Path of a scenario's baseline in `dir`.
pub fn baseline_path(dir: &Path, scenario: &str) -> PathBuf {
    dir.join(format!("{scenario}.toml"))
}

/// Reads a baseline; `scenario_path` is named in the error's advice.
pub fn read_baseline(path: &Path, scenario: &str, scenario_path: &Path) -> Result<Baseline, BaselineError> {
    let scenario_path = scenario_path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|_| BaselineError::Missing {
        path: path.into(),
        scenario: scenario.into(),
        scenario_path: scenario_path.clone(),
    })?;
    toml::from_str(&text).map_err(|e| BaselineError::Malformed {
        path: path.into(),
        message: e.to_string(),
        scenario_path,
    })
}

/// Writes a baseline (temporary file, then rename).
pub fn write_baseline(path: &Path, baseline: &Baseline) -> Result<(), BaselineError> {
    let err = |e: &dyn std::fmt::Display| BaselineError::Write { path: path.into(), message: e.to_string() };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| err(&e))?;
    }
    let text = toml::to_string_pretty(baseline).map_err(|e| err(&e))?;
    let header = "# Regression baseline: written by `pipearm check --bless`; tolerances in docs/regression.md.\n";
    let tmp = path.with_extension("toml.tmp");
    std::fs::write(&tmp, format!("{header}{text}")).map_err(|e| err(&e))?;
    std::fs::rename(&tmp, path).map_err(|e| err(&e))
}
