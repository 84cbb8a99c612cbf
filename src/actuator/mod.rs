//! What turns the hub: an ideal drive, a geared servo motor or a hydraulic cylinder, each
//! tracking the drive's motion profile as its reference.
//!
//! - [`Actuator::Ideal`]: the hub follows the profile exactly (infinite stiffness); the torque
//!   that realizes it is an output.
//! - [`Actuator::Servo`]: a motor behind a gearbox and a drive-train spring, under a discrete
//!   PID position controller with velocity and acceleration feed-forward, its torque saturated
//!   with anti-windup ([`servo`]).
//! - [`Actuator::Hydraulic`]: double-acting cylinders (one or several) each between a pin on the
//!   base and a pin on the arm, fed by one valve or by one each, its chamber pressures built up from the oil's bulk modulus (Merritt's equations), a
//!   proportional valve with a first-order spool, a relief valve per chamber, end of stroke, and
//!   a discrete position controller driving the valve ([`hydraulic`]).
//!
//! The machine's parts come from the URDF (a `pipearm:` element on the lift joint); how it is
//! operated (pressures, valve, controller) from the scenario's `[actuator]` table.
//!
//! Conventions: angles in radians, every quantity on the arm's side of a gearbox (a motor angle
//! φ is the motor's angle divided by the gear ratio); pin coordinates in metres relative to the
//! pivot, x horizontal and y up in the base frame, x along the arm and y across it in the arm's
//! hub frame.

mod channels;
mod column;
pub mod controller;
pub mod hydraulic;
mod plant;
pub mod servo;
mod summary;

pub use channels::channels;
pub use column::{CylinderStrokes, PerCylinder, Stroke};
pub use controller::{Controller, ControllerGains};
pub use hydraulic::{Cylinder, Cylinders, HydraulicCircuit, HydraulicDrive, Valve, ValveFeed, cylinder_number};
pub use plant::{ActuatorOutputs, ActuatorPlant, CylinderReading, PinCouplings, Strokes};
pub use servo::{ServoDrive, ServoMachine};
pub use summary::ActuatorSummary;

/// What turns the hub.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Actuator {
    /// The hub follows the reference exactly.
    #[default]
    Ideal,
    /// A geared motor on a drive-train spring under a position controller.
    Servo(ServoDrive),
    /// A hydraulic cylinder driven by a proportional valve under a position controller.
    Hydraulic(HydraulicDrive),
}

impl Actuator {
    /// The kind as a scenario writes it: `ideal`, `servo` or `hydraulic`.
    pub fn kind(&self) -> &'static str {
        match self {
            Actuator::Ideal => "ideal",
            Actuator::Servo(_) => "servo",
            Actuator::Hydraulic(_) => "hydraulic",
        }
    }

    /// The controller's gains and rate, for the actuators that have one.
    pub fn controller(&self) -> Option<&ControllerGains> {
        match self {
            Actuator::Ideal => None,
            Actuator::Servo(s) => Some(&s.controller),
            Actuator::Hydraulic(h) => Some(&h.controller),
        }
    }
}
