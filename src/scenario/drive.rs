//! The `[drive]` table: the hub's motion as a scenario states it (degrees), its checks, and the
//! profile it resolves to — shaped, if it asks for an input shaper, tuned to the modes given or
//! to those the move leaves ringing ([`crate::tuning`]).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{Check, Scenario, ScenarioError};
use crate::drive::{DriveError, MotionLaw, MotionProfile, SCurveLimit, Shaper, ShaperMode, TableError, TrapezoidLimit};
use crate::model::Model;

/// A number for every mode, or one per mode: `shaper_hz = 5.1`, `shaper_hz = [2.85, 5.1]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged, expecting = "a number or a list of numbers")]
pub enum PerMode {
    /// One number.
    One(f64),
    /// One per mode.
    Many(Vec<f64>),
}

/// `drive.shaper_hz`, its key named if it is neither a number nor a list of them.
fn shaper_hz<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<PerMode>, D::Error> {
    PerMode::deserialize(d)
        .map(Some)
        .map_err(|_| serde::de::Error::custom("key `drive.shaper_hz`: allowed a number or a list of numbers (Hz)"))
}

/// `drive.shaper_damping_ratio`, as [`shaper_hz`].
fn shaper_damping_ratio<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<PerMode>, D::Error> {
    PerMode::deserialize(d).map(Some).map_err(|_| {
        serde::de::Error::custom("key `drive.shaper_damping_ratio`: allowed a number or a list of numbers")
    })
}

impl PerMode {
    /// The numbers given.
    pub fn values(&self) -> &[f64] {
        match self {
            PerMode::One(x) => std::slice::from_ref(x),
            PerMode::Many(v) => v,
        }
    }
}

/// A drive's `shaper` keys as written, each perhaps absent.
struct ShaperKeys<'a> {
    shaper: Option<Shaper>,
    frequencies_hz: Option<&'a [f64]>,
    damping_ratios: Option<&'a [f64]>,
}

/// What a drive's `shaper` keys ask for: the shaper, and the modes' frequencies (Hz) and damping
/// ratios if given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaperRequest<'a> {
    /// The shaper.
    pub shaper: Shaper,
    /// `shaper_hz`: the modes' natural frequencies, Hz.
    pub frequencies_hz: Option<&'a [f64]>,
    /// `shaper_damping_ratio`: one for every mode, or one per mode.
    pub damping_ratios: Option<&'a [f64]>,
}

/// Hub motion profiles; angles in degrees.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum DriveSpec {
    /// Constant rate from start to end.
    Uniform {
        start_deg: f64,
        end_deg: f64,
        duration_s: f64,
        /// Input shaper convolved with the move (docs/drive.md); left out of the canonical form
        /// when absent, so that a sweep's case hashes do not change.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper: Option<Shaper>,
        /// The natural frequencies the shaper cancels, Hz: one or a list (default: the modes the
        /// move leaves ringing, found when the scenario is compiled: [`crate::tuning::tuned`]).
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_hz")]
        shaper_hz: Option<PerMode>,
        /// Their damping ratios: one for all, or one per `shaper_hz` (default: the arm's first
        /// modal one; with automatic tuning, each mode's own).
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_damping_ratio")]
        shaper_damping_ratio: Option<PerMode>,
    },
    /// Accel-limited: give `accel_deg_s2` or `ramp_fraction` (accel phase / duration).
    Trapezoidal {
        start_deg: f64,
        end_deg: f64,
        duration_s: f64,
        accel_deg_s2: Option<f64>,
        ramp_fraction: Option<f64>,
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper: Option<Shaper>,
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_hz")]
        shaper_hz: Option<PerMode>,
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_damping_ratio")]
        shaper_damping_ratio: Option<PerMode>,
    },
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
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper: Option<Shaper>,
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_hz")]
        shaper_hz: Option<PerMode>,
        /// As the uniform drive's.
        #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "shaper_damping_ratio")]
        shaper_damping_ratio: Option<PerMode>,
    },
    /// Hold still at an angle.
    Hold { angle_deg: f64 },
    /// Through the rows of a CSV file of time and angle (header `t[s],angle[deg]`, relative to
    /// the scenario file): the clamped cubic spline, at rest at the first row, at
    /// `end_rate_deg_s` (default 0: at rest) at the last row and after it (docs/drive.md).
    Table { file: PathBuf, end_rate_deg_s: Option<f64> },
}

