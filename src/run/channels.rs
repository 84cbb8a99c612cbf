//! A run's channels ([`crate::channel`]) for a model, as their producers declare them, and their
//! values in its series.

use super::Series;
use crate::channel::{ActuatorOutput, Channel, Reading};
use crate::model::Model;

/// Every channel a run of `model` gives, in the tables' order ([`crate::channel`]), with
/// `modal_dofs` elastic coordinates recorded (0 for fe, which records none).
pub fn channels(model: &Model, modal_dofs: usize) -> Vec<Channel> {
    let mut out = crate::arm::channels();
    out.extend(crate::actuator::channels(&model.drive.actuator));
    out.extend(crate::scene::pair_channels(model));
    if let Some(head) = &model.robot.head {
        out.extend(crate::arm::head_channels(head));
    }
    if let Some(held) = model.payload.string() {
        out.extend(crate::sensor::string::channels(held));
    }
    out.extend(crate::sensor::channels(&model.sensors));
    out.extend(crate::arm::state_channels(modal_dofs));
    out
}

/// The channels a measured column may name for a run of `model`: the sensors' first.
pub fn measurable_channels(model: &Model) -> Vec<Channel> {
    let (sensors, others): (Vec<Channel>, Vec<Channel>) = channels(model, 0)
        .into_iter()
        .filter(|c| c.measurable)
        .partition(|c| matches!(c.reading(), Reading::Sensor { .. }));
    sensors.into_iter().chain(others).collect()
}

impl Series {
    /// What `reading` reads at step `k`, SI.
    pub fn value(&self, reading: Reading, k: usize) -> f64 {
        match reading {
            Reading::HubAngle => self.hub_angle_rad[k],
            Reading::HubRate => self.hub_rate_rad_s[k],
            Reading::HubAccel => self.hub_accel_rad_s2[k],
            Reading::TipDeflection(i) => self.tip_deflection_m[k][i],
            Reading::TipVelocity(i) => self.tip_velocity_m_s[k][i],
            Reading::DriveTorque => self.drive_torque_n_m[k],
            Reading::HubReference => self.hub_angle_rad[k] + self.actuator[k].tracking_error_rad,
            Reading::Actuator(output) => actuator_output(&self.actuator[k], output),
            Reading::ContactForce(pair) => self.pad_force_n[pair][k],
            Reading::HeadAngle => self.head_angle_rad[k],
            Reading::HeadDriveTorque => self.head_drive_torque_n_m[k],
            Reading::StringSlip => self.string_slip_m[k],
            Reading::JawSinking => self.jaw_sinking_m[k],
            Reading::StringTipDeflection => self.string_tip_deflection_m[k],
            Reading::StringBendingStress => self.string_stress_pa[k],
            Reading::Sensor { index, channel } => self.sensors[index].values[k][channel],
            Reading::Energy(i) => self.energies_j[k][i],
            Reading::Modal(i) => self.modal_q[k * self.modal_dofs + i],
            Reading::Stress { station, upper } => {
                let fibre = if upper { crate::stress::Fibre::Upper } else { crate::stress::Fibre::Lower };
                self.stress.stress_pa(station, fibre, k)
            }
            Reading::PivotForce(axis) => {
                let (sn, cs) = self.hub_angle_rad[k].sin_cos();
                let [x, y] = [0, 1].map(|a| self.sign_off_value(k, self.stress.pivot_index + a));
                [cs * x - sn * y, sn * x + cs * y][axis]
            }
            Reading::SignOffValue { at, sign } => sign * self.sign_off_value(k, at),
            Reading::PinForce { at } => self.sign_off_value(k, at).hypot(self.sign_off_value(k, at + 1)),
        }
    }

    /// The sign-off's value at offset `at` of step `k`.
    fn sign_off_value(&self, k: usize, at: usize) -> f64 {
        f64::from(self.stress.values[k * self.stress.width + at])
    }

    /// `channel`'s values at every step, SI.
    pub fn values(&self, channel: &Channel) -> Vec<f64> {
        (0..self.t_s.len()).map(|k| self.value(channel.reading(), k)).collect()
    }
}

/// An actuator's `output` in `outputs` (NaN for a cylinder or valve it lacks).
fn actuator_output(outputs: &crate::actuator::ActuatorOutputs, output: ActuatorOutput) -> f64 {
    match output {
        ActuatorOutput::TrackingError => outputs.tracking_error_rad,
        ActuatorOutput::Command => outputs.command,
        ActuatorOutput::RodForce(i) => outputs.cylinders.get(i).map_or(f64::NAN, |c| c.rod_force_n),
        ActuatorOutput::Pressure(i, k) => outputs.cylinders.get(i).map_or(f64::NAN, |c| c.pressures_pa[k]),
    }
}
