//! Panel 2, the lift plane in the world at true scale: the base, the arm with what it carries
//! at the drive's start angle (solid) and its end angle (dashed), the lift angle's arc from one to
//! the other, the pads at their stops, the structures, and the cylinder between its pins.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::arm_view::outline_shape;
use super::outline::{self, EMPTY, Outline, add, grow, rotate, union};
use super::paint::{
    ARM_EDGE, ARM_FILL, BASE, BODY, CYLINDER, Drawn, INK, LIFT, MIN_FEATURE_PX, PAD, Painter, Px, Rect, STRING,
    STRUCTURE, UPPER_FACE, View, degrees, font, metres, mm, trimmed,
};
use super::subject::{Lift, Subject, pad_span_y_m};
use crate::actuator::Cylinder;
use crate::model::{Dampener, StructureShape};
use crate::robot::section_extent;

/// Height of the caption, px.
const CAPTION_PX: i32 = 34;
/// Room around the geometry, px.
const MARGIN_PX: f64 = 60.0;
/// Narrowest panel 2 is, px.
const MIN_WIDTH_PX: f64 = 860.0;
/// Radius of the lift angle's arc, as a fraction of the arm's length.
const ARC_FRACTION: f64 = 0.3;
/// Longest arc drawn, rad: a drive of a turn or more is drawn as one turn less a gap.
const ARC_MAX_RAD: f64 = std::f64::consts::TAU - 0.3;

/// How an arm pose is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Stroke {
    /// The drive's start (the robot alone: 0°): everything, filled.
    Solid,
    /// The drive's end (the robot alone: its joint limits): the arm and string outlined.
    Dashed,
}

/// Where panel 2's parts go.
#[derive(Debug, Clone)]
pub struct WorldPlan {
    /// The world's lift plane in pixels.
    pub view: View,
    /// The panel's rectangle.
    pub rect: Rect,
    /// The lift angles drawn, each with its stroke.
    poses: Vec<(f64, Stroke)>,
}

impl WorldPlan {
    /// Plans panel 2 for `subject` in `[left, right]` from `top`, at most `max_height_px` tall.
    pub fn new(subject: &Subject, [left, right]: [i32; 2], top: i32, max_height_px: i32) -> Self {
        let poses = poses(subject);
        let [x0, x1, y0, y1] = extents(subject, &poses);
        let width = (right - left) as f64 - 2.0 * MARGIN_PX;
        let height = (max_height_px - CAPTION_PX) as f64 - 2.0 * MARGIN_PX;
        let s = (width / (x1 - x0)).min(height / (y1 - y0));
        let geometry_top = top as f64 + CAPTION_PX as f64 + MARGIN_PX;
        // As wide as its content needs, the rest to the notes beside it.
        let right = right.min(left + ((x1 - x0) * s + 2.0 * MARGIN_PX).max(MIN_WIDTH_PX).ceil() as i32);
        let origin_x = left as f64 + 0.5 * ((right - left) as f64 - (x1 - x0) * s) - x0 * s;
        let view = View { origin_px: [origin_x.round(), (geometry_top + y1 * s).round()], px_per_m: s };
        let bottom = (geometry_top + (y1 - y0) * s + MARGIN_PX).round() as i32;
        WorldPlan { view, rect: [left, top, right, bottom], poses }
    }

    /// Candidate centres for a label near `at`: around it, nearest first.
    fn slots(&self, at: Px) -> Vec<Px> {
        let mut slots = Vec::new();
        for ring in 1..=10 {
            let (dx, dy) = (60 * ring, 22 * ring);
            for (sx, sy) in [(0, -1), (0, 1), (1, -1), (-1, -1), (1, 1), (-1, 1), (1, 0), (-1, 0)] {
                slots.push((at.0 + sx * dx, at.1 + sy * dy));
            }
        }
        slots
    }
}

