//! The arm's equations of motion as a [`Dynamics`] system.

use std::cell::{Cell, RefCell};

use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;

use super::pin::ArmPin;
use super::products::{add_product, bilinear, dot, product};
use super::{ArmContact, ArmModel, Energies};
use crate::actuator::{Actuator, ActuatorOutputs, ActuatorPlant, CylinderStrokes, Stroke, Strokes};
use crate::drive::{DriveState, MotionProfile};
use crate::integrate::Dynamics;

/// How the hub moves.
#[derive(Debug, Clone, PartialEq)]
pub enum HubDrive {
    /// θ(t) prescribed; the torque that realizes it is an output. Coordinates: q.
    Prescribed(MotionProfile),
    /// θ integrated under a constant applied torque, N·m. Coordinates: [θ, q].
    Free { torque_n_m: f64 },
    /// θ integrated under an actuator tracking a reference. Coordinates: [θ, q, the actuator's
    /// own] ([`ActuatorPlant`]).
    Actuated(Box<ActuatorPlant>),
}

impl HubDrive {
    /// Whether θ is a coordinate (a free or actuated hub) rather than prescribed.
    pub fn hub_is_free(&self) -> bool {
        !matches!(self, HubDrive::Prescribed(_))
    }

    /// The actuator, if one drives the hub.
    pub fn plant(&self) -> Option<&ActuatorPlant> {
        match self {
            HubDrive::Actuated(plant) => Some(plant),
            _ => None,
        }
    }
}

/// External loads already mapped to generalized forces, held over a step.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralizedLoad {
    /// Moment about the pivot, N·m.
    pub hub_torque_n_m: f64,
    /// Forces on the elastic coordinates.
    pub modal: DVector<f64>,
}

impl GeneralizedLoad {
    /// No load on an arm with `elastic_dofs` coordinates.
    pub fn zero(elastic_dofs: usize) -> Self {
        GeneralizedLoad { hub_torque_n_m: 0.0, modal: DVector::zeros(elastic_dofs) }
    }

    /// Back to no load, in place.
    pub fn clear(&mut self) {
        self.hub_torque_n_m = 0.0;
        self.modal.fill(0.0);
    }

    /// Adds another load.
    pub fn add(&mut self, other: &GeneralizedLoad) {
        self.hub_torque_n_m += other.hub_torque_n_m;
        self.modal += &other.modal;
    }
}

/// The arm with its drive and load, seen by an integrator.
pub struct ArmSystem<'a> {
    /// The model.
    pub arm: &'a ArmModel,
    /// The hub drive.
    pub drive: &'a HubDrive,
    /// External loads.
    pub load: &'a GeneralizedLoad,
    /// Pad contacts, evaluated on the current configuration.
    pub contacts: &'a [ArmContact],
    /// The prescribed hub by time, shared with the simulation's outputs.
    pub(super) hub: &'a HubCache,
    /// A free hub's buffers, reused by every evaluation within the step.
    scratch: RefCell<FreeHubScratch>,
}

/// Buffers of a free hub's evaluations: q and q̇ split off the integrator's vectors, and the
/// mass solve's intermediates (several evaluations a step; on a 3-mode arm an allocation costs
/// more than the arithmetic it serves).
#[derive(Debug, Default)]
struct FreeHubScratch {
    q: DVector<f64>,
    qd: DVector<f64>,
    coupling: DVector<f64>,
    y: DVector<f64>,
    w: DVector<f64>,
}

impl FreeHubScratch {
    /// q and q̇ from the integrator's [θ, q, …] coordinates and rates.
    fn split(&mut self, x: &DVector<f64>, v: &DVector<f64>, n: usize) {
        for buffer in [&mut self.q, &mut self.qd, &mut self.coupling, &mut self.y, &mut self.w] {
            if buffer.len() != n {
                *buffer = DVector::zeros(n);
            }
        }
        self.q.copy_from(&x.rows(1, n));
        self.qd.copy_from(&v.rows(1, n));
    }
}

