//! The seed paper's experiment matrix (§3.1–3.4): scenario families under `scenarios/seed/`,
//! run in parallel, charted in the style of the paper's figures, and the quantities its trends
//! speak of. `pipearm seed [SECTION]`; results in `docs/seed-experiments.md`.

use std::path::{Path, PathBuf};

use plotters::prelude::*;
use rayon::prelude::*;

use crate::run::{RunOptions, RunSummary, Series, run_compiled};
use crate::scenario::Scenario;
use crate::scene::SceneError;

/// One variant of a family, run.
pub struct Variant {
    /// File stem (`uniform`, `10s`, ...).
    pub name: String,
    /// The scenario.
    pub scenario: Scenario,
    /// Its summary.
    pub summary: RunSummary,
    /// Its series.
    pub series: Series,
}

/// The families under `root`: (section, variant files), sorted.
pub fn sections(root: &Path) -> std::io::Result<Vec<(String, Vec<PathBuf>)>> {
    let mut out = Vec::new();
    for dir in std::fs::read_dir(root)? {
        let dir = dir?.path();
        if !dir.is_dir() {
            continue;
        }
        let files = crate::scenario::scenario_files(&dir)?;
        out.push((dir.file_name().unwrap_or_default().to_string_lossy().into_owned(), files));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

/// Errors running a family.
#[derive(Debug, thiserror::Error)]
pub enum SeedError {
    /// In a scenario.
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    /// In a run.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Writing a chart.
    #[error("chart {path}: {message}")]
    Chart { path: PathBuf, message: String },
}

/// Runs every variant of a family in parallel (each run is deterministic and independent).
pub fn run_family(files: &[PathBuf], capture_frames: bool) -> Result<Vec<Variant>, SeedError> {
    files
        .par_iter()
        .map(|path| {
            let scenario = Scenario::load(path)?;
            let options = RunOptions { capture_frames, ..RunOptions::default() };
            let compiled = scenario.compile(None)?;
            let (summary, series) = run_compiled(&compiled, &options);
            let summary = summary?;
            let name = path.file_stem().unwrap_or_default().to_string_lossy().into_owned();
            Ok(Variant { name, scenario, summary, series })
        })
        .collect()
}

/// A chart in the style of the seed's figures: tip deflection, tip velocity, drive torque and
/// (where there are pads) contact force against time, one curve per variant (SVG).
pub fn chart(path: &Path, title: &str, variants: &[Variant]) -> Result<(), SeedError> {
    let err = |e: &dyn std::fmt::Display| SeedError::Chart { path: path.into(), message: e.to_string() };
    crate::bench::register_font();
    let contact = variants.iter().any(|v| !v.series.pad_force_n.is_empty());
    let panels = if contact { 4 } else { 3 };
    let root = SVGBackend::new(path, (900, 260 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let areas = root.split_evenly((panels, 1));
    type Pick = fn(&Series, usize) -> f64;
    let mut quantities: Vec<(&str, Pick)> = vec![
        ("tip deflection, transverse (mm)", |s, i| 1e3 * s.tip_deflection_m[i][1]),
        ("tip velocity, transverse (mm/s)", |s, i| 1e3 * s.tip_velocity_m_s[i][1]),
        ("drive torque (N·m)", |s, i| s.drive_torque_n_m[i]),
    ];
    if contact {
        quantities.push(("contact force (N)", |s, i| s.pad_force_n.first().map_or(0.0, |f| f[i])));
    }
    for (area, (label, pick)) in areas.iter().zip(quantities) {
        let t_end = variants.iter().map(|v| *v.series.t_s.last().unwrap_or(&1.0)).fold(0.0, f64::max);
        let (lo, hi) = variants
            .iter()
            .flat_map(|v| (0..v.series.t_s.len()).map(move |i| pick(&v.series, i)))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| (lo.min(y), hi.max(y)));
        let pad = 0.05 * (hi - lo).max(1e-9);
        let mut c = ChartBuilder::on(area)
            .caption(format!("{title}: {label}"), ("sans-serif", 16))
            .margin(8)
            .x_label_area_size(28)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))
            .map_err(|e| err(&e))?;
        c.configure_mesh().x_desc("time (s)").draw().map_err(|e| err(&e))?;
        for (k, v) in variants.iter().enumerate() {
            let color = crate::bench::chart::AXIS_COLOURS[k % crate::bench::chart::AXIS_COLOURS.len()];
            // At most about 2000 points a curve: a figure, not the data (the recordings hold it).
            let stride = (v.series.t_s.len() / 2000).max(1);
            let points = v.series.t_s.iter().enumerate().step_by(stride).map(|(i, t)| (*t, pick(&v.series, i)));
            c.draw_series(LineSeries::new(points, color.stroke_width(1)))
                .map_err(|e| err(&e))?
                .label(v.name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
        }
        c.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw().map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))
}

/// The quantities the seed's trends speak of, as a Markdown table row per variant.
pub fn table(variants: &[Variant]) -> String {
    let mut out = String::from(
        "| variant | static w/l | max tip deflection (mm) | residual amplitude (mm) | frequency (Hz) | log decrement | settling (s) | peak torque (N·m) | peak contact force (N) | max w/l |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for v in variants {
        let s = &v.summary;
        let r = &s.residual;
        let force = s.pairs.iter().map(|p| p.peak_force_n).fold(f64::NAN, f64::max);
        out += &format!(
            "| {} | 1/{:.0} | {:.3} | {:.4} | {:.2} | {:.3} | {:.2} | {:.1} | {} | 1/{:.0} |\n",
            v.name,
            1.0 / s.static_w_over_l,
            1e3 * s.max_tip_deflection_m,
            1e3 * r.amplitude_m,
            r.frequency_hz,
            r.log_decrement,
            r.settling_time_s,
            s.peak_drive_torque_n_m,
            if force.is_nan() { "—".to_string() } else { format!("{force:.1}") },
            1.0 / s.max_w_over_l
        );
    }
    out
}
