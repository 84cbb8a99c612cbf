//! An actuator running: its machine, its controller and its reference, and the coordinates it
//! adds to the arm's equations.
//!
//! The arm's integrator coordinates become [θ, q, own] where `own` is
//! - servo: the motor angle φ (second order, inertia N² J_m);
//! - hydraulic: the first-order block (p₁/p_s, p₂/p_s, spool opening), carried as *rates*: a
//!   first-order state z enters the integrators as the velocity of a coordinate whose position
//!   is not used (ż is its acceleration), so every integrator's velocity update advances it and
//!   the implicit ones solve it in the same Newton iteration as the arm. Pressures are scaled by
//!   the supply pressure so that the iteration's norms weigh them like the arm's coordinates.

use nalgebra::DVector;

use super::{Actuator, Controller, HydraulicDrive};
use crate::drive::{DriveState, MotionProfile};

/// What an actuator reports at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ActuatorOutputs {
    /// Torque the actuator puts on the hub, N·m.
    pub hub_torque_n_m: f64,
    /// Rod force of a cylinder (positive: extending), N.
    pub rod_force_n: Option<f64>,
    /// Chamber pressures of a cylinder (cap, rod), Pa.
    pub pressures_pa: Option<[f64; 2]>,
    /// Pin-to-pin length of a cylinder, m.
    pub cylinder_length_m: Option<f64>,
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
    /// A cylinder's arm pin on the arm it drives, set by that arm: the rod pushes on the
    /// deformed arm.
    pub arm_pin: Option<PinCoupling>,
}

/// A cylinder's arm pin as the arm's model sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct PinCoupling {
    /// The pin's hub-frame (axial, transverse) displacement as rows over the elastic coordinates.
    pub rows: [DVector<f64>; 2],
    /// The static flexibility at the pin that the elastic coordinates leave out (the truncated
    /// modes' share), hub frame, m/N: a massless spring in series with the oil column
    /// (docs/model-actuators.md, "The cylinder's pin: residual flexibility").
    pub residual_flexibility_m_per_n: [[f64; 2]; 2],
}

impl PinCoupling {
    /// The residual flexibility along a hub-frame unit vector `unit` (the rod's), m/N.
    pub fn flexibility_along_m_per_n(&self, unit: [f64; 2]) -> f64 {
        let c = &self.residual_flexibility_m_per_n;
        unit[0] * (c[0][0] * unit[0] + c[0][1] * unit[1]) + unit[1] * (c[1][0] * unit[0] + c[1][1] * unit[1])
    }
}

/// The actuator's stroke as the arm's step hands it over: the hub's (θ, θ̇) for a servo; for a
/// hydraulic drive the pin-to-pin length and rate the arm's coordinates give (m, m/s), and the
/// residual flexibility in series with the rod (m/N), which lengthens the cylinder by its
/// flexibility times the rod's pressure force.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stroke {
    /// Hub angle (rad), or the pin-to-pin length the arm's coordinates give (m).
    pub position: f64,
    /// Its rate, rad/s or m/s.
    pub rate: f64,
    /// Flexibility in series with the rod, m/N (0 for a servo).
    pub series_flexibility_m_per_n: f64,
}

