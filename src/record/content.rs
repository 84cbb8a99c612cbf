//! What a recording holds, as rerun chunks whatever carries them to a file or a viewer: the
//! plots, the 3D scene, the events and (for a finished run) the summary. Layout in the module
//! above.

use std::borrow::Cow;

use rerun::log::{Chunk, RowId};
use rerun::{RecordingStreamResult, TextLogLevel, TimeColumn};

use super::writer::{Writer, centreline_points, from_first_row};
use super::{CENTRELINE_ENTITY, CONTACT_FORCE_ENTITY, Ending, PIECES_ENTITY, Recorded};
use crate::channel::{Channel, Plot, Reading};
use crate::contact::{Impact, ImpactTracker};
use crate::model::StructureShape;
use crate::scene::{Frame, SceneLayout};

/// Display magnification of the deflection: a power of ten that makes the largest tip
/// deflection `max_tip_deflection_m` (m) show as about 2 % of the arm's length `length_m` (m)
/// (1 if it already does).
pub fn magnification(max_tip_deflection_m: f64, length_m: f64) -> f64 {
    let d = max_tip_deflection_m.max(1e-12);
    10f64.powf((0.02 * length_m / d).log10().round()).max(1.0)
}

/// Newtons per metre of force arrow: the power of ten above the largest contact force `peak_n` (N).
pub fn arrow_scale_n_per_m(peak_n: f64) -> f64 {
    10f64.powf(peak_n.max(1.0).log10().ceil())
}

/// The chunks of `run`, one per entity (two for named series, [`Writer::send_named`]), each
/// handed to `out` as it is made.
pub(super) fn chunks(run: &Recorded, out: &mut dyn FnMut(Chunk)) -> RecordingStreamResult<()> {
    let pairs = pairs(run);
    let mut keep = Cow::Borrowed(&run.series.keep[..]);
    if matches!(run.ending, Ending::Diverged { .. })
        && let Some(last) = keep.to_mut().last_mut()
    {
        // The plots run up to the last step the guard passed, whatever the record rate.
        *last = true;
    }
    let mut writer = Writer { out, run, keep: &keep };
    writer.plots(&pairs)?;
    let note = run.series.layout.as_ref().map(|layout| writer.scene(layout, &pairs)).transpose()?;
    writer.events(&pairs, note)?;
    if let Ending::Finished(summary) = run.ending {
        let text = serde_json::to_string_pretty(summary).expect("a summary serializes");
        writer.log_static("summary", &rerun::TextDocument::from_markdown(format!("```json\n{text}\n```")))?;
    }
    // The name the viewer lists the recording under.
    writer.log_static("__properties", &rerun::RecordingInfo::update_fields().with_name(recording_name(run)))?;
    run.overlay.iter().cloned().for_each(writer.out);
    Ok(())
}

/// What the viewer lists a recording as: its scenario, model and largest peak force, or where it
/// diverged.
fn recording_name(run: &Recorded) -> String {
    match run.ending {
        Ending::Finished(summary) => {
            let peak = summary.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max);
            format!("{} — {}, peak {peak:.1} N", summary.scenario, summary.model)
        }
        Ending::Diverged { scenario, t_s, .. } => format!("{scenario} — diverged at {t_s:.3} s"),
    }
}

/// A contact pair's label (`arm-<pad>`) and impacts: the summary's, or for a diverged run those
/// of its force series so far.
type Pair = (String, Vec<Impact>);

fn pairs(run: &Recorded) -> Vec<Pair> {
    match run.ending {
        Ending::Finished(summary) => summary.pairs.iter().map(|p| (p.pair.clone(), p.impacts.clone())).collect(),
        Ending::Diverged { .. } => run
            .series
            .pair_names
            .iter()
            .zip(&run.series.pad_force_n)
            .map(|(name, forces)| {
                let mut tracker = ImpactTracker::default();
                run.series.t_s.iter().zip(forces).for_each(|(t, f)| tracker.push(*t, *f));
                (name.clone(), tracker.impacts())
            })
            .collect(),
    }
}

