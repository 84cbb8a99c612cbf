//! Scenario files (TOML): robot, payload, drive, dampeners, model, integrator, time and outputs.
//! Every key is checked: unknown keys, missing keys and out-of-range values fail with the file,
//! the key and what is allowed, before anything runs or is written.
//!
//! Units are SI and stated in the key names; drive angles are in degrees (`*_deg`, `*_deg_s2`)
//! because that is how rig engineers state them, and are converted to radians here. Paths
//! (`robot`) are relative to the scenario file.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::arm::{ArmError, ArmModel, ArmOptions, Fidelity, HubDrive, STANDARD_GRAVITY_M_S2};
use crate::beam::{BeamModel, BeamSpec, ConcentratedMass};
use crate::contact::ForceLaw;
use crate::drive::{DriveError, MotionProfile, SCurveLimit, TrapezoidLimit};
use crate::integrate::IntegratorKind;
use crate::robot::{PipeString, Robot, RobotError, StringSpec, load_robot};

/// The scenario files in `dir` (`*.toml`, hidden ones left out), sorted.
pub fn scenario_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .filter(|p| !p.file_name().is_some_and(|n| n.to_string_lossy().starts_with('.')))
        .collect();
    files.sort();
    Ok(files)
}

/// Errors reading or checking a scenario; each names the file.
#[derive(Debug, Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// TOML syntax, an unknown key, a missing key or a wrong type.
    #[error("{path}: {message}")]
    Parse { path: PathBuf, message: String },
    /// A value outside its allowed range.
    #[error("{path}: key `{key}`: {message}")]
    Invalid { path: PathBuf, key: String, message: String },
    /// In the robot the scenario names.
    #[error("{path}: robot: {source}")]
    Robot { path: PathBuf, source: RobotError },
}

/// A scenario as written in its file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Name used in reports and output files.
    pub name: String,
    /// URDF of the robot, relative to the scenario file.
    pub robot: PathBuf,
    /// What the gripper holds.
    #[serde(default)]
    pub payload: PayloadSpec,
    /// The hub motion.
    pub drive: DriveSpec,
    /// Rubber dampeners.
    #[serde(default)]
    pub dampeners: Vec<DampenerSpec>,
    /// How contact forces are computed.
    #[serde(default)]
    pub contact: ContactSpec,
    /// Model fidelity (default `auto`: the cheapest the scene needs, [`crate::select`]).
    #[serde(default)]
    pub model: ModelSpec,
    /// Physical options (stiffening, gravity).
    #[serde(default)]
    pub physics: PhysicsSpec,
    /// Time integrator (default generalized-α, ρ∞ = 0.8).
    #[serde(default)]
    pub integrator: IntegratorKind,
    /// Time step and span.
    pub time: TimeSpec,
}

/// The model a scenario asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ModelSpec {
    /// The cheapest fidelity the scene needs.
    #[default]
    Auto,
    /// Rigid arm.
    Rigid,
    /// The first `modes` clamped modes.
    Modal { modes: usize },
    /// Every FE DOF.
    Fe,
}

/// The payload.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum PayloadSpec {
    /// Nothing in the gripper.
    #[default]
    None,
    /// A pipe string from the catalogue, held by the gripper.
    String {
        #[serde(flatten)]
        string: StringSpec,
        /// Carried body whose station the string is clamped at (default `gripper`).
        #[serde(default = "default_clamp_body")]
        at: String,
        /// How the jaws hold it (default `rigid`).
        #[serde(default)]
        clamp: Clamp,
        /// Coulomb friction between jaws and string (`friction` clamp; default 0.3, steel on
        /// steel, dry).
        #[serde(default = "default_friction")]
        friction_coefficient: f64,
        /// Squeeze of each jaw, N (`friction` clamp; default: the jaw joint's URDF effort).
        squeeze_n: Option<f64>,
    },
    /// One of the seed's lab blocks (1: 100 g, 2: 206 g, 3: 412 g) at the arm tip.
    Block { block: u8 },
}