impl Stroke {
    /// A stroke with no series flexibility.
    pub fn rigid(position: f64, rate: f64) -> Self {
        Stroke { position, rate, series_flexibility_m_per_n: 0.0 }
    }
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
        Some(ActuatorPlant { actuator, reference, controller: Controller::new(gains, period_s, limit), arm_pin: None })
    }

    /// Second-order coordinates it adds (the servo's motor angle).
    pub fn second_order_dofs(&self) -> usize {
        usize::from(matches!(self.actuator, Actuator::Servo(_)))
    }

    /// First-order states it adds (the hydraulic pressures and spool).
    pub fn first_order_dofs(&self) -> usize {
        if matches!(self.actuator, Actuator::Hydraulic(_)) { 3 } else { 0 }
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

    /// What it puts on the arm at `stroke` with its coordinates `x` and rates `v`: the torque on
    /// the hub (servo, N·m) or the rod force (hydraulic, N, positive extending).
    pub fn load(&self, stroke: Stroke, x: &[f64], v: &[f64]) -> f64 {
        match &self.actuator {
            Actuator::Ideal => 0.0,
            Actuator::Servo(s) => s.machine.spring_torque_n_m((x[0], v[0]), (stroke.position, stroke.rate)),
            Actuator::Hydraulic(h) => rod_force_n(h, stroke, v),
        }
    }

    /// Writes the generalized forces of its coordinates into `f` (the motor's torques; the
    /// first-order states' rates).
    pub fn forces(&self, stroke: Stroke, x: &[f64], v: &[f64], f: &mut [f64]) {
        match &self.actuator {
            Actuator::Ideal => {}
            Actuator::Servo(s) => {
                f[0] =
                    self.controller.output - s.machine.spring_torque_n_m((x[0], v[0]), (stroke.position, stroke.rate))
            }
            Actuator::Hydraulic(h) => hydraulic_rates(h, stroke, self.controller.output, v, f),
        }
    }

    /// The own equation the controller's output enters and its coefficient there: the motor's
    /// torque balance (1), or the spool's lag (1/τ_s).
    pub fn command_row(&self) -> (usize, f64) {
        match &self.actuator {
            Actuator::Hydraulic(h) => (2, 1.0 / h.circuit.valve.spool_time_constant_s),
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
    /// the hub's (θ, θ̇) for a cylinder — and the feed-forward.
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

    /// How far below the reference the hub rests when it holds `load` at rest (a servo's hub
    /// torque, N·m; a cylinder's rod force, N), rad: the drive train's twist, and the offset a
    /// proportional controller needs for its output (a servo's torque, a leaking valve's spool
    /// opening).
    pub fn static_lag_rad(&self, load: f64) -> f64 {
        let c = &self.controller.gains;
        // With integral action the integral holds the output (and without gains nothing does:
        // `holding` refuses it).
        let offset = |output: f64| if c.ki > 0.0 || c.kp <= 0.0 { 0.0 } else { output / c.kp };
        match &self.actuator {
            Actuator::Servo(s) => load / s.machine.stiffness_n_m_per_rad + offset(load),
            Actuator::Hydraulic(h) => h.holding_state(load).map_or(0.0, |(_, spool)| offset(spool)),
            Actuator::Ideal => 0.0,
        }
    }

    /// Its coordinates and rates holding the hub at rest at `angle_rad` with a load `load` (the
    /// hub torque of a servo, N·m; the rod force of a cylinder, N), the controller preset to
    /// hold it (the arm waits on its drive before the lift). `Err` with a reason when the
    /// actuator cannot hold it.
    pub fn holding(&mut self, angle_rad: f64, load: f64) -> Result<(DVector<f64>, DVector<f64>), String> {
        let torque_n_m = load;
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
                let (p, spool) =
                    h.holding_state(load).map_err(|why| format!("at {:.1} deg, {why}", angle_rad.to_degrees()))?;
                let ps = h.circuit.supply_pressure_pa;
                (v[0], v[1], v[2]) = (p[0] / ps, p[1] / ps, spool);
                self.controller.hold(spool);
                return Ok((x, v));
            }
        }
        self.controller.hold(torque_n_m);
        Ok((x, v))
    }

    /// What it reports at time `t_s` with the hub at `angle_rad`, at `stroke`, putting
    /// `hub_torque_n_m` on the hub.
    pub fn outputs(&self, t_s: f64, angle_rad: f64, stroke: Stroke, hub_torque_n_m: f64, v: &[f64]) -> ActuatorOutputs {
        let mut out = ActuatorOutputs {
            hub_torque_n_m,
            command: self.controller.output,
            tracking_error_rad: self.reference.sample(t_s).angle_rad - angle_rad,
            ..ActuatorOutputs::default()
        };
        if let Actuator::Hydraulic(h) = &self.actuator {
            let ps = h.circuit.supply_pressure_pa;
            out.rod_force_n = Some(rod_force_n(h, stroke, v));
            out.pressures_pa = Some([v[0] * ps, v[1] * ps]);
            out.cylinder_length_m = Some(stroke.position + stroke.series_flexibility_m_per_n * pressure_force_n(h, v));
        }
        out
    }
}

/// The rod's force from the chamber pressures, scaled `v[0..2]`, N.
fn pressure_force_n(h: &HydraulicDrive, v: &[f64]) -> f64 {
    let c = &h.cylinder;
    h.circuit.supply_pressure_pa * (v[0] * c.cap_area_m2() - v[1] * c.rod_area_m2())
}

