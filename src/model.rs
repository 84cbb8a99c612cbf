//! The machine and its scene, resolved: what a scenario file says, checked once and turned into
//! the quantities the step loop needs (SI units, radians).
//!
//! Data flows one way: a scenario file ([`crate::scenario`]) is read, checked and resolved into a
//! [`Model`] (the file's model); a run compiles it once into a [`crate::run::CompiledModel`] (the
//! arm reduced to its fidelity, the choices, the channels) and steps a fresh scene from that;
//! [`crate::select`], [`crate::scene`], [`crate::run`] and [`crate::bench`] take the model, never
//! the file. A model may also be built or edited in code (the bench varies its step,
//! integrator and pad laws); it is then the caller's to keep within the ranges the scenario's
//! checks enforce.
//!
//! The drive is a reference motion and the actuator that tracks it ([`crate::actuator`]). The
//! string is a body of its own ([`HeldString`]): lumped at its centre (`rigid`), or a tube beam
//! clamped at its hands and reduced to its own modes (`modal`, `fe`).

use serde::{Deserialize, Serialize};

use crate::actuator::{Actuator, ActuatorPlant};
use crate::arm::{ArmError, ArmModel, ArmOptions, Fidelity, HubDrive, STANDARD_GRAVITY_M_S2};
use crate::beam::{BeamError, BeamModel, BeamSpec, ConcentratedMass, MemberPiece, MemberSpec, SectionShape, Segment};
use crate::contact::ForceLaw;
use crate::drive::{MotionProfile, Shaper};
use crate::integrate::IntegratorKind;
use crate::robot::{PipeString, Robot};

/// `auto`'s default error budget (`[model] tolerance`): 1 % on the headline quantities.
pub const DEFAULT_MODEL_TOLERANCE: f64 = 0.01;

/// A scene ready to simulate: the machine (robot, payload, drive), the dampeners it strikes, and
/// how to simulate it.
#[derive(Debug, Clone)]
pub struct Model {
    /// Name used in reports and output files.
    pub name: String,
    /// The robot: lift joint, flexible arm, carried bodies.
    pub robot: Robot,
    /// What the gripper holds.
    pub payload: Payload,
    /// What moves the hub.
    pub drive: Drive,
    /// Rubber dampeners at the stops.
    pub dampeners: Vec<Dampener>,
    /// Fixed rig structure the arm and the string can strike.
    pub structures: Vec<Structure>,
    /// How contact forces are computed.
    pub contact: ContactOptions,
    /// The arm's fidelity; `None`: the cheapest the scene needs ([`crate::select`]).
    pub fidelity: Option<Fidelity>,
    /// `auto`'s error budget on the scene's headline quantities, relative (`[model] tolerance`).
    pub tolerance: f64,
    /// Physical options of the scene.
    pub physics: PhysicsOptions,
    /// Time integrator of the arm.
    pub integrator: IntegratorKind,
    /// Time step and span.
    pub time: TimeOptions,
    /// Sensors read at every step ([`crate::sensor`]).
    pub sensors: Vec<crate::sensor::Sensor>,
    /// How the run's stresses are judged ([`crate::stress`]).
    pub checks: SignOffChecks,
}

/// How the run's stresses are judged: the scenario's `[checks]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SignOffChecks {
    /// Design factor on stress, applied to utilisation and to the fatigue ranges.
    pub stress_factor: f64,
}

impl Default for SignOffChecks {
    fn default() -> Self {
        SignOffChecks { stress_factor: 1.0 }
    }
}

impl Model {
    /// The beam description with a held string at `string` fidelity (`None`: as lumped masses,
    /// the only form other payloads take).
    pub fn beam_spec_with_string(&self, string: Option<Fidelity>) -> Result<BeamSpec, BeamError> {
        match (self.payload.string(), string) {
            (Some(held), Some(fidelity)) if fidelity != Fidelity::Rigid => {
                let mut spec = self.robot.beam_spec(&[])?;
                spec.member = Some(held.member_spec(fidelity)?);
                spec.validate()?;
                Ok(spec)
            }
            _ => self.robot.beam_spec(&self.payload.masses()),
        }
    }

    /// Arm options: the robot's damping and hub inertia, the scene's physics.
    pub fn arm_options(&self) -> ArmOptions {
        ArmOptions {
            damping_ratios: self.robot.arm.damping_ratios.clone(),
            geometric_stiffening: self.physics.geometric_stiffening,
            gravity_m_s2: self.physics.gravity_m_s2,
            hub_inertia_kg_m2: self.robot.arm.hub_inertia_kg_m2,
        }
    }

