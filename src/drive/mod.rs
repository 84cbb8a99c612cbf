//! Prescribed hub motion of an arm pivoting at its base.
//!
//! A [`MotionProfile`] moves the hub angle from a start angle `A` to an end
//! angle `B` in a duration `T`; [`MotionProfile::sample`] returns the exact
//! angle, rate, acceleration and jerk at any time.
//!
//! # Conventions
//!
//! * SI units throughout: angles in rad, rates in rad/s, accelerations in
//!   rad/s², jerks in rad/s³, times in s.
//! * The motion starts at `t = 0`. Before `t = 0` every profile holds at `A`
//!   at rest; from `t = T` on it holds at `B` at rest. The exception is the
//!   spin-up profile, which keeps its final constant rate forever after its
//!   ramp time, and a table given an end rate, which keeps it after its last
//!   sample.
//! * Where a quantity jumps, `sample` returns the value just *after* the
//!   instant (right-continuous).
//! * Moving down (`B < A`) is the exact mirror image of moving up.
//!
//! # Continuity per profile
//!
//! | profile       | continuous                    | discontinuous                                   |
//! |---------------|-------------------------------|-------------------------------------------------|
//! | `uniform`     | angle                         | rate jumps at 0 and `T` (see [`MotionProfile::rate_jumps`]); the matching acceleration impulses are not reported (accel 0) |
//! | `trapezoidal` | angle, rate                   | accel jumps at 0, `t_a`, `T - t_a`, `T`; jerk is impulsive there and reported as 0 |
//! | `s-curve`     | angle, rate, accel            | jerk is piecewise constant and jumps at the 8 segment boundaries |
//! | `spin-up`     | angle, rate, accel, jerk      | snap (d jerk/dt) jumps at 0 and the ramp time   |
//! | `hold`        | everything (constant)         | nothing                                         |
//! | `table`       | angle, rate; accel on `[0, T]` | accel steps from/to 0 at 0 and `T`; jerk is piecewise constant and jumps at the samples |
//! | shaped        | its base's                    | its base's, at every `t_i + b` (`t_i` an impulse's time, `b` 0 or a breakpoint of the base); a shaped uniform's rate jumps by `A_i` times the base's |
//!
//! # Implementation
//!
//! A shaped profile ([`MotionProfile::shaped`], [`Shaper`]) is a uniform, trapezoidal or
//! s-curve base of duration `T_b` convolved with an input shaper's impulses `(t_i, A_i)`,
//! `θ(t) = Σ A_i θ_base(t − t_i)` with `Σ A_i = 1`: it keeps the base's start and end angles,
//! lasts `T = T_b + t_N` and is not point-symmetric. [`MotionProfile::name`] is its base's.
//!
//! The symmetric profiles (uniform, trapezoidal, s-curve) are stored as
//! constant-jerk segments covering the first half `[0, T/2]`, with the state
//! at each segment start precomputed at construction. The second half follows
//! from the point symmetry `θ(t) = A + B − θ(T − t)`, so `θ(T) = B` holds
//! exactly (to rounding). A table and a shaped profile are stored as segments over all of
//! `[0, T]`. Sampling is a closed-form cubic per segment; there is no numerical integration.
//!
//! # Layout
//!
//! * `profile`: the profile kinds and their constructors.
//! * `trapezoid`, `s_curve`: each limited profile's timing, solved from its limit.
//! * `shaper`: input shapers (ZV, ZVD, EI), their impulses and residual vibration.
//! * `shaped`: a move convolved with a shaper's impulses.
//! * `state`: the kinematic state and constant-jerk motion of it.
//! * `sample`: the state of a profile at a time.
//! * `table`: the clamped cubic spline through samples of angle against time.
//! * `table_file`: a table drive's CSV file (`t[s],angle[deg]`) and its checks.
//! * `breakpoints`: where a profile is not smooth.
//! * `validate`: the checks on parameters and the error they raise.

mod breakpoints;
mod profile;
mod s_curve;
mod sample;
mod shaped;
mod shaper;
mod state;
mod table;
mod table_file;
#[cfg(test)]
mod test_support;
mod trapezoid;
mod validate;

pub use profile::{MotionLaw, MotionProfile};
pub use s_curve::SCurveLimit;
pub use shaper::{EI_TOLERANCE, Shaper, ShaperMode, convolve, residual_vibration};
pub use state::DriveState;
pub use table::MIN_TABLE_SAMPLES;
pub use table_file::TableError;
pub use trapezoid::TrapezoidLimit;
pub use validate::DriveError;
