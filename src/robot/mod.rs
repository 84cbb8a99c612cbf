//! Robots: the arm and what it carries, read from URDF with pipearm's flexible-link parameters,
//! and the pipe catalogue.
//!
//! A robot is a base, a revolute lift joint about z (the lift plane is XY, Y up), a flexible arm
//! link along its x axis, and rigid links carried by the arm (hand, gripper palm, jaws) through
//! fixed or prismatic joints. Each carried link becomes a concentrated mass at the arm station
//! of its centre of mass; its offset across the arm and out of the plane is kept for geometry only.
//! Links below a revolute joint with a spring hinge form a tilting head ([`TiltingHead`]): one
//! rigid body turning on the arm.

mod head;
pub mod pipes;
mod urdf;

use std::path::PathBuf;

use thiserror::Error;

use crate::fatigue::SnCurve;

pub use head::{HingeLaw, TiltingHead};
pub use pipes::{
    ConnectionPiece, CustomPipeSpec, Joints, PIPE_CATALOGUE, Pipe, PipeSize, PipeString, Product, Range, StringSpec,
    find_row, pipe_size,
};
pub use urdf::load_robot;

use crate::beam::{BeamError, BeamSpec, ConcentratedMass, Material, SectionShape, Segment};

/// Errors in a robot description; each names the file (where there is one) and the key.
#[derive(Debug, Error)]
pub enum RobotError {
    /// The file could not be read or is not well-formed XML / URDF.
    #[error("{path}: {message}")]
    Parse { path: PathBuf, message: String },
    /// A value missing, malformed or out of range.
    #[error("{path}: `{key}`: {message}")]
    InvalidInFile { path: PathBuf, key: String, message: String },
    /// A value out of range, outside any file.
    #[error("`{key}`: {message}")]
    Invalid { key: String, message: String },
}

/// A uniform length of the flexible arm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmSegment {
    /// Length, m.
    pub length_m: f64,
    /// Section.
    pub section: SectionShape,
    /// Material.
    pub material: Material,
    /// Its yield strength and welded detail, for the sign-off ([`crate::stress`]).
    pub checks: SegmentChecks,
}

/// The flexible link's parameters (`<pipearm:flexible>` in the URDF).
#[derive(Debug, Clone, PartialEq)]
pub struct FlexibleLink {
    /// Link name.
    pub name: String,
    /// Segments from the hub outwards.
    pub segments: Vec<ArmSegment>,
    /// Finite elements along the arm.
    pub elements: usize,
    /// Modal damping ratio per clamped mode (the last repeats).
    pub damping_ratios: Vec<f64>,
    /// Inertia of the hub and drive train about the pivot, kg·m².
    pub hub_inertia_kg_m2: f64,
}

impl FlexibleLink {
    /// Arm length, m.
    pub fn length_m(&self) -> f64 {
        self.segments.iter().map(|s| s.length_m).sum()
    }

    /// Depth of the section at the tip in the lift plane, m (for geometry and contact offsets).
    pub fn depth_m(&self) -> f64 {
        self.segments.last().map_or(0.0, |s| section_extent(&s.section).1)
    }

    /// Width of the section at the tip across the lift plane, m.
    pub fn width_m(&self) -> f64 {
        self.segments.last().map_or(0.0, |s| section_extent(&s.section).0)
    }
}

/// (width, depth) of a section's bounding box, m.
pub fn section_extent(shape: &SectionShape) -> (f64, f64) {
    match *shape {
        SectionShape::SolidCircle { diameter_m } => (diameter_m, diameter_m),
        SectionShape::SolidRectangle { width_m, depth_m } => (width_m, depth_m),
        SectionShape::HollowRectangle { width_m, depth_m, .. } => (width_m, depth_m),
        SectionShape::Tube { outer_diameter_m, .. } => (outer_diameter_m, outer_diameter_m),
    }
}