    /// The names of the scene's contact pairs' series, in the scene's order: each pad's (the arm
    /// strikes it), then each structure's for the arm and, with a held string, `string-<name>`.
    pub fn pair_series_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.dampeners.iter().map(|d| d.name.clone()).collect();
        for s in &self.structures {
            names.push(s.name.clone());
            if self.payload.string().is_some() {
                names.push(format!("string-{}", s.name));
            }
        }
        names
    }

    /// The arm model at `fidelity`.
    pub fn arm_model(&self, fidelity: Fidelity) -> Result<ArmModel, ArmError> {
        ArmModel::new(BeamModel::new(self.beam_spec()?)?, fidelity, self.arm_options())?
            .with_head(self.robot.head.as_ref())
    }

    /// How the arm's hub moves: prescribed by the profile under an ideal drive, else driven by
    /// the actuator tracking it.
    pub fn hub_drive(&self) -> HubDrive {
        match ActuatorPlant::new(self.drive.actuator.clone(), self.drive.motion.clone(), self.time.step_s) {
            Some(plant) => HubDrive::Actuated(Box::new(plant)),
            None => HubDrive::Prescribed(self.drive.motion.clone()),
        }
    }

    /// The hub drive held at rest at `angle_rad`: an actuator's reference replaced by a hold
    /// there (where a linear analysis looks at the arm and its drive); an ideal drive held there.
    pub fn hub_drive_held_at(&self, angle_rad: f64) -> HubDrive {
        let mut drive = self.hub_drive();
        match &mut drive {
            HubDrive::Actuated(plant) => plant.reference = MotionProfile::hold(angle_rad),
            other => *other = HubDrive::Prescribed(MotionProfile::hold(angle_rad)),
        }
        drive
    }

    /// Time the drive ends, s.
    pub fn drive_end_s(&self) -> f64 {
        self.drive.motion.duration_s()
    }

    /// Total simulated time: drive plus settling, s.
    pub fn duration_s(&self) -> f64 {
        self.drive_end_s() + self.time.settle_s
    }
}

/// What moves the hub: the reference motion and the actuator that tracks it.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// The hub's reference motion, rad.
    pub motion: MotionProfile,
    /// What tracks it ([`Actuator::Ideal`]: the hub follows it exactly).
    pub actuator: Actuator,
    /// The modes an input shaper on the motion was tuned to when they were found rather than
    /// given, with their shares of the residual ([`crate::tuning`]); empty otherwise.
    pub shaper_tuning: Vec<TunedMode>,
    /// An input shaper to tune to the arm's modes when the model is compiled
    /// ([`crate::tuning::tuned`]): `motion` is then the unshaped move, which the compiled model
    /// replaces by the shaped one (within the same duration).
    pub untuned_shaper: Option<Shaper>,
}

/// A mode a drive's input shaper was tuned to, found by [`crate::tuning`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TunedMode {
    /// Natural frequency |λ|/2π of the linearised arm's pole, Hz.
    pub frequency_hz: f64,
    /// Its damping ratio −Re λ/|λ|.
    pub damping_ratio: f64,
    /// Its largest share of an output's residual vibration after the unshaped move (0..1).
    pub residual_share: f64,
}

/// What the gripper holds.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Payload {
    /// Nothing.
    #[default]
    None,
    /// A lumped mass on the arm (the seed's lab blocks).
    Lumped(ConcentratedMass),
    /// A pipe string held by the gripper.
    String(HeldString),
    /// A pipe string held by hands on the tilting head: rigid with it, its mass and inertia the
    /// head's ([`crate::robot::TiltingHead::carrying`]), so the arm carries it at the hinge; it is
    /// drawn turning with the head, and nothing reads it as a string of its own (no string
    /// outputs, no string contact).
    StringOnHead(HeldString),
}

impl Payload {
    /// The payload as concentrated masses on the arm.
    pub fn masses(&self) -> Vec<ConcentratedMass> {
        match self {
            Payload::None => Vec::new(),
            Payload::Lumped(mass) => vec![mass.clone()],
            Payload::String(held) => vec![held.lumped_mass()],
            Payload::StringOnHead(_) => Vec::new(),
        }
    }

    /// Total mass, kg.
    pub fn mass_kg(&self) -> f64 {
        match self {
            Payload::None => 0.0,
            Payload::Lumped(mass) => mass.mass_kg,
            Payload::String(held) | Payload::StringOnHead(held) => held.pipe.mass_kg(),
        }
    }

