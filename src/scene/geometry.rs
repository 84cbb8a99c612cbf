//! rapier shapes of the arm and what it carries, and their poses from the arm's state.

use nalgebra::DVector;
use rapier3d_f64::math::glamx::EulerRot;
use rapier3d_f64::prelude::*;

use crate::arm::{ArmModel, StationRows};
use crate::beam::BeamModel;
use crate::drive::DriveState;
use crate::model::Model;
use crate::robot::Shape;

/// The body of the machine on one side of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The arm, its hub and the bodies it carries.
    Arm,
    /// The held string (rigid or a beam of its own).
    String,
}

impl Side {
    /// The side's name in pair names.
    pub fn name(self) -> &'static str {
        match self {
            Side::Arm => "arm",
            Side::String => "string",
        }
    }
}

/// A rapier shape riding on the arm at a station.
#[derive(Debug, Clone)]
pub struct ArmPiece {
    /// Part name (`arm`, a link name, `string`), for the recording.
    pub name: String,
    /// Whose body it is: the arm's (the arm and the links it carries) or the held string's.
    pub side: Side,
    /// True for the finite-element boxes of the arm itself.
    pub is_arm_element: bool,
    /// True for the segments of a string modelled as a beam of its own: they ride on the string's
    /// section at their station, not the arm's, and are drawn as its centreline.
    pub on_string: bool,
    /// Station of the shape's centre, m.
    pub station_m: f64,
    /// How far it has moved along the arm from its station, m: a friction-clamped string's slip
    /// (its shapes keep the rows of the material at their station; 0 for everything else).
    pub axial_shift_m: f64,
    /// Offset of its centre across the arm (body y), m.
    pub lateral_m: f64,
    /// Offset normal to the lift plane (body z), m.
    pub normal_offset_m: f64,
    /// Rotation of the shape relative to the section, about body z, rad (plus a fixed tilt for
    /// cylinders), applied before the section's rotation.
    pub local_rotation: Rotation,
    /// Section depth (arm elements), m.
    pub depth_m: f64,
    /// Half extents of its bounding box in its own frame, m (for drawing).
    pub half_extents_m: [f64; 3],
    /// Its station's shape rows over the arm's coordinates (set when the scene is built).
    pub rows: StationRows,
    /// Whether it can come near a pad (set when the scene is built): only those are posed for
    /// contact every step.
    pub near_pad: bool,
    /// Its collision shape, in its own frame.
    pub shape: SharedShape,
    /// The tilting head's hinge [station, across the arm] (m), for a piece that turns with it
    /// (its station and offset are then its rest pose's, and its rows the hinge station's).
    pub hinge_m: Option<[f64; 2]>,
}

impl ArmPiece {
    /// Half extents of its box along the section's axes [along the arm, across it], m.
    pub fn section_extents_m(&self) -> [f64; 2] {
        let [hx, hy, hz] = self.half_extents_m;
        let axes = [Vector::new(hx, 0.0, 0.0), Vector::new(0.0, hy, 0.0), Vector::new(0.0, 0.0, hz)];
        axes.iter().map(|a| self.local_rotation * *a).fold([0.0, 0.0], |e, r| [e[0] + r.x.abs(), e[1] + r.y.abs()])
    }

    fn new(
        name: &str,
        [station_m, lateral_m, normal_offset_m]: [f64; 3],
        local_rotation: Rotation,
        half: [f64; 3],
        shape: SharedShape,
    ) -> Self {
        ArmPiece {
            name: name.into(),
            side: Side::Arm,
            is_arm_element: false,
            on_string: false,
            station_m,
            axial_shift_m: 0.0,
            lateral_m,
            normal_offset_m,
            local_rotation,
            depth_m: 0.0,
            half_extents_m: half,
            rows: StationRows([DVector::zeros(0), DVector::zeros(0), DVector::zeros(0)]),
            near_pad: true,
            shape,
            hinge_m: None,
        }
    }

