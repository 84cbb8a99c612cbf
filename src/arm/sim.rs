//! Time-stepping the arm alone (no contact) and reading its outputs.

use std::borrow::Cow;
use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use super::dynamics::HubCache;
use super::pin::ArmPin;
use super::products::dot;
use super::{ArmContact, ArmError, ArmModel, ArmSystem, GeneralizedLoad, HeadState, HubDrive};
use crate::actuator::{Actuator, ActuatorOutputs, ActuatorPlant};
use crate::drive::DriveState;
use crate::integrate::{Integrator, IntegratorKind, State, StepControl};

/// Energies of the arm, J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energies {
    /// Kinetic energy of arm, masses and hub.
    pub kinetic_j: f64,
    /// Elastic strain energy ½ qᵀKq.
    pub strain_j: f64,
    /// Gravity potential relative to the pivot's height (foreshortening included).
    pub gravity_j: f64,
}

impl Energies {
    /// Sum of the three.
    pub fn total_j(&self) -> f64 {
        self.kinetic_j + self.strain_j + self.gravity_j
    }
}

/// What one step reports.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmSample {
    /// Time, s.
    pub t_s: f64,
    /// Hub angle, rate, acceleration.
    pub hub: DriveState,
    /// Tip displacement in the hub frame: [axial stretch, deflection], m.
    pub tip_deflection_hub_m: [f64; 2],
    /// Tip velocity relative to the hub frame: [axial, transverse], m/s.
    pub tip_velocity_hub_m_s: [f64; 2],
    /// Tip position in the world (pivot at the origin, Y up), m.
    pub tip_position_world_m: [f64; 2],
    /// Tip velocity in the world, m/s.
    pub tip_velocity_world_m_s: [f64; 2],
    /// Torque the drive applies at the pivot, N·m.
    pub drive_torque_n_m: f64,
    /// Energies.
    pub energies: Energies,
    /// Elastic coordinates q.
    pub q: DVector<f64>,
    /// What the actuator reports, if one drives the hub.
    pub actuator: Option<ActuatorOutputs>,
}

/// The arm, its drive and an integrator, stepped in time.
pub struct ArmSimulation {
    /// The model, compiled (shared with the runs that share it).
    pub arm: Arc<ArmModel>,
    /// The hub drive.
    pub drive: HubDrive,
    /// External load held over the next step.
    pub load: GeneralizedLoad,
    /// Pad contacts active over the next step (their force follows the arm within the step).
    pub contacts: Vec<ArmContact>,
    integrator: Box<dyn Integrator>,
    state: State,
    /// The state before a controlled step, to take it back.
    saved: State,
    rate_jumps: Vec<(f64, f64)>,
    /// Where the prescribed drive changes piece, s: controlled steps end there.
    breakpoints_s: Vec<f64>,
    /// The prescribed hub by time, shared by the integrator's evaluations and the outputs.
    hub: HubCache,
}

impl ArmSimulation {
    /// Starts at t = 0 at rest, the arm in static equilibrium under gravity at the start angle
    /// (a lift begins from the arm sagging on its hub, not from an undeformed arm dropped).
    /// An actuated hub starts at rest at its reference's start angle (less the drive's static
    /// lag), held there by the actuator ([`ActuatorPlant::holding`]).
    pub fn new(arm: impl Into<Arc<ArmModel>>, drive: HubDrive, integrator: IntegratorKind) -> Result<Self, ArmError> {
        let arm = arm.into();
        let n = arm.elastic_dofs();
        let start_rad = match drive {
            HubDrive::Prescribed(ref p) => p.sample(0.0).angle_rad,
            HubDrive::Free { .. } => 0.0,
            HubDrive::Actuated(plant) => return Self::held_by(arm, plant, integrator),
        };
        if arm.head.is_some() {
            let (q0, head, _) = super::head::static_with_head(&arm, start_rad, &DVector::zeros(n))?;
            let free = usize::from(drive.hub_is_free());
            let coordinate = arm.head_dofs() == 1;
            let x = DVector::from_iterator(
                free + n + arm.head_dofs(),
                std::iter::repeat_n(0.0, free).chain(q0.iter().copied()).chain(coordinate.then_some(head.angle_rad)),
            );
            let v = DVector::zeros(x.len());
            return Self::from_coordinates(arm, drive, integrator, x, v);
        }
        let q0 = arm.static_deflection(start_rad)?;
        Self::with_initial(arm, drive, integrator, q0, DVector::zeros(n))
    }

