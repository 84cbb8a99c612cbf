//! A run set against measurements: `pipearm compare SCENARIO --measured FILE.csv`.
//!
//! The measured file ([`crate::measured`]) names, per column, a signal of the run
//! ([`measurable_channels`]: the channels a measured column may name, as their producers declare
//! them, [`crate::channel`]). Its columns are checked against the
//! scenario's signals before anything runs; then the scenario runs, optionally the measured file
//! is shifted in time to the cross-correlation's peak ([`align::estimate_shift`], one shift for
//! every column), the simulated signal is interpolated linearly at the measured times (within
//! the run's span), and each signal is reported ([`SignalComparison`]).
//!
//! The dominant frequency and the logarithmic decrement are those of the residual vibration after
//! the drive stops ([`crate::analysis::residual`]: up-crossings of the final mean, and successive
//! peaks above it). Crossings rather than an FFT: after the drive there are a few seconds of
//! one decaying mode, and an FFT over T seconds resolves 1/T (0.2 Hz over 5 s, 5 % of the
//! default arm's 4.7 Hz), where crossings, interpolated between samples, time each period to a
//! fraction of a sample. They need the signal to cross its mean cleanly: measured noise of more
//! than a few percent of the vibration's amplitude should be filtered first.

pub mod align;
pub mod overlay;

use std::path::{Path, PathBuf};

use serde::Serialize;
use thiserror::Error;

use crate::analysis::residual;
use crate::arm::Fidelity;
use crate::measured::{Column, Known, Measured, MeasuredError};
use crate::model::Model;
pub use crate::run::measurable_channels;
use crate::run::{CompiledModel, RunOptions, RunSummary, Series, run_compiled};
use crate::scene::SceneError;
pub use crate::sensor::sensor_entity;

/// Errors of a comparison.
#[derive(Debug, Error)]
pub enum CompareError {
    /// In the measured file.
    #[error(transparent)]
    Measured(#[from] MeasuredError),
    /// Running the scenario.
    #[error("running the scenario: {0}")]
    Run(#[from] SceneError),
    /// The measured file and the run share too little time.
    #[error("{path}: {samples} samples fall within the run's 0 ..= {end_s} s{shift}: allowed at least {min}")]
    NoOverlap { path: PathBuf, samples: usize, end_s: f64, shift: String, min: usize },
    /// Writing the report.
    #[error("{path}: cannot write: {message}")]
    Write { path: PathBuf, message: String },
}

/// How to compare.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CompareOptions {
    /// Fidelity of the run (the scenario's if `None`).
    pub fidelity: Option<Fidelity>,
    /// Shift the measured file in time to the cross-correlation's peak.
    pub shift: bool,
}

/// One signal, measured against simulated, over the samples both cover.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignalComparison {
    /// The signal's name.
    pub signal: String,
    /// Its SI unit (every figure below is in it, or stated).
    pub unit: &'static str,
    /// Measured samples compared.
    pub samples: usize,
    /// Largest |measured| and when (run time, after the shift).
    pub peak_measured: f64,
    /// Time of that peak, s.
    pub peak_time_measured_s: f64,
    /// Largest |simulated| at the same samples and when.
    pub peak_simulated: f64,
    /// Time of that peak, s.
    pub peak_time_simulated_s: f64,
    /// Simulated peak less measured peak.
    pub peak_error: f64,
    /// That over the measured peak.
    pub peak_error_relative: f64,
    /// RMS of (simulated − measured) over the measured peak.
    pub rms_error_over_peak: f64,
    /// Dominant frequency of the residual vibration after the drive, measured, Hz (NaN: none).
    pub frequency_measured_hz: f64,
    /// The same, simulated, Hz.
    pub frequency_simulated_hz: f64,
    /// Simulated less measured, Hz.
    pub frequency_difference_hz: f64,
    /// Logarithmic decrement of the residual vibration, measured (NaN: fewer than two peaks).
    pub log_decrement_measured: f64,
    /// The same, simulated.
    pub log_decrement_simulated: f64,
    /// Simulated less measured.
    pub log_decrement_difference: f64,
}

