//! Panel 1, the arm in its own frame at true scale: x the station along the arm from the pivot,
//! y across it toward the upper face. The segments with their sections, the bodies the arm
//! carries, the string in its hands (its overhangs dimensioned above), the pads on their faces,
//! the cylinder's arm pin; below, a dimension line from the pivot to each station.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::outline::{self, EMPTY, Outline, grow, union};
use super::paint::{
    ARM_EDGE, ARM_FILL, BODY, CYLINDER, Dimension, Drawn, INK, MIN_FEATURE_PX, PAD, Painter, Px, Rect, STRING,
    UPPER_FACE, View, degrees, font, metres, mm, trimmed,
};
use super::subject::{Subject, pad_span_y_m};
use crate::beam::SectionShape;
use crate::robot::{Mount, section_extent};

/// Height of a row of labels or dimension lines, px.
const ROW_PX: i32 = 24;
/// Height of the caption, px.
const CAPTION_PX: i32 = 34;
/// Tallest the arm's geometry is drawn, px.
const MAX_GEOMETRY_PX: f64 = 280.0;
/// Room left and right of the geometry, px.
const SIDE_PX: f64 = 90.0;

/// Where panel 1's parts go.
#[derive(Debug, Clone)]
pub struct ArmPlan {
    /// The arm frame in pixels.
    pub view: View,
    /// The panel's rectangle.
    pub rect: Rect,
    /// Rows for labels above the geometry, and below it.
    above: [i32; 2],
    below: [i32; 2],
    /// The string's dimension rows: its whole length, then its pieces.
    chain: [i32; 2],
    /// Top and bottom of the geometry, px.
    geometry: [i32; 2],
    /// The stations dimensioned below, with what is at each.
    stations: Vec<(f64, String)>,
    /// The first dimension row's line.
    first_dimension: i32,
}

impl ArmPlan {
    /// Plans panel 1 for `subject` between `left` and `right`, from `top` down.
    pub fn new(subject: &Subject, [left, right]: [i32; 2], top: i32) -> Self {
        let [x0, x1, y0, y1] = extents(subject);
        let width = (right - left) as f64 - 2.0 * SIDE_PX;
        let s = (width / (x1 - x0)).min(MAX_GEOMETRY_PX / (y1 - y0));
        let above = [top + CAPTION_PX + ROW_PX / 2, top + CAPTION_PX + 3 * ROW_PX / 2];
        let chain_top = top + CAPTION_PX + 2 * ROW_PX + 6;
        let chain = [chain_top + ROW_PX - 4, chain_top + 2 * ROW_PX - 4];
        let chain_rows = if subject.string().is_some() { 2 } else { 0 };
        let geometry_top = chain_top + chain_rows * ROW_PX + 12;
        let geometry_bottom = geometry_top + ((y1 - y0) * s).ceil() as i32;
        let origin_x = left as f64 + 0.5 * ((right - left) as f64 - (x1 - x0) * s) - x0 * s;
        let view = View { origin_px: [origin_x.round(), (geometry_top as f64 + y1 * s).round()], px_per_m: s };
        let below = [geometry_bottom + 8 + ROW_PX / 2, geometry_bottom + 8 + 3 * ROW_PX / 2];
        let stations = stations(subject);
        let first_dimension = geometry_bottom + 8 + 3 * ROW_PX - 4;
        let bottom = first_dimension + stations.len() as i32 * ROW_PX + 8;
        ArmPlan {
            view,
            rect: [left, top, right, bottom],
            above,
            below,
            chain,
            geometry: [geometry_top, geometry_bottom],
            stations,
            first_dimension,
        }
    }

    /// Candidate centres for a label near `x` in `rows`: straight over it, then further aside.
    fn slots(&self, x: i32, rows: [i32; 2]) -> Vec<Px> {
        let shifts = (0..14).map(|k| if k % 2 == 0 { k / 2 * 70 } else { -(k / 2 + 1) * 70 });
        let shifts: Vec<i32> = shifts.collect();
        rows.iter().flat_map(|&y| shifts.iter().map(move |&dx| (x + dx, y))).collect()
    }
}