    /// Starts an actuated hub in static equilibrium, its actuator holding it.
    fn held_by(
        arm: Arc<ArmModel>,
        mut plant: Box<ActuatorPlant>,
        integrator: IntegratorKind,
    ) -> Result<Self, ArmError> {
        if let Actuator::Hydraulic(h) = &plant.actuator {
            let pins: Vec<[f64; 2]> = h.cylinders.each.iter().map(|c| c.arm_pin_m).collect();
            plant.arm_pins = Some(arm.pin_couplings(&pins)?);
        }
        let Hold { angle_rad: angle, q: q0, head, torque_n_m: load, levers_m } = static_hold(&arm, &plant)?;
        let (own_x, own_v) =
            plant.holding(angle, load, &levers_m).map_err(|why| ArmError::ActuatorCannotHold { load, why })?;
        let own = 1 + arm.elastic_dofs() + arm.head_dofs();
        let coordinates = std::iter::once(angle)
            .chain(q0.iter().copied())
            .chain(head.filter(|_| arm.head_dofs() == 1).map(|h| h.angle_rad))
            .chain(own_x.iter().copied());
        let x = DVector::from_iterator(own + own_x.len(), coordinates);
        let mut v = DVector::zeros(x.len());
        v.rows_mut(own, own_v.len()).copy_from(&own_v);
        Self::from_coordinates(arm, HubDrive::Actuated(plant), integrator, x, v)
    }

    /// Starts at t = 0 from elastic coordinates `q0` and rates `qd0`.
    pub fn with_initial(
        arm: impl Into<Arc<ArmModel>>,
        drive: HubDrive,
        integrator: IntegratorKind,
        q0: DVector<f64>,
        qd0: DVector<f64>,
    ) -> Result<Self, ArmError> {
        let arm = arm.into();
        let n = arm.elastic_dofs();
        if q0.len() != n || qd0.len() != n {
            return Err(ArmError::InvalidParameter {
                name: "initial q".into(),
                value: q0.len() as f64,
                allowed: format!("{n} elastic coordinates"),
            });
        }
        // A tilting head starts at its rest pose, at rest on the arm.
        let head = |z: DVector<f64>| z.push(0.0);
        let (q0, qd0) = if arm.head_dofs() == 1 { (head(q0), head(qd0)) } else { (q0, qd0) };
        let (x, v) = match &drive {
            HubDrive::Prescribed(_) => (q0, qd0),
            HubDrive::Free { .. } => (prepend(0.0, &q0), prepend(0.0, &qd0)),
            HubDrive::Actuated(_) => {
                return Err(ArmError::InvalidParameter {
                    name: "initial q".into(),
                    value: f64::NAN,
                    allowed: "an actuated hub starts held by its actuator (ArmSimulation::new)".into(),
                });
            }
        };
        Self::from_coordinates(arm, drive, integrator, x, v)
    }

    /// Starts at t = 0 from the integrator's coordinates `x` and rates `v`.
    fn from_coordinates(
        arm: Arc<ArmModel>,
        drive: HubDrive,
        integrator: IntegratorKind,
        x: DVector<f64>,
        v: DVector<f64>,
    ) -> Result<Self, ArmError> {
        let n = arm.elastic_dofs();
        let (rate_jumps, breakpoints_s) = match &drive {
            HubDrive::Prescribed(p) => (p.rate_jumps(), p.breakpoints_s()),
            HubDrive::Free { .. } | HubDrive::Actuated(_) => (Vec::new(), Vec::new()),
        };
        let load = GeneralizedLoad::zero(n);
        let hub = HubCache::default();
        let system = ArmSystem::new(&arm, &drive, &load, &[], &hub);
        let state = State::consistent(&system, 0.0, x, v)?;
        let mut sim = ArmSimulation {
            integrator: integrator.build()?,
            arm,
            drive,
            load,
            contacts: Vec::new(),
            saved: state.clone(),
            state,
            rate_jumps,
            breakpoints_s,
            hub,
        };
        sim.apply_rate_jumps_up_to(0.0)?;
        Ok(sim)
    }

