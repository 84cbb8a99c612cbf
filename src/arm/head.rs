//! A tilting head on the arm: a rigid body hinged on the arm's section at a station, its angle
//! ψ (relative to that section, about the lift axis z, 0 at the URDF pose) one more coordinate
//! of the arm's equations, solved in the same step as the hub and the modes.
//!
//! The arm's beam already carries the head's whole mass as a point at the hinge's station
//! ([`crate::robot::Robot::beam_spec`]), with that point's centrifugal and gravity stiffening of
//! the arm. What a point at the hinge misses is added here, exactly: the rigid head's mass matrix
//! and forces over z = [θ, q, ψ] by its Jacobians (virtual power), less the point's.
//!
//! ```text
//! c = h(q) + R(β) r₀,  h = (s + u_h, y + v_h),  β = φ_h + ψ      (hub frame)
//! J_v = [k × c | H + (k × ρ) Φ_φ | k × ρ],  J_ω = [1 | Φ_φ | 1],  ρ = R(β) r₀
//! M += m J_vᵀ J_v + J J_ωᵀ J_ω
//! f += m J_vᵀ (g_hub − 2θ̇ k × ċ + θ̇² c + β̇² ρ) − (k_ψ ψ + c_ψ ψ̇) e_ψ
//! ```
//! and the same terms with r₀ = 0, J = 0, the hinge's point on the arm's axis, subtracted.

use std::ops::AddAssign;

use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;

use super::products::dot;
use super::{ArmModel, ArmSystem, HubDrive};
use crate::drive::DriveState;
use crate::robot::TiltingHead;

/// The head compiled against an arm model's coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadModel {
    /// The head as the robot describes it.
    pub head: TiltingHead,
    /// Rows over q of the hinge point's (axial, transverse) displacement and of the section's
    /// slope at the hinge station.
    hinge_rows: [DVector<f64>; 3],
    /// Rows over q of the hinge station's point on the arm's axis (where the beam carries the
    /// head's mass).
    axis_rows: [DVector<f64>; 2],
}

/// The head's angle ψ relative to the arm's section and its rate, rad and rad/s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HeadState {
    /// ψ, rad.
    pub angle_rad: f64,
    /// ψ̇, rad/s.
    pub rate_rad_s: f64,
}

/// How much of the head's mass matrix over z = [θ, q, ψ] to write.
pub(crate) enum HeadMass<'m> {
    /// None: the forces alone.
    None,
    /// Its θ column (what a prescribed hub's θ̈ pushes on the rest).
    HubColumn(&'m mut DVector<f64>),
    /// All of it.
    Full(&'m mut DMatrix<f64>),
}

/// The full configuration the head's terms read: the hub (θ, θ̇), q, q̇ and ψ.
pub(crate) struct HeadFrame<'a> {
    pub hub: (f64, f64),
    pub q: &'a [f64],
    pub qd: &'a [f64],
    pub head: HeadState,
}

/// One body's kinematics in the hub frame: its centre, the centre's rate, its offset ρ from
/// the hinge (turned) and the turn rate β̇.
struct BodyPoint {
    centre: [f64; 2],
    rate: [f64; 2],
    rho: [f64; 2],
    turn_rate: f64,
}

impl BodyPoint {
    /// Its hub-frame acceleration at zero z̈, the hub turning at `hub_rate`:
    /// a_vp = 2θ̇ k × ċ − θ̇² c − β̇² ρ.
    fn velocity_product_accel(&self, hub_rate: f64) -> [f64; 2] {
        let (w, b2) = (hub_rate, self.turn_rate * self.turn_rate);
        [
            -2.0 * w * self.rate[1] - w * w * self.centre[0] - b2 * self.rho[0],
            2.0 * w * self.rate[0] - w * w * self.centre[1] - b2 * self.rho[1],
        ]
    }
}

