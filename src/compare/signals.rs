//! The signals of a run a measured column may name: every sensor's channels and the run's own
//! series, each with its SI unit and the recording's plot it belongs in.

use crate::actuator::{Actuator, ActuatorOutputs};
use crate::model::Model;
use crate::run::Series;

/// Where a signal's values come from in a run's [`Series`].
#[derive(Debug, Clone, PartialEq)]
enum Source {
    HubAngle,
    HubRate,
    HubAccel,
    TipDeflection(usize),
    TipVelocity(usize),
    DriveTorque,
    ContactForce(usize),
    Sensor { index: usize, channel: usize },
    Actuator(ActuatorSignal),
}

/// One of an actuator's outputs ([`ActuatorOutputs`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum ActuatorSignal {
    TrackingError,
    Command,
    /// Cylinder i's rod force.
    RodForce(usize),
    /// Cylinder i's pressure in chamber k (0 cap, 1 rod).
    Pressure(usize, usize),
}

impl ActuatorSignal {
    fn of(self, o: &ActuatorOutputs) -> f64 {
        match self {
            ActuatorSignal::TrackingError => o.tracking_error_rad,
            ActuatorSignal::Command => o.command,
            ActuatorSignal::RodForce(i) => o.cylinders.get(i).map_or(f64::NAN, |c| c.rod_force_n),
            ActuatorSignal::Pressure(i, k) => o.cylinders.get(i).map_or(f64::NAN, |c| c.pressures_pa[k]),
        }
    }
}

/// A signal of a run, before it has run: name, unit and plot.
#[derive(Debug, Clone, PartialEq)]
pub struct SignalDef {
    /// `<sensor>.<channel>` or the series' name (`hub.angle`, `tip_deflection.transverse`,
    /// `drive_torque`, `contact_force.<pad>`).
    pub name: String,
    /// SI unit, as a CSV header writes it.
    pub unit: &'static str,
    /// Entity path of the recording's plot of this signal.
    pub entity: String,
    /// Factor from SI to the plot's unit (the hub is plotted in degrees).
    pub plot_scale: f64,
    source: Source,
}

impl SignalDef {
    /// The signal's values per step of `series`, SI.
    pub fn values(&self, series: &Series) -> Vec<f64> {
        match self.source {
            Source::HubAngle => series.hub_angle_rad.clone(),
            Source::HubRate => series.hub_rate_rad_s.clone(),
            Source::HubAccel => series.hub_accel_rad_s2.clone(),
            Source::TipDeflection(k) => series.tip_deflection_m.iter().map(|d| d[k]).collect(),
            Source::TipVelocity(k) => series.tip_velocity_m_s.iter().map(|d| d[k]).collect(),
            Source::DriveTorque => series.drive_torque_n_m.clone(),
            Source::ContactForce(pad) => series.pad_force_n[pad].clone(),
            Source::Sensor { index, channel } => series.sensors[index].values.iter().map(|v| v[channel]).collect(),
            Source::Actuator(signal) => series.actuator.iter().map(|o| signal.of(o)).collect(),
        }
    }
}

/// Entity path of a sensor channel's plot.
pub fn sensor_entity(sensor: &str, channel: &str) -> String {
    format!("plots/sensors/{sensor}/{channel}")
}