/// [x_min, x_max, y_min, y_max] of everything panel 1 draws, arm frame, m.
fn extents(subject: &Subject) -> [f64; 4] {
    let robot = subject.robot();
    let mut b = grow(EMPTY, [0.0, 0.0]);
    let mut x = 0.0;
    for segment in &robot.arm.segments {
        let depth = section_extent(&segment.section).1;
        b = union(b, [x, x + segment.length_m, -0.5 * depth, 0.5 * depth]);
        x += segment.length_m;
    }
    for body in &robot.carried {
        b = grow(b, [body.station_m, body.lateral_m]);
        b = body.shapes.iter().fold(b, |b, s| union(b, outline::of_placed(s).bounds()));
    }
    if let Some((held, lateral, radius)) = string_band(subject) {
        b = union(b, [held.start_m(), held.start_m() + held.pipe.length_m, lateral - radius, lateral + radius]);
    }
    for d in subject.dampeners() {
        let [face, far] = pad_span_y_m(d, robot);
        b = union(b, [d.station_m - 0.5 * d.length_m, d.station_m + 0.5 * d.length_m, face.min(far), face.max(far)]);
    }
    for (cylinder, _) in subject.cylinders() {
        b = grow(b, cylinder.arm_pin_m);
    }
    if let Some((_, station, _)) = subject.lumped_payload() {
        b = grow(b, [station, 0.0]);
    }
    // A margin of 2 % of the length around it, so that markers on its edge show whole.
    let margin = 0.02 * (b[1] - b[0]).max(b[3] - b[2]);
    [b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin]
}

/// The held string: itself, its axis's body y and its radius, m.
fn string_band<'a>(subject: &Subject<'a>) -> Option<(&'a crate::model::HeldString, f64, f64)> {
    let held = subject.string()?;
    let robot = subject.robot();
    let [lateral, _] = robot.body(&held.palm().hand).map_or([0.0, 0.0], |palm| robot.string_axis_offset_m(palm));
    Some((held, lateral, 0.5 * held.pipe.pipe.outer_diameter_m))
}

/// The stations dimensioned from the pivot, each with what is there (what shares a station on
/// one row), nearest first.
fn stations(subject: &Subject) -> Vec<(f64, String)> {
    let robot = subject.robot();
    let mut items: Vec<(f64, String)> = Vec::new();
    let mut x = 0.0;
    let count = robot.arm.segments.len();
    for (k, segment) in robot.arm.segments.iter().enumerate().take(count.saturating_sub(1)) {
        x += segment.length_m;
        items.push((x, format!("segment {} | {}", k + 1, k + 2)));
    }
    items.extend(robot.carried.iter().map(|b| (b.station_m, b.name.clone())));
    items.extend(subject.dampeners().iter().map(|d| (d.station_m, d.name.clone())));
    for (cylinder, _) in subject.cylinders() {
        items.push((cylinder.arm_pin_m[0], "cylinder arm pin".into()));
    }
    if let Some(held) = subject.string() {
        items.push((held.start_m(), "string inner end".into()));
        items.push((held.start_m() + held.pipe.length_m, "string outer end".into()));
    }
    if let Some((name, station, _)) = subject.lumped_payload() {
        items.push((station, name.to_string()));
    }
    items.retain(|(x, _)| x.abs() > 1e-6);
    items.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
    let mut merged: Vec<(f64, String)> = Vec::new();
    for (x, what) in items {
        match merged.last_mut() {
            Some((last, names)) if (*last - x).abs() < 5e-4 => *names = format!("{names}, {what}"),
            _ => merged.push((x, what)),
        }
    }
    // The arm's length on a row of its own, below what else is at its tip.
    let length = robot.arm.length_m();
    let at = merged.iter().position(|(x, _)| x.abs() > length + 5e-4).unwrap_or(merged.len());
    merged.insert(at, (length, "arm length".into()));
    merged
}