/// Gravity `g_m_s2` in the hub frame, the hub at `theta_rad`, m/s².
fn gravity_in_hub(theta_rad: f64, g_m_s2: f64) -> [f64; 2] {
    let (s, c) = theta_rad.sin_cos();
    [-g_m_s2 * s, -g_m_s2 * c]
}

impl HeadModel {
    /// `head` on `arm`'s coordinates.
    pub fn new(arm: &ArmModel, head: &TiltingHead) -> Self {
        let [u, v, phi] = arm.station_rows(head.hinge_station_m).0;
        let hinge_u = &u - head.hinge_lateral_m * &phi;
        HeadModel { hinge_rows: [hinge_u, v.clone(), phi], axis_rows: [u, v], head: head.clone() }
    }

    fn head_point(&self, q: &[f64], qd: &[f64], head: HeadState) -> BodyPoint {
        let [ru, rv, rphi] = &self.hinge_rows;
        let h = &self.head;
        let beta = dot(rphi, q) + head.angle_rad;
        let turn_rate = dot(rphi, qd) + head.rate_rad_s;
        let (sb, cb) = beta.sin_cos();
        let [x0, y0] = h.centre_of_mass_m;
        let rho = [cb * x0 - sb * y0, sb * x0 + cb * y0];
        let centre = [h.hinge_station_m + dot(ru, q) + rho[0], h.hinge_lateral_m + dot(rv, q) + rho[1]];
        let rate = [dot(ru, qd) - turn_rate * rho[1], dot(rv, qd) + turn_rate * rho[0]];
        BodyPoint { centre, rate, rho, turn_rate }
    }

    fn axis_point(&self, q: &[f64], qd: &[f64]) -> BodyPoint {
        let [ru, rv] = &self.axis_rows;
        BodyPoint {
            centre: [self.head.hinge_station_m + dot(ru, q), dot(rv, q)],
            rate: [dot(ru, qd), dot(rv, qd)],
            rho: [0.0; 2],
            turn_rate: 0.0,
        }
    }

    /// The head's forces over z = [θ, q, ψ] (size n + 2) and as much of its mass matrix as
    /// `mass` asks, less the point at the hinge station the beam carries, gravity `g_m_s2`.
    pub(crate) fn terms(&self, at: &HeadFrame, g_m_s2: f64, mass: HeadMass, force: &mut DVector<f64>) {
        let n = at.q.len();
        let m = self.head.mass_kg;
        let body = self.head_point(at.q, at.qd, at.head);
        let point = self.axis_point(at.q, at.qd);
        let (body_j, point_j) = (self.jacobian(&body, n, true), self.jacobian(&point, n, false));
        let gravity = gravity_in_hub(at.hub.0, g_m_s2);
        // m (g − a_vp): the load at zero z̈.
        let load = |p: &BodyPoint| {
            let accel = p.velocity_product_accel(at.hub.1);
            [m * (gravity[0] - accel[0]), m * (gravity[1] - accel[1])]
        };
        let (body_load, point_load) = (load(&body), load(&point));
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        for (j, (bj, pj)) in body_j.iter().zip(&point_j).enumerate() {
            force[j] = dot(*bj, body_load) - dot(*pj, point_load);
        }
        force[n + 1] -= self.head.stiffness_n_m_per_rad() * at.head.angle_rad
            + self.head.damping_n_m_s_per_rad() * at.head.rate_rad_s;
        let spin = |j: usize| if j == 0 || j == n + 1 { 1.0 } else { self.hinge_rows[2][j - 1] };
        let inertia = self.head.inertia_kg_m2;
        let entry = |i: usize, j: usize| {
            m * (dot(body_j[i], body_j[j]) - dot(point_j[i], point_j[j])) + inertia * spin(i) * spin(j)
        };
        match mass {
            HeadMass::None => {}
            HeadMass::HubColumn(column) => column.iter_mut().enumerate().for_each(|(i, c)| *c = entry(i, 0)),
            HeadMass::Full(mass) => {
                for j in 0..n + 2 {
                    for i in 0..=j {
                        let e = entry(i, j);
                        mass[(i, j)] = e;
                        mass[(j, i)] = e;
                    }
                }
            }
        }
    }