impl Check<'_> {
    /// The drive's profile; a table is read from its file, relative to the scenario.
    pub(super) fn drive(&self, drive: &DriveSpec) -> Result<MotionProfile, ScenarioError> {
        let (tunes_nothing, damps_unknown) = match drive.shaping_keys() {
            Some(k) => (
                k.shaper.is_none() && k.frequencies_hz.is_some(),
                k.frequencies_hz.is_none() && k.damping_ratios.is_some(),
            ),
            None => (false, false),
        };
        if tunes_nothing {
            return Err(self.invalid("drive.shaper_hz", "tunes an input shaper: set drive.shaper (zv, zvd or ei) too"));
        }
        if damps_unknown {
            return Err(self.invalid(
                "drive.shaper_damping_ratio",
                "needs drive.shaper_hz (the modes it damps); without it each mode found is tuned to its own damping",
            ));
        }
        match drive {
            DriveSpec::Table { file, end_rate_deg_s } => {
                let csv = Scenario::table_path(self.path, file);
                MotionProfile::from_csv(&csv, end_rate_deg_s.unwrap_or(0.0).to_radians()).map_err(|e| match e {
                    TableError::Drive { source, .. } => drive_error(self.path, source),
                    other => self.invalid("drive.file", other.to_string()),
                })
            }
            law => law.motion().map_err(|e| drive_error(self.path, e)),
        }
    }

    /// The drive's motion shaped to the modes `frequencies_hz` and `damping_ratios` give (from
    /// `shaper_hz` and `shaper_damping_ratio`; without them the shaper is tuned when the model is
    /// compiled, [`crate::tuning::tuned`]).
    pub(super) fn shaped(
        &self,
        drive: &DriveSpec,
        (frequencies_hz, damping_ratios): (&[f64], Option<&[f64]>),
        model: &Model,
    ) -> Result<MotionProfile, ScenarioError> {
        let modes = self.given_modes(frequencies_hz, damping_ratios, model)?;
        drive.shaped_motion(&modes).map_err(|e| drive_error(self.path, e))
    }

    /// The modes `shaper_hz` and `shaper_damping_ratio` give.
    fn given_modes(
        &self,
        frequencies_hz: &[f64],
        damping_ratios: Option<&[f64]>,
        model: &Model,
    ) -> Result<Vec<ShaperMode>, ScenarioError> {
        if frequencies_hz.is_empty() {
            return Err(self.invalid("drive.shaper_hz", "is empty: give a frequency or a list of them (Hz)"));
        }
        if let Some(f) = frequencies_hz.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
            return Err(self.invalid("drive.shaper_hz", format!("{f} is outside > 0 Hz (finite)")));
        }
        let first_modal = model.robot.arm.damping_ratios.first().copied().unwrap_or(0.0);
        let ratios: Vec<f64> = match damping_ratios {
            None => vec![first_modal; frequencies_hz.len()],
            Some([one]) => vec![*one; frequencies_hz.len()],
            Some(each) if each.len() == frequencies_hz.len() => each.to_vec(),
            Some(each) => {
                return Err(self.invalid(
                    "drive.shaper_damping_ratio",
                    format!(
                        "has {} values for {} frequencies in drive.shaper_hz: give one for all or one per frequency",
                        each.len(),
                        frequencies_hz.len()
                    ),
                ));
            }
        };
        if let Some(z) = ratios.iter().find(|z| !(0.0..1.0).contains(*z)) {
            return Err(self.invalid("drive.shaper_damping_ratio", format!("{z} is outside 0 <= ratio < 1")));
        }
        Ok(frequencies_hz
            .iter()
            .zip(ratios)
            .map(|(&frequency_hz, damping_ratio)| ShaperMode { frequency_hz, damping_ratio })
            .collect())
    }

    /// The drive against the lift joint's URDF limits: its angles within the joint's range over
    /// the run, its peak rate within the joint's velocity (known before the run, so refused;
    /// the torque is known only after it, and flagged in the run's summary).
    pub(super) fn drive_limits(&self, model: &Model) -> Result<(), ScenarioError> {
        let lift = &model.robot.lift;
        let (lo, hi) = lift.limits_rad;
        let deg = f64::to_degrees;
        let limits = format!("the lift joint's limits {:.3} ..= {:.3} deg", deg(lo), deg(hi));
        let outside = |angle: f64| !(lo - 1e-9..=hi + 1e-9).contains(&angle);
        let motion = &model.drive.motion;
        let table = motion.law() == MotionLaw::Table;
        if table {
            let (min, max) = motion.angle_range_rad(model.duration_s());
            if outside(min) || outside(max) {
                let span = format!("the table's spline spans {:.3} ..= {:.3} deg over the run", deg(min), deg(max));
                return Err(self.invalid("drive.file", format!("{span}: allowed within {limits}")));
            }
        }
        for (key, angle) in [("drive.start_deg", motion.start_rad()), ("drive.end_deg", motion.end_rad())] {
            if !table && outside(angle) {
                return Err(self.invalid(key, format!("{:.3} is outside {limits}", deg(angle))));
            }
        }
        let (rate, velocity) = (motion.peak_rate_rad_s(), lift.velocity_rad_s);
        if rate > velocity * (1.0 + 1e-9) {
            let (key, remedy) =
                if table { ("drive.file", "a slower table") } else { ("drive.duration_s", "a longer move") };
            return Err(self.invalid(
                key,
                format!(
                    "the drive's peak rate {:.3} deg/s exceeds the velocity limit of the lift joint `{}` \
                     ({:.3} deg/s = {velocity} rad/s in {}): allowed a peak rate up to that ({remedy})",
                    deg(rate),
                    lift.name,
                    deg(velocity),
                    model.robot.source.display()
                ),
            ));
        }
        Ok(())
    }
}

