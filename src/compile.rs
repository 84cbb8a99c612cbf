//! The parts of a run derived from its model before the first step — the beam with its clamped
//! modes, the arm reduced to its fidelity — compiled once and kept for the next run that shares
//! them.
//!
//! A sweep's, envelope's, design's or fit's cases differ in a few keys; most keys (a pad's gap
//! or stiffness, the drive, the integrator) leave the beam and the reduced arm as they were. A
//! [`Compiler`] keeps the last few it compiled, each under everything it was derived from: a
//! case whose keys touch none of it takes it as compiled, one whose keys do (the arm's section,
//! the string's size, a damping ratio) compiles its own. Taken or compiled, the run's numbers
//! are the same to the bit: the same inputs give the same matrices.
//!
//! `auto`'s choice of the arm's fidelity is kept the same way, under every key it reads (the
//! robot, payload, drive, pads, structures, physics, time, integrator and tolerance): cases that
//! differ only in what it does not read (the contact method, the sensors, the sign-off's factor)
//! or not at all take it with its error estimate as made.
//!
//! What is kept is immutable once compiled (the running state lives in the scene), so the runs
//! of every thread share it.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::arm::{ArmError, ArmModel, ArmOptions, Fidelity};
use crate::beam::{BeamError, BeamModel, BeamSpec, ModalBasis};
use crate::choice::Choice;
use crate::model::Model;
use crate::robot::TiltingHead;

/// How many compiled parts of each kind are kept: a sweep's cases arrive in cost order, not
/// grouped by what they share, and a handful covers the distinct beams of a sweep over pads,
/// drives or damping.
const KEPT: usize = 8;

/// A beam with the arm's clamped modes.
type BuiltBeam = (BeamModel, ModalBasis);

/// What a beam was compiled from: its description, and how many of its member's (the string's)
/// modes a run keeps (`None`: as described).
#[derive(Debug, Clone, PartialEq)]
struct BeamKey {
    spec: BeamSpec,
    member_modes: Option<usize>,
}

/// What a reduced arm was compiled from.
#[derive(Debug, Clone, PartialEq)]
struct ArmKey {
    beam: BeamKey,
    fidelity: Fidelity,
    options: ArmOptions,
    head: Option<TiltingHead>,
}

/// What `auto`'s choice of the arm's fidelity reads: the beam it chose on, and the model's keys
/// the band, the coupled frequencies and the error estimate read.
#[derive(Debug, Clone, PartialEq)]
struct ChoiceKey {
    beam: BeamKey,
    robot: crate::robot::Robot,
    payload: crate::model::Payload,
    drive: crate::model::Drive,
    dampeners: Vec<crate::model::Dampener>,
    structures: Vec<crate::model::Structure>,
    physics: crate::model::PhysicsOptions,
    time: crate::model::TimeOptions,
    integrator: crate::integrate::IntegratorKind,
    tolerance: f64,
}

impl ChoiceKey {
    fn new(beam: &BeamKey, model: &Model) -> Self {
        ChoiceKey {
            beam: beam.clone(),
            robot: model.robot.clone(),
            payload: model.payload.clone(),
            drive: model.drive.clone(),
            dampeners: model.dampeners.clone(),
            structures: model.structures.clone(),
            physics: model.physics,
            time: model.time,
            integrator: model.integrator,
            tolerance: model.tolerance,
        }
    }
}

/// The last [`KEPT`] values compiled, by what they were compiled from.
#[derive(Debug)]
struct Kept<K, V> {
    entries: Mutex<VecDeque<(K, V)>>,
    /// How many were compiled (not taken as kept).
    compiled: AtomicUsize,
}

impl<K, V> Default for Kept<K, V> {
    fn default() -> Self {
        Kept { entries: Mutex::new(VecDeque::with_capacity(KEPT)), compiled: AtomicUsize::new(0) }
    }
}

impl<K: PartialEq, V: Clone> Kept<K, V> {
    /// The value kept under `key`, or `compile`'s, kept (the oldest dropped beyond [`KEPT`]).
    /// Two threads missing the same key at once both compile it; the values are equal.
    fn get_or_compile<E>(&self, key: K, compile: impl FnOnce() -> Result<V, E>) -> Result<V, E> {
        let entries = || self.entries.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((_, value)) = entries().iter().find(|(k, _)| *k == key) {
            return Ok(value.clone());
        }
        let value = compile()?;
        self.compiled.fetch_add(1, Ordering::Relaxed);
        let mut kept = entries();
        if kept.len() == KEPT {
            kept.pop_front();
        }
        kept.push_back((key, value.clone()));
        Ok(value)
    }
}