    /// Sets the hub's rate of a free or actuated hub (an initial condition), rad/s.
    pub fn set_free_hub_rate(&mut self, rate_rad_s: f64) -> Result<(), ArmError> {
        if !self.drive.hub_is_free() {
            return Err(ArmError::InvalidParameter {
                name: "hub rate".into(),
                value: rate_rad_s,
                allowed: "a free hub only (a prescribed hub follows its drive)".into(),
            });
        }
        self.state.v[0] = rate_rad_s;
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        self.state.refresh_acceleration(&system)?;
        self.integrator.reset();
        Ok(())
    }

    /// Sets the tilting head's angle and rate (an initial condition).
    pub fn set_head_state(&mut self, head: HeadState) -> Result<(), ArmError> {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        let Some(i) = system.head_index() else {
            return Err(ArmError::InvalidParameter {
                name: "head".into(),
                value: head.angle_rad,
                allowed: "an arm with a tilting head (a spring hinge in its URDF)".into(),
            });
        };
        (self.state.x[i], self.state.v[i]) = (head.angle_rad, head.rate_rad_s);
        self.state.refresh_acceleration(&system)?;
        self.integrator.reset();
        Ok(())
    }

    /// Current time, s.
    pub fn time_s(&self) -> f64 {
        self.state.t
    }

    /// The integrator's state (q or [θ, q], their rates and accelerations).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Advances by `h_s` seconds, splitting the step at any jump of the drive's rate and at its
    /// controller's samples.
    pub fn step(&mut self, h_s: f64) -> Result<(), ArmError> {
        let t_end = self.state.t + h_s;
        if self.drive.plant().is_some() {
            return self.step_actuated(t_end);
        }
        let next_jump = self.rate_jumps.first().map(|j| j.0).filter(|&tj| tj <= t_end);
        if let Some(tj) = next_jump {
            self.advance(tj - self.state.t)?;
            self.apply_rate_jumps_up_to(tj)?;
            return self.advance(t_end - self.state.t);
        }
        self.advance(h_s)
    }

    /// Advances an actuated hub to `t_end`, sampling its controller wherever a sample falls due.
    fn step_actuated(&mut self, t_end: f64) -> Result<(), ArmError> {
        let tiny = 1e-9 * (t_end - self.state.t).abs().max(1e-12);
        loop {
            self.sample_controller();
            let next_sample = self.drive.plant().map_or(t_end, |p| p.next_sample_s());
            let stop = if next_sample < t_end - tiny { next_sample } else { t_end };
            self.advance(stop - self.state.t)?;
            if stop >= t_end - tiny {
                return Ok(());
            }
        }
    }

    /// Samples an actuator's controller if a sample is due; the held output enters one of the
    /// actuator's own equations linearly, so the state's acceleration there is brought up to
    /// date exactly (its mass is diagonal and apart from the arm's: no solve).
    fn sample_controller(&mut self) {
        let own = 1 + self.arm.elastic_dofs() + self.arm.head_dofs();
        let HubDrive::Actuated(plant) = &mut self.drive else { return };
        let s = &mut self.state;
        let output = plant.controller.output;
        plant.sample_if_due(s.t, (s.x[0], s.v[0]), &s.x.as_slice()[own..], &s.v.as_slice()[own..]);
        let (row, gain) = plant.command_row();
        s.a[own + row] += gain * (plant.controller.output - output) / plant.mass(row);
    }