    /// The velocity Jacobian of a point over z = [θ, q, ψ] in the hub frame, column by column
    /// (hub-frame x, y per coordinate).
    fn jacobian(&self, p: &BodyPoint, n: usize, turns: bool) -> SmallVec<[[f64; 2]; 16]> {
        let [ru, rv] =
            if turns { [&self.hinge_rows[0], &self.hinge_rows[1]] } else { [&self.axis_rows[0], &self.axis_rows[1]] };
        let phi = |i: usize| if turns { self.hinge_rows[2][i] } else { 0.0 };
        let mut j = SmallVec::with_capacity(n + 2);
        j.push([-p.centre[1], p.centre[0]]);
        j.extend((0..n).map(|i| [ru[i] - p.rho[1] * phi(i), rv[i] + p.rho[0] * phi(i)]));
        j.push(if turns { [-p.rho[1], p.rho[0]] } else { [0.0, 0.0] });
        j
    }

    /// A point's hub-frame velocity at the rates `z_rate` over z = [θ, q, ψ].
    fn velocity(jacobian: &[[f64; 2]], z_rate: &DVector<f64>) -> [f64; 2] {
        jacobian.iter().zip(z_rate.iter()).fold([0.0; 2], |v, (c, r)| [v[0] + c[0] * r, v[1] + c[1] * r])
    }

    /// Kinetic and potential energy the head adds to the arm's (the point at the hinge
    /// station aside), gravity `g_m_s2`, J: [kinetic, hinge spring, gravity].
    pub(crate) fn energies_j(&self, at: &HeadFrame, z_rate: &DVector<f64>, g_m_s2: f64) -> [f64; 3] {
        let n = at.q.len();
        let body = self.head_point(at.q, at.qd, at.head);
        let point = self.axis_point(at.q, at.qd);
        let square = |v: [f64; 2]| v[0] * v[0] + v[1] * v[1];
        let body_v = Self::velocity(&self.jacobian(&body, n, true), z_rate);
        let point_v = Self::velocity(&self.jacobian(&point, n, false), z_rate);
        let turn_rate = z_rate[0] + body.turn_rate;
        let kinetic = 0.5 * self.head.mass_kg * (square(body_v) - square(point_v))
            + 0.5 * self.head.inertia_kg_m2 * turn_rate * turn_rate;
        let spring = 0.5 * self.head.stiffness_n_m_per_rad() * at.head.angle_rad.powi(2);
        let d = [body.centre[0] - point.centre[0], body.centre[1] - point.centre[1]];
        let (s, c) = at.hub.0.sin_cos();
        let gravity = self.head.mass_kg * g_m_s2 * (s * d[0] + c * d[1]);
        [kinetic, spring, gravity]
    }
}

