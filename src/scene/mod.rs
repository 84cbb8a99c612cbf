//! The rapier world around the arm and the coupling loop.
//!
//! The arm's dynamics live in [`ArmSimulation`] (floating frame, modal or FE). rapier holds its
//! geometry: each finite element is a kinematic box posed from the deformed centreline where it
//! is queried, stepped or drawn, and the bodies the arm carries (hand, gripper, jaws, a rigidly clamped string) are
//! kinematic shapes riding on their stations. The dampeners are rubber pads.
//!
//! One step, top to bottom:
//! 1. `rapier`: pose every kinematic shape from the arm's state;
//! 2. `compliant`: parry's contact query on the rapier colliders finds, per pad, the deepest
//!    point of the arm within reach (the shapes posed from the arm's state); it becomes a
//!    [`PointContact`] whose force law the arm step evaluates on the arm's configuration within
//!    the step (no staggering, no added-mass trap);
//!    `rapier`: the last rapier step's contact impulse / dt is applied to the arm as a load;
//! 3. advance the arm;
//! 4. `rapier`: move the kinematic shapes to the new pose and step rapier (the pad is a body on
//!    a spring);
//! 5. measure each pad's force;
//! 6. a friction clamp: move its palm with the gripper, step its world, measure the slip and the
//!    correction it hands the arm next step ([`FrictionGrip`]).

mod clamp;
mod geometry;

use rapier3d_f64::prelude::*;

use crate::arm::{ArmContact, ArmError, ArmSimulation, GeneralizedLoad, PointContact};
use crate::drive::DriveState;
use crate::integrate::StepControl;
use crate::scenario::{ContactMethod, DampenerSpec, Face, PayloadSpec, Scenario, ScenarioError};
pub use clamp::FrictionGrip;
use geometry::{ArmPiece, pose_piece, shapes_of_robot};

/// The arm's shapes touch the pads and nothing else (not each other, not the ground).
const ARM_GROUPS: InteractionGroups = InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And);
/// The pads touch the arm's shapes.
const PAD_GROUPS: InteractionGroups = InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);
/// Kinematic arm shapes against fixed pads (`compliant`) or dynamic pads (`rapier`).
const PAD_CONTACT_TYPES: ActiveCollisionTypes =
    ActiveCollisionTypes::DYNAMIC_KINEMATIC.union(ActiveCollisionTypes::KINEMATIC_FIXED);

/// A rubber pad and what the scene knows of it.
#[derive(Debug, Clone)]
pub struct Pad {
    /// Its description.
    pub spec: DampenerSpec,
    /// Unit normal of its face in the world (X, Y), pointing at the arm.
    pub normal_world: [f64; 2],
    /// World position of its face centre, m.
    pub face_centre_m: [f64; 3],
    body: RigidBodyHandle,
    collider: ColliderHandle,
    /// Closing speed at first touch of the current impact, m/s.
    impact_speed_m_s: f64,
    /// Force at the end of the last step, N.
    pub force_n: f64,
    /// How far the pad is compressed at the end of the last step, m (the arm's penetration for
    /// `compliant`, the pad body's travel for `rapier`); beyond the pad's thickness the run is
    /// meaningless.
    pub compression_m: f64,
    /// Point of application of that force (world X, Y), m.
    pub point_m: [f64; 2],
    /// Name of the arm part touching it.
    pub touching: Option<String>,
    /// The pad's mounting spring (`rapier` method).
    spring: Option<PadSpring>,
    /// What tells, without rapier, that the arm is far from it.
    watch: PadWatch,
}

/// The arm's face point at a pad's station, to measure the clearance cheaply.
#[derive(Debug, Clone)]
struct PadWatch {
    rows: crate::arm::StationRows,
    /// Body-frame y of the face that meets the pad, m.
    face_lateral_m: f64,
    /// Extra clearance for shapes standing out beyond the face, plus 0.1 mm, m.
    margin_m: f64,
}

