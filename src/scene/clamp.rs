//! The friction clamp: two jaws on force-limited prismatic motors squeeze a dynamic string.
//!
//! Coupling by added-mass partitioning: the string and the jaws stay lumped in the arm model,
//! as if clamped rigidly, and rapier moves them as bodies of their own. What the arm is given
//! each step is only the difference: the string's acceleration along the arm relative to the
//! palm, `−m a_rel` at the gripper — zero while the string sticks, the load the jaws fail to
//! carry while it slips. (Across the arm the jaws hold the string by their normal force; the
//! rigid lump already carries that, and rapier's contact chatter there is noise, not load.) A staggered scheme that fed the whole
//! string force back a step late would be unstable once the string outweighed the arm's
//! effective mass at the gripper (the added-mass trap); this one only lags the slip.
//!
//! The clamp has a rapier world of its own (a kinematic palm, the jaws, the string): calling
//! `detect_collisions` on a world, as the `compliant` pads once did every step (they now query
//! parry directly), stops rapier 0.36 from moving that world's dynamic bodies in later steps.

use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView};
use super::source::{ContactSource, GripReading};
use crate::arm::{ArmContact, GeneralizedLoad};
use crate::model::HeldString;
use crate::robot::{CarriedBody, Mount, Robot, Shape};

/// Largest step of the clamp's world, s: the jaw–string contact is stiff, and at the arm's
/// 2 ms step rapier's friction lets a held string creep (17 mm over the default lift, measured).
const CLAMP_SUBSTEP_S: f64 = 2.5e-4;

/// Deepest a jaw may sink into a clamped string before the contact is meaningless, m (with the
/// clamp's stiff contact it sinks ≈ 0.1 mm; rapier's default soft contact let it reach the axis).
const MAX_JAW_SINKING_M: f64 = 5e-3;

/// A string held by friction, its jaws, and what they do to the arm.
pub struct FrictionGrip {
    world: PhysicsWorld,
    palm: RigidBodyHandle,
    /// Index of the scene's piece that carries the jaws.
    palm_piece: usize,
    /// Station of the gripper, m.
    pub station_m: f64,
    string: RigidBodyHandle,
    string_mass_kg: f64,
    initial_offset_m: f64,
    last_relative_velocity: Option<f64>,
    /// Slip of the string along the arm relative to the gripper, m (positive toward the tip).
    pub slip_m: f64,
    /// How deep the deepest jaw face has sunk into the string, m (its face's distance from the
    /// string's axis short of the radius; 0 or less while the jaws only touch it).
    pub jaw_sinking_m: f64,
    /// Force the clamp puts on the arm beyond the lumped rigid clamp, world (X, Y), N.
    pub correction_force_n: [f64; 2],
    /// Squeeze per jaw, N.
    pub squeeze_n: f64,
    /// Force of the scene's structures on the string (world X, Y), N: its component along the
    /// arm pushes the string in the jaws over the next step (across the arm the lump carries it).
    pub string_load_n: [f64; 2],
    /// Each jaw: its body, closing axis in the palm frame and half thickness along it (m).
    jaws: Vec<(RigidBodyHandle, Vector, f64)>,
    /// The string's outer radius, m.
    radius_m: f64,
    /// The string's length, m.
    length_m: f64,
}

/// Where a friction clamp sits on the arm: the piece that carries its jaws and the string's.
pub struct ClampPlacement<'a> {
    /// Index of the palm among the scene's pieces.
    pub palm_index: usize,
    /// The palm.
    pub palm: &'a ArmPiece,
    /// Its world pose now.
    pub palm_pose: Pose,
    /// The string, as it rides on the arm with a rigid clamp.
    pub string: &'a ArmPiece,
}

