//! `contact.kind = "rapier"`: each pad is a rapier body of its own mass on its spring, struck
//! by the arm's shapes (kinematic bodies posed from the arm's state) in rapier's world.
//!
//! Coupled so that it is stable at the scene's own step:
//! - the pad's spring is a force-based prismatic joint motor to its mount, inside rapier's
//!   constraint solver (implicit: stable at any step, where a spring force applied to the body
//!   diverges above 2√(m/k));
//! - the arm step evaluates the spring's law itself, at the arm's penetration of the pad's rest
//!   face (the pad-face points of `compliant`, implicit in the arm step);
//! - what rapier's contact force adds to that law — the pad body's inertia, its lifting off a
//!   retreating arm — is handed to the arm over the next step. Only that correction is staggered:
//!   it scales with the pad's mass, so the method tends to `compliant` as the mass goes to zero,
//!   and it is stable while the pad is light against the arm's effective mass at the pad (the
//!   added-mass ratio; docs/accuracy.md maps where it fails).

use rapier3d_f64::prelude::*;

use super::geometry::ArmView;
use super::pad_faces::PadFaces;
use super::pair::{ContactPair, PointReading};
use super::source::ContactSource;
use crate::arm::{ArmContact, GeneralizedLoad};
use crate::contact::ForceLaw;
use crate::model::Dampener;

/// The arm's shapes touch the pads and nothing else (not each other).
const ARM_GROUPS: InteractionGroups = InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And);
/// The pads touch the arm's shapes.
const PAD_GROUPS: InteractionGroups = InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);
/// Kinematic arm shapes against dynamic pads.
const PAD_CONTACT_TYPES: ActiveCollisionTypes = ActiveCollisionTypes::DYNAMIC_KINEMATIC;

/// The spring of a pad the `rapier` method can model, (stiffness N/m, damping N·s/m): its law
/// must be linear. The error names the dampener's key and what is allowed.
pub fn rapier_pad_spring(dampener: &Dampener) -> Result<(f64, f64), (&'static str, String)> {
    let ForceLaw::Linear { stiffness_n_m, damping_n_s_m } = dampener.law else {
        return Err((
            "law",
            "contact.kind = \"rapier\" models the pad as a linear spring: allowed law kind = \"linear\"".into(),
        ));
    };
    Ok((stiffness_n_m, damping_n_s_m))
}

/// Pads as rapier bodies on sprung mounts, struck by the arm's shapes in rapier's world.
pub struct RapierPads {
    world: PhysicsWorld,
    /// The pads as the arm step sees them: their spring laws at the arm's penetration.
    springs: PadFaces,
    /// The pads as rapier resolves them: the contact force on each pad body.
    pads: Vec<ContactPair>,
    /// Per pad, its body on its mount.
    bodies: Vec<PadBody>,
    /// Per arm piece (the scene's order): its kinematic body and collider.
    pieces: Vec<(RigidBodyHandle, ColliderHandle)>,
    pad_mass_kg: f64,
    /// Per pad, rapier's contact force less the spring law's at the end of the last step, handed
    /// to the arm over the next: (station, force world X/Y).
    handed_over: Vec<(f64, [f64; 2])>,
    last_step_s: f64,
}

/// A pad's rapier body and its spring.
struct PadBody {
    body: RigidBodyHandle,
    collider: ColliderHandle,
    stiffness_n_m: f64,
    damping_n_s_m: f64,
    /// Its travel's rate at the end of the last step, m/s.
    rate_m_s: f64,
}

/// Why a pad cannot be a rapier body.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{name}: key `{key}`: {message}")]
pub struct UnsupportedPad {
    /// The pad.
    pub name: String,
    /// The key of the dampener at fault.
    pub key: &'static str,
    /// What is allowed.
    pub message: String,
}

/// Natural frequency of rapier's soft contact constraint, Hz: a pad body lags the arm's face by
/// F / (m ω²), 2 × 10⁻⁵ µm for a 1 kg pad at 800 N here, where rapier's default 30 Hz would let
/// it lag by 20 mm, and 1 kHz by 20 µm, a fifth of the default pad's compression. Above
/// ω h ≫ 1 the constraint is simply hard: the frequency costs nothing.
const CONTACT_HZ: f64 = 1.0e6;