impl DriveSpec {
    /// The input shaper a uniform, trapezoidal or s-curve drive asks for, with its tuning if
    /// given.
    pub fn shaping(&self) -> Option<ShaperRequest<'_>> {
        let keys = self.shaping_keys()?;
        Some(ShaperRequest {
            shaper: keys.shaper?,
            frequencies_hz: keys.frequencies_hz,
            damping_ratios: keys.damping_ratios,
        })
    }

    /// The `shaper`, `shaper_hz` and `shaper_damping_ratio` of a drive that takes them.
    fn shaping_keys(&self) -> Option<ShaperKeys<'_>> {
        match self {
            DriveSpec::Uniform { shaper, shaper_hz, shaper_damping_ratio, .. }
            | DriveSpec::Trapezoidal { shaper, shaper_hz, shaper_damping_ratio, .. }
            | DriveSpec::SCurve { shaper, shaper_hz, shaper_damping_ratio, .. } => Some(ShaperKeys {
                shaper: *shaper,
                frequencies_hz: shaper_hz.as_ref().map(PerMode::values),
                damping_ratios: shaper_damping_ratio.as_ref().map(PerMode::values),
            }),
            DriveSpec::Hold { .. } | DriveSpec::Table { .. } => None,
        }
    }

    /// The motion profile of a built-in law, in radians, unshaped: a drive's `shaper` is applied
    /// by [`Self::shaped_motion`] where its modes are given, and when the scenario is compiled
    /// where they are found from the arm's ([`crate::tuning::tuned`]). A
    /// table is read relative to its scenario file ([`Scenario::load`],
    /// [`MotionProfile::from_csv`]); here it is an error.
    pub fn motion(&self) -> Result<MotionProfile, DriveError> {
        let r = f64::to_radians;
        match *self {
            DriveSpec::Uniform { start_deg, end_deg, duration_s, .. } => {
                MotionProfile::uniform(r(start_deg), r(end_deg), duration_s)
            }
            DriveSpec::Trapezoidal { start_deg, end_deg, duration_s, accel_deg_s2, ramp_fraction, .. } => {
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
                ..
            } => {
                let limit = match (accel_deg_s2, jerk_deg_s3, ramp_fraction, jerk_fraction) {
                    (Some(a), Some(j), None, None) => SCurveLimit::AccelJerk { accel_rad_s2: r(a), jerk_rad_s3: r(j) },
                    (None, None, Some(f), Some(jf)) => SCurveLimit::Fractions { ramp_fraction: f, jerk_fraction: jf },
                    _ => return Err(either("accel_deg_s2 + jerk_deg_s3 | ramp_fraction + jerk_fraction")),
                };
                MotionProfile::s_curve(r(start_deg), r(end_deg), duration_s, limit)
            }
            DriveSpec::Hold { angle_deg } => Ok(MotionProfile::hold(r(angle_deg))),
            DriveSpec::Table { .. } => Err(DriveError::InvalidParameter {
                name: "file",
                value: f64::NAN,
                allowed: "a table read with its scenario (Scenario::load) or by MotionProfile::from_csv".into(),
            }),
        }
    }

    /// The drive with its `shaper` tuned to every one of `modes`: the base move over
    /// `duration_s` minus the shaper's length, convolved with the shaper's impulses, so that the
    /// whole lift still takes `duration_s`. Without a shaper, [`Self::motion`].
    ///
    /// # Errors
    /// As [`Self::motion`]; `duration_s` not longer than the shaper's length; modes
    /// [`MotionProfile::shaped_for`] refuses.
    pub fn shaped_motion(&self, modes: &[ShaperMode]) -> Result<MotionProfile, DriveError> {
        match self.shaping() {
            Some(request) => self.motion()?.shaped_within(request.shaper, modes),
            None => self.motion(),
        }
    }
}