impl FrictionGrip {
    /// Builds a palm where `at` says, and the string and the robot's jaws on it.
    pub fn new(held: &HeldString, robot: &Robot, at: ClampPlacement, gravity_m_s2: f64, step_s: f64) -> Self {
        let (palm, palm_pose, string_piece) = (at.palm, at.palm_pose, at.string);
        let clamp = held.friction;
        let string = &held.pipe;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, -gravity_m_s2, 0.0);
        world.integration_parameters.dt = step_s;
        // rapier's contacts are soft (30 Hz by default): under the jaws' tens of kilonewtons on a
        // 12 kg jaw that lets a jaw sink ≈ F / (m ω²) = 0.1 m — through the string (measured:
        // the jaws met at its axis within 0.5 s). At 1 kHz the sinking is 0.1 mm.
        world.integration_parameters.contact_softness = SpringCoefficients::new(1000.0, 10.0);
        let palm_body = world.insert_body(RigidBodyBuilder::kinematic_position_based().pose(palm_pose));
        // The string's centre in the palm's frame, and its turn along the arm.
        let string_centre = Vector::new(
            string_piece.station_m - palm.station_m,
            string_piece.lateral_m - palm.lateral_m,
            string_piece.normal_offset_m - palm.normal_offset_m,
        );
        let string_pose = palm_pose * Pose::from_parts(string_centre, string_piece.local_rotation);
        let string_body = world.insert_body(RigidBodyBuilder::dynamic().pose(string_pose).can_sleep(false));
        let collider = ColliderBuilder::new(string_piece.shape.clone())
            .mass(string.mass_kg())
            .friction(clamp.friction_coefficient);
        world.insert_collider(collider, Some(string_body));
        let radius = 0.5 * string.pipe.outer_diameter_m;
        let mut squeeze_n = f64::INFINITY;
        let mut jaws = Vec::new();
        for jaw in robot.carried.iter().filter(|b| b.mount.is_prismatic()) {
            let Mount::Prismatic { axis, effort_n, travel_m } = jaw.mount else { continue };
            let n = clamp.squeeze_n.unwrap_or(effort_n);
            squeeze_n = squeeze_n.min(n);
            let closing = Vector::new(axis[0], axis[1], axis[2]);
            let at =
                JawPlacement { palm_body, palm_pose, palm_station_m: palm.station_m, string_centre, radius_m: radius };
            jaws.push(insert_jaw(&mut world, jaw, closing, (n, travel_m), &at, clamp.friction_coefficient));
        }
        let mut grip = FrictionGrip {
            world,
            palm: palm_body,
            palm_piece: at.palm_index,
            station_m: palm.station_m,
            string: string_body,
            string_mass_kg: string.mass_kg(),
            initial_offset_m: 0.0,
            last_relative_velocity: None,
            slip_m: 0.0,
            jaw_sinking_m: 0.0,
            correction_force_n: [0.0; 2],
            squeeze_n,
            string_load_n: [0.0; 2],
            jaws,
            radius_m: radius,
            length_m: string.length_m,
        };
        grip.initial_offset_m = grip.axial_offset();
        grip
    }

    /// The jaws' sinking into the string now ([`Self::jaw_sinking_m`]), m.
    fn measure_jaw_sinking_m(&self) -> f64 {
        let palm = *self.world.bodies[self.palm].position();
        let string = palm.inverse() * *self.world.bodies[self.string].position();
        self.jaws
            .iter()
            .map(|&(body, closing, half_thickness)| {
                let jaw = palm.inverse() * *self.world.bodies[body].position();
                let face_from_axis = (string.translation - jaw.translation).dot(closing).abs() - half_thickness;
                self.radius_m - face_from_axis
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// String position along the arm axis relative to the palm, m.
    fn axial_offset(&self) -> f64 {
        let palm = self.world.bodies[self.palm].position();
        let along = palm.rotation * Vector::X;
        (self.world.bodies[self.string].translation() - palm.translation).dot(along)
    }

    /// Moves the palm to `palm_pose` over `h_s`, steps the clamp's world in substeps, and
    /// measures the slip and the force to hand the arm next step.
    pub fn step(&mut self, palm_pose: Pose, h_s: f64) {
        let start = *self.world.bodies[self.palm].position();
        let along = palm_pose.rotation * Vector::X;
        let load = Vector::new(self.string_load_n[0], self.string_load_n[1], 0.0);
        if let Some(string) = self.world.bodies.get_mut(self.string) {
            string.reset_forces(false);
            string.add_force(along * along.dot(load), true);
        }
        let substeps = (h_s / CLAMP_SUBSTEP_S).ceil().max(1.0) as usize;
        self.world.integration_parameters.dt = h_s / substeps as f64;
        for k in 1..=substeps {
            let pose = start.lerp(&palm_pose, k as f64 / substeps as f64);
            if let Some(palm) = self.world.bodies.get_mut(self.palm) {
                palm.set_next_kinematic_position(pose);
            }
            self.world.step();
        }
        self.slip_m = self.axial_offset() - self.initial_offset_m;
        self.jaw_sinking_m = self.measure_jaw_sinking_m();
        let palm = self.world.bodies[self.palm].position();
        let along = palm.rotation * Vector::X;
        let relative = (self.world.bodies[self.string].linvel() - self.world.bodies[self.palm].linvel()).dot(along);
        if let Some(last) = self.last_relative_velocity {
            let force = along * (-self.string_mass_kg * (relative - last) / h_s);
            self.correction_force_n = [force.x, force.y];
        }
        self.last_relative_velocity = Some(relative);
    }
}

impl ContactSource for FrictionGrip {
    fn add_loads(&self, arm: &ArmView, load: &mut GeneralizedLoad) {
        load.add(&arm.arm.point_force(self.station_m, self.correction_force_n, arm.hub.angle_rad, arm.q));
    }

    fn advance(&mut self, arm: &ArmView, h_s: f64) {
        let palm_pose = arm.pose(&arm.pieces[self.palm_piece]);
        self.step(palm_pose, h_s);
    }

    fn measure(&mut self, _arm: &ArmView, _contacts: &[ArmContact]) {}

    fn allows_free_step(&self, _arm: &ArmView, _h_s: f64) -> bool {
        false
    }

    /// The slip not finite, the jaws sunk into the string, or the string out of the jaws.
    fn fault(&self) -> Option<String> {
        if !self.slip_m.is_finite() {
            Some("the string's slip is no longer finite".into())
        } else if self.jaw_sinking_m > MAX_JAW_SINKING_M {
            Some(format!("the clamp's jaws sank {:.1} mm into the string", 1e3 * self.jaw_sinking_m))
        } else if self.slip_m.abs() > self.length_m {
            Some(format!("the string slid {:.3} m in the jaws, out of its {:.2} m length", self.slip_m, self.length_m))
        } else {
            None
        }
    }

    fn divergence_advice(&self, step_s: f64) -> Option<String> {
        Some(format!(
            "the friction clamp held at every step and model measured (docs/accuracy.md); check its squeeze_n and \
             friction_coefficient against the string's weight, try step_s = {:.3e} s, or a rigid clamp",
            0.5 * step_s
        ))
    }

    fn grip(&self) -> Option<GripReading> {
        Some(GripReading { slip_m: self.slip_m, jaw_sinking_m: self.jaw_sinking_m, squeeze_n: self.squeeze_n })
    }

    fn take_string_load(&mut self, load_n: [f64; 2]) -> Option<f64> {
        self.string_load_n = load_n;
        Some(self.slip_m)
    }
}

/// Where a jaw goes: the palm, and the string's centre and radius in the palm's frame.
struct JawPlacement {
    palm_body: RigidBodyHandle,
    palm_pose: Pose,
    palm_station_m: f64,
    string_centre: Vector,
    radius_m: f64,
}

/// A jaw as a dynamic body on a prismatic joint to the palm, placed touching the string and
/// closing on it along `closing` with a motor limited to `squeeze_n`.
fn insert_jaw(
    world: &mut PhysicsWorld,
    jaw: &CarriedBody,
    closing: Vector,
    (squeeze_n, travel_m): (f64, [f64; 2]),
    at: &JawPlacement,
    friction: f64,
) -> (RigidBodyHandle, Vector, f64) {
    let half = match jaw.shapes.first().map(|s| s.shape) {
        Some(Shape::Box { half_extents_m }) => half_extents_m,
        _ => [0.05; 3],
    };
    // Half thickness of the jaw along its closing axis.
    let thickness = (closing.x * half[0]).abs() + (closing.y * half[1]).abs() + (closing.z * half[2]).abs();
    let centre = Vector::new(jaw.station_m - at.palm_station_m, 0.0, 0.0) + at.string_centre.with_x(0.0)
        - closing * (at.radius_m + thickness);
    let body = world
        .insert_body(RigidBodyBuilder::dynamic().pose(at.palm_pose * Pose::from_translation(centre)).can_sleep(false));
    let shape = ColliderBuilder::cuboid(half[0], half[1], half[2]).mass(jaw.mass_kg.max(1e-3)).friction(friction);
    world.insert_collider(shape, Some(body));
    let joint = PrismaticJointBuilder::new(closing)
        .local_anchor1(centre)
        .motor_model(MotorModel::ForceBased)
        .motor_velocity(0.05, 1e9)
        .motor_max_force(squeeze_n)
        // The URDF's travel, from the touching position: without it the two saturated motors'
        // equal and opposite forces leave jaws and string free to drift across the arm together.
        .limits(travel_m);
    world.insert_impulse_joint(at.palm_body, body, joint);
    (body, closing, thickness)
}