/// A section as the URDF names it, with its dimensions in mm.
pub fn section_text(shape: &SectionShape) -> String {
    match *shape {
        SectionShape::SolidCircle { diameter_m } => format!("solid-circle Ø{} mm", mm(diameter_m)),
        SectionShape::SolidRectangle { width_m, depth_m } => {
            format!("solid-rectangle {} × {} mm (width × depth)", mm(width_m), mm(depth_m))
        }
        SectionShape::HollowRectangle { width_m, depth_m, wall_m } => {
            format!("hollow-rectangle {} × {} mm (width × depth), wall {} mm", mm(width_m), mm(depth_m), mm(wall_m))
        }
        SectionShape::Tube { outer_diameter_m, wall_m } => {
            format!("tube Ø{} mm, wall {} mm", mm(outer_diameter_m), mm(wall_m))
        }
    }
}

/// Draws panel 1.
pub fn draw<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let caption = "1  The arm in its own frame, true scale: x = station along the arm from the pivot (m), \
                   y across it toward the upper face; z, toward you, out of the lift plane";
    p.text(caption, (plan.rect[0] + 12, plan.rect[1] + 10), &font(16, INK, (HPos::Left, VPos::Top)))?;
    p.reserve([plan.rect[0], plan.rect[1], plan.rect[2], plan.rect[1] + CAPTION_PX]);
    let at = plan.view.px([0.0, 0.0]);
    let text = format!("pivot, joint `{}`", subject.robot().lift.name);
    p.label(&text, Some(at), &plan.slots(at.0, plan.below), INK, plan.rect)?;
    segments(p, plan, subject)?;
    bodies(p, plan, subject)?;
    string(p, plan, subject)?;
    pads(p, plan, subject)?;
    pin_and_payload(p, plan, subject)?;
    pivot(p, plan)?;
    dimensions(p, plan)
}

fn segments<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let v = &plan.view;
    let arm = &subject.robot().arm;
    let mut x = 0.0;
    for (k, segment) in arm.segments.iter().enumerate() {
        let half = 0.5 * section_extent(&segment.section).1;
        let (a, b) = (v.px([x, half]), v.px([x + segment.length_m, -half]));
        p.rect(a, b, ARM_FILL.mix(1.0), ARM_EDGE)?;
        p.line(&[a, (b.0, a.1)], UPPER_FACE, 3)?;
        let which = match arm.segments.len() {
            1 => format!("arm `{}`", arm.name),
            _ => format!("segment {} of `{}`", k + 1, arm.name),
        };
        let text = format!(
            "{which}: {} m, {}; E {} GPa, ρ {} kg/m³",
            metres(segment.length_m),
            section_text(&segment.section),
            trimmed(segment.material.youngs_modulus_pa / 1e9, 1),
            trimmed(segment.material.density_kg_m3, 0),
        );
        let anchor = v.px([x + 0.5 * segment.length_m, half]);
        p.label(&text, Some(anchor), &plan.slots(anchor.0, plan.above), ARM_EDGE, plan.rect)?;
        x += segment.length_m;
    }
    let half = 0.5 * arm.depth_m();
    let at = 0.06 * arm.length_m();
    let upper = v.px([at, half]);
    p.label("upper face (+y)", Some(upper), &plan.slots(upper.0, plan.above), UPPER_FACE, plan.rect)?;
    let lower = v.px([at, -half]);
    p.label("lower face (−y)", Some(lower), &plan.slots(lower.0, plan.below), ARM_EDGE, plan.rect)?;
    Ok(())
}

fn bodies<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let v = &plan.view;
    for body in &subject.robot().carried {
        let jaw = body.mount.is_prismatic();
        let fill = if jaw { BODY.mix(0.45) } else { BODY.mix(0.18) };
        for shape in &body.shapes {
            outline_shape(p, v, &outline::of_placed(shape), fill, BODY)?;
        }
        let anchor = if body.shapes.is_empty() {
            let at = v.px([body.station_m, body.lateral_m]);
            let d = 5;
            p.polygon(
                &[(at.0, at.1 - d), (at.0 + d, at.1), (at.0, at.1 + d), (at.0 - d, at.1)],
                BODY.mix(0.8),
                BODY,
                1,
            )?;
            at
        } else {
            v.px([body.station_m, body.lateral_m])
        };
        let role = match (subject.grips_of(body), body.mount) {
            (Some(k), _) => format!(" (grip {k})"),
            (None, Mount::Prismatic { .. }) => " (jaw, prismatic)".to_string(),
            (None, Mount::Fixed) => String::new(),
        };
        let mass = if body.mass_kg > 0.0 { format!(", {} kg", trimmed(body.mass_kg, 3)) } else { String::new() };
        let text = format!("{}{role}{mass}", body.name);
        p.label(&text, Some(anchor), &plan.slots(anchor.0, plan.below), INK, plan.rect)?;
    }
    Ok(())
}

