//! The discrete position controller an actuator runs: PID with feed-forward, sampled at its own
//! rate and held between samples (zero-order hold), its output saturated with anti-windup.
//!
//! At each sample, with e = θ_ref − y and ė = θ̇_ref − ẏ (y the measured angle, ẏ its rate):
//!
//! ```text
//! u = clamp(kp e + ki ∫e dt + kd ė + feed-forward, −limit, limit)
//! ```
//!
//! The integral grows only while the output is unsaturated or the error drives it back out of
//! saturation (conditional integration), so it cannot wind up against a stop. The derivative
//! acts on the rate error, measured directly (an encoder's speed), not on a differenced error.

use serde::{Deserialize, Serialize};

use crate::drive::DriveState;

/// Gains and sampling of a position controller. The output is a hub torque (N·m, servo) or a
/// spool opening (fraction of full opening, hydraulic); the gains are in that output's unit per
/// radian (kp), per radian·second (ki), per rad/s (kd and `velocity_feedforward`) and per rad/s²
/// (`acceleration_feedforward`); a hydraulic drive's feed-forward is scaled differently (see
/// [`crate::actuator::hydraulic`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerGains {
    /// Proportional gain.
    pub kp: f64,
    /// Integral gain.
    #[serde(default)]
    pub ki: f64,
    /// Derivative gain, on the rate error.
    #[serde(default)]
    pub kd: f64,
    /// Feed-forward of the reference rate.
    #[serde(default)]
    pub velocity_feedforward: f64,
    /// Feed-forward of the reference acceleration.
    #[serde(default)]
    pub acceleration_feedforward: f64,
    /// Sampling rate, Hz (default: one sample per scene step).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate_hz: Option<f64>,
}

/// A running controller: its gains, its period, what it holds and what it has integrated.
#[derive(Debug, Clone, PartialEq)]
pub struct Controller {
    /// Its gains.
    pub gains: ControllerGains,
    /// Sampling period, s.
    pub period_s: f64,
    /// Largest |output| (torque or spool limit).
    pub limit: f64,
    /// ∫e dt, rad·s.
    pub integral: f64,
    /// The output held since the last sample.
    pub output: f64,
    /// Time of the next sample, s.
    pub next_sample_s: f64,
}

impl Controller {
    /// A controller sampling every `period_s`, first at t = 0, output limited to ±`limit`.
    pub fn new(gains: ControllerGains, period_s: f64, limit: f64) -> Self {
        Controller { gains, period_s, limit, integral: 0.0, output: 0.0, next_sample_s: 0.0 }
    }

    /// Whether a sample is due at `t_s` (within a millionth of a period).
    pub fn due(&self, t_s: f64) -> bool {
        t_s >= self.next_sample_s - 1e-6 * self.period_s
    }

    /// Samples: computes and holds the output for the reference `reference`, the measured angle
    /// `angle_rad` and rate `rate_rad_s`, and the feed-forward `feedforward` (in output units).
    pub fn sample(&mut self, reference: &DriveState, angle_rad: f64, rate_rad_s: f64, feedforward: f64) -> f64 {
        let error = reference.angle_rad - angle_rad;
        let unsaturated = self.law(reference, angle_rad, rate_rad_s, feedforward);
        self.output = unsaturated.clamp(-self.limit, self.limit);
        let saturated = self.output != unsaturated;
        if !saturated || error.signum() != unsaturated.signum() {
            self.integral += error * self.period_s;
        }
        self.next_sample_s += self.period_s;
        self.output
    }

    /// The control law before saturation, with the integral as it stands: what the output would
    /// be if the controller sampled continuously.
    pub fn law(&self, reference: &DriveState, angle_rad: f64, rate_rad_s: f64, feedforward: f64) -> f64 {
        let g = &self.gains;
        let error = reference.angle_rad - angle_rad;
        g.kp * error + g.ki * self.integral + g.kd * (reference.rate_rad_s - rate_rad_s) + feedforward
    }

    /// The feed-forward of a reference in output units: `velocity_feedforward` θ̇_ref +
    /// `acceleration_feedforward` θ̈_ref.
    pub fn feedforward(&self, reference: &DriveState) -> f64 {
        self.gains.velocity_feedforward * reference.rate_rad_s
            + self.gains.acceleration_feedforward * reference.accel_rad_s2
    }

    /// Presets the integral so that, with zero error and rate, the output is `output`: a
    /// controller that has been holding the arm before the lift begins.
    pub fn hold(&mut self, output: f64) {
        if self.gains.ki > 0.0 {
            self.integral = output / self.gains.ki;
        }
        self.output = output;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gains(kp: f64, ki: f64) -> ControllerGains {
        ControllerGains { kp, ki, kd: 0.0, velocity_feedforward: 0.0, acceleration_feedforward: 0.0, rate_hz: None }
    }

    #[test]
    fn integral_stops_growing_while_saturated() {
        let mut c = Controller::new(gains(1.0, 10.0), 0.01, 1.0);
        let reference = DriveState { angle_rad: 5.0, ..DriveState::default() };
        for _ in 0..100 {
            c.sample(&reference, 0.0, 0.0, 0.0);
        }
        assert_eq!(c.output, 1.0);
        // Saturated from the first sample: one period of integration at most.
        assert!(c.integral <= 5.0 * 0.01 + 1e-12, "integral {}", c.integral);
        // An error of the other sign integrates again.
        c.sample(&DriveState { angle_rad: -1.0, ..DriveState::default() }, 0.0, 0.0, 0.0);
        assert!(c.integral < 0.05);
    }

    #[test]
    fn holds_its_output_between_samples() {
        let mut c = Controller::new(gains(2.0, 0.0), 0.01, 10.0);
        assert!(c.due(0.0));
        let u = c.sample(&DriveState { angle_rad: 1.0, ..DriveState::default() }, 0.25, 0.0, 0.0);
        assert_eq!(u, 1.5);
        assert!(!c.due(0.005));
        assert!(c.due(0.01));
    }
}