/// A prescribed hub at the last time asked, with (sin, cos) of its angle: RK4 evaluates twice at
/// the half step, its last stage and the end-of-step acceleration at the same time, and the
/// outputs and the scene's checks ask again at that time.
#[derive(Debug, Default)]
pub struct HubCache(Cell<Option<HubAt>>);

/// Time (s), the hub's state then, and (sin, cos) of its angle.
type HubAt = (f64, DriveState, (f64, f64));

impl HubCache {
    /// `profile` at `t`, s, and (sin, cos) of its angle.
    pub fn at(&self, profile: &MotionProfile, t: f64) -> (DriveState, (f64, f64)) {
        if let Some((cached_t, hub, trig)) = self.0.get()
            && cached_t == t
        {
            return (hub, trig);
        }
        let hub = profile.sample(t);
        let trig = hub.angle_rad.sin_cos();
        self.0.set(Some((t, hub, trig)));
        (hub, trig)
    }
}

impl<'a> ArmSystem<'a> {
    /// The arm under its drive, loads and contacts; `hub` remembers the prescribed hub by time.
    pub fn new(
        arm: &'a ArmModel,
        drive: &'a HubDrive,
        load: &'a GeneralizedLoad,
        contacts: &'a [ArmContact],
        hub: &'a HubCache,
    ) -> Self {
        ArmSystem { arm, drive, load, contacts, hub, scratch: RefCell::default() }
    }

    /// A free hub's state and q, q̇ from the integrator's coordinates [θ, q] (the hub's
    /// acceleration is unknown here and reported as 0).
    pub fn split_free_hub(&self, x: &DVector<f64>, v: &DVector<f64>) -> (DriveState, DVector<f64>, DVector<f64>) {
        let n = self.arm.elastic_dofs();
        let hub = DriveState { angle_rad: x[0], rate_rad_s: v[0], accel_rad_s2: 0.0, jerk_rad_s3: 0.0 };
        (hub, x.rows(1, n).into_owned(), v.rows(1, n).into_owned())
    }

    /// Adds the elastic generalized forces and the hub's known θ̈ = `hub.accel_rad_s2` on C q,
    /// without θ̈ S and the contacts, to `f` (allocation-free: it runs several times a step):
    /// −(D + 2θ̇C) q̇ − (K − θ̇²W − g s K_g + θ̈ C) q + θ̇² a − g s b_u − g c b_v + Q_q. A free
    /// hub's θ̈ is unknown here (0 in its state): its mass matrix carries the whole θ̈ S̃.
    pub(super) fn add_elastic_forces(
        &self,
        hub: &DriveState,
        (s, c): (f64, f64),
        q: &DVector<f64>,
        qd: &DVector<f64>,
        f: &mut [f64],
    ) {
        let a = self.arm;
        let (w, g) = (hub.rate_rad_s, a.options.gravity_m_s2);
        let n = f.len();
        let (qs, qds) = (&q.as_slice()[..n], &qd.as_slice()[..n]);
        // One pass over the five matrices, column by column (their storage order): −K_t q − C_t q̇.
        let matrices = [&a.stiffness, &a.spin_mass, &a.gravity_stiffness, &a.damping, &a.gyroscopic];
        let [k, spin, kg, d, gyro] = matrices.map(|m| m.as_slice());
        let (w2, two_w, acc) = (w * w, 2.0 * w, hub.accel_rad_s2);
        for j in 0..n {
            let column = j * n..(j + 1) * n;
            let (k, spin, kg) = (&k[column.clone()], &spin[column.clone()], &kg[column.clone()]);
            let (d, gyro) = (&d[column.clone()], &gyro[column]);
            let (qj, qdj) = (qs[j], qds[j]);
            for i in 0..n {
                f[i] += (w2 * spin[i] + s * kg[i] - k[i] - acc * gyro[i]) * qj - (d[i] + two_w * gyro[i]) * qdj;
            }
        }
        let vectors = [&a.axial_moment, &a.axial_mass, &a.transverse_mass, &self.load.modal];
        let [moment, axial, transverse, load] = vectors.map(|v| &v.as_slice()[..n]);
        for i in 0..n {
            f[i] += w * w * moment[i] - g * s * axial[i] - g * c * transverse[i] + load[i];
        }
    }