    /// The held string, if the payload is one.
    pub fn string(&self) -> Option<&HeldString> {
        match self {
            Payload::String(held) => Some(held),
            _ => None,
        }
    }

    /// The held string, on the arm or on the tilting head, if the payload is one (for what is
    /// drawn: [`Self::string`] is the string as a body of its own).
    pub fn held_string(&self) -> Option<&HeldString> {
        match self {
            Payload::String(held) | Payload::StringOnHead(held) => Some(held),
            _ => None,
        }
    }

    /// The held string, mutable, if the payload is one.
    pub fn string_mut(&mut self) -> Option<&mut HeldString> {
        match self {
            Payload::String(held) => Some(held),
            _ => None,
        }
    }
}

/// A pipe string held by the arm's hands.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldString {
    /// The string, from the pipe catalogue.
    pub pipe: PipeString,
    /// Where each hand grips it, ascending along the arm (at least one).
    pub grips: Vec<Grip>,
    /// How the jaws hold it.
    pub clamp: Clamp,
    /// The jaws' friction, used when `clamp` is [`Clamp::Friction`].
    pub friction: FrictionClamp,
    /// Its fidelity (`None`: the cheapest the scene needs, [`crate::select::string_fidelity`]).
    pub model: Option<Fidelity>,
    /// Damping ratio of its bending modes (held in the hands).
    pub damping_ratio: f64,
}

/// Where one hand grips the string.
#[derive(Debug, Clone, PartialEq)]
pub struct Grip {
    /// The carried body (URDF link) that grips.
    pub hand: String,
    /// Its arm station, m.
    pub station_m: f64,
    /// Where it grips, measured along the string from its end nearest the pivot, m.
    pub at_m: f64,
}

/// Finite elements along a flexibly modelled string: a 12.5 m joint at 0.5 m per element, where
/// the overhangs' first three frequencies are within 0.1 % of their converged values.
pub const STRING_ELEMENTS: usize = 25;

/// Default damping ratio of a held string's bending modes: 1 %, a steel tube in clamps (the
/// arm's default, MSC ADAMS' for flexible bodies).
pub const DEFAULT_STRING_DAMPING_RATIO: f64 = 0.01;

impl HeldString {
    /// Arm station of the string's end nearest the pivot, m (it may lie behind the pivot).
    pub fn start_m(&self) -> f64 {
        self.grips[0].station_m - self.grips[0].at_m
    }

    /// Arm station of the string's centre, m.
    pub fn centre_m(&self) -> f64 {
        self.start_m() + 0.5 * self.pipe.length_m
    }

    /// Arm station of the string's centre of mass, m (its centre but for its connections).
    pub fn mass_centre_m(&self) -> f64 {
        self.start_m() + self.pipe.mass_centre_m()
    }

    /// The hand that carries the jaws and draws the string: the outermost grip's.
    pub fn palm(&self) -> &Grip {
        self.grips.last().expect("a held string has a grip")
    }

    /// The string as one rigid mass at its centre of mass (the `rigid` fidelity).
    pub fn lumped_mass(&self) -> ConcentratedMass {
        ConcentratedMass {
            name: format!("string {}", self.pipe.pipe.size),
            position_m: self.mass_centre_m(),
            mass_kg: self.pipe.mass_kg(),
            rotary_inertia_kg_m2: self.pipe.transverse_inertia_kg_m2(),
        }
    }

    /// The string as a beam clamped at its hands, at `fidelity` (`modal` keeps that many
    /// fixed-interface modes, `fe` every DOF).
    pub fn member_spec(&self, fidelity: Fidelity) -> Result<MemberSpec, BeamError> {
        let p = &self.pipe.pipe;
        let section = SectionShape::Tube { outer_diameter_m: p.outer_diameter_m, wall_m: p.wall_m };
        let steel = p.material();
        let mut segment = Segment::from_shape(self.pipe.length_m, &section, &steel)?;
        // The pipe's weight (a uniform string's nominal weight spreads its couplings over it),
        // not the plain tube's of its section.
        segment.mass_per_length_kg_m = p.mass_per_length_kg_m;
        let pieces = self
            .pipe
            .connections
            .iter()
            .map(|c| {
                let wall_m = 0.5 * (c.outer_diameter_m - c.bore_m);
                let shape = SectionShape::Tube { outer_diameter_m: c.outer_diameter_m, wall_m };
                let mut piece = Segment::from_shape(c.length_m(), &shape, &steel)?;
                piece.mass_per_length_kg_m = p.mass_per_length_kg_m + c.added_mass_kg / c.length_m();
                Ok(MemberPiece { from_m: c.from_m, segment: piece })
            })
            .collect::<Result<Vec<_>, BeamError>>()?;
        let elements = ((STRING_ELEMENTS as f64 * self.pipe.length_m / 12.5).round() as usize).max(4);
        Ok(MemberSpec {
            name: format!("string {}", p.size),
            start_m: self.start_m(),
            segment,
            clamps_m: self.grips.iter().map(|g| g.station_m).collect(),
            elements,
            kept_modes: match fidelity {
                Fidelity::Modal { modes } => Some(modes),
                _ => None,
            },
            damping_ratio: self.damping_ratio,
            pieces,
        })
    }

