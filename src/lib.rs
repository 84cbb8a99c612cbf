//! pipearm: flexible pipe-handling arms on oil rigs and the impacts they take on their rubber
//! dampeners.
//!
//! Data flows one way: a description (scenario) → a model ([`beam`] reduced by [`arm`]) → the
//! step loop ([`integrate`], driven by [`drive`]) → outputs. Physics functions are pure and in
//! SI units; the conventions are stated in each module.

pub mod analysis;
pub mod arm;
pub mod beam;
pub mod drive;
pub mod integrate;
pub mod scenario;