/// Compiles beams and reduced arms, keeping the last few for the runs that share them.
#[derive(Debug, Default)]
pub struct Compiler {
    beams: Kept<BeamKey, Arc<BuiltBeam>>,
    arms: Kept<ArmKey, Arc<ArmModel>>,
    choices: Kept<ChoiceKey, Choice>,
}

/// How many beams and reduced arms a [`Compiler`] compiled (the rest it took as kept).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Compilations {
    /// Beams with their clamped modes (each an eigenproblem), and beams keeping fewer of their
    /// member's modes.
    pub beams: usize,
    /// Arms reduced to a fidelity.
    pub arms: usize,
    /// `auto`'s choices of the arm's fidelity (each with its error estimate).
    pub choices: usize,
}

/// A beam with the arm's clamped modes, as compiled, and what it was compiled from.
#[derive(Debug, Clone)]
pub struct CompiledBeam {
    key: BeamKey,
    built: Arc<BuiltBeam>,
}

impl CompiledBeam {
    /// The beam.
    pub fn beam(&self) -> &BeamModel {
        &self.built.0
    }

    /// The arm's clamped modes (with the member riding on its hands).
    pub fn modes(&self) -> &ModalBasis {
        &self.built.1
    }
}

impl Compiler {
    /// A compiler that has kept nothing yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many it compiled so far.
    pub fn compilations(&self) -> Compilations {
        Compilations {
            beams: self.beams.compiled.load(Ordering::Relaxed),
            arms: self.arms.compiled.load(Ordering::Relaxed),
            choices: self.choices.compiled.load(Ordering::Relaxed),
        }
    }

    /// The beam described by `spec` with the arm's clamped modes.
    pub fn beam(&self, spec: &BeamSpec) -> Result<CompiledBeam, BeamError> {
        let key = BeamKey { spec: spec.clone(), member_modes: None };
        let built = self.beams.get_or_compile(key.clone(), || {
            let beam = BeamModel::new(spec.clone())?;
            let modes = beam.modes()?;
            Ok(Arc::new((beam, modes)))
        })?;
        Ok(CompiledBeam { key, built })
    }

    /// `compiled` keeping the first `member_modes` of its member's (the string's) modes; the
    /// arm's clamped modes are `compiled`'s.
    pub fn keeping_member_modes(&self, compiled: &CompiledBeam, member_modes: usize) -> CompiledBeam {
        let key = BeamKey { spec: compiled.key.spec.clone(), member_modes: Some(member_modes) };
        let built = self.beams.get_or_compile(key.clone(), || {
            let (mut beam, modes) = (*compiled.built).clone();
            beam.keep_member_modes(Some(member_modes));
            Ok::<_, std::convert::Infallible>(Arc::new((beam, modes)))
        });
        let Ok(built) = built;
        CompiledBeam { key, built }
    }

    /// `auto`'s choice of the arm's fidelity for `model` on `compiled`, made by `choose` unless a
    /// run with the same keys made it.
    pub fn choice(
        &self,
        model: &Model,
        compiled: &CompiledBeam,
        choose: impl FnOnce() -> Result<Choice, BeamError>,
    ) -> Result<Choice, BeamError> {
        self.choices.get_or_compile(ChoiceKey::new(&compiled.key, model), choose)
    }

    /// The arm of `compiled` reduced to `fidelity` with `options`, with the robot's tilting
    /// `head` turning on it.
    pub fn arm(
        &self,
        compiled: &CompiledBeam,
        fidelity: Fidelity,
        options: &ArmOptions,
        head: Option<&TiltingHead>,
    ) -> Result<Arc<ArmModel>, ArmError> {
        let key = ArmKey { beam: compiled.key.clone(), fidelity, options: options.clone(), head: head.cloned() };
        self.arms.get_or_compile(key, || {
            let (beam, modes) = (*compiled.built).clone();
            ArmModel::with_modes(beam, modes, fidelity, options.clone())?.with_head(head).map(Arc::new)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_value_is_taken_and_the_oldest_is_dropped_beyond_the_limit() {
        let kept: Kept<usize, usize> = Kept::default();
        let compile = |k: usize| kept.get_or_compile(k, || Ok::<_, ()>(10 * k)).unwrap();
        assert_eq!(compile(1), 10);
        assert_eq!(kept.get_or_compile(1, || Err(())), Ok(10), "taken as kept, not compiled");
        for k in 2..=KEPT + 1 {
            compile(k);
        }
        assert_eq!(kept.compiled.load(Ordering::Relaxed), KEPT + 1);
        assert_eq!(kept.get_or_compile(1, || Err(())), Err(()), "the oldest was dropped");
        assert_eq!(kept.get_or_compile(KEPT + 1, || Err(())), Ok(10 * (KEPT + 1)));
    }
}