/// A pad body's linear spring–damper to its rest position (`rapier` method).
#[derive(Debug, Clone, Copy)]
struct PadSpring {
    rest_m: [f64; 3],
    stiffness_n_m: f64,
    damping_n_s_m: f64,
}

fn pad_error(scenario: &Scenario, spec: &DampenerSpec, message: &str) -> ScenarioError {
    ScenarioError::Invalid {
        path: scenario.path.clone(),
        key: format!("dampeners.{}", spec.name),
        message: message.into(),
    }
}

/// The rapier world, the arm and the pads.
pub struct Scene {
    /// The arm.
    pub arm: ArmSimulation,
    /// The pads.
    pub pads: Vec<Pad>,
    /// How contact forces are computed.
    pub method: ContactMethod,
    world: PhysicsWorld,
    pieces: Vec<ArmPiece>,
    pivot_m: [f64; 3],
    /// Pad forces measured by rapier over the last step: (pad, station, force world X/Y).
    rapier_load: Vec<(usize, f64, [f64; 2])>,
    /// The friction clamp, if the string is held by one.
    pub grip: Option<FrictionGrip>,
    /// Index of the piece carrying the clamp.
    grip_palm: Option<usize>,
    /// Stations at which a frame samples the centreline, with their rows.
    centreline: Vec<(f64, crate::arm::StationRows)>,
}

/// Stations along the arm at which a frame samples the centreline.
const CENTRELINE_STATIONS: usize = 20;

/// Errors building or stepping a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// In the scenario.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// In the arm.
    #[error(transparent)]
    Arm(#[from] ArmError),
    /// The run's energy grew without a source, or its values stopped being finite.
    #[error("the run diverged at t = {t_s:.4} s: {what}. Advice: {advice}")]
    Diverged { t_s: f64, what: String, advice: String },
}

impl Scene {
    /// Builds the world of a scenario at its own fidelity.
    pub fn new(scenario: &Scenario) -> Result<Self, SceneError> {
        Self::with_fidelity(scenario, scenario.fidelity()?.fidelity)
    }

    /// Builds the world of a scenario at `fidelity`.
    pub fn with_fidelity(scenario: &Scenario, fidelity: crate::arm::Fidelity) -> Result<Self, SceneError> {
        Self::with_arm(scenario, scenario.arm_model(fidelity)?)
    }