impl Writer<'_> {
    /// A pad's force at the kept steps with each impact's interpolated peak inserted at its
    /// time, so the plotted series peaks at the reported peak.
    fn send_force(&mut self, entity: &str, forces: &[f64], impacts: &[Impact]) -> RecordingStreamResult<()> {
        let mut rows: Vec<(f64, f64)> = self.kept(self.run.series.t_s.iter().copied().zip(forces.iter().copied()));
        let peaks = impacts.iter().map(|i| (i.peak_time_s, i.peak_force_n));
        for (t, f) in peaks.filter(|p| p.0.is_finite()) {
            let at = rows.partition_point(|r| r.0 < t);
            if rows.get(at).is_none_or(|r| r.0 != t) {
                rows.insert(at, (t, f));
            }
        }
        let times = TimeColumn::new_duration_secs("sim_time", rows.iter().map(|r| r.0));
        let columns = rerun::Scalars::new(rows.iter().map(|r| r.1)).columns_of_unit_batches()?;
        self.send_columns(entity, times, columns)
    }

    /// Every plotted channel as its producer declares it ([`crate::channel`]): a contact force
    /// with its impacts' peaks, the traces of a shared entity together, the rest an entity
    /// each; then the sign-off's.
    fn plots(&mut self, pairs: &[Pair]) -> RecordingStreamResult<()> {
        let s = self.run.series;
        let plotted: Vec<(&Channel, &Plot)> =
            s.channels.iter().filter_map(|c| c.plot.as_ref().map(|plot| (c, plot))).collect();
        let mut rest = &plotted[..];
        while let Some(&(channel, plot)) = rest.first() {
            let shared = |(_, p): &&(&Channel, &Plot)| p.entity == plot.entity && p.trace.is_some();
            let width = if plot.trace.is_some() { rest.iter().take_while(shared).count() } else { 1 };
            let (group, next) = rest.split_at(width);
            rest = next;
            match channel.reading() {
                Reading::ContactForce(pair) => {
                    let impacts = pairs.get(pair).map_or(&[][..], |p| &p.1[..]);
                    self.send_force(&plot.entity, &s.pad_force_n[pair], impacts)?;
                }
                _ if plot.trace.is_some() => {
                    let names: Vec<String> = group.iter().filter_map(|(_, p)| p.trace.clone()).collect();
                    let value = |k, i: usize| s.value(group[i].0.reading(), k) * group[i].1.scale;
                    self.send_named(&plot.entity, &names, value)?;
                }
                reading => self.send_kept(&plot.entity, |k| s.value(reading, k) * plot.scale)?,
            }
        }
        self.sign_off_plots(super::stress::Shading::of(self.run).as_ref())
    }

    /// The 3D scene; returns the note on its display scales for the events.
    fn scene(&mut self, layout: &SceneLayout, pairs: &[Pair]) -> RecordingStreamResult<String> {
        let run = self.run;
        self.log_static("world", &rerun::ViewCoordinates::RIGHT_HAND_Y_UP())?;
        // Sized to the arm (15 × 10 m for the 9 m arm), so a lab arm is not lost on a rig's floor.
        let l = layout.length_m as f32;
        let half = (5.0 / 3.0 * l, 0.05 / 9.0 * l, 5.0 / 9.0 * l);
        self.log_static(
            "world/ground",
            &rerun::Boxes3D::from_centers_and_half_sizes([(0.0, -half.1, 0.0)], [half])
                .with_colors([rerun::Color::from_rgb(90, 90, 90)]),
        )?;
        let max_deflection = run.series.tip_deflection_m.iter().map(|d| d[1].abs()).fold(0.0, f64::max);
        let magnify = magnification(max_deflection, layout.length_m);
        let peak = pairs.iter().flat_map(|p| &p.1).map(|i| i.peak_force_n).fold(0.0, f64::max);
        let scale = arrow_scale_n_per_m(peak);
        // Fixed entity paths, so that saved layouts and comparisons hold between runs; the display
        // scales, which follow each run's deflection and peak force, are stated in the events.
        let (centreline, arrows) = (CENTRELINE_ENTITY, CONTACT_FORCE_ENTITY);
        let note = format!(
            "display: deflection magnified {magnify:.0}x on `{centreline}`; force arrows on `{arrows}` at {scale:.0} N \
             per metre"
        );
        let frames = &run.series.frames;
        let times = || TimeColumn::new_duration_secs("sim_time", frames.iter().map(|f| f.t_s));
        // Every piece of the machine in one entity, a box each: its poses at every frame, its
        // sizes and colours at the first (they hold for the later ones). rerun's cost is per
        // chunk (encoding, footer manifest), so one chunk for all.
        let per_frame = layout.pieces.len();
        let centers = frames.iter().flat_map(|f| f.pieces.iter().map(|p| vec3(p.translation)));
        let quats = frames.iter().flat_map(|f| f.pieces.iter().map(|p| quat(p.rotation)));
        let poses = rerun::Boxes3D::update_fields()
            .with_centers(centers.collect::<Vec<_>>())
            .with_quaternions(quats.collect::<Vec<_>>())
            .columns(std::iter::repeat_n(per_frame, frames.len()))?;
        let shapes = rerun::Boxes3D::update_fields()
            .with_half_sizes(layout.pieces.iter().map(|p| p.1.map(|v| v as f32)).collect::<Vec<_>>())
            .with_colors(piece_colours(layout))
            .columns([per_frame])?;
        self.send_columns(PIECES_ENTITY, times(), poses.chain(from_first_row(shapes, frames.len())))?;
        let poses = || frames.iter().flat_map(|f| f.pads.iter());
        let columns = rerun::Boxes3D::update_fields()
            .with_centers(poses().map(|pose| vec3(pose.translation)).collect::<Vec<_>>())
            .with_quaternions(poses().map(|pose| quat(pose.rotation)).collect::<Vec<_>>())
            .columns(std::iter::repeat_n(layout.pads.len(), frames.len()))?;
        let shapes = rerun::Boxes3D::update_fields()
            .with_half_sizes(layout.pads.iter().map(|p| p.1.map(|v| v as f32)).collect::<Vec<_>>())
            .with_labels(layout.pads.iter().map(|p| p.0.clone()).collect::<Vec<_>>())
            .with_colors(layout.pads.iter().map(|_| rerun::Color::from_rgb(40, 40, 40)).collect::<Vec<_>>())
            .columns([layout.pads.len()])?;
        // The fill mode is one value for all the boxes, not one per box: a partition of its own.
        let fill = rerun::Boxes3D::update_fields().with_many_fill_mode([rerun::FillMode::Solid]).columns([1])?;
        let columns = columns.chain(from_first_row(shapes.chain(fill), frames.len()));
        self.send_columns("world/pads", times(), columns)?;
        let note = match super::stress::Shading::of(run) {
            Some(shading) => {
                self.shaded_centreline(&shading, layout, magnify)?;
                format!("{note}; {}", shading.note())
            }
            None => {
                let magnified = frames.iter().map(|f| centreline_points(layout, f, magnify));
                let columns = rerun::LineStrips3D::update_fields()
                    .with_strips(magnified.collect::<Vec<_>>())
                    .columns(std::iter::repeat_n(1, frames.len()))?;
                self.send_columns(centreline, times(), columns)?;
                note
            }
        };
        if frames.iter().any(|f| !f.string_centreline.is_empty()) {
            let strips = frames.iter().map(|f| string_points(layout, f));
            let columns = rerun::LineStrips3D::update_fields()
                .with_strips(strips.collect::<Vec<_>>())
                .columns_of_unit_batches()?;
            let style = rerun::LineStrips3D::update_fields()
                .with_colors([rerun::Color::from_rgb(30, 110, 200)])
                .with_radii([rerun::Radius::new_scene_units(0.04)])
                .columns([1])?;
            self.send_columns("world/string", times(), columns.chain(from_first_row(style, frames.len())))?;
        }
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
            .columns(frames.iter().map(|f| f.contacts.len()))?;
        self.send_columns(arrows, times(), columns)?;
        if !layout.cylinders.is_empty() {
            self.cylinders(&layout.cylinders, layout.pivot_m)?;
        }
        self.structures(layout)?;
        Ok(note)
    }

    /// The rig structures, fixed: boxes and cylinders (standing along world z), labelled.
    fn structures(&mut self, layout: &SceneLayout) -> RecordingStreamResult<()> {
        let colour = rerun::Color::from_rgb(150, 120, 60);
        for (name, pose, shape) in &layout.structures {
            let entity = format!("world/structures/{name}");
            match *shape {
                StructureShape::Box { half_extents_m } => self.log_static(
                    &entity,
                    &rerun::Boxes3D::from_centers_and_half_sizes(
                        [vec3(pose.translation)],
                        [half_extents_m.map(|v| v as f32)],
                    )
                    .with_quaternions([quat(pose.rotation)])
                    .with_labels([name.clone()])
                    .with_colors([colour])
                    .with_fill_mode(rerun::FillMode::Solid),
                )?,
                StructureShape::Cylinder { radius_m, half_length_m } => self.log_static(
                    &entity,
                    &rerun::Cylinders3D::from_lengths_and_radii([2.0 * half_length_m as f32], [radius_m as f32])
                        .with_centers([vec3(pose.translation)])
                        .with_labels([name.clone()])
                        .with_colors([colour])
                        .with_fill_mode(rerun::FillMode::Solid),
                )?,
            }
        }
        Ok(())
    }

    /// The lift cylinders between their pins, per frame: barrel (bore) from the base pin, rod
    /// from the arm pin, in the lift plane; two strips per cylinder in one entity.
    fn cylinders(&mut self, cylinders: &[crate::actuator::Cylinder], pivot_m: [f64; 3]) -> RecordingStreamResult<()> {
        let frames = &self.run.series.frames;
        let times = TimeColumn::new_duration_secs("sim_time", frames.iter().map(|f| f.t_s));
        let point = |p: [f64; 2]| [(pivot_m[0] + p[0]) as f32, (pivot_m[1] + p[1]) as f32, pivot_m[2] as f32];
        let strips_of = |c: &crate::actuator::Cylinder, angle_rad: f64| {
            let (base, pin) = (c.base_pin_m, c.arm_pin_at_m(angle_rad));
            let length = (pin[0] - base[0]).hypot(pin[1] - base[1]);
            let along = |from: [f64; 2], to: [f64; 2], d: f64| {
                [from[0] + d / length * (to[0] - from[0]), from[1] + d / length * (to[1] - from[1])]
            };
            let barrel_end = along(base, pin, (0.9 * c.closed_length_m).min(length));
            [vec![point(base), point(barrel_end)], vec![point(along(barrel_end, base, 0.1)), point(pin)]]
        };
        let strips: Vec<Vec<[f32; 3]>> =
            frames.iter().flat_map(|f| cylinders.iter().flat_map(move |c| strips_of(c, f.hub_angle_rad))).collect();
        let radii = frames
            .iter()
            .flat_map(|_| cylinders.iter().flat_map(|c| [0.5 * c.bore_m as f32 + 0.01, 0.5 * c.rod_m as f32]))
            .map(rerun::Radius::new_scene_units)
            .collect::<Vec<_>>();
        let colors = frames
            .iter()
            .flat_map(|_| {
                cylinders
                    .iter()
                    .flat_map(|_| [rerun::Color::from_rgb(200, 160, 40), rerun::Color::from_rgb(210, 210, 220)])
            })
            .collect::<Vec<_>>();
        let columns = rerun::LineStrips3D::update_fields()
            .with_strips(strips)
            .with_radii(radii)
            .with_colors(colors)
            .columns(std::iter::repeat_n(2 * cylinders.len(), frames.len()))?;
        self.send_columns("world/cylinder", times, columns)
    }

    /// The events at their times: impacts, warnings, the model, the display `note`; for a
    /// diverged run, the guard's message last. (Not static: a static text log on `events` would
    /// shadow every timed one in the viewer.)
    fn events(&mut self, pairs: &[Pair], note: Option<String>) -> RecordingStreamResult<()> {
        let mut events: Vec<(f64, String, &str)> = Vec::new();
        for (pair, impacts) in pairs {
            for (k, i) in impacts.iter().enumerate() {
                let n = k + 1;
                events.push((i.start_s, format!("{pair}: impact {n} starts"), TextLogLevel::INFO));
                let peak = format!("{pair}: impact {n} peak {:.1} N", i.peak_force_n);
                events.push((i.peak_time_s, peak, TextLogLevel::INFO));
                let end = format!(
                    "{pair}: impact {n} ends after {:.1} ms, impulse {:.3} N·s",
                    1e3 * i.duration_s(),
                    i.impulse_n_s
                );
                events.push((i.end_s, end, TextLogLevel::INFO));
            }
        }
        if let Ending::Finished(summary) = self.run.ending {
            events.extend(findings(summary));
        }
        events.extend(note.map(|note| (0.0, note, TextLogLevel::INFO)));
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Ending::Diverged { t_s, message, .. } = self.run.ending {
            events.push((t_s, message.to_string(), TextLogLevel::ERROR));
        }
        // One chunk: a row per event at its time on `sim_time` (nanoseconds, as `TimeColumn` rounds).
        let chunk = events
            .into_iter()
            .fold(Chunk::builder("events"), |chunk, (t, message, level)| {
                let time = rerun::TimePoint::from([(rerun::Timeline::new_duration("sim_time"), nanos(t))]);
                chunk.with_archetype(RowId::new(), time, &rerun::TextLog::new(message).with_level(level))
            })
            .build()?;
        (self.out)(chunk);
        Ok(())
    }
}

