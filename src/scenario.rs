//! Scenario files (TOML): robot, payload, drive, dampeners, model, integrator, time and outputs.
//! Every key is checked: unknown keys, missing keys and out-of-range values fail with the file,
//! the key and what is allowed, before anything runs or is written.
//!
//! Units are SI and stated in the key names; drive angles are in degrees (`*_deg`, `*_deg_s2`)
//! because that is how rig engineers state them, and are converted to radians here. Paths
//! (`robot`, a table drive's `file`) are relative to the scenario file.

mod actuator;
mod capacity;
mod checks;
mod clamp;
mod compile;
mod drive;
mod grips;
mod loop_advice;
mod sensors;
pub mod spelling;
mod strikes;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::arm::Fidelity;
use crate::beam::{BeamModel, ConcentratedMass};
use crate::compile::Compiler;
use crate::integrate::IntegratorKind;
use crate::model::{
    Clamp, ContactOptions, Drive, FrictionClamp, HeldString, Model, Payload, PhysicsOptions, TimeOptions,
};
use crate::robot::{PipeString, Robot, RobotError, StringSpec, load_robot};
use crate::scene::SceneError;
use crate::sensor::{SensorKind, SensorSpec};

pub use actuator::ActuatorSpec;
pub use checks::ChecksSpec;
pub use drive::{DriveSpec, HeadSpec, PerMode, ShaperRequest};
pub use strikes::{DampenerSpec, ShapeSpec, StructureSpec};

/// A scenario file as written, and as a TOML document with its old spellings rewritten to the
/// current ones, with the rewrites made.
struct ReadFile {
    text: String,
    document: toml::Table,
    deprecations: Vec<spelling::Deprecation>,
}

impl ReadFile {
    fn read(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Io { path: path.into(), source })?;
        let mut document: toml::Table = text.parse().map_err(|e| parse_error(path, e))?;
        let deprecations = spelling::modernize(&mut document);
        Ok(ReadFile { text, document, deprecations })
    }
}

fn parse_error(path: &Path, e: toml::de::Error) -> ScenarioError {
    ScenarioError::Parse { path: path.into(), message: drive::parse_hint(e.to_string()) }
}

/// A scenario file as a TOML document, its old spellings rewritten to the current ones.
pub fn read_document(path: &Path) -> Result<toml::Table, ScenarioError> {
    ReadFile::read(path).map(|file| file.document)
}

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
    /// Compiling it for its runs ([`Scenario::compile`]): its shaper's tuning or its arm.
    #[error("{path}: {error}")]
    Compile { path: PathBuf, error: SceneError },
    /// In the robot the scenario names.
    #[error("{path}: robot: {error}")]
    Robot { path: PathBuf, error: RobotError },
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
    /// The hub motion: the reference the actuator tracks.
    pub drive: DriveSpec,
    /// What tracks the drive's profile (default: ideal, the hub follows it exactly). Left out of
    /// the canonical form when ideal, so that a sweep's case hashes do not change for scenarios
    /// without it.
    #[serde(default, skip_serializing_if = "ActuatorSpec::is_ideal")]
    pub actuator: ActuatorSpec,
    /// Rubber dampeners.
    #[serde(default)]
    pub dampeners: Vec<DampenerSpec>,
    /// Fixed rig structure the arm and the string can strike.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub structures: Vec<StructureSpec>,
    /// How contact forces are computed.
    #[serde(default)]
    pub contact: ContactOptions,
    /// Overrides of the robot's arm (default: the URDF's). Left out of the canonical form when
    /// empty, so that a sweep's case hashes do not change for scenarios without it.
    #[serde(default, skip_serializing_if = "ArmOverrides::is_empty")]
    pub arm: ArmOverrides,
    /// Model fidelity (default `auto`: the cheapest the scene needs, [`crate::select`]).
    #[serde(default)]
    pub model: ModelSpec,
    /// Physical options (stiffening, gravity).
    #[serde(default)]
    pub physics: PhysicsOptions,
    /// Time integrator (default generalized-α, ρ∞ = 0.8).
    #[serde(default)]
    pub integrator: IntegratorKind,
    /// Time step and span.
    pub time: TimeOptions,
    /// Sensors read at every step.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorSpec>,
    /// A driven tilting head's drive (`docs/model-head.md`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head: Option<HeadSpec>,
    /// The sign-off's settings (`docs/sign-off.md`); its presence asks for utilisation. Left out
    /// of the canonical form when absent, so that a sweep's case hashes do not change for
    /// scenarios without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub checks: Option<ChecksSpec>,
}

