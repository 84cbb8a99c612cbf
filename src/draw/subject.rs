//! What is drawn: a scenario's machine in its scene, or a robot alone; and what the drawing reads
//! of it, as the rest of pipearm reads it.

use crate::actuator::{Actuator, Cylinder};
use crate::model::{Dampener, HeldString, Model, Payload, Structure};
use crate::robot::{CarriedBody, Robot};

/// The machine to draw.
#[derive(Debug, Clone, Copy)]
pub enum Subject<'a> {
    /// A scenario's machine and scene (robot, payload, drive, pads, structures).
    Scene(&'a Model),
    /// A robot alone, at its lift joint's limits.
    Robot(&'a Robot),
}

/// The lift angles a drawing shows: where the arc starts and ends, and what it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Lift {
    pub from_rad: f64,
    pub to_rad: f64,
    /// What the angles are (`trapezoidal, 15 s`, `joint limits`).
    pub what: String,
}

impl<'a> Subject<'a> {
    pub fn robot(&self) -> &'a Robot {
        match self {
            Subject::Scene(model) => &model.robot,
            Subject::Robot(robot) => robot,
        }
    }

    pub fn model(&self) -> Option<&'a Model> {
        match self {
            Subject::Scene(model) => Some(model),
            Subject::Robot(_) => None,
        }
    }

    /// The scenario's name, or the robot's.
    pub fn name(&self) -> &'a str {
        match self {
            Subject::Scene(model) => &model.name,
            Subject::Robot(robot) => &robot.name,
        }
    }

    pub fn string(&self) -> Option<&'a HeldString> {
        self.model().and_then(|m| m.payload.string())
    }

    pub fn dampeners(&self) -> &'a [Dampener] {
        self.model().map_or(&[], |m| &m.dampeners)
    }

    pub fn structures(&self) -> &'a [Structure] {
        self.model().map_or(&[], |m| &m.structures)
    }

    /// The URDF's cylinders, each with whether it drives the scene's lift.
    pub fn cylinders(&self) -> Vec<(&'a Cylinder, bool)> {
        let drives = self.model().is_some_and(|m| matches!(m.drive.actuator, Actuator::Hydraulic(_)));
        self.robot().lift.cylinders.iter().flat_map(|c| &c.each).map(|c| (c, drives)).collect()
    }

    /// The drive's start and end angles, or the lift joint's limits for a robot alone.
    pub fn lift(&self) -> Lift {
        match self {
            Subject::Scene(model) => {
                let motion = &model.drive.motion;
                Lift {
                    from_rad: motion.start_rad(),
                    to_rad: motion.end_rad(),
                    what: format!("{}, {} s", motion.name(), super::paint::trimmed(motion.duration_s(), 3)),
                }
            }
            Subject::Robot(robot) => {
                let (lower, upper) = robot.lift.limits_rad;
                Lift { from_rad: lower, to_rad: upper, what: format!("joint `{}` limits", robot.lift.name) }
            }
        }
    }

    /// The hands that grip the string: (body, grip number from 1), by station.
    pub fn grips_of(&self, body: &CarriedBody) -> Option<usize> {
        self.string()?.grips.iter().position(|g| g.hand == body.name).map(|k| k + 1)
    }

    /// A lumped payload: its name, arm station (m) and mass (kg).
    pub fn lumped_payload(&self) -> Option<(&'a str, f64, f64)> {
        match self.model().map(|m| &m.payload) {
            Some(Payload::Lumped(mass)) => Some((&mass.name, mass.position_m, mass.mass_kg)),
            _ => None,
        }
    }
}

/// Body-frame y of a pad's face and of its far side, m, as the scene places it against the
/// undeformed arm (scene::pads): `gap_m` off the face of the arm's tip section.
pub fn pad_span_y_m(dampener: &Dampener, robot: &Robot) -> [f64; 2] {
    let sign = dampener.face.sign();
    let face = sign * (0.5 * robot.arm.depth_m() + dampener.gap_m);
    [face, face + sign * dampener.thickness_m]
}
