//! The actuator's channels ([`crate::channel`]), declared once here: the recording plots them, the
//! tables hold them and `compare` matches measured columns against them.
//!
//! Servo and hydraulic: `actuator.tracking_error` (rad, plotted in degrees) and `actuator.command`
//! (the controller's output: N·m for a servo, the spool command for a valve). Hydraulic, per
//! cylinder its rod force and, per valve, its chamber pressures: a single cylinder's are
//! `actuator.rod_force` and `actuator.pressure.<cap|rod>`; of several, cylinder k's (from 1, the
//! URDF's order; [`super::cylinder_number`]) are `actuator.rod_force.<k>` and, a valve each,
//! `actuator.pressure.<k>.<cap|rod>` (one shared valve keeps `actuator.pressure.<cap|rod>`),
//! plotted as the traces `cylinder_<k>` of [`ROD_FORCE_ENTITY`] and `<cap|rod>` (several valves:
//! `<cap|rod>_<k>`) of [`PRESSURE_ENTITY`], the names the viewer's legend shows. Besides, plotted
//! only: the reference the controller tracks, `plots/hub/reference_deg`, beside the hub's angle.

use super::{Actuator, cylinder_number};
use crate::channel::{ActuatorOutput, Channel, Reading};

/// Entity path of the rods' forces, N: a lone cylinder's, or a trace per cylinder.
pub const ROD_FORCE_ENTITY: &str = "plots/actuator/rod_force";

/// Entity path of the chamber pressures, Pa: a trace per chamber of each valve.
pub const PRESSURE_ENTITY: &str = "plots/actuator/pressure";

/// The channels of `actuator` (module doc); none for the ideal drive.
pub fn channels(actuator: &Actuator) -> Vec<Channel> {
    let degrees = 180.0 / std::f64::consts::PI;
    let reference =
        Channel::new("actuator.reference", "rad", Reading::HubReference).plotted("plots/hub/reference_deg", degrees);
    let tracking = Channel::new("actuator.tracking_error", "rad", Reading::Actuator(ActuatorOutput::TrackingError))
        .plotted("plots/actuator/tracking_error_deg", degrees)
        .measurable();
    let command = |unit| {
        Channel::new("actuator.command", unit, Reading::Actuator(ActuatorOutput::Command))
            .plotted("plots/actuator/command", 1.0)
            .measurable()
    };
    let h = match actuator {
        Actuator::Ideal => return Vec::new(),
        Actuator::Servo(_) => return vec![tracking, command("N*m"), reference.untabled()],
        Actuator::Hydraulic(h) => h,
    };
    let mut out = vec![tracking, command("1")];
    let (count, valves) = (h.cylinders.each.len(), h.cylinders.chambers());
    for i in 0..count {
        let reading = Reading::Actuator(ActuatorOutput::RodForce(i));
        let force = match cylinder_number(i, count) {
            None => Channel::new("actuator.rod_force", "N", reading).plotted(ROD_FORCE_ENTITY, 1.0),
            Some(k) => Channel::new(format!("actuator.rod_force.{k}"), "N", reading)
                .traced(ROD_FORCE_ENTITY, format!("cylinder_{k}")),
        };
        out.push(force.measurable());
    }
    for i in 0..valves {
        for (k, chamber) in ["cap", "rod"].into_iter().enumerate() {
            let (name, trace) = match cylinder_number(i, valves) {
                None => (format!("actuator.pressure.{chamber}"), chamber.to_string()),
                Some(n) => (format!("actuator.pressure.{n}.{chamber}"), format!("{chamber}_{n}")),
            };
            let pressure = Channel::new(name, "Pa", Reading::Actuator(ActuatorOutput::Pressure(i, k)));
            out.push(pressure.traced(PRESSURE_ENTITY, trace).measurable());
        }
    }
    out.push(reference.untabled());
    out
}
