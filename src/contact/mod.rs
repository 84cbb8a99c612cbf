//! Contact between the arm (and what it carries) and the rubber dampeners: force laws and the
//! per-pair bookkeeping of impacts.

mod impacts;
mod law;

pub use impacts::{Impact, ImpactTracker};
pub use law::ForceLaw;
