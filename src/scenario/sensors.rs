//! The checks of a scenario's `[[sensors]]`.

use super::{Check, ScenarioError};
use crate::model::Payload;
use crate::robot::Robot;
use crate::sensor::{Sensor, SensorKind, SensorSpec};

impl Check<'_> {
    /// `[[sensors]]`: each resolved on the robot, names unique; no strain gauge with a friction
    /// clamp (its load reaches the arm as generalized forces, without a point to take moments at).
    pub(super) fn sensors(
        &self,
        specs: &[SensorSpec],
        robot: &Robot,
        payload: &Payload,
    ) -> Result<Vec<Sensor>, ScenarioError> {
        let mut sensors: Vec<Sensor> = Vec::with_capacity(specs.len());
        for (i, spec) in specs.iter().enumerate() {
            let sensor =
                spec.resolve(robot).map_err(|(key, message)| self.invalid(&format!("sensors[{i}].{key}"), message))?;
            if let Some(j) = sensors.iter().position(|s| s.name == sensor.name) {
                return Err(self.invalid(
                    &format!("sensors[{i}].name"),
                    format!("`{}` is already the name of sensors[{j}]", sensor.name),
                ));
            }
            let friction = payload.string().is_some_and(|held| held.friction_clamp().is_some());
            if friction && matches!(sensor.kind, SensorKind::StrainGauge { .. }) {
                return Err(self.invalid(
                    &format!("sensors[{i}].kind"),
                    "a strain gauge needs a rigid clamp (payload.clamp = \"rigid\"): a friction-clamped string's load reaches the arm as generalized forces, without a point to take moments at",
                ));
            }
            sensors.push(sensor);
        }
        Ok(sensors)
    }
}