/// What a scenario may change of the robot's arm.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmOverrides {
    /// Modal damping ratio ζ per clamped mode, lowest first (the last applies to every higher
    /// mode); replaces the URDF's `damping_ratios`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratios: Option<Vec<f64>>,
}

impl ArmOverrides {
    /// Whether it overrides nothing.
    pub fn is_empty(&self) -> bool {
        self.damping_ratios.is_none()
    }
}

/// The model a scenario asks for (of the arm in `[model]`, of a string in `payload.model`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ModelSpec {
    /// The cheapest fidelity the scene needs, within `tolerance` (relative; the arm's only,
    /// default [`crate::model::DEFAULT_MODEL_TOLERANCE`]).
    Auto {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        tolerance: Option<f64>,
    },
    /// Rigid arm.
    Rigid,
    /// The first `modes` clamped modes.
    Modal { modes: usize },
    /// Every FE DOF.
    Fe,
}

impl Default for ModelSpec {
    fn default() -> Self {
        ModelSpec::Auto { tolerance: None }
    }
}

/// A fidelity set by hand (a command line's `--model`) as the file would give it.
impl From<Fidelity> for ModelSpec {
    fn from(fidelity: Fidelity) -> Self {
        match fidelity {
            Fidelity::Rigid => ModelSpec::Rigid,
            Fidelity::Modal { modes } => ModelSpec::Modal { modes },
            Fidelity::Fe => ModelSpec::Fe,
        }
    }
}

impl ModelSpec {
    /// Whether it leaves the choice to `auto` with the default budget.
    pub fn is_auto(&self) -> bool {
        *self == ModelSpec::default()
    }

    /// The fidelity it sets (`None` for `auto`).
    pub fn fidelity(self) -> Option<Fidelity> {
        match self {
            ModelSpec::Auto { .. } => None,
            ModelSpec::Rigid => Some(Fidelity::Rigid),
            ModelSpec::Modal { modes } => Some(Fidelity::Modal { modes }),
            ModelSpec::Fe => Some(Fidelity::Fe),
        }
    }
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
        string: Box<StringSpec>,
        /// One hand gripping the string at its middle (default `gripper`, when `grips` is not
        /// given).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        at: Option<String>,
        /// The hands that grip the string and where along it each grips.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        grips: Option<Vec<GripSpec>>,
        /// The string's fidelity (default `auto`: the cheapest the scene needs).
        #[serde(default, skip_serializing_if = "ModelSpec::is_auto")]
        model: ModelSpec,
        /// Damping ratio of the string's bending modes (default 0.01).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        damping_ratio: Option<f64>,
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

/// One hand's grip on the string, as a scenario states it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GripSpec {
    /// The carried body (URDF link) that grips.
    pub hand: String,
    /// Where it grips along the string from its end nearest the pivot, m (default: the string
    /// centred between its hands; give it for every grip or for none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_m: Option<f64>,
}

/// The one hand that grips a string when a scenario names none.
const DEFAULT_HAND: &str = "gripper";

fn default_friction() -> f64 {
    0.3
}

/// The seed's lab mass blocks, kg.
pub const LAB_BLOCKS_KG: [f64; 3] = [0.100, 0.206, 0.412];

/// A scenario file, checked and resolved: what it says, and the model of the machine and scene.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file it came from.
    pub path: PathBuf,
    /// What the file says.
    pub spec: ScenarioSpec,
    /// The machine and scene it describes, resolved and checked; a shaper tuned by default is
    /// tuned when it is compiled ([`Scenario::compile`]).
    pub model: Model,
    /// What its compile derives (the beam and its modes, the arm at its fidelity, the shaper's
    /// tuning arm) goes through this, kept for the next: one for all the scenarios of a sweep,
    /// design or fit.
    pub compiler: Arc<Compiler>,
}

