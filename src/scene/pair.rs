//! Contact pairs: one body of the machine (the arm with what it carries, or the held string)
//! against one thing it can strike (a rubber pad at a stop, a piece of rig structure), and the
//! force measured between them.

use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView, Side};
use super::pads::PadPlacement;
use crate::arm::ArmModel;
use crate::channel::{Channel, Reading};
use crate::contact::ForceLaw;
use crate::drive::DriveState;
use crate::model::{Dampener, Model, Structure, StructureShape};
use nalgebra::DVector;

/// A contact pair's name, `<side>-<obstacle>` as the summary gives it, from its series name
/// ([`Model::pair_series_names`]: `<pad>` or `<structure>` for the arm's pairs,
/// `string-<structure>` for the string's).
pub fn pair_name(series_name: &str) -> String {
    if series_name.starts_with("string-") { series_name.to_string() } else { format!("arm-{series_name}") }
}

/// Entity path of a contact pair's force plot, from its series name.
pub fn force_entity(series_name: &str) -> String {
    format!("plots/contact_force/{}", pair_name(series_name))
}

/// Each contact pair's force channel ([`crate::channel`]), in the scene's order:
/// `contact_force.<pair>` ([`pair_name`]: `arm-<pad>`, `arm-<structure>`, `string-<structure>`,
/// as the summary and the recording name the pair), N, plotted at [`force_entity`]; a pad's is
/// measurable.
pub fn pair_channels(model: &Model) -> Vec<Channel> {
    let pads = model.dampeners.len();
    let channel = |(k, name): (usize, String)| {
        let channel = Channel::new(format!("contact_force.{}", pair_name(&name)), "N", Reading::ContactForce(k))
            .plotted(force_entity(&name), 1.0);
        if k < pads { channel.measurable() } else { channel }
    };
    model.pair_series_names().into_iter().enumerate().map(channel).collect()
}

/// Each contact pair's name ([`pair_name`]), in the scene's order.
pub fn pair_names(model: &Model) -> Vec<String> {
    model.pair_series_names().iter().map(|name| pair_name(name)).collect()
}

/// What a pair's body strikes.
#[derive(Debug, Clone)]
pub enum Obstacle {
    /// A rubber pad set against the arm at a stop.
    Pad(Dampener),
    /// A piece of fixed rig structure.
    Structure(Structure),
}

impl Obstacle {
    /// Its name as the scenario gives it.
    pub fn name(&self) -> &str {
        match self {
            Obstacle::Pad(d) => &d.name,
            Obstacle::Structure(s) => &s.name,
        }
    }

    /// The force law of its face.
    pub fn law(&self) -> ForceLaw {
        match self {
            Obstacle::Pad(d) => d.law,
            Obstacle::Structure(s) => s.law,
        }
    }

    /// Coulomb friction of its face (pads are frictionless).
    pub fn friction(&self) -> f64 {
        match self {
            Obstacle::Pad(_) => 0.0,
            Obstacle::Structure(s) => s.friction,
        }
    }
}

/// A manifold point of the last step: where it is and the force it put on the machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointReading {
    /// World position, m.
    pub point_m: [f64; 3],
    /// Force on the machine (world X, Y), N.
    pub force_n: [f64; 2],
}

/// A body of the machine against an obstacle, and its state at the end of the last step.
#[derive(Debug, Clone)]
pub struct ContactPair {
    /// `<side>-<obstacle>`, as reported.
    pub name: String,
    /// The machine's body.
    pub side: Side,
    /// What it strikes.
    pub obstacle: Obstacle,
    /// The obstacle's world pose (a `rapier` pad body's where it is now).
    pub pose: Pose,
    /// The obstacle's shape in its own frame.
    pub shape: SharedShape,
    /// Unit normal (world X, Y) along which the obstacle pushes: a pad's face normal, or a
    /// structure's at the last contact.
    pub normal_world: [f64; 2],
    /// Normal force at the end of the last step, N.
    pub force_n: f64,
    /// Deepest penetration (or a `rapier` pad's travel) at the end of the last step, m; beyond
    /// a pad's thickness the run is meaningless.
    pub compression_m: f64,
    /// Point of application of the force (force-weighted over the points) relative to the pivot
    /// (world X, Y), m.
    pub point_m: [f64; 2],
    /// Arm station of that point, m (for a string, its station along the arm's axis).
    pub station_m: f64,
    /// Name of the part touching it.
    pub touching: Option<String>,
    /// The points of the last step.
    pub points: Vec<PointReading>,
    /// A pad's placement against the arm (its face and the arm's face point).
    pub pad: Option<PadPlacement>,
}

