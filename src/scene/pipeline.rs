//! `contact.detection = "pipeline"`: contacts from rapier's collision pipeline, each pair's law
//! evaluated inside the implicit arm step.
//!
//! Every shape that can reach something (arm elements, hub, carried bodies, the string or its
//! segments) and everything it can strike (pads, structures) is a collider in one rapier world;
//! the pieces are posed from the arm's state each step and rapier's broad phase, narrow phase and
//! contact manifolds find the points within reach. A pair's law is spread over its points as a
//! Winkler bed: each of the N points a pair's manifolds hold carries 1/N of the law at its own
//! penetration and rate. A flat face pressed evenly then gives the law's force whatever N is; a
//! tilted one the mean of the law over the points.

use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView};
use super::pair::{ContactPair, measure_points};
use super::source::ContactSource;
use crate::arm::{ArmContact, PointContact};

/// Pieces touch obstacles, not each other; obstacles touch pieces.
const PIECE_GROUPS: InteractionGroups =
    InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And);
const OBSTACLE_GROUPS: InteractionGroups =
    InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);
/// The colliders have no bodies (rapier treats them as fixed): only collision detection runs.
const TYPES: ActiveCollisionTypes = ActiveCollisionTypes::FIXED_FIXED;
/// `user_data` of an obstacle's collider: this bit and the index of its first pair.
const OBSTACLE_TAG: u128 = 1 << 64;
/// A normal whose in-plane part is shorter than this is across the lift plane: not modelled.
const MIN_IN_PLANE_NORMAL: f64 = 0.1;

/// A point of a contact manifold, on the struck body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ManifoldPoint {
    /// World position on the struck body, m.
    pub point_m: [f64; 3],
    /// In-plane unit normal (world X, Y) along which the other body pushes it.
    pub normal_world: [f64; 2],
    /// Penetration, m (negative: a gap within reach).
    pub depth_m: f64,
}

/// The points within `reach_m` of a contact pair's manifolds, on the body that is collider 1 if
/// `first` (else collider 2) and posed at `pose`; normals across the lift plane left out.
fn manifold_points(
    contact: &rapier3d_f64::geometry::ContactPair,
    first: bool,
    pose: &Pose,
    reach_m: f64,
) -> impl Iterator<Item = ManifoldPoint> {
    contact.manifolds().iter().flat_map(move |manifold| {
        // rapier's normal points from collider 1 to collider 2; the other body pushes this one.
        let n = manifold.data.normal * if first { -1.0 } else { 1.0 };
        let in_plane = n.x.hypot(n.y);
        let points = if in_plane < MIN_IN_PLANE_NORMAL { &manifold.points[..0] } else { &manifold.points[..] };
        points.iter().filter(move |p| p.dist <= reach_m).map(move |p| {
            let world = pose * if first { p.local_p1 } else { p.local_p2 };
            ManifoldPoint {
                point_m: [world.x, world.y, world.z],
                normal_world: [n.x / in_plane, n.y / in_plane],
                depth_m: -p.dist,
            }
        })
    })
}

/// The points rapier's collision pipeline finds between a struck shape `a` and a shape `b` it
/// presses on, within `reach_m`: each carries 1/N of a pair's law (module doc).
pub fn manifold_between(a: (&SharedShape, Pose), b: (&SharedShape, Pose), reach_m: f64) -> Vec<ManifoldPoint> {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.length_unit = 1.0;
    world.integration_parameters.normalized_prediction_distance = reach_m;
    let collider = |(shape, pose): (&SharedShape, Pose)| {
        ColliderBuilder::new(shape.clone()).position(pose).active_collision_types(TYPES)
    };
    let ha = world.insert_collider(collider(a), None);
    world.insert_collider(collider(b), None);
    world.detect_collisions(&(), &());
    let pose = *world.colliders[ha].position();
    world
        .narrow_phase
        .contact_pairs()
        .flat_map(|c| manifold_points(c, c.collider1 == ha, &pose, reach_m).collect::<Vec<_>>())
        .collect()
}

/// A manifold point found this step, before its pair's share is known.
struct Found {
    pair: usize,
    piece: usize,
    world_m: [f64; 3],
    normal_world: [f64; 2],
    depth_m: f64,
}

/// Contact pairs found by rapier's collision pipeline.
pub struct PipelineContacts {
    world: PhysicsWorld,
    pairs: Vec<ContactPair>,
    /// Per piece (the scene's order): its collider, if it can reach an obstacle.
    pieces: Vec<Option<ColliderHandle>>,
    /// Per pair, the closing speed at first touch of its current impact, m/s.
    impact_speed_m_s: Vec<f64>,
    found: Vec<Found>,
}

impl PipelineContacts {
    /// rapier's world of the pieces that can reach an obstacle (`near_pad`) and the obstacles of
    /// `pairs` (pairs on one obstacle share its collider).
    pub fn new(arm: &ArmView, pairs: Vec<ContactPair>) -> Self {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.length_unit = 1.0;
        let pieces = arm
            .pieces
            .iter()
            .enumerate()
            .map(|(i, piece)| {
                piece.near_pad.then(|| {
                    let collider = ColliderBuilder::new(piece.shape.clone())
                        .position(arm.pose(piece))
                        .active_collision_types(TYPES)
                        .collision_groups(PIECE_GROUPS)
                        .user_data(i as u128);
                    world.insert_collider(collider, None)
                })
            })
            .collect();
        let mut placed: Vec<&str> = Vec::new();
        for (i, pair) in pairs.iter().enumerate() {
            if placed.contains(&pair.obstacle.name()) {
                continue;
            }
            placed.push(pair.obstacle.name());
            let collider = ColliderBuilder::new(pair.shape.clone())
                .position(pair.pose)
                .active_collision_types(TYPES)
                .collision_groups(OBSTACLE_GROUPS)
                .user_data(OBSTACLE_TAG | i as u128);
            world.insert_collider(collider, None);
        }
        let impact_speed_m_s = vec![0.0; pairs.len()];
        PipelineContacts { world, pairs, pieces, impact_speed_m_s, found: Vec::new() }
    }