    /// Adds the pad contacts' generalized forces: on q to `f_q`, and their moment about the pivot
    /// to `f_theta` where the hub is free (each contact evaluated once).
    pub(super) fn add_contact_forces(
        &self,
        hub: &DriveState,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        mut f_theta: Option<&mut f64>,
        f_q: &mut [f64],
    ) {
        for contact in self.contacts {
            let state = contact.state(hub, q, qd);
            contact.add_direction(&state, state.force_n, f_q);
            contact.add_friction(&state, f_q);
            if let Some(f) = f_theta.as_deref_mut() {
                *f += state.moment_n_m;
            }
        }
    }

    /// Hub generalized force without inertia, the hub angle's (sin, cos) given:
    /// τ_applied + Q_θ − 2θ̇(a + Wq)ᵀq̇ + gravity moment (the contacts' moment in Q_θ if
    /// `with_contacts`).
    fn hub_force_at(
        &self,
        hub: &DriveState,
        trig: (f64, f64),
        q: &DVector<f64>,
        qd: &DVector<f64>,
        applied_n_m: f64,
        with_contacts: bool,
    ) -> f64 {
        self.hub_force_with(&self.forms(q, qd), hub, trig, (q, qd), applied_n_m, with_contacts)
    }

    /// [`Self::hub_force_at`] with the quadratic forms of (q, q̇) given.
    fn hub_force_with(
        &self,
        forms: &Forms,
        hub: &DriveState,
        trig: (f64, f64),
        (q, qd): (&DVector<f64>, &DVector<f64>),
        applied_n_m: f64,
        with_contacts: bool,
    ) -> f64 {
        let a = self.arm;
        let g = a.options.gravity_m_s2;
        let spin = 2.0 * hub.rate_rad_s * (dot(&a.axial_moment, qd.as_slice()) + forms.qd_spin_q);
        let contact: f64 =
            if with_contacts { self.contacts.iter().map(|k| k.state(hub, q, qd).moment_n_m).sum() } else { 0.0 };
        applied_n_m + self.load.hub_torque_n_m + contact - spin + a.gravity_moment_with(trig, q, g, forms.q_kg_q)
    }

    /// The quadratic forms in (q, q̇) of the hub's equation and the energies, W q multiplied once.
    fn forms(&self, q: &DVector<f64>, qd: &DVector<f64>) -> Forms {
        let a = self.arm;
        let spin_q = product(&a.spin_mass, q);
        Forms {
            q_spin_q: dot(&spin_q, q.as_slice()),
            qd_spin_q: dot(&spin_q, qd.as_slice()),
            q_kg_q: bilinear(&a.gravity_stiffness, q, q),
        }
    }

    /// Ĵ(q) = J₀ + 2aᵀq + qᵀWq, kg·m².
    fn pivot_inertia(&self, q: &DVector<f64>) -> f64 {
        self.pivot_inertia_with(q, bilinear(&self.arm.spin_mass, q, q))
    }

    /// [`Self::pivot_inertia`] with qᵀWq given.
    fn pivot_inertia_with(&self, q: &DVector<f64>, q_spin_q: f64) -> f64 {
        let a = self.arm;
        a.pivot_inertia_kg_m2 + 2.0 * dot(&a.axial_moment, q.as_slice()) + q_spin_q
    }

    /// S̃ = S + C q.
    fn coupling(&self, q: &DVector<f64>) -> DVector<f64> {
        &self.arm.coupling + &self.arm.gyroscopic * q
    }

    /// S̃ · y = S·y + (C q)·y, without forming S̃.
    fn coupling_dot(&self, q: &DVector<f64>, y: &DVector<f64>) -> f64 {
        dot(&self.arm.coupling, y.as_slice()) + bilinear(&self.arm.gyroscopic, y, q)
    }

    /// Kinetic, strain and gravity energy at (hub, q, q̇), J.
    pub fn energies(&self, hub: &DriveState, q: &DVector<f64>, qd: &DVector<f64>) -> Energies {
        let quadratic = (self.pivot_inertia(q), self.coupling_dot(q, qd), bilinear(&self.arm.gravity_stiffness, q, q));
        self.energies_with(hub, hub.angle_rad.sin_cos(), quadratic, q, qd)
    }

