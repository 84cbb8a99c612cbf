//! What a run reports about its actuator.

use serde::Serialize;

use super::ActuatorOutputs;
use crate::drive::MotionProfile;

/// The actuator's peaks over a run (the summary's `actuator` object).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ActuatorSummary {
    /// `ideal`, `servo` or `hydraulic`.
    pub kind: String,
    /// Largest |torque| the actuator puts on the hub, N·m.
    pub peak_torque_n_m: f64,
    /// Largest |rod force| of any cylinder, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_force_n: Option<f64>,
    /// Largest pressure in any chamber of any cylinder, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_pressure_pa: Option<f64>,
    /// Largest |reference − hub angle| over the run, deg.
    pub max_tracking_error_deg: f64,
    /// How far the hub went past the reference's end angle in the direction of travel, deg
    /// (negative: it stopped short, on a pad or under a lagging drive).
    pub overtravel_deg: f64,
}

impl ActuatorSummary {
    /// The summary of a run of `kind` tracking `reference`, from its hub angles and torques and
    /// (for a servo or hydraulic drive) the actuator's outputs per step. An ideal hub follows its
    /// reference exactly: no outputs, no tracking error.
    pub fn of(
        kind: &str,
        reference: &MotionProfile,
        hub_angle_rad: &[f64],
        hub_torque_n_m: &[f64],
        outputs: &[ActuatorOutputs],
    ) -> Self {
        let direction = if reference.end_rad() < reference.start_rad() { -1.0 } else { 1.0 };
        let beyond =
            hub_angle_rad.iter().map(|a| direction * (a - reference.end_rad())).fold(f64::NEG_INFINITY, f64::max);
        let tracking = outputs.iter().map(|o| o.tracking_error_rad.abs()).fold(0.0, f64::max);
        ActuatorSummary {
            kind: kind.into(),
            peak_torque_n_m: hub_torque_n_m.iter().map(|t| t.abs()).fold(0.0, f64::max),
            peak_force_n: outputs.iter().flat_map(|o| &o.cylinders).map(|c| c.rod_force_n.abs()).reduce(f64::max),
            peak_pressure_pa: outputs.iter().flat_map(|o| &o.cylinders).flat_map(|c| c.pressures_pa).reduce(f64::max),
            max_tracking_error_deg: tracking.to_degrees(),
            overtravel_deg: if beyond.is_finite() { beyond.to_degrees() } else { 0.0 },
        }
    }
}