impl ArmModel {
    /// This model with `head` turning on it (its mass already on the beam at the hinge station):
    /// one more coordinate ψ, and the highest frequency the pair keeps, at rest, for an explicit
    /// integrator's step.
    pub fn with_head(mut self, head: Option<&TiltingHead>) -> Result<Self, super::ArmError> {
        let Some(head) = head else { return Ok(self) };
        let model = HeadModel::new(&self, head);
        if head.is_driven() {
            if head.profile().is_none() {
                return Err(super::ArmError::InvalidParameter {
                    name: "head.drive".into(),
                    value: f64::NAN,
                    allowed: format!("a drive for the driven hinge `{}` (the scenario's head.drive)", head.joint),
                });
            }
            self.head = Some(model);
            return Ok(self);
        }
        let n = self.elastic_dofs();
        let zeros = vec![0.0; n];
        let at = HeadFrame { hub: (0.0, 0.0), q: &zeros, qd: &zeros, head: HeadState::default() };
        let (mut mass, mut force) = (DMatrix::zeros(n + 2, n + 2), DVector::zeros(n + 2));
        model.terms(&at, 0.0, HeadMass::Full(&mut mass), &mut force);
        let mut coupled_mass = mass.view((1, 1), (n + 1, n + 1)).into_owned();
        let mut coupled_stiffness = DMatrix::zeros(n + 1, n + 1);
        coupled_mass.view_mut((0, 0), (n, n)).add_assign(&self.mass);
        coupled_stiffness.view_mut((0, 0), (n, n)).copy_from(&self.stiffness);
        coupled_stiffness[(n, n)] = head.stiffness_n_m_per_rad();
        let highest = crate::beam::solve_generalized(&coupled_stiffness, &coupled_mass)?.omegas_rad_s;
        self.highest_omega_rad_s = self.highest_omega_rad_s.max(highest.last().copied().unwrap_or(0.0));
        self.head = Some(model);
        Ok(self)
    }

    /// Coordinates the head adds: 1 with a tilting head on a spring, else 0 (a driven head's
    /// angle is its profile's).
    pub fn head_dofs(&self) -> usize {
        usize::from(self.head.as_ref().is_some_and(|h| !h.head.is_driven()))
    }
}

