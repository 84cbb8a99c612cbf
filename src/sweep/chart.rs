//! The sweep's chart: peak contact force (the largest over the contact pairs, N) against the
//! string's mass (the payload's, kg), each point labelled with the string's catalogue entry
//! (`9-5/8@47.00`), one curve per combination of the varied keys outside `payload.` (SVG).
//! [`compare`] draws several sweeps' curves on the same axes, each under its own label
//! (`pipearm sweep chart`).

use std::path::Path;

use plotters::prelude::*;

use super::SweepError;
use super::plan::Plan;
use super::row::{Row, cell};
use crate::robot::pipes::ENTRY_SEPARATOR;

/// One point: the payload's mass (kg), the largest peak contact force (N), and what the string
/// is (its entry; empty without a catalogue string).
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Payload mass, kg.
    pub kg: f64,
    /// Largest peak contact force over the pairs, N.
    pub force_n: f64,
    /// The string's catalogue entry (`9-5/8@47.00`), its size alone, or empty.
    pub label: String,
}

/// One curve: its label and its points, by mass.
pub type Curve = (String, Vec<Point>);

/// The curves of the chart, in the order their first case comes in the plan. Cases without a
/// contact pair have no peak force and are left out.
pub fn curves(plan: &Plan, rows: &[Row]) -> Vec<Curve> {
    let others: Vec<&str> = plan.keys().into_iter().filter(|k| !k.starts_with("payload.")).collect();
    let mut curves: Vec<Curve> = Vec::new();
    for (case, row) in plan.cases.iter().zip(rows) {
        let Some(point) = point(row) else { continue };
        let label = if others.is_empty() { "all cases".to_string() } else { case.describe(&others) };
        match curves.iter_mut().find(|(l, _)| *l == label) {
            Some((_, points)) => points.push(point),
            None => curves.push((label, vec![point])),
        }
    }
    for (_, points) in &mut curves {
        points.sort_by(|a, b| a.kg.total_cmp(&b.kg));
    }
    curves
}

/// A case's point.
fn point(row: &Row) -> Option<Point> {
    let kg = row.get("summary.payload_kg")?.as_f64()?;
    let force_n = row.largest_peak_force_n("summary.")?;
    Some(Point { kg, force_n, label: string_label(row, "summary.") })
}

/// What the string of a summary at `prefix` is, as an entry (`9-5/8@47.00`): its size and
/// nominal weight (its size alone for a pipe of the user's own; empty without a string).
pub fn string_label(row: &Row, prefix: &str) -> String {
    let size = row.get(&format!("{prefix}string.size")).map(cell).unwrap_or_default();
    match row.get(&format!("{prefix}string.weight_lb_ft")).and_then(|w| w.as_f64()) {
        Some(w) => format!("{size}{ENTRY_SEPARATOR}{w:.2}"),
        None => size,
    }
}

/// Draws the chart of one sweep to `path`.
pub fn force_vs_weight(path: &Path, plan: &Plan, rows: &[Row]) -> Result<(), SweepError> {
    // The scenario's name from the results, not the plan's path: shards may name the file differently.
    let name = rows.first().and_then(|r| r.get("summary.scenario")).map(cell).unwrap_or_default();
    draw(path, &format!("{name}: peak contact force against string weight"), &curves(plan, rows))
}

/// Draws the curves of several sweeps on the same axes to `path`, each sweep's curves labelled
/// `label` (or `label: key=value, ...` when the sweep varies more than the payload).
pub fn compare(path: &Path, caption: &str, sweeps: &[(String, Plan, Vec<Row>)]) -> Result<(), SweepError> {
    let labelled: Vec<Curve> = sweeps
        .iter()
        .flat_map(|(label, plan, rows)| {
            let own = curves(plan, rows);
            let single = own.len() == 1;
            own.into_iter()
                .map(move |(l, points)| (if single { label.clone() } else { format!("{label}: {l}") }, points))
        })
        .collect();
    draw(path, caption, &labelled)
}

/// Draws `curves` under `caption` to `path`: a polyline with dots per curve, each dot labelled
/// with its string, and a legend.
fn draw(path: &Path, caption: &str, curves: &[Curve]) -> Result<(), SweepError> {
    let err = |e: &dyn std::fmt::Display| SweepError::Chart { path: path.into(), message: e.to_string() };
    let points = || curves.iter().flat_map(|(_, p)| p.iter());
    let (x_lo, x_hi) = padded(points().map(|p| p.kg), false);
    // Headroom above the highest point for the legend, a line per curve.
    let (_, y_hi) = padded(points().map(|p| p.force_n), true);
    let y_hi = y_hi * (1.0 + 0.06 * curves.len() as f64);
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    let mut chart = force_weight_axes(&root, caption, x_lo..x_hi, y_hi).map_err(|e| err(&e))?;
    for (k, (label, points)) in curves.iter().enumerate() {
        let color = crate::bench::chart::AXIS_COLOURS[k % crate::bench::chart::AXIS_COLOURS.len()];
        let xy: Vec<(f64, f64)> = points.iter().map(|p| (p.kg, p.force_n)).collect();
        chart
            .draw_series(LineSeries::new(xy.iter().copied(), color.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label(label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2)));
        chart.draw_series(xy.iter().map(|p| Circle::new(*p, 3, color.filled()))).map_err(|e| err(&e))?;
    }
    // Each string once, above its highest point: the curves share their strings.
    let mut labels: Vec<(f64, f64, &str)> = Vec::new();
    for p in points() {
        match labels.iter_mut().find(|l| l.2 == p.label) {
            Some(l) if l.1 < p.force_n => *l = (p.kg, p.force_n, p.label.as_str()),
            Some(_) => {}
            None => labels.push((p.kg, p.force_n, p.label.as_str())),
        }
    }
    label_points(&mut chart, &labels, y_hi).map_err(|e| err(&e))?;
    if !curves.is_empty() {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))
}

