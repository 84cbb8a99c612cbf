//! The stress envelope along the arm (SVG): the largest and smallest σ over the run at each
//! section, against its station, both fibres together; each segment's yield strength (over the
//! design factor) as ± lines, and the segments' boundaries.

use std::path::Path;

use plotters::prelude::*;

use super::StressSeries;
use crate::robot::ArmSegment;

/// The envelope of `series` on an arm of `segments`, with the design factor `stress_factor`,
/// drawn to `path` under `caption`. Returns a message on a drawing error.
pub fn envelope(
    path: &Path,
    caption: &str,
    series: &StressSeries,
    segments: &[ArmSegment],
    stress_factor: f64,
) -> Result<(), String> {
    const MPA: f64 = 1e-6;
    let points: Vec<(f64, f64, f64)> = series
        .stations
        .iter()
        .zip(series.extremes())
        .map(|(s, [upper, lower])| (s.station_m, MPA * upper.max.max(lower.max), MPA * upper.min.min(lower.min)))
        .collect();
    let mut ends = Vec::new();
    let mut x = 0.0;
    for s in segments {
        ends.push((x, x + s.length_m, s.checks.yield_strength.map(|y| MPA * y.strength_pa / stress_factor)));
        x += s.length_m;
    }
    let reach = points.iter().map(|p| p.1.abs().max(p.2.abs())).fold(0.0, f64::max);
    let yield_reach = ends.iter().filter_map(|e| e.2).fold(0.0, f64::max);
    let top = 1.1 * reach.max(yield_reach).max(1e-3);
    crate::bench::register_font();
    let root = SVGBackend::new(path, (900, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..x, -top..top)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("station from the pivot (m)")
        .y_desc("normal stress at the outer fibres (MPa)")
        .draw()
        .map_err(|e| e.to_string())?;
    let blue = RGBColor(31, 119, 180);
    let orange = RGBColor(255, 127, 14);
    chart
        .draw_series(LineSeries::new(points.iter().map(|p| (p.0, p.1)), blue.stroke_width(2)))
        .map_err(|e| e.to_string())?
        .label("largest σ over the run")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], blue.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(points.iter().map(|p| (p.0, p.2)), orange.stroke_width(2)))
        .map_err(|e| e.to_string())?
        .label("smallest σ over the run")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], orange.stroke_width(2)));
    let red = RGBColor(214, 39, 40);
    for (k, (from, to, fy)) in ends.iter().enumerate() {
        if let Some(fy) = fy {
            for sign in [1.0, -1.0] {
                let line = chart
                    .draw_series(LineSeries::new([(*from, sign * fy), (*to, sign * fy)], red.stroke_width(1)))
                    .map_err(|e| e.to_string())?;
                if k == 0 && sign > 0.0 {
                    line.label("± yield / stress factor")
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], red.stroke_width(1)));
                }
            }
        }
        if k > 0 {
            chart
                .draw_series(LineSeries::new([(*from, -top), (*from, top)], BLACK.mix(0.4).stroke_width(1)))
                .map_err(|e| e.to_string())?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}