/// Draws an outline in a view: a polygon or a circle.
pub fn outline_shape<DB: DrawingBackend>(
    p: &Painter<DB>,
    v: &View,
    shape: &Outline,
    fill: RGBAColor,
    edge: RGBColor,
) -> Drawn {
    match shape {
        Outline::Polygon(points) => {
            let px: Vec<Px> = points.iter().map(|q| v.px(*q)).collect();
            p.polygon(&px, fill, edge, 1)
        }
        Outline::Circle { centre, radius } => {
            let r = v.len(*radius).round().max(2.0) as i32;
            p.circle(v.px(*centre), r, fill.filled())?;
            p.circle(v.px(*centre), r, edge.stroke_width(1))
        }
    }
}

fn string<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let Some((held, lateral, radius)) = string_band(subject) else { return Ok(()) };
    let v = &plan.view;
    let (start, end) = (held.start_m(), held.start_m() + held.pipe.length_m);
    let half_px = v.len(radius).max(1.5);
    let centre = v.px([start, lateral]).1;
    let (top, bottom) = ((centre as f64 - half_px).round() as i32, (centre as f64 + half_px).round() as i32);
    p.rect((v.px([start, 0.0]).0, top), (v.px([end, 0.0]).0, bottom), STRING.mix(0.9), RGBColor(150, 80, 10))?;
    for grip in &held.grips {
        let x = v.px([grip.station_m, 0.0]).0;
        p.arrowhead((x, top - 1), [0.0, 1.0], 9.0, INK)?;
        p.arrowhead((x, bottom + 1), [0.0, -1.0], 9.0, INK)?;
    }
    let [_, normal] =
        subject.robot().body(&held.palm().hand).map_or([0.0, 0.0], |b| subject.robot().string_axis_offset_m(b));
    let pipe = &held.pipe.pipe;
    let clamp =
        held.friction_clamp().map_or(String::new(), |f| format!(", friction clamp μ {}", f.friction_coefficient));
    let text = format!(
        "string {}: Ø{} mm, wall {} mm, {} kg{clamp}; axis {} m toward you",
        pipe.label,
        mm(pipe.outer_diameter_m),
        mm(pipe.wall_m),
        trimmed(held.pipe.mass_kg(), 1),
        metres(normal)
    );
    let anchor = v.px([end - 0.03 * held.pipe.length_m, lateral]);
    p.label(&text, Some((anchor.0, top)), &plan.slots(anchor.0 - 200, plan.above), RGBColor(150, 80, 10), plan.rect)?;
    string_chain(p, plan, held, top)
}

/// The string's dimensions along it, above the arm: each piece between its ends and hands, then
/// its whole length.
fn string_chain<DB: DrawingBackend>(
    p: &mut Painter<DB>,
    plan: &ArmPlan,
    held: &crate::model::HeldString,
    string_top: i32,
) -> Drawn {
    let v = &plan.view;
    let start = held.start_m();
    let end = start + held.pipe.length_m;
    let mut marks = vec![start];
    marks.extend(held.grips.iter().map(|g| g.station_m));
    marks.push(end);
    let x = |m: f64| v.px([m, 0.0]).0;
    let pieces = marks.len() - 1;
    let mut dimensions = Vec::new();
    for k in 0..pieces {
        let (a, b) = (marks[k], marks[k + 1]);
        if b - a < 1e-6 {
            continue;
        }
        let what = if k == 0 || k + 1 == pieces { "overhang" } else { "between hands" };
        let text = format!("{what} {} m", metres(b - a));
        dimensions.push(Dimension { x: [x(a), x(b)], y: plan.chain[1], from_y: [string_top; 2], text });
    }
    let text = format!("string {} m", metres(held.pipe.length_m));
    dimensions.push(Dimension { x: [x(start), x(end)], y: plan.chain[0], from_y: [plan.chain[1]; 2], text });
    p.dimensions(&dimensions)
}

