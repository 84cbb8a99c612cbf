//! The column beside panel 2: the legend, the units and conventions, and what the scenario (or
//! the robot) says, key by key, for the reader to check against the drawing.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::paint::{
    ARM_EDGE, ARM_FILL, BASE, BODY, CYLINDER, Drawn, INK, LIFT, MIN_FEATURE_PX, PAD, Painter, Rect, STRING, STRUCTURE,
    UPPER_FACE, degrees, font, metres, mm, trimmed,
};
use super::subject::Subject;
use crate::actuator::Cylinder;
use crate::contact::ForceLaw;
use crate::model::{Payload, StructureShape};

/// Line height of the notes, px.
const LINE_PX: i32 = 19;
/// Font size of the notes, px.
const NOTE_PX: u32 = 14;
/// Widest a character of the notes is on average, px (DejaVu Sans at 14 px, with margin).
const CHAR_PX: i32 = 8;

/// How a legend entry is shown.
enum Swatch {
    Fill(RGBColor, f64),
    Line(RGBColor, u32),
    Dashed(RGBColor),
}

/// The legend's entries.
fn legend() -> Vec<(Swatch, String)> {
    vec![
        (Swatch::Fill(ARM_FILL, 1.0), "arm: its segments at their section's depth".into()),
        (Swatch::Line(UPPER_FACE, 3), "the arm's upper face (+y): θ grows toward it".into()),
        (Swatch::Dashed(ARM_EDGE), "the arm at the end angle (a robot alone: its limits)".into()),
        (Swatch::Fill(BODY, 0.3), "bodies on the arm (URDF collision shapes)".into()),
        (Swatch::Fill(STRING, 0.9), "the string, and ▼▲ where its hands grip it".into()),
        (Swatch::Fill(PAD, 0.9), format!("pads, drawn at least {MIN_FEATURE_PX} px each way")),
        (Swatch::Fill(STRUCTURE, 0.35), "structures".into()),
        (Swatch::Line(CYLINDER, 4), "hydraulic cylinder between its pins".into()),
        (Swatch::Line(LIFT, 2), "lift angle θ from start (dot) to end (arrow)".into()),
        (Swatch::Fill(BASE, 0.35), "base (URDF collision shapes)".into()),
    ]
}

/// Units and conventions.
const CONVENTIONS: [&str; 4] = [
    "Lengths in m (to the mm); sections, pads and gaps in mm; angles in degrees.",
    "Station: distance along the undeformed arm from the pivot (the arm frame's x).",
    "θ turns about +z, toward you: counter-clockwise from world +X, toward the arm's upper face.",
    "Each panel is at true scale (panel 2's bar gives its scale); the SVG's <metadata> holds both.",
];

/// Characters per line in a column `width_px` wide.
fn line_chars(width_px: i32) -> usize {
    ((width_px - 30) / CHAR_PX).max(20) as usize
}

/// Wraps `text` at word boundaries into lines of at most `chars` characters, the lines after
/// the first indented.
fn wrap(text: &str, chars: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > chars {
            lines.push(std::mem::take(&mut line));
            line.push_str("    ");
        } else if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    lines.push(line);
    lines
}

/// A force law as a scenario writes it: its kind, then its parameters.
fn law_text(law: &ForceLaw) -> String {
    let value = serde_json::to_value(law).unwrap_or_default();
    let Some(map) = value.as_object() else { return String::new() };
    let kind = map.get("kind").and_then(|k| k.as_str()).unwrap_or("?");
    let params: Vec<String> = map
        .iter()
        .filter(|(k, _)| *k != "kind")
        .map(|(k, v)| format!("{k} {}", v.as_f64().map_or(v.to_string(), |x| format!("{x}"))))
        .collect();
    format!("{kind} ({})", params.join(", "))
}

/// What the scenario or the robot says, one entry per thing.
fn facts(subject: &Subject) -> Vec<String> {
    let robot = subject.robot();
    let lift = &robot.lift;
    let (lower, upper) = lift.limits_rad;
    let mut facts = vec![
        format!("robot {}: {}", robot.name, super::clean_path(&robot.source)),
        format!(
            "lift joint `{}`: limits {} … {}, {} °/s, {} kN·m",
            lift.name,
            degrees(lower),
            degrees(upper),
            trimmed(lift.velocity_rad_s.to_degrees(), 2),
            trimmed(lift.effort_n_m / 1e3, 1)
        ),
    ];
    let arm = &robot.arm;
    let ratios: Vec<String> = arm.damping_ratios.iter().map(|z| z.to_string()).collect();
    facts.push(format!(
        "arm `{}`: {} m in {} segment(s), {} elements; damping ratios {}; hub inertia {} kg·m²",
        arm.name,
        metres(arm.length_m()),
        arm.segments.len(),
        arm.elements,
        ratios.join(", "),
        trimmed(arm.hub_inertia_kg_m2, 3)
    ));
    facts.extend(cylinder_facts(subject));
    if let Some(model) = subject.model() {
        facts.extend(scene_facts(model));
    }
    facts
}

/// What the URDF says of each cylinder, and whether it drives the scene's lift.
fn cylinder_facts(subject: &Subject) -> Vec<String> {
    let cylinders = subject.cylinders();
    let count = cylinders.len();
    let feed = subject.robot().lift.cylinders.as_ref().map(|c| c.feed.name()).unwrap_or_default();
    let name = |k: usize| match count {
        1 => "cylinder".to_string(),
        _ => format!("cylinder {} of {count} (valve {feed})", k + 1),
    };
    cylinders.into_iter().enumerate().map(|(k, (c, drives))| cylinder_fact(&name(k), c, drives, subject)).collect()
}