/// Every signal a run of `model` gives, sensors first.
pub fn signal_defs(model: &Model) -> Vec<SignalDef> {
    let def =
        |name: String, unit, entity: String, plot_scale, source| SignalDef { name, unit, entity, plot_scale, source };
    let mut defs = Vec::new();
    for (index, sensor) in model.sensors.iter().enumerate() {
        for (channel, c) in sensor.kind.channels().iter().enumerate() {
            let name = format!("{}.{}", sensor.name, c.name);
            defs.push(def(name, c.unit, sensor_entity(&sensor.name, c.name), 1.0, Source::Sensor { index, channel }));
        }
    }
    let degrees = 180.0 / std::f64::consts::PI;
    defs.push(def("hub.angle".into(), "rad", "plots/hub/angle_deg".into(), degrees, Source::HubAngle));
    defs.push(def("hub.rate".into(), "rad/s", "plots/hub/rate_deg_s".into(), degrees, Source::HubRate));
    defs.push(def("hub.accel".into(), "rad/s^2", "plots/hub/accel_deg_s2".into(), degrees, Source::HubAccel));
    for (k, axis) in ["axial", "transverse"].into_iter().enumerate() {
        let entity = format!("plots/tip_deflection/{axis}");
        defs.push(def(format!("tip_deflection.{axis}"), "m", entity, 1.0, Source::TipDeflection(k)));
        let entity = format!("plots/tip_velocity/{axis}");
        defs.push(def(format!("tip_velocity.{axis}"), "m/s", entity, 1.0, Source::TipVelocity(k)));
    }
    defs.push(def("drive_torque".into(), "N*m", "plots/drive_torque".into(), 1.0, Source::DriveTorque));
    for (pad, dampener) in model.dampeners.iter().enumerate() {
        let entity = crate::record::force_entity(&dampener.name);
        defs.push(def(format!("contact_force.{}", dampener.name), "N", entity, 1.0, Source::ContactForce(pad)));
    }
    defs.extend(actuator_signal_defs(&model.drive.actuator));
    defs
}

/// The actuator's signals, which the recording plots too: the tracking error and the
/// controller's command; per cylinder its rod force and, per valve, its chamber pressures. A
/// single cylinder's are `actuator.rod_force` and `actuator.pressure.<chamber>`; of several,
/// cylinder k's (from 1, the URDF's order) are `actuator.rod_force.<k>` and
/// `actuator.pressure.<k>.<chamber>` (on a shared valve the one pair, `actuator.pressure.<chamber>`).
pub fn actuator_signal_defs(actuator: &Actuator) -> Vec<SignalDef> {
    let def = |name: String, unit, entity: String, plot_scale, signal| SignalDef {
        name,
        unit,
        entity,
        plot_scale,
        source: Source::Actuator(signal),
    };
    let degrees = 180.0 / std::f64::consts::PI;
    let tracking = def(
        "actuator.tracking_error".into(),
        "rad",
        "plots/actuator/tracking_error_deg".into(),
        degrees,
        ActuatorSignal::TrackingError,
    );
    let command =
        |unit| def("actuator.command".into(), unit, "plots/actuator/command".into(), 1.0, ActuatorSignal::Command);
    match actuator {
        Actuator::Ideal => Vec::new(),
        Actuator::Servo(_) => vec![tracking, command("N*m")],
        Actuator::Hydraulic(h) => {
            let mut defs = vec![tracking, command("1")];
            let count = h.cylinders.each.len();
            let number = |i: usize, count: usize| crate::actuator::cylinder_number(i, count);
            let suffix = |i: usize| number(i, count).map_or(String::new(), |k| format!(".{k}"));
            let path = |i: usize| number(i, count).map_or(String::new(), |k| format!("/{k}"));
            for i in 0..count {
                let (name, entity) =
                    (format!("actuator.rod_force{}", suffix(i)), format!("plots/actuator/rod_force{}", path(i)));
                defs.push(def(name, "N", entity, 1.0, ActuatorSignal::RodForce(i)));
            }
            let valves = h.cylinders.chambers();
            for i in 0..valves {
                let (suffix, path) = match number(i, valves) {
                    None => (String::new(), String::new()),
                    Some(_) => (suffix(i), path(i)),
                };
                for (k, chamber) in ["cap", "rod"].into_iter().enumerate() {
                    let name = format!("actuator.pressure{suffix}.{chamber}");
                    let entity = format!("plots/actuator/pressure{path}/{chamber}");
                    defs.push(def(name, "Pa", entity, 1.0, ActuatorSignal::Pressure(i, k)));
                }
            }
            defs
        }
    }
}