/// Rod force (N) at `stroke` with scaled pressures `v[0..2]` and the spool `v[2]`: the pressures'
/// force and, past the stroke, the end cap's.
fn rod_force_n(h: &HydraulicDrive, stroke: Stroke, v: &[f64]) -> f64 {
    let c = &h.cylinder;
    let force = pressure_force_n(h, v);
    let length = stroke.position + stroke.series_flexibility_m_per_n * force;
    let extension = length - c.closed_length_m;
    if (0.0..=c.stroke_m).contains(&extension) {
        return force;
    }
    force + c.end_stop_force_n(length, ColumnFlow::at(h, stroke, v).rate_m_s)
}

/// The oil column under a series flexibility c: the cylinder's length is s + c F_p (F_p the
/// pressures' force) and its rate ṡ + c Ḟ_p, with Ḟ_p = Ḟ₀ − k ṡ_eff from the chamber equations
/// (Ḟ₀ the valve's flows' share, k = β (A₁²/V₁ + A₂²/V₂) the oil spring), so
/// ṡ_eff = (ṡ + c Ḟ₀) / (1 + c k): the column and the flexibility in series.
struct ColumnFlow {
    /// Chamber volumes (cap, rod), m³.
    volumes_m3: (f64, f64),
    /// Flows into the chambers through the valve, relief included (cap, rod), m³/s.
    flows_m3_s: [f64; 2],
    /// The cylinder's rate of extension, m/s.
    rate_m_s: f64,
}

impl ColumnFlow {
    fn at(h: &HydraulicDrive, stroke: Stroke, v: &[f64]) -> Self {
        let (c, circuit) = (&h.cylinder, &h.circuit);
        let ps = circuit.supply_pressure_pa;
        let flexibility = stroke.series_flexibility_m_per_n;
        let (v1, v2) = c.volumes_m3(stroke.position + flexibility * pressure_force_n(h, v));
        let (v1, v2) = (v1.max(1e-9), v2.max(1e-9));
        let flows = circuit.flows_m3_s(v[2].clamp(-1.0, 1.0), [v[0] * ps, v[1] * ps]);
        let (a1, a2, beta) = (c.cap_area_m2(), c.rod_area_m2(), circuit.bulk_modulus_pa);
        let rate_m_s = if flexibility > 0.0 {
            let force_rate = beta * (a1 * flows[0] / v1 - a2 * flows[1] / v2);
            let column = beta * (a1 * a1 / v1 + a2 * a2 / v2);
            (stroke.rate + flexibility * force_rate) / (1.0 + flexibility * column)
        } else {
            stroke.rate
        };
        ColumnFlow { volumes_m3: (v1, v2), flows_m3_s: flows, rate_m_s }
    }
}

/// Rates of the scaled pressures and of the spool (module doc of [`super::hydraulic`]).
fn hydraulic_rates(h: &HydraulicDrive, stroke: Stroke, command: f64, v: &[f64], f: &mut [f64]) {
    let (c, circuit) = (&h.cylinder, &h.circuit);
    let ColumnFlow { volumes_m3: (v1, v2), flows_m3_s: [q1, q2], rate_m_s } = ColumnFlow::at(h, stroke, v);
    let beta = circuit.bulk_modulus_pa / circuit.supply_pressure_pa;
    f[0] = beta / v1 * (q1 - c.cap_area_m2() * rate_m_s);
    f[1] = beta / v2 * (q2 + c.rod_area_m2() * rate_m_s);
    f[2] = (command - v[2]) / circuit.valve.spool_time_constant_s;
}

/// The spool command that feeds the reference forward (module doc of [`super::hydraulic`]).
fn hydraulic_feedforward(h: &HydraulicDrive, controller: &Controller, reference: &DriveState, v: &[f64]) -> f64 {
    let (_, arm) = h.cylinder.length_and_arm(reference.angle_rad);
    let gains = &controller.gains;
    let pressures = [v[0], v[1]].map(|p| p * h.circuit.supply_pressure_pa);
    gains.velocity_feedforward * h.feedforward_opening(arm * reference.rate_rad_s, pressures)
        + gains.acceleration_feedforward * reference.accel_rad_s2
}
