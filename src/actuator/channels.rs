//! The actuator's channels, declared once by the actuator: each with its name, SI unit, the
//! recording's plot and its factor to the plot's unit, and which output it reads. The recording
//! plots these declarations and `compare` matches measured columns against them.
//!
//! Servo and hydraulic: `actuator.tracking_error` (rad, plotted in degrees) and `actuator.command`
//! (the controller's output: N·m for a servo, the spool command for a valve). Hydraulic, per
//! cylinder its rod force and, per valve, its chamber pressures: a single cylinder's are
//! `actuator.rod_force` and `actuator.pressure.<cap|rod>`; of several, cylinder k's (from 1, the
//! URDF's order; [`super::cylinder_number`]) are `actuator.rod_force.<k>` and, a valve each,
//! `actuator.pressure.<k>.<cap|rod>` (one shared valve keeps `actuator.pressure.<cap|rod>`),
//! plotted at `plots/actuator/rod_force/cylinder_<k>` and `plots/actuator/pressure/<cap|rod>_<k>`
//! (the leaf is what the viewer's legend shows).

use super::{Actuator, ActuatorOutputs, cylinder_number};

/// Which output a channel reads.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Reading {
    TrackingError,
    Command,
    /// Cylinder i's rod force.
    RodForce(usize),
    /// Cylinder i's pressure in chamber k (0 cap, 1 rod).
    Pressure(usize, usize),
}

/// One of an actuator's channels.
#[derive(Debug, Clone, PartialEq)]
pub struct ActuatorChannel {
    /// Its name, as a measured column or a CSV header names it.
    pub name: String,
    /// SI unit, as a CSV header writes it.
    pub unit: &'static str,
    /// Entity path of the recording's plot.
    pub entity: String,
    /// Factor from SI to the plot's unit.
    pub plot_scale: f64,
    reading: Reading,
}

impl ActuatorChannel {
    /// Its value in `outputs`, SI (NaN where the outputs lack it).
    pub fn of(&self, outputs: &ActuatorOutputs) -> f64 {
        match self.reading {
            Reading::TrackingError => outputs.tracking_error_rad,
            Reading::Command => outputs.command,
            Reading::RodForce(i) => outputs.cylinders.get(i).map_or(f64::NAN, |c| c.rod_force_n),
            Reading::Pressure(i, k) => outputs.cylinders.get(i).map_or(f64::NAN, |c| c.pressures_pa[k]),
        }
    }
}

/// The channels of `actuator` (module doc); none for the ideal drive.
pub fn channels(actuator: &Actuator) -> Vec<ActuatorChannel> {
    let channel = |name: String, unit, entity: String, plot_scale, reading| ActuatorChannel {
        name,
        unit,
        entity,
        plot_scale,
        reading,
    };
    let degrees = 180.0 / std::f64::consts::PI;
    let tracking = channel(
        "actuator.tracking_error".into(),
        "rad",
        "plots/actuator/tracking_error_deg".into(),
        degrees,
        Reading::TrackingError,
    );
    let command =
        |unit| channel("actuator.command".into(), unit, "plots/actuator/command".into(), 1.0, Reading::Command);
    let h = match actuator {
        Actuator::Ideal => return Vec::new(),
        Actuator::Servo(_) => return vec![tracking, command("N*m")],
        Actuator::Hydraulic(h) => h,
    };
    let mut out = vec![tracking, command("1")];
    let (count, valves) = (h.cylinders.each.len(), h.cylinders.chambers());
    // `.k` in a name for cylinder (or valve) i of `of`, nothing for a lone one; a plot's leaf,
    // which the viewer's legend shows, says `cylinder_k`.
    let number = |i: usize, of: usize| cylinder_number(i, of);
    for i in 0..count {
        let (name, entity) = match number(i, count) {
            None => ("actuator.rod_force".to_string(), "plots/actuator/rod_force".to_string()),
            Some(k) => (format!("actuator.rod_force.{k}"), format!("plots/actuator/rod_force/cylinder_{k}")),
        };
        out.push(channel(name, "N", entity, 1.0, Reading::RodForce(i)));
    }
    for i in 0..valves {
        for (k, chamber) in ["cap", "rod"].into_iter().enumerate() {
            let (name, entity) = match number(i, valves) {
                None => (format!("actuator.pressure.{chamber}"), format!("plots/actuator/pressure/{chamber}")),
                Some(n) => {
                    (format!("actuator.pressure.{n}.{chamber}"), format!("plots/actuator/pressure/{chamber}_{n}"))
                }
            };
            out.push(channel(name, "Pa", entity, 1.0, Reading::Pressure(i, k)));
        }
    }
    out
}
