//! Painting on a plotters drawing area in pixels: a view from a plane in metres to pixels, the
//! drawing's colours, labels placed where no other label is, arrowheads and dimension lines.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};

/// What painting returns: plotters' errors as text.
pub type Drawn = Result<(), String>;

/// A pixel position.
pub type Px = (i32, i32);

/// A plane in metres (x right, y up) mapped to pixels: `px = origin + (x, −y) · px_per_m`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct View {
    /// Pixel of the plane's origin, [x, y].
    pub origin_px: [f64; 2],
    /// Pixels per metre.
    pub px_per_m: f64,
}

impl View {
    /// The pixel of a point, m.
    pub fn px(&self, [x, y]: [f64; 2]) -> Px {
        let s = self.px_per_m;
        ((self.origin_px[0] + x * s).round() as i32, (self.origin_px[1] - y * s).round() as i32)
    }

    /// A length in pixels, m.
    pub fn len(&self, metres: f64) -> f64 {
        metres * self.px_per_m
    }
}

pub const INK: RGBColor = RGBColor(30, 30, 30);
pub const GREY: RGBColor = RGBColor(130, 130, 130);
pub const FRAME: RGBColor = RGBColor(170, 170, 170);
pub const ARM_FILL: RGBColor = RGBColor(184, 202, 224);
pub const ARM_EDGE: RGBColor = RGBColor(40, 60, 90);
pub const UPPER_FACE: RGBColor = RGBColor(0, 114, 200);
pub const BODY: RGBColor = RGBColor(90, 90, 90);
pub const STRING: RGBColor = RGBColor(222, 125, 20);
pub const PAD: RGBColor = RGBColor(205, 25, 35);
pub const STRUCTURE: RGBColor = RGBColor(128, 70, 170);
pub const CYLINDER: RGBColor = RGBColor(0, 140, 95);
pub const LIFT: RGBColor = RGBColor(0, 90, 190);
pub const BASE: RGBColor = RGBColor(160, 150, 135);

/// Font size of labels, px.
pub const LABEL_PX: u32 = 14;

/// Smallest size a pad or pin is drawn at, px: smaller ones would vanish (the legend says so).
pub const MIN_FEATURE_PX: f64 = 5.0;

/// A pixel rectangle [x0, y0, x1, y1].
pub type Rect = [i32; 4];

fn overlaps(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The font of the drawing at `size_px`, `colour`, anchored at `anchor`.
pub fn font(size_px: u32, colour: RGBColor, anchor: (HPos, VPos)) -> TextStyle<'static> {
    ("sans-serif", size_px).into_font().color(&colour).pos(Pos::new(anchor.0, anchor.1))
}

/// Paints on an area and keeps the rectangles its labels took.
pub struct Painter<'a, DB: DrawingBackend> {
    area: &'a DrawingArea<DB, Shift>,
    taken: Vec<Rect>,
}

impl<'a, DB: DrawingBackend> Painter<'a, DB> {
    pub fn new(area: &'a DrawingArea<DB, Shift>) -> Self {
        Painter { area, taken: Vec::new() }
    }

    /// Width and height of `text` at `size_px`, px.
    pub fn text_size(&self, text: &str, size_px: u32) -> (i32, i32) {
        let (w, h) = self.area.estimate_text_size(text, &font(size_px, INK, (HPos::Left, VPos::Top))).unwrap_or((0, 0));
        (w as i32, h as i32)
    }

    pub fn line(&self, points: &[Px], colour: impl Color, width: u32) -> Drawn {
        self.area.draw(&PathElement::new(points.to_vec(), colour.stroke_width(width))).map_err(err)
    }

    pub fn dashed(&self, points: &[Px], colour: impl Color, width: u32) -> Drawn {
        let style = colour.stroke_width(width);
        self.area.draw(&DashedPathElement::new(points.iter().copied(), 7, 5, style)).map_err(err)
    }