/// A collision / visual primitive in the arm frame (x along the arm, y across it in the lift
/// plane, z normal to the plane), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Box with half extents.
    Box { half_extents_m: [f64; 3] },
    /// Cylinder along its local z.
    Cylinder { radius_m: f64, half_length_m: f64 },
    /// Sphere.
    Sphere { radius_m: f64 },
}

/// A primitive placed in a frame: position (m) and roll-pitch-yaw (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedShape {
    /// Position of the primitive's centre, m.
    pub position_m: [f64; 3],
    /// Roll, pitch, yaw, rad.
    pub rpy_rad: [f64; 3],
    /// The primitive.
    pub shape: Shape,
}

/// How a carried link hangs on the arm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mount {
    /// Welded or bolted.
    Fixed,
    /// On a prismatic joint (the gripper's jaws), at its zero position.
    Prismatic {
        /// Unit axis in the arm frame along which the joint moves (closes), m/m.
        axis: [f64; 3],
        /// Force the joint's actuator can give, N (the URDF limit's effort).
        effort_n: f64,
        /// Travel allowed from where the jaw first touches the string, [lower, upper] along the
        /// axis, m (the URDF limit's lower and upper).
        travel_m: [f64; 2],
    },
}

impl Mount {
    /// True for a prismatic mount.
    pub fn is_prismatic(&self) -> bool {
        matches!(self, Mount::Prismatic { .. })
    }
}

/// A rigid link carried by the arm.
#[derive(Debug, Clone, PartialEq)]
pub struct CarriedBody {
    /// Link name.
    pub name: String,
    /// How it is mounted.
    pub mount: Mount,
    /// Arm station of its centre of mass, m.
    pub station_m: f64,
    /// Offset of its centre of mass across the arm, in the lift plane, m.
    pub lateral_m: f64,
    /// Offset of its centre of mass normal to the lift plane, m.
    pub normal_offset_m: f64,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Inertia about its centre of mass, normal to the lift plane, kg·m².
    pub rotary_inertia_kg_m2: f64,
    /// Collision shapes in the arm frame.
    pub shapes: Vec<PlacedShape>,
    /// Whether it hangs below the tilting head's hinge (and turns with it); its station and
    /// shapes are then given at the hinge's rest pose.
    pub tilts: bool,
}

/// The lift joint.
#[derive(Debug, Clone, PartialEq)]
pub struct LiftJoint {
    /// Joint name.
    pub name: String,
    /// Pivot position in the world, m.
    pub pivot_m: [f64; 3],
    /// Lower and upper limits, rad.
    pub limits_rad: (f64, f64),
    /// Torque the drive can give, N·m (the URDF limit's effort): a run whose peak drive torque
    /// exceeds it is flagged in its summary.
    pub effort_n_m: f64,
    /// Fastest rate the drive can turn the joint, rad/s (the URDF limit's velocity): a scenario
    /// whose drive is faster is refused.
    pub velocity_rad_s: f64,
    /// The hydraulic cylinders that can turn it (the `<pipearm:cylinder>` elements on the joint).
    pub cylinders: Option<crate::actuator::Cylinders>,
    /// The servo motor and gearbox that can turn it (`<pipearm:servo>` on the joint).
    pub servo: Option<crate::actuator::ServoMachine>,
}

/// How errors and drawings name cylinder `k` (from 0) of the `count` on joint `joint`:
/// `joint[<joint>].pipearm:cylinder`, or `…pipearm:cylinder[<k + 1>]` among several.
pub fn cylinder_element(joint: &str, k: usize, count: usize) -> String {
    match count {
        1 => format!("joint[{joint}].pipearm:cylinder"),
        _ => format!("joint[{joint}].pipearm:cylinder[{}]", k + 1),
    }
}