    /// Advances by a step chosen by `control` from the integrator's local error estimate, at most
    /// `h_s`: a step whose tip error exceeds the tolerance is taken again, shorter. Returns the
    /// step taken and the step to try next, s. Without an error estimate (explicit methods) or
    /// across a jump of the drive's rate, the step is taken as asked.
    pub fn step_controlled(&mut self, h_s: f64, control: &StepControl) -> Result<(f64, f64), ArmError> {
        let t = self.state.t;
        let next_break = self.breakpoints_s.iter().copied().find(|&b| b > t + 1e-9 * h_s);
        let mut h = match next_break {
            Some(b) if b < t + h_s => b - t,
            _ => h_s,
        };
        loop {
            let t_end = self.state.t + h;
            let crosses_jump = self.rate_jumps.first().is_some_and(|j| j.0 <= t_end);
            self.saved.clone_from(&self.state);
            self.integrator.checkpoint();
            self.step(h)?;
            let Some(error_m) = self.local_tip_error_m().filter(|_| !crosses_jump) else {
                return Ok((h, h));
            };
            if control.accepts(h, error_m) {
                return Ok((h, control.next_step_s(h, error_m)));
            }
            self.state.clone_from(&self.saved);
            self.integrator.rollback();
            h = control.next_step_s(h, error_m).min(h);
        }
    }

    /// The integrator's estimate of the last step's local error, as displacement of the tip
    /// (the larger of axial and transverse, the hub's error included for a free hub), m.
    fn local_tip_error_m(&self) -> Option<f64> {
        let error = self.integrator.local_error()?;
        let [ru, rv, _] = self.arm.tip_rows();
        let n = self.arm.elastic_dofs();
        let (hub_error_rad, q_error) = match self.drive {
            HubDrive::Prescribed(_) => (0.0, &error.as_slice()[..n]),
            HubDrive::Free { .. } | HubDrive::Actuated(_) => (error[0], &error.as_slice()[1..1 + n]),
        };
        Some(dot(ru, q_error).abs().max((dot(rv, q_error) + self.arm.length_m() * hub_error_rad).abs()))
    }

    fn advance(&mut self, h: f64) -> Result<(), ArmError> {
        if h <= 1e-12 * self.state.t.abs().max(1.0) {
            return Ok(());
        }
        if self.state.x.is_empty() {
            self.state.t += h;
            return Ok(());
        }
        self.advance_halving(h, 0)
    }

    /// One integrator step of `h`; where Newton's iteration fails (a contact law's kink inside
    /// the step), the step is retried as two halves, down to 1/64 of it.
    fn advance_halving(&mut self, h: f64, depth: u32) -> Result<(), ArmError> {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        match self.integrator.step(&system, &mut self.state, h) {
            Err(crate::integrate::IntegrateError::NoConvergence { .. }) if depth < 6 => {
                // A failed step leaves the state as it was; the integrator's history is dropped.
                self.integrator.reset();
                self.advance_halving(0.5 * h, depth + 1)?;
                self.advance_halving(0.5 * h, depth + 1)
            }
            result => Ok(result?),
        }
    }

    /// A jump Δθ̇ of a prescribed rate is an impulse on q: M Δq̇ = −S̃ Δθ̇ (q's momentum equation
    /// integrated over the instant).
    fn apply_rate_jumps_up_to(&mut self, t: f64) -> Result<(), ArmError> {
        while let Some(&(tj, jump)) = self.rate_jumps.first() {
            if tj > t + 1e-12 {
                break;
            }
            self.rate_jumps.remove(0);
            if self.state.x.is_empty() {
                continue;
            }
            let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
            let coupling = system.hub_column(tj, &self.state.x);
            let mut mass = DMatrix::zeros(coupling.len(), coupling.len());
            crate::integrate::Dynamics::mass_matrix(&system, tj, &self.state.x, &mut mass);
            let dqd = mass
                .lu()
                .solve(&(-jump * coupling))
                .ok_or(ArmError::Integrate(crate::integrate::IntegrateError::SingularMatrix { t: tj }))?;
            self.state.v += dqd;
            self.state.refresh_acceleration(&system)?;
            self.integrator.reset();
        }
        Ok(())
    }

    /// Steps with `step_s` until `until_s`, handing each sample (the initial one included) to
    /// `observe`. The last step is shortened to land on `until_s`.
    pub fn run_until(
        &mut self,
        until_s: f64,
        step_s: f64,
        mut observe: impl FnMut(&ArmSample),
    ) -> Result<(), ArmError> {
        observe(&self.sample());
        let steps = ((until_s - self.state.t) / step_s).ceil().max(0.0) as usize;
        for _ in 0..steps {
            let h = step_s.min(until_s - self.state.t);
            self.step(h)?;
            observe(&self.sample());
        }
        Ok(())
    }