fn default_clamp_body() -> String {
    "gripper".into()
}

fn default_friction() -> f64 {
    0.3
}

/// How the gripper holds a string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Clamp {
    /// Welded to the gripper: string and jaws are lumped into the arm's masses, their shapes
    /// follow the gripper.
    #[default]
    Rigid,
    /// Held by friction: the jaws close on force-limited prismatic motors and squeeze a dynamic
    /// string in rapier; it slips when its load exceeds μ times the squeeze of both jaws.
    Friction,
}

/// A friction clamp's parameters, resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionClamp {
    /// Coulomb coefficient.
    pub friction_coefficient: f64,
    /// Squeeze per jaw, N (`None`: the jaw joint's effort).
    pub squeeze_n: Option<f64>,
}

/// The seed's lab mass blocks, kg.
pub const LAB_BLOCKS_KG: [f64; 3] = [0.100, 0.206, 0.412];

/// Physical options of the arm model that belong to the scene, not the robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PhysicsSpec {
    /// Geometric stiffening from centrifugal and gravity axial load (default on).
    pub geometric_stiffening: bool,
    /// Gravity, m/s².
    pub gravity_m_s2: f64,
}

impl Default for PhysicsSpec {
    fn default() -> Self {
        PhysicsSpec { geometric_stiffening: true, gravity_m_s2: STANDARD_GRAVITY_M_S2 }
    }
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

/// A rubber pad placed against the arm at a stop.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampenerSpec {
    /// Name of the pad (the contact pair is reported as `arm–<name>`).
    pub name: String,
    /// Lift angle of the stop the pad is set against, deg.
    pub angle_deg: f64,
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

/// Contact response.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// `compliant` (the pad's force law, implicit in the arm step) or `rapier`.
    #[serde(default)]
    pub method: ContactMethod,
    /// Mass of the pad body for the `rapier` method, kg.
    #[serde(default = "default_pad_mass")]
    pub pad_mass_kg: f64,
}

fn default_pad_mass() -> f64 {
    1.0
}

impl Default for ContactSpec {
    fn default() -> Self {
        ContactSpec { method: ContactMethod::default(), pad_mass_kg: default_pad_mass() }
    }
}

/// How contact forces are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactMethod {
    /// The pad's force law, evaluated inside the implicit arm step from rapier's contact geometry.
    #[default]
    Compliant,
    /// rapier's constraint solver against a pad body on a linear spring joint; the contact
    /// impulse / dt is fed back to the arm.
    Rapier,
}

/// Hub motion profiles; angles in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "profile", rename_all = "kebab-case", deny_unknown_fields)]
pub enum DriveSpec {
    /// Constant rate from start to end.
    Uniform { start_deg: f64, end_deg: f64, duration_s: f64 },
    /// Accel-limited: give `accel_deg_s2` or `ramp_fraction` (accel phase / duration).
    Trapezoidal { start_deg: f64, end_deg: f64, duration_s: f64, accel_deg_s2: Option<f64>, ramp_fraction: Option<f64> },
    /// Jerk-limited 7 segments: give `accel_deg_s2` + `jerk_deg_s3`, or `ramp_fraction` +
    /// `jerk_fraction`.
    SCurve {
        start_deg: f64,
        end_deg: f64,
        duration_s: f64,
        accel_deg_s2: Option<f64>,
        jerk_deg_s3: Option<f64>,
        ramp_fraction: Option<f64>,
        jerk_fraction: Option<f64>,
    },
    /// Hold still at an angle.
    Hold { angle_deg: f64 },
}

/// Local error per controlled step allowed by default, m of tip displacement (docs/performance.md:
/// chosen from measured errors against the converged reference).
pub const DEFAULT_TOLERANCE_M: f64 = 1e-6;

/// Time step and span.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
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

