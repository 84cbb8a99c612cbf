//! The actuator's channels ([`crate::channel`]), declared once here: the recording plots them, the
//! tables hold them and `compare` matches measured columns against them.
//!
//! Servo and hydraulic: `actuator.tracking_error` (rad, plotted in degrees) and `actuator.command`
//! (the controller's output: N·m for a servo, the spool command for a valve). Hydraulic, per
//! cylinder its rod force and, per valve, its chamber pressures: a single cylinder's are
//! `actuator.rod_force` and `actuator.pressure.<cap|rod>`; of several, cylinder k's (from 1, the
//! URDF's order; [`super::cylinder_number`]) are `actuator.rod_force.<k>` and, a valve each,
//! `actuator.pressure.<k>.<cap|rod>` (one shared valve keeps `actuator.pressure.<cap|rod>`),
//! plotted at `plots/actuator/rod_force/cylinder_<k>` and `plots/actuator/pressure/<cap|rod>_<k>`
//! (the leaf is what the viewer's legend shows). Besides, plotted only: the reference the
//! controller tracks, `plots/hub/reference_deg`, beside the hub's angle.

use super::{Actuator, cylinder_number};
use crate::channel::{ActuatorOutput, Channel, Reading};

/// The channels of `actuator` (module doc); none for the ideal drive.
pub fn channels(actuator: &Actuator) -> Vec<Channel> {
    let degrees = 180.0 / std::f64::consts::PI;
    let output = |name: String, unit, entity: String, output| {
        Channel::new(name, unit, Reading::Actuator(output)).plotted(entity, 1.0).measurable()
    };
    let reference =
        Channel::new("actuator.reference", "rad", Reading::HubReference).plotted("plots/hub/reference_deg", degrees);
    let tracking = Channel::new("actuator.tracking_error", "rad", Reading::Actuator(ActuatorOutput::TrackingError))
        .plotted("plots/actuator/tracking_error_deg", degrees)
        .measurable();
    let command =
        |unit| output("actuator.command".into(), unit, "plots/actuator/command".into(), ActuatorOutput::Command);
    let h = match actuator {
        Actuator::Ideal => return Vec::new(),
        Actuator::Servo(_) => return vec![tracking, command("N*m"), reference.untabled()],
        Actuator::Hydraulic(h) => h,
    };
    let mut out = vec![tracking, command("1")];
    let (count, valves) = (h.cylinders.each.len(), h.cylinders.chambers());
    for i in 0..count {
        let (name, entity) = match cylinder_number(i, count) {
            None => ("actuator.rod_force".to_string(), "plots/actuator/rod_force".to_string()),
            Some(k) => (format!("actuator.rod_force.{k}"), format!("plots/actuator/rod_force/cylinder_{k}")),
        };
        out.push(output(name, "N", entity, ActuatorOutput::RodForce(i)));
    }
    for i in 0..valves {
        for (k, chamber) in ["cap", "rod"].into_iter().enumerate() {
            let (name, entity) = match cylinder_number(i, valves) {
                None => (format!("actuator.pressure.{chamber}"), format!("plots/actuator/pressure/{chamber}")),
                Some(n) => {
                    (format!("actuator.pressure.{n}.{chamber}"), format!("plots/actuator/pressure/{chamber}_{n}"))
                }
            };
            out.push(output(name, "Pa", entity, ActuatorOutput::Pressure(i, k)));
        }
    }
    out.push(reference.untabled());
    out
}
