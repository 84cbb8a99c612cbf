//! A servo drive: motor, gearbox and drive-train spring under a position controller.
//!
//! On the arm's side of the gearbox (ratio N), with φ the motor angle over N, J_m the rotor
//! inertia, k and c the drive train's torsional stiffness and damping between gearbox and hub:
//!
//! ```text
//! N² J_m φ̈ = τ − k (φ − θ) − c (φ̇ − θ̇)        motor, τ = N × motor torque (controller output)
//! torque on the hub = k (φ − θ) + c (φ̇ − θ̇)
//! ```
//!
//! The controller measures the motor's encoder (φ, φ̇): the collocated loop servo drives close.
//! The motor's current loop is taken as instantaneous (its bandwidth, kHz, is far above the
//! arm's), so the torque follows the controller's output; it saturates at N times the motor's
//! torque limit. The speed limit is checked against the reference before a run.

use serde::{Deserialize, Serialize};

use super::ControllerGains;

/// The machine's parts, from the URDF's `<pipearm:servo>` on the lift joint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoMachine {
    /// Gearbox ratio N (motor turns per hub turn), > 0.
    pub gear_ratio: f64,
    /// Motor rotor inertia (plus the fast gear stages'), kg·m², on the motor shaft.
    pub rotor_inertia_kg_m2: f64,
    /// Torsional stiffness of the drive train at the hub, N·m/rad.
    pub stiffness_n_m_per_rad: f64,
    /// Torsional damping of the drive train at the hub, N·m·s/rad.
    pub damping_n_m_s_per_rad: f64,
    /// Largest motor torque, N·m, on the motor shaft.
    pub torque_limit_n_m: f64,
    /// Largest motor speed, rad/s, on the motor shaft.
    pub speed_limit_rad_s: f64,
}

impl ServoMachine {
    /// The rotor's inertia seen at the hub, N² J_m, kg·m².
    pub fn reflected_inertia_kg_m2(&self) -> f64 {
        self.gear_ratio.powi(2) * self.rotor_inertia_kg_m2
    }

    /// Largest torque the motor gives at the hub, N·m.
    pub fn hub_torque_limit_n_m(&self) -> f64 {
        self.gear_ratio * self.torque_limit_n_m
    }

    /// Fastest hub rate the motor allows, rad/s.
    pub fn hub_speed_limit_rad_s(&self) -> f64 {
        self.speed_limit_rad_s / self.gear_ratio
    }

    /// Torque the drive train puts on the hub, N·m, with the motor at (φ, φ̇) and the hub at
    /// (θ, θ̇).
    pub fn spring_torque_n_m(&self, motor: (f64, f64), hub: (f64, f64)) -> f64 {
        self.stiffness_n_m_per_rad * (motor.0 - hub.0) + self.damping_n_m_s_per_rad * (motor.1 - hub.1)
    }
}

/// A servo drive: its machine and how it is controlled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoDrive {
    /// The machine.
    pub machine: ServoMachine,
    /// The position controller; its output is the hub-side motor torque, N·m.
    pub controller: ControllerGains,
}