/// rapier's contact resolution: stiff enough that the pad body follows the arm's face to well
/// within a pad's compression (tens of micrometres), where rapier's defaults (30 Hz softness,
/// millimetres of allowed error) are tuned for games.
fn contact_parameters(world: &mut PhysicsWorld, step_s: f64) {
    let p = &mut world.integration_parameters;
    p.dt = step_s;
    p.length_unit = 1.0;
    p.normalized_allowed_linear_error = 1e-7;
    p.normalized_prediction_distance = 2e-3;
    let softness = SpringCoefficients::new(CONTACT_HZ, 10.0);
    p.contact_softness = softness;
    p.static_contact_softness = softness;
}

impl RapierPads {
    /// rapier's world of the arm's shapes (posed from `arm`) and the pads on their mounts.
    pub fn new(
        arm: &ArmView,
        pads: Vec<ContactPair>,
        gravity_m_s2: f64,
        step_s: f64,
        pad_mass_kg: f64,
    ) -> Result<Self, UnsupportedPad> {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, -gravity_m_s2, 0.0);
        contact_parameters(&mut world, step_s);
        let pieces = arm
            .pieces
            .iter()
            .map(|piece| {
                let body = world.insert_body(RigidBodyBuilder::kinematic_position_based().pose(arm.pose(piece)));
                let collider = ColliderBuilder::new(piece.shape.clone())
                    .active_collision_types(PAD_CONTACT_TYPES)
                    .collision_groups(ARM_GROUPS)
                    .friction(0.0);
                (body, world.insert_collider(collider, Some(body)))
            })
            .collect();
        let mut bodies = Vec::with_capacity(pads.len());
        for pad in &pads {
            let dampener = pad.dampener().ok_or_else(|| UnsupportedPad {
                name: pad.obstacle.name().into(),
                key: "contact.kind",
                message: "the rapier method models pads only: allowed method \"compliant\" with structures".into(),
            })?;
            let (stiffness_n_m, damping_n_s_m) = rapier_pad_spring(dampener)
                .map_err(|(key, message)| UnsupportedPad { name: dampener.name.clone(), key, message })?;
            let mount = world.insert_body(RigidBodyBuilder::fixed().pose(pad.pose));
            let body = world.insert_body(
                RigidBodyBuilder::dynamic().gravity_scale(0.0).can_sleep(false).lock_rotations().pose(pad.pose),
            );
            let collider = ColliderBuilder::new(pad.shape.clone())
                .active_collision_types(PAD_CONTACT_TYPES)
                .collision_groups(PAD_GROUPS)
                .friction(0.0)
                .mass(pad_mass_kg);
            let collider = world.insert_collider(collider, Some(body));
            // The pad slides along its face normal, its own y axis, on a spring to its rest place.
            let spring = PrismaticJointBuilder::new(Vector::Y).motor_model(MotorModel::ForceBased).motor_position(
                0.0,
                stiffness_n_m,
                damping_n_s_m,
            );
            world.insert_impulse_joint(mount, body, spring);
            bodies.push(PadBody { body, collider, stiffness_n_m, damping_n_s_m, rate_m_s: 0.0 });
        }
        let springs = PadFaces::new(pads.clone());
        Ok(RapierPads {
            world,
            springs,
            pads,
            bodies,
            pieces,
            pad_mass_kg,
            handed_over: Vec::new(),
            last_step_s: step_s,
        })
    }

    /// Moves the arm's shapes that can reach a pad to their poses now (`next`: as the kinematic
    /// target of the coming rapier step).
    fn pose_pieces(&mut self, arm: &ArmView, next: bool) {
        for (piece, &(body, _)) in arm.pieces.iter().zip(&self.pieces).filter(|(p, _)| p.near_pad) {
            let pose = arm.pose(piece);
            if let Some(body) = self.world.bodies.get_mut(body) {
                if next {
                    body.set_next_kinematic_position(pose);
                } else {
                    body.set_position(pose, true);
                }
            }
        }
    }

    /// Each pad's force on the arm at the end of the last step, into `pads`: while rapier holds
    /// the pad body in contact with an arm shape, what its mount and its inertia take,
    /// k x + c ẋ + m ẍ (x its travel); 0 once it has lifted off.
    fn measure_rapier(&mut self, arm: &ArmView) {
        let rest = self.springs.pairs().iter().map(|p| p.pose);
        for ((pad, mount), rest) in self.pads.iter_mut().zip(&mut self.bodies).zip(rest) {
            pad.clear_measurement();
            pad.touching = None;
            let Some(body) = self.world.bodies.get(mount.body) else { continue };
            let n = Vector::new(pad.normal_world[0], pad.normal_world[1], 0.0);
            let travel_m = (rest.translation - body.translation()).dot(n);
            let rate_m_s = -body.linvel().dot(n);
            let accel_m_s2 = (rate_m_s - mount.rate_m_s) / self.last_step_s;
            mount.rate_m_s = rate_m_s;
            pad.compression_m = travel_m.max(0.0);
            pad.pose = *body.position();
            let touching = arm.pieces.iter().zip(&self.pieces).find_map(|(piece, &(_, piece_collider))| {
                let pair = self.world.narrow_phase.contact_pair(piece_collider, mount.collider)?;
                (pair.total_impulse().length() > 0.0).then_some((piece, piece_collider))
            });
            let Some((piece, piece_collider)) = touching else { continue };
            let force = mount.stiffness_n_m * travel_m + mount.damping_n_s_m * rate_m_s + self.pad_mass_kg * accel_m_s2;
            let force = force.max(0.0);
            // The force acts on the arm's section at the pad's station, on the arm's face.
            let arm_collider = &self.world.colliders[piece_collider];
            let face = rest.translation - n * (pad.dampener().map_or(0.0, |d| 0.5 * d.thickness_m) - travel_m);
            let (station, _) = piece.station_of(arm_collider.position(), [face.x, face.y, face.z]);
            pad.force_n = force;
            pad.point_m = [face.x - arm.pivot_m[0], face.y - arm.pivot_m[1]];
            pad.station_m = station;
            pad.points.push(PointReading { point_m: [face.x, face.y, face.z], force_n: [force * n.x, force * n.y] });
            pad.touching = Some(piece.name.clone());
        }
    }
}

