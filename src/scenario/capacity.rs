//! The scenario's payload against its machine ([`crate::capacity`]), checked before a run.

use super::{Check, ScenarioError};
use crate::actuator::Actuator;
use crate::capacity::CapacityError;
use crate::model::Model;

impl Check<'_> {
    /// The payload within what the machine holds and lifts ([`crate::capacity`]): a pipe its
    /// jaws close on, a weight its drive holds at every angle of the drive's path.
    pub(super) fn capacity(&self, model: &Model) -> Result<(), ScenarioError> {
        if !self.capacity {
            return Ok(());
        }
        match crate::capacity::check(model) {
            Ok(()) => Ok(()),
            Err(e @ CapacityError::Jaws { .. }) => {
                let own = model.payload.string().is_some_and(|h| h.pipe.pipe.row.is_none());
                let key = if own { "payload.pipe.outer_diameter_m" } else { "payload.size" };
                Err(self.invalid(key, e.to_string()))
            }
            // A servo or cylinder too weak for the arm itself: its holding checks name the setting.
            Err(CapacityError::ArmAlone { .. }) if !matches!(model.drive.actuator, Actuator::Ideal) => Ok(()),
            Err(e @ CapacityError::ArmAlone { .. }) => Err(self.invalid("robot", e.to_string())),
            Err(e) => Err(self.invalid("payload", e.to_string())),
        }
    }
}