fn pads<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let v = &plan.view;
    for d in subject.dampeners() {
        let [face, far] = pad_span_y_m(d, subject.robot());
        let face_px = v.px([d.station_m, face]).1;
        let thick = v.len(d.thickness_m).max(MIN_FEATURE_PX);
        let far_px = face_px + if far > face { -thick } else { thick }.round() as i32;
        let half = (0.5 * v.len(d.length_m).max(MIN_FEATURE_PX)).round() as i32;
        let cx = v.px([d.station_m, 0.0]).0;
        p.rect((cx - half, face_px.min(far_px)), (cx + half, face_px.max(far_px)), PAD.mix(0.9), PAD)?;
        let face_name = if d.face.sign() > 0.0 { "upper" } else { "lower" };
        let text = format!(
            "pad {}: stop {}, {face_name} face, gap {} mm; {} thick × {} long mm",
            d.name,
            degrees(d.angle_rad),
            mm(d.gap_m),
            mm(d.thickness_m),
            mm(d.length_m)
        );
        let rows = if far > face { plan.above } else { plan.below };
        let anchor = (cx, (face_px + far_px) / 2);
        p.label(&text, Some(anchor), &plan.slots(cx - 150, rows), PAD, plan.rect)?;
    }
    Ok(())
}

fn pin_and_payload<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan, subject: &Subject) -> Drawn {
    let v = &plan.view;
    for (cylinder, _) in subject.cylinders() {
        let [x, y] = cylinder.arm_pin_m;
        let (pin, axis) = (v.px([x, y]), v.px([x, 0.0]));
        p.dashed(&[pin, axis], CYLINDER, 2)?;
        p.circle(pin, 5, CYLINDER.filled())?;
        let text = format!("cylinder arm pin ({}, {}) m", metres(x), metres(y));
        let rows = if y < 0.0 { plan.below } else { plan.above };
        p.label(&text, Some(pin), &plan.slots(pin.0, rows), CYLINDER, plan.rect)?;
    }
    if let Some((name, station, mass_kg)) = subject.lumped_payload() {
        let at = v.px([station, 0.0]);
        p.rect((at.0 - 5, at.1 - 5), (at.0 + 5, at.1 + 5), STRING.mix(0.9), INK)?;
        let text = format!("payload {name}: {} kg, lumped at {} m", trimmed(mass_kg, 3), metres(station));
        p.label(&text, Some(at), &plan.slots(at.0, plan.above), RGBColor(150, 80, 10), plan.rect)?;
    }
    Ok(())
}

fn pivot<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan) -> Drawn {
    let at = plan.view.px([0.0, 0.0]);
    p.circle(at, 7, WHITE.filled())?;
    p.circle(at, 7, INK.stroke_width(2))?;
    p.line(&[(at.0 - 11, at.1), (at.0 + 11, at.1)], INK, 1)?;
    p.line(&[(at.0, at.1 - 11), (at.0, at.1 + 11)], INK, 1)
}

/// A dimension line from the pivot to each station, nearest first, one row each.
fn dimensions<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &ArmPlan) -> Drawn {
    let v = &plan.view;
    let x0 = v.px([0.0, 0.0]).0;
    let from = plan.geometry[1] + 2;
    let dimensions: Vec<Dimension> = plan
        .stations
        .iter()
        .enumerate()
        .map(|(k, (station, what))| Dimension {
            x: [x0, v.px([*station, 0.0]).0],
            y: plan.first_dimension + k as i32 * ROW_PX,
            from_y: [from, from],
            text: format!("{what} {} m", metres(*station)),
        })
        .collect();
    p.dimensions(&dimensions)
}
