//! A hydraulic cylinder's pin on the deformed arm.

use nalgebra::DVector;

use super::products::dot;
use crate::actuator::{Cylinder, Stroke};

/// A cylinder's arm pin on the deformed arm, and what the rod force does through it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArmPin {
    /// Pin-to-pin length and its rate from the arm's coordinates, m and m/s.
    pub stroke: Stroke,
    /// Moment about the pivot per newton of rod force, m.
    pub lever_m: f64,
    /// The rod's direction (base to arm pin) in the hub frame.
    pub body_unit: [f64; 2],
}

impl ArmPin {
    /// The pin of `cylinder` on the arm, its hub-frame displacement `rows` over q, the hub at
    /// (θ, θ̇) and the arm at (q, q̇).
    pub(crate) fn at(cylinder: &Cylinder, rows: &[DVector<f64>; 2], hub: (f64, f64), q: &[f64], qd: &[f64]) -> Self {
        let [ax, ay] = cylinder.arm_pin_m;
        let body = [ax + dot(&rows[0], q), ay + dot(&rows[1], q)];
        // Hub-frame velocity of the pin: its elastic rate plus the frame's rotation θ̇ k × r.
        let body_rate = [dot(&rows[0], qd) - hub.1 * body[1], dot(&rows[1], qd) + hub.1 * body[0]];
        let (s, c) = hub.0.sin_cos();
        let world = |r: [f64; 2]| [c * r[0] - s * r[1], s * r[0] + c * r[1]];
        let (point, velocity) = (world(body), world(body_rate));
        let d = [point[0] - cylinder.base_pin_m[0], point[1] - cylinder.base_pin_m[1]];
        let length = d[0].hypot(d[1]);
        let unit = [d[0] / length, d[1] / length];
        ArmPin {
            stroke: Stroke { position: length, rate: unit[0] * velocity[0] + unit[1] * velocity[1] },
            lever_m: point[0] * unit[1] - point[1] * unit[0],
            body_unit: [c * unit[0] + s * unit[1], -s * unit[0] + c * unit[1]],
        }
    }
}