    /// [`Self::energies`] with the hub angle's (sin, cos), Ĵ(q), S̃·q̇ and qᵀK_g q given.
    fn energies_with(
        &self,
        hub: &DriveState,
        (s, c): (f64, f64),
        (pivot_inertia, coupling_qd, q_kg_q): (f64, f64, f64),
        q: &DVector<f64>,
        qd: &DVector<f64>,
    ) -> Energies {
        let a = self.arm;
        let w = hub.rate_rad_s;
        let kinetic_j = 0.5 * w * w * pivot_inertia + w * coupling_qd + 0.5 * bilinear(&a.mass, qd, qd);
        let g = a.options.gravity_m_s2;
        let gravity_j = g * s * (a.first_moment_kg_m + dot(&a.axial_mass, q.as_slice()))
            + g * c * dot(&a.transverse_mass, q.as_slice())
            - 0.5 * s * q_kg_q;
        Energies { kinetic_j, strain_j: 0.5 * bilinear(&a.stiffness, q, q), gravity_j }
    }

    /// The torque the drive applies to realize the hub motion, given q̈ (N·m), and the energies
    /// (J) together: what every step records, sharing the hub's
    /// trigonometry `trig` = (sin θ, cos θ) (the caller has it), Ĵ(q) and the products of q with
    /// W, C and K_g, each matrix multiplied once (this runs every step).
    pub fn torque_and_energies(
        &self,
        hub: &DriveState,
        trig: (f64, f64),
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> (f64, Energies) {
        let a = self.arm;
        let forms = self.forms(q, qd);
        let inertia = self.pivot_inertia_with(q, forms.q_spin_q);
        let gyro_q = product(&a.gyroscopic, q);
        let coupling_dot = |y: &DVector<f64>| dot(&a.coupling, y.as_slice()) + dot(&gyro_q, y.as_slice());
        let torque_n_m = match self.drive {
            HubDrive::Free { torque_n_m } => *torque_n_m,
            // The actuator's torque depends on its own coordinates: the simulation reports it.
            HubDrive::Actuated(_) => f64::NAN,
            HubDrive::Prescribed(_) => {
                inertia * hub.accel_rad_s2 + coupling_dot(qdd)
                    - self.hub_force_with(&forms, hub, trig, (q, qd), 0.0, true)
            }
        };
        (torque_n_m, self.energies_with(hub, trig, (inertia, coupling_dot(qd), forms.q_kg_q), q, qd))
    }
}

impl ArmSystem<'_> {
    /// Torque applied at the hub by a free hub's constant torque, N·m (an actuator's loads are
    /// added by [`Self::add_actuator_forces`]).
    fn applied_torque_n_m(&self) -> f64 {
        match self.drive {
            HubDrive::Free { torque_n_m } => *torque_n_m,
            _ => 0.0,
        }
    }

    /// The actuator's strokes at (x, v), and the cylinders' pins on the deformed arm.
    fn actuator_strokes(&self, plant: &ActuatorPlant, x: &[f64], v: &[f64]) -> (Strokes, SmallVec<[ArmPin; 2]>) {
        match (&plant.actuator, &plant.arm_pins) {
            (Actuator::Hydraulic(h), Some(couplings)) => {
                let n = self.arm.elastic_dofs();
                let (q, qd) = (&x[1..1 + n], &v[1..1 + n]);
                let pins: SmallVec<[ArmPin; 2]> = h
                    .cylinders
                    .each
                    .iter()
                    .zip(&couplings.rows)
                    .map(|(c, rows)| ArmPin::at(c, rows, (x[0], v[0]), q, qd))
                    .collect();
                let units: SmallVec<[[f64; 2]; 2]> = pins.iter().map(|p| p.body_unit).collect();
                let strokes = CylinderStrokes {
                    strokes: pins.iter().map(|p| p.stroke).collect(),
                    flexibility_m_per_n: couplings.flexibility_along_m_per_n(&units),
                };
                (Strokes::Cylinders(strokes), pins)
            }
            _ => (Strokes::Hub(Stroke { position: x[0], rate: v[0] }), SmallVec::new()),
        }
    }