impl ArmSystem<'_> {
    /// Where the actuator's own coordinates start: after θ, q and the head's ψ.
    pub(crate) fn own_start(&self) -> usize {
        1 + self.arm.elastic_dofs() + self.arm.head_dofs()
    }

    /// Index of ψ among the integrator's coordinates: after q, and after θ where the hub is free.
    pub(crate) fn head_index(&self) -> Option<usize> {
        (self.arm.head_dofs() == 1).then(|| self.arm.elastic_dofs() + usize::from(self.drive.hub_is_free()))
    }

    /// A driven head's angle, rate and acceleration at `t` (rad, rad/s, rad/s²).
    fn driven_head(&self, t: f64) -> Option<DriveState> {
        self.arm.head.as_ref()?.head.profile().map(|p| p.sample(t))
    }

    /// Where entry `j` of z = [θ, q, ψ] sits among the integrator's coordinates (`None`:
    /// prescribed, a prescribed hub's θ or a driven head's ψ).
    fn z_coordinate(&self, j: usize) -> Option<usize> {
        let (n, first) = (self.arm.elastic_dofs(), usize::from(self.drive.hub_is_free()));
        match j {
            0 => (first == 1).then_some(0),
            j if j <= n => Some(first + j - 1),
            _ => self.head_index(),
        }
    }

    /// The accelerations of z's prescribed entries (θ̈ of a prescribed hub, ψ̈ of a driven head)
    /// at `t`, 0 for the others.
    fn prescribed_accels(&self, t: f64, theta_dd: f64) -> [f64; 2] {
        let hub = if self.drive.hub_is_free() { 0.0 } else { theta_dd };
        [hub, self.driven_head(t).map_or(0.0, |h| h.accel_rad_s2)]
    }

    /// The hub (θ, θ̇, θ̈ where prescribed, else 0) and the configuration at (t, x, v).
    fn head_frame<'x>(&self, t: f64, x: &'x DVector<f64>, v: &'x DVector<f64>) -> (f64, HeadFrame<'x>) {
        let n = self.arm.elastic_dofs();
        let (hub, first) = match self.drive {
            HubDrive::Prescribed(profile) => {
                let (hub, _) = self.hub.at(profile, t);
                ((hub.angle_rad, hub.rate_rad_s, hub.accel_rad_s2), 0)
            }
            _ => ((x[0], v[0], 0.0), 1),
        };
        let head = match self.driven_head(t) {
            Some(h) => HeadState { angle_rad: h.angle_rad, rate_rad_s: h.rate_rad_s },
            None => HeadState { angle_rad: x[first + n], rate_rad_s: v[first + n] },
        };
        let frame = HeadFrame {
            hub: (hub.0, hub.1),
            q: &x.as_slice()[first..first + n],
            qd: &v.as_slice()[first..first + n],
            head,
        };
        (hub.2, frame)
    }

    /// Adds the head's mass matrix over the integrator's coordinates to `m`.
    pub(super) fn add_head_mass(&self, t: f64, x: &DVector<f64>, m: &mut DMatrix<f64>) {
        let Some(head) = &self.arm.head else { return };
        let n = self.arm.elastic_dofs();
        let (_, at) = self.head_frame(t, x, x);
        let (mut mass, mut force) = (DMatrix::zeros(n + 2, n + 2), DVector::zeros(n + 2));
        head.terms(&at, self.arm.options.gravity_m_s2, HeadMass::Full(&mut mass), &mut force);
        for j in 0..n + 2 {
            let Some(cj) = self.z_coordinate(j) else { continue };
            for i in 0..n + 2 {
                if let Some(ci) = self.z_coordinate(i) {
                    m[(ci, cj)] += mass[(i, j)];
                }
            }
        }
    }

    /// The head's forces over the integrator's coordinates, added to `f`; the prescribed
    /// entries' accelerations (a prescribed hub's θ̈, a driven head's ψ̈) move to the right-hand
    /// side.
    pub(super) fn add_head_forces(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>, f: &mut DVector<f64>) {
        let Some(head) = &self.arm.head else { return };
        let n = self.arm.elastic_dofs();
        let (theta_dd, at) = self.head_frame(t, x, v);
        let [hub_dd, head_dd] = self.prescribed_accels(t, theta_dd);
        // The whole mass matrix only for a driven head's ψ̈ (its column); θ̈'s column alone else.
        let driven = head_dd != 0.0;
        let mut mass = if driven { DMatrix::zeros(n + 2, n + 2) } else { DMatrix::zeros(0, 0) };
        let (mut column, mut force) = (DVector::zeros(n + 2), DVector::zeros(n + 2));
        let asked = match (driven, hub_dd != 0.0) {
            (true, _) => HeadMass::Full(&mut mass),
            (false, true) => HeadMass::HubColumn(&mut column),
            (false, false) => HeadMass::None,
        };
        head.terms(&at, self.arm.options.gravity_m_s2, asked, &mut force);
        if driven {
            column.copy_from(&mass.column(0));
        }
        for j in 0..n + 2 {
            if let Some(cj) = self.z_coordinate(j) {
                let head_inertia = if driven { mass[(j, n + 1)] * head_dd } else { 0.0 };
                f[cj] += force[j] - column[j] * hub_dd - head_inertia;
            }
        }
    }

    /// A prescribed hub's forces over [q, ψ] with the head.
    pub(super) fn prescribed_forces_with_head(
        &self,
        t: f64,
        hub: &DriveState,
        trig: (f64, f64),
        x: &DVector<f64>,
        v: &DVector<f64>,
        f: &mut DVector<f64>,
    ) {
        let n = self.arm.elastic_dofs();
        let (q, qd) = (x.rows(0, n).into_owned(), v.rows(0, n).into_owned());
        f.fill(0.0);
        let elastic = &mut f.as_mut_slice()[..n];
        elastic.copy_from_slice(self.arm.coupling.as_slice());
        elastic.iter_mut().for_each(|fi| *fi *= -hub.accel_rad_s2);
        self.add_elastic_forces(hub, trig, &q, &qd, elastic);
        self.add_contact_forces(hub, &q, &qd, None, elastic);
        self.add_head_forces(t, x, v, f);
    }
}