/// A checked scenario with its robot loaded.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file it came from.
    pub path: PathBuf,
    /// What the file says.
    pub spec: ScenarioSpec,
    /// The robot it names.
    pub robot: Robot,
    /// The hub motion, rad.
    pub motion: MotionProfile,
}

impl Scenario {
    /// Reads and checks a scenario file and the robot it names.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Io { path: path.into(), source })?;
        let spec: ScenarioSpec =
            toml::from_str(&text).map_err(|e| ScenarioError::Parse { path: path.into(), message: e.to_string() })?;
        Self::from_spec(path, spec)
    }

    /// Checks a spec as if read from `path` (robot paths resolve against its folder).
    pub fn from_spec(path: &Path, spec: ScenarioSpec) -> Result<Self, ScenarioError> {
        let robot = Self::load_robot(path, &spec)?;
        Self::from_spec_and_robot(path, spec, robot)
    }

    /// The robot file `spec` names, as a spec read from `path` resolves it.
    pub fn robot_path(path: &Path, spec: &ScenarioSpec) -> PathBuf {
        path.parent().unwrap_or(Path::new(".")).join(&spec.robot)
    }

    /// Reads and checks the robot `spec` names.
    pub fn load_robot(path: &Path, spec: &ScenarioSpec) -> Result<Robot, ScenarioError> {
        load_robot(&Self::robot_path(path, spec)).map_err(|source| ScenarioError::Robot { path: path.into(), source })
    }

    /// Checks a spec as if read from `path`, with its robot already read by
    /// [`Scenario::load_robot`] (a sweep reads each robot file once for all its cases).
    pub fn from_spec_and_robot(path: &Path, spec: ScenarioSpec, robot: Robot) -> Result<Self, ScenarioError> {
        let motion = spec.drive.motion().map_err(|e| drive_error(path, e))?;
        let scenario = Scenario { path: path.into(), spec, robot, motion };
        scenario.validate()?;
        Ok(scenario)
    }

    fn invalid(&self, key: &str, message: impl Into<String>) -> ScenarioError {
        ScenarioError::Invalid { path: self.path.clone(), key: key.into(), message: message.into() }
    }

    /// Checks the ranges serde cannot, building each part once.
    fn validate(&self) -> Result<(), ScenarioError> {
        let spec = &self.spec;
        let beam =
            self.beam_spec().and_then(|b| BeamModel::new(b).map_err(|e| self.invalid("payload", e.to_string())))?;
        if let ModelSpec::Modal { modes } = spec.model
            && !(1..=beam.dofs()).contains(&modes)
        {
            return Err(self.invalid(
                "model.modes",
                format!("{modes} is outside 1 ..= {} (the FE DOFs of this arm)", beam.dofs()),
            ));
        }
        self.check_drive_limits()?;
        spec.integrator.build().map_err(|e| self.invalid("integrator", e.to_string()))?;
        let t = spec.time;
        if !(t.step_s.is_finite() && t.step_s > 0.0 && t.step_s <= 0.1) {
            return Err(self.invalid("time.step_s", format!("{} is outside 0 < step_s <= 0.1", t.step_s)));
        }
        if let Some(free) = t.free_step_s
            && !(free.is_finite() && free >= t.step_s && free <= 0.1)
        {
            return Err(self.invalid(
                "time.free_step_s",
                format!("{free} is outside step_s ({}) <= free_step_s <= 0.1", t.step_s),
            ));
        }
        if let Some(tol) = t.tolerance_m {
            if !(tol.is_finite() && tol > 0.0 && tol <= 1e-2) {
                return Err(self.invalid("time.tolerance_m", format!("{tol} is outside 0 < tolerance_m <= 0.01")));
            }
            if t.free_step_s.is_none() {
                return Err(self.invalid("time.tolerance_m", "controls free_step_s: set free_step_s (> step_s) too"));
            }
        }
        if t.free_step_s.is_some() && spec.integrator.stability_limit_omega_dt().is_some() {
            return Err(self.invalid(
                "time.free_step_s",
                format!(
                    "needs an implicit integrator (generalized-alpha, hht, newmark with 2 beta >= gamma); {} estimates \
                     no local error",
                    spec.integrator.name()
                ),
            ));
        }
        if !(t.settle_s.is_finite() && (0.0..=3600.0).contains(&t.settle_s)) {
            return Err(self.invalid("time.settle_s", format!("{} is outside 0 <= settle_s <= 3600", t.settle_s)));
        }
        let g = spec.physics.gravity_m_s2;
        if !(g.is_finite() && (0.0..=100.0).contains(&g)) {
            return Err(self.invalid("physics.gravity_m_s2", format!("{g} is outside 0 ..= 100")));
        }
        if !(spec.contact.pad_mass_kg.is_finite() && spec.contact.pad_mass_kg > 0.0) {
            return Err(self.invalid("contact.pad_mass_kg", format!("{} is outside > 0", spec.contact.pad_mass_kg)));
        }
        self.check_clamp()?;
        spec.dampeners.iter().enumerate().try_for_each(|(i, d)| self.check_dampener(i, d))
    }

    fn check_clamp(&self) -> Result<(), ScenarioError> {
        let Some(clamp) = self.friction_clamp() else { return Ok(()) };
        let mu = clamp.friction_coefficient;
        if !(mu.is_finite() && mu > 0.0 && mu <= 2.0) {
            return Err(self.invalid("payload.friction_coefficient", format!("{mu} is outside 0 < μ <= 2")));
        }
        if let Some(n) = clamp.squeeze_n
            && !(n.is_finite() && n > 0.0)
        {
            return Err(self.invalid("payload.squeeze_n", format!("{n} is outside > 0 N")));
        }
        let jaws = self.robot.carried.iter().filter(|b| b.mount.is_prismatic()).count();
        if jaws != 2 {
            return Err(self.invalid(
                "payload.clamp",
                format!(
                    "a friction clamp needs a gripper with two jaws on prismatic joints; {} has {jaws}",
                    self.robot.name
                ),
            ));
        }
        Ok(())
    }

    fn check_drive_limits(&self) -> Result<(), ScenarioError> {
        let (lo, hi) = self.robot.lift.limits_rad;
        for (key, angle) in [("drive.start_deg", self.motion.start_rad()), ("drive.end_deg", self.motion.end_rad())] {
            if !(lo - 1e-9..=hi + 1e-9).contains(&angle) {
                let allowed = format!(
                    "{:.3} is outside the lift joint's limits {:.3} ..= {:.3} deg",
                    angle.to_degrees(),
                    lo.to_degrees(),
                    hi.to_degrees()
                );
                return Err(self.invalid(key, allowed));
            }
        }
        Ok(())
    }

    fn check_dampener(&self, i: usize, d: &DampenerSpec) -> Result<(), ScenarioError> {
        let key = |k: &str| format!("dampeners[{i}].{k}");
        let length = self.robot.arm.length_m();
        if !(d.station_m.is_finite() && (0.0..=length).contains(&d.station_m)) {
            return Err(
                self.invalid(&key("station_m"), format!("{} is outside 0 ..= {length} (the arm length)", d.station_m))
            );
        }
        if !(d.angle_deg.is_finite() && (-180.0..=180.0).contains(&d.angle_deg)) {
            return Err(self.invalid(&key("angle_deg"), format!("{} is outside -180 ..= 180", d.angle_deg)));
        }
        if !(d.gap_m.is_finite() && (0.0..=1.0).contains(&d.gap_m)) {
            return Err(self.invalid(&key("gap_m"), format!("{} is outside 0 ..= 1", d.gap_m)));
        }
        for (name, v) in [("thickness_m", d.thickness_m), ("length_m", d.length_m), ("width_m", d.width_m)] {
            if !(v.is_finite() && v > 0.0 && v <= 5.0) {
                return Err(self.invalid(&key(name), format!("{v} is outside 0 < {name} <= 5")));
            }
        }
        d.law.validate().map_err(|(name, v, allowed)| {
            self.invalid(&key(&format!("law.{name}")), format!("{v} is outside {allowed}"))
        })
    }

    /// The payload as concentrated masses on the arm.
    pub fn payload_masses(&self) -> Result<Vec<ConcentratedMass>, ScenarioError> {
        Ok(match &self.spec.payload {
            PayloadSpec::None => Vec::new(),
            PayloadSpec::String { at, .. } => {
                let s = self.pipe_string()?.expect("a string payload");
                let body = self.robot.body(at).ok_or_else(|| {
                    let names: Vec<_> = self.robot.carried.iter().map(|b| b.name.as_str()).collect();
                    self.invalid("payload.at", format!("`{at}` is not a link on the arm: allowed {}", names.join(", ")))
                })?;
                vec![ConcentratedMass {
                    name: format!("string {}", s.pipe.size),
                    position_m: body.station_m,
                    mass_kg: s.mass_kg(),
                    rotary_inertia_kg_m2: s.transverse_inertia_kg_m2(),
                }]
            }
            PayloadSpec::Block { block } => {
                let mass_kg = *LAB_BLOCKS_KG
                    .get((*block as usize).wrapping_sub(1))
                    .ok_or_else(|| self.invalid("payload.block", format!("{block}: allowed 1, 2, 3")))?;
                // A cube of steel: side from its mass, inertia m a²/6.
                let side = (mass_kg / 7850.0).cbrt();
                vec![ConcentratedMass {
                    name: format!("block {block}"),
                    position_m: self.robot.arm.length_m(),
                    mass_kg,
                    rotary_inertia_kg_m2: mass_kg * side * side / 6.0,
                }]
            }
        })
    }

    /// The friction clamp, if the payload is a string held by one.
    pub fn friction_clamp(&self) -> Option<FrictionClamp> {
        match &self.spec.payload {
            PayloadSpec::String { clamp: Clamp::Friction, friction_coefficient, squeeze_n, .. } => {
                Some(FrictionClamp { friction_coefficient: *friction_coefficient, squeeze_n: *squeeze_n })
            }
            _ => None,
        }
    }

    /// The clamped pipe string, if the payload is one.
    pub fn pipe_string(&self) -> Result<Option<PipeString>, ScenarioError> {
        match &self.spec.payload {
            PayloadSpec::String { string, .. } => PipeString::from_spec(string)
                .map(Some)
                .map_err(|source| ScenarioError::Robot { path: self.path.clone(), source }),
            _ => Ok(None),
        }
    }

    /// The beam description: robot plus payload.
    pub fn beam_spec(&self) -> Result<BeamSpec, ScenarioError> {
        let payload = self.payload_masses()?;
        self.robot.beam_spec(&payload).map_err(|e| self.invalid("payload", e.to_string()))
    }

    /// Arm options: the robot's damping and hub, the scene's physics.
    pub fn arm_options(&self) -> ArmOptions {
        ArmOptions {
            damping_ratios: self.robot.arm.damping_ratios.clone(),
            geometric_stiffening: self.spec.physics.geometric_stiffening,
            gravity_m_s2: self.spec.physics.gravity_m_s2,
            hub_inertia_kg_m2: self.robot.arm.hub_inertia_kg_m2,
        }
    }

    /// The arm model at `fidelity`.
    pub fn arm_model(&self, fidelity: Fidelity) -> Result<ArmModel, ArmError> {
        let spec = self.beam_spec().map_err(|e| ArmError::InvalidParameter {
            name: "payload".into(),
            value: f64::NAN,
            allowed: e.to_string(),
        })?;
        ArmModel::new(BeamModel::new(spec)?, fidelity, self.arm_options())
    }

    /// The fidelity to run at: the scenario's, or the one `auto` chooses, with the reason.
    pub fn fidelity(&self) -> Result<crate::select::Choice, ScenarioError> {
        self.fidelity_by(|| crate::select::choose(self))
    }

    /// [`Self::fidelity`] with the scenario's beam and clamped modes already built.
    pub fn fidelity_for(
        &self,
        beam: &BeamModel,
        modes: &crate::beam::ModalBasis,
    ) -> Result<crate::select::Choice, ScenarioError> {
        self.fidelity_by(|| crate::select::choose_for(self, beam, modes))
    }

    fn fidelity_by(
        &self,
        auto: impl FnOnce() -> Result<crate::select::Choice, crate::beam::BeamError>,
    ) -> Result<crate::select::Choice, ScenarioError> {
        let fixed = |fidelity| Ok(crate::select::Choice { fidelity, reason: "set in the scenario".into() });
        match self.spec.model {
            ModelSpec::Auto => auto().map_err(|e| self.invalid("model", e.to_string())),
            ModelSpec::Rigid => fixed(Fidelity::Rigid),
            ModelSpec::Modal { modes } => fixed(Fidelity::Modal { modes }),
            ModelSpec::Fe => fixed(Fidelity::Fe),
        }
    }

    /// The hub drive.
    pub fn hub_drive(&self) -> HubDrive {
        HubDrive::Prescribed(self.motion.clone())
    }

    /// Time the drive ends, s.
    pub fn drive_end_s(&self) -> f64 {
        self.motion.duration_s()
    }

    /// Total simulated time: drive plus settling, s.
    pub fn duration_s(&self) -> f64 {
        self.drive_end_s() + self.spec.time.settle_s
    }
}

