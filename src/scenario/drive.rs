//! The `[drive]` table: the hub's motion as a scenario states it (degrees), its checks, and the
//! profile it resolves to — shaped, if it asks for an input shaper, with the arm's frequency
//! ([`crate::select::shaper_tuning_hz`]).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{Check, Scenario, ScenarioError};
use crate::drive::{DriveError, MotionProfile, SCurveLimit, Shaper, TableError, TrapezoidLimit};
use crate::model::Model;
use crate::select;

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
        /// The shaper's tuning frequency, Hz (default: the arm's first mode,
        /// [`select::shaper_tuning_hz`]).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper_hz: Option<f64>,
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
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper_hz: Option<f64>,
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
        #[serde(default, skip_serializing_if = "Option::is_none")]
        shaper_hz: Option<f64>,
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
        let tunes_nothing = matches!(
            drive,
            DriveSpec::Uniform { shaper: None, shaper_hz: Some(_), .. }
                | DriveSpec::Trapezoidal { shaper: None, shaper_hz: Some(_), .. }
                | DriveSpec::SCurve { shaper: None, shaper_hz: Some(_), .. }
        );
        if tunes_nothing {
            return Err(self.invalid("drive.shaper_hz", "tunes an input shaper: set drive.shaper (zv, zvd or ei) too"));
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

    /// The shaped drive: tuned to `shaper_hz` (Hz) if given, else to the arm's first mode with
    /// its payload and actuator at the end of the path ([`select::shaper_tuning_hz`], on `model`
    /// built with the unshaped move), damped by the arm's first modal damping ratio; the base
    /// move shortened by the shaper's length so that the lift keeps its `duration_s`.
    pub(super) fn shaped(
        &self,
        drive: &DriveSpec,
        shaper_hz: Option<f64>,
        model: &Model,
    ) -> Result<MotionProfile, ScenarioError> {
        let frequency_hz = match shaper_hz {
            Some(f) if f.is_finite() && f > 0.0 => f,
            Some(f) => return Err(self.invalid("drive.shaper_hz", format!("{f} is outside > 0 Hz (finite)"))),
            None => select::shaper_tuning_hz(model).ok_or_else(|| {
                self.invalid(
                    "drive.shaper",
                    "the arm's first frequency at the end of the path cannot be computed (the arm or its drive does \
                     not linearise there): set drive.shaper_hz",
                )
            })?,
        };
        let damping_ratio = model.robot.arm.damping_ratios.first().copied().unwrap_or(0.0);
        drive.shaped_motion(frequency_hz, damping_ratio).map_err(|e| drive_error(self.path, e))
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
        let table = motion.name() == "table";
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
    /// The input shaper a uniform, trapezoidal or s-curve drive asks for, with its tuning
    /// frequency (Hz) if given.
    pub fn shaping(&self) -> Option<(Shaper, Option<f64>)> {
        match *self {
            DriveSpec::Uniform { shaper, shaper_hz, .. }
            | DriveSpec::Trapezoidal { shaper, shaper_hz, .. }
            | DriveSpec::SCurve { shaper, shaper_hz, .. } => shaper.map(|s| (s, shaper_hz)),
            DriveSpec::Hold { .. } | DriveSpec::Table { .. } => None,
        }
    }

    /// The motion profile of a built-in law, in radians, unshaped: a drive's `shaper`, which needs
    /// the arm's frequency, is applied by [`Self::shaped_motion`] (as [`Scenario::load`] does). A
    /// table is read relative to its scenario file ([`Scenario::load`],
    /// [`MotionProfile::from_csv`]); here it is an error.
    pub fn motion(&self) -> Result<MotionProfile, DriveError> {
        self.profile(None)
    }

    /// The drive with its `shaper` tuned to `frequency_hz` (Hz) and `damping_ratio`: the base
    /// move over `duration_s` minus the shaper's length, convolved with the shaper's impulses, so
    /// that the whole lift still takes `duration_s`. Without a shaper, [`Self::motion`].
    ///
    /// # Errors
    /// As [`Self::motion`]; `duration_s` not longer than the shaper's length; a frequency or
    /// damping ratio [`MotionProfile::shaped`] refuses.
    pub fn shaped_motion(&self, frequency_hz: f64, damping_ratio: f64) -> Result<MotionProfile, DriveError> {
        let (Some((shaper, _)), Some(duration_s)) = (self.shaping(), self.duration_s()) else { return self.motion() };
        if !(frequency_hz.is_finite() && frequency_hz > 0.0 && (0.0..1.0).contains(&damping_ratio)) {
            return MotionProfile::shaped(self.motion()?, shaper, frequency_hz, damping_ratio);
        }
        let length_s = shaper.length_s(frequency_hz, damping_ratio);
        if duration_s <= length_s {
            return Err(DriveError::InvalidParameter {
                name: "duration_s",
                value: duration_s,
                allowed: format!(
                    "> the {} shaper's length {length_s:.3} s at {frequency_hz:.4} Hz (the base move lasts duration_s \
                     minus it)",
                    shaper.name()
                ),
            });
        }
        MotionProfile::shaped(self.profile(Some(duration_s - length_s))?, shaper, frequency_hz, damping_ratio)
    }

    /// The lift time of a point-to-point drive, s.
    fn duration_s(&self) -> Option<f64> {
        match *self {
            DriveSpec::Uniform { duration_s, .. }
            | DriveSpec::Trapezoidal { duration_s, .. }
            | DriveSpec::SCurve { duration_s, .. } => Some(duration_s),
            DriveSpec::Hold { .. } | DriveSpec::Table { .. } => None,
        }
    }

    /// The unshaped profile, over `duration` (s) instead of the drive's `duration_s` if given.
    fn profile(&self, duration: Option<f64>) -> Result<MotionProfile, DriveError> {
        let r = f64::to_radians;
        let over = |duration_s: f64| duration.unwrap_or(duration_s);
        match *self {
            DriveSpec::Uniform { start_deg, end_deg, duration_s, .. } => {
                MotionProfile::uniform(r(start_deg), r(end_deg), over(duration_s))
            }
            DriveSpec::Trapezoidal { start_deg, end_deg, duration_s, accel_deg_s2, ramp_fraction, .. } => {
                let limit = match (accel_deg_s2, ramp_fraction) {
                    (Some(a), None) => TrapezoidLimit::AccelRadS2(r(a)),
                    (None, Some(f)) => TrapezoidLimit::RampFraction(f),
                    _ => return Err(either("accel_deg_s2 | ramp_fraction")),
                };
                MotionProfile::trapezoidal(r(start_deg), r(end_deg), over(duration_s), limit)
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
                MotionProfile::s_curve(r(start_deg), r(end_deg), over(duration_s), limit)
            }
            DriveSpec::Hold { angle_deg } => Ok(MotionProfile::hold(r(angle_deg))),
            DriveSpec::Table { .. } => Err(DriveError::InvalidParameter {
                name: "file",
                value: f64::NAN,
                allowed: "a table read with its scenario (Scenario::load) or by MotionProfile::from_csv".into(),
            }),
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
fn drive_error(path: &Path, e: DriveError) -> ScenarioError {
    let (DriveError::InvalidParameter { name, .. } | DriveError::InvalidSample { name, .. }) = &e;
    let key = name.replace("_rad", "_deg");
    let message = if key == *name { e.to_string() } else { format!("{e} (values in radians)") };
    ScenarioError::Invalid { path: path.into(), key: format!("drive.{key}"), message }
}
