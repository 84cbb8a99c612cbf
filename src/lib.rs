//! pipearm: flexible pipe-handling arms on oil rigs and the impacts they take on their rubber
//! dampeners.
//!
//! Data flows one way: a [`scenario`] file (with its [`robot`]) is checked and resolved once into a
//! [`model`] of the machine and scene → the arm ([`beam`] reduced by [`arm`], at the fidelity
//! [`select`] picks) → the step loop of a [`scene`] ([`integrate`], driven by [`drive`], with
//! [`contact`] laws) → [`run`] series → ([`record`], [`export`], [`analysis`]) → summary. No module below
//! [`scenario`] imports it. Physics functions are pure and in SI units; the conventions are stated
//! in each module.

pub mod actuator;
pub mod analysis;
pub mod arm;
pub mod beam;
pub mod bench;
pub mod capacity;
pub mod channel;
pub mod choice;
pub mod compare;
pub mod compile;
pub mod contact;
mod cores;
pub mod design;
pub mod draw;
pub mod drive;
pub mod envelope;
pub mod export;
pub mod fatigue;
pub mod fit;
pub mod guard;
pub mod integrate;
pub mod measured;
pub mod model;
pub mod point_load;
pub mod record;
pub mod regression;
pub mod robot;
pub mod run;
pub mod scenario;
pub mod scene;
pub mod seed;
pub mod select;
pub mod sensor;
pub mod steel;
pub mod stress;
pub mod sweep;
pub mod tuning;