/// The lift angles drawn: the start solid and the end dashed (a robot alone: 0° solid, its
/// limits dashed), and each pad's stop where it is neither.
fn poses(subject: &Subject) -> Vec<(f64, Stroke)> {
    let lift = subject.lift();
    let mut poses = match subject {
        Subject::Scene(_) => vec![(lift.from_rad, Stroke::Solid), (lift.to_rad, Stroke::Dashed)],
        Subject::Robot(_) => vec![(0.0, Stroke::Solid), (lift.from_rad, Stroke::Dashed), (lift.to_rad, Stroke::Dashed)],
    };
    for d in subject.dampeners() {
        poses.push((d.angle_rad, Stroke::Dashed));
    }
    let mut kept: Vec<(f64, Stroke)> = Vec::new();
    for (angle, stroke) in poses {
        let same = |a: f64| {
            ((a - angle).rem_euclid(std::f64::consts::TAU)).min((angle - a).rem_euclid(std::f64::consts::TAU)) < 1e-3
        };
        if !kept.iter().any(|(a, _)| same(*a)) {
            kept.push((angle, stroke));
        }
    }
    kept
}

/// The arm's segments in its own frame, m.
fn arm_outlines(subject: &Subject) -> Vec<Outline> {
    let mut x = 0.0;
    let mut outlines = Vec::new();
    for segment in &subject.robot().arm.segments {
        let half = 0.5 * section_extent(&segment.section).1;
        outlines.push(Outline::rectangle([x, x + segment.length_m], [-half, half]));
        x += segment.length_m;
    }
    outlines
}

/// The held string's band in the arm frame, m.
fn string_outline(subject: &Subject) -> Option<Outline> {
    let held = subject.string()?;
    let robot = subject.robot();
    let [lateral, _] = robot.body(&held.palm().hand).map_or([0.0, 0.0], |palm| robot.string_axis_offset_m(palm));
    let r = 0.5 * held.pipe.pipe.outer_diameter_m;
    Some(Outline::rectangle([held.start_m(), held.start_m() + held.pipe.length_m], [lateral - r, lateral + r]))
}

/// A pad in the arm frame at its stop, m, at least `min_m` each way (its face kept in place).
fn pad_outline(d: &Dampener, subject: &Subject, min_m: f64) -> Outline {
    let [face, far] = pad_span_y_m(d, subject.robot());
    let thick = (far - face).abs().max(min_m) * (far - face).signum();
    let half = 0.5 * d.length_m.max(min_m);
    Outline::rectangle([d.station_m - half, d.station_m + half], [face, face + thick])
}

/// [x_min, x_max, y_min, y_max] of everything panel 2 draws, world, m.
fn extents(subject: &Subject, poses: &[(f64, Stroke)]) -> [f64; 4] {
    let robot = subject.robot();
    let pivot = [robot.lift.pivot_m[0], robot.lift.pivot_m[1]];
    let mut b = grow(grow(EMPTY, [0.0, 0.0]), pivot);
    let on_arm: Vec<Outline> = arm_outlines(subject).into_iter().chain(string_outline(subject)).collect();
    for (angle, _) in poses {
        b = on_arm.iter().fold(b, |b, o| union(b, o.placed(*angle, pivot).bounds()));
    }
    b = robot.base_shapes.iter().fold(b, |b, s| union(b, outline::of_placed(s).bounds()));
    b = subject.structures().iter().fold(b, |b, s| union(b, outline::of_structure(s).bounds()));
    for d in subject.dampeners() {
        b = union(b, pad_outline(d, subject, 0.0).placed(d.angle_rad, pivot).bounds());
    }
    let lift = subject.lift();
    let sweep = (lift.to_rad - lift.from_rad).clamp(-ARC_MAX_RAD, ARC_MAX_RAD);
    let radius = ARC_FRACTION * robot.arm.length_m();
    for k in 0..=32 {
        b = grow(b, add(pivot, rotate([radius, 0.0], lift.from_rad + sweep * k as f64 / 32.0)));
    }
    for (cylinder, _) in subject.cylinders() {
        b = grow(b, add(pivot, cylinder.base_pin_m));
        for (angle, _) in poses {
            b = grow(b, add(pivot, cylinder.arm_pin_at_m(*angle)));
        }
    }
    b
}

/// A label to place once every shape is drawn: its text, the point it names, its colour.
type Pending = (String, Px, RGBColor);

