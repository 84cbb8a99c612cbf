//! Recordings for the rerun viewer (`.rrd`), on a `sim_time` timeline, with a blueprint that
//! opens the 3D scene beside the time series.
//!
//! Layout of a recording:
//!
//! | entity | what |
//! |---|---|
//! | `world/…` | 3D: hub, arm elements, hand, gripper, jaws, string, pads, ground (boxes, m, Y up) |
//! | `world/centreline_x<M>` | the deformed centreline with its deflection magnified M times |
//! | `world/contact_force_<S>N_per_m` | contact points and force arrows, S newtons per metre of arrow |
//! | `plots/contact_force/arm-<pad>` | contact force per pair, N |
//! | `plots/tip_deflection/{axial,transverse}` | tip displacement in the hub frame, m |
//! | `plots/tip_velocity/{axial,transverse}` | tip velocity in the hub frame, m/s |
//! | `plots/hub/{angle_deg,rate_deg_s,accel_deg_s2}` | hub motion |
//! | `plots/drive_torque` | N·m |
//! | `plots/modal/q<i>` | elastic coordinates (modal models) |
//! | `plots/energy/{kinetic,strain,gravity}` | J |
//! | `plots/string_slip` | friction clamp slip, m |
//! | `plots/sensors/<sensor>/<channel>` | each sensor's channels, SI (`crate::sensor`) |
//! | `events` | impacts (start, peak, end), warnings, the model, the display scales: each at its time |
//! | `summary` | the run summary (JSON) |
//!
//! Steps are kept at the record rate in free motion and every step in contact, and each impact's
//! interpolated peak is inserted at its time in its pad's force series, so no peak is lost and the
//! plot peaks at the summary's figure ([`crate::run::RunOptions`]). Files are written to a temporary name and renamed when
//! complete, so a failed run leaves no half recording.

use std::path::Path;

mod rrd;

pub use rrd::BlueprintLayout;
use rrd::{RrdFile, RrdResult, text};

use crate::run::{PairSummary, RunSummary, Series};
use crate::scene::{Frame, SceneLayout};

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
    format!("plots/contact_force/arm-{pad}")
}

/// Entity path of the transverse tip deflection series.
pub const TIP_DEFLECTION_ENTITY: &str = "plots/tip_deflection/transverse";

/// Display magnification of the deflection: a power of ten that makes the largest tip
/// deflection show as about 2 % of the arm's length (1 if it already does).
pub fn magnification(summary: &RunSummary, length_m: f64) -> f64 {
    let d = summary.max_tip_deflection_m.max(1e-12);
    10f64.powf((0.02 * length_m / d).log10().round()).max(1.0)
}

/// Newtons per metre of force arrow: the power of ten above the largest contact force.
pub fn arrow_scale_n_per_m(summary: &RunSummary) -> f64 {
    let peak = summary.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max).max(1.0);
    10f64.powf(peak.log10().ceil())
}

/// Writes a run to `path` (.rrd).
pub fn write_recording(
    path: &Path,
    summary: &RunSummary,
    series: &Series,
    pad_names: &[String],
) -> Result<(), RecordError> {
    let shown = path.display().to_string();
    let rerun_err = |message: String| RecordError::Rerun { path: shown.clone(), message };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| RecordError::Io { path: shown.clone(), source })?;
    }
    let tmp = path.with_extension("rrd.tmp");
    let file = std::fs::File::create(&tmp).map_err(|source| RecordError::Io { path: shown.clone(), source })?;
    let written = write_rrd(file, summary, series, pad_names);
    if let Err(message) = written {
        std::fs::remove_file(&tmp).ok();
        return Err(rerun_err(message));
    }
    replace(&tmp, path).map_err(|source| RecordError::Io { path: shown.clone(), source })
}

/// Moves the complete file `tmp` to `path`. The old file is removed first: renamed over, ext4
/// (`auto_da_alloc`) starts writing the new file's blocks out inside the rename (3 % of a run's
/// samples in `perf record`), to keep the old file readable until the last instant, which
/// nothing here needs. A crash between the two leaves no file, never a partial one.
fn replace(tmp: &Path, path: &Path) -> std::io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    std::fs::rename(tmp, path)
}

fn write_rrd(file: std::fs::File, summary: &RunSummary, series: &Series, pad_names: &[String]) -> RrdResult<()> {
    let mut writer = Writer { out: RrdFile::create(file, "pipearm", &summary.scenario)?, series };
    writer.plots(pad_names, summary)?;
    let note = series.layout.as_ref().map(|layout| writer.scene(layout, summary)).transpose()?;
    writer.events(summary, note)?;
    let text = serde_json::to_string_pretty(summary).map_err(text)?;
    writer.out.log_static("summary", &rerun::TextDocument::from_markdown(format!("```json\n{text}\n```")))?;
    writer.out.blueprint(&blueprint())?;
    writer.out.finish()
}

