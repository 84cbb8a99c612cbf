//! A model compiled for its runs: everything a run derives from the model before its first step,
//! derived once and immutable — the arm reduced to its fidelity, the string's and the arm's
//! fidelity choices with their reasons, the fastest motion the step must resolve, the run's
//! channels and its contact pairs' names. A run ([`super::run_compiled`]) steps a fresh scene
//! from it and fills a fresh series, as MuJoCo's `mjData` steps beside its `mjModel`.

use std::borrow::Cow;

use crate::arm::{ArmError, Fidelity};
use crate::channel::Channel;
use crate::compile::Compiler;
use crate::model::Model;
use crate::scene::SceneError;
use crate::select::CompiledArm;

/// A model compiled for its runs (module doc).
pub struct CompiledModel<'a> {
    /// The model, as the scenario file gives it, checked, its drive's shaper tuned
    /// ([`crate::tuning::tuned`]).
    pub model: Cow<'a, Model>,
    /// Its arm at the chosen fidelity, with the choices and the fastest motion.
    pub arm: CompiledArm,
    /// The run's channels as their producers declare them, but the sign-off's (those follow
    /// where the run's peak falls): [`super::channels`].
    pub channels: Vec<Channel>,
    /// Each contact pair's name, in the scene's order ([`crate::scene::pair_names`]).
    pub pair_names: Vec<String>,
    /// A held string's natural frequencies clamped in its hands, Hz: of the run's beam where it
    /// holds the string as a beam of its own (every fixed-interface mode is solved whatever the
    /// kept count), else of the fe string's (compiled here, not after the run); empty without a
    /// string.
    pub string_frequencies_hz: Vec<f64>,
}

impl<'a> CompiledModel<'a> {
    /// Compiles `model` at `fidelity` (`auto`'s choice if `None`), taking from `compiler` what it
    /// kept from earlier compilations that it shares (the beam, its modes, the reduced arm).
    ///
    /// # Errors
    /// The shaper cannot be tuned ([`crate::tuning::TuningError`]) or the arm not compiled.
    pub fn new(model: &'a Model, fidelity: Option<Fidelity>, compiler: &Compiler) -> Result<Self, SceneError> {
        let model = crate::tuning::tuned(model, compiler)?;
        let arm = crate::select::compile_arm(&model, fidelity, compiler)?;
        let string_frequencies_hz = string_frequencies_hz(&model, &arm)?;
        let pair_names = crate::scene::pair_names(&model);
        let channels = Vec::new();
        let mut compiled = CompiledModel { model, arm, channels, pair_names, string_frequencies_hz };
        compiled.channels = super::channels(&compiled.model, compiled.modal_dofs());
        Ok(compiled)
    }

    /// The elastic coordinates a run records per step (none for fe).
    pub fn modal_dofs(&self) -> usize {
        if self.arm.arm.fidelity == Fidelity::Fe { 0 } else { self.arm.model.elastic_dofs() }
    }
}

/// [`CompiledModel::string_frequencies_hz`] of `model` with its arm compiled as `arm`.
fn string_frequencies_hz(model: &Model, arm: &CompiledArm) -> Result<Vec<f64>, ArmError> {
    if model.payload.string().is_none() {
        return Ok(Vec::new());
    }
    if let Some(modes) = arm.model.beam.member_modes() {
        return Ok(modes.frequencies_hz());
    }
    // The fe string's fixed-interface modes only: the beam's own clamped modes, which the
    // compiler would solve with it, are not needed for them.
    let fe = crate::beam::BeamModel::new(model.beam_spec_with_string(Some(Fidelity::Fe))?)?;
    Ok(fe.member_modes().map(|m| m.frequencies_hz()).unwrap_or_default())
}