/// Draws panel 2: the shapes first, then their labels where no shape or label is.
pub fn draw<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &WorldPlan, subject: &Subject) -> Drawn {
    let caption = match subject {
        Subject::Scene(_) => {
            "2  The lift plane, true scale: world X across, Y up (m); the arm at the drive's start angle (filled) and end angle (dashed)"
        }
        Subject::Robot(_) => {
            "2  The lift plane, true scale: world X across, Y up (m); the arm at 0° (filled) and at its joint limits (dashed)"
        }
    };
    p.text(caption, (plan.rect[0] + 12, plan.rect[1] + 10), &font(16, INK, (HPos::Left, VPos::Top)))?;
    p.reserve([plan.rect[0], plan.rect[1], plan.rect[2], plan.rect[1] + CAPTION_PX]);
    let v = &plan.view;
    for shape in &subject.robot().base_shapes {
        let outline = outline::of_placed(shape);
        outline_shape(p, v, &outline, BASE.mix(0.35), BASE)?;
        reserve_outline(p, v, &outline);
    }
    axes(p, v)?;
    for (angle, stroke) in &plan.poses {
        arm_at(p, plan, subject, *angle, *stroke)?;
    }
    let mut labels = vec![pivot(p, plan, subject)?];
    labels.extend(lift_arc(p, plan, subject)?);
    labels.extend(pads(p, plan, subject)?);
    labels.extend(structures(p, plan, subject)?);
    for (k, (c, drives)) in subject.cylinders().into_iter().enumerate() {
        labels.extend(cylinder(p, plan, subject, (c, drives, k))?);
    }
    scale_bar(p, plan)?;
    for (text, at, colour) in labels {
        p.label(&text, Some(at), &plan.slots(at), colour, plan.rect)?;
    }
    Ok(())
}

/// Marks an outline's bounding box as taken.
fn reserve_outline<DB: DrawingBackend>(p: &mut Painter<DB>, v: &View, outline: &Outline) {
    let [x0, x1, y0, y1] = outline.bounds();
    let (a, b) = (v.px([x0, y1]), v.px([x1, y0]));
    p.reserve([a.0 - 2, a.1 - 2, b.0 + 2, b.1 + 2]);
}

/// The world axes at the origin.
fn axes<DB: DrawingBackend>(p: &mut Painter<DB>, v: &View) -> Drawn {
    let o = v.px([0.0, 0.0]);
    let style = font(13, INK, (HPos::Left, VPos::Center));
    p.line(&[o, (o.0 + 40, o.1)], INK, 1)?;
    p.arrowhead((o.0 + 40, o.1), [1.0, 0.0], 8.0, INK)?;
    p.text("X", (o.0 + 44, o.1), &style)?;
    p.line(&[o, (o.0, o.1 - 40)], INK, 1)?;
    p.arrowhead((o.0, o.1 - 40), [0.0, -1.0], 8.0, INK)?;
    p.text("Y", (o.0 + 4, o.1 - 44), &style)?;
    p.text("world origin", (o.0 + 6, o.1 + 12), &style)?;
    p.reserve([o.0 - 4, o.1 - 52, o.0 + 90, o.1 + 22]);
    Ok(())
}

/// The arm at `angle`: its segments (the upper face marked), and, filled, what it carries.
fn arm_at<DB: DrawingBackend>(
    p: &mut Painter<DB>,
    plan: &WorldPlan,
    subject: &Subject,
    angle: f64,
    stroke: Stroke,
) -> Drawn {
    let v = &plan.view;
    let robot = subject.robot();
    let pivot = [robot.lift.pivot_m[0], robot.lift.pivot_m[1]];
    let to_px = |o: &Outline| match o.placed(angle, pivot) {
        Outline::Polygon(points) => points.iter().map(|q| v.px(*q)).collect::<Vec<Px>>(),
        Outline::Circle { .. } => Vec::new(),
    };
    let string = string_outline(subject);
    let half_depth = (0.5 * v.len(robot.arm.depth_m())).round() as i32 + 3;
    let tip = add(pivot, rotate([robot.arm.length_m(), 0.0], angle));
    p.reserve_path(&[v.px(pivot), v.px(tip)], half_depth);
    if let Some(o) = &string {
        let [x0, x1, y0, y1] = o.bounds();
        let y = 0.5 * (y0 + y1);
        let ends = [x0, x1].map(|x| v.px(add(pivot, rotate([x, y], angle))));
        p.reserve_path(&ends, 4);
    }
    if stroke == Stroke::Dashed {
        for o in arm_outlines(subject).iter().chain(string.as_ref()) {
            let mut points = to_px(o);
            points.extend(points.first().copied());
            p.dashed(&points, ARM_EDGE.mix(0.8), 1)?;
        }
        return Ok(());
    }
    for o in &arm_outlines(subject) {
        let points = to_px(o);
        p.polygon(&points, ARM_FILL.mix(1.0), ARM_EDGE, 1)?;
        // The rectangle's corners run counter-clockwise from (x0, −h): its upper edge is 2 → 3.
        p.line(&[points[2], points[3]], UPPER_FACE, 3)?;
    }
    for body in &robot.carried {
        let fill = if body.mount.is_prismatic() { BODY.mix(0.45) } else { BODY.mix(0.18) };
        for shape in &body.shapes {
            let outline = outline::of_placed(shape).placed(angle, pivot);
            outline_shape(p, v, &outline, fill, BODY)?;
        }
    }
    if let Some(o) = string {
        p.polygon(&to_px(&o), STRING.mix(0.9), RGBColor(150, 80, 10), 1)?;
    }
    Ok(())
}

