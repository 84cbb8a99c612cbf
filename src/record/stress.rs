//! The sign-off in a recording: the centreline shaded by utilisation (by |σ| against the run's
//! peak where no segment has a yield strength) with its legend beside the lift, the peak's
//! station marked, the stress at the worst station against its yield line, and the pin and grip
//! loads. Only a finished run has them: the worst station and the yields come from its summary.

use rerun::{RecordingStreamResult, TimeColumn};

use super::writer::{Writer, centreline_points, from_first_row};
use super::{Ending, Recorded};
use crate::scene::SceneLayout;
use crate::stress::{Fibre, StressSeries};

/// Entity path of the stress at the worst station, Pa.
pub const WORST_STATION_ENTITY: &str = "plots/stress/worst_station";

/// Entity path of the yield line the worst station's stress is plotted against, Pa.
pub const YIELD_ENTITY: &str = "plots/stress/yield";

/// The share of the yield line the worst station's peak |σ| reaches before the line is drawn.
pub const YIELD_DRAWN_FROM: f64 = 0.5;

pub use crate::stress::PINS_ENTITY;

/// Entity path of the peak's marker on the centreline.
pub const PEAK_ENTITY: &str = "world/stress_peak";

/// Entity path of the shading's legend.
pub const LEGEND_ENTITY: &str = "world/stress_legend";

/// How the centreline is shaded: each station's |σ| scaled to 0 (blue) … 1 (red).
pub(super) struct Shading<'a> {
    series: &'a StressSeries,
    /// Per station, the factor taking its |σ| (Pa) to the shade: stress_factor / yield by
    /// utilisation (0 for a segment without a yield strength: grey), else 1 / the run's peak |σ|.
    per_pa: Vec<f64>,
    /// By utilisation (else by |σ|).
    by_utilisation: bool,
    /// |σ| at full scale, Pa (the peak's with no yield: the legend's top).
    full_scale_pa: f64,
    /// The worst station (the largest utilisation's, else the largest |σ|'s) and its fibre.
    worst: (usize, Fibre),
    /// The yield line at the worst station, yield / stress_factor, Pa.
    worst_yield_pa: Option<f64>,
    /// The marker's label.
    label: String,
}

impl<'a> Shading<'a> {
    /// The shading of `run`: `None` for a run without the sign-off, or diverged.
    pub(super) fn of(run: &Recorded<'a>) -> Option<Self> {
        let Ending::Finished(summary) = run.ending else { return None };
        let stress = &summary.sign_off.as_ref()?.stress;
        let series = &run.series.stress;
        if series.stations.is_empty() || series.steps() == 0 {
            return None;
        }
        let by_utilisation = stress.utilisation.is_some();
        let yield_of = |segment: usize| stress.segments.get(segment).and_then(|s| s.yield_strength_pa);
        let full_scale_pa = stress.peak_stress_pa.max(f64::MIN_POSITIVE);
        let per_pa = series
            .stations
            .iter()
            .map(|st| match by_utilisation {
                true => yield_of(st.segment).map_or(0.0, |y| stress.stress_factor / y),
                false => 1.0 / full_scale_pa,
            })
            .collect();
        let (station_m, fibre, time_s) =
            match (stress.utilisation_station_m, stress.utilisation_fibre, stress.utilisation_time_s) {
                (Some(x), Some(f), Some(t)) => (x, f, t),
                _ => (stress.peak_station_m, stress.peak_fibre, stress.peak_time_s),
            };
        let worst = series
            .stations
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1.station_m - station_m).abs().total_cmp(&(b.1.station_m - station_m).abs()))
            .map_or(0, |(i, _)| i);
        let segment = series.stations[worst].segment;
        let worst_yield_pa = yield_of(segment).map(|y| y / stress.stress_factor);
        let peak_mpa = 1e-6 * stress.peak_stress_pa;
        let label = match stress.utilisation {
            Some(u) => format!("utilisation {u:.2} at {station_m:.2} m, {} fibre, {time_s:.3} s", fibre.name()),
            None => format!("peak |σ| {peak_mpa:.1} MPa at {station_m:.2} m, {} fibre, {time_s:.3} s", fibre.name()),
        };
        Some(Shading { series, per_pa, by_utilisation, full_scale_pa, worst: (worst, fibre), worst_yield_pa, label })
    }

    /// The shade of station `i` at step `k`: the larger fibre's |σ| scaled (`None`: no yield).
    fn value(&self, i: usize, k: usize) -> Option<f64> {
        let scale = self.per_pa[i];
        let sigma = Fibre::BOTH.map(|f| self.series.stress_pa(i, f, k).abs());
        (scale > 0.0).then(|| scale * sigma[0].max(sigma[1]))
    }

    /// The events' note on the shading.
    pub(super) fn note(&self) -> String {
        let scale = if self.by_utilisation {
            "utilisation (stress_factor × |σ| / yield; grey: no yield strength)".to_string()
        } else {
            format!("|σ| against the run's peak {:.1} MPa (no yield strength given)", 1e-6 * self.full_scale_pa)
        };
        format!("centreline shaded by {scale}, blue 0 to red 1; `{PEAK_ENTITY}` marks the {}", self.label)
    }
}