impl ContactPair {
    /// The pair of the arm and a pad placed against it at its stop.
    pub fn pad(dampener: &Dampener, pieces: &[ArmPiece], arm: &ArmModel, pivot_m: [f64; 3]) -> Self {
        let (placement, pose) = PadPlacement::place(dampener, pieces, arm, pivot_m);
        let shape = SharedShape::cuboid(0.5 * dampener.length_m, 0.5 * dampener.thickness_m, 0.5 * dampener.width_m);
        let normal_world = placement.normal_world;
        Self::new(Side::Arm, Obstacle::Pad(dampener.clone()), pose, shape, normal_world, Some(placement))
    }

    /// The pair of `side` and a structure.
    pub fn structure(structure: &Structure, side: Side) -> Self {
        let [x, y, z] = structure.position_m;
        let rotation = Rotation::from_rotation_z(structure.angle_rad);
        let (shape, rotation) = match structure.shape {
            StructureShape::Box { half_extents_m: [hx, hy, hz] } => (SharedShape::cuboid(hx, hy, hz), rotation),
            // parry's cylinders run along their y; a structure's along world z.
            StructureShape::Cylinder { radius_m, half_length_m } => (
                SharedShape::cylinder(half_length_m, radius_m),
                rotation * Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2),
            ),
        };
        let pose = Pose::from_parts(Vector::new(x, y, z), rotation);
        Self::new(side, Obstacle::Structure(structure.clone()), pose, shape, [0.0, 1.0], None)
    }

    fn new(
        side: Side,
        obstacle: Obstacle,
        pose: Pose,
        shape: SharedShape,
        normal_world: [f64; 2],
        pad: Option<PadPlacement>,
    ) -> Self {
        ContactPair {
            name: format!("{}-{}", side.name(), obstacle.name()),
            side,
            obstacle,
            pose,
            shape,
            normal_world,
            force_n: 0.0,
            compression_m: 0.0,
            point_m: [0.0; 2],
            station_m: 0.0,
            touching: None,
            points: Vec::new(),
            pad,
        }
    }

    /// The pad it is, if it is one.
    pub fn dampener(&self) -> Option<&Dampener> {
        match &self.obstacle {
            Obstacle::Pad(d) => Some(d),
            Obstacle::Structure(_) => None,
        }
    }

    /// Whether a piece takes part in this pair.
    pub fn involves(&self, piece: &ArmPiece) -> bool {
        piece.side == self.side
    }

    /// Whether the machine could touch the obstacle within `travel_m`, the fastest point's travel
    /// in the coming step with margin: a pad from its clearance, a structure from the bounding
    /// boxes of the pieces on its side.
    pub fn within_reach(&self, arm: &ArmView, travel_m: f64) -> bool {
        if let Some(pad) = &self.pad {
            return pad.within_reach(arm, travel_m);
        }
        let obstacle = self.shape.compute_aabb(&self.pose).loosened(travel_m);
        arm.pieces
            .iter()
            .filter(|p| p.near_pad && self.involves(p))
            .any(|p| p.shape.compute_aabb(&arm.pose(p)).intersects(&obstacle))
    }

    /// Whether no pair of `pairs` can be touched within a step of `h_s` (the step may then be a
    /// free one, and detection skipped).
    pub fn none_within_reach(pairs: &[ContactPair], arm: &ArmView, h_s: f64) -> bool {
        let travel_m = arm.step_travel_m(h_s);
        !pairs.iter().any(|p| p.within_reach(arm, travel_m))
    }

    /// The arm's effective mass at a pad's station along the arm's normal with the hub held,
    /// 1 / (rᵀ M⁻¹ r), kg, given M⁻¹ (`None`: a structure, or no elastic coordinates).
    pub fn effective_mass_kg(&self, mass_inverse: Option<&nalgebra::DMatrix<f64>>) -> Option<f64> {
        self.pad.as_ref()?.effective_mass_kg(mass_inverse)
    }

    /// What makes the pair's state meaningless: a force that is not finite, or a pad crushed
    /// beyond its thickness.
    pub fn fault(&self) -> Option<String> {
        let name = &self.name;
        let thickness = self.dampener().map_or(f64::INFINITY, |d| d.thickness_m);
        if !self.force_n.is_finite() {
            Some(format!("pair {name}'s contact force is no longer finite"))
        } else if self.compression_m > thickness {
            Some(format!(
                "pad {} is compressed {:.1} mm, beyond its {:.1} mm thickness",
                self.obstacle.name(),
                1e3 * self.compression_m,
                1e3 * thickness
            ))
        } else {
            None
        }
    }

    /// Clears the measured state before a step's measurement.
    pub fn clear_measurement(&mut self) {
        self.force_n = 0.0;
        self.compression_m = 0.0;
        self.points.clear();
    }
}