fn structures<DB: DrawingBackend>(
    p: &mut Painter<DB>,
    plan: &WorldPlan,
    subject: &Subject,
) -> Result<Vec<Pending>, String> {
    let v = &plan.view;
    let mut labels = Vec::new();
    for s in subject.structures() {
        let shape = outline::of_structure(s);
        outline_shape(p, v, &shape, STRUCTURE.mix(0.35), STRUCTURE)?;
        reserve_outline(p, v, &shape);
        let size = match s.shape {
            StructureShape::Box { half_extents_m: [x, y, z] } => {
                format!("box {} × {} × {} m", trimmed(2.0 * x, 3), trimmed(2.0 * y, 3), trimmed(2.0 * z, 3))
            }
            StructureShape::Cylinder { radius_m, half_length_m } => {
                format!("cylinder r {} m, {} m long", trimmed(radius_m, 3), trimmed(2.0 * half_length_m, 3))
            }
        };
        let text = format!("structure {}: {size}, centre z {} m", s.name, metres(s.position_m[2]));
        labels.push((text, v.px(shape.centre()), STRUCTURE));
    }
    Ok(labels)
}

fn pads<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &WorldPlan, subject: &Subject) -> Result<Vec<Pending>, String> {
    let v = &plan.view;
    let robot = subject.robot();
    let pivot = [robot.lift.pivot_m[0], robot.lift.pivot_m[1]];
    let mut labels = Vec::new();
    for d in subject.dampeners() {
        let shape = pad_outline(d, subject, MIN_FEATURE_PX / v.px_per_m).placed(d.angle_rad, pivot);
        outline_shape(p, v, &shape, PAD.mix(0.9), PAD)?;
        reserve_outline(p, v, &shape);
        let text = format!("pad {} at its stop, {}", d.name, degrees(d.angle_rad));
        labels.push((text, v.px(shape.centre()), PAD));
    }
    Ok(labels)
}

/// Cylinder `k` (from 0) of the URDF, drawn between its pins at each pose; `drives` whether it
/// drives the scene's lift.
fn cylinder<DB: DrawingBackend>(
    p: &mut Painter<DB>,
    plan: &WorldPlan,
    subject: &Subject,
    (cylinder, drives, k): (&Cylinder, bool, usize),
) -> Result<Vec<Pending>, String> {
    let count = subject.cylinders().len();
    let v = &plan.view;
    let robot = subject.robot();
    let pivot = [robot.lift.pivot_m[0], robot.lift.pivot_m[1]];
    let base = v.px(add(pivot, cylinder.base_pin_m));
    for (angle, stroke) in &plan.poses {
        let pin = v.px(add(pivot, cylinder.arm_pin_at_m(*angle)));
        match stroke {
            Stroke::Solid => p.line(&[base, pin], CYLINDER, 4)?,
            Stroke::Dashed => p.dashed(&[base, pin], CYLINDER, 2)?,
        }
        p.circle(pin, 4, CYLINDER.filled())?;
        p.reserve_path(&[base, pin], 4);
    }
    p.circle(base, 5, CYLINDER.filled())?;
    let lift = subject.lift();
    let (from, to) = (cylinder.length_and_arm(lift.from_rad).0, cylinder.length_and_arm(lift.to_rad).0);
    let role = match (subject, drives) {
        (Subject::Robot(_), _) => "",
        (Subject::Scene(_), true) => ", drives the lift",
        (Subject::Scene(_), false) => " (not this scenario's actuator)",
    };
    let name = if count == 1 { "cylinder".to_string() } else { format!("cylinder {} of {count}", k + 1) };
    let text = format!(
        "{name} Ø{}/{} mm{role}: pins {} m apart at {}, {} m at {}",
        mm(cylinder.bore_m),
        mm(cylinder.rod_m),
        metres(from),
        degrees(lift.from_rad),
        metres(to),
        degrees(lift.to_rad),
    );
    let [bx, by] = cylinder.base_pin_m;
    let pin = format!("base pin ({}, {}) m from the pivot", metres(bx), metres(by));
    let arm_pin = v.px(add(pivot, cylinder.arm_pin_at_m(lift.from_rad)));
    let middle = ((base.0 + arm_pin.0) / 2, (base.1 + arm_pin.1) / 2);
    Ok(vec![(text, middle, CYLINDER), (pin, base, CYLINDER)])
}

