//! A run's channels: every time series a run gives, each declared once by the part of the model
//! that produces it — its name (a table's column and a measured file's column), SI unit, the
//! recording's plot and whether the tables hold it and `compare` may match it. The recording, the
//! CSV/Parquet tables, `compare` and `fit` read these declarations; none of them spells a channel
//! of its own.
//!
//! The producers, in the tables' order: the arm ([`crate::arm::channels`]: hub motion, tip,
//! drive torque), the actuator ([`crate::actuator::channels`]), each contact pair
//! ([`crate::scene::pair_channels`]), a tilting head ([`crate::arm::head_channels`]), a held
//! string and its clamp ([`crate::sensor::string::channels`]), each sensor
//! ([`crate::sensor::channels`]), then the arm's energies and elastic coordinates
//! ([`crate::arm::state_channels`]); [`crate::run::channels`] lists them for a model and
//! [`crate::run::Series::values`] reads them. The sign-off's columns (σ where the run's peak fell,
//! pin and grip loads) are declared by the series that holds them once the run has read every
//! step, where its peak fell (`crate::stress::StressSeries::channels`).

/// One channel of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Its name: a table's column (before the unit) and a measured file's column.
    pub name: String,
    /// SI unit, ASCII as a CSV header writes it (`m/s^2`, `N*m`).
    pub unit: &'static str,
    /// Where the recording plots it, if it does.
    pub plot: Option<Plot>,
    /// Whether the CSV/Parquet tables hold it.
    pub tabled: bool,
    /// Whether a measured column may name it (`compare`, `fit`).
    pub measurable: bool,
    reading: Reading,
}

/// A channel's plot in the recording.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// Entity path.
    pub entity: String,
    /// Factor from SI to the plot's unit (the hub is plotted in degrees).
    pub scale: f64,
    /// The trace's name where several channels share the entity, an instance each (the tip's
    /// axial and transverse, the energies, the elastic coordinates, the pins); `None` for an
    /// entity of its own.
    pub trace: Option<String>,
}

/// Which of a run's series a channel reads, and where in it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reading {
    /// Hub angle, rad.
    HubAngle,
    /// Hub rate, rad/s.
    HubRate,
    /// Hub acceleration, rad/s².
    HubAccel,
    /// Tip displacement in the hub frame, [axial, transverse] component k, m.
    TipDeflection(usize),
    /// Tip velocity relative to the hub frame, component k, m/s.
    TipVelocity(usize),
    /// The drive's torque on the hub, N·m.
    DriveTorque,
    /// An actuator's reference angle: the hub angle plus the tracking error, rad.
    HubReference,
    /// An actuator's output.
    Actuator(ActuatorOutput),
    /// Contact pair k's force, N.
    ContactForce(usize),
    /// A tilting head's angle on its hinge, rad.
    HeadAngle,
    /// A driven head's drive torque, N·m.
    HeadDriveTorque,
    /// A friction-clamped string's slip along the arm, m.
    StringSlip,
    /// How deep the friction clamp's jaws have sunk into the string, m.
    JawSinking,
    /// The held string's far-end deflection, m.
    StringTipDeflection,
    /// The largest bending stress at the held string's hands, Pa.
    StringBendingStress,
    /// Sensor `index`'s channel `channel` (0 or 1).
    Sensor { index: usize, channel: usize },
    /// Kinetic (0), strain (1) or gravity (2) energy, J.
    Energy(usize),
    /// Elastic coordinate i (from 0), m·kg^½.
    Modal(usize),
    /// σ at the sign-off's station `station`, its upper fibre or its lower, Pa.
    Stress { station: usize, upper: bool },
    /// The pivot's force on the arm, world component k (x, y), N.
    PivotForce(usize),
    /// `sign` times the sign-off's value at offset `at` of a step (a cylinder pin's force, world,
    /// N; a string's load on a hand, arm frame, N or N·m).
    SignOffValue { at: usize, sign: f64 },
    /// The magnitude of the sign-off's force at offsets `at`, `at + 1` of a step (a pin's or a
    /// hand's), N.
    PinForce { at: usize },
}

/// Which of an actuator's outputs a channel reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActuatorOutput {
    /// The reference less the hub angle, rad.
    TrackingError,
    /// The controller's output (N·m for a servo, the spool command for a valve).
    Command,
    /// Cylinder i's rod force, N.
    RodForce(usize),
    /// Valve i's pressure in chamber k (0 cap, 1 rod), Pa.
    Pressure(usize, usize),
}

impl Channel {
    /// A channel named `name` in `unit`, reading `reading`, in the tables and not plotted nor
    /// measurable (the builders below say otherwise).
    pub fn new(name: impl Into<String>, unit: &'static str, reading: Reading) -> Self {
        Channel { name: name.into(), unit, plot: None, tabled: true, measurable: false, reading }
    }

    /// Plotted at `entity`, scaled by `scale` from SI.
    pub fn plotted(mut self, entity: impl Into<String>, scale: f64) -> Self {
        self.plot = Some(Plot { entity: entity.into(), scale, trace: None });
        self
    }

    /// Plotted as the trace `trace` of `entity`, which other channels share.
    pub fn traced(mut self, entity: &str, trace: impl Into<String>) -> Self {
        self.plot = Some(Plot { entity: entity.into(), scale: 1.0, trace: Some(trace.into()) });
        self
    }

    /// A measured column may name it.
    pub fn measurable(mut self) -> Self {
        self.measurable = true;
        self
    }

    /// Not in the tables (plotted only).
    pub fn untabled(mut self) -> Self {
        self.tabled = false;
        self
    }

    /// What it reads.
    pub fn reading(&self) -> Reading {
        self.reading
    }

    /// `name[unit]`, a table's header.
    pub fn header(&self) -> String {
        format!("{}[{}]", self.name, self.unit)
    }
}
