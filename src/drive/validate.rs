//! Checks on the parameters of a drive: the error they raise, the validated point-to-point move
//! and the slack allowed on feasibility limits.

/// Relative slack accepted on feasibility limits, so that a limit computed to
/// be exactly the minimum is not rejected because of rounding.
pub(super) const FEASIBILITY_SLACK: f64 = 1e-12;

/// Error building a [`MotionProfile`](super::MotionProfile).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DriveError {
    /// A parameter is out of its allowed range (value in the parameter's SI unit).
    #[error("drive parameter `{name}` = {value} is invalid: allowed {allowed}")]
    InvalidParameter {
        /// Name of the offending parameter, e.g. `"duration_s"`.
        name: &'static str,
        /// The rejected value, in the parameter's SI unit.
        value: f64,
        /// Human-readable description of the allowed values.
        allowed: String,
    },
    /// One sample of a table is out of its allowed range.
    #[error("drive sample `{name}[{index}]` = {value} is invalid: allowed {allowed}")]
    InvalidSample {
        /// Which samples, `"times_s"` or `"angles_rad"`.
        name: &'static str,
        /// Index of the offending sample, from 0.
        index: usize,
        /// The rejected value, in the samples' SI unit.
        value: f64,
        /// Human-readable description of the allowed values.
        allowed: String,
    },
}

impl DriveError {
    /// The offending parameter's or samples' name (SI: `_rad` for angles).
    pub fn name(&self) -> &'static str {
        let (DriveError::InvalidParameter { name, .. } | DriveError::InvalidSample { name, .. }) = self;
        name
    }

    /// Its key as a scenario's `[drive]` spells it (`_deg` for `_rad`).
    pub fn scenario_key(&self) -> String {
        format!("drive.{}", self.name().replace("_rad", "_deg"))
    }

    /// What a scenario's error adds to it: a note that the values are in radians where its key
    /// is in degrees.
    pub fn in_degrees_note(&self) -> &'static str {
        if self.name().contains("_rad") { " (values in radians)" } else { "" }
    }
}

/// A validated point-to-point move.
#[derive(Debug, Clone, Copy)]
pub(super) struct Move {
    pub(super) start_rad: f64,
    pub(super) end_rad: f64,
    pub(super) duration_s: f64,
}

impl Move {
    pub(super) fn new(start_rad: f64, end_rad: f64, duration_s: f64) -> Result<Self, DriveError> {
        let start_rad = require_finite("start_rad", start_rad)?;
        let end_rad = require_finite("end_rad", end_rad)?;
        let duration_s = require_positive("duration_s", duration_s)?;
        if start_rad == end_rad {
            return Err(invalid("end_rad", end_rad, "finite and different from start_rad (use `hold` for no motion)"));
        }
        if !(end_rad - start_rad).is_finite() {
            return Err(invalid("end_rad", end_rad, "such that end_rad - start_rad is finite"));
        }
        Ok(Self { start_rad, end_rad, duration_s })
    }

    /// Signed displacement `B − A`, rad.
    pub(super) fn delta(&self) -> f64 {
        self.end_rad - self.start_rad
    }

    /// Displacement magnitude `|B − A|`, rad.
    pub(super) fn distance(&self) -> f64 {
        self.delta().abs()
    }

    /// Direction of motion, ±1.
    pub(super) fn sign(&self) -> f64 {
        self.delta().signum()
    }
}

pub(super) fn invalid(name: &'static str, value: f64, allowed: impl Into<String>) -> DriveError {
    DriveError::InvalidParameter { name, value, allowed: allowed.into() }
}

pub(super) fn require_finite(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value.is_finite() { Ok(value) } else { Err(invalid(name, value, "any finite value")) }
}

pub(super) fn require_positive(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(invalid(name, value, "finite and > 0")) }
}

pub(super) fn require_fraction(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value > 0.0 && value <= 0.5 { Ok(value) } else { Err(invalid(name, value, "in (0, 0.5]")) }
}