/// Shades per unit of the scaled |σ|: the centreline is shaded in steps of 1/`SHADE_STEPS`, so
/// that neighbouring pieces of one shade are drawn as one strip.
const SHADE_STEPS: f64 = 20.0;

/// The shade step of a scaled |σ|, 0 to `SHADE_STEPS` (`None`: no value).
fn shade_step(value: Option<f64>) -> Option<u32> {
    value.map(|v| (v.clamp(0.0, 1.0) * SHADE_STEPS).round() as u32)
}

/// Blue (0), green (0.4), yellow (0.7), red (1 and above); grey for no value.
fn shade(value: Option<f64>) -> rerun::Color {
    const STOPS: [(f64, [f64; 3]); 4] = [
        (0.0, [40.0, 90.0, 220.0]),
        (0.4, [40.0, 180.0, 90.0]),
        (0.7, [235.0, 200.0, 40.0]),
        (1.0, [220.0, 30.0, 30.0]),
    ];
    let Some(v) = value else { return rerun::Color::from_rgb(150, 150, 150) };
    let v = v.clamp(0.0, 1.0);
    let at = STOPS.iter().position(|s| s.0 >= v).unwrap_or(STOPS.len() - 1).max(1);
    let ((v0, c0), (v1, c1)) = (STOPS[at - 1], STOPS[at]);
    let w = (v - v0) / (v1 - v0);
    let [r, g, b] = [0, 1, 2].map(|j| (c0[j] + w * (c1[j] - c0[j])).round() as u8);
    rerun::Color::from_rgb(r, g, b)
}

