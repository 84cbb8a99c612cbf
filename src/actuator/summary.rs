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
    /// Largest |rod force| of a cylinder, N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_force_n: Option<f64>,
    /// Largest pressure in either chamber of a cylinder, Pa.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_pressure_pa: Option<f64>,
    /// Largest |reference − hub angle| over the run, deg.
    pub max_tracking_error_deg: f64,
    /// How far the hub went past the reference's end angle in the direction of travel, deg
    /// (negative: it stopped short, on a pad or under a lagging drive).
    pub overtravel_deg: f64,
}

impl ActuatorSummary {
    /// The summary of a run of `kind` tracking `reference`, from its times `t_s`, hub angles,
    /// hub torques and (for a servo or hydraulic drive) the actuator's outputs per step.
    pub fn of(
        kind: &str,
        reference: &MotionProfile,
        t_s: &[f64],
        hub_angle_rad: &[f64],
        hub_torque_n_m: &[f64],
        outputs: &[ActuatorOutputs],
    ) -> Self {
        let largest = |values: &mut dyn Iterator<Item = f64>| values.fold(0.0_f64, |a, b| a.max(b.abs()));
        let forces: Vec<f64> = outputs.iter().filter_map(|o| o.rod_force_n).collect();
        let pressures: Vec<f64> = outputs.iter().filter_map(|o| o.pressures_pa).flatten().collect();
        let tracking = t_s.iter().zip(hub_angle_rad).map(|(t, a)| reference.sample(*t).angle_rad - a);
        let travel = reference.end_rad() - reference.start_rad();
        let direction = if travel < 0.0 { -1.0 } else { 1.0 };
        let beyond =
            hub_angle_rad.iter().map(|a| direction * (a - reference.end_rad())).fold(f64::NEG_INFINITY, f64::max);
        ActuatorSummary {
            kind: kind.into(),
            peak_torque_n_m: largest(&mut hub_torque_n_m.iter().copied()),
            peak_force_n: (!forces.is_empty()).then(|| largest(&mut forces.iter().copied())),
            peak_pressure_pa: (!pressures.is_empty()).then(|| pressures.iter().copied().fold(f64::MIN, f64::max)),
            max_tracking_error_deg: largest(&mut tracking.into_iter()).to_degrees(),
            overtravel_deg: if beyond.is_finite() { beyond.to_degrees() } else { 0.0 },
        }
    }
}
