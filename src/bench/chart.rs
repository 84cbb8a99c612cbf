//! The speed-against-accuracy chart: error against cost, log–log, one panel per error measure
//! (SVG and PNG). Every point is a marker coloured by its axis of the grid; only the Pareto front
//! and the scene's own setting are labelled (the CSV names every point); the legend stands beside
//! the plot, not over it.

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

/// Marker colours, one per axis of the grid: strong, and apart on white (Tableau 10, then darker
/// tones).
pub const AXIS_COLOURS: [RGBColor; 14] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
    RGBColor(0, 100, 0),
    RGBColor(90, 60, 0),
];

/// Width of the legend beside each panel, px.
const LEGEND_PX: u32 = 300;

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
    for (whole, (name, pick)) in areas.iter().zip(panels) {
        let width = whole.dim_in_pixel().0;
        let (area, legend_area) = whole.split_horizontally(width.saturating_sub(LEGEND_PX));
        let area = &area;
        let legend_area = &legend_area;
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
        chart.draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(2))).map_err(|e| err(&e))?;
        for (k, axis) in axes.iter().enumerate() {
            let color = AXIS_COLOURS[k % AXIS_COLOURS.len()];
            let mine = ran.iter().filter(|r| &r.0.variant.axis == axis);
            chart.draw_series(mine.map(|r| Circle::new(r.1, 4, color.filled()))).map_err(|e| err(&e))?;
        }
        chart.draw_series(front.iter().map(|&p| Circle::new(p, 7, BLACK.stroke_width(1)))).map_err(|e| err(&e))?;
        // Labels on the front and on the scene's own setting only: elsewhere they pile up.
        let labelled = ran.iter().filter(|r| front.contains(&r.1) || r.0.variant.label() == result.own_label);
        let font = ("sans-serif", 11).into_font().color(&BLACK);
        chart.draw_series(labelled.map(|r| Text::new(short_label(r.0), r.1, font.clone()))).map_err(|e| err(&e))?;
        legend(legend_area, &axes)?;
    }
    root.present().map_err(|e| err(&e))
}

/// The legend beside a panel: the Pareto front, then each axis's marker colour.
fn legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, axes: &[String]) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let font = ("sans-serif", 13).into_font().color(&BLACK);
    let row = |k: usize| 40 + 20 * k as i32;
    area.draw(&PathElement::new(vec![(10, row(0)), (34, row(0))], BLACK.stroke_width(2))).map_err(|e| err(&e))?;
    area.draw(&Circle::new((22, row(0)), 7, BLACK.stroke_width(1))).map_err(|e| err(&e))?;
    area.draw(&Text::new("Pareto front (labelled)", (42, row(0) - 7), font.clone())).map_err(|e| err(&e))?;
    for (k, axis) in axes.iter().enumerate() {
        let color = AXIS_COLOURS[k % AXIS_COLOURS.len()];
        area.draw(&Circle::new((22, row(k + 1)), 5, color.filled())).map_err(|e| err(&e))?;
        area.draw(&Text::new(axis.as_str(), (42, row(k + 1) - 7), font.clone())).map_err(|e| err(&e))?;
    }
    Ok(())
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
