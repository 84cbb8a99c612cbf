//! The CLI's longer commands, each in its own file (the binary's; the library has none of this).

pub mod capacity;
pub mod design;
pub mod draw;
pub mod envelope;
pub mod help;
pub mod measured;
pub mod modes;
pub mod overrides;
pub mod pipes;
pub mod project;
pub mod seed;
pub mod sign_off;
pub mod summary;
pub mod sweep;
