//! Recordings for the rerun viewer (`.rrd`), written on a `sim_time` timeline.
//!
//! Files are written to a temporary name and renamed when complete, so a failed run leaves no
//! half recording.

use std::path::Path;

use crate::run::{RunSummary, Series};

/// Errors writing a recording.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// From the rerun SDK.
    #[error("recording {path}: {message}")]
    Rerun { path: String, message: String },
    /// Filesystem.
    #[error("recording {path}: {source}")]
    Io { path: String, source: std::io::Error },
}

/// Entity path of a pad's contact force series.
pub fn force_entity(pad: &str) -> String {
    format!("plots/contact_force/arm–{pad}")
}

/// Entity path of the transverse tip deflection series.
pub const TIP_DEFLECTION_ENTITY: &str = "plots/tip_deflection/transverse";

/// Writes the time series of a run to `path` (.rrd).
pub fn write_recording(
    path: &Path,
    summary: &RunSummary,
    series: &Series,
    pad_names: &[String],
) -> Result<(), RecordError> {
    let shown = path.display().to_string();
    let rerun_err = |e: &dyn std::fmt::Display| RecordError::Rerun { path: shown.clone(), message: e.to_string() };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| RecordError::Io { path: shown.clone(), source })?;
    }
    let tmp = path.with_extension("rrd.tmp");
    let rec = rerun::RecordingStreamBuilder::new("pipearm")
        .recording_id(summary.scenario.clone())
        .save(&tmp)
        .map_err(|e| rerun_err(&e))?;
    let times = || rerun::TimeColumn::new_duration_secs("sim_time", series.t_s.iter().copied());
    let send = |entity: &str, values: Vec<f64>| -> Result<(), RecordError> {
        let columns = rerun::Scalars::new(values).columns_of_unit_batches().map_err(|e| rerun_err(&e))?;
        rec.send_columns(entity, [times()], columns).map_err(|e| rerun_err(&e))
    };
    send(TIP_DEFLECTION_ENTITY, series.tip_deflection_m.iter().map(|d| d[1]).collect())?;
    send("plots/drive_torque", series.drive_torque_n_m.clone())?;
    if !series.string_slip_m.is_empty() {
        send("plots/string_slip", series.string_slip_m.clone())?;
    }
    for (name, forces) in pad_names.iter().zip(&series.pad_force_n) {
        send(&force_entity(name), forces.clone())?;
    }
    let text = serde_json::to_string_pretty(summary).map_err(|e| rerun_err(&e))?;
    rec.log_static("summary", &rerun::TextDocument::new(text)).map_err(|e| rerun_err(&e))?;
    rec.flush_blocking().map_err(|e| rerun_err(&e))?;
    drop(rec);
    std::fs::rename(&tmp, path).map_err(|source| RecordError::Io { path: shown.clone(), source })
}

/// Writes the summary as JSON to `path`, atomically.
pub fn write_summary(path: &Path, summary: &RunSummary) -> Result<(), RecordError> {
    let shown = path.display().to_string();
    let io = |source| RecordError::Io { path: shown.clone(), source };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    let tmp = path.with_extension("json.tmp");
    let text = serde_json::to_string_pretty(summary)
        .map_err(|e| RecordError::Rerun { path: shown.clone(), message: e.to_string() })?;
    std::fs::write(&tmp, text).map_err(io)?;
    std::fs::rename(&tmp, path).map_err(io)
}
