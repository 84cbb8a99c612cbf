//! Sensors on the machine, read as the real instruments read them: an accelerometer on the arm,
//! a strain gauge on the arm's upper face, an encoder on the hub.
//!
//! Each sensor gives two channels, in SI units:
//!
//! | kind | channels | what |
//! |---|---|---|
//! | [`SensorKind::Accelerometer`] | `axial`, `transverse` (m/s²) | specific force (acceleration minus gravity) of the arm's point at the station, in the section's own axes: along the arm (toward the tip) and across it (the arm's upper face, +y); at rest on a horizontal arm it reads (0, +g) |
//! | [`SensorKind::StrainGauge`] | `moment` (N·m), `stress` (Pa) | bending moment at the station, positive when it puts the upper (+y) face in tension (a cantilever under its own weight), and that face's stress σ = M c / I |
//! | [`SensorKind::Encoder`] | `angle` (rad), `rate` (rad/s) | the hub's angle from horizontal, counter-clockwise, and its rate |
//!
//! The readings ([`probe`]) come from the arm's kinematics, the integrator's accelerations and
//! the contact forces: the bending moment is the moment of the loads outboard of the station
//! (inertial, gravity, the carried masses and the pads' forces), not EI times the curvature, so a
//! few modes give it right (the curvature of a truncated modal sum converges slowly).

pub mod probe;
pub mod string;
pub mod summary;

use serde::{Deserialize, Serialize};

use crate::beam::SectionShape;
use crate::robot::{Robot, section_extent};

pub use probe::SensorProbe;

/// A sensor placed on the machine.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensor {
    /// Its name: the prefix of its channels' names (`<name>.<channel>`).
    pub name: String,
    /// What it is and where.
    pub kind: SensorKind,
}

/// What a sensor is, and where it sits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SensorKind {
    /// An accelerometer on the arm's axis at `station_m` (m from the pivot along the arm).
    Accelerometer { station_m: f64 },
    /// A strain gauge on the arm's upper face at `station_m`, on a section of half depth
    /// `half_depth_m` (m) and second moment `second_moment_m4` (m⁴) about its neutral axis.
    StrainGauge { station_m: f64, half_depth_m: f64, second_moment_m4: f64 },
    /// An encoder on the hub.
    Encoder,
}

/// One channel of a sensor: its name and SI unit as written in a CSV header (`name[unit]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChannelDef {
    /// The channel's name after the sensor's (`axial`, `moment`, `angle`, ...).
    pub name: &'static str,
    /// Its SI unit, ASCII (`m/s^2`, `N*m`, `Pa`, `rad`, `rad/s`).
    pub unit: &'static str,
    /// The name with its unit, for JSON keys (`axial_m_s2`).
    pub key: &'static str,
}

const fn channel(name: &'static str, unit: &'static str, key: &'static str) -> ChannelDef {
    ChannelDef { name, unit, key }
}

/// The kinds a scenario may name, as written there.
pub const KIND_NAMES: [&str; 3] = ["accelerometer", "strain-gauge", "encoder"];

impl SensorKind {
    /// The kind's name as a scenario writes it.
    pub fn name(&self) -> &'static str {
        match self {
            SensorKind::Accelerometer { .. } => KIND_NAMES[0],
            SensorKind::StrainGauge { .. } => KIND_NAMES[1],
            SensorKind::Encoder => KIND_NAMES[2],
        }
    }

    /// Its two channels, in the order of the readings.
    pub fn channels(&self) -> [ChannelDef; 2] {
        match self {
            SensorKind::Accelerometer { .. } => {
                [channel("axial", "m/s^2", "axial_m_s2"), channel("transverse", "m/s^2", "transverse_m_s2")]
            }
            SensorKind::StrainGauge { .. } => {
                [channel("moment", "N*m", "moment_n_m"), channel("stress", "Pa", "stress_pa")]
            }
            SensorKind::Encoder => [channel("angle", "rad", "angle_rad"), channel("rate", "rad/s", "rate_rad_s")],
        }
    }

    /// The arm station it sits at, m (`None` for the encoder).
    pub fn station_m(&self) -> Option<f64> {
        match *self {
            SensorKind::Accelerometer { station_m } | SensorKind::StrainGauge { station_m, .. } => Some(station_m),
            SensorKind::Encoder => None,
        }
    }
}