    /// Poses the pieces and runs rapier's broad and narrow phases with `reach_m` of prediction.
    fn detect(&mut self, arm: &ArmView, reach_m: f64) {
        for (piece, collider) in arm.pieces.iter().zip(&self.pieces) {
            if let Some(collider) = collider.and_then(|h| self.world.colliders.get_mut(h)) {
                collider.set_position(arm.pose(piece));
            }
        }
        self.world.integration_parameters.normalized_prediction_distance = reach_m;
        self.world.detect_collisions(&(), &());
    }

    /// The manifold points within `reach_m`, into `self.found`.
    fn collect(&mut self, arm: &ArmView, reach_m: f64) {
        self.found.clear();
        let colliders = &self.world.colliders;
        for contact in self.world.narrow_phase.contact_pairs() {
            let (Some(c1), Some(c2)) = (colliders.get(contact.collider1), colliders.get(contact.collider2)) else {
                continue;
            };
            let piece_first = c1.user_data & OBSTACLE_TAG == 0;
            let (piece_collider, obstacle) = if piece_first { (c1, c2) } else { (c2, c1) };
            let piece = piece_collider.user_data as usize;
            let first_pair = (obstacle.user_data & !OBSTACLE_TAG) as usize;
            let name = self.pairs[first_pair].obstacle.name();
            let Some(pair) =
                self.pairs.iter().position(|p| p.obstacle.name() == name && p.involves(&arm.pieces[piece]))
            else {
                continue;
            };
            for point in manifold_points(contact, piece_first, piece_collider.position(), reach_m) {
                self.found.push(Found {
                    pair,
                    piece,
                    world_m: point.point_m,
                    normal_world: point.normal_world,
                    depth_m: point.depth_m,
                });
            }
        }
    }

    /// The arm contact of a found point carrying `share` of its pair's law.
    fn arm_contact(&self, arm: &ArmView, found: &Found, share: f64) -> ArmContact {
        let pair = &self.pairs[found.pair];
        let piece: &ArmPiece = &arm.pieces[found.piece];
        let (material_m, lateral_m) = piece.station_of(&arm.pose(piece), found.world_m);
        let point = PointContact {
            pair: found.pair,
            station_m: material_m + piece.axial_shift_m,
            lateral_m,
            normal_world: found.normal_world,
            depth_m: found.depth_m,
            reference_point_m: [found.world_m[0] - arm.pivot_m[0], found.world_m[1] - arm.pivot_m[1]],
            law: pair.obstacle.law(),
            impact_speed_m_s: self.impact_speed_m_s[found.pair],
            share,
            friction: pair.obstacle.friction(),
        };
        if piece.is_arm_element {
            arm.arm.arm_contact(point)
        } else if piece.on_string {
            let rows = arm.arm.string_station_rows(material_m).unwrap_or_else(|| piece.rows.clone());
            ArmContact::on_section(point, &rows, 0.0)
        } else {
            ArmContact::on_section(point, &piece.rows, material_m - piece.station_m)
        }
    }
}

impl ContactSource for PipelineContacts {
    fn find_contacts(&mut self, arm: &ArmView, h_s: f64, contacts: &mut Vec<ArmContact>) {
        // Contact detection is most of a step's cost: skipped while nothing is within reach.
        if self.allows_free_step(arm, h_s) {
            return;
        }
        let reach = arm.contact_reach_m(h_s);
        self.detect(arm, reach);
        self.collect(arm, reach);
        let mut count = vec![0usize; self.pairs.len()];
        self.found.iter().for_each(|f| count[f.pair] += 1);
        let start = contacts.len();
        for found in &self.found {
            contacts.push(self.arm_contact(arm, found, 1.0 / count[found.pair] as f64));
        }
        // A pair not in contact at the last step starts an impact: its fastest closing point
        // sets the v₀ of restitution laws.
        let mut closing = vec![0.0_f64; self.pairs.len()];
        for c in &contacts[start..] {
            let rate = c.state(&arm.hub, arm.q, arm.qd).rate_m_s;
            closing[c.contact.pair] = closing[c.contact.pair].max(rate);
        }
        for (i, pair) in self.pairs.iter().enumerate() {
            if pair.force_n <= 0.0 && count[i] > 0 {
                self.impact_speed_m_s[i] = closing[i].max(1e-6);
            }
        }
        for c in &mut contacts[start..] {
            c.contact.impact_speed_m_s = self.impact_speed_m_s[c.contact.pair];
        }
    }

    fn measure(&mut self, arm: &ArmView, contacts: &[ArmContact]) {
        // The contacts are this source's, in the order `found` holds their points.
        let found = &self.found;
        measure_points(&mut self.pairs, arm, contacts, |k| &arm.pieces[found[k].piece].name);
    }

    fn pairs(&self) -> &[ContactPair] {
        &self.pairs
    }

    fn allows_free_step(&self, arm: &ArmView, h_s: f64) -> bool {
        ContactPair::none_within_reach(&self.pairs, arm, h_s)
    }

    fn fault(&self) -> Option<String> {
        self.pairs.iter().find_map(ContactPair::fault)
    }
}
