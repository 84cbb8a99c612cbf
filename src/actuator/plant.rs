//! An actuator running: its machine, its controller and its reference, and the coordinates it
//! adds to the arm's equations.
//!
//! The arm's integrator coordinates become [θ, q, own] where `own` is
//! - servo: the motor angle φ (second order, inertia N² J_m);
//! - hydraulic: the first-order block (p₁/p_s, p₂/p_s per valve, then the spool opening),
//!   carried as *rates*: a first-order state z enters the integrators as the velocity of a
//!   coordinate whose position is not used (ż is its acceleration), so every integrator's
//!   velocity update advances it and the implicit ones solve it in the same Newton iteration as
//!   the arm. Pressures are scaled by the supply pressure so that the iteration's norms weigh
//!   them like the arm's coordinates.

use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;

use super::column::{self, CylinderStrokes, PerCylinder, Stroke};
use super::{Actuator, Controller, HydraulicDrive};
use crate::drive::{DriveState, MotionProfile};

/// What one cylinder reports at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CylinderReading {
    /// Rod force (positive: extending), N.
    pub rod_force_n: f64,
    /// Chamber pressures (cap, rod), Pa.
    pub pressures_pa: [f64; 2],
    /// Pin-to-pin length, m.
    pub length_m: f64,
}

/// What an actuator reports at one instant.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ActuatorOutputs {
    /// Torque the actuator puts on the hub, N·m.
    pub hub_torque_n_m: f64,
    /// Each cylinder's readings, in the URDF's order (none without cylinders).
    pub cylinders: SmallVec<[CylinderReading; 2]>,
    /// The controller's held output (hub torque N·m, or spool command).
    pub command: f64,
    /// Reference angle minus hub angle, rad.
    pub tracking_error_rad: f64,
}

/// An actuator with its running controller, tracking a reference.
#[derive(Debug, Clone, PartialEq)]
pub struct ActuatorPlant {
    /// The machine and its gains.
    pub actuator: Actuator,
    /// The reference the controller tracks.
    pub reference: MotionProfile,
    /// The running controller.
    pub controller: Controller,
    /// The cylinders' arm pins on the arm they drive, set by that arm: the rods push on the
    /// deformed arm.
    pub arm_pins: Option<PinCouplings>,
}

/// The cylinders' arm pins as the arm's model sees them.
#[derive(Debug, Clone, PartialEq)]
pub struct PinCouplings {
    /// Per pin, its hub-frame (axial, transverse) displacement as rows over the elastic
    /// coordinates.
    pub rows: Vec<[DVector<f64>; 2]>,
    /// The static flexibility between the pins that the elastic coordinates leave out (the
    /// truncated modes' share), hub frame, m/N: entry (2i + a, 2j + b) is pin i's displacement
    /// along axis a per newton on pin j along axis b. A massless spring in series with the oil
    /// columns (docs/model-actuators.md, "The cylinder's pin: residual flexibility").
    pub residual_flexibility_m_per_n: DMatrix<f64>,
}

impl PinCouplings {
    /// The residual flexibility between the rods along their hub-frame unit vectors `units`,
    /// row-major n × n, m/N.
    pub fn flexibility_along_m_per_n(&self, units: &[[f64; 2]]) -> SmallVec<[f64; 4]> {
        let c = &self.residual_flexibility_m_per_n;
        let mut out = SmallVec::new();
        for (i, u) in units.iter().enumerate() {
            for (j, w) in units.iter().enumerate() {
                let entry = |a: usize, b: usize| c[(2 * i + a, 2 * j + b)];
                out.push(
                    u[0] * (entry(0, 0) * w[0] + entry(0, 1) * w[1]) + u[1] * (entry(1, 0) * w[0] + entry(1, 1) * w[1]),
                );
            }
        }
        out
    }
}

/// The actuator's stroke as the arm's step hands it over: the hub's (θ, θ̇) for a servo; for
/// cylinders each pin-to-pin length and rate the arm's coordinates give, and the residual
/// flexibility in series with the rods.
#[derive(Debug, Clone, PartialEq)]
pub enum Strokes {
    /// The hub's angle and rate (rad, rad/s).
    Hub(Stroke),
    /// The cylinders' strokes.
    Cylinders(CylinderStrokes),
}

impl ActuatorPlant {
    /// A plant for `actuator` (servo or hydraulic) tracking `reference`, its controller sampling
    /// at its own rate or every `step_s`.
    pub fn new(actuator: Actuator, reference: MotionProfile, step_s: f64) -> Option<Self> {
        let gains = *actuator.controller()?;
        let period_s = gains.rate_hz.map_or(step_s, |hz| 1.0 / hz);
        let limit = match &actuator {
            Actuator::Servo(s) => s.machine.hub_torque_limit_n_m(),
            _ => 1.0,
        };
        Some(ActuatorPlant { actuator, reference, controller: Controller::new(gains, period_s, limit), arm_pins: None })
    }