    /// Adds the actuator's generalized forces at (x, v) to `f`: its load on the hub (a servo's
    /// torque) or on the arm through the cylinders' pins (each rod force's moment on θ and its
    /// work through q), and its own coordinates' forces and rates.
    pub(crate) fn add_actuator_forces(&self, x: &[f64], v: &[f64], f: &mut [f64]) {
        let Some(plant) = self.drive.plant() else { return };
        let own = self.own_start();
        let (strokes, pins) = self.actuator_strokes(plant, x, v);
        let m = plant.dofs();
        let mut rates: SmallVec<[f64; 8]> = SmallVec::from_elem(0.0, m);
        let loads = plant.forces_and_load(&strokes, &x[own..], &v[own..], &mut rates);
        f[own..own + m].iter_mut().zip(&rates).for_each(|(fi, r)| *fi += r);
        match &plant.arm_pins {
            Some(couplings) if !pins.is_empty() => {
                for ((pin, rows), load) in pins.iter().zip(&couplings.rows).zip(&loads) {
                    f[0] += load * pin.lever_m;
                    for (i, fi) in f[1..1 + self.arm.elastic_dofs()].iter_mut().enumerate() {
                        *fi += load * (pin.body_unit[0] * rows[0][i] + pin.body_unit[1] * rows[1][i]);
                    }
                }
            }
            _ => f[0] += loads[0],
        }
    }

    /// What the actuator reports at (x, v) and time `t_s`: its moment about the pivot with its
    /// own outputs.
    pub(crate) fn actuator_outputs(&self, t_s: f64, x: &[f64], v: &[f64]) -> Option<ActuatorOutputs> {
        let plant = self.drive.plant()?;
        let own = self.own_start();
        let (strokes, pins) = self.actuator_strokes(plant, x, v);
        let loads = plant.load(&strokes, &x[own..], &v[own..]);
        let hub_torque =
            if pins.is_empty() { loads[0] } else { pins.iter().zip(&loads).map(|(p, l)| l * p.lever_m).sum() };
        Some(plant.outputs(t_s, x[0], &strokes, hub_torque, &v[own..]))
    }

    /// Solves the free hub's M ẍ = rhs by eliminating q̈ with the constant M_qq⁻¹:
    /// θ̈ = (f_θ − S̃ᵀ M⁻¹ f_q) / (Ĵ − S̃ᵀ M⁻¹ S̃), q̈ = M⁻¹ (f_q − S̃ θ̈); the actuator's own
    /// coordinates have a diagonal mass of their own. O(n²) instead of a factorisation per stage.
    fn solve_free_hub_mass(&self, x: &DVector<f64>, rhs: &DVector<f64>, out: &mut DVector<f64>) {
        let a = self.arm;
        let n = a.elastic_dofs();
        let mut scratch = self.scratch.borrow_mut();
        scratch.split(x, x, n);
        let FreeHubScratch { q, coupling, y, w, .. } = &mut *scratch;
        coupling.copy_from(&a.coupling);
        add_product(coupling.as_mut_slice(), 1.0, &a.gyroscopic, q.as_slice());
        y.fill(0.0);
        add_product(y.as_mut_slice(), 1.0, &a.mass_inverse, &rhs.as_slice()[1..1 + n]);
        w.fill(0.0);
        add_product(w.as_mut_slice(), 1.0, &a.mass_inverse, coupling.as_slice());
        let theta_dd = (rhs[0] - coupling.dot(y)) / (self.pivot_inertia(q) - coupling.dot(w));
        out[0] = theta_dd;
        for i in 0..n {
            out[1 + i] = y[i] - theta_dd * w[i];
        }
        if let Some(plant) = self.drive.plant() {
            for i in 0..plant.dofs() {
                out[1 + n + i] = rhs[1 + n + i] / plant.mass(i);
            }
        }
    }