    /// Hub state and elastic coordinates q, q̇ at the current state, without the outputs
    /// [`Self::sample`] computes (torque, energies): what the step loop needs. Borrowed under a
    /// prescribed hub (q and q̇ are the integrator's coordinates), copied under a free one.
    pub fn kinematics(&self) -> (DriveState, Cow<'_, DVector<f64>>, Cow<'_, DVector<f64>>) {
        let s = &self.state;
        let n = self.arm.elastic_dofs();
        match &self.drive {
            HubDrive::Prescribed(profile) if self.arm.head.is_some() => (
                self.hub.at(profile, s.t).0,
                Cow::Owned(s.x.rows(0, n).into_owned()),
                Cow::Owned(s.v.rows(0, n).into_owned()),
            ),
            HubDrive::Prescribed(profile) => (self.hub.at(profile, s.t).0, Cow::Borrowed(&s.x), Cow::Borrowed(&s.v)),
            HubDrive::Free { .. } | HubDrive::Actuated(_) => {
                let (mut hub, q, qd) = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub)
                    .split_free_hub(&s.x, &s.v);
                hub.accel_rad_s2 = s.a[0];
                (hub, Cow::Owned(q), Cow::Owned(qd))
            }
        }
    }

    /// Elastic accelerations q̈ at the current state (the integrator's, consistent with the
    /// state's loads): borrowed under a prescribed hub, copied under a free one.
    pub fn elastic_accelerations(&self) -> Cow<'_, DVector<f64>> {
        let a = &self.state.a;
        match self.drive {
            HubDrive::Prescribed(_) if self.arm.head.is_some() => {
                Cow::Owned(a.rows(0, self.arm.elastic_dofs()).into_owned())
            }
            HubDrive::Prescribed(_) => Cow::Borrowed(a),
            HubDrive::Free { .. } | HubDrive::Actuated(_) => {
                Cow::Owned(a.rows(1, self.arm.elastic_dofs()).into_owned())
            }
        }
    }

    /// The tilting head's angle relative to the arm's section, and its rate, if there is one.
    pub fn head_state(&self) -> Option<HeadState> {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        system.head_state(self.state.t, &self.state.x, &self.state.v)
    }

    /// The torque a driven head's drive puts on the head now, N·m (`None` unless driven).
    pub fn head_drive_torque_n_m(&self) -> Option<f64> {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        let s = &self.state;
        system.head_drive_torque(s.t, &s.x, &s.v, &s.a)
    }

    /// What a tilting head puts on the arm beyond the mass the beam carries at its hinge
    /// (hub-frame point loads; none without a head), for the section forces.
    pub fn head_loads_on_arm(&self) -> Vec<crate::point_load::PointLoad<crate::point_load::Hub>> {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        let s = &self.state;
        system.head_loads_on_arm(s.t, &s.x, &s.v, &s.a)
    }

    /// Outputs at the current state.
    pub fn sample(&self) -> ArmSample {
        let system = ArmSystem::new(&self.arm, &self.drive, &self.load, &self.contacts, &self.hub);
        let s = &self.state;
        let (hub, q, qd) = self.kinematics();
        let qdd = self.elastic_accelerations();
        let [ru, rv, _] = self.arm.tip_rows();
        let (u, v, ud, vd) =
            (dot(ru, q.as_slice()), dot(rv, q.as_slice()), dot(ru, qd.as_slice()), dot(rv, qd.as_slice()));
        let l = self.arm.length_m();
        let (sn, cs) = hub.angle_rad.sin_cos();
        let w = hub.rate_rad_s;
        // World velocity: R(θ)[ṙ + θ̇ k × r] with r = (L + u, v) in the hub frame.
        let vel_body = [ud - w * v, vd + w * (l + u)];
        let (mut drive_torque_n_m, mut energies) = system.torque_and_energies(&hub, (sn, cs), &q, &qd, &qdd);
        if let Some((torque_n_m, [kinetic_j, strain_j, gravity_j])) =
            system.head_torque_and_energies(s.t, &s.x, &s.v, &s.a)
        {
            if !self.drive.hub_is_free() {
                drive_torque_n_m += torque_n_m;
            }
            energies.kinetic_j += kinetic_j;
            energies.strain_j += strain_j;
            energies.gravity_j += gravity_j;
        }
        let actuator = system.actuator_outputs(s.t, s.x.as_slice(), s.v.as_slice());
        if let Some(outputs) = &actuator {
            drive_torque_n_m = outputs.hub_torque_n_m;
        }
        ArmSample {
            t_s: s.t,
            hub,
            tip_deflection_hub_m: [u, v],
            tip_velocity_hub_m_s: [ud, vd],
            tip_position_world_m: [cs * (l + u) - sn * v, sn * (l + u) + cs * v],
            tip_velocity_world_m_s: [cs * vel_body[0] - sn * vel_body[1], sn * vel_body[0] + cs * vel_body[1]],
            drive_torque_n_m,
            energies,
            q: q.into_owned(),
            actuator,
        }
    }
}