/// A robot read from URDF.
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    /// Robot name.
    pub name: String,
    /// The file it came from.
    pub source: PathBuf,
    /// The lift joint.
    pub lift: LiftJoint,
    /// The flexible arm.
    pub arm: FlexibleLink,
    /// Rigid links carried by the arm.
    pub carried: Vec<CarriedBody>,
    /// The tilting head, where a spring hinge carries links.
    pub head: Option<TiltingHead>,
    /// Shapes of the base (world-fixed), in the world frame.
    pub base_shapes: Vec<PlacedShape>,
}

impl Robot {
    /// The beam description of the arm with its carried bodies, plus `extra` masses (payload).
    /// A tilting head's whole mass sits at its hinge's station: the arm carries it there, and
    /// what turns about the hinge is the head's own coordinate ([`crate::arm::HeadModel`]).
    pub fn beam_spec(&self, extra: &[ConcentratedMass]) -> Result<BeamSpec, BeamError> {
        let segments = self
            .arm
            .segments
            .iter()
            .map(|s| Segment::from_shape(s.length_m, &s.section, &s.material))
            .collect::<Result<Vec<_>, _>>()?;
        let masses = self
            .carried
            .iter()
            .filter(|b| b.mass_kg > 0.0 && !b.tilts)
            .map(|b| ConcentratedMass {
                name: b.name.clone(),
                position_m: b.station_m,
                mass_kg: b.mass_kg,
                rotary_inertia_kg_m2: b.rotary_inertia_kg_m2,
            })
            .chain(self.head.iter().filter(|h| h.mass_kg > 0.0).map(|h| ConcentratedMass {
                name: h.joint.clone(),
                position_m: h.hinge_station_m,
                mass_kg: h.mass_kg,
                rotary_inertia_kg_m2: 0.0,
            }))
            .chain(extra.iter().cloned())
            .collect();
        let spec = BeamSpec { segments, masses, elements: self.arm.elements, member: None };
        spec.validate()?;
        Ok(spec)
    }

    /// The carried body with this name.
    pub fn body(&self, name: &str) -> Option<&CarriedBody> {
        self.carried.iter().find(|b| b.name == name)
    }

    /// Where a string gripped by `palm` runs, off the arm's axis, m: [across the arm in the lift
    /// plane (body y), normal to the plane (body z)]; midway between the jaws (the carried bodies
    /// on prismatic joints), else through the palm's centre of mass.
    pub fn string_axis_offset_m(&self, palm: &CarriedBody) -> [f64; 2] {
        let jaws: Vec<&CarriedBody> = self.carried.iter().filter(|b| b.mount.is_prismatic()).collect();
        if jaws.is_empty() {
            return [palm.lateral_m, palm.normal_offset_m];
        }
        let mean = |f: fn(&CarriedBody) -> f64| jaws.iter().map(|j| f(j)).sum::<f64>() / jaws.len() as f64;
        [mean(|b| b.lateral_m), mean(|b| b.normal_offset_m)]
    }
}

/// How a segment's yield strength was given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum YieldSource {
    /// `yield_strength_pa` on the segment.
    Given,
    /// `steel` on the segment: a grade, read off its table at the section's thickness.
    Grade(&'static crate::steel::SteelGrade),
}

/// A segment's yield strength and where it comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YieldStrength {
    /// Minimum yield strength, Pa.
    pub strength_pa: f64,
    /// Its source.
    pub source: YieldSource,
}

impl YieldStrength {
    /// How a summary states it: `yield_strength_pa` or `S355 (EN 10025-2, t = 12.5 mm)`.
    pub fn describe(&self, thickness_m: f64) -> String {
        match self.source {
            YieldSource::Given => "yield_strength_pa".into(),
            YieldSource::Grade(g) => format!("{} ({}, t = {} mm)", g.name, g.standard, thickness_m * 1e3),
        }
    }
}

/// What a segment is checked against: its yield strength and its welded detail's S–N curve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SegmentChecks {
    /// Yield strength (`None`: no utilisation for this segment).
    pub yield_strength: Option<YieldStrength>,
    /// S–N curve of its worst detail (`None`: no fatigue for this segment).
    pub sn_curve: Option<SnCurve>,
}