    /// Second-order coordinates it adds (the servo's motor angle).
    pub fn second_order_dofs(&self) -> usize {
        usize::from(matches!(self.actuator, Actuator::Servo(_)))
    }

    /// First-order states it adds (the hydraulic pressures, a pair per valve, and the spool).
    pub fn first_order_dofs(&self) -> usize {
        match &self.actuator {
            Actuator::Hydraulic(h) => column::spool_index(h) + 1,
            _ => 0,
        }
    }

    /// All coordinates it adds.
    pub fn dofs(&self) -> usize {
        self.second_order_dofs() + self.first_order_dofs()
    }

    /// Diagonal mass of its coordinates: N² J_m for a motor angle, 1 for a first-order state.
    pub fn mass(&self, i: usize) -> f64 {
        match &self.actuator {
            Actuator::Servo(s) if i == 0 => s.machine.reflected_inertia_kg_m2(),
            _ => 1.0,
        }
    }

    /// What it puts on the arm at `strokes` with its coordinates `x` and rates `v`: the torque on
    /// the hub (servo, N·m, one entry) or each cylinder's rod force (N, positive extending).
    pub fn load(&self, strokes: &Strokes, x: &[f64], v: &[f64]) -> PerCylinder {
        match (&self.actuator, strokes) {
            (Actuator::Servo(s), Strokes::Hub(hub)) => {
                PerCylinder::from_elem(s.machine.spring_torque_n_m((x[0], v[0]), (hub.position, hub.rate)), 1)
            }
            (Actuator::Hydraulic(h), Strokes::Cylinders(c)) => column::rod_forces_n(h, c, v),
            _ => PerCylinder::from_elem(0.0, 1),
        }
    }

    /// Writes the generalized forces of its coordinates into `f` (the motor's torques; the
    /// first-order states' rates) and returns what it puts on the arm ([`Self::load`]).
    pub fn forces_and_load(&self, strokes: &Strokes, x: &[f64], v: &[f64], f: &mut [f64]) -> PerCylinder {
        match (&self.actuator, strokes) {
            (Actuator::Servo(s), Strokes::Hub(hub)) => {
                let torque = s.machine.spring_torque_n_m((x[0], v[0]), (hub.position, hub.rate));
                f[0] = self.controller.output - torque;
                PerCylinder::from_elem(torque, 1)
            }
            (Actuator::Hydraulic(h), Strokes::Cylinders(c)) => {
                column::rates_and_rod_forces(h, c, self.controller.output, v, f)
            }
            _ => PerCylinder::from_elem(0.0, 1),
        }
    }

    /// The own equation the controller's output enters and its coefficient there: the motor's
    /// torque balance (1), or the spool's lag (1/τ_s).
    pub fn command_row(&self) -> (usize, f64) {
        match &self.actuator {
            Actuator::Hydraulic(h) => (column::spool_index(h), 1.0 / h.circuit.valve.spool_time_constant_s),
            _ => (0, 1.0),
        }
    }

    /// Samples the controller if a sample is due at `t_s`, reading the state (θ, θ̇) of the hub
    /// and `x`, `v` of its own coordinates.
    pub fn sample_if_due(&mut self, t_s: f64, hub: (f64, f64), x: &[f64], v: &[f64]) {
        if !self.controller.due(t_s) || matches!(self.actuator, Actuator::Ideal) {
            return;
        }
        let (reference, measured, feedforward) = self.measure(t_s, hub, x, v);
        self.controller.sample(&reference, measured.0, measured.1, feedforward);
    }

    /// The controller's law at this state as if it sampled continuously (unsaturated, the
    /// integral as it stands): what the linearised closed loop sees.
    pub fn continuous_output(&self, t_s: f64, hub: (f64, f64), x: &[f64], v: &[f64]) -> f64 {
        let (reference, measured, feedforward) = self.measure(t_s, hub, x, v);
        self.controller.law(&reference, measured.0, measured.1, feedforward)
    }

    /// The reference at `t_s`, what the controller measures — the motor's (φ, φ̇) for a servo,
    /// the hub's (θ, θ̇) for cylinders — and the feed-forward.
    fn measure(&self, t_s: f64, hub: (f64, f64), x: &[f64], v: &[f64]) -> (DriveState, (f64, f64), f64) {
        let reference = self.reference.sample(t_s);
        match &self.actuator {
            Actuator::Servo(_) => (reference, (x[0], v[0]), self.controller.feedforward(&reference)),
            Actuator::Hydraulic(h) => (reference, hub, hydraulic_feedforward(h, &self.controller, &reference, v)),
            Actuator::Ideal => (reference, hub, 0.0),
        }
    }