fn prepend(first: f64, rest: &DVector<f64>) -> DVector<f64> {
    DVector::from_iterator(rest.len() + 1, std::iter::once(first).chain(rest.iter().copied()))
}

/// The arm at rest held by its actuator.
struct Hold {
    /// The hub's angle, rad.
    angle_rad: f64,
    /// The arm's deflection.
    q: DVector<f64>,
    /// The tilting head's rest, if there is one.
    head: Option<HeadState>,
    /// The actuator's torque on the hub, N·m.
    torque_n_m: f64,
    /// The cylinders' moment arms on the deflected arm, m (none for a servo).
    levers_m: Vec<f64>,
}

/// The hub's angle, the arm's deflection and the actuator's hub torque at rest with the
/// actuator holding the arm: gravity on the hub balanced by the actuator, the arm deflected by
/// gravity and by the cylinders' pin forces, the hub short of the reference by the drive's
/// static lag. Each depends on the others: a fixed point a stiff drive reaches in a few passes.
fn static_hold(arm: &ArmModel, plant: &ActuatorPlant) -> Result<Hold, ArmError> {
    let reference_rad = plant.reference.sample(0.0).angle_rad;
    let g = arm.options.gravity_m_s2;
    let n = arm.elastic_dofs();
    let (mut angle, mut pin_load, mut torque, mut levers) = (reference_rad, DVector::zeros(n), 0.0, Vec::new());
    let (mut q0, mut head) = (DVector::zeros(n), None);
    for _ in 0..12 {
        if arm.head.is_some() {
            let (q, rest, moment) = super::head::static_with_head(arm, angle, &pin_load)?;
            (q0, head, torque) = (q, Some(rest), -moment);
        } else {
            q0 = arm.static_deflection_under(angle, &pin_load)?;
            torque = -arm.gravity_moment_n_m(angle.sin_cos(), &q0, g);
        }
        if let (Actuator::Hydraulic(h), Some(couplings)) = (&plant.actuator, &plant.arm_pins) {
            let zero = vec![0.0; n];
            let pins: Vec<ArmPin> = h
                .cylinders
                .each
                .iter()
                .zip(&couplings.rows)
                .map(|(c, rows)| ArmPin::at(c, rows, (angle, 0.0), q0.as_slice(), &zero))
                .collect();
            levers = pins.iter().map(|p| p.lever_m).collect();
            // Every chamber pair holds the same pressures (HydraulicDrive::holding_state); where
            // they cannot, the actuator's holding says why.
            let Ok(([p1, p2], _)) = h.holding_state(torque, &levers) else { break };
            pin_load = DVector::zeros(n);
            for ((pin, rows), c) in pins.iter().zip(&couplings.rows).zip(&h.cylinders.each) {
                let force = p1 * c.cap_area_m2() - p2 * c.rod_area_m2();
                pin_load += force * (pin.body_unit[0] * &rows[0] + pin.body_unit[1] * &rows[1]);
            }
        }
        angle = reference_rad - plant.static_lag_rad(torque, &levers);
    }
    Ok(Hold { angle_rad: angle, q: q0, head, torque_n_m: torque, levers_m: levers })
}
