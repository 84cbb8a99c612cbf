//! Point contacts on the arm: a pad's force law evaluated on the arm's current configuration,
//! so that the implicit step sees the contact force at the end of the step.
//!
//! The geometry (station, face offset, normal, depth) comes from the contact source at the start
//! of a step; within the step the penetration follows the arm linearly along the normal:
//! `δ(q) = δ₀ − n·(r(θ, q) − r₀)`. A point carries its `share` of the law (a manifold's points
//! share the law equally) and Coulomb friction along the in-plane tangent, regularised over
//! [`FRICTION_SLIP_SPEED_M_S`]; the implicit steps' Jacobian leaves friction out.

use nalgebra::DVector;

use super::ArmModel;
use crate::contact::ForceLaw;
use crate::drive::DriveState;

/// Sliding speed over which friction rises to its full Coulomb value, m/s (a regularised
/// Coulomb law: F_t = −μ F_n v_t / √(v_t² + v_ε²)).
pub const FRICTION_SLIP_SPEED_M_S: f64 = 1e-3;

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
    /// The share of the law this point carries (1 for a single point; 1/N for each of the N
    /// points a pair's manifolds found).
    pub share: f64,
    /// Coulomb friction coefficient (0: frictionless).
    pub friction: f64,
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
    /// Friction force along the in-plane tangent (−n_y, n_x) of the world normal, N.
    pub friction_n: f64,
    /// World point of application, m.
    pub point_m: [f64; 2],
    /// The normal in the hub frame: the generalized force per newton is
    /// `normal_hub[0] · axial row + normal_hub[1] · transverse row` ([`ArmContact::direction`]).
    pub normal_hub: [f64; 2],
    /// Moment about the pivot of the normal and friction forces, N·m.
    pub moment_n_m: f64,
}

impl ArmModel {
    /// Projects a contact on the arm's own section at its station onto this model's coordinates.
    pub fn arm_contact(&self, contact: PointContact) -> ArmContact {
        let rows = self.station_rows(contact.station_m);
        ArmContact::on_section(contact, &rows, 0.0)
    }
}

impl ArmContact {
    /// A contact on a body carried rigidly by the section whose rows are `rows`, the point
    /// `along_m` beyond that section along the arm: it moves by (u − y φ, v + a φ).
    pub fn on_section(contact: PointContact, rows: &super::StationRows, along_m: f64) -> Self {
        let [u, v, phi] = &rows.0;
        let point_rows = [u - contact.lateral_m * phi, v + along_m * phi];
        ArmContact { contact, point_rows }
    }

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
        let elastic = [self.point_rows[0].dot(qd), self.point_rows[1].dot(qd)];
        let rate_m_s = -(nb[0] * elastic[0] + nb[1] * elastic[1] + spin);
        let force_n = c.share * c.law.force_n(depth_m, rate_m_s, c.impact_speed_m_s);
        let friction_n = if c.friction > 0.0 && force_n > 0.0 {
            // The point's speed along the tangent tb = (−nb_y, nb_x), elastic and from the spin.
            let slip = -nb[1] * elastic[0] + nb[0] * elastic[1] + hub.rate_rad_s * (nb[0] * r[0] + nb[1] * r[1]);
            -c.friction * force_n * slip / slip.hypot(FRICTION_SLIP_SPEED_M_S)
        } else {
            0.0
        };
        let moment_n_m =
            force_n * (point_m[0] * n[1] - point_m[1] * n[0]) + friction_n * (point_m[0] * n[0] + point_m[1] * n[1]);
        ContactState { depth_m, rate_m_s, force_n, friction_n, point_m, normal_hub: nb, moment_n_m }
    }

    /// Adds the generalized force of the contact's friction at `state` to `f`.
    pub fn add_friction(&self, state: &ContactState, f: &mut [f64]) {
        if state.friction_n == 0.0 {
            return;
        }
        let nb = state.normal_hub;
        for (row, tb) in self.point_rows.iter().zip([-nb[1], nb[0]]) {
            for (fi, ri) in f.iter_mut().zip(row.iter()) {
                *fi += state.friction_n * tb * ri;
            }
        }
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
        let (k, c) = self.contact.law.derivatives(state.depth_m, state.rate_m_s, self.contact.impact_speed_m_s);
        (self.contact.share * k, self.contact.share * c)
    }
}