/// The lift angle's arc about the pivot from its start to its end angle, with an arrowhead at
/// the end (a drive of more than a turn: a turn, its count written).
fn lift_arc<DB: DrawingBackend>(
    p: &mut Painter<DB>,
    plan: &WorldPlan,
    subject: &Subject,
) -> Result<Vec<Pending>, String> {
    let Lift { from_rad, to_rad, what } = subject.lift();
    let v = &plan.view;
    let pivot = v.px([subject.robot().lift.pivot_m[0], subject.robot().lift.pivot_m[1]]);
    let radius = v.len(ARC_FRACTION * subject.robot().arm.length_m());
    let sweep = (to_rad - from_rad).clamp(-ARC_MAX_RAD, ARC_MAX_RAD);
    let at =
        |a: f64, r: f64| ((pivot.0 as f64 + r * a.cos()).round() as i32, (pivot.1 as f64 - r * a.sin()).round() as i32);
    let points: Vec<Px> = (0..=64).map(|k| at(from_rad + sweep * k as f64 / 64.0, radius)).collect();
    p.line(&points, LIFT, 2)?;
    p.reserve_path(&points, 4);
    let end = from_rad + sweep;
    let sense = sweep.signum();
    p.arrowhead(at(end, radius), [-end.sin() * sense, -end.cos() * sense], 14.0, LIFT)?;
    p.circle(at(from_rad, radius), 4, LIFT.filled())?;
    let turns = (to_rad - from_rad).abs() / std::f64::consts::TAU;
    let turns = if turns > 1.0 { format!(", {} turns", trimmed(turns, 1)) } else { String::new() };
    let text = format!("lift angle θ: {} → {} ({what}{turns})", degrees(from_rad), degrees(to_rad));
    Ok(vec![(text, at(from_rad + 0.5 * sweep, radius), LIFT)])
}

fn pivot<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &WorldPlan, subject: &Subject) -> Result<Pending, String> {
    let [x, y, _] = subject.robot().lift.pivot_m;
    let at = plan.view.px([x, y]);
    p.circle(at, 6, WHITE.filled())?;
    p.circle(at, 6, INK.stroke_width(2))?;
    p.line(&[(at.0 - 9, at.1), (at.0 + 9, at.1)], INK, 1)?;
    p.line(&[(at.0, at.1 - 9), (at.0, at.1 + 9)], INK, 1)?;
    p.reserve([at.0 - 10, at.1 - 10, at.0 + 10, at.1 + 10]);
    Ok((format!("pivot ({}, {}) m", metres(x), metres(y)), at, INK))
}

/// A bar of a round length at the panel's lower left.
fn scale_bar<DB: DrawingBackend>(p: &mut Painter<DB>, plan: &WorldPlan) -> Drawn {
    let s = plan.view.px_per_m;
    let raw = 150.0 / s;
    let decade = 10f64.powf(raw.log10().floor());
    let length = [1.0, 2.0, 5.0, 10.0].iter().map(|k| k * decade).rfind(|l| l * s <= 200.0).unwrap_or(decade);
    let (x, y) = (plan.rect[0] + 20, plan.rect[3] - 16);
    let end = x + (length * s).round() as i32;
    p.line(&[(x, y), (end, y)], INK, 3)?;
    p.line(&[(x, y - 5), (x, y + 5)], INK, 1)?;
    p.line(&[(end, y - 5), (end, y + 5)], INK, 1)?;
    p.reserve([x - 4, y - 10, end + 60, y + 10]);
    p.text(&format!("{} m", trimmed(length, 3)), (end + 8, y), &font(13, INK, (HPos::Left, VPos::Center)))
}