impl Writer<'_> {
    /// The magnified centreline in pieces between its sampled stations, each shaded by the
    /// largest value of the stress stations on it (the nearest if none is), neighbours of one
    /// shade step drawn as one strip; the peak's marker on it, and the legend.
    pub(super) fn shaded_centreline(
        &mut self,
        shading: &Shading,
        layout: &SceneLayout,
        magnify: f64,
    ) -> RecordingStreamResult<()> {
        let frames = &self.run.series.frames;
        let t = &self.run.series.t_s;
        let steps = shading.series.steps();
        let stations = &shading.series.stations;
        let Some(first) = frames.first() else { return Ok(()) };
        // The stress stations on each piece: fixed, as the sampled stations are.
        let pieces: Vec<Vec<usize>> = first
            .centreline
            .windows(2)
            .map(|w| {
                let (x0, x1) = (w[0].0, w[1].0);
                let on: Vec<usize> =
                    (0..stations.len()).filter(|&i| (x0 - 1e-9..=x1 + 1e-9).contains(&stations[i].station_m)).collect();
                if on.is_empty() {
                    let mid = 0.5 * (x0 + x1);
                    let near = (0..stations.len())
                        .min_by(|&a, &b| {
                            (stations[a].station_m - mid).abs().total_cmp(&(stations[b].station_m - mid).abs())
                        })
                        .unwrap_or(0);
                    vec![near]
                } else {
                    on
                }
            })
            .collect();
        let (mut strips, mut colors, mut per_frame) = (Vec::new(), Vec::new(), Vec::new());
        let mut markers = Vec::new();
        let worst_m = stations[shading.worst.0].station_m;
        for frame in frames {
            let k = t.partition_point(|s| *s < frame.t_s).min(steps - 1);
            let points = centreline_points(layout, frame, magnify);
            let before = strips.len();
            let mut strip: Vec<[f32; 3]> = Vec::new();
            let mut step = None;
            for (w, on) in points.windows(2).zip(&pieces) {
                let here = shade_step(on.iter().filter_map(|&i| shading.value(i, k)).reduce(f64::max));
                if strip.is_empty() || here != step {
                    if !strip.is_empty() {
                        strips.push(std::mem::take(&mut strip));
                        colors.push(shade(step.map(|s| f64::from(s) / SHADE_STEPS)));
                    }
                    strip.push(w[0]);
                    step = here;
                }
                strip.push(w[1]);
            }
            if !strip.is_empty() {
                strips.push(strip);
                colors.push(shade(step.map(|s| f64::from(s) / SHADE_STEPS)));
            }
            per_frame.push(strips.len() - before);
            markers.push(interpolate(&frame.centreline, &points, worst_m));
        }
        let radius = rerun::Radius::new_scene_units(0.006 * layout.length_m as f32);
        let times = || TimeColumn::new_duration_secs("sim_time", frames.iter().map(|f| f.t_s));
        let columns = rerun::LineStrips3D::update_fields()
            .with_radii(vec![radius; strips.len()])
            .with_strips(strips)
            .with_colors(colors)
            .columns(per_frame)?;
        self.send_columns(super::CENTRELINE_ENTITY, times(), columns)?;
        let marker = rerun::Radius::new_scene_units(0.015 * layout.length_m as f32);
        // The marker moves with the arm; its label, colour and size do not: at the first frame,
        // they hold for the later ones.
        let style = rerun::Points3D::update_fields()
            .with_labels([shading.label.clone()])
            .with_colors([rerun::Color::from_rgb(200, 0, 200)])
            .with_radii([marker])
            .columns([1])?;
        let columns = rerun::Points3D::update_fields().with_positions(markers).columns_of_unit_batches()?;
        self.send_columns(PEAK_ENTITY, times(), columns.chain(from_first_row(style, frames.len())))?;
        self.legend(shading, layout)
    }

    /// A colour bar beyond the arm's reach, upper right of the lift's quarter disc, in five
    /// labelled bands.
    fn legend(&mut self, shading: &Shading, layout: &SceneLayout) -> RecordingStreamResult<()> {
        const BANDS: usize = 5;
        let (l, p) = (layout.length_m, layout.pivot_m);
        let (x, y0, h) = (p[0] + 1.05 * l, p[1] + 0.5 * l, 0.09 * l);
        let point = |y: f64| [x as f32, y as f32, p[2] as f32];
        let strips: Vec<Vec<[f32; 3]>> =
            (0..BANDS).map(|b| vec![point(y0 + h * b as f64), point(y0 + h * (b + 1) as f64)]).collect();
        let colors: Vec<rerun::Color> = (0..BANDS).map(|b| shade(Some((b as f64 + 0.5) / BANDS as f64))).collect();
        let labels: Vec<String> = (0..BANDS)
            .map(|b| {
                let (lo, hi) = (b as f64 / BANDS as f64, (b + 1) as f64 / BANDS as f64);
                match (shading.by_utilisation, b) {
                    (true, 0) => format!("utilisation {lo:.1}–{hi:.1}"),
                    (true, b) if b == BANDS - 1 => format!("{lo:.1}–{hi:.1} (yield)"),
                    (true, _) => format!("{lo:.1}–{hi:.1}"),
                    (false, b) => {
                        let mpa = 1e-6 * shading.full_scale_pa;
                        let prefix = if b == 0 { "|σ| " } else { "" };
                        format!("{prefix}{:.0}–{:.0} MPa", lo * mpa, hi * mpa)
                    }
                }
            })
            .collect();
        let radius = rerun::Radius::new_scene_units(0.02 * l as f32);
        let legend = rerun::LineStrips3D::new(strips).with_colors(colors).with_labels(labels).with_radii([radius]);
        self.log_static(LEGEND_ENTITY, &legend)
    }

    /// The stress at the worst station against its yield line (the pin and grip loads are
    /// channels of the sign-off's, [`crate::stress::StressSeries::channels`]).
    pub(super) fn sign_off_plots(&mut self, shading: Option<&Shading>) -> RecordingStreamResult<()> {
        let series = &self.run.series.stress;
        let steps = series.steps();
        if steps == 0 {
            return Ok(());
        }
        if let Some(shading) = shading {
            let (i, fibre) = shading.worst;
            // The kept steps and the peak's, so that the plot reaches the summary's figure.
            let sigma: Vec<f64> = (0..steps).map(|k| series.stress_pa(i, fibre, k)).collect();
            let peak = (0..steps).max_by(|&a, &b| sigma[a].abs().total_cmp(&sigma[b].abs())).unwrap_or(0);
            // A yield line far above the trace flattens it: drawn from half the yield up, else
            // named beside the trace.
            let drawn_yield_pa = shading.worst_yield_pa.filter(|&y| sigma[peak].abs() >= YIELD_DRAWN_FROM * y);
            let mut name = format!("σ at {:.2} m, {} fibre", series.stations[i].station_m, fibre.name());
            if let (Some(y), None) = (shading.worst_yield_pa, drawn_yield_pa) {
                name += &format!(" (yield / stress_factor {:.0} MPa, off the scale)", 1e-6 * y);
            }
            let t = &self.run.series.t_s;
            let rows: Vec<usize> = (0..steps).filter(|&k| k == peak || self.keeps(k)).collect();
            let times = TimeColumn::new_duration_secs("sim_time", rows.iter().map(|&k| t[k]));
            let columns = rerun::Scalars::new(rows.iter().map(|&k| sigma[k])).columns_of_unit_batches()?;
            let named =
                from_first_row(rerun::SeriesLines::update_fields().with_names([name]).columns([1])?, rows.len());
            self.send_columns(WORST_STATION_ENTITY, times, columns.chain(named))?;
            if let Some(yield_pa) = drawn_yield_pa {
                // Two points each: a constant needs no more.
                let t = &self.run.series.t_s;
                let ends = [t[0], t[t.len() - 1]];
                for (side, sign) in [("tension", 1.0), ("compression", -1.0)] {
                    let entity = format!("{YIELD_ENTITY}/{side}");
                    let style = rerun::SeriesLines::update_fields()
                        .with_names([format!("yield / stress_factor ({side})")])
                        .with_colors([rerun::Color::from_rgb(220, 30, 30)])
                        .columns([1])?;
                    let times = TimeColumn::new_duration_secs("sim_time", ends);
                    let columns = rerun::Scalars::new([sign * yield_pa; 2]).columns_of_unit_batches()?;
                    self.send_columns(&entity, times, columns.chain(from_first_row(style, ends.len())))?;
                }
            }
        }
        Ok(())
    }
}

