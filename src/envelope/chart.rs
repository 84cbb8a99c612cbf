//! The envelope's chart: peak contact force (largest pair, N) against the string's mass (kg),
//! one point per group labelled with its string (`9-5/8@47.00`): the p5–p95 band shaded, the
//! median as a line, the p95 dashed and the largest run as markers (SVG).

use std::path::Path;

use plotters::prelude::*;

use super::EnvelopeError;
use super::stats::GroupEnvelope;

/// Draws `groups` (by weight) under `caption` to `path`.
pub fn force_vs_weight(path: &Path, caption: &str, groups: &[GroupEnvelope]) -> Result<(), EnvelopeError> {
    let err = |e: &dyn std::fmt::Display| EnvelopeError::Chart { path: path.into(), message: e.to_string() };
    let mut points: Vec<&GroupEnvelope> = groups.iter().filter(|g| g.peak_force_n.max.is_finite()).collect();
    points.sort_by(|a, b| a.payload_kg.total_cmp(&b.payload_kg));
    let (w_lo, w_hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| (lo.min(g.payload_kg), hi.max(g.payload_kg)));
    let (x_lo, x_hi) = if w_lo.is_finite() {
        let margin = 0.08 * (w_hi - w_lo).max(0.2 * w_hi.abs()).max(1.0);
        (w_lo - margin, w_hi + margin)
    } else {
        (0.0, 1.0)
    };
    let y_hi = points.iter().map(|g| g.peak_force_n.max).fold(1.0, f64::max) * 1.25;
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    let mut chart = crate::sweep::chart::force_weight_axes(&root, caption, x_lo..x_hi, y_hi).map_err(|e| err(&e))?;
    let band = RGBColor(70, 130, 180);
    let half_width = 0.012 * (x_hi - x_lo);
    // The band: a polygon through the p95s and back through the p5s; a bar where one group.
    let polygon: Vec<(f64, f64)> = if points.len() > 1 {
        let upper = points.iter().map(|g| (g.payload_kg, g.peak_force_n.p95));
        let lower = points.iter().rev().map(|g| (g.payload_kg, g.peak_force_n.p5));
        upper.chain(lower).collect()
    } else {
        points
            .iter()
            .flat_map(|g| {
                let (w, f) = (g.payload_kg, g.peak_force_n);
                [(w - half_width, f.p5), (w + half_width, f.p5), (w + half_width, f.p95), (w - half_width, f.p95)]
            })
            .collect()
    };
    chart
        .draw_series([Polygon::new(polygon, band.mix(0.3).filled())])
        .map_err(|e| err(&e))?
        .label("p5–p95 of the runs")
        .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 16, y + 5)], band.mix(0.3).filled()));
    let median: Vec<(f64, f64)> = points.iter().map(|g| (g.payload_kg, g.peak_force_n.p50)).collect();
    chart
        .draw_series(LineSeries::new(median.iter().copied(), band.stroke_width(2)))
        .map_err(|e| err(&e))?
        .label("median")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], band.stroke_width(2)));
    chart.draw_series(median.iter().map(|p| Circle::new(*p, 3, band.filled()))).map_err(|e| err(&e))?;
    let p95: Vec<(f64, f64)> = points.iter().map(|g| (g.payload_kg, g.peak_force_n.p95)).collect();
    chart
        .draw_series(DashedLineSeries::new(p95, 6, 4, band.stroke_width(2)))
        .map_err(|e| err(&e))?
        .label("p95")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], band.stroke_width(1)));
    let labels: Vec<(f64, f64, &str)> =
        points.iter().map(|g| (g.payload_kg, g.peak_force_n.max, g.label.as_str())).collect();
    crate::sweep::chart::label_points(&mut chart, &labels, y_hi).map_err(|e| err(&e))?;
    let max_colour = RGBColor(200, 30, 30);
    chart
        .draw_series(
            points.iter().map(|g| Cross::new((g.payload_kg, g.peak_force_n.max), 6, max_colour.stroke_width(2))),
        )
        .map_err(|e| err(&e))?
        .label("largest run")
        .legend(move |(x, y)| Cross::new((x + 8, y), 5, max_colour.stroke_width(2)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))
}
