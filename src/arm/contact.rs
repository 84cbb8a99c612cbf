//! Point contacts on the arm: a pad's force law evaluated on the arm's current configuration,
//! so that the implicit step sees the contact force at the end of the step.
//!
//! The geometry (station, face offset, normal, depth) comes from rapier's narrow phase at the
//! start of a step; within the step the penetration follows the arm linearly along the normal:
//! `δ(q) = δ₀ − n·(r(θ, q) − r₀)`.

use nalgebra::DVector;

use super::ArmModel;
use crate::contact::ForceLaw;
use crate::drive::DriveState;

/// A contact between a point of the arm (or of a body it carries rigidly) and a pad.
#[derive(Debug, Clone, PartialEq)]
pub struct PointContact {
    /// Index of the contact pair it belongs to, for reporting.
    pub pair: usize,
    /// Arm station of the contact point, m.
    pub station_m: f64,
    /// Offset of the contact point across the arm in the lift plane (body y), m.
    pub lateral_m: f64,
    /// Unit normal in the world (X, Y) along which the pad pushes the arm.
    pub normal_world: [f64; 2],
    /// Penetration at the reference configuration, m (negative: a gap).
    pub depth_m: f64,
    /// World position (X, Y) of the arm's contact point at the reference configuration, m.
    pub reference_point_m: [f64; 2],
    /// The pad's force law.
    pub law: ForceLaw,
    /// Closing speed at first touch, m/s (the v₀ of restitution laws).
    pub impact_speed_m_s: f64,
}

/// A [`PointContact`] with its shape rows projected on the arm's coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmContact {
    /// The contact.
    pub contact: PointContact,
    /// The contact point's hub-frame displacement rows: axial Φᵀ(N_u − y N_φ), transverse Φᵀ N_v.
    point_rows: [DVector<f64>; 2],
}

/// A contact's state and generalized force at one configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactState {
    /// Penetration, m.
    pub depth_m: f64,
    /// Closing rate, m/s.
    pub rate_m_s: f64,
    /// Normal force, N.
    pub force_n: f64,
    /// World point of application, m.
    pub point_m: [f64; 2],
    /// The normal in the hub frame: the generalized force per newton is
    /// `normal_hub[0] · axial row + normal_hub[1] · transverse row` ([`ArmContact::direction`]).
    pub normal_hub: [f64; 2],
    /// Moment about the pivot, N·m.
    pub moment_n_m: f64,
}

impl ArmModel {
    /// Projects a contact onto this model's coordinates.
    pub fn arm_contact(&self, contact: PointContact) -> ArmContact {
        let [u, v, phi] = self.station_rows(contact.station_m).0;
        let point_rows = [u - contact.lateral_m * phi, v];
        ArmContact { contact, point_rows }
    }
}

impl ArmContact {
    /// Contact point in the hub frame: (x + u − y φ, y + v), m.
    fn point_body(&self, q: &DVector<f64>) -> [f64; 2] {
        let c = &self.contact;
        [c.station_m + self.point_rows[0].dot(q), c.lateral_m + self.point_rows[1].dot(q)]
    }

    /// Evaluates penetration, force and generalized force direction at (θ, θ̇, q, q̇).
    pub fn state(&self, hub: &DriveState, q: &DVector<f64>, qd: &DVector<f64>) -> ContactState {
        let c = &self.contact;
        let (s, co) = hub.angle_rad.sin_cos();
        let r = self.point_body(q);
        let point_m = [co * r[0] - s * r[1], s * r[0] + co * r[1]];
        let n = c.normal_world;
        // Normal in the hub frame, and the point's velocity along it.
        let nb = [co * n[0] + s * n[1], -s * n[0] + co * n[1]];
        let spin = hub.rate_rad_s * (nb[1] * r[0] - nb[0] * r[1]);
        let depth_m =
            c.depth_m - (n[0] * (point_m[0] - c.reference_point_m[0]) + n[1] * (point_m[1] - c.reference_point_m[1]));
        let rate_m_s = -(nb[0] * self.point_rows[0].dot(qd) + nb[1] * self.point_rows[1].dot(qd) + spin);
        let force_n = c.law.force_n(depth_m, rate_m_s, c.impact_speed_m_s);
        let moment_n_m = force_n * (point_m[0] * n[1] - point_m[1] * n[0]);
        ContactState { depth_m, rate_m_s, force_n, point_m, normal_hub: nb, moment_n_m }
    }

    /// Adds `scale` × the generalized force per newton of the contact at `state` to `f`.
    pub fn add_direction(&self, state: &ContactState, scale: f64, f: &mut [f64]) {
        for (row, nb) in self.point_rows.iter().zip(state.normal_hub) {
            for (fi, ri) in f.iter_mut().zip(row.iter()) {
                *fi += scale * nb * ri;
            }
        }
    }

    /// The generalized force per newton of the contact at `state` (∂Q/∂F).
    pub fn direction(&self, state: &ContactState) -> DVector<f64> {
        let mut d = DVector::zeros(self.point_rows[0].len());
        self.add_direction(state, 1.0, d.as_mut_slice());
        d
    }

    /// The normal's lever about the pivot at `state`, m: the moment per newton, and how fast the
    /// penetration closes per radian of hub rotation.
    pub fn lever_m(&self, state: &ContactState) -> f64 {
        let n = self.contact.normal_world;
        state.point_m[0] * n[1] - state.point_m[1] * n[0]
    }

    /// (∂F/∂δ, ∂F/∂δ̇) at a state.
    pub fn stiffness_damping(&self, state: &ContactState) -> (f64, f64) {
        self.contact.law.derivatives(state.depth_m, state.rate_m_s, self.contact.impact_speed_m_s)
    }
}