impl Scenario {
    /// Reads, checks and resolves a scenario file and the robot it names: no eigenproblem and no
    /// simulation (those are its compile's, [`Scenario::compile`]).
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        Self::from_spec(path, Self::read_spec(path)?)
    }

    /// Reads a scenario file as written, before its checks (to edit it first), its old
    /// spellings read as the current ones ([`spelling`]).
    pub fn read_spec(path: &Path) -> Result<ScenarioSpec, ScenarioError> {
        let file = ReadFile::read(path)?;
        if file.deprecations.is_empty() {
            // From the text, so that an error shows the line it is on.
            toml::from_str(&file.text).map_err(|e| parse_error(path, e))
        } else {
            toml::Value::Table(file.document).try_into().map_err(|e| parse_error(path, e))
        }
    }

    /// The old spellings a scenario file uses, as [`spelling::Deprecation`]s to report.
    pub fn deprecations(path: &Path) -> Result<Vec<spelling::Deprecation>, ScenarioError> {
        ReadFile::read(path).map(|file| file.deprecations)
    }

    /// Checks and resolves a spec as if read from `path` (robot paths resolve against its folder).
    pub fn from_spec(path: &Path, spec: ScenarioSpec) -> Result<Self, ScenarioError> {
        let robot = Self::load_robot(path, &spec)?;
        Self::from_spec_and_robot(path, spec, robot)
    }

    /// The robot file `spec` names, as a spec read from `path` resolves it.
    pub fn robot_path(path: &Path, spec: &ScenarioSpec) -> PathBuf {
        path.parent().unwrap_or(Path::new(".")).join(&spec.robot)
    }

    /// The table file of a table drive read from `path`, resolved against its folder.
    pub fn table_path(path: &Path, file: &Path) -> PathBuf {
        path.parent().unwrap_or(Path::new(".")).join(file)
    }

    /// Reads and checks the robot `spec` names.
    pub fn load_robot(path: &Path, spec: &ScenarioSpec) -> Result<Robot, ScenarioError> {
        load_robot(&Self::robot_path(path, spec)).map_err(|error| ScenarioError::Robot { path: path.into(), error })
    }

    /// Checks and resolves a spec as if read from `path`, with its robot already read by
    /// [`Scenario::load_robot`] (a sweep reads each robot file once for all its cases).
    pub fn from_spec_and_robot(path: &Path, spec: ScenarioSpec, robot: Robot) -> Result<Self, ScenarioError> {
        Self::from_spec_and_robot_sharing(path, spec, robot, &Arc::new(Compiler::new()))
    }

    /// [`Scenario::from_spec_and_robot`], keeping `compiler` for its compile
    /// ([`Scenario::compile`]): the scenarios of a sweep share what their compiles derive.
    pub fn from_spec_and_robot_sharing(
        path: &Path,
        spec: ScenarioSpec,
        robot: Robot,
        compiler: &Arc<Compiler>,
    ) -> Result<Self, ScenarioError> {
        Self::resolve(Check { path, capacity: true }, spec, robot, compiler)
    }

    /// Reads, checks and resolves a scenario file as [`Scenario::load`] does, but for its payload
    /// against the machine's capacity ([`crate::capacity`]): to show what the machine lifts.
    pub fn load_beyond_capacity(path: &Path) -> Result<Self, ScenarioError> {
        let spec = Self::read_spec(path)?;
        let robot = Self::load_robot(path, &spec)?;
        Self::resolve(Check { path, capacity: false }, spec, robot, &Arc::new(Compiler::new()))
    }

    fn resolve(
        check: Check,
        spec: ScenarioSpec,
        mut robot: Robot,
        compiler: &Arc<Compiler>,
    ) -> Result<Self, ScenarioError> {
        let path = check.path;
        if let Some(ratios) = &spec.arm.damping_ratios {
            robot.arm.damping_ratios = check.damping_ratios(ratios)?;
        }
        let motion = check.drive(&spec.drive)?;
        check.head(spec.head.as_ref(), &mut robot)?;
        let actuator = check.actuator(&spec.actuator, &robot)?;
        let payload = check.payload(&spec.payload, &robot)?;
        if let Payload::StringOnHead(held) = &payload {
            check.head_without_structures(&spec.structures)?;
            robot.head = robot.head.take().map(|head| head.carrying(&held.lumped_mass()));
        }
        let dampeners: Result<Vec<_>, _> =
            spec.dampeners.iter().enumerate().map(|(i, d)| check.dampener(i, d, &robot, &spec)).collect();
        let sensors = check.sensors(&spec.sensors, &robot, &payload)?;
        let names: Vec<&str> = spec.dampeners.iter().map(|d| d.name.as_str()).collect();
        let structures = check.structures(&spec.structures, &names, &spec.contact)?;
        let checks = check.checks(spec.checks.as_ref(), &robot)?;
        let mut model = Model {
            name: spec.name.clone(),
            robot,
            payload,
            drive: Drive { motion, actuator, shaper_tuning: Vec::new(), untuned_shaper: None },
            dampeners: dampeners?,
            structures,
            contact: spec.contact,
            fidelity: spec.model.fidelity(),
            tolerance: check.tolerance(&spec.model, "model")?,
            physics: spec.physics,
            integrator: spec.integrator,
            time: spec.time,
            sensors,
            checks,
        };
        if let Some(request) = spec.drive.shaping() {
            match request.frequencies_hz {
                Some(given) => {
                    model.drive.motion = check.shaped(&spec.drive, (given, request.damping_ratios), &model)?;
                }
                None => model.drive.untuned_shaper = Some(request.shaper),
            }
        }
        check.model(&model)?;
        check.structures_clear(&model)?;
        Ok(Scenario { path: path.into(), spec, model, compiler: compiler.clone() })
    }
}