/// A run set against a measured file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// Scenario name.
    pub scenario: String,
    /// The measured file.
    pub measured_file: PathBuf,
    /// Model fidelity of the run.
    pub model: String,
    /// The shift applied, s: measured(t) is set against simulated(t − shift) (`None`: not asked).
    pub shift_s: Option<f64>,
    /// When the drive stops, s (the residual vibration's start).
    pub drive_end_s: f64,
    /// Per measured column, in file order.
    pub signals: Vec<SignalComparison>,
}

/// Fewest samples a compared signal must keep within the run.
const MIN_OVERLAP: usize = crate::measured::MIN_ROWS;

/// A comparison with the run it was made from.
#[derive(Debug, Clone)]
pub struct Compared {
    /// The comparison.
    pub comparison: Comparison,
    /// The run's summary.
    pub summary: RunSummary,
    /// The run's series.
    pub series: Series,
    /// The measured columns in SI units, in file order.
    pub columns: Vec<Column>,
}

/// Checks `measured`'s columns against the compiled model's signals (nothing runs if they do
/// not fit), runs it and compares.
pub fn compare(
    compiled: &CompiledModel,
    measured: &Measured,
    options: &CompareOptions,
) -> Result<Compared, CompareError> {
    let model: &Model = &compiled.model;
    let defs = measurable_channels(model);
    let known: Vec<Known> = defs.iter().map(Known::from).collect();
    let columns = measured.to_si(&known)?;
    // With the 3D scene, for the recording the measured series are drawn over.
    let run_options = RunOptions { fidelity: options.fidelity, capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_compiled(compiled, &run_options);
    let summary = summary?;
    let simulated: Vec<Vec<f64>> = columns
        .iter()
        .map(|c| series.values(defs.iter().find(|d| d.name == c.name).expect("checked by to_si")))
        .collect();
    let shift_s = options.shift.then(|| {
        let pairs: Vec<align::Pair> = columns
            .iter()
            .zip(&simulated)
            .map(|(c, s)| ((&measured.t_s[..], &c.values[..]), (&series.t_s[..], &s[..])))
            .collect();
        align::estimate_shift(&pairs).unwrap_or(0.0)
    });
    let shift = shift_s.unwrap_or(0.0);
    let times: Vec<f64> = measured.t_s.iter().map(|t| t - shift).collect();
    let drive_end_s = model.drive_end_s();
    let signals = columns
        .iter()
        .zip(&simulated)
        .map(|(column, sim)| compare_signal(column, &times, &series.t_s, sim, drive_end_s))
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| CompareError::NoOverlap {
            path: measured.path.clone(),
            samples: times.iter().filter(|t| (0.0..=summary.simulated_s).contains(*t)).count(),
            end_s: summary.simulated_s,
            shift: shift_s.map_or(String::new(), |s| format!(" after the shift of {s:.4} s")),
            min: MIN_OVERLAP,
        })?;
    let comparison = Comparison {
        scenario: model.name.clone(),
        measured_file: measured.path.clone(),
        model: summary.model.clone(),
        shift_s,
        drive_end_s,
        signals,
    };
    Ok(Compared { comparison, summary, series, columns })
}