    /// Each pad contact's stiffness and damping over [θ, q]: k w wᵀ and c w wᵀ, w = (lever about
    /// the pivot, direction over q); without the θ terms every strike of a free hub would cost
    /// Newton its convergence.
    fn add_free_hub_contact_tangents(
        &self,
        hub: &DriveState,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        k: &mut DMatrix<f64>,
        c: &mut DMatrix<f64>,
    ) {
        let n = q.len();
        for contact in self.contacts {
            let state = contact.state(hub, q, qd);
            let (k_c, c_c) = contact.stiffness_damping(&state);
            if k_c == 0.0 && c_c == 0.0 {
                continue;
            }
            let mut w = DVector::zeros(n + 1);
            w[0] = contact.lever_m(&state);
            contact.add_direction(&state, 1.0, &mut w.as_mut_slice()[1..]);
            k.view_mut((0, 0), (n + 1, n + 1)).ger(k_c, &w, &w, 1.0);
            c.view_mut((0, 0), (n + 1, n + 1)).ger(c_c, &w, &w, 1.0);
        }
    }

    /// The actuator's tangents, by central differences of [`Self::add_actuator_forces`] over the
    /// coordinates it reads (θ, q for a cylinder's pin, its own) and their rates: a few
    /// evaluations of a few flops each, exact enough for Newton.
    fn add_actuator_tangents(&self, x: &DVector<f64>, v: &DVector<f64>, k: &mut DMatrix<f64>, c: &mut DMatrix<f64>) {
        let Some(plant) = self.drive.plant() else { return };
        let n = x.len();
        let own = self.own_start();
        // A cylinder's pins read θ and q; a servo's torque θ alone; both their own coordinates.
        let read = if plant.arm_pins.is_some() { 0..own } else { 0..1 };
        let columns: Vec<usize> = read.chain(own..n).collect();
        let (mut xp, mut vp) = (x.as_slice().to_vec(), v.as_slice().to_vec());
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        for is_rate in [false, true] {
            for &j in &columns {
                let value = if is_rate { vp[j] } else { xp[j] };
                let h = 1e-7 * value.abs().max(1e-3);
                for (sign, out) in [(1.0, &mut plus), (-1.0, &mut minus)] {
                    if is_rate {
                        vp[j] = value + sign * h
                    } else {
                        xp[j] = value + sign * h
                    }
                    out.fill(0.0);
                    self.add_actuator_forces(&xp, &vp, out);
                }
                if is_rate {
                    vp[j] = value
                } else {
                    xp[j] = value
                }
                let target = if is_rate { &mut *c } else { &mut *k };
                for i in 0..n {
                    target[(i, j)] -= (plus[i] - minus[i]) / (2.0 * h);
                }
            }
        }
    }
}

