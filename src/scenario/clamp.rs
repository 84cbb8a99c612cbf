//! The checks of a string held by friction between a gripper's jaws (`payload.clamp = "friction"`).

use super::{Check, ScenarioError};
use crate::model::HeldString;
use crate::robot::Robot;

impl Check<'_> {
    /// A friction clamp: one grip, μ and squeeze in range, a gripper with two prismatic jaws and a
    /// palm with a shape to carry them.
    pub(super) fn clamp(&self, held: &HeldString, robot: &Robot) -> Result<(), ScenarioError> {
        let Some(clamp) = held.friction_clamp() else { return Ok(()) };
        if held.grips.len() > 1 {
            return Err(self.invalid(
                "payload.grips",
                "a friction clamp holds the string in one hand's jaws: give one grip (`at`)",
            ));
        }
        let mu = clamp.friction_coefficient;
        if !(mu.is_finite() && mu > 0.0 && mu <= 2.0) {
            return Err(self.invalid("payload.friction_coefficient", format!("{mu} is outside 0 < μ <= 2")));
        }
        if let Some(n) = clamp.squeeze_n
            && !(n.is_finite() && n > 0.0)
        {
            return Err(self.invalid("payload.squeeze_n", format!("{n} is outside > 0 N")));
        }
        let jaws = robot.carried.iter().filter(|b| b.mount.is_prismatic()).count();
        if jaws != 2 {
            return Err(self.invalid(
                "payload.clamp",
                format!(
                    "a friction clamp needs a gripper with two jaws on prismatic joints; {} has {jaws}",
                    robot.name
                ),
            ));
        }
        if robot.body(&held.palm().hand).is_some_and(|b| b.shapes.is_empty()) {
            return Err(
                self.invalid("payload.at", format!("`{}` has no collision shape to carry the jaws", held.palm().hand))
            );
        }
        Ok(())
    }
}