/// The point at station `x_m` on the drawn centreline `points` sampled at `centreline`'s stations.
fn interpolate(centreline: &[(f64, [f64; 2])], points: &[[f32; 3]], x_m: f64) -> [f32; 3] {
    let at = centreline.partition_point(|c| c.0 < x_m).clamp(1, points.len().max(2) - 1);
    let (x0, x1) = (centreline[at - 1].0, centreline[at].0);
    let w = if x1 > x0 { ((x_m - x0) / (x1 - x0)).clamp(0.0, 1.0) as f32 } else { 0.0 };
    let (a, b) = (points[at - 1], points[at]);
    [0, 1, 2].map(|j| a[j] + w * (b[j] - a[j]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shades_step_by_a_twentieth_and_run_blue_to_red_and_grey_without_a_value() {
        assert_eq!(shade_step(Some(0.52)), Some(10));
        assert_eq!(shade_step(Some(0.53)), Some(11));
        assert_eq!(shade_step(Some(4.0)), Some(20));
        assert_eq!(shade_step(None), None);
        assert_eq!(shade(Some(0.0)), rerun::Color::from_rgb(40, 90, 220));
        assert_eq!(shade(Some(1.0)), rerun::Color::from_rgb(220, 30, 30));
        assert_eq!(shade(Some(3.0)), shade(Some(1.0)), "above yield stays red");
        assert_eq!(shade(Some(0.4)), rerun::Color::from_rgb(40, 180, 90));
        assert_eq!(shade(None), rerun::Color::from_rgb(150, 150, 150));
    }
}