impl Dynamics for ArmSystem<'_> {
    fn dofs(&self) -> usize {
        (match self.drive {
            HubDrive::Prescribed(_) => self.arm.elastic_dofs(),
            HubDrive::Free { .. } => self.arm.elastic_dofs() + 1,
            HubDrive::Actuated(plant) => self.arm.elastic_dofs() + 1 + plant.dofs(),
        }) + self.arm.head_dofs()
    }

    fn mass_matrix(&self, t: f64, x: &DVector<f64>, m: &mut DMatrix<f64>) {
        let n = self.arm.elastic_dofs();
        if self.arm.head.is_some() {
            m.fill(0.0);
        }
        match self.drive {
            HubDrive::Prescribed(_) => m.view_mut((0, 0), (n, n)).copy_from(&self.arm.mass),
            HubDrive::Free { .. } | HubDrive::Actuated(_) => {
                let q = x.rows(1, n).into_owned();
                let s = self.coupling(&q);
                m[(0, 0)] = self.pivot_inertia(&q);
                m.view_mut((1, 0), (n, 1)).copy_from(&s);
                m.view_mut((0, 1), (1, n)).copy_from(&s.transpose());
                m.view_mut((1, 1), (n, n)).copy_from(&self.arm.mass);
                if let Some(plant) = self.drive.plant() {
                    let own = self.own_start();
                    for i in 0..plant.dofs() {
                        m[(own + i, own + i)] = plant.mass(i);
                    }
                }
            }
        }
        self.add_head_mass(t, x, m);
    }

    fn forces(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>, f: &mut DVector<f64>) {
        match self.drive {
            HubDrive::Prescribed(profile) => {
                // q = x, q̇ = v: no split, no copies.
                let (hub, trig) = self.hub.at(profile, t);
                if self.arm.head.is_some() {
                    return self.prescribed_forces_with_head(t, &hub, trig, x, v, f);
                }
                // −θ̈ S̃ = −θ̈ (S + C q): θ̈ S here, θ̈ C q with the elastic forces.
                f.copy_from(&self.arm.coupling);
                *f *= -hub.accel_rad_s2;
                let f = f.as_mut_slice();
                self.add_elastic_forces(&hub, trig, x, v, f);
                self.add_contact_forces(&hub, x, v, None, f);
            }
            HubDrive::Free { .. } | HubDrive::Actuated(_) => {
                let n = self.arm.elastic_dofs();
                let mut scratch = self.scratch.borrow_mut();
                scratch.split(x, v, n);
                let (q, qd) = (&scratch.q, &scratch.qd);
                let hub = DriveState { angle_rad: x[0], rate_rad_s: v[0], accel_rad_s2: 0.0, jerk_rad_s3: 0.0 };
                let trig = hub.angle_rad.sin_cos();
                let mut hub_force = self.hub_force_at(&hub, trig, q, qd, self.applied_torque_n_m(), false);
                let (elastic, own) = f.as_mut_slice()[1..].split_at_mut(n);
                elastic.fill(0.0);
                own.fill(0.0);
                self.add_elastic_forces(&hub, trig, q, qd, elastic);
                self.add_contact_forces(&hub, q, qd, Some(&mut hub_force), elastic);
                f[0] = hub_force;
                drop(scratch);
                self.add_actuator_forces(x.as_slice(), v.as_slice(), f.as_mut_slice());
                self.add_head_forces(t, x, v, f);
            }
        }
    }

    fn solve_mass(&self, _t: f64, x: &DVector<f64>, rhs: &DVector<f64>, out: &mut DVector<f64>) -> bool {
        if self.arm.head.is_some() {
            // The head's mass moves with ψ: the integrator factorises.
            return false;
        }
        match self.drive {
            HubDrive::Prescribed(_) => {
                out.gemv(1.0, &self.arm.mass_inverse, rhs, 0.0);
                true
            }
            HubDrive::Free { .. } | HubDrive::Actuated(_) => {
                self.solve_free_hub_mass(x, rhs, out);
                true
            }
        }
    }

    /// Exact for a prescribed hub; for a free hub the derivative of the mass matrix is left
    /// out (a quasi-Newton iteration that converges in a few steps).
    fn tangents(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>, k: &mut DMatrix<f64>, c: &mut DMatrix<f64>) {
        if self.arm.head.is_some() {
            return self.tangents_with_head(t, x, v, k, c);
        }
        self.arm_tangents(t, x, v, k, c);
    }

    fn first_order_dofs(&self) -> usize {
        self.drive.plant().map_or(0, |p| p.first_order_dofs())
    }

    fn is_linear(&self) -> bool {
        matches!(self.drive, HubDrive::Prescribed(_)) && self.contacts.is_empty() && self.arm.head.is_none()
    }
}