/// The view the file opens with: 3D scene left, force / tip deflection / torque right, events
/// below them.
fn blueprint() -> BlueprintLayout {
    let view = |class, name, origin| BlueprintLayout::View { class, name, origin };
    let plots = BlueprintLayout::Vertical(vec![
        view("TimeSeries", "contact force (N)", "plots/contact_force"),
        view("TimeSeries", "tip deflection (m)", "plots/tip_deflection"),
        view("TimeSeries", "drive torque (N·m)", "plots/drive_torque"),
        view("TextLog", "events", "events"),
    ]);
    BlueprintLayout::Horizontal(vec![view("3D", "scene", "world"), plots])
}

struct Writer<'a> {
    out: RrdFile,
    series: &'a Series,
}

impl Writer<'_> {
    /// Times of the kept steps.
    fn kept<T: Copy>(&self, values: impl IntoIterator<Item = T>) -> Vec<T> {
        values.into_iter().zip(&self.series.keep).filter(|(_, k)| **k).map(|(v, _)| v).collect()
    }

    fn send(&mut self, entity: &str, values: impl IntoIterator<Item = f64>) -> RrdResult<()> {
        let times = rerun::TimeColumn::new_duration_secs("sim_time", self.kept(self.series.t_s.iter().copied()));
        let columns = rerun::Scalars::new(self.kept(values)).columns_of_unit_batches().map_err(text)?;
        self.out.send_columns(entity, times, columns)
    }

    /// A pad's force at the kept steps with each impact's interpolated peak (summary) inserted at
    /// its time, so the plotted series peaks at the reported peak.
    fn send_force(&mut self, entity: &str, forces: &[f64], pair: Option<&PairSummary>) -> RrdResult<()> {
        let mut rows: Vec<(f64, f64)> = self.kept(self.series.t_s.iter().copied().zip(forces.iter().copied()));
        let peaks = pair.map_or(&[][..], |p| &p.impacts[..]).iter().map(|i| (i.peak_time_s, i.peak_force_n));
        for (t, f) in peaks.filter(|p| p.0.is_finite()) {
            let at = rows.partition_point(|r| r.0 < t);
            if rows.get(at).is_none_or(|r| r.0 != t) {
                rows.insert(at, (t, f));
            }
        }
        let times = rerun::TimeColumn::new_duration_secs("sim_time", rows.iter().map(|r| r.0));
        let columns = rerun::Scalars::new(rows.iter().map(|r| r.1)).columns_of_unit_batches().map_err(text)?;
        self.out.send_columns(entity, times, columns)
    }

    fn plots(&mut self, pad_names: &[String], summary: &RunSummary) -> RrdResult<()> {
        let s = self.series;
        for (k, axis) in ["axial", "transverse"].iter().enumerate() {
            self.send(&format!("plots/tip_deflection/{axis}"), s.tip_deflection_m.iter().map(|d| d[k]))?;
            self.send(&format!("plots/tip_velocity/{axis}"), s.tip_velocity_m_s.iter().map(|d| d[k]))?;
        }
        self.send("plots/hub/angle_deg", s.hub_angle_rad.iter().map(|a| a.to_degrees()))?;
        self.send("plots/hub/rate_deg_s", s.hub_rate_rad_s.iter().map(|a| a.to_degrees()))?;
        self.send("plots/hub/accel_deg_s2", s.hub_accel_rad_s2.iter().map(|a| a.to_degrees()))?;
        self.send("plots/drive_torque", s.drive_torque_n_m.iter().copied())?;
        for (k, name) in ["kinetic", "strain", "gravity"].iter().enumerate() {
            self.send(&format!("plots/energy/{name}"), s.energies_j.iter().map(|e| e[k]))?;
        }
        for i in 0..s.modal_dofs {
            self.send(&format!("plots/modal/q{}", i + 1), s.modal_q.iter().skip(i).step_by(s.modal_dofs).copied())?;
        }
        if !s.string_slip_m.is_empty() {
            self.send("plots/string_slip", s.string_slip_m.iter().copied())?;
        }
        for (k, (name, forces)) in pad_names.iter().zip(&s.pad_force_n).enumerate() {
            self.send_force(&force_entity(name), forces, summary.pairs.get(k))?;
        }
        for sensor in &s.sensors {
            for (k, channel) in sensor.sensor.kind.channels().iter().enumerate() {
                let entity = crate::compare::sensor_entity(&sensor.sensor.name, channel.name);
                self.send(&entity, sensor.values.iter().map(|v| v[k]))?;
            }
        }
        Ok(())
    }

    /// The 3D scene; returns the note on its display scales for the events.
    fn scene(&mut self, layout: &SceneLayout, summary: &RunSummary) -> RrdResult<String> {
        let out = &mut self.out;
        out.log_static("world", &rerun::ViewCoordinates::RIGHT_HAND_Y_UP())?;
        // Sized to the arm (15 × 10 m for the 9 m arm), so a lab arm is not lost on a rig's floor.
        let l = layout.length_m as f32;
        let half = (5.0 / 3.0 * l, 0.05 / 9.0 * l, 5.0 / 9.0 * l);
        out.log_static(
            "world/ground",
            &rerun::Boxes3D::from_centers_and_half_sizes([(0.0, -half.1, 0.0)], [half])
                .with_colors([rerun::Color::from_rgb(90, 90, 90)]),
        )?;
        let magnify = magnification(summary, layout.length_m);
        let scale = arrow_scale_n_per_m(summary);
        let centreline = format!("world/centreline_x{magnify:.0}");
        let arrows = format!("world/contact_force_{scale:.0}N_per_m");
        let note = format!(
            "display: deflection magnified {magnify:.0}x on `{centreline}`; force arrows {scale:.0} N per metre"
        );
        let frames = &self.series.frames;
        let times = || rerun::TimeColumn::new_duration_secs("sim_time", frames.iter().map(|f| f.t_s));
        // One chunk per entity: shapes and poses go in the same columns (send_columns), not a
        // log call per frame, nor a static chunk for the shapes beside the poses — rerun's cost
        // is per chunk (encoding, footer manifest), the repeated half sizes are a few kB.
        for (name, indices) in group_pieces(layout) {
            let entity = format!("world/{name}");
            let half_sizes = frames.iter().flat_map(|_| indices.iter().map(|&i| layout.pieces[i].1.map(|v| v as f32)));
            let centers = frames.iter().flat_map(|f| indices.iter().map(|&i| vec3(f.pieces[i].translation)));
            let quats = frames.iter().flat_map(|f| indices.iter().map(|&i| quat(f.pieces[i].rotation)));
            let columns = rerun::Boxes3D::update_fields()
                .with_half_sizes(half_sizes.collect::<Vec<_>>())
                .with_centers(centers.collect::<Vec<_>>())
                .with_quaternions(quats.collect::<Vec<_>>())
                .columns(std::iter::repeat_n(indices.len(), frames.len()))
                .map_err(text)?;
            out.send_columns(&entity, times(), columns)?;
        }
        let pads = || frames.iter().flat_map(|f| f.pads.iter().zip(&layout.pads));
        let columns = rerun::Boxes3D::update_fields()
            .with_half_sizes(pads().map(|(_, p)| p.1.map(|v| v as f32)).collect::<Vec<_>>())
            .with_labels(pads().map(|(_, p)| p.0.clone()).collect::<Vec<_>>())
            .with_colors(pads().map(|_| rerun::Color::from_rgb(40, 40, 40)).collect::<Vec<_>>())
            .with_centers(pads().map(|(pose, _)| vec3(pose.translation)).collect::<Vec<_>>())
            .with_quaternions(pads().map(|(pose, _)| quat(pose.rotation)).collect::<Vec<_>>())
            .columns(std::iter::repeat_n(layout.pads.len(), frames.len()))
            .map_err(text)?;
        // The fill mode is one value per row, not per box: its own partition, the same chunk.
        let fill_rows = std::iter::repeat_n(rerun::FillMode::Solid, frames.len()).collect::<Vec<_>>();
        let fill =
            rerun::Boxes3D::update_fields().with_many_fill_mode(fill_rows).columns_of_unit_batches().map_err(text)?;
        out.send_columns("world/pads", times(), columns.chain(fill))?;
        let strips: Vec<Vec<[f32; 3]>> = frames.iter().map(|f| centreline_points(layout, f, magnify)).collect();
        let columns = rerun::LineStrips3D::update_fields()
            .with_strips(strips)
            .columns(std::iter::repeat_n(1, frames.len()))
            .map_err(text)?;
        out.send_columns(&centreline, times(), columns)?;
        let origins: Vec<[f32; 3]> =
            frames.iter().flat_map(|f| f.contacts.iter().map(|c| c.1.map(|v| v as f32))).collect();
        let vectors: Vec<[f32; 3]> = frames
            .iter()
            .flat_map(|f| f.contacts.iter().map(|c| [(c.2[0] / scale) as f32, (c.2[1] / scale) as f32, 0.0]))
            .collect();
        let red = std::iter::repeat_n(rerun::Color::from_rgb(220, 40, 40), origins.len()).collect::<Vec<_>>();
        let columns = rerun::Arrows3D::update_fields()
            .with_colors(red)
            .with_origins(origins)
            .with_vectors(vectors)
            .columns(frames.iter().map(|f| f.contacts.len()))
            .map_err(text)?;
        out.send_columns(&arrows, times(), columns)?;
        Ok(note)
    }

    /// The events at their times: impacts, warnings, the model, the display `note`. (Not static:
    /// a static text log on `events` would shadow every timed one in the viewer.)
    fn events(&mut self, summary: &RunSummary, note: Option<String>) -> RrdResult<()> {
        let mut events: Vec<(f64, String, &str)> = Vec::new();
        for pair in &summary.pairs {
            for (k, i) in pair.impacts.iter().enumerate() {
                let n = k + 1;
                events.push((i.start_s, format!("{}: impact {n} starts", pair.pair), rerun::TextLogLevel::INFO));
                events.push((
                    i.peak_time_s,
                    format!("{}: impact {n} peak {:.1} N", pair.pair, i.peak_force_n),
                    rerun::TextLogLevel::INFO,
                ));
                events.push((
                    i.end_s,
                    format!(
                        "{}: impact {n} ends after {:.1} ms, impulse {:.3} N·s",
                        pair.pair,
                        1e3 * i.duration_s(),
                        i.impulse_n_s
                    ),
                    rerun::TextLogLevel::INFO,
                ));
            }
        }
        if let Some(slip) = &summary.string_slip
            && slip.max_slip_m > 1e-3
        {
            let message = format!("the string slipped {:.1} mm in the jaws", 1e3 * slip.max_slip_m);
            events.push((summary.simulated_s, message, rerun::TextLogLevel::WARN));
        }
        let limit = summary.stability_limit_omega_dt;
        if let Some(limit) = limit.filter(|l| summary.highest_omega_dt > 0.8 * l) {
            let message = format!(
                "near instability: ω_max·dt = {:.3} against the explicit integrator's limit {limit:.3}",
                summary.highest_omega_dt
            );
            events.push((0.0, message, rerun::TextLogLevel::WARN));
        }
        if summary.static_w_over_l > 1.0 / 250.0 {
            events.push((
                0.0,
                format!("static w/l {:.5}: {}", summary.static_w_over_l, summary.stiffness_class),
                rerun::TextLogLevel::WARN,
            ));
        }
        events.push((0.0, format!("model {}: {}", summary.model, summary.stiffness_class), rerun::TextLogLevel::INFO));
        events.extend(note.map(|note| (0.0, note, rerun::TextLogLevel::INFO)));
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        // One chunk: a row per event at its time on `sim_time` (nanoseconds, as `TimeColumn` rounds).
        let logs: Vec<(f64, rerun::TextLog)> =
            events.into_iter().map(|(t, message, level)| (t, rerun::TextLog::new(message).with_level(level))).collect();
        let rows = logs.iter().map(|(t, log)| {
            let time = rerun::TimePoint::from([(rerun::Timeline::new_duration("sim_time"), nanos(*t))]);
            (time, log as &dyn rerun::AsComponents)
        });
        self.out.log_rows("events", rows)
    }
}

