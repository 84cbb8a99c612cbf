//! `[checks]`: how a run's stresses are judged ([`crate::stress`], `docs/sign-off.md`).

use serde::{Deserialize, Serialize};

use super::{Check, ScenarioError};
use crate::model::SignOffChecks;
use crate::robot::Robot;

/// `[checks]`: how the run's stresses are judged.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChecksSpec {
    /// Design factor on stress, applied to utilisation and to the fatigue ranges (default 1.0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stress_factor: Option<f64>,
}

impl Check<'_> {
    /// `[model] tolerance`: `auto`'s error budget, 0 < tolerance < 1 (the string's `auto` works
    /// to the arm's, so `payload.model` takes none).
    pub(super) fn tolerance(&self, spec: &super::ModelSpec, key: &str) -> Result<f64, ScenarioError> {
        let super::ModelSpec::Auto { tolerance: Some(tolerance) } = *spec else {
            return Ok(crate::model::DEFAULT_MODEL_TOLERANCE);
        };
        let key = format!("{key}.tolerance");
        if key != "model.tolerance" {
            return Err(self.invalid(&key, "the string's auto works to the arm's budget: set [model] tolerance"));
        }
        if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
            return Err(self.invalid(&key, format!("{tolerance} is outside 0 < tolerance < 1 (relative; 0.01 = 1 %)")));
        }
        Ok(tolerance)
    }

    /// `[checks]`: a design factor > 0; utilisation, which the table asks for, needs a yield
    /// strength on at least one of the robot's segments.
    pub(super) fn checks(&self, spec: Option<&ChecksSpec>, robot: &Robot) -> Result<SignOffChecks, ScenarioError> {
        let Some(spec) = spec else { return Ok(SignOffChecks::default()) };
        let stress_factor = spec.stress_factor.unwrap_or(1.0);
        if !(stress_factor.is_finite() && stress_factor > 0.0) {
            return Err(self.invalid(
                "checks.stress_factor",
                format!("{stress_factor}: allowed a finite number > 0 (1.0 by default)"),
            ));
        }
        if robot.arm.segments.iter().all(|s| s.checks.yield_strength.is_none()) {
            return Err(self.invalid(
                "checks",
                format!(
                    "utilisation needs a yield strength, and no segment of {} has one: allowed yield_strength_pa (Pa) or steel ({}) on a <pipearm:segment>",
                    robot.source.display(),
                    crate::steel::grade_names()
                ),
            ));
        }
        Ok(SignOffChecks { stress_factor })
    }
}
