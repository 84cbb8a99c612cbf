//! pipearm: flexible pipe-handling arms on oil rigs and the impacts they take on their rubber
//! dampeners.
//!
//! Data flows one way: a [`scenario`] (with its [`robot`]) → a model ([`beam`] reduced by
//! [`arm`]) → the step loop of a [`scene`] ([`integrate`], driven by [`drive`], with
//! [`contact`]) → [`run`] series → ([`record`], [`analysis`]) → summary. Physics functions are
//! pure and in SI units; the conventions are stated in each module.

pub mod analysis;
pub mod arm;
pub mod beam;
pub mod bench;
pub mod contact;
pub mod drive;
pub mod guard;
pub mod integrate;
pub mod record;
pub mod regression;
pub mod robot;
pub mod run;
pub mod scenario;
pub mod scene;
pub mod seed;
pub mod select;
pub mod sweep;