/// Which structure, if any, overlaps the machine in its rest pose at the drive's start (the arm
/// as one box, what it carries, the string as one rigid piece), and the part it overlaps.
pub fn structure_in_rest_pose(model: &Model) -> Option<(usize, String)> {
    let pieces = super::geometry::shapes_over(model, std::iter::once((0.0, model.robot.arm.length_m())));
    let hub = DriveState { angle_rad: model.drive.motion.start_rad(), ..DriveState::default() };
    let q = DVector::zeros(0);
    // The pieces' rows are still empty: posed undeformed.
    let posed: Vec<(Pose, &ArmPiece)> =
        pieces.iter().map(|p| (super::geometry::pose_piece(p, &hub, &q, 0.0, model.robot.lift.pivot_m), p)).collect();
    model.structures.iter().enumerate().find_map(|(i, s)| {
        let pair = ContactPair::structure(s, Side::Arm);
        posed.iter().find_map(|(pose, piece)| {
            parry3d_f64::query::intersection_test(pose, &*piece.shape, &pair.pose, &*pair.shape)
                .ok()
                .filter(|hit| hit.intersecting)
                .map(|_| (i, piece.name.clone()))
        })
    })
}

/// Measures `pairs` from the contacts a source handed the step (each naming its pair): the sum
/// of their normal forces, the deepest penetration, the force-weighted point and station, each
/// point's force; `touching(k)` names the part of contact `k`.
pub fn measure_points<'a>(
    pairs: &mut [ContactPair],
    arm: &ArmView,
    contacts: &[crate::arm::ArmContact],
    touching: impl Fn(usize) -> &'a str,
) {
    pairs.iter_mut().for_each(ContactPair::clear_measurement);
    let mut weighted = vec![[0.0_f64; 3]; pairs.len()];
    for (k, c) in contacts.iter().enumerate() {
        let state = c.state(&arm.hub, arm.q, arm.qd);
        let i = c.contact.pair;
        let pair = &mut pairs[i];
        pair.force_n += state.force_n;
        pair.compression_m = pair.compression_m.max(state.depth_m);
        if state.force_n <= 0.0 {
            continue;
        }
        let n = c.contact.normal_world;
        let (f, t) = (state.force_n, state.friction_n);
        let [px, py] = state.point_m;
        pair.normal_world = n;
        pair.touching = Some(touching(k).to_string());
        pair.points.push(PointReading {
            point_m: [px + arm.pivot_m[0], py + arm.pivot_m[1], arm.pivot_m[2]],
            force_n: [f * n[0] - t * n[1], f * n[1] + t * n[0]],
        });
        let w = &mut weighted[i];
        *w = [w[0] + f * px, w[1] + f * py, w[2] + f * c.contact.station_m];
    }
    for (pair, w) in pairs.iter_mut().zip(weighted) {
        if pair.force_n > 0.0 {
            pair.point_m = [w[0] / pair.force_n, w[1] / pair.force_n];
            pair.station_m = w[2] / pair.force_n;
        } else {
            pair.touching = None;
        }
    }
}