impl ArmSystem<'_> {
    /// A prescribed hub's column of the whole mass matrix over the integrator's coordinates
    /// [q, ψ]: what a jump of θ̇ pushes on them.
    pub(super) fn hub_column(&self, t: f64, x: &DVector<f64>) -> DVector<f64> {
        let n = self.arm.elastic_dofs();
        let q = x.rows(0, n).into_owned();
        let mut column = DVector::zeros(x.len());
        column.rows_mut(0, n).copy_from(&(&self.arm.coupling + &self.arm.gyroscopic * &q));
        if let Some(head) = &self.arm.head {
            let (_, at) = self.head_frame(t, x, x);
            let (mut head_column, mut force) = (DVector::zeros(n + 2), DVector::zeros(n + 2));
            head.terms(&at, 0.0, HeadMass::HubColumn(&mut head_column), &mut force);
            for j in 1..n + 2 {
                if let Some(cj) = self.z_coordinate(j) {
                    column[cj] += head_column[j];
                }
            }
        }
        column
    }

    /// [θ part, q, ψ] over z: `hub` (θ̇ or θ̈), the q of the integrator's `values` (its rates or
    /// accelerations) and their ψ entry, or `head` (ψ̇ or ψ̈) for a driven head.
    fn over_z(&self, hub: f64, values: &DVector<f64>, head: f64) -> DVector<f64> {
        let n = self.arm.elastic_dofs();
        let first = usize::from(self.drive.hub_is_free());
        let psi = self.head_index().map_or(head, |i| values[i]);
        let q = values.rows(first, n);
        DVector::from_iterator(n + 2, std::iter::once(hub).chain(q.iter().copied()).chain([psi]))
    }

    /// θ̈: the integrator's `a` under a free hub, the prescribed `profile_rad_s2` otherwise.
    fn hub_accel(&self, profile_rad_s2: f64, a: &DVector<f64>) -> f64 {
        if self.drive.hub_is_free() { a[0] } else { profile_rad_s2 }
    }

    /// The head's angle and rate in the integrator's (x, v).
    pub(crate) fn head_state(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>) -> Option<HeadState> {
        self.arm.head.as_ref()?;
        Some(self.head_frame(t, x, v).1.head)
    }

    /// The head's share of the hub torque a prescribed drive applies (its θ row of M z̈ − f) and
    /// of the energies [kinetic, strain (the hinge spring), gravity], J, at the state (t, x, v, a).
    pub(super) fn head_torque_and_energies(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
    ) -> Option<(f64, [f64; 3])> {
        let head = self.arm.head.as_ref()?;
        let n = self.arm.elastic_dofs();
        let (theta_dd, at) = self.head_frame(t, x, v);
        let g = self.arm.options.gravity_m_s2;
        let (mut column, mut force) = (DVector::zeros(n + 2), DVector::zeros(n + 2));
        head.terms(&at, g, HeadMass::HubColumn(&mut column), &mut force);
        let (z_rate, z_accel) = self.z_rates(t, theta_dd, v, a, at.hub.1);
        let torque = column.dot(&z_accel) - force[0];
        Some((torque, head.energies_j(&at, &z_rate, g)))
    }

    /// ż and z̈ at the state (t, v, a), the hub's rate `theta_d` and prescribed θ̈ `theta_dd`.
    fn z_rates(
        &self,
        t: f64,
        theta_dd: f64,
        v: &DVector<f64>,
        a: &DVector<f64>,
        theta_d: f64,
    ) -> (DVector<f64>, DVector<f64>) {
        let driven = self.driven_head(t).unwrap_or_default();
        (self.over_z(theta_d, v, driven.rate_rad_s), self.over_z(self.hub_accel(theta_dd, a), a, driven.accel_rad_s2))
    }

    /// The torque a driven head's drive puts on the head at the state (t, x, v, a), N·m: its ψ
    /// row of M z̈ − f.
    pub(crate) fn head_drive_torque(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
    ) -> Option<f64> {
        let head = self.arm.head.as_ref().filter(|h| h.head.is_driven())?;
        let n = self.arm.elastic_dofs();
        let (theta_dd, at) = self.head_frame(t, x, v);
        let (mut mass, mut force) = (DMatrix::zeros(n + 2, n + 2), DVector::zeros(n + 2));
        head.terms(&at, self.arm.options.gravity_m_s2, HeadMass::Full(&mut mass), &mut force);
        let (_, z_accel) = self.z_rates(t, theta_dd, v, a, at.hub.1);
        Some(mass.row(n + 1).transpose().dot(&z_accel) - force[n + 1])
    }
}

