//! `contact.method = "rapier"`: each pad is a rapier body on a linear spring–damper mount, and
//! rapier's constraint solver resolves its contact with the arm's shapes (kinematic bodies posed
//! from the arm's state). The contact impulse / dt of one rapier step is handed to the arm as a
//! load over the next step: staggered, and rapier integrates the pad body explicitly, so the
//! method is stable only below [`ForceLaw::explicit_body_limit_s`] of the pad's law and mass.

use std::any::Any;

use rapier3d_f64::prelude::*;

use super::geometry::ArmView;
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
/// must be linear, and its face normal along a world axis (rapier locks translations in world
/// axes). The error names the dampener's key and what is allowed.
pub fn rapier_pad_spring(dampener: &Dampener) -> Result<(f64, f64), (&'static str, String)> {
    let ForceLaw::Linear { stiffness_n_m, damping_n_s_m } = dampener.law else {
        return Err((
            "law",
            "contact.method = \"rapier\" models the pad as a linear spring: allowed law kind = \"linear\"".into(),
        ));
    };
    let (s, c) = dampener.angle_rad.sin_cos();
    if s.abs() < 1.0 - 1e-9 && c.abs() < 1.0 - 1e-9 {
        return Err((
            "angle_deg",
            "contact.method = \"rapier\" needs a pad facing a world axis: allowed angle_deg 0, ±90, 180".into(),
        ));
    }
    Ok((stiffness_n_m, damping_n_s_m))
}

/// A pad body's linear spring–damper to its rest position.
#[derive(Debug, Clone, Copy)]
struct PadSpring {
    rest_m: [f64; 3],
    stiffness_n_m: f64,
    damping_n_s_m: f64,
}

/// Pads as rapier bodies on springs, struck by the arm's shapes in rapier's world.
pub struct RapierPads {
    world: PhysicsWorld,
    pads: Vec<ContactPair>,
    /// Per pad: its body, collider and mount.
    bodies: Vec<(RigidBodyHandle, ColliderHandle, PadSpring)>,
    /// Per arm piece (the scene's order): its kinematic body and collider.
    pieces: Vec<(RigidBodyHandle, ColliderHandle)>,
    pad_mass_kg: f64,
    /// Per pad, the forces measured by the last rapier step: (station, force world X/Y).
    handed_over: Vec<(f64, [f64; 2])>,
    last_step_s: f64,
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
        world.integration_parameters.dt = step_s;
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
                key: "contact.method",
                message: "the rapier method models pads only: allowed method \"compliant\" with structures".into(),
            })?;
            let (stiffness_n_m, damping_n_s_m) = rapier_pad_spring(dampener)
                .map_err(|(key, message)| UnsupportedPad { name: dampener.name.clone(), key, message })?;
            let t = pad.pose.translation;
            let spring = PadSpring { rest_m: [t.x, t.y, t.z], stiffness_n_m, damping_n_s_m };
            // The pad slides along its normal only.
            let along_x = pad.normal_world[0].abs() > 1.0 - 1e-9;
            let builder = RigidBodyBuilder::dynamic()
                .gravity_scale(0.0)
                .can_sleep(false)
                .lock_rotations()
                .enabled_translations(along_x, !along_x, false)
                .pose(pad.pose);
            let body = world.insert_body(builder);
            let collider = ColliderBuilder::new(pad.shape.clone())
                .active_collision_types(PAD_CONTACT_TYPES)
                .collision_groups(PAD_GROUPS)
                .friction(0.0)
                .mass(pad_mass_kg);
            bodies.push((body, world.insert_collider(collider, Some(body)), spring));
        }
        Ok(RapierPads { world, pads, bodies, pieces, pad_mass_kg, handed_over: Vec::new(), last_step_s: step_s })
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

    /// Spring–damper force of each pad's mount, held over the rapier step.
    fn apply_pad_springs(&mut self) {
        for &(handle, _, spring) in &self.bodies {
            let Some(body) = self.world.bodies.get_mut(handle) else { continue };
            let x = body.translation();
            let v = body.linvel();
            let rest = Vector::new(spring.rest_m[0], spring.rest_m[1], spring.rest_m[2]);
            let force = -(x - rest) * spring.stiffness_n_m - v * spring.damping_n_s_m;
            body.reset_forces(false);
            body.add_force(force, true);
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

    fn advance(&mut self, arm: &ArmView, h_s: f64) {
        self.pose_pieces(arm, true);
        self.apply_pad_springs();
        self.world.integration_parameters.dt = h_s;
        self.world.step();
        self.last_step_s = h_s;
    }

    /// Each pad's force from rapier's contact impulses over the last step.
    fn measure(&mut self, arm: &ArmView, _contacts: &[ArmContact]) {
        self.handed_over.clear();
        for (pad, &(handle, collider, spring)) in self.pads.iter_mut().zip(&self.bodies) {
            pad.clear_measurement();
            pad.touching = None;
            if let Some(body) = self.world.bodies.get(handle) {
                let travel = [0, 1].map(|k| spring.rest_m[k] - body.translation()[k]);
                pad.compression_m = (travel[0] * pad.normal_world[0] + travel[1] * pad.normal_world[1]).max(0.0);
                pad.pose = *body.position();
            }
            for (piece, &(_, piece_collider)) in arm.pieces.iter().zip(&self.pieces) {
                let Some(pair) = self.world.narrow_phase.contact_pair(piece_collider, collider) else { continue };
                let magnitude = pair.total_impulse().length();
                if magnitude <= 0.0 {
                    continue;
                }
                let force = magnitude / self.last_step_s;
                let arm_collider = &self.world.colliders[piece_collider];
                let point = pair
                    .find_deepest_contact()
                    .map(|(_, c)| {
                        let local = if pair.collider1 == piece_collider { c.local_p1 } else { c.local_p2 };
                        arm_collider.position() * local
                    })
                    .unwrap_or(arm_collider.translation());
                // The force acts on the arm's section at the point's station.
                let (station, _) = piece.station_of(arm_collider.position(), [point.x, point.y, point.z]);
                pad.force_n += force;
                pad.point_m = [point.x - arm.pivot_m[0], point.y - arm.pivot_m[1]];
                pad.station_m = station;
                let n = pad.normal_world;
                pad.points
                    .push(PointReading { point_m: [point.x, point.y, point.z], force_n: [force * n[0], force * n[1]] });
                pad.touching = Some(piece.name.clone());
                self.handed_over.push((station, [force * pad.normal_world[0], force * pad.normal_world[1]]));
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
        let limit = self
            .pads
            .iter()
            .filter_map(|p| p.obstacle.law().explicit_body_limit_s(self.pad_mass_kg))
            .fold(f64::INFINITY, f64::min);
        Some(format!(
            "rapier integrates the pad body on its spring-damper explicitly, stable only below {limit:.3e} s: use \
             step_s <= {:.3e} s, a heavier pad body, or contact.method = \"compliant\"",
            0.9 * limit
        ))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