impl DriveSpec {
    /// The motion profile, in radians.
    pub fn motion(&self) -> Result<MotionProfile, DriveError> {
        let r = f64::to_radians;
        match *self {
            DriveSpec::Uniform { start_deg, end_deg, duration_s } => {
                MotionProfile::uniform(r(start_deg), r(end_deg), duration_s)
            }
            DriveSpec::Trapezoidal { start_deg, end_deg, duration_s, accel_deg_s2, ramp_fraction } => {
                let limit = match (accel_deg_s2, ramp_fraction) {
                    (Some(a), None) => TrapezoidLimit::AccelRadS2(r(a)),
                    (None, Some(f)) => TrapezoidLimit::RampFraction(f),
                    _ => return Err(either("accel_deg_s2 | ramp_fraction")),
                };
                MotionProfile::trapezoidal(r(start_deg), r(end_deg), duration_s, limit)
            }
            DriveSpec::SCurve {
                start_deg,
                end_deg,
                duration_s,
                accel_deg_s2,
                jerk_deg_s3,
                ramp_fraction,
                jerk_fraction,
            } => {
                let limit = match (accel_deg_s2, jerk_deg_s3, ramp_fraction, jerk_fraction) {
                    (Some(a), Some(j), None, None) => SCurveLimit::AccelJerk { accel_rad_s2: r(a), jerk_rad_s3: r(j) },
                    (None, None, Some(f), Some(jf)) => SCurveLimit::Fractions { ramp_fraction: f, jerk_fraction: jf },
                    _ => return Err(either("accel_deg_s2 + jerk_deg_s3 | ramp_fraction + jerk_fraction")),
                };
                MotionProfile::s_curve(r(start_deg), r(end_deg), duration_s, limit)
            }
            DriveSpec::Hold { angle_deg } => Ok(MotionProfile::hold(r(angle_deg))),
        }
    }
}

fn either(allowed: &str) -> DriveError {
    DriveError::InvalidParameter { name: "limit", value: f64::NAN, allowed: format!("exactly one of: {allowed}") }
}

/// Drive errors name radians; the file states degrees, so the key is given in the file's terms.
fn drive_error(path: &Path, e: DriveError) -> ScenarioError {
    let DriveError::InvalidParameter { name, .. } = &e;
    let key = name.replace("_rad", "_deg");
    let message = if key == *name { e.to_string() } else { format!("{e} (values in radians)") };
    ScenarioError::Invalid { path: path.into(), key: format!("drive.{key}"), message }
}