/// The arm at rest with its head, the hub held at `angle_rad` and generalized forces `extra` on
/// q besides gravity (a cylinder holding the arm): (q, ψ) where every force on q and ψ balances,
/// by Newton's method from the arm's static deflection and ψ = 0, and the moment gravity then
/// puts on the hub, N·m.
pub(super) fn static_with_head(
    arm: &ArmModel,
    angle_rad: f64,
    extra: &DVector<f64>,
) -> Result<(DVector<f64>, HeadState, f64), super::ArmError> {
    let n = arm.elastic_dofs();
    let load = super::GeneralizedLoad { hub_torque_n_m: 0.0, modal: extra.clone() };
    let (drive, hub) = (HubDrive::Free { torque_n_m: 0.0 }, super::HubCache::default());
    let system = ArmSystem::new(arm, &drive, &load, &[], &hub);
    // The unknowns: q, and ψ on a spring (a driven head rests where its profile starts).
    let unknowns = n + arm.head_dofs();
    let mut x = DVector::zeros(1 + unknowns);
    x[0] = angle_rad;
    x.rows_mut(1, n).copy_from(&arm.static_deflection_under(angle_rad, extra)?);
    let v = DVector::zeros(1 + unknowns);
    let (mut f, mut k, mut c) = (
        DVector::zeros(1 + unknowns),
        DMatrix::zeros(1 + unknowns, 1 + unknowns),
        DMatrix::zeros(1 + unknowns, 1 + unknowns),
    );
    let rest = |x: &DVector<f64>, f: &mut DVector<f64>| {
        crate::integrate::Dynamics::forces(&system, 0.0, x, &v, f);
        let head = system.head_state(0.0, x, &v).unwrap_or_default();
        (x.rows(1, n).into_owned(), HeadState { rate_rad_s: 0.0, ..head }, f[0])
    };
    if unknowns == 0 {
        return Ok(rest(&x, &mut f));
    }
    for _ in 0..50 {
        crate::integrate::Dynamics::forces(&system, 0.0, &x, &v, &mut f);
        crate::integrate::finite_difference_tangents(&system, 0.0, &x, &v, &mut k, &mut c);
        let step = k.view((1, 1), (unknowns, unknowns)).into_owned().lu().solve(&f.rows(1, unknowns).into_owned());
        let Some(step) = step else { break };
        x.rows_mut(1, unknowns).add_assign(&step);
        if step.amax() <= 1e-13 * (1.0 + x.rows(1, unknowns).amax()) {
            return Ok(rest(&x, &mut f));
        }
    }
    Err(super::ArmError::InvalidParameter {
        name: "head".into(),
        value: angle_rad,
        allowed: "a hub angle at which the head's hinge spring finds a rest (Newton did not converge)".into(),
    })
}