    /// A filled polygon (`fill` with its alpha) with an outline.
    pub fn polygon(&self, points: &[Px], fill: RGBAColor, edge: RGBColor, width: u32) -> Drawn {
        self.area.draw(&Polygon::new(points.to_vec(), fill.filled())).map_err(err)?;
        let mut closed = points.to_vec();
        closed.extend(points.first());
        self.line(&closed, edge, width)
    }

    /// A filled rectangle between two corners, with an outline.
    pub fn rect(&self, a: Px, b: Px, fill: RGBAColor, edge: RGBColor) -> Drawn {
        self.area.draw(&Rectangle::new([a, b], fill.filled())).map_err(err)?;
        self.area.draw(&Rectangle::new([a, b], edge.stroke_width(1))).map_err(err)
    }

    pub fn circle(&self, centre: Px, radius_px: i32, style: ShapeStyle) -> Drawn {
        self.area.draw(&Circle::new(centre, radius_px, style)).map_err(err)
    }

    pub fn text(&self, text: &str, at: Px, style: &TextStyle) -> Drawn {
        self.area.draw_text(text, style, at).map_err(err)
    }

    /// A filled arrowhead with its tip at `tip`, pointing along `direction` (px, any length).
    pub fn arrowhead(&self, tip: Px, direction: [f64; 2], length_px: f64, colour: RGBColor) -> Drawn {
        let norm = direction[0].hypot(direction[1]).max(1e-9);
        let (ux, uy) = (direction[0] / norm, direction[1] / norm);
        let (bx, by) = (tip.0 as f64 - ux * length_px, tip.1 as f64 - uy * length_px);
        let half = 0.35 * length_px;
        let corner = |s: f64| ((bx - uy * half * s).round() as i32, (by + ux * half * s).round() as i32);
        self.area.draw(&Polygon::new(vec![tip, corner(1.0), corner(-1.0)], colour.filled())).map_err(err)
    }

    /// Marks a rectangle as taken, so that no label is placed over it.
    pub fn reserve(&mut self, rect: Rect) {
        self.taken.push(rect);
    }