impl ContactSource for RapierPads {
    fn pose(&mut self, arm: &ArmView) {
        self.pose_pieces(arm, false);
    }

    fn add_loads(&self, arm: &ArmView, load: &mut GeneralizedLoad) {
        for &(station, force) in &self.handed_over {
            load.add(&arm.arm.point_force(station, force, arm.hub.angle_rad, arm.q));
        }
    }

    fn find_contacts(&mut self, arm: &ArmView, h_s: f64, contacts: &mut Vec<ArmContact>) {
        self.springs.find_contacts(arm, h_s, contacts);
    }

    fn advance(&mut self, arm: &ArmView, h_s: f64) {
        self.pose_pieces(arm, true);
        self.world.integration_parameters.dt = h_s;
        self.world.step();
        self.last_step_s = h_s;
    }

    /// Each pad's force as rapier resolves it, and what it adds to the spring law the arm step
    /// evaluated: the correction handed over next step.
    fn measure(&mut self, arm: &ArmView, contacts: &[ArmContact]) {
        self.springs.measure(arm, contacts);
        self.measure_rapier(arm);
        self.handed_over.clear();
        for (rapier, spring) in self.pads.iter().zip(self.springs.pairs()) {
            let extra = rapier.force_n - spring.force_n;
            if extra != 0.0 {
                let n = rapier.normal_world;
                let station = rapier.dampener().map_or(0.0, |d| d.station_m);
                self.handed_over.push((station, [extra * n[0], extra * n[1]]));
            }
        }
    }

    fn pairs(&self) -> &[ContactPair] {
        &self.pads
    }

    fn allows_free_step(&self, _arm: &ArmView, _h_s: f64) -> bool {
        false
    }

    fn fault(&self) -> Option<String> {
        self.pads.iter().find_map(ContactPair::fault)
    }

    fn divergence_advice(&self, _step_s: f64) -> Option<String> {
        Some(format!(
            "the rapier method hands the pad body's inertia ({:.3} kg) to the arm one step late, stable while it is \
             light against the arm's effective mass at the pad: use a lighter contact.pad_mass_kg, or \
             contact.kind = \"compliant\"",
            self.pad_mass_kg
        ))
    }
}