/// A parse error's message, with what is allowed where serde's own message cannot say it: a
/// shaper on a drive that takes none reads to serde as an unknown field.
pub(super) fn parse_hint(message: String) -> String {
    if message.contains("unknown field `shaper") {
        format!(
            "{}\nkey `drive.shaper`: allowed on uniform, trapezoidal and s-curve drives only (a shaper shapes a \
             point-to-point move)",
            message.trim_end()
        )
    } else {
        message
    }
}

fn either(allowed: &str) -> DriveError {
    DriveError::InvalidParameter { name: "limit", value: f64::NAN, allowed: format!("exactly one of: {allowed}") }
}

/// Drive errors name radians; the file states degrees, so the key is given in the file's terms.
/// The `[head]` table: a driven tilting head's own drive (`head.drive`, any drive kind but
/// unshaped), in degrees on its hinge from the URDF pose.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadSpec {
    /// The head's drive.
    pub drive: DriveSpec,
}

impl Check<'_> {
    /// Sets a driven hinge's profile from `head.drive`; a driven hinge without one, or a `[head]`
    /// for a robot without a driven hinge, is refused.
    pub(super) fn head(&self, spec: Option<&HeadSpec>, robot: &mut crate::robot::Robot) -> Result<(), ScenarioError> {
        match (robot.head.as_mut(), spec) {
            (Some(head), Some(spec)) if head.is_driven() => {
                if spec.drive.shaping().is_some() {
                    return Err(
                        self.invalid("head.drive.shaper", "an input shaper shapes the hub's drive: allowed unshaped")
                    );
                }
                let profile = self.drive(&spec.drive).map_err(|e| match e {
                    ScenarioError::Invalid { path, key, message } => {
                        ScenarioError::Invalid { path, key: format!("head.{key}"), message }
                    }
                    other => other,
                })?;
                head.law = crate::robot::HingeLaw::Driven { profile: Some(profile) };
                Ok(())
            }
            (Some(head), None) if head.is_driven() => Err(self.invalid(
                "head.drive",
                format!("missing: joint `{}` is a driven hinge (kind=\"driven\"): give the head's drive", head.joint),
            )),
            (Some(head), Some(_)) => Err(self.invalid(
                "head",
                format!(
                    "joint `{}` is a spring hinge: a head drive is for a driven hinge (kind=\"driven\")",
                    head.joint
                ),
            )),
            (None, Some(_)) => Err(self.invalid(
                "head",
                "the robot has no tilting head: allowed with a revolute joint on the arm whose <pipearm:hinge> is \
                 kind=\"driven\"",
            )),
            (_, None) => Ok(()),
        }
    }
}

fn drive_error(path: &Path, e: DriveError) -> ScenarioError {
    let message = format!("{e}{}", e.in_degrees_note());
    ScenarioError::Invalid { path: path.into(), key: e.scenario_key(), message }
}