impl ArmSystem<'_> {
    /// The arm's tangents over its own coordinates (a head's are added by the caller).
    pub(super) fn arm_tangents(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        k: &mut DMatrix<f64>,
        c: &mut DMatrix<f64>,
    ) {
        let a = self.arm;
        if let HubDrive::Prescribed(profile) = self.drive {
            // In place: this runs at every Newton iteration.
            let (hub, (s, _)) = self.hub.at(profile, t);
            let (w, acc) = (hub.rate_rad_s, hub.accel_rad_s2);
            let (stiffness, spin) = (a.stiffness.as_slice(), a.spin_mass.as_slice());
            let (gravity, gyroscopic, damping) =
                (a.gravity_stiffness.as_slice(), a.gyroscopic.as_slice(), a.damping.as_slice());
            for (i, (kij, cij)) in k.as_mut_slice().iter_mut().zip(c.as_mut_slice()).enumerate() {
                *kij = stiffness[i] - w * w * spin[i] - s * gravity[i] + acc * gyroscopic[i];
                *cij = damping[i] + 2.0 * w * gyroscopic[i];
            }
            for contact in self.contacts {
                let state = contact.state(&hub, x, v);
                let (k_c, c_c) = contact.stiffness_damping(&state);
                let direction = contact.direction(&state);
                k.ger(k_c, &direction, &direction, 1.0);
                c.ger(c_c, &direction, &direction, 1.0);
            }
            return;
        }
        let (hub, q, qd) = self.split_free_hub(x, v);
        let (w, g) = (hub.rate_rad_s, a.options.gravity_m_s2);
        let (s, co) = hub.angle_rad.sin_cos();
        let k_qq = &a.stiffness - w * w * &a.spin_mass - s * &a.gravity_stiffness;
        let c_qq = &a.damping + 2.0 * w * &a.gyroscopic;
        let n = q.len();
        k.fill(0.0);
        c.fill(0.0);
        let spin_arm = &a.axial_moment + &a.spin_mass * &q;
        let kg_q = &a.gravity_stiffness * &q;
        k.view_mut((1, 1), (n, n)).copy_from(&k_qq);
        c.view_mut((1, 1), (n, n)).copy_from(&c_qq);
        let k_q_theta = co * (g * &a.axial_mass - &kg_q) - g * s * &a.transverse_mass;
        k.view_mut((1, 0), (n, 1)).copy_from(&k_q_theta);
        let c_q_theta = 2.0 * (&a.gyroscopic * &qd) - 2.0 * w * &spin_arm;
        c.view_mut((1, 0), (n, 1)).copy_from(&c_q_theta);
        k[(0, 0)] = -(g * s * (a.first_moment_kg_m + dot(&a.axial_mass, q.as_slice()))
            + g * co * dot(&a.transverse_mass, q.as_slice())
            - 0.5 * s * dot(&q, kg_q.as_slice()));
        let k_theta_q = 2.0 * w * (&a.spin_mass * &qd) + co * (g * &a.axial_mass - &kg_q) - g * s * &a.transverse_mass;
        k.view_mut((0, 1), (1, n)).copy_from(&k_theta_q.transpose());
        c[(0, 0)] = 2.0 * dot(&spin_arm, qd.as_slice());
        c.view_mut((0, 1), (1, n)).copy_from(&(2.0 * w * spin_arm).transpose());
        self.add_free_hub_contact_tangents(&hub, &q, &qd, k, c);
        self.add_actuator_tangents(x, v, k, c);
    }
}

/// The quadratic forms in (q, q̇) the hub's equation and the energies share.
struct Forms {
    /// qᵀ W q, kg·m².
    q_spin_q: f64,
    /// q̇ᵀ W q, kg·m²/s.
    qd_spin_q: f64,
    /// qᵀ K_g q, J.
    q_kg_q: f64,
}

impl ArmModel {
    /// Moment of gravity about the pivot on the arm deformed by `q`, with (sin θ, cos θ) of the
    /// hub angle and gravity `g`, N·m.
    pub(crate) fn gravity_moment_n_m(&self, trig: (f64, f64), q: &DVector<f64>, g: f64) -> f64 {
        self.gravity_moment_with(trig, q, g, bilinear(&self.gravity_stiffness, q, q))
    }

    /// [`Self::gravity_moment_n_m`] with qᵀK_g q given.
    fn gravity_moment_with(&self, (s, c): (f64, f64), q: &DVector<f64>, g: f64, q_kg_q: f64) -> f64 {
        let a = self;
        // K_g already carries g; this is −∂/∂θ of −½ g s qᵀK_g q, the foreshortening's potential.
        let foreshortening = 0.5 * c * q_kg_q;
        -g * c * (a.first_moment_kg_m + dot(&a.axial_mass, q.as_slice()))
            + g * s * dot(&a.transverse_mass, q.as_slice())
            + foreshortening
    }
}