fn cylinder_fact(name: &str, c: &Cylinder, drives: bool, subject: &Subject) -> String {
    let [bx, by] = c.base_pin_m;
    let [ax, ay] = c.arm_pin_m;
    let role = match subject.model() {
        Some(_) if drives => "; drives this lift",
        Some(_) => "; not this scenario's actuator",
        None => "",
    };
    format!(
        "{name}: bore {} mm, rod {} mm; closed {} m, stroke {} m; base pin ({}, {}) m from the pivot, arm pin ({}, {}) m in the arm frame{role}",
        mm(c.bore_m),
        mm(c.rod_m),
        metres(c.closed_length_m),
        metres(c.stroke_m),
        metres(bx),
        metres(by),
        metres(ax),
        metres(ay)
    )
}

/// What the scenario says of its drive, payload, pads and structures.
fn scene_facts(model: &crate::model::Model) -> Vec<String> {
    let mut facts = Vec::new();
    let motion = &model.drive.motion;
    facts.push(format!(
        "drive {}: θ {} → {} in {} s; actuator {}",
        motion.name(),
        degrees(motion.start_rad()),
        degrees(motion.end_rad()),
        trimmed(motion.duration_s(), 3),
        model.drive.actuator.kind()
    ));
    facts.push(match &model.payload {
        Payload::None => "payload: none".into(),
        Payload::Lumped(mass) => {
            format!("payload {}: {} kg at station {} m", mass.name, trimmed(mass.mass_kg, 3), metres(mass.position_m))
        }
        Payload::String(held) => {
            let grips: Vec<String> = held.grips.iter().map(|g| format!("{} at {} m", g.hand, metres(g.at_m))).collect();
            format!(
                "payload string {}: {} m, {} kg; gripped by {} along it (from its inner end); clamp {}",
                held.pipe.pipe.label,
                metres(held.pipe.length_m),
                trimmed(held.pipe.mass_kg(), 1),
                grips.join(" and "),
                if held.friction_clamp().is_some() { "friction" } else { "rigid" }
            )
        }
        Payload::StringOnHead(held) => format!(
            "payload string {}: {} m, {} kg; rigid in the tilting head's {}",
            held.pipe.pipe.label,
            metres(held.pipe.length_m),
            trimmed(held.pipe.mass_kg(), 1),
            held.grips.iter().map(|g| g.hand.as_str()).collect::<Vec<_>>().join(" and ")
        ),
    });
    for d in &model.dampeners {
        facts.push(format!(
            "pad {}: stop {}, station {} m, {} face, gap {} mm; {} × {} × {} mm (thick × long × wide); {}",
            d.name,
            degrees(d.angle_rad),
            metres(d.station_m),
            if d.face.sign() > 0.0 { "upper" } else { "lower" },
            mm(d.gap_m),
            mm(d.thickness_m),
            mm(d.length_m),
            mm(d.width_m),
            law_text(&d.law)
        ));
    }
    for s in &model.structures {
        let [x, y, z] = s.position_m;
        let kind = match s.shape {
            StructureShape::Box { .. } => "box",
            StructureShape::Cylinder { .. } => "cylinder",
        };
        facts.push(format!(
            "structure {}: {kind} centred at ({}, {}, {}) m, turned {}; {}, friction {}",
            s.name,
            metres(x),
            metres(y),
            metres(z),
            degrees(s.angle_rad),
            law_text(&s.law),
            s.friction
        ));
    }
    facts
}

/// The height the notes take in a column `width_px` wide, px.
pub fn height_px(subject: &Subject, width_px: i32) -> i32 {
    let chars = line_chars(width_px);
    let wrapped = |texts: &[String]| texts.iter().map(|t| wrap(t, chars).len()).sum::<usize>();
    let conventions: Vec<String> = CONVENTIONS.iter().map(|c| c.to_string()).collect();
    let lines = 3 * 2 + legend().len() + wrapped(&conventions) + wrapped(&facts(subject));
    30 + lines as i32 * LINE_PX
}

/// Draws the notes in `rect`.
pub fn draw<DB: DrawingBackend>(p: &mut Painter<DB>, rect: Rect, subject: &Subject) -> Drawn {
    let chars = line_chars(rect[2] - rect[0]);
    let x = rect[0] + 14;
    let mut y = rect[1] + 20;
    let heading = font(16, INK, (HPos::Left, VPos::Center));
    let body = font(NOTE_PX, INK, (HPos::Left, VPos::Center));
    p.text("Legend", (x, y), &heading)?;
    y += 2 * LINE_PX;
    for (swatch, text) in legend() {
        match swatch {
            Swatch::Fill(colour, alpha) => p.rect((x, y - 6), (x + 28, y + 6), colour.mix(alpha), colour)?,
            Swatch::Line(colour, width) => p.line(&[(x, y), (x + 28, y)], colour, width)?,
            Swatch::Dashed(colour) => p.dashed(&[(x, y), (x + 28, y)], colour, 1)?,
        }
        p.text(&text, (x + 38, y), &body)?;
        y += LINE_PX;
    }
    y += LINE_PX;
    p.text("Units and conventions", (x, y), &heading)?;
    y += LINE_PX + 6;
    for line in CONVENTIONS.iter().flat_map(|c| wrap(c, chars)) {
        p.text(&line, (x, y), &body)?;
        y += LINE_PX;
    }
    y += LINE_PX;
    let what = if subject.model().is_some() { "What the scenario says" } else { "What the URDF says" };
    p.text(what, (x, y), &heading)?;
    y += LINE_PX + 6;
    for line in facts(subject).iter().flat_map(|f| wrap(f, chars)) {
        p.text(&line, (x, y), &body)?;
        y += LINE_PX;
    }
    Ok(())
}