    /// Builds the world of a scenario around an arm model already reduced for it.
    pub fn with_arm(scenario: &Scenario, arm_model: crate::arm::ArmModel) -> Result<Self, SceneError> {
        let arm = ArmSimulation::new(arm_model, scenario.hub_drive(), scenario.spec.integrator)?;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, -scenario.spec.physics.gravity_m_s2, 0.0);
        world.integration_parameters.dt = scenario.spec.time.step_s;
        let pivot_m = scenario.robot.lift.pivot_m;
        let friction = scenario.friction_clamp();
        let jaw_names: Vec<&str> =
            scenario.robot.carried.iter().filter(|b| b.mount.is_prismatic()).map(|b| b.name.as_str()).collect();
        // With a friction clamp, string and jaws are rapier bodies of their own.
        let (held, riding): (Vec<_>, Vec<_>) = shapes_of_robot(scenario)?
            .into_iter()
            .partition(|(p, _)| friction.is_some() && (p.name == "string" || jaw_names.contains(&p.name.as_str())));
        let pieces: Vec<ArmPiece> = riding
            .into_iter()
            .map(|(piece, shape)| {
                let body = world.insert_body(RigidBodyBuilder::kinematic_position_based());
                let collider = ColliderBuilder::new(shape)
                    .active_collision_types(PAD_CONTACT_TYPES)
                    .collision_groups(ARM_GROUPS)
                    .friction(0.0);
                let collider = world.insert_collider(collider, Some(body));
                let rows = arm.arm.station_rows(piece.station_m);
                ArmPiece { body, collider, rows, ..piece }
            })
            .collect();
        world.insert_body(RigidBodyBuilder::fixed());
        let ground = ColliderBuilder::cuboid(50.0, 0.5, 50.0)
            .translation(Vector::new(0.0, -0.5, 0.0))
            .collision_groups(InteractionGroups::new(Group::GROUP_3, Group::NONE, InteractionTestMode::And));
        world.insert_collider(ground, None);
        let method = scenario.spec.contact.method;
        let mut scene = Scene {
            arm,
            pads: Vec::new(),
            method,
            world,
            pieces,
            pivot_m,
            rapier_load: Vec::new(),
            grip: None,
            grip_palm: None,
            centreline: Vec::new(),
        };
        let length = scene.arm.arm.length_m();
        scene.centreline = (0..=CENTRELINE_STATIONS)
            .map(|i| length * i as f64 / CENTRELINE_STATIONS as f64)
            .map(|x| (x, scene.arm.arm.station_rows(x)))
            .collect();
        for spec in &scenario.spec.dampeners {
            let pad = scene.insert_pad(spec, scenario)?;
            scene.pads.push(pad);
        }
        scene.pose_pieces(false);
        if let (Some(clamp), Some((string, shape))) = (friction, held.into_iter().find(|(p, _)| p.name == "string")) {
            let PayloadSpec::String { at, .. } = &scenario.spec.payload else {
                unreachable!("a friction clamp holds a string")
            };
            let palm = scene.pieces.iter().find(|p| &p.name == at).ok_or_else(|| ScenarioError::Invalid {
                path: scenario.path.clone(),
                key: "payload.at".into(),
                message: format!("`{at}` has no collision shape to carry the jaws"),
            })?;
            let palm_pose = *scene.world.bodies[palm.body].position();
            scene.grip = Some(FrictionGrip::new(scenario, clamp, palm, palm_pose, &string, shape)?);
            scene.grip_palm = scene.pieces.iter().position(|p| &p.name == at);
        }
        scene.mark_pieces_near_pads();
        Ok(scene)
    }

    /// Marks the shapes whose extent along the arm comes within 0.5 m of a pad.
    fn mark_pieces_near_pads(&mut self) {
        for piece in &mut self.pieces {
            let reach = piece.half_extents_m.iter().fold(0.0_f64, |a, b| a.max(*b)) + 0.5;
            piece.near_pad =
                self.pads.iter().any(|p| (p.spec.station_m - piece.station_m).abs() <= 0.5 * p.spec.length_m + reach);
        }
    }

    /// Places a pad against the undeformed arm at its stop, `gap_m` from the named face.
    fn insert_pad(&mut self, spec: &DampenerSpec, scenario: &Scenario) -> Result<Pad, ScenarioError> {
        let theta = spec.angle_deg.to_radians();
        let (s, c) = theta.sin_cos();
        let half_depth = 0.5 * self.arm_depth_at(spec.station_m);
        let sign = match spec.face {
            Face::Upper => 1.0,
            Face::Lower => -1.0,
        };
        // Body-frame y of the pad's face and centre; the normal points back at the arm.
        let face_y = sign * (half_depth + spec.gap_m);
        let centre_y = face_y + sign * 0.5 * spec.thickness_m;
        let to_world =
            |x: f64, y: f64| [self.pivot_m[0] + c * x - s * y, self.pivot_m[1] + s * x + c * y, self.pivot_m[2]];
        let normal_world = [sign * s, -sign * c];
        let centre = to_world(spec.station_m, centre_y);
        let pose = Pose::from_parts(Vector::new(centre[0], centre[1], centre[2]), Rotation::from_rotation_z(theta));
        let spring = match (self.method, spec.law) {
            (ContactMethod::Compliant, _) => None,
            (ContactMethod::Rapier, crate::contact::ForceLaw::Linear { stiffness_n_m, damping_n_s_m }) => {
                Some(PadSpring { rest_m: centre, stiffness_n_m, damping_n_s_m })
            }
            (ContactMethod::Rapier, _) => {
                return Err(pad_error(
                    scenario,
                    spec,
                    "contact.method = \"rapier\" models the pad as a linear spring: allowed law kind = \"linear\"",
                ));
            }
        };
        let builder = match spring {
            None => RigidBodyBuilder::fixed(),
            Some(_) => {
                // The pad slides along its normal only; that must be a world axis, as rapier
                // locks translations in world axes.
                let along_x = normal_world[0].abs() > 1.0 - 1e-9;
                if !along_x && normal_world[1].abs() < 1.0 - 1e-9 {
                    return Err(pad_error(
                        scenario,
                        spec,
                        "contact.method = \"rapier\" needs a pad facing a world axis: allowed angle_deg 0, ±90, 180",
                    ));
                }
                RigidBodyBuilder::dynamic()
                    .gravity_scale(0.0)
                    .can_sleep(false)
                    .lock_rotations()
                    .enabled_translations(along_x, !along_x, false)
            }
        };
        let body = self.world.insert_body(builder.pose(pose));
        let shape = ColliderBuilder::cuboid(0.5 * spec.length_m, 0.5 * spec.thickness_m, 0.5 * spec.width_m)
            .active_collision_types(PAD_CONTACT_TYPES)
            .collision_groups(PAD_GROUPS)
            .friction(0.0)
            .mass(scenario.spec.contact.pad_mass_kg);
        let collider = self.world.insert_collider(shape, Some(body));
        // How far any shape riding on the arm across the pad's length stands out beyond the arm's
        // face on the pad's side (its box turned into the section's axes).
        let protrusion = self
            .pieces
            .iter()
            .filter(|p| !p.is_arm_element)
            .filter_map(|p| {
                let [ext_x, ext_y] = p.section_extents_m();
                let overlaps = (p.station_m - spec.station_m).abs() <= 0.5 * spec.length_m + ext_x;
                overlaps.then_some(sign * p.lateral_m + ext_y - half_depth)
            })
            .fold(0.0, f64::max);
        let watch = PadWatch {
            rows: self.arm.arm.station_rows(spec.station_m),
            face_lateral_m: sign * half_depth,
            margin_m: protrusion + 1e-4,
        };
        Ok(Pad {
            spec: spec.clone(),
            normal_world,
            face_centre_m: to_world(spec.station_m, face_y),
            body,
            collider,
            impact_speed_m_s: 0.0,
            force_n: 0.0,
            compression_m: 0.0,
            point_m: [0.0; 2],
            touching: None,
            spring,
            watch,
        })
    }

    /// Depth of the arm section at a station, m.
    fn arm_depth_at(&self, station_m: f64) -> f64 {
        self.pieces
            .iter()
            .filter(|p| p.is_arm_element)
            .min_by(|a, b| (a.station_m - station_m).abs().total_cmp(&(b.station_m - station_m).abs()))
            .map_or(0.0, |p| p.depth_m)
    }

    /// The hub state at the arm's current time.
    pub fn hub(&self) -> DriveState {
        self.arm.kinematics().0
    }

    /// Pose of each rapier shape from the arm's state: each at its station, turned with the
    /// section there.
    fn pose_pieces(&mut self, next_kinematic: bool) {
        let (hub, q, _) = self.arm.kinematics();
        // Only shapes that can reach a pad: moving the others would only cost rapier's broad
        // phase (the drawing poses every shape afresh, see `frame`).
        for piece in self.pieces.iter().filter(|p| p.near_pad) {
            let pose = pose_piece(piece, &hub, &q, self.pivot_m);
            if let Some(body) = self.world.bodies.get_mut(piece.body) {
                if next_kinematic {
                    body.set_next_kinematic_position(pose);
                } else {
                    body.set_position(pose, true);
                }
            }
        }
    }

    /// Per pad, the arm's effective mass at the pad's station along the arm's normal with the hub
    /// held, 1 / (rᵀ M⁻¹ r), kg. `None` for a rigid arm on a prescribed hub (infinite).
    pub fn pad_effective_masses_kg(&self) -> Vec<Option<f64>> {
        let inverse = self.arm.arm.mass.clone().try_inverse().filter(|m| m.nrows() > 0);
        self.pads
            .iter()
            .map(|pad| {
                let row = &pad.watch.rows.0[1];
                let m_eff = 1.0 / row.dot(&(inverse.as_ref()? * row));
                m_eff.is_finite().then_some(m_eff)
            })
            .collect()
    }

    /// Per pad, the explicit stability limit of its penalty contact, 2√(m_eff/k), s, with k the
    /// law's tangent stiffness at `force_n` ([`Self::pad_effective_masses_kg`] for m_eff).
    pub fn penalty_limits_s(&self, force_n: f64) -> Vec<Option<f64>> {
        self.pads
            .iter()
            .zip(self.pad_effective_masses_kg())
            .map(|(pad, m_eff)| {
                let k = pad.spec.law.tangent_stiffness_at_force(force_n);
                m_eff.filter(|_| k > 0.0).map(|m| 2.0 * (m / k).sqrt())
            })
            .collect()
    }

    /// Advances the scene by `h_s` seconds (the order of the module doc).
    pub fn step(&mut self, h_s: f64) -> Result<(), SceneError> {
        if self.method == ContactMethod::Rapier {
            self.pose_pieces(false);
        }
        self.set_loads_from_rapier();
        self.arm.contacts = match self.method {
            ContactMethod::Compliant => self.compliant_contacts(h_s),
            ContactMethod::Rapier => Vec::new(),
        };
        self.arm.step(h_s)?;
        if self.method == ContactMethod::Compliant {
            self.measure_compliant_forces();
        }
        if self.method == ContactMethod::Rapier {
            self.pose_pieces(true);
            self.apply_pad_springs();
            self.world.integration_parameters.dt = h_s;
            self.world.step();
            self.measure_rapier_forces(h_s);
        }
        if let (Some(grip), Some(palm)) = (self.grip.as_mut(), self.grip_palm) {
            let (hub, q, _) = self.arm.kinematics();
            let pose = pose_piece(&self.pieces[palm], &hub, &q, self.pivot_m);
            grip.step(pose, h_s);
        }
        Ok(())
    }

    /// Sets the arm's load to what rapier's last step measured, as generalized forces on the arm
    /// now: the pads' (`rapier` method) and the friction clamp's correction (in place: no
    /// allocation on the steps without either).
    fn set_loads_from_rapier(&mut self) {
        let mut load = std::mem::replace(&mut self.arm.load, GeneralizedLoad::zero(0));
        load.clear();
        if !self.rapier_load.is_empty() || self.grip.is_some() {
            let (hub, q, _) = self.arm.kinematics();
            let arm = &self.arm.arm;
            let grip = self.grip.as_ref().map(|g| (g.station_m, g.correction_force_n));
            for (station, force) in self.rapier_load.iter().map(|&(_, s, f)| (s, f)).chain(grip) {
                load.add(&arm.point_force(station, force, hub.angle_rad, &q));
            }
        }
        self.arm.load = load;
    }

    /// Whether the arm could reach a pad within a step of `h_s`: each pad's clearance, less what
    /// stands out beyond the arm's face, against three times the travel of the arm's fastest point.
    pub fn pad_within_reach(&self, h_s: f64) -> bool {
        let travel = 3.0 * self.speed_bound_m_s() * h_s;
        self.pads.iter().any(|p| self.clearance_m(p) <= travel + p.watch.margin_m)
    }

    /// Whether the next step may be `free_step_s` long: no pad within its reach, and nothing
    /// staggered (the `rapier` pad body, a friction clamp) that needs the contact step.
    pub fn free_step_allowed(&self, free_step_s: f64) -> bool {
        self.method == ContactMethod::Compliant && self.grip.is_none() && !self.pad_within_reach(free_step_s)
    }

    /// A step of free motion of at most `h_s` under error `control` (call where
    /// [`Self::free_step_allowed`] holds: no pad in reach, nothing else to step). Returns the step
    /// taken and the next to try, s.
    pub fn step_free(&mut self, h_s: f64, control: &StepControl) -> Result<(f64, f64), SceneError> {
        self.set_loads_from_rapier();
        self.arm.contacts.clear();
        let steps = self.arm.step_controlled(h_s, control)?;
        self.measure_compliant_forces();
        Ok(steps)
    }

    /// Per pad, the deepest point of the arm within reach, as contacts for the implicit step.
    fn compliant_contacts(&mut self, h_s: f64) -> Vec<ArmContact> {
        // Contact queries are most of a step's cost: skip them while every pad is out of reach.
        if !self.pad_within_reach(h_s) {
            return Vec::new();
        }
        let reach = self.contact_reach(h_s);
        (0..self.pads.len()).filter_map(|i| self.deepest_point(i, reach)).collect()
    }

    /// Distance from a pad's face to the arm's face, m: the nearer of the face's two ends from
    /// the line of the arm's face at the pad's station (its tangent there, with the elastic
    /// slope), measured along the face's outward normal. Exact for the straight face across the
    /// pad's length, whatever the arm's angle to the pad; negative in contact.
    fn clearance_m(&self, pad: &Pad) -> f64 {
        let (hub, q, _) = self.arm.kinematics();
        let [u, v, phi] = pad.watch.rows.displacement(&q);
        let lateral = pad.watch.face_lateral_m;
        let (x, y) = (pad.spec.station_m + u - lateral * phi, lateral + v);
        let (s, c) = hub.angle_rad.sin_cos();
        let point = [self.pivot_m[0] + c * x - s * y, self.pivot_m[1] + s * x + c * y];
        // The face's outward normal: the body's ±y turned by the hub angle and the slope.
        let (sf, cf) = (hub.angle_rad + phi).sin_cos();
        let outward = [-sf * lateral.signum(), cf * lateral.signum()];
        let n = pad.normal_world;
        let half = 0.5 * pad.spec.length_m;
        [-1.0, 1.0]
            .map(|side| {
                let end = [pad.face_centre_m[0] - side * half * n[1], pad.face_centre_m[1] + side * half * n[0]];
                outward[0] * (end[0] - point[0]) + outward[1] * (end[1] - point[1])
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min)
    }

    /// Each pad's force at the end of the step, from its contact on the arm's new state.
    fn measure_compliant_forces(&mut self) {
        let (hub, q, qd) = self.arm.kinematics();
        for pad in &mut self.pads {
            pad.force_n = 0.0;
            pad.compression_m = 0.0;
        }
        for c in &self.arm.contacts {
            let state = c.state(&hub, &q, &qd);
            let pad = &mut self.pads[c.contact.pair];
            pad.force_n = state.force_n;
            pad.compression_m = state.depth_m.max(0.0);
            pad.point_m = state.point_m;
            if state.force_n <= 0.0 {
                pad.touching = None;
            }
        }
    }

    /// How far ahead a contact must be seen: the arm's fastest closing during a step, with margin.
    fn contact_reach(&self, h_s: f64) -> f64 {
        (3.0 * self.speed_bound_m_s() * h_s).max(2e-3)
    }

    /// A bound on any arm point's speed: the hub's rotation at the tip (plus a metre) plus the
    /// tip's elastic speed, m/s.
    fn speed_bound_m_s(&self) -> f64 {
        let (hub, _, qd) = self.arm.kinematics();
        let [ru, rv, _] = self.arm.arm.tip_rows();
        hub.rate_rad_s.abs() * (self.arm.arm.length_m() + 1.0) + ru.dot(&qd).hypot(rv.dot(&qd))
    }

    /// The deepest point of the arm against pad `i`, within `reach` of touching: parry's contact
    /// query between the pad's collider and each shape that can reach it, posed from the arm's
    /// state. (rapier's `detect_collisions` gave the same points through its broad phase and
    /// manifolds at 34 000 instructions a detection with the posing; this takes 15 000.)
    fn deepest_point(&mut self, i: usize, reach: f64) -> Option<ArmContact> {
        let pad = &self.pads[i];
        let pad_collider = &self.world.colliders[pad.collider];
        // Shapes whose bounding box is beyond reach of the pad's are not queried.
        let pad_box = pad_collider.compute_aabb().loosened(reach);
        let (hub, q, _) = self.arm.kinematics();
        let mut best: Option<(f64, Vector, &ArmPiece, Pose)> = None;
        for piece in self.pieces.iter().filter(|p| p.near_pad) {
            let pose = pose_piece(piece, &hub, &q, self.pivot_m);
            let shape = self.world.colliders[piece.collider].shape();
            if !shape.compute_aabb(&pose).intersects(&pad_box) {
                continue;
            }
            let found = parry3d_f64::query::contact(&pose, shape, pad_collider.position(), pad_collider.shape(), reach);
            if let Ok(Some(contact)) = found
                && contact.dist <= reach
                && best.as_ref().is_none_or(|b| contact.dist < b.0)
            {
                best = Some((contact.dist, contact.point1, piece, pose));
            }
        }
        let (dist, world, piece, pose) = best?;
        let world = [world.x, world.y, world.z];
        let (station_m, lateral_m) = piece.station_of(&pose, world);
        let name = piece.name.clone();
        let point = PointContact {
            pair: i,
            station_m,
            lateral_m,
            normal_world: pad.normal_world,
            depth_m: -dist,
            reference_point_m: [world[0] - self.pivot_m[0], world[1] - self.pivot_m[1]],
            law: pad.spec.law,
            impact_speed_m_s: pad.impact_speed_m_s,
        };
        // Projected once: the same rows give the closing speed now and the force in the step.
        let mut contact = self.arm.arm.arm_contact(point);
        let (hub, q, qd) = self.arm.kinematics();
        let closing = contact.state(&hub, &q, &qd).rate_m_s;
        let pad = &mut self.pads[i];
        if pad.force_n <= 0.0 {
            pad.impact_speed_m_s = closing.max(1e-6);
        }
        pad.touching = Some(name);
        contact.contact.impact_speed_m_s = pad.impact_speed_m_s;
        Some(contact)
    }

    /// Spring–damper force of each pad's mount, held over the rapier step.
    fn apply_pad_springs(&mut self) {
        for pad in &self.pads {
            let (Some(spring), Some(body)) = (pad.spring, self.world.bodies.get_mut(pad.body)) else { continue };
            let x = body.translation();
            let v = body.linvel();
            let rest = Vector::new(spring.rest_m[0], spring.rest_m[1], spring.rest_m[2]);
            let force = -(x - rest) * spring.stiffness_n_m - v * spring.damping_n_s_m;
            body.reset_forces(false);
            body.add_force(force, true);
        }
    }

    /// Each pad's force from rapier's contact impulses over the last step.
    fn measure_rapier_forces(&mut self, h_s: f64) {
        self.rapier_load.clear();
        for (i, pad) in self.pads.iter_mut().enumerate() {
            pad.force_n = 0.0;
            pad.touching = None;
            if let (Some(spring), Some(body)) = (pad.spring, self.world.bodies.get(pad.body)) {
                let travel = [0, 1].map(|k| spring.rest_m[k] - body.translation()[k]);
                pad.compression_m = (travel[0] * pad.normal_world[0] + travel[1] * pad.normal_world[1]).max(0.0);
            }
            for piece in &self.pieces {
                let Some(pair) = self.world.narrow_phase.contact_pair(piece.collider, pad.collider) else { continue };
                let impulse = pair.total_impulse();
                let magnitude = impulse.length();
                if magnitude <= 0.0 {
                    continue;
                }
                let force = magnitude / h_s;
                let arm_collider = &self.world.colliders[piece.collider];
                let point = pair
                    .find_deepest_contact()
                    .map(|(_, c)| {
                        let local = if pair.collider1 == piece.collider { c.local_p1 } else { c.local_p2 };
                        arm_collider.position() * local
                    })
                    .unwrap_or(arm_collider.translation());
                // The force acts on the arm's section at the point's station.
                let (station, _) = piece.station_of(arm_collider.position(), [point.x, point.y, point.z]);
                pad.force_n += force;
                pad.point_m = [point.x - self.pivot_m[0], point.y - self.pivot_m[1]];
                pad.touching = Some(piece.name.clone());
                let f = [force * pad.normal_world[0], force * pad.normal_world[1]];
                self.rapier_load.push((i, station, f));
            }
        }
    }

    /// What is drawn and never changes shape: each piece's and pad's name and half extents (m).
    pub fn layout(&self) -> SceneLayout {
        let pads = self
            .pads
            .iter()
            .map(|p| (p.spec.name.clone(), [0.5 * p.spec.length_m, 0.5 * p.spec.thickness_m, 0.5 * p.spec.width_m]));
        SceneLayout {
            pieces: self.pieces.iter().map(|p| (p.name.clone(), p.half_extents_m)).collect(),
            pads: pads.collect(),
            pivot_m: self.pivot_m,
            length_m: self.arm.arm.length_m(),
        }
    }

    /// The scene's state for drawing, from the arm's current state (poses in `layout` order).
    pub fn frame(&self) -> Frame {
        // The kinematics only: the torque and energies `sample` would compute are not drawn.
        let (hub, q, _) = self.arm.kinematics();
        let pieces = self.pieces.iter().map(|p| pose_piece(p, &hub, &q, self.pivot_m)).collect();
        let pads = self.pads.iter().map(|p| *self.world.bodies[p.body].position()).collect();
        let contacts = self
            .pads
            .iter()
            .filter(|p| p.force_n > 0.0)
            .map(|p| {
                let point = [p.point_m[0] + self.pivot_m[0], p.point_m[1] + self.pivot_m[1], self.pivot_m[2]];
                (p.spec.name.clone(), point, [p.force_n * p.normal_world[0], p.force_n * p.normal_world[1]])
            })
            .collect();
        let centreline = self
            .centreline
            .iter()
            .map(|(x, rows)| {
                let [u, v, _] = rows.displacement(&q);
                (*x, [u, v])
            })
            .collect();
        Frame { t_s: self.arm.time_s(), hub_angle_rad: hub.angle_rad, pieces, pads, contacts, centreline }
    }
}

/// The unchanging part of what is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneLayout {
    /// Piece names and half extents, m.
    pub pieces: Vec<(String, [f64; 3])>,
    /// Pad names and half extents, m.
    pub pads: Vec<(String, [f64; 3])>,
    /// Pivot in the world, m.
    pub pivot_m: [f64; 3],
    /// Arm length, m.
    pub length_m: f64,
}

/// The scene at one instant, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Time, s.
    pub t_s: f64,
    /// Hub angle, rad.
    pub hub_angle_rad: f64,
    /// World pose of each piece (layout order).
    pub pieces: Vec<Pose>,
    /// World pose of each pad.
    pub pads: Vec<Pose>,
    /// Pads in contact: name, world point (m), force on the arm (world X, Y, N).
    pub contacts: Vec<(String, [f64; 3], [f64; 2])>,
    /// Centreline: station (m) and displacement in the hub frame (axial, transverse, m).
    pub centreline: Vec<(f64, [f64; 2])>,
}
