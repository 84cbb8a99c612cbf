//! The signals of a run a measured column may name: every sensor's channels and the run's own
//! series, each with its SI unit and the recording's plot it belongs in.

use crate::actuator::ActuatorChannel;
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
    Sensor {
        index: usize,
        channel: usize,
    },
    /// The actuator's channel, as it declares it.
    Actuator(ActuatorChannel),
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
        match &self.source {
            Source::HubAngle => series.hub_angle_rad.clone(),
            Source::HubRate => series.hub_rate_rad_s.clone(),
            Source::HubAccel => series.hub_accel_rad_s2.clone(),
            &Source::TipDeflection(k) => series.tip_deflection_m.iter().map(|d| d[k]).collect(),
            &Source::TipVelocity(k) => series.tip_velocity_m_s.iter().map(|d| d[k]).collect(),
            Source::DriveTorque => series.drive_torque_n_m.clone(),
            &Source::ContactForce(pad) => series.pad_force_n[pad].clone(),
            &Source::Sensor { index, channel } => series.sensors[index].values.iter().map(|v| v[channel]).collect(),
            Source::Actuator(channel) => series.actuator.iter().map(|o| channel.of(o)).collect(),
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
    defs.extend(crate::actuator::channels(&model.drive.actuator).into_iter().map(|c| SignalDef {
        name: c.name.clone(),
        unit: c.unit,
        entity: c.entity.clone(),
        plot_scale: c.plot_scale,
        source: Source::Actuator(c),
    }));
    defs
}
