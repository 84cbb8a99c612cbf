//! A fidelity chosen and why: what `auto` (or the scenario, or the command line) settled on, the
//! reason in words, and the error it expects.

use serde::Serialize;

use crate::arm::Fidelity;

/// The fidelity chosen and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// The fidelity.
    pub fidelity: Fidelity,
    /// Why, in a sentence.
    pub reason: String,
    /// The error `auto` expects of it on the scene's headline quantities (`None` for a fidelity
    /// set by hand).
    pub expected: Option<ExpectedError>,
}

impl Choice {
    /// A fidelity set by hand (`why`: where), with no estimate.
    pub fn set(fidelity: Fidelity, why: &str) -> Self {
        Choice { fidelity, reason: why.into(), expected: None }
    }
}

/// The error a choice expects, relative, and on what it is based.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExpectedError {
    /// The largest expected relative error of a headline quantity (0.01 = 1 %).
    pub fraction: f64,
    /// Which quantity, and the estimate it comes from.
    pub basis: String,
    /// The fewest modes the scene's band (and an actuator's coupled frequencies) need, the floor
    /// the budget adds to; 0 for the string's estimate, which has no floor of its own.
    pub floor_modes: usize,
    /// The expected relative error of the residual vibration's amplitude, where the estimate
    /// measures it (a linear run through the drive); stated, not held to the budget.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_fraction: Option<f64>,
}