    /// Station and body-y of a world point on this piece posed at `pose` (the piece moves
    /// rigidly with the section at its station): the station of the material there, whose rows
    /// it moves with; the point itself lies [`Self::axial_shift_m`] further along the arm.
    pub fn station_of(&self, pose: &Pose, world: [f64; 3]) -> (f64, f64) {
        let local = pose.rotation.inverse() * (Vector::new(world[0], world[1], world[2]) - pose.translation);
        // Back into the section frame: undo the piece's own rotation.
        let section = self.local_rotation * local;
        (self.station_m + section.x, self.lateral_m + section.y)
    }
}

/// Every shape of the scene that rides on the arm: the hub, the arm's elements (`beam`'s mesh),
/// the carried bodies and a held string (one piece, lumped or not).
pub fn shapes_of_robot(model: &Model, beam: &BeamModel) -> Vec<ArmPiece> {
    shapes_over(model, beam.elements.iter().map(|el| (el.x0_m, el.length_m)))
}

/// Segments a flexible string's surface is cut into for contact: each a cylinder riding on the
/// string's section at its middle, a fraction of the span between its hands long.
const STRING_SEGMENTS: usize = 24;

/// A flexible string's contact segments, from the one-piece `string` of [`shapes_of_robot`]; the
/// arm model gives each its station's rows on the string's coordinates.
pub fn string_segments(string: &ArmPiece, arm: &ArmModel) -> Vec<ArmPiece> {
    let [radius, half_length, _] = string.half_extents_m;
    let segment = 2.0 * half_length / STRING_SEGMENTS as f64;
    (0..STRING_SEGMENTS)
        .filter_map(|i| {
            let station = string.station_m - half_length + (i as f64 + 0.5) * segment;
            let rows = arm.string_station_rows(station)?;
            let shape = SharedShape::cylinder(0.5 * segment, radius);
            let at = [station, string.lateral_m, string.normal_offset_m];
            let mut piece = ArmPiece::new("string", at, string.local_rotation, [radius, 0.5 * segment, radius], shape);
            piece.on_string = true;
            piece.side = Side::String;
            piece.rows = rows;
            Some(piece)
        })
        .collect()
}

/// The pieces of [`shapes_of_robot`] over the arm's elements given as (start, length), m.
pub(super) fn shapes_over(model: &Model, elements: impl Iterator<Item = (f64, f64)>) -> Vec<ArmPiece> {
    let robot = &model.robot;
    let (width, depth) = (robot.arm.width_m(), robot.arm.depth_m());
    // The hub: a drum on the pivot, turning with the drive.
    let (hub_radius, hub_half_length) = (0.6 * depth, 0.5 * width.max(depth));
    let drum = Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2);
    let hub_shape = SharedShape::cylinder(hub_half_length, hub_radius);
    let mut pieces = vec![ArmPiece::new("hub", [0.0; 3], drum, [hub_radius, hub_half_length, hub_radius], hub_shape)];
    for (x0_m, length_m) in elements {
        let half = [0.5 * length_m, 0.5 * depth, 0.5 * width];
        let shape = SharedShape::cuboid(half[0], half[1], half[2]);
        let mut piece = ArmPiece::new("arm", [x0_m + 0.5 * length_m, 0.0, 0.0], Rotation::IDENTITY, half, shape);
        piece.is_arm_element = true;
        piece.depth_m = depth;
        pieces.push(piece);
    }
    for body in &robot.carried {
        for placed in &body.shapes {
            let rpy = placed.rpy_rad;
            let rotation = Rotation::from_euler(EulerRot::ZYX, rpy[2], rpy[1], rpy[0]);
            let (shape, rotation, half) = match placed.shape {
                Shape::Box { half_extents_m: h } => (SharedShape::cuboid(h[0], h[1], h[2]), rotation, h),
                // parry's cylinders run along y, URDF's along z.
                Shape::Cylinder { radius_m, half_length_m } => (
                    SharedShape::cylinder(half_length_m, radius_m),
                    rotation * Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2),
                    [radius_m, half_length_m, radius_m],
                ),
                Shape::Sphere { radius_m } => (SharedShape::ball(radius_m), rotation, [radius_m; 3]),
            };
            let mut piece = ArmPiece::new(&body.name, placed.position_m, rotation, half, shape);
            piece.hinge_m = robot.head.as_ref().filter(|_| body.tilts).map(|h| [h.hinge_station_m, h.hinge_lateral_m]);
            pieces.push(piece);
        }
    }
    if let Some(held) = model.payload.held_string()
        && let Some(clamp) = robot.body(&held.palm().hand)
    {
        let [lateral, normal] = robot.string_axis_offset_m(clamp);
        let radius = 0.5 * held.pipe.pipe.outer_diameter_m;
        let half_length = 0.5 * held.pipe.length_m;
        let along_arm = Rotation::from_rotation_z(-std::f64::consts::FRAC_PI_2);
        let mut string = ArmPiece::new(
            "string",
            [held.centre_m(), lateral, normal],
            along_arm,
            [radius, half_length, radius],
            SharedShape::cylinder(half_length, radius),
        );
        string.side = Side::String;
        // In the tilting head's hands it turns with the head (drawn only: it strikes nothing).
        string.hinge_m = robot.head.as_ref().filter(|_| clamp.tilts).map(|h| [h.hinge_station_m, h.hinge_lateral_m]);
        pieces.push(string);
    }
    pieces
}