/// The checks of one scenario file: each error names the file, the key and what is allowed.
struct Check<'a> {
    path: &'a Path,
    /// Whether the payload is checked against the machine's capacity.
    capacity: bool,
}

impl Check<'_> {
    fn invalid(&self, key: &str, message: impl Into<String>) -> ScenarioError {
        ScenarioError::Invalid { path: self.path.into(), key: key.into(), message: message.into() }
    }

    /// The ranges serde cannot check, on the resolved model.
    fn model(&self, model: &Model) -> Result<(), ScenarioError> {
        let arm_m = model.robot.arm.length_m();
        let centre_on_arm = |held: &HeldString| (0.0..=arm_m).contains(&held.mass_centre_m());
        if let Some(held) = model.payload.string() {
            self.clamp(held, &model.robot)?;
            if held.model == Some(Fidelity::Rigid) && !centre_on_arm(held) {
                let message = format!(
                    "a lumped string is one mass on the arm, and this one's centre of mass lies {:.2} m from the \
                     pivot, off the arm (0 to {arm_m:.2} m): hold it nearer the pivot (its grips' `at_m`) or leave \
                     `model` out to hold it flexibly",
                    held.mass_centre_m()
                );
                return Err(self.invalid("payload.model", message));
            }
        }
        // The arm with a string lumped (cheap: no eigenproblem) where the lumped mass lies on the
        // arm; a flexible string's own beam is checked from its description (what `auto` builds
        // is the run's), its centre of mass may lie beyond the tip.
        let beam = model
            .beam_spec_with_string(None)
            .and_then(BeamModel::new)
            .or_else(|e| match model.payload.string() {
                Some(held) if !centre_on_arm(held) => BeamModel::new(model.robot.beam_spec(&[])?),
                _ => Err(e),
            })
            .map_err(|e| self.invalid("payload", e.to_string()))?;
        let member = match model.payload.string().filter(|held| held.model != Some(Fidelity::Rigid)) {
            Some(held) => {
                let spec = held.member_spec(Fidelity::Fe).map_err(|e| self.invalid("payload", e.to_string()))?;
                spec.validate(model.robot.arm.length_m()).map_err(|e| self.invalid("payload", e.to_string()))?;
                Some(spec)
            }
            None => None,
        };
        if let Some(Fidelity::Modal { modes }) = model.fidelity
            && !(1..=beam.arm_dofs()).contains(&modes)
        {
            return Err(self.invalid(
                "model.modes",
                format!("{modes} is outside 1 ..= {} (the FE DOFs of this arm)", beam.arm_dofs()),
            ));
        }
        if let Some(member) = &member {
            let clamps = &member.clamps_m;
            let straddles = |x: f64| clamps.iter().any(|&c| c <= x) && clamps.iter().any(|&c| c > x);
            let gauge = model.sensors.iter().position(|s| match s.kind {
                SensorKind::StrainGauge { station_m, .. } => straddles(station_m),
                _ => false,
            });
            if let Some(i) = gauge {
                return Err(self.invalid(
                    &format!("sensors[{i}].station_m"),
                    format!(
                        "a strain gauge between the hands of a flexible string (stations {clamps:?} m) needs the clamps' reactions: \
                         put it inboard of the first hand or outboard of the last, or make the string rigid (payload.model = {{ kind = \"rigid\" }})"
                    ),
                ));
            }
        }
        if let (Some(Fidelity::Modal { modes }), Some(member)) = (model.payload.string().and_then(|h| h.model), &member)
            && !(1..=member.own_dofs()).contains(&modes)
        {
            return Err(self.invalid(
                "payload.model.modes",
                format!("{modes} is outside 1 ..= {} (the FE DOFs of this string)", member.own_dofs()),
            ));
        }
        self.drive_limits(model)?;
        self.capacity(model)?;
        model.integrator.build().map_err(|e| self.invalid("integrator", e.to_string()))?;
        self.time(model)?;
        let g = model.physics.gravity_m_s2;
        if !(g.is_finite() && (0.0..=100.0).contains(&g)) {
            return Err(self.invalid("physics.gravity_m_s2", format!("{g} is outside 0 ..= 100")));
        }
        if !(model.contact.pad_mass_kg.is_finite() && model.contact.pad_mass_kg > 0.0) {
            return Err(self.invalid("contact.pad_mass_kg", format!("{} is outside > 0", model.contact.pad_mass_kg)));
        }
        self.actuator_in_scene(model)
    }

    fn damping_ratios(&self, ratios: &[f64]) -> Result<Vec<f64>, ScenarioError> {
        if ratios.is_empty() {
            return Err(self.invalid("arm.damping_ratios", "empty: allowed one or more ratios 0 <= ratio < 2"));
        }
        match ratios.iter().position(|z| !(0.0..2.0).contains(z)) {
            Some(i) => {
                Err(self
                    .invalid(&format!("arm.damping_ratios[{i}]"), format!("{} is outside 0 <= ratio < 2", ratios[i])))
            }
            None => Ok(ratios.to_vec()),
        }
    }

    fn time(&self, model: &Model) -> Result<(), ScenarioError> {
        let t = model.time;
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
        if t.free_step_s.is_some() && model.integrator.stability_limit_omega_dt().is_some() {
            return Err(self.invalid(
                "time.free_step_s",
                format!(
                    "needs an implicit integrator (generalized-alpha, hht, newmark with 2 beta >= gamma); {} estimates \
                     no local error",
                    model.integrator.name()
                ),
            ));
        }
        if !(t.settle_s.is_finite() && (0.0..=3600.0).contains(&t.settle_s)) {
            return Err(self.invalid("time.settle_s", format!("{} is outside 0 <= settle_s <= 3600", t.settle_s)));
        }
        Ok(())
    }

    fn payload(&self, spec: &PayloadSpec, robot: &Robot) -> Result<Payload, ScenarioError> {
        Ok(match spec {
            PayloadSpec::None => Payload::None,
            PayloadSpec::String { string, at, grips, clamp, friction_coefficient, squeeze_n, model, damping_ratio } => {
                let pipe = PipeString::from_spec(string).map_err(|e| match e {
                    RobotError::Invalid { key, message } => self.invalid(&key, message),
                    other => ScenarioError::Robot { path: self.path.into(), error: other },
                })?;
                let damping_ratio = damping_ratio.unwrap_or(crate::model::DEFAULT_STRING_DAMPING_RATIO);
                if !(damping_ratio.is_finite() && (0.0..2.0).contains(&damping_ratio)) {
                    return Err(
                        self.invalid("payload.damping_ratio", format!("{damping_ratio} is outside 0 <= ratio < 2"))
                    );
                }
                let held = HeldString {
                    grips: self.grips(at.as_deref(), grips.as_deref(), &pipe, robot)?,
                    pipe,
                    clamp: *clamp,
                    friction: FrictionClamp { friction_coefficient: *friction_coefficient, squeeze_n: *squeeze_n },
                    model: {
                        self.tolerance(model, "payload.model")?;
                        model.fidelity()
                    },
                    damping_ratio,
                };
                if self.string_on_head(&held, robot)? { Payload::StringOnHead(held) } else { Payload::String(held) }
            }
            PayloadSpec::Block { block } => {
                let mass_kg = *LAB_BLOCKS_KG
                    .get((*block as usize).wrapping_sub(1))
                    .ok_or_else(|| self.invalid("payload.block", format!("{block}: allowed 1, 2, 3")))?;
                // A cube of steel: side from its mass, inertia m a²/6.
                let side = (mass_kg / 7850.0).cbrt();
                Payload::Lumped(ConcentratedMass {
                    name: format!("block {block}"),
                    position_m: robot.arm.length_m(),
                    mass_kg,
                    rotary_inertia_kg_m2: mass_kg * side * side / 6.0,
                })
            }
        })
    }
}