    /// Held by `hand` alone, at arm station `station_m`, gripping the string at its middle.
    pub fn in_one_hand(&mut self, hand: &str, station_m: f64) {
        self.grips = vec![Grip { hand: hand.into(), station_m, at_m: 0.5 * self.pipe.length_m }];
    }

    /// The friction clamp's parameters, if the string is held by one.
    pub fn friction_clamp(&self) -> Option<FrictionClamp> {
        (self.clamp == Clamp::Friction).then_some(self.friction)
    }
}

/// How the gripper holds a string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Clamp {
    /// Held fast by its hands: at its `model` fidelity the string rides on them, lumped into the
    /// arm's masses (`rigid`) or as a beam clamped at each hand (`modal`, `fe`).
    #[default]
    Rigid,
    /// Held by friction: the jaws close on force-limited prismatic motors and squeeze a dynamic
    /// string in rapier; it slips when its load exceeds μ times the squeeze of both jaws.
    Friction,
}

/// A friction clamp's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionClamp {
    /// Coulomb coefficient between jaws and string.
    pub friction_coefficient: f64,
    /// Squeeze per jaw, N (`None`: the jaw joint's URDF effort).
    pub squeeze_n: Option<f64>,
}

/// Which arm face touches a pad, named as seen with the arm horizontal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Face {
    /// The +y face: the side the arm moves toward as the lift angle grows.
    Upper,
    /// The −y face.
    Lower,
}

impl Face {
    /// +1 for the upper face, −1 for the lower: the sign of the face's body-frame y.
    pub fn sign(self) -> f64 {
        match self {
            Face::Upper => 1.0,
            Face::Lower => -1.0,
        }
    }
}

/// A rubber pad placed against the arm at a stop.
#[derive(Debug, Clone, PartialEq)]
pub struct Dampener {
    /// Its name (the contact pair is reported as `arm-<name>`).
    pub name: String,
    /// Lift angle of the stop the pad is set against, rad.
    pub angle_rad: f64,
    /// Arm station the pad's centre faces, m.
    pub station_m: f64,
    /// Arm face it touches.
    pub face: Face,
    /// Clearance between that face and the pad with the undeformed arm at the stop, m.
    pub gap_m: f64,
    /// Pad thickness (normal to the face), m.
    pub thickness_m: f64,
    /// Pad extent along the arm, m.
    pub length_m: f64,
    /// Pad extent across the lift plane, m.
    pub width_m: f64,
    /// Force law of the rubber.
    pub law: ForceLaw,
}

/// A fixed piece of rig structure placed in the world (the well-centre guide, the V-door ramp,
/// the catwalk): its shape, the force law of its face and its friction.
#[derive(Debug, Clone, PartialEq)]
pub struct Structure {
    /// Its name (contact pairs are reported as `arm-<name>` and `string-<name>`).
    pub name: String,
    /// Its shape, centred on `position_m`.
    pub shape: StructureShape,
    /// World position of its centre, m (the lift plane is z = the pivot's z).
    pub position_m: [f64; 3],
    /// Rotation about the world z axis, rad.
    pub angle_rad: f64,
    /// Force law of its face.
    pub law: ForceLaw,
    /// Coulomb friction coefficient of its face against steel.
    pub friction: f64,
}

/// A structure's shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StructureShape {
    /// A box of these half extents along its own x, y, z, m.
    Box { half_extents_m: [f64; 3] },
    /// A cylinder along world z (normal to the lift plane): radius and half length, m.
    Cylinder { radius_m: f64, half_length_m: f64 },
}