    /// Time of the controller's next sample, s.
    pub fn next_sample_s(&self) -> f64 {
        self.controller.next_sample_s
    }

    /// How far below the reference the hub rests when it holds a hub torque `torque_n_m` at
    /// rest (cylinders on moment arms `levers_m`), rad: the drive train's twist, and the offset
    /// a proportional controller needs for its output (a servo's torque, a leaking valve's
    /// spool opening).
    pub fn static_lag_rad(&self, torque_n_m: f64, levers_m: &[f64]) -> f64 {
        let c = &self.controller.gains;
        // With integral action the integral holds the output (and without gains nothing does:
        // `holding` refuses it).
        let offset = |output: f64| if c.ki > 0.0 || c.kp <= 0.0 { 0.0 } else { output / c.kp };
        match &self.actuator {
            Actuator::Servo(s) => torque_n_m / s.machine.stiffness_n_m_per_rad + offset(torque_n_m),
            Actuator::Hydraulic(h) => h.holding_state(torque_n_m, levers_m).map_or(0.0, |(_, spool)| offset(spool)),
            Actuator::Ideal => 0.0,
        }
    }

    /// Its coordinates and rates holding the hub at rest at `angle_rad` against a hub torque
    /// `torque_n_m` (cylinders on moment arms `levers_m`), the controller preset to hold it
    /// (the arm waits on its drive before the lift). `Err` with a reason when the actuator
    /// cannot hold it.
    pub fn holding(
        &mut self,
        angle_rad: f64,
        torque_n_m: f64,
        levers_m: &[f64],
    ) -> Result<(DVector<f64>, DVector<f64>), String> {
        let n = self.dofs();
        let (mut x, mut v) = (DVector::zeros(n), DVector::zeros(n));
        match &self.actuator {
            Actuator::Ideal => {}
            Actuator::Servo(s) => {
                x[0] = angle_rad + torque_n_m / s.machine.stiffness_n_m_per_rad;
                if torque_n_m != 0.0 && s.controller.kp <= 0.0 && s.controller.ki <= 0.0 {
                    return Err("a controller without kp or ki cannot hold the arm against gravity".into());
                }
                if torque_n_m.abs() > s.machine.hub_torque_limit_n_m() {
                    return Err(format!(
                        "holding the arm at {:.1} deg takes {:.0} N·m at the hub, above the motor's {:.0} N·m",
                        angle_rad.to_degrees(),
                        torque_n_m.abs(),
                        s.machine.hub_torque_limit_n_m()
                    ));
                }
            }
            Actuator::Hydraulic(h) => {
                let (p, spool) = h
                    .holding_state(torque_n_m, levers_m)
                    .map_err(|why| format!("at {:.1} deg, {why}", angle_rad.to_degrees()))?;
                let ps = h.circuit.supply_pressure_pa;
                for g in 0..h.cylinders.chambers() {
                    (v[2 * g], v[2 * g + 1]) = (p[0] / ps, p[1] / ps);
                }
                v[column::spool_index(h)] = spool;
                self.controller.hold(spool);
                return Ok((x, v));
            }
        }
        self.controller.hold(torque_n_m);
        Ok((x, v))
    }

    /// What it reports at time `t_s` with the hub at `angle_rad`, at `strokes`, putting
    /// `hub_torque_n_m` on the hub.
    pub fn outputs(
        &self,
        t_s: f64,
        angle_rad: f64,
        strokes: &Strokes,
        hub_torque_n_m: f64,
        v: &[f64],
    ) -> ActuatorOutputs {
        let mut out = ActuatorOutputs {
            hub_torque_n_m,
            command: self.controller.output,
            tracking_error_rad: self.reference.sample(t_s).angle_rad - angle_rad,
            ..ActuatorOutputs::default()
        };
        if let (Actuator::Hydraulic(h), Strokes::Cylinders(c)) = (&self.actuator, strokes) {
            let (forces, lengths) = (column::rod_forces_n(h, c, v), column::cylinder_lengths_m(h, c, v));
            let pressures = column::pressures_pa(h, v);
            out.cylinders = (0..forces.len())
                .map(|i| CylinderReading { rod_force_n: forces[i], pressures_pa: pressures[i], length_m: lengths[i] })
                .collect();
        }
        out
    }
}

/// The spool command that feeds the reference forward (module doc of [`super::hydraulic`]).
fn hydraulic_feedforward(h: &HydraulicDrive, controller: &Controller, reference: &DriveState, v: &[f64]) -> f64 {
    let gains = &controller.gains;
    let pressures = column::pressures_per_valve_pa(h, v);
    gains.velocity_feedforward * h.feedforward_opening(reference.angle_rad, reference.rate_rad_s, &pressures)
        + gains.acceleration_feedforward * reference.accel_rad_s2
}
