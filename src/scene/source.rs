//! The one interface between the arm's step and whatever it touches.
//!
//! A [`ContactSource`] is anything that puts loads on the arm: contact pairs found by rapier's
//! collision pipeline or one point per pad (`compliant`), pads that are rapier bodies (`rapier`),
//! a friction clamp. The scene's step calls
//! every source in the same named stages, in the spirit of MuJoCo's forward pass:
//!
//! 1. [`pose`](ContactSource::pose) its shapes from the arm's state at the start of the step;
//! 2. [`add_loads`](ContactSource::add_loads): forces its own bodies put on the arm, held over the
//!    step (generalized forces; staggered by one step);
//! 3. [`find_contacts`](ContactSource::find_contacts): point contacts whose force law the implicit
//!    arm step evaluates on its own configuration (not staggered);
//! 4. the arm advances;
//! 5. [`advance`](ContactSource::advance) its own bodies to the arm's new pose;
//! 6. [`measure`](ContactSource::measure) its forces at the end of the step.
//!
//! A new source implements the trait and is added to the scene's list; the step does not change.

use super::geometry::ArmView;
use super::pair::ContactPair;
use crate::arm::{ArmContact, GeneralizedLoad};

/// Something that puts loads on the arm, called by the scene's step in stages (module doc).
/// Every stage but [`measure`](Self::measure) does nothing unless the source needs it.
pub trait ContactSource {
    /// Stage 1: pose the source's shapes from the arm's state at the start of the step.
    fn pose(&mut self, _arm: &ArmView) {}

    /// Stage 2: add the loads the source's own bodies put on the arm over the coming step.
    fn add_loads(&self, _arm: &ArmView, _load: &mut GeneralizedLoad) {}

    /// Stage 3: append the point contacts the implicit arm step of `h_s` evaluates itself.
    fn find_contacts(&mut self, _arm: &ArmView, _h_s: f64, _contacts: &mut Vec<ArmContact>) {}

    /// Stage 5: advance the source's own bodies over `h_s` to the arm's new pose.
    fn advance(&mut self, _arm: &ArmView, _h_s: f64) {}

    /// Stage 6: measure the forces at the end of the step; `contacts` are the ones this source
    /// appended in stage 3, evaluated by the step.
    fn measure(&mut self, arm: &ArmView, contacts: &[ArmContact]);

    /// The contact pairs this source holds, with their forces at the end of the last step.
    fn pairs(&self) -> &[ContactPair] {
        &[]
    }

    /// Whether the next step may be `h_s` long under error control: nothing of this source can
    /// begin or change within it.
    fn allows_free_step(&self, arm: &ArmView, h_s: f64) -> bool;

    /// What makes this source's state meaningless, if anything (checked after every step).
    fn fault(&self) -> Option<String>;

    /// Advice when a run diverges with this source in it, if the source is the likely cause.
    fn divergence_advice(&self, _step_s: f64) -> Option<String> {
        None
    }

    /// What a friction clamp reads of the string it holds, if this source is one.
    fn grip(&self) -> Option<GripReading> {
        None
    }

    /// Hands a source that holds the string the structures' force on it, N in the hub frame
    /// (x along the arm, y across it), for its next step; returns the string's slip along the
    /// arm, m, where this source is the one that integrates it.
    fn take_string_load(&mut self, _load_n: [f64; 2]) -> Option<f64> {
        None
    }
}

/// What a friction clamp reads of the string it holds, at the end of the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GripReading {
    /// The string's slip along the arm from where it was gripped, m.
    pub slip_m: f64,
    /// How deep the jaws have sunk into the string, m.
    pub jaw_sinking_m: f64,
    /// Each jaw's squeeze, N.
    pub squeeze_n: f64,
}