impl ArmSystem<'_> {
    /// Tangents with a head: the arm's own over its coordinates, and the head's by central
    /// differences of its forces alone (a few flops each), over every coordinate.
    pub(super) fn tangents_with_head(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        k: &mut DMatrix<f64>,
        c: &mut DMatrix<f64>,
    ) {
        let dofs = x.len();
        if self.drive.hub_is_free() {
            // The free hub's tangents fill their blocks of the whole matrices; ψ's stay 0.
            self.arm_tangents(t, x, v, k, c);
        } else {
            let n = self.arm.elastic_dofs();
            let (mut k_arm, mut c_arm) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
            self.arm_tangents(t, &x.rows(0, n).into_owned(), &v.rows(0, n).into_owned(), &mut k_arm, &mut c_arm);
            k.fill(0.0);
            c.fill(0.0);
            k.view_mut((0, 0), (n, n)).copy_from(&k_arm);
            c.view_mut((0, 0), (n, n)).copy_from(&c_arm);
        }
        let (mut xp, mut vp) = (x.clone(), v.clone());
        let (mut plus, mut minus) = (DVector::zeros(dofs), DVector::zeros(dofs));
        for is_rate in [false, true] {
            for j in 0..dofs {
                let value = if is_rate { v[j] } else { x[j] };
                let h = 1e-7 * value.abs().max(1e-3);
                for (sign, out) in [(1.0, &mut plus), (-1.0, &mut minus)] {
                    let target = if is_rate { &mut vp } else { &mut xp };
                    target[j] = value + sign * h;
                    out.fill(0.0);
                    self.add_head_forces(t, &xp, &vp, out);
                }
                if is_rate {
                    vp[j] = value
                } else {
                    xp[j] = value
                }
                let tangent = if is_rate { &mut *c } else { &mut *k };
                for i in 0..dofs {
                    tangent[(i, j)] -= (plus[i] - minus[i]) / (2.0 * h);
                }
            }
        }
    }
}

impl ArmSystem<'_> {
    /// What the head puts on the arm beyond the point mass the beam carries at the hinge
    /// station, at the state (t, x, v, a), as hub-frame point loads on the arm there: the head's
    /// d'Alembert and gravity load m (g − a_c) at the hinge, less the point's m (g − a_p), with
    /// the hinge's couple (the mount's torque, or the wrist drive's reaction).
    pub(crate) fn head_loads_on_arm(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
    ) -> Vec<crate::point_load::PointLoad<crate::point_load::Hub>> {
        use crate::point_load::PointLoad;
        let Some(head) = &self.arm.head else { return Vec::new() };
        let n = self.arm.elastic_dofs();
        let (theta_dd, at) = self.head_frame(t, x, v);
        let (_, z_accel) = self.z_rates(t, theta_dd, v, a, at.hub.1);
        let gravity = gravity_in_hub(at.hub.0, self.arm.options.gravity_m_s2);
        let m = head.head.mass_kg;
        let body = head.head_point(at.q, at.qd, at.head);
        let point = head.axis_point(at.q, at.qd);
        let load = |p: &BodyPoint, turns: bool, sign: f64| {
            let [jx, jy] = HeadModel::velocity(&head.jacobian(p, n, turns), &z_accel);
            let [vx, vy] = p.velocity_product_accel(at.hub.1);
            [sign * m * (gravity[0] - jx - vx), sign * m * (gravity[1] - jy - vy)]
        };
        let station = head.head.hinge_station_m;
        let hinge = [body.centre[0] - body.rho[0], body.centre[1] - body.rho[1]];
        // The mount's torque on the arm, or the wrist drive's reaction.
        let couple = match self.head_drive_torque(t, x, v, a) {
            Some(drive_n_m) => -drive_n_m,
            None => {
                head.head.stiffness_n_m_per_rad() * at.head.angle_rad
                    + head.head.damping_n_m_s_per_rad() * at.head.rate_rad_s
            }
        };
        // One load at the hinge: the head's, less the point's moved there from the axis (its
        // moment about the hinge joins the spring's couple).
        let (on_hinge, off_point) = (load(&body, true, 1.0), load(&point, false, -1.0));
        let lever = [point.centre[0] - hinge[0], point.centre[1] - hinge[1]];
        let moved = lever[0] * off_point[1] - lever[1] * off_point[0];
        let force = [on_hinge[0] + off_point[0], on_hinge[1] + off_point[1]];
        vec![PointLoad::new(station, hinge, force).with_couple(couple + moved)]
    }
}
