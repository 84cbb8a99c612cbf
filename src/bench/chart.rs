//! The speed-against-accuracy chart: error against cost, log–log, every point labelled, the
//! Pareto front drawn, one panel per error measure (SVG and PNG).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{BenchResult, Measured, Point};

/// DejaVu Sans (assets/fonts, Bitstream Vera licence): the PNG needs glyphs, and measuring text
/// must not depend on the fonts a machine happens to have.
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the chart font with plotters (once; every chart of the crate calls it).
pub fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // A font compiled into the binary cannot fail to parse.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Indices of the points on the Pareto front of (cost, error): no other point is both cheaper
/// and more accurate. Sorted by cost.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> =
        (0..points.len()).filter(|&i| points[i].0.is_finite() && points[i].1.is_finite()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut best = f64::INFINITY;
    order.into_iter().filter(|&i| (points[i].1 < best).then(|| best = points[i].1).is_some()).collect()
}

type Pick = fn(&Measured) -> f64;

/// The error measures charted, one panel each.
const PANELS: [(&str, Pick); 2] = [
    ("peak contact force error", |m| m.peak_force_error),
    ("tip deflection history error (RMS / peak)", |m| m.tip_rms_error),
];

/// Errors below this are drawn at it (a log axis has no zero).
const ERROR_FLOOR: f64 = 1e-7;

/// Writes the chart as SVG.
pub fn chart_svg(path: &Path, result: &BenchResult) -> Result<(), String> {
    register_font();
    let root = SVGBackend::new(path, (1400, 1100)).into_drawing_area();
    draw(root, result)
}

/// Writes the chart as PNG.
pub fn chart_png(path: &Path, result: &BenchResult) -> Result<(), String> {
    register_font();
    let root = BitMapBackend::new(path, (1400, 1100)).into_drawing_area();
    draw(root, result)
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, result: &BenchResult) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let has_contact = result.points.iter().filter_map(Point::measured).any(|m| m.peak_force_n > 0.0);
    let panels: Vec<_> = PANELS.iter().filter(|(name, _)| has_contact || !name.starts_with("peak")).collect();
    let areas = root.split_evenly((panels.len(), 1));
    let axes = axis_names(result);
    for (area, (name, pick)) in areas.iter().zip(panels) {
        let ran: Vec<(&Point, (f64, f64))> = result
            .points
            .iter()
            .filter_map(|p| p.measured().map(|m| (p, (m.cost_s_per_s, pick(m).max(ERROR_FLOOR)))))
            .filter(|(_, (c, e))| c.is_finite() && e.is_finite())
            .collect();
        let (cost_lo, cost_hi) = range(ran.iter().map(|r| r.1.0));
        let (err_lo, err_hi) = range(ran.iter().map(|r| r.1.1));
        let mut chart = ChartBuilder::on(area)
            .caption(format!("{}: {name} against cost", result.scenario), ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (cost_lo / 1.5..cost_hi * 1.5).log_scale(),
                (err_lo / 2.0..(err_hi * 2.0).max(err_lo * 10.0)).log_scale(),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("wall time per simulated second (s/s, one thread)")
            .y_desc(format!("{name} against the fe reference"))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| err(&e))?;
        let xy: Vec<(f64, f64)> = ran.iter().map(|r| r.1).collect();
        let front: Vec<(f64, f64)> = pareto_front(&xy).into_iter().map(|i| xy[i]).collect();
        chart
            .draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(2)));
        for (k, axis) in axes.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            let mine: Vec<&(&Point, (f64, f64))> = ran.iter().filter(|r| &r.0.variant.axis == axis).collect();
            chart
                .draw_series(mine.iter().map(|r| Circle::new(r.1, 4, color.filled())))
                .map_err(|e| err(&e))?
                .label(axis.as_str())
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
            chart
                .draw_series(
                    mine.iter().map(|r| {
                        Text::new(short_label(r.0), r.1, ("sans-serif", 9).into_font().color(&color.mix(0.9)))
                    }),
                )
                .map_err(|e| err(&e))?;
        }
        chart.draw_series(front.iter().map(|&p| Circle::new(p, 7, BLACK.stroke_width(1)))).map_err(|e| err(&e))?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))
}

/// The axes of the grid, in order of appearance.
fn axis_names(result: &BenchResult) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for p in &result.points {
        if !names.contains(&p.variant.axis) {
            names.push(p.variant.axis.clone());
        }
    }
    names
}

/// The label beside a point: what differs from its axis's defaults is enough to tell points
/// apart on the chart (the CSV has everything).
fn short_label(p: &Point) -> String {
    format!(" {}", p.variant.label().replace("generalized-alpha", "g-α").replace("symplectic-euler", "s-euler"))
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo.is_finite() && hi > 0.0 { (lo.max(1e-12), hi.max(lo * 10.0)) } else { (1e-6, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::pareto_front;

    #[test]
    fn the_pareto_front_keeps_exactly_the_undominated_points() {
        // (cost, error): 1 and 3 are dominated by 0 and 2; 4 is cheapest-but-worst and stays.
        let points = [(2.0, 0.1), (3.0, 0.2), (5.0, 0.01), (6.0, 0.05), (1.0, 0.5), (f64::NAN, 0.0)];
        assert_eq!(pareto_front(&points), vec![4, 0, 2]);
    }
}