    /// Marks the band `half_px` either side of a polyline as taken (sampled every 8 px).
    pub fn reserve_path(&mut self, points: &[Px], half_px: i32) {
        for pair in points.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) / 8).max(1);
            for k in 0..=steps {
                let x = a.0 + (b.0 - a.0) * k / steps;
                let y = a.1 + (b.1 - a.1) * k / steps;
                self.taken.push([x - half_px, y - half_px, x + half_px, y + half_px]);
            }
        }
    }

    /// How many taken rectangles `rect` overlaps; `None` outside `bounds`.
    fn clashes(&self, rect: &Rect, bounds: &Rect) -> Option<usize> {
        let inside = rect[0] >= bounds[0] && rect[1] >= bounds[1] && rect[2] <= bounds[2] && rect[3] <= bounds[3];
        inside.then(|| self.taken.iter().filter(|t| overlaps(t, rect)).count())
    }

    /// Writes `text` with its centre at the first of `centres` where it overlaps nothing taken
    /// and stays inside `bounds` (else where it overlaps least), with a leader from `anchor` when
    /// it is away from it. Returns the rectangle it took.
    pub fn label(
        &mut self,
        text: &str,
        anchor: Option<Px>,
        centres: &[Px],
        colour: RGBColor,
        bounds: Rect,
    ) -> Result<Rect, String> {
        let (w, h) = self.text_size(text, LABEL_PX);
        let rect_at = |(x, y): Px| [x - w / 2 - 3, y - h / 2 - 2, x + w / 2 + 3, y + h / 2 + 2];
        let mut best: Option<(usize, Px)> = None;
        for c in centres {
            match self.clashes(&rect_at(*c), &bounds) {
                Some(0) => {
                    best = Some((0, *c));
                    break;
                }
                Some(n) if best.is_none_or(|(m, _)| n < m) => best = Some((n, *c)),
                _ => {}
            }
        }
        let centre = best.map_or(centres[0], |(_, c)| c);
        let rect = rect_at(centre);
        if let Some(anchor) = anchor {
            let inside = anchor.0 >= rect[0] && anchor.0 <= rect[2] && anchor.1 >= rect[1] && anchor.1 <= rect[3];
            if !inside {
                let end =
                    (anchor.0.clamp(rect[0] + 2, rect[2] - 2), if anchor.1 < rect[1] { rect[1] } else { rect[3] });
                self.line(&[anchor, end], colour.mix(0.7), 1)?;
                self.circle(anchor, 2, colour.filled())?;
            }
        }
        self.text(text, centre, &font(LABEL_PX, colour, (HPos::Center, VPos::Center)))?;
        self.taken.push(rect);
        Ok(rect)
    }

    /// Dimension lines: every extension line first, then each line with its arrowheads and its
    /// text on a white ground, so that no extension line runs through a text.
    pub fn dimensions(&mut self, dimensions: &[Dimension]) -> Drawn {
        for d in dimensions {
            let [x0, x1] = d.x;
            for (x, fy) in [(x0, d.from_y[0]), (x1, d.from_y[1])] {
                let (start, end) = if fy > d.y { (fy - 3, d.y - 6) } else { (fy + 3, d.y + 6) };
                self.line(&[(x, start), (x, end)], GREY, 1)?;
            }
        }
        for d in dimensions {
            self.dimension_line(d)?;
        }
        Ok(())
    }

    fn dimension_line(&mut self, d: &Dimension) -> Drawn {
        let ([x0, x1], y) = (d.x, d.y);
        self.line(&[(x0, y), (x1, y)], INK, 1)?;
        let sign = if x1 >= x0 { 1.0 } else { -1.0 };
        self.arrowhead((x0, y), [-sign, 0.0], 9.0, INK)?;
        self.arrowhead((x1, y), [sign, 0.0], 9.0, INK)?;
        let (w, h) = self.text_size(&d.text, LABEL_PX);
        let centred = w + 12 <= (x1 - x0).abs();
        let left = if centred { (x0 + x1) / 2 - w / 2 } else { x0.max(x1) + 12 };
        // The white ground breaks the extension lines that cross the text, as drafting does.
        let rect = [left - 3, y - h - 8, left + w + 3, y - 1];
        self.area.draw(&Rectangle::new([(rect[0], rect[1]), (rect[2], rect[3])], WHITE.filled())).map_err(err)?;
        self.taken.push(rect);
        self.text(&d.text, (left, y - 2), &font(LABEL_PX, INK, (HPos::Left, VPos::Bottom)))
    }
}

/// A dimension line at height `y` between `x` (px), its text above it, with extension lines
/// from `from_y` at each end.
#[derive(Debug, Clone)]
pub struct Dimension {
    pub x: [i32; 2],
    pub y: i32,
    pub from_y: [i32; 2],
    pub text: String,
}

/// A length, m, to the millimetre.
pub fn metres(value_m: f64) -> String {
    format!("{value_m:.3}")
}

/// A number with at most `decimals` decimals, trailing zeros dropped.
pub fn trimmed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text };
    if text == "-0" { "0".into() } else { text }
}

/// A length, m, in millimetres (to 0.01 mm, trailing zeros dropped).
pub fn mm(value_m: f64) -> String {
    trimmed(1e3 * value_m, 2)
}

/// An angle, rad, in degrees (to 0.1°).
pub fn degrees(angle_rad: f64) -> String {
    format!("{}°", trimmed(angle_rad.to_degrees(), 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_without_trailing_zeros() {
        assert_eq!(mm(0.0125), "12.5");
        assert_eq!(mm(0.25), "250");
        assert_eq!(degrees(std::f64::consts::FRAC_PI_2), "90°");
        assert_eq!(trimmed(-0.0001, 2), "0");
        assert_eq!(metres(13.75), "13.750");
    }

    #[test]
    fn a_view_puts_y_up() {
        let view = View { origin_px: [100.0, 200.0], px_per_m: 10.0 };
        assert_eq!(view.px([2.0, 3.0]), (120, 170));
    }
}