/// One column against its simulated signal, at the measured `times` (run time) within the run.
fn compare_signal(
    column: &Column,
    times: &[f64],
    sim_t: &[f64],
    sim: &[f64],
    drive_end_s: f64,
) -> Option<SignalComparison> {
    let pairs: Vec<(f64, f64, f64)> = times
        .iter()
        .zip(&column.values)
        .filter_map(|(&t, &m)| align::interpolate(sim_t, sim, t).map(|s| (t, m, s)))
        .collect();
    if pairs.len() < MIN_OVERLAP {
        return None;
    }
    let peak = |pick: fn(&(f64, f64, f64)) -> f64| {
        pairs.iter().map(|p| (p.0, pick(p).abs())).fold((f64::NAN, 0.0), |b, p| if p.1 > b.1 { p } else { b })
    };
    let (measured_time, measured_peak) = peak(|p| p.1);
    let (simulated_time, simulated_peak) = peak(|p| p.2);
    let rms = (pairs.iter().map(|p| (p.2 - p.1).powi(2)).sum::<f64>() / pairs.len() as f64).sqrt();
    let residual_of = |pick: fn(&(f64, f64, f64)) -> f64| {
        let series: Vec<(f64, f64)> = pairs.iter().map(|p| (p.0, pick(p))).collect();
        residual(&series, drive_end_s)
    };
    let (rm, rs) = (residual_of(|p| p.1), residual_of(|p| p.2));
    Some(SignalComparison {
        signal: column.name.clone(),
        unit: unit_of(&column.unit),
        samples: pairs.len(),
        peak_measured: measured_peak,
        peak_time_measured_s: measured_time,
        peak_simulated: simulated_peak,
        peak_time_simulated_s: simulated_time,
        peak_error: simulated_peak - measured_peak,
        peak_error_relative: (simulated_peak - measured_peak) / measured_peak,
        rms_error_over_peak: rms / measured_peak,
        frequency_measured_hz: rm.frequency_hz,
        frequency_simulated_hz: rs.frequency_hz,
        frequency_difference_hz: rs.frequency_hz - rm.frequency_hz,
        log_decrement_measured: rm.log_decrement,
        log_decrement_simulated: rs.log_decrement,
        log_decrement_difference: rs.log_decrement - rm.log_decrement,
    })
}

/// The static SI unit of a column already converted by [`Measured::to_si`].
fn unit_of(unit: &str) -> &'static str {
    ["m/s^2", "N*m", "Pa", "rad", "rad/s", "rad/s^2", "m", "m/s", "N"].into_iter().find(|u| *u == unit).unwrap_or("")
}

/// The comparison as a text table, one signal a row.
pub fn table(c: &Comparison) -> String {
    let shift = c.shift_s.map_or("none".into(), |s| format!("{s:+.4} s (measured late by it)"));
    let mut out = format!("{} against {} ({}), shift {shift}\n", c.scenario, c.measured_file.display(), c.model);
    // As wide as the longest signal's name (`contact_force.arm-<pad>` runs long).
    let width = c.signals.iter().map(|s| s.signal.len()).fold(28, usize::max);
    out += &format!(
        "{:<width$} {:>8} {:>12} {:>12} {:>8} {:>9} {:>16} {:>20}\n",
        "signal", "unit", "peak meas", "peak sim", "error", "rms/peak", "f meas/sim Hz", "log dec meas/sim"
    );
    for s in &c.signals {
        out += &format!(
            "{:<width$} {:>8} {:>12.5e} {:>12.5e} {:>7.2}% {:>8.2}% {:>7.3} / {:<7.3} {:>9.4} / {:<9.4}\n",
            s.signal,
            s.unit,
            s.peak_measured,
            s.peak_simulated,
            100.0 * s.peak_error_relative,
            100.0 * s.rms_error_over_peak,
            s.frequency_measured_hz,
            s.frequency_simulated_hz,
            s.log_decrement_measured,
            s.log_decrement_simulated
        );
    }
    out
}

/// Writes the comparison as JSON to `path`, under a temporary name renamed when complete.
pub fn write_json(path: &Path, comparison: &Comparison) -> Result<(), CompareError> {
    let error = |message: String| CompareError::Write { path: path.into(), message };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| error(e.to_string()))?;
    }
    let text = serde_json::to_string_pretty(comparison).map_err(|e| error(e.to_string()))?;
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text).map_err(|e| error(e.to_string()))?;
    std::fs::rename(&tmp, path).map_err(|e| error(e.to_string()))
}