/// A sensor as a scenario file declares it (`[[sensors]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorSpec {
    /// Its name: letters, digits, `_` and `-`.
    pub name: String,
    /// `accelerometer`, `strain-gauge` or `encoder`.
    pub kind: String,
    /// Arm station, m from the pivot (accelerometer and strain gauge; not the encoder).
    #[serde(default)]
    pub station_m: Option<f64>,
}

/// Names a sensor may not take: the first part of the run's other channels' names
/// ([`crate::channel`]) and of the tables' sign-off columns, which a sensor's `<name>.<channel>`
/// would otherwise spell again.
pub const RESERVED_NAMES: [&str; 15] = [
    "t",
    "hub",
    "tip_deflection",
    "tip_velocity",
    "drive_torque",
    "contact_force",
    "actuator",
    "head",
    "string",
    "energy",
    "modal",
    "stress",
    "pivot",
    "cylinder_pin",
    "grip",
];

/// A sensor declaration that cannot be resolved: the key (under `sensors[i].`) and what is wrong.
pub type SpecError = (&'static str, String);

impl SensorSpec {
    /// Resolves the declaration on `robot`: checks the kind, the station and the name's
    /// characters (uniqueness across sensors is the caller's).
    pub fn resolve(&self, robot: &Robot) -> Result<Sensor, SpecError> {
        let name_ok = !self.name.is_empty()
            && self.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            && !RESERVED_NAMES.contains(&self.name.as_str());
        if !name_ok {
            let reserved = RESERVED_NAMES.join(", ");
            let message = format!(
                "`{}`: allowed a non-empty name of letters, digits, `_` and `-`, other than {reserved}",
                self.name
            );
            return Err(("name", message));
        }
        let length = robot.arm.length_m();
        let station = |kind: &str| -> Result<f64, SpecError> {
            match self.station_m {
                Some(x) if x.is_finite() && (0.0..=length).contains(&x) => Ok(x),
                Some(x) => Err(("station_m", format!("{x} is outside 0 ..= {length} (the arm length)"))),
                None => Err(("station_m", format!("missing: an {kind} needs the arm station it sits at, m"))),
            }
        };
        let kind = match self.kind.as_str() {
            "accelerometer" => SensorKind::Accelerometer { station_m: station("accelerometer")? },
            "strain-gauge" => {
                let station_m = station("strain gauge")?;
                let section = section_at(robot, station_m);
                let properties = section.properties().map_err(|e| ("station_m", e.to_string()))?;
                SensorKind::StrainGauge {
                    station_m,
                    half_depth_m: 0.5 * section_extent(&section).1,
                    second_moment_m4: properties.second_moment_m4,
                }
            }
            "encoder" => {
                if self.station_m.is_some() {
                    return Err(("station_m", "an encoder sits on the hub: leave station_m out".into()));
                }
                SensorKind::Encoder
            }
            other => {
                return Err(("kind", format!("`{other}` is not a sensor kind: allowed {}", KIND_NAMES.join(", "))));
            }
        };
        Ok(Sensor { name: self.name.clone(), kind })
    }
}
/// Entity path of a sensor channel's plot.
pub fn sensor_entity(sensor: &str, channel: &str) -> String {
    format!("plots/sensors/{sensor}/{channel}")
}

/// Each sensor's two channels ([`crate::channel`]), in the model's order: `<sensor>.<channel>`,
/// plotted at [`sensor_entity`], measurable.
pub fn channels(sensors: &[Sensor]) -> Vec<crate::channel::Channel> {
    use crate::channel::{Channel, Reading};
    let mut out = Vec::new();
    for (index, sensor) in sensors.iter().enumerate() {
        for (channel, c) in sensor.kind.channels().into_iter().enumerate() {
            let reading = Reading::Sensor { index, channel };
            let named = Channel::new(format!("{}.{}", sensor.name, c.name), c.unit, reading);
            out.push(named.plotted(sensor_entity(&sensor.name, c.name), 1.0).measurable());
        }
    }
    out
}

/// The arm's section at `station_m`: the segment that holds it (at a joint between segments,
/// the outboard one, whose section carries the moment just past the joint; at the tip, the last).
pub fn section_at(robot: &Robot, station_m: f64) -> SectionShape {
    let mut end = 0.0;
    for segment in &robot.arm.segments {
        end += segment.length_m;
        if station_m < end {
            return segment.section;
        }
    }
    robot.arm.segments.last().expect("an arm has segments").section
}