/// The summary's warnings and its model, as events.
fn findings(summary: &crate::run::RunSummary) -> Vec<(f64, String, &'static str)> {
    let mut events = Vec::new();
    if let Some(slip) = &summary.string_slip
        && slip.max_slip_m > 1e-3
    {
        let message = format!("the string slipped {:.1} mm in the jaws", 1e3 * slip.max_slip_m);
        events.push((summary.simulated_s, message, TextLogLevel::WARN));
    }
    let limit = summary.stability_limit_omega_dt;
    if let Some(limit) = limit.filter(|l| summary.highest_omega_dt > 0.8 * l) {
        let message = format!(
            "near instability: ω_max·dt = {:.3} against the explicit integrator's limit {limit:.3}",
            summary.highest_omega_dt
        );
        events.push((0.0, message, TextLogLevel::WARN));
    }
    if summary.static_w_over_l > 1.0 / 250.0 {
        let message = format!("static w/l {:.5}: {}", summary.static_w_over_l, summary.stiffness_class);
        events.push((0.0, message, TextLogLevel::WARN));
    }
    events.push((0.0, format!("model {}: {}", summary.model, summary.stiffness_class), TextLogLevel::INFO));
    events
}

/// Each piece's colour: one per kind of piece (those of one name: the arm's segments, a hand, a
/// jaw), in the order the kinds first appear, from a palette of distinct hues.
fn piece_colours(layout: &SceneLayout) -> Vec<rerun::Color> {
    const PALETTE: [(u8, u8, u8); 6] =
        [(110, 110, 120), (120, 170, 210), (230, 160, 50), (90, 190, 120), (200, 100, 160), (170, 140, 220)];
    let mut kinds: Vec<&str> = Vec::new();
    layout
        .pieces
        .iter()
        .map(|(name, _)| {
            let kind = kinds.iter().position(|k| k == name).unwrap_or_else(|| {
                kinds.push(name);
                kinds.len() - 1
            });
            let (r, g, b) = PALETTE[kind % PALETTE.len()];
            rerun::Color::from_rgb(r, g, b)
        })
        .collect()
}

/// The held string's deformed centreline at true scale, on its axis off the lift plane.
fn string_points(layout: &SceneLayout, frame: &Frame) -> Vec<[f32; 3]> {
    let (s, c) = frame.hub_angle_rad.sin_cos();
    let p = layout.pivot_m;
    let z = (p[2] + layout.string_normal_offset_m) as f32;
    frame
        .string_centreline
        .iter()
        .map(|[x, y]| [(p[0] + c * x - s * y) as f32, (p[1] + s * x + c * y) as f32, z])
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_scales_are_powers_of_ten() {
        // 18 mm on a 9 m arm: ×10 shows 180 mm, 2 % of the length.
        assert_eq!(magnification(0.018, 9.0), 10.0);
        assert_eq!(magnification(1.0, 9.0), 1.0, "already visible: not shrunk");
        assert_eq!(arrow_scale_n_per_m(1506.3), 1e4);
        assert_eq!(arrow_scale_n_per_m(0.0), 1.0);
    }
}
