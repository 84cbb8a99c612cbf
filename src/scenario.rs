//! Scenario files (TOML): the arm, its drive, the model fidelity, the integrator and the time
//! span. Every key is checked: unknown keys, missing keys and out-of-range values fail with the
//! file, the key and what is allowed.
//!
//! Units are SI and stated in the key names; drive angles are in degrees (`*_deg`, `*_deg_s2`)
//! because that is how rig engineers state them, and are converted to radians here.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::arm::{ArmError, ArmModel, ArmOptions, Fidelity, HubDrive};
use crate::beam::{BeamError, BeamModel, BeamSpec, ConcentratedMass, Material, SectionShape, Segment};
use crate::drive::{DriveError, MotionProfile, SCurveLimit, TrapezoidLimit};
use crate::integrate::IntegratorKind;

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
}

/// A scenario as written in its file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Name used in reports and output files.
    pub name: String,
    /// The arm.
    pub arm: ArmSpec,
    /// The hub motion.
    pub drive: DriveSpec,
    /// Model fidelity.
    pub model: Fidelity,
    /// Time integrator (default generalized-α, ρ∞ = 0.8).
    #[serde(default)]
    pub integrator: IntegratorKind,
    /// Time step and span.
    pub time: TimeSpec,
}

/// An arm: segments from the hub out, concentrated masses, mesh and physical options.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmSpec {
    /// Finite elements along the arm (the fe reference and the mesh the modes come from).
    pub elements: usize,
    /// Segments from the hub outwards.
    pub segments: Vec<SegmentSpec>,
    /// Hand, gripper, string and other lumped masses.
    #[serde(default)]
    pub masses: Vec<ConcentratedMass>,
    /// Damping, stiffening, gravity and hub inertia.
    #[serde(default)]
    pub options: ArmOptions,
}

/// A uniform length of arm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// Length, m.
    pub length_m: f64,
    /// Section shape and dimensions.
    pub section: SectionShape,
    /// Material.
    pub material: Material,
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

/// Time step and span.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Fixed step, s.
    pub step_s: f64,
    /// Time simulated after the drive ends, s.
    pub settle_s: f64,
}

impl Scenario {
    /// Reads and checks a scenario file.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Io { path: path.into(), source })?;
        let scenario: Scenario =
            toml::from_str(&text).map_err(|e| ScenarioError::Parse { path: path.into(), message: e.to_string() })?;
        scenario.validate(path)?;
        Ok(scenario)
    }

    /// Checks the ranges serde cannot: builds every part once.
    pub fn validate(&self, path: &Path) -> Result<(), ScenarioError> {
        let beam = self.beam_spec().and_then(BeamModel::new).map_err(|e| beam_error(path, e))?;
        if let Fidelity::Modal { modes } = self.model
            && !(1..=beam.dofs()).contains(&modes)
        {
            let allowed = format!("{modes} is outside 1 ..= {} (the FE DOFs of this arm)", beam.dofs());
            return Err(invalid(path, "model.modes", allowed));
        }
        self.motion().map_err(|e| drive_error(path, e))?;
        self.integrator.build().map_err(|e| invalid(path, "integrator", e.to_string()))?;
        let t = self.time;
        if !(t.step_s.is_finite() && t.step_s > 0.0 && t.step_s <= 1.0) {
            return Err(invalid(path, "time.step_s", format!("{} is outside 0 < step_s <= 1", t.step_s)));
        }
        if !(t.settle_s.is_finite() && t.settle_s >= 0.0) {
            return Err(invalid(path, "time.settle_s", format!("{} is outside settle_s >= 0", t.settle_s)));
        }
        Ok(())
    }

    /// The beam description.
    pub fn beam_spec(&self) -> Result<BeamSpec, BeamError> {
        let segments = self
            .arm
            .segments
            .iter()
            .map(|s| Segment::from_shape(s.length_m, &s.section, &s.material))
            .collect::<Result<Vec<_>, _>>()?;
        let spec = BeamSpec { segments, masses: self.arm.masses.clone(), elements: self.arm.elements };
        spec.validate()?;
        Ok(spec)
    }

    /// The arm model at the scenario's fidelity.
    pub fn arm_model(&self, fidelity: Fidelity) -> Result<ArmModel, ArmError> {
        ArmModel::new(BeamModel::new(self.beam_spec()?)?, fidelity, self.arm.options.clone())
    }

    /// The hub motion in radians.
    pub fn motion(&self) -> Result<MotionProfile, DriveError> {
        self.drive.motion()
    }

    /// The hub drive.
    pub fn hub_drive(&self) -> Result<HubDrive, DriveError> {
        Ok(HubDrive::Prescribed(self.motion()?))
    }

    /// Total simulated time: drive plus settling, s.
    pub fn duration_s(&self) -> f64 {
        self.motion().map_or(0.0, |m| m.duration_s()) + self.time.settle_s
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
                    _ => {
                        return Err(either("accel_deg_s2 + jerk_deg_s3 | ramp_fraction + jerk_fraction"));
                    }
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

fn invalid(path: &Path, key: &str, message: String) -> ScenarioError {
    ScenarioError::Invalid { path: path.into(), key: key.into(), message }
}

fn beam_error(path: &Path, e: BeamError) -> ScenarioError {
    match e {
        BeamError::InvalidParameter { ref name, .. } => invalid(path, &format!("arm.{name}"), e.to_string()),
        other => invalid(path, "arm", other.to_string()),
    }
}

/// Drive errors name radians; the file states degrees, so the key is given in the file's terms.
fn drive_error(path: &Path, e: DriveError) -> ScenarioError {
    let DriveError::InvalidParameter { name, .. } = &e;
    let key = name.replace("_rad", "_deg");
    let message = if key == *name { e.to_string() } else { format!("{e} (values in radians)") };
    invalid(path, &format!("drive.{key}"), message)
}