impl StructureShape {
    /// Radius of the sphere about its centre that holds it, m.
    pub fn bounding_radius_m(&self) -> f64 {
        match *self {
            StructureShape::Box { half_extents_m: [x, y, z] } => (x * x + y * y + z * z).sqrt(),
            StructureShape::Cylinder { radius_m, half_length_m } => radius_m.hypot(half_length_m),
        }
    }
}

/// How contact forces are computed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactOptions {
    /// `compliant` (the pad's force law, implicit in the arm step) or `rapier` (the key `kind`;
    /// `method` is its old spelling).
    #[serde(default, rename = "kind")]
    pub method: ContactMethod,
    /// Where the `compliant` method finds its contact points: `pipeline` (rapier's collision
    /// pipeline, every manifold point), `pad-face` (each pad's face against the arm's, no query)
    /// or `auto` (`pad-face` only where it matches the pipeline, docs/scene.md).
    #[serde(default, skip_serializing_if = "Detection::is_auto")]
    pub detection: Detection,
    /// Mass of the pad body for the `rapier` method, kg.
    #[serde(default = "default_pad_mass")]
    pub pad_mass_kg: f64,
}

fn default_pad_mass() -> f64 {
    1.0
}

impl Default for ContactOptions {
    fn default() -> Self {
        ContactOptions {
            method: ContactMethod::default(),
            detection: Detection::default(),
            pad_mass_kg: default_pad_mass(),
        }
    }
}

/// How contact forces are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactMethod {
    /// Each pair's force law, evaluated inside the implicit arm step on the contact points
    /// [`Detection`] finds.
    #[default]
    Compliant,
    /// Each pad a rapier body on its spring (a joint motor in rapier's solver): the spring's law
    /// in the arm step, the pad body's inertia handed to the arm one step late.
    Rapier,
}

impl ContactMethod {
    /// The method's name as a scenario writes it.
    pub fn name(self) -> &'static str {
        match self {
            ContactMethod::Compliant => "compliant",
            ContactMethod::Rapier => "rapier",
        }
    }
}

/// Where the `compliant` method finds its contact points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Detection {
    /// `pad-face` where it matches the pipeline (pads only, struck by the arm's own face), else
    /// `pipeline`.
    #[default]
    Auto,
    /// rapier's collision pipeline: broad phase, narrow phase, every manifold point.
    Pipeline,
    /// Each pad's face against the arm's face at its two ends, found without a collision query.
    PadFace,
}

impl Detection {
    /// Whether it is `auto` (left out of a scenario's canonical form, so that a sweep's case
    /// hashes do not change for scenarios without it).
    pub fn is_auto(&self) -> bool {
        *self == Detection::Auto
    }

    /// The name as a scenario writes it.
    pub fn name(self) -> &'static str {
        match self {
            Detection::Auto => "auto",
            Detection::Pipeline => "pipeline",
            Detection::PadFace => "pad-face",
        }
    }
}

/// Physical options of the arm model that belong to the scene, not the robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PhysicsOptions {
    /// Geometric stiffening from centrifugal and gravity axial load (default on).
    pub geometric_stiffening: bool,
    /// Gravity, m/s².
    pub gravity_m_s2: f64,
}

impl Default for PhysicsOptions {
    fn default() -> Self {
        PhysicsOptions { geometric_stiffening: true, gravity_m_s2: STANDARD_GRAVITY_M_S2 }
    }
}

/// Local error per controlled step allowed by default, m of tip displacement (chosen from the
/// errors measured against the converged reference, docs/performance.md).
pub const DEFAULT_TOLERANCE_M: f64 = 1e-6;

/// Time step and span.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeOptions {
    /// Step around contact (and everywhere without `free_step_s`), s.
    pub step_s: f64,
    /// Longest step while no pad is within reach of the arm, s (default: `step_s`, fixed steps).
    /// In free motion the step is then controlled by the implicit integrator's local error
    /// estimate (between `step_s` and this); the scene predicts the approach from each pad's
    /// clearance and the arm's speed and falls back to `step_s` before a contact can begin.
    /// `compliant` contact with a rigid clamp and an implicit integrator only (the `rapier` pad
    /// body and the friction clamp keep `step_s`; the explicit methods estimate no error).
    #[serde(default)]
    pub free_step_s: Option<f64>,
    /// Local error allowed per controlled step, as displacement of the arm's tip, m (default
    /// [`DEFAULT_TOLERANCE_M`]; used with `free_step_s`).
    #[serde(default)]
    pub tolerance_m: Option<f64>,
    /// Time simulated after the drive ends, s.
    pub settle_s: f64,
}