/// Piece indices grouped by name, in first-seen order (all elements of the arm in one entity).
fn group_pieces(layout: &SceneLayout) -> Vec<(String, Vec<usize>)> {
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, (name, _)) in layout.pieces.iter().enumerate() {
        match groups.iter_mut().find(|g| &g.0 == name) {
            Some(g) => g.1.push(i),
            None => groups.push((name.clone(), vec![i])),
        }
    }
    groups
}

fn centreline_points(layout: &SceneLayout, frame: &Frame, magnify: f64) -> Vec<[f32; 3]> {
    let (s, c) = frame.hub_angle_rad.sin_cos();
    let p = layout.pivot_m;
    frame
        .centreline
        .iter()
        .map(|(x, [u, v])| {
            let (bx, by) = (x + magnify * u, magnify * v);
            [(p[0] + c * bx - s * by) as f32, (p[1] + s * bx + c * by) as f32, p[2] as f32]
        })
        .collect()
}

/// Seconds to the nanoseconds of a duration timeline, rounded as `TimeColumn::new_duration_secs` does.
fn nanos(t_s: f64) -> rerun::TimeCell {
    rerun::TimeCell::from_duration_nanos((1e9 * t_s).round() as i64)
}

fn vec3(v: rapier3d_f64::math::Vector) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

fn quat(q: rapier3d_f64::math::Rotation) -> rerun::Quaternion {
    rerun::Quaternion::from_xyzw([q.x as f32, q.y as f32, q.z as f32, q.w as f32])
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
    replace(&tmp, path).map_err(io)
}