/// World pose of a piece from the arm's state: the section at its station carries it rigidly,
/// or, on the tilting head, the section at the hinge turned by the head's angle `head_rad`.
pub fn pose_piece(piece: &ArmPiece, hub: &DriveState, q: &DVector<f64>, head_rad: f64, pivot_m: [f64; 3]) -> Pose {
    let [u, v, slope] = piece.rows.displacement(q);
    let (body, slope) = match piece.hinge_m {
        Some([hx, hy]) => {
            let turn = slope + head_rad;
            let (st, ct) = turn.sin_cos();
            let [ox, oy] = [piece.station_m - hx, piece.lateral_m - hy];
            ([hx + u - hy * slope + ct * ox - st * oy, hy + v + st * ox + ct * oy], turn)
        }
        None => {
            let (x, y) = (piece.station_m + piece.axial_shift_m, piece.lateral_m);
            ([x + u - y * slope, y + v], slope)
        }
    };
    let (s, c) = hub.angle_rad.sin_cos();
    let translation = Vector::new(
        pivot_m[0] + c * body[0] - s * body[1],
        pivot_m[1] + s * body[0] + c * body[1],
        pivot_m[2] + piece.normal_offset_m,
    );
    let rotation = Rotation::from_rotation_z(hub.angle_rad + slope) * piece.local_rotation;
    Pose::from_parts(translation, rotation)
}

/// The arm at one instant, as a contact source sees it.
pub struct ArmView<'a> {
    /// The arm's model.
    pub arm: &'a ArmModel,
    /// The hub's state.
    pub hub: DriveState,
    /// Elastic coordinates.
    pub q: &'a DVector<f64>,
    /// Their rates.
    pub qd: &'a DVector<f64>,
    /// The shapes riding on the arm.
    pub pieces: &'a [ArmPiece],
    /// The lift joint's pivot in the world, m.
    pub pivot_m: [f64; 3],
    /// The tilting head's angle on its hinge, rad (0 without one).
    pub head_rad: f64,
}

impl ArmView<'_> {
    /// World pose of a piece riding on the arm.
    pub fn pose(&self, piece: &ArmPiece) -> Pose {
        pose_piece(piece, &self.hub, self.q, self.head_rad, self.pivot_m)
    }

    /// How far ahead a contact must be seen over a step of `h_s`: three times the travel of the
    /// arm's fastest point, m.
    pub fn step_travel_m(&self, h_s: f64) -> f64 {
        3.0 * self.speed_bound_m_s() * h_s
    }

    /// The reach a contact detection looks ahead over a step of `h_s`: [`Self::step_travel_m`],
    /// at least 2 mm, m.
    pub fn contact_reach_m(&self, h_s: f64) -> f64 {
        self.step_travel_m(h_s).max(2e-3)
    }

    /// A bound on any arm point's speed: the hub's rotation at the tip (plus a metre) plus the
    /// tip's elastic speed, m/s.
    pub fn speed_bound_m_s(&self) -> f64 {
        let [ru, rv, _] = self.arm.tip_rows();
        self.hub.rate_rad_s.abs() * (self.arm.length_m() + 1.0) + ru.dot(self.qd).hypot(rv.dot(self.qd))
    }
}