/// A chart of force against mass, as [`force_weight_axes`] makes it.
pub(crate) type ForceChart<'a> = ChartContext<
    'a,
    SVGBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Writes each point's string (`9-5/8@47.00`) just above it, turned up so that the labels of
/// neighbouring points do not run into each other; `force_hi_n` is the top of the force axis.
/// Where points crowd, a label is left out unless it clears the last one written by a line's
/// height (left to right): an unreadable pile of labels names nothing.
pub(crate) fn label_points(
    chart: &mut ForceChart<'_>,
    points: &[(f64, f64, &str)],
    force_hi_n: f64,
) -> Result<(), String> {
    const LINE_PX: i32 = 13;
    let style = ("sans-serif", 11).into_font().transform(FontTransform::Rotate270).color(&BLACK);
    let mut sorted: Vec<&(f64, f64, &str)> = points.iter().filter(|p| !p.2.is_empty()).collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut last_px: Option<i32> = None;
    let mut labelled = Vec::new();
    for point in sorted {
        let px = chart.as_coord_spec().translate(&(point.0, point.1)).0;
        if last_px.is_none_or(|last| px - last >= LINE_PX) {
            labelled.push(point);
            last_px = Some(px);
        }
    }
    let labelled = labelled.into_iter();
    chart
        .draw_series(
            labelled.map(|(x, y, label)| Text::new(label.to_string(), (*x, y + 0.015 * force_hi_n), style.clone())),
        )
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// The axes every force-against-weight chart shares (sweeps, envelopes): the string's mass
/// (kg) across, peak contact force of the largest pair (N) up from 0, on a white `root`.
pub(crate) fn force_weight_axes<'a>(
    root: &DrawingArea<SVGBackend<'a>, plotters::coord::Shift>,
    caption: &str,
    mass_kg: std::ops::Range<f64>,
    force_hi_n: f64,
) -> Result<ForceChart<'a>, String> {
    crate::bench::register_font();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d(mass_kg, 0.0..force_hi_n)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("string weight, payload mass (kg)")
        .y_desc("peak contact force, largest pair (N)")
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// An axis range around `values` with 5 % margins (from 0 if `from_zero`; 0..1 if empty).
fn padded(values: impl Iterator<Item = f64>, from_zero: bool) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let lo = if from_zero { 0.0 } else { lo };
    let margin = 0.05 * (hi - lo).max(0.1 * hi.abs()).max(1e-9);
    (if from_zero { 0.0 } else { lo - margin }, hi + margin)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sweep over two strings whose peak forces are `forces`.
    fn sweep(forces: [f64; 2]) -> (Plan, Vec<Row>) {
        let vary = vec!["payload.size=2-7/8,4-1/2".parse().unwrap()];
        let plan_json = r#"{"scenario": "s.toml", "vary": [], "cases": [
            {"index": 0, "hash": "0", "values": {"payload.size": "2-7/8"}},
            {"index": 1, "hash": "1", "values": {"payload.size": "4-1/2"}}]}"#;
        let plan = Plan { vary, ..serde_json::from_str(plan_json).unwrap() };
        let rows = [(121.0, forces[0]), (200.0, forces[1])]
            .iter()
            .map(|(kg, n)| {
                let text = format!(r#"{{"summary": {{"payload_kg": {kg}, "pairs": [{{"peak_force_n": {n}}}]}}}}"#);
                Row::read(text, &[]).unwrap()
            })
            .collect();
        (plan, rows)
    }

    #[test]
    fn three_sweeps_give_three_labelled_polylines_on_one_chart() {
        let sweeps: Vec<(String, Plan, Vec<Row>)> =
            [("ideal", [1.0e3, 2.0e3]), ("servo", [8e3, 9e3]), ("hydraulic", [7e3, 7.5e3])]
                .into_iter()
                .map(|(label, forces)| {
                    let (plan, rows) = sweep(forces);
                    (label.to_string(), plan, rows)
                })
                .collect();
        let path = std::env::temp_dir().join(format!("pipearm-chart-compare-{}.svg", std::process::id()));
        compare(&path, "drives", &sweeps).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        // A curve is a 2-px polyline of two points (its legend swatch is a 2-px polyline too).
        let curves: Vec<&str> = svg
            .lines()
            .filter(|l| l.starts_with("<polyline") && l.contains(r#"stroke-width="2""#))
            .filter(|l| l.matches(',').count() == 2)
            .collect();
        assert_eq!(curves.len(), 2 * 3, "{svg}");
        let colours: std::collections::HashSet<&str> =
            curves.iter().map(|l| l.split("stroke=\"").nth(1).unwrap().split('"').next().unwrap()).collect();
        assert_eq!(colours.len(), 3, "{curves:?}");
        for label in ["ideal", "servo", "hydraulic"] {
            assert!(svg.contains(&format!("\n{label}\n")), "no legend entry {label}");
        }
    }
}
