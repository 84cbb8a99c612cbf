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
//!   ramp time.
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
//!
//! # Implementation
//!
//! The symmetric profiles (uniform, trapezoidal, s-curve) are stored as
//! constant-jerk segments covering the first half `[0, T/2]`, with the state
//! at each segment start precomputed at construction. The second half follows
//! from the point symmetry `θ(t) = A + B − θ(T − t)`, so `θ(T) = B` holds
//! exactly (to rounding). Sampling is a closed-form cubic per segment; there is
//! no numerical integration.

use std::f64::consts::PI;

/// Relative slack accepted on feasibility limits, so that a limit computed to
/// be exactly the minimum is not rejected because of rounding.
const FEASIBILITY_SLACK: f64 = 1e-12;

/// Kinematic state of the hub at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveState {
    /// Hub angle, rad.
    pub angle_rad: f64,
    /// Hub angular rate, rad/s.
    pub rate_rad_s: f64,
    /// Hub angular acceleration, rad/s².
    pub accel_rad_s2: f64,
    /// Hub angular jerk, rad/s³.
    pub jerk_rad_s3: f64,
}

impl DriveState {
    /// At rest at `angle_rad` (rad).
    const fn at_rest(angle_rad: f64) -> Self {
        Self { angle_rad, rate_rad_s: 0.0, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 }
    }

    /// State after `dt` seconds of constant jerk `self.jerk_rad_s3`.
    fn advanced(&self, dt: f64) -> Self {
        let j = self.jerk_rad_s3;
        Self {
            angle_rad: self.angle_rad + dt * (self.rate_rad_s + dt * (0.5 * self.accel_rad_s2 + dt * j / 6.0)),
            rate_rad_s: self.rate_rad_s + dt * (self.accel_rad_s2 + 0.5 * dt * j),
            accel_rad_s2: self.accel_rad_s2 + dt * j,
            jerk_rad_s3: j,
        }
    }

    /// Point mirror `θ(t) = angle_sum − θ(T − t)`: rate and jerk keep their
    /// sign, acceleration flips.
    fn point_mirrored(&self, angle_sum_rad: f64) -> Self {
        Self {
            angle_rad: angle_sum_rad - self.angle_rad,
            rate_rad_s: self.rate_rad_s,
            accel_rad_s2: -self.accel_rad_s2,
            jerk_rad_s3: self.jerk_rad_s3,
        }
    }
}

/// How the acceleration of a [`MotionProfile::trapezoidal`] profile is limited.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrapezoidLimit {
    /// Acceleration (and deceleration) magnitude, rad/s²; must be at least
    /// `4|B − A|/T²`. The profile uses exactly this acceleration.
    AccelRadS2(f64),
    /// Accel-phase duration divided by `T` (dimensionless), in `(0, 0.5]`;
    /// 0.5 gives a triangular rate profile.
    RampFraction(f64),
}

/// How a [`MotionProfile::s_curve`] profile is limited.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SCurveLimit {
    /// Peak acceleration (rad/s²) and jerk (rad/s³) limits; the profile uses
    /// exactly these peaks and fits `T`.
    AccelJerk {
        /// Peak acceleration magnitude, rad/s².
        accel_rad_s2: f64,
        /// Peak jerk magnitude, rad/s³.
        jerk_rad_s3: f64,
    },
    /// Shape given by dimensionless fractions.
    Fractions {
        /// Accel-phase (3 segments) duration divided by `T`, in `(0, 0.5]`.
        ramp_fraction: f64,
        /// Each jerk segment's duration divided by the accel-phase duration,
        /// in `(0, 0.5]` (0.5 = no constant-accel segment).
        jerk_fraction: f64,
    },
}

/// Error building a [`MotionProfile`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DriveError {
    /// A parameter is out of its allowed range (value in the parameter's SI unit).
    #[error("drive parameter `{name}` = {value} is invalid: allowed {allowed}")]
    InvalidParameter {
        /// Name of the offending parameter, e.g. `"duration_s"`.
        name: &'static str,
        /// The rejected value, in the parameter's SI unit.
        value: f64,
        /// Human-readable description of the allowed values.
        allowed: String,
    },
}

/// Which kind of profile a [`MotionProfile`] is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Uniform,
    Trapezoidal,
    SCurve,
    Hold,
    SpinUp { final_rate_rad_s: f64 },
}

/// One constant-jerk segment: the full state (including its constant jerk)
/// at its start time `t0_s` (s).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    t0_s: f64,
    state: DriveState,
}

/// Segment specification before integration: start time (s), acceleration
/// at the start (rad/s²) and constant jerk (rad/s³).
#[derive(Debug, Clone, Copy)]
struct Piece {
    t0_s: f64,
    accel_rad_s2: f64,
    jerk_rad_s3: f64,
}

impl Piece {
    const fn new(t0_s: f64, accel_rad_s2: f64, jerk_rad_s3: f64) -> Self {
        Self { t0_s, accel_rad_s2, jerk_rad_s3 }
    }
}

/// Peak magnitudes of a profile (rad/s, rad/s², rad/s³).
#[derive(Debug, Clone, Copy)]
struct Peaks {
    rate: f64,
    accel: f64,
    jerk: f64,
}

/// A validated point-to-point move.
#[derive(Debug, Clone, Copy)]
struct Move {
    start_rad: f64,
    end_rad: f64,
    duration_s: f64,
}

impl Move {
    fn new(start_rad: f64, end_rad: f64, duration_s: f64) -> Result<Self, DriveError> {
        let start_rad = require_finite("start_rad", start_rad)?;
        let end_rad = require_finite("end_rad", end_rad)?;
        let duration_s = require_positive("duration_s", duration_s)?;
        if start_rad == end_rad {
            return Err(invalid("end_rad", end_rad, "finite and different from start_rad (use `hold` for no motion)"));
        }
        if !(end_rad - start_rad).is_finite() {
            return Err(invalid("end_rad", end_rad, "such that end_rad - start_rad is finite"));
        }
        Ok(Self { start_rad, end_rad, duration_s })
    }

    /// Signed displacement `B − A`, rad.
    fn delta(&self) -> f64 {
        self.end_rad - self.start_rad
    }

    /// Displacement magnitude `|B − A|`, rad.
    fn distance(&self) -> f64 {
        self.delta().abs()
    }

    /// Direction of motion, ±1.
    fn sign(&self) -> f64 {
        self.delta().signum()
    }
}

/// Profile of prescribed hub angle versus time.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionProfile {
    kind: Kind,
    start_rad: f64,
    end_rad: f64,
    duration_s: f64,
    peak_rate_rad_s: f64,
    peak_accel_rad_s2: f64,
    peak_jerk_rad_s3: f64,
    /// Constant-jerk segments covering `[0, T/2]` (symmetric profiles only).
    first_half: Vec<Segment>,
}

impl MotionProfile {
    /// Constant rate `(B − A)/T` (rad/s) for `0 < t < T`, from `start_rad`
    /// (rad) to `end_rad` (rad) in `duration_s` (s). The rate jumps at `t = 0`
    /// and `t = T` (angle continuous only; see [`Self::rate_jumps`]).
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for non-finite angles, `start == end`
    /// or a non-positive / non-finite duration.
    pub fn uniform(start_rad: f64, end_rad: f64, duration_s: f64) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let rate = mv.delta() / mv.duration_s;
        let initial = DriveState { angle_rad: mv.start_rad, rate_rad_s: rate, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 };
        let segments = chain(initial, &[Piece::new(0.0, 0.0, 0.0)]);
        let peaks = Peaks { rate: rate.abs(), accel: 0.0, jerk: 0.0 };
        Self::assemble(Kind::Uniform, &mv, peaks, segments)
    }

    /// Acceleration-limited symmetric move from `start_rad` (rad) to `end_rad`
    /// (rad) in `duration_s` (s): constant acceleration, constant rate,
    /// constant deceleration. Rate is continuous, acceleration jumps.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for invalid move parameters, a
    /// non-positive acceleration, an acceleration below `4|B − A|/T²` (the
    /// minimum is given in `allowed`) or a ramp fraction outside `(0, 0.5]`.
    pub fn trapezoidal(
        start_rad: f64,
        end_rad: f64,
        duration_s: f64,
        limit: TrapezoidLimit,
    ) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let (t_a, accel) = match limit {
            TrapezoidLimit::AccelRadS2(accel) => (trapezoid_ramp_time(&mv, accel)?, accel),
            TrapezoidLimit::RampFraction(fraction) => {
                let t_a = require_fraction("ramp_fraction", fraction)? * mv.duration_s;
                (t_a, mv.distance() / (t_a * (mv.duration_s - t_a)))
            }
        };
        let pieces = [Piece::new(0.0, mv.sign() * accel, 0.0), Piece::new(t_a, 0.0, 0.0)];
        let segments = chain(DriveState::at_rest(mv.start_rad), &pieces);
        let peaks = Peaks { rate: mv.distance() / (mv.duration_s - t_a), accel, jerk: f64::INFINITY };
        Self::assemble(Kind::Trapezoidal, &mv, peaks, segments)
    }

    /// Jerk-limited symmetric 7-segment S-curve from `start_rad` (rad) to
    /// `end_rad` (rad) in `duration_s` (s): jerk `+J`, 0, `−J` (accel phase),
    /// cruise, then the mirror image. Acceleration is continuous, jerk is
    /// piecewise constant.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for invalid move parameters,
    /// non-positive limits, fractions outside `(0, 0.5]`, or accel/jerk limits
    /// with which the profile cannot reach `end_rad` in `duration_s` while
    /// using exactly those peaks (the bound is given in `allowed`).
    pub fn s_curve(start_rad: f64, end_rad: f64, duration_s: f64, limit: SCurveLimit) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let (t_a, t_j, accel, jerk) = s_curve_shape(&mv, limit)?;
        let (signed_accel, signed_jerk) = (mv.sign() * accel, mv.sign() * jerk);
        let pieces = [
            Piece::new(0.0, 0.0, signed_jerk),
            Piece::new(t_j, signed_accel, 0.0),
            Piece::new(t_a - t_j, signed_accel, -signed_jerk),
            Piece::new(t_a, 0.0, 0.0),
        ];
        let segments = chain(DriveState::at_rest(mv.start_rad), &pieces);
        let peaks = Peaks { rate: mv.distance() / (mv.duration_s - t_a), accel, jerk };
        Self::assemble(Kind::SCurve, &mv, peaks, segments)
    }

    /// Hold at `angle_rad` (rad) forever, at rest.
    pub fn hold(angle_rad: f64) -> Self {
        Self {
            kind: Kind::Hold,
            start_rad: angle_rad,
            end_rad: angle_rad,
            duration_s: 0.0,
            peak_rate_rad_s: 0.0,
            peak_accel_rad_s2: 0.0,
            peak_jerk_rad_s3: 0.0,
            first_half: Vec::new(),
        }
    }

    /// Kane–Ryan–Banerjee spin-up to `final_rate_rad_s` (rad/s, `w`) over
    /// `ramp_time_s` (s, `Ts`), offset by `start_rad` (rad):
    /// `θ(t) = A + (w/Ts)[t²/2 + (Ts/2π)²(cos(2πt/Ts) − 1)]` for `0 ≤ t ≤ Ts`,
    /// `θ(t) = A + w(t − Ts/2)` after (constant rate `w` forever).
    /// Angle, rate, acceleration and jerk are all continuous.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for a non-finite start angle or final
    /// rate, or a non-positive / non-finite ramp time.
    pub fn spin_up(start_rad: f64, final_rate_rad_s: f64, ramp_time_s: f64) -> Result<Self, DriveError> {
        let start_rad = require_finite("start_rad", start_rad)?;
        let rate = require_finite("final_rate_rad_s", final_rate_rad_s)?;
        let ramp = require_positive("ramp_time_s", ramp_time_s)?;
        let end_rad = start_rad + 0.5 * rate * ramp;
        let peak_accel = 2.0 * rate.abs() / ramp;
        let peak_jerk = 2.0 * PI * rate.abs() / (ramp * ramp);
        if !(end_rad.is_finite() && peak_accel.is_finite() && peak_jerk.is_finite()) {
            return Err(invalid("ramp_time_s", ramp, "such that the end angle, peak accel and peak jerk are finite"));
        }
        Ok(Self {
            kind: Kind::SpinUp { final_rate_rad_s: rate },
            start_rad,
            end_rad,
            duration_s: ramp,
            peak_rate_rad_s: rate.abs(),
            peak_accel_rad_s2: peak_accel,
            peak_jerk_rad_s3: peak_jerk,
            first_half: Vec::new(),
        })
    }

    /// Exact state at time `t_s` (s; 0 = start of motion). At a discontinuity
    /// the value just after `t_s` is returned.
    pub fn sample(&self, t_s: f64) -> DriveState {
        if let Kind::SpinUp { final_rate_rad_s } = self.kind {
            return self.sample_spin_up(final_rate_rad_s, t_s);
        }
        if t_s < 0.0 {
            DriveState::at_rest(self.start_rad)
        } else if t_s >= self.duration_s {
            DriveState::at_rest(self.end_rad)
        } else if t_s < 0.5 * self.duration_s {
            self.first_half_state(t_s, true)
        } else {
            self.first_half_state(self.duration_s - t_s, false).point_mirrored(self.start_rad + self.end_rad)
        }
    }

    /// Instants where the rate jumps (uniform profile only), as
    /// `(time s, jump in rate rad/s)`; empty for every other profile.
    /// [`Self::sample`] returns the rate just after each instant.
    pub fn rate_jumps(&self) -> Vec<(f64, f64)> {
        match self.kind {
            Kind::Uniform => {
                let rate = (self.end_rad - self.start_rad) / self.duration_s;
                vec![(0.0, rate), (self.duration_s, -rate)]
            }
            _ => Vec::new(),
        }
    }

    /// Instants inside the motion where its acceleration or jerk jumps (the ends of its
    /// constant-jerk pieces; the end of a spin-up's ramp), s, in order. A time step that
    /// straddles one integrates across a kink of the load; fixed steps that divide the pieces land
    /// on them, a controlled step is cut to end there.
    pub fn breakpoints_s(&self) -> Vec<f64> {
        let half = 0.5 * self.duration_s;
        let inner: Vec<f64> = self.first_half.iter().map(|s| s.t0_s).filter(|&t| t > 0.0 && t < half).collect();
        let mirrored = inner.iter().rev().map(|t| self.duration_s - t);
        let end = (self.duration_s > 0.0).then_some(self.duration_s);
        inner.iter().copied().chain(mirrored).chain(end).collect()
    }

    /// Angle at `t = 0`, rad.
    pub fn start_rad(&self) -> f64 {
        self.start_rad
    }

    /// Angle at `t = duration_s()`, rad (for spin-up `A + w Ts/2`; for hold the
    /// held angle).
    pub fn end_rad(&self) -> f64 {
        self.end_rad
    }

    /// Duration of the motion, s (ramp time for spin-up, 0 for hold).
    pub fn duration_s(&self) -> f64 {
        self.duration_s
    }

    /// Peak rate magnitude, rad/s (0 for hold, `|w|` for spin-up).
    pub fn peak_rate_rad_s(&self) -> f64 {
        self.peak_rate_rad_s
    }

    /// Peak acceleration magnitude, rad/s² (0 for uniform, whose rate jumps
    /// are impulses, and for hold).
    pub fn peak_accel_rad_s2(&self) -> f64 {
        self.peak_accel_rad_s2
    }

    /// Peak jerk magnitude, rad/s³: finite for s-curve and spin-up,
    /// `f64::INFINITY` for trapezoidal (acceleration steps), 0 for uniform
    /// and hold.
    pub fn peak_jerk_rad_s3(&self) -> f64 {
        self.peak_jerk_rad_s3
    }

    /// Profile name: `"uniform"`, `"trapezoidal"`, `"s-curve"`, `"hold"` or
    /// `"spin-up"`.
    pub fn name(&self) -> &'static str {
        match self.kind {
            Kind::Uniform => "uniform",
            Kind::Trapezoidal => "trapezoidal",
            Kind::SCurve => "s-curve",
            Kind::Hold => "hold",
            Kind::SpinUp { .. } => "spin-up",
        }
    }

    /// Builds a symmetric profile and checks that its first half really
    /// reaches the midpoint angle (guards against degenerate extreme inputs).
    fn assemble(kind: Kind, mv: &Move, peaks: Peaks, first_half: Vec<Segment>) -> Result<Self, DriveError> {
        let jerk_ok = peaks.jerk.is_finite() || kind == Kind::Trapezoidal;
        if !(peaks.rate.is_finite() && peaks.accel.is_finite() && jerk_ok) {
            return Err(invalid(
                "duration_s",
                mv.duration_s,
                "long enough that the peak rate, accel and jerk are finite",
            ));
        }
        let profile = Self {
            kind,
            start_rad: mv.start_rad,
            end_rad: mv.end_rad,
            duration_s: mv.duration_s,
            peak_rate_rad_s: peaks.rate,
            peak_accel_rad_s2: peaks.accel,
            peak_jerk_rad_s3: peaks.jerk,
            first_half,
        };
        profile.check_midpoint()?;
        Ok(profile)
    }

    /// Verifies that the first half ends at `(A + B)/2` at `T/2`.
    fn check_midpoint(&self) -> Result<(), DriveError> {
        let mid = self.start_rad.midpoint(self.end_rad);
        let reached = self.first_half_state(0.5 * self.duration_s, false).angle_rad;
        let tol = 1e-9 * (self.end_rad - self.start_rad).abs()
            + 8.0 * f64::EPSILON * (self.start_rad.abs() + self.end_rad.abs());
        if (reached - mid).abs() <= tol {
            Ok(())
        } else {
            Err(invalid(
                "duration_s",
                self.duration_s,
                "a value for which the requested limits give a numerically representable profile",
            ))
        }
    }

    /// State at `s` (s) in `[0, T/2]` from the precomputed segments. With
    /// `right_limit` a segment boundary belongs to the later segment,
    /// otherwise to the earlier one (used for the mirrored half, where time
    /// runs backwards).
    fn first_half_state(&self, s: f64, right_limit: bool) -> DriveState {
        let after = if right_limit {
            self.first_half.partition_point(|seg| seg.t0_s <= s)
        } else {
            self.first_half.partition_point(|seg| seg.t0_s < s)
        };
        match self.first_half.get(after.saturating_sub(1)) {
            Some(seg) => seg.state.advanced(s - seg.t0_s),
            None => DriveState::at_rest(self.start_rad),
        }
    }

    /// Kane–Ryan–Banerjee spin-up state at `t_s` (s) for final rate
    /// `rate` (rad/s).
    fn sample_spin_up(&self, rate: f64, t_s: f64) -> DriveState {
        let ramp = self.duration_s;
        if t_s < 0.0 {
            return DriveState::at_rest(self.start_rad);
        }
        if t_s >= ramp {
            return DriveState {
                angle_rad: self.start_rad + rate * (t_s - 0.5 * ramp),
                rate_rad_s: rate,
                accel_rad_s2: 0.0,
                jerk_rad_s3: 0.0,
            };
        }
        let k = rate / ramp;
        let omega = 2.0 * PI / ramp;
        let (sin, cos) = (omega * t_s).sin_cos();
        DriveState {
            angle_rad: self.start_rad + k * (0.5 * t_s * t_s + (cos - 1.0) / (omega * omega)),
            rate_rad_s: k * (t_s - sin / omega),
            accel_rad_s2: k * (1.0 - cos),
            jerk_rad_s3: k * omega * sin,
        }
    }
}

/// Integrates constant-jerk pieces from `initial` (at `t = 0`): each piece
/// starts from the state reached at its start time, with its own acceleration
/// and jerk imposed exactly.
fn chain(initial: DriveState, pieces: &[Piece]) -> Vec<Segment> {
    let mut segments = Vec::with_capacity(pieces.len());
    let mut current = Segment { t0_s: 0.0, state: initial };
    for piece in pieces {
        let reached = current.state.advanced(piece.t0_s - current.t0_s);
        current = Segment {
            t0_s: piece.t0_s,
            state: DriveState { accel_rad_s2: piece.accel_rad_s2, jerk_rad_s3: piece.jerk_rad_s3, ..reached },
        };
        segments.push(current);
    }
    segments
}

/// Accel-phase length `t_a` (s) of a trapezoid with acceleration `accel`
/// (rad/s²): smaller root of `a t (T − t) = |Δ|`.
fn trapezoid_ramp_time(mv: &Move, accel: f64) -> Result<f64, DriveError> {
    let accel = require_positive("accel_rad_s2", accel)?;
    let t = mv.duration_s;
    let accel_min = 4.0 * mv.distance() / (t * t);
    if accel < accel_min * (1.0 - FEASIBILITY_SLACK) {
        return Err(invalid(
            "accel_rad_s2",
            accel,
            format!(
                ">= {accel_min:e} rad/s^2 (4|end_rad - start_rad|/duration_s^2, \
                 the minimum to reach end_rad within duration_s)"
            ),
        ));
    }
    let d = mv.distance() / accel;
    let root = (t * t - 4.0 * d).max(0.0).sqrt();
    // Stable form of (T − sqrt(T² − 4d))/2.
    Ok((2.0 * d / (t + root)).min(0.5 * t))
}

/// S-curve shape `(t_a s, t_j s, peak accel rad/s², peak jerk rad/s³)`.
fn s_curve_shape(mv: &Move, limit: SCurveLimit) -> Result<(f64, f64, f64, f64), DriveError> {
    match limit {
        SCurveLimit::AccelJerk { accel_rad_s2, jerk_rad_s3 } => {
            let accel = require_positive("accel_rad_s2", accel_rad_s2)?;
            let jerk = require_positive("jerk_rad_s3", jerk_rad_s3)?;
            let (t_a, t_j) = s_curve_times(mv, accel, jerk)?;
            Ok((t_a, t_j, accel, jerk))
        }
        SCurveLimit::Fractions { ramp_fraction, jerk_fraction } => {
            let t_a = require_fraction("ramp_fraction", ramp_fraction)? * mv.duration_s;
            let t_j = require_fraction("jerk_fraction", jerk_fraction)? * t_a;
            let accel = mv.distance() / ((t_a - t_j) * (mv.duration_s - t_a));
            Ok((t_a, t_j, accel, accel / t_j))
        }
    }
}

/// Accel-phase length `t_a` and jerk time `t_j = a/j` (both s) of an S-curve
/// using exactly the peaks `accel` (rad/s²) and `jerk` (rad/s³): smaller root
/// of `(t_a − t_j)(T − t_a) = |Δ|/a`, required in `[2 t_j, T/2]`.
fn s_curve_times(mv: &Move, accel: f64, jerk: f64) -> Result<(f64, f64), DriveError> {
    let (t, dist) = (mv.duration_s, mv.distance());
    let jerk_min = 32.0 * dist / (t * t * t);
    if jerk < jerk_min * (1.0 - FEASIBILITY_SLACK) {
        return Err(invalid(
            "jerk_rad_s3",
            jerk,
            format!(
                ">= {jerk_min:e} rad/s^3 (32|end_rad - start_rad|/duration_s^3, \
                 the minimum to reach end_rad within duration_s with any accel)"
            ),
        ));
    }
    let d = dist / accel;
    let t_j = accel / jerk;
    let t_j_max = max_jerk_time(t, d);
    if t_j > t_j_max * (1.0 + FEASIBILITY_SLACK) {
        let jerk_needed = accel / t_j_max;
        return Err(invalid(
            "jerk_rad_s3",
            jerk,
            format!(
                ">= {jerk_needed:e} rad/s^3 for accel_rad_s2 = {accel:e}: the two jerk ramps \
                 (accel/jerk each) must fit in the accel phase so that the accel peak is reached"
            ),
        ));
    }
    if d > (0.5 * t - t_j) * 0.5 * t * (1.0 + FEASIBILITY_SLACK) {
        let accel_min = min_s_curve_accel(t, dist, jerk);
        return Err(invalid(
            "accel_rad_s2",
            accel,
            format!(
                ">= {accel_min:e} rad/s^2 for jerk_rad_s3 = {jerk:e}, \
                 the minimum to reach end_rad within duration_s"
            ),
        ));
    }
    let sum = t + t_j;
    let product = t_j * t + d;
    // Stable form of [(T + t_j) − sqrt((T + t_j)² − 4(t_j T + d))]/2.
    let t_a = 2.0 * product / (sum + (sum * sum - 4.0 * product).max(0.0).sqrt());
    let t_a = t_a.max(2.0 * t_j).min(0.5 * t);
    Ok((t_a, t_j.min(0.5 * t_a)))
}

/// Largest jerk time `t_j` (s) for which the accel peak is reached within a
/// move of duration `t` (s) and `d = |Δ|/a` (s²): `t_j (T − 2 t_j) ≤ d`,
/// `t_j ≤ T/4`.
fn max_jerk_time(t: f64, d: f64) -> f64 {
    let disc = t * t - 8.0 * d;
    if disc >= 0.0 {
        // Stable form of (T − sqrt(T² − 8d))/4.
        2.0 * d / (t + disc.sqrt())
    } else {
        0.25 * t
    }
}

/// Smallest accel (rad/s²) that reaches distance `dist` (rad) in `t` (s)
/// with jerk `jerk` (rad/s³): smaller root of `a² − (jT/2) a + 2 j |Δ|/T = 0`.
fn min_s_curve_accel(t: f64, dist: f64, jerk: f64) -> f64 {
    let half_sum = 0.25 * jerk * t;
    let product = 2.0 * jerk * dist / t;
    let larger = half_sum + (half_sum * half_sum - product).max(0.0).sqrt();
    product / larger
}

fn invalid(name: &'static str, value: f64, allowed: impl Into<String>) -> DriveError {
    DriveError::InvalidParameter { name, value, allowed: allowed.into() }
}

fn require_finite(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value.is_finite() { Ok(value) } else { Err(invalid(name, value, "any finite value")) }
}

fn require_positive(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(invalid(name, value, "finite and > 0")) }
}

fn require_fraction(name: &'static str, value: f64) -> Result<f64, DriveError> {
    if value > 0.0 && value <= 0.5 { Ok(value) } else { Err(invalid(name, value, "in (0, 0.5]")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    const START: f64 = 0.25;
    const END: f64 = 1.75;
    const DUR: f64 = 2.0;

    fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
        assert!((actual - expected).abs() <= tol, "{what}: got {actual}, expected {expected} (tol {tol})");
    }

    /// Between breakpoints the jerk is constant (a kink-free piece); at each breakpoint the
    /// acceleration or the jerk changes.
    #[test]
    fn breakpoints_are_where_the_pieces_change() {
        let trapezoid = MotionProfile::trapezoidal(0.0, 1.5, 15.0, TrapezoidLimit::RampFraction(0.2)).unwrap();
        let expected = [3.0, 12.0, 15.0];
        let found = trapezoid.breakpoints_s();
        assert_eq!(found.len(), 3);
        found.iter().zip(expected).for_each(|(f, e)| assert_close(*f, e, 1e-12, "trapezoid breakpoint"));
        let limit = SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.25 };
        let s_curve = MotionProfile::s_curve(START, END, DUR, limit).unwrap();
        for p in [trapezoid, s_curve] {
            let points = p.breakpoints_s();
            let bounds: Vec<f64> = std::iter::once(0.0).chain(points.iter().copied()).collect();
            for window in bounds.windows(2) {
                let (a, b) = (window[0], window[1]);
                let jerks: Vec<f64> =
                    (1..10).map(|k| p.sample(a + (b - a) * f64::from(k) / 10.0).jerk_rad_s3).collect();
                assert!(jerks.iter().all(|j| (j - jerks[0]).abs() < 1e-9), "jerk varies in ({a}, {b})");
            }
            for &b in &points[..points.len() - 1] {
                let (before, after) = (p.sample(b - 1e-9), p.sample(b + 1e-9));
                let changed = (before.jerk_rad_s3 - after.jerk_rad_s3).abs() > 1e-6
                    || (before.accel_rad_s2 - after.accel_rad_s2).abs() > 1e-6;
                assert!(changed, "nothing changes at {b}");
            }
        }
    }

    /// `n + 1` evenly spaced times over `[-0.05 T, 1.05 T]`.
    fn dense_times(duration: f64, n: u32) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| duration * (-0.05 + 1.1 * f64::from(i) / f64::from(n)))
    }

    fn err_name(result: Result<MotionProfile, DriveError>) -> &'static str {
        match result {
            Err(DriveError::InvalidParameter { name, .. }) => name,
            Ok(p) => panic!("expected an error, got {p:?}"),
        }
    }

    /// Parses the bound `x` out of an `allowed` text of the form ">= x ...".
    fn allowed_bound(result: Result<MotionProfile, DriveError>) -> f64 {
        match result {
            Err(DriveError::InvalidParameter { allowed, .. }) => {
                allowed.split_whitespace().nth(1).and_then(|s| s.parse().ok()).unwrap_or(f64::NAN)
            }
            Ok(p) => panic!("expected an error, got {p:?}"),
        }
    }

    /// Start at `start` with rate `start_rate`, exact end at `end` at rest,
    /// holds outside `[0, T]`; the left limit at T must approach the end
    /// (at rest unless the profile starts moving, i.e. uniform).
    fn check_ends(p: &MotionProfile, start: f64, end: f64, duration: f64, start_rate: f64) {
        let dist = (end - start).abs();
        let s0 = p.sample(0.0);
        assert_close(s0.angle_rad, start, 1e-12 * dist, "angle at 0");
        assert_close(s0.rate_rad_s, start_rate, 1e-12 * dist / duration, "rate at 0");
        let before = p.sample(-0.5 * duration);
        assert_eq!(before.angle_rad, start);
        assert_eq!(before.rate_rad_s, 0.0);
        let at_end = p.sample(duration);
        assert!((at_end.angle_rad - end).abs() < 1e-12 * dist, "end angle");
        assert_eq!(at_end.rate_rad_s, 0.0);
        assert_eq!(at_end.accel_rad_s2, 0.0);
        let after = p.sample(1.5 * duration);
        assert_eq!(after.angle_rad, at_end.angle_rad);
        assert_eq!(after.rate_rad_s, 0.0);
        let near = p.sample(duration * (1.0 - 1e-9));
        assert_close(near.angle_rad, end, 1e-8 * dist, "angle just before T");
        if start_rate == 0.0 {
            assert_close(near.rate_rad_s, 0.0, 1e-6 * dist / duration, "rate just before T");
        }
        assert_close(p.end_rad(), end, 0.0, "end_rad()");
        assert_close(p.start_rad(), start, 0.0, "start_rad()");
        assert_close(p.duration_s(), duration, 0.0, "duration_s()");
    }

    /// The first half must end at the midpoint with the expected peak rate
    /// (this is where the forward integration is checked; the second half is
    /// its mirror).
    fn check_midpoint(p: &MotionProfile, start: f64, end: f64, duration: f64, peak_rate: f64) {
        let dist = (end - start).abs();
        let mid = 0.5 * (start + end);
        let dt = 1e-9 * duration;
        let expected = mid - (end - start).signum() * peak_rate * dt;
        assert_close(p.sample(0.5 * duration).angle_rad, mid, 1e-12 * dist, "angle at T/2");
        assert_close(p.sample(0.5 * duration - dt).angle_rad, expected, 1e-11 * dist, "angle just before T/2");
    }

    /// Central differences of angle, rate and accel against rate, accel and
    /// jerk, at points at least 4h away from `boundaries`.
    fn check_derivatives(p: &MotionProfile, t_end: f64, boundaries: &[f64], scales: [f64; 3]) {
        let h = 1e-5 * t_end;
        let n = 1000_u32;
        for i in 1..n {
            let t = t_end * f64::from(i) / f64::from(n);
            if boundaries.iter().any(|b| (t - b).abs() < 4.0 * h) {
                continue;
            }
            let (lo, mid, hi) = (p.sample(t - h), p.sample(t), p.sample(t + h));
            let numeric = [
                (hi.angle_rad - lo.angle_rad) / (2.0 * h),
                (hi.rate_rad_s - lo.rate_rad_s) / (2.0 * h),
                (hi.accel_rad_s2 - lo.accel_rad_s2) / (2.0 * h),
            ];
            let analytic = [mid.rate_rad_s, mid.accel_rad_s2, mid.jerk_rad_s3];
            let labels = ["rate", "accel", "jerk"];
            for ((num, ana), (scale, label)) in numeric.iter().zip(analytic).zip(scales.iter().zip(labels)) {
                assert_close(*num, ana, 1e-6 * scale, &format!("{label} at t = {t}"));
            }
        }
    }

    /// `down` must be `up` reflected about `pivot` (angles) at every time.
    fn check_mirror(up: &MotionProfile, down: &MotionProfile, pivot: f64, t_end: f64) {
        for t in dense_times(t_end, 4000) {
            let (u, d) = (up.sample(t), down.sample(t));
            let tol = 1e-12 * (1.0 + pivot.abs() + u.angle_rad.abs());
            assert_close(d.angle_rad - pivot, -(u.angle_rad - pivot), tol, "mirrored angle");
            let tol_of = |x: f64| 1e-12 * (1.0 + x.abs());
            assert_close(d.rate_rad_s, -u.rate_rad_s, tol_of(u.rate_rad_s), "mirrored rate");
            assert_close(d.accel_rad_s2, -u.accel_rad_s2, tol_of(u.accel_rad_s2), "mirrored accel");
            assert_close(d.jerk_rad_s3, -u.jerk_rad_s3, tol_of(u.jerk_rad_s3), "mirrored jerk");
        }
    }

    fn max_abs(p: &MotionProfile, duration: f64, pick: fn(&DriveState) -> f64) -> f64 {
        dense_times(duration, 100_000).map(|t| pick(&p.sample(t)).abs()).fold(0.0_f64, f64::max)
    }

    #[test]
    fn uniform_is_linear_with_rate_jumps() {
        let p = MotionProfile::uniform(START, END, DUR).expect("valid uniform");
        let rate = (END - START) / DUR;
        check_ends(&p, START, END, DUR, rate);
        check_midpoint(&p, START, END, DUR, rate);
        for i in 0..=100_u32 {
            let t = DUR * f64::from(i) / 100.0;
            let s = p.sample(t);
            let expected = if i == 100 { END } else { START + rate * t };
            assert_close(s.angle_rad, expected, 1e-12, "linear angle");
            if i < 100 {
                assert_close(s.rate_rad_s, rate, 1e-12, "uniform rate");
                assert_eq!(s.accel_rad_s2, 0.0);
            }
        }
        assert_eq!(p.rate_jumps(), vec![(0.0, rate), (DUR, -rate)]);
        assert_close(p.peak_rate_rad_s(), rate, 1e-15, "peak rate");
        assert_eq!(p.peak_accel_rad_s2(), 0.0);
        assert_eq!(p.peak_jerk_rad_s3(), 0.0);
        assert_eq!(p.name(), "uniform");
    }

    #[test]
    fn trapezoid_with_accel_limit() {
        let accel = 2.5;
        let p =
            MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::AccelRadS2(accel)).expect("valid trapezoid");
        let dist = END - START;
        let t_a = (DUR - (DUR * DUR - 4.0 * dist / accel).sqrt()) / 2.0;
        let peak = dist / (DUR - t_a);
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, peak);
        assert_eq!(p.peak_accel_rad_s2(), accel);
        assert!(p.peak_jerk_rad_s3().is_infinite());
        assert_close(p.peak_rate_rad_s(), peak, 1e-12 * peak, "peak rate");
        assert_close(p.sample(t_a).rate_rad_s, peak, 1e-12 * peak, "rate at t_a");
        assert_eq!(p.sample(0.5 * t_a).accel_rad_s2, accel);
        assert_eq!(p.sample(DUR - 0.5 * t_a).accel_rad_s2, -accel);
        assert_eq!(p.sample(0.5 * DUR).accel_rad_s2, 0.0);
        assert_eq!(max_abs(&p, DUR, |s| s.accel_rad_s2), accel);
        let boundaries = [0.0, t_a, 0.5 * DUR, DUR - t_a, DUR];
        check_derivatives(&p, DUR, &boundaries, [peak, accel, accel / DUR]);
        assert_eq!(p.name(), "trapezoidal");
    }

    #[test]
    fn trapezoid_with_ramp_fraction() {
        let fraction = 0.25;
        let p = MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::RampFraction(fraction))
            .expect("valid trapezoid");
        let t_a = fraction * DUR;
        let peak = (END - START) / (DUR - t_a);
        let accel = peak / t_a;
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, peak);
        assert_close(p.sample(t_a).rate_rad_s, peak, 1e-12 * peak, "rate at f T");
        assert!(p.sample(t_a * (1.0 - 1e-6)).rate_rad_s < peak);
        assert_close(p.sample(t_a * (1.0 - 1e-6)).accel_rad_s2, accel, 1e-12 * accel, "accel");
        assert_eq!(p.sample(t_a * (1.0 + 1e-6)).accel_rad_s2, 0.0);
        assert_close(p.peak_accel_rad_s2(), accel, 1e-12 * accel, "peak accel");
        assert!(max_abs(&p, DUR, |s| s.accel_rad_s2) <= accel * (1.0 + 1e-12));
        let boundaries = [0.0, t_a, 0.5 * DUR, DUR - t_a, DUR];
        check_derivatives(&p, DUR, &boundaries, [peak, accel, accel / DUR]);
    }

    #[test]
    fn trapezoid_at_minimum_accel_is_triangular() {
        let dist = END - START;
        let accel = 4.0 * dist / (DUR * DUR);
        let p = MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::AccelRadS2(accel))
            .expect("minimum accel is feasible");
        let peak = 2.0 * dist / DUR;
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, peak);
        let triangle =
            MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::RampFraction(0.5)).expect("triangle");
        check_ends(&triangle, START, END, DUR, 0.0);
        check_midpoint(&triangle, START, END, DUR, peak);
        assert_eq!(triangle.sample(0.5 * DUR).accel_rad_s2, -accel);
    }

    /// Dense checks of an S-curve against its limits `accel`, `jerk`.
    fn check_s_curve_limits(p: &MotionProfile, accel: f64, jerk: f64) {
        let n = 200_000_u32;
        let dt = 1.1 * DUR / f64::from(n);
        let mut previous: Option<f64> = None;
        for t in dense_times(DUR, n) {
            let s = p.sample(t);
            assert!(s.accel_rad_s2.abs() <= accel * (1.0 + 1e-9), "accel at {t}");
            assert!(s.jerk_rad_s3.abs() <= jerk * (1.0 + 1e-9), "jerk at {t}");
            if let Some(prev) = previous {
                let step = (s.accel_rad_s2 - prev).abs();
                assert!(step <= jerk * dt * (1.0 + 1e-9) + 1e-12 * accel, "accel jump at {t}");
            }
            previous = Some(s.accel_rad_s2);
        }
        // The grid of `max_abs` may miss an isolated peak by half a step.
        let grid = 1.1 * DUR / 100_000.0;
        let reached = max_abs(p, DUR, |s| s.accel_rad_s2);
        assert!(reached >= accel - jerk * grid, "peak accel reached: {reached} vs {accel}");
    }

    #[test]
    fn s_curve_with_accel_and_jerk_limits() {
        let (accel, jerk) = (2.5, 20.0);
        let limit = SCurveLimit::AccelJerk { accel_rad_s2: accel, jerk_rad_s3: jerk };
        let p = MotionProfile::s_curve(START, END, DUR, limit).expect("valid s-curve");
        let dist = END - START;
        let t_j = accel / jerk;
        let sum = DUR + t_j;
        let t_a = (sum - (sum * sum - 4.0 * (t_j * DUR + dist / accel)).sqrt()) / 2.0;
        let peak = dist / (DUR - t_a);
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, peak);
        check_s_curve_limits(&p, accel, jerk);
        assert_eq!(p.peak_accel_rad_s2(), accel);
        assert_eq!(p.peak_jerk_rad_s3(), jerk);
        assert_close(p.peak_rate_rad_s(), peak, 1e-12 * peak, "peak rate");
        assert_close(p.sample(t_a).rate_rad_s, peak, 1e-10 * peak, "rate at t_a");
        assert_close(p.sample(0.5 * t_a).accel_rad_s2, accel, 1e-12 * accel, "const accel");
        assert_eq!(p.sample(0.5 * t_j).jerk_rad_s3, jerk);
        assert_eq!(p.sample(DUR - 0.5 * t_j).jerk_rad_s3, jerk);
        assert_eq!(p.sample(DUR - t_a + 0.5 * t_j).jerk_rad_s3, -jerk);
        let boundaries = [0.0, t_j, t_a - t_j, t_a, 0.5 * DUR, DUR - t_a, DUR - t_a + t_j, DUR - t_j, DUR];
        check_derivatives(&p, DUR, &boundaries, [peak, accel, jerk]);
        assert_eq!(p.name(), "s-curve");
    }

    #[test]
    fn s_curve_with_fractions() {
        let (ramp, jerk_fraction) = (0.4, 0.25);
        let limit = SCurveLimit::Fractions { ramp_fraction: ramp, jerk_fraction };
        let p = MotionProfile::s_curve(START, END, DUR, limit).expect("valid s-curve");
        let t_a = ramp * DUR;
        let t_j = jerk_fraction * t_a;
        let accel = (END - START) / ((t_a - t_j) * (DUR - t_a));
        let jerk = accel / t_j;
        let peak = (END - START) / (DUR - t_a);
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, peak);
        check_s_curve_limits(&p, accel, jerk);
        assert_close(p.sample(t_a).rate_rad_s, peak, 1e-12 * peak, "rate at t_a");
        let boundaries = [0.0, t_j, t_a - t_j, t_a, 0.5 * DUR, DUR - t_a, DUR - t_a + t_j, DUR - t_j, DUR];
        check_derivatives(&p, DUR, &boundaries, [peak, accel, jerk]);
    }

    #[test]
    fn pure_jerk_s_curve_needs_minimum_jerk() {
        let limit = SCurveLimit::Fractions { ramp_fraction: 0.5, jerk_fraction: 0.5 };
        let p = MotionProfile::s_curve(START, END, DUR, limit).expect("valid s-curve");
        let dist = END - START;
        let jerk_min = 32.0 * dist / (DUR * DUR * DUR);
        let accel = jerk_min * DUR / 4.0;
        check_ends(&p, START, END, DUR, 0.0);
        check_midpoint(&p, START, END, DUR, 2.0 * dist / DUR);
        check_s_curve_limits(&p, accel, jerk_min);
        assert_close(p.peak_jerk_rad_s3(), jerk_min, 1e-12 * jerk_min, "peak jerk");
        assert_close(p.sample(0.25 * DUR).accel_rad_s2, accel, 1e-12 * accel, "accel at T/4");
    }

    #[test]
    fn s_curve_feasibility_bounds_are_reported_and_tight() {
        let dist = END - START;
        // Jerk too small for any accel: j >= 32|Δ|/T³.
        let too_little_jerk = SCurveLimit::AccelJerk { accel_rad_s2: 2.5, jerk_rad_s3: 5.0 };
        let jerk_min = 32.0 * dist / DUR.powi(3);
        let bound = allowed_bound(MotionProfile::s_curve(START, END, DUR, too_little_jerk));
        assert_close(bound, jerk_min, 1e-12 * jerk_min, "minimum jerk");

        // Accel too small for this jerk.
        let jerk = 100.0;
        let accel_min = jerk * (DUR / 2.0 - (DUR * DUR / 4.0 - 8.0 * dist / (jerk * DUR)).sqrt()) / 2.0;
        let low = SCurveLimit::AccelJerk { accel_rad_s2: 1.4, jerk_rad_s3: jerk };
        let bound = allowed_bound(MotionProfile::s_curve(START, END, DUR, low));
        assert_close(bound, accel_min, 1e-9 * accel_min, "minimum accel");
        let just_enough = SCurveLimit::AccelJerk { accel_rad_s2: accel_min * (1.0 + 1e-6), jerk_rad_s3: jerk };
        let p = MotionProfile::s_curve(START, END, DUR, just_enough).expect("feasible");
        check_ends(&p, START, END, DUR, 0.0);
        assert_close(p.peak_rate_rad_s(), 2.0 * dist / DUR, 1e-3, "near-triangular peak rate");

        // Accel so large that the jerk ramps do not fit: j >= a / t_j,max.
        let accel = 100.0;
        let t_j_max = (DUR - (DUR * DUR - 8.0 * dist / accel).sqrt()) / 4.0;
        let jerk_needed = accel / t_j_max;
        let short = SCurveLimit::AccelJerk { accel_rad_s2: accel, jerk_rad_s3: 200.0 };
        let bound = allowed_bound(MotionProfile::s_curve(START, END, DUR, short));
        assert_close(bound, jerk_needed, 1e-9 * jerk_needed, "jerk to reach accel");
        let fits = SCurveLimit::AccelJerk { accel_rad_s2: accel, jerk_rad_s3: jerk_needed * (1.0 + 1e-6) };
        let p = MotionProfile::s_curve(START, END, DUR, fits).expect("feasible");
        check_ends(&p, START, END, DUR, 0.0);
        let t_j = accel / (jerk_needed * (1.0 + 1e-6));
        assert_close(p.sample(t_j).accel_rad_s2, accel, 1e-9 * accel, "accel peak reached");
    }

    #[test]
    fn trapezoid_minimum_accel_is_reported() {
        let result = MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::AccelRadS2(1.0));
        let expected = 4.0 * (END - START) / (DUR * DUR);
        assert_close(allowed_bound(result), expected, 1e-12 * expected, "minimum accel");
    }

    #[test]
    fn spin_up_closed_form() {
        let (start, rate, ramp) = (0.4, 3.0, 1.5);
        let p = MotionProfile::spin_up(start, rate, ramp).expect("valid spin-up");
        let s0 = p.sample(0.0);
        assert_eq!((s0.angle_rad, s0.rate_rad_s, s0.accel_rad_s2), (start, 0.0, 0.0));
        let before = p.sample(-1.0);
        assert_eq!((before.angle_rad, before.rate_rad_s), (start, 0.0));
        // Half way: θ = w Ts/8 − w Ts/(2π²), rate w/2, accel 2w/Ts (peak).
        let half = p.sample(0.5 * ramp);
        let expected = start + rate * ramp / 8.0 - rate * ramp / (2.0 * PI * PI);
        assert_close(half.angle_rad, expected, 1e-12, "angle at Ts/2");
        assert_close(half.rate_rad_s, 0.5 * rate, 1e-12, "rate at Ts/2");
        assert_close(half.accel_rad_s2, 2.0 * rate / ramp, 1e-12, "accel at Ts/2");
        // At and just before Ts.
        let at = p.sample(ramp);
        assert_close(at.angle_rad, start + 0.5 * rate * ramp, 1e-12, "angle at Ts");
        assert_eq!((at.rate_rad_s, at.accel_rad_s2), (rate, 0.0));
        let near = p.sample(ramp * (1.0 - 1e-9));
        assert_close(near.angle_rad, start + 0.5 * rate * ramp, 1e-8, "angle before Ts");
        assert_close(near.rate_rad_s, rate, 1e-8 * rate, "rate before Ts");
        assert_close(near.accel_rad_s2, 0.0, 1e-6 * rate / ramp, "accel before Ts");
        assert_close(near.jerk_rad_s3, 0.0, 1e-6 * rate / (ramp * ramp), "jerk before Ts");
        let later = p.sample(ramp + 2.0);
        assert_close(later.angle_rad, start + rate * (ramp + 2.0 - 0.5 * ramp), 1e-12, "cruise");
        assert_eq!(later.rate_rad_s, rate);
        assert_close(p.end_rad(), start + 0.5 * rate * ramp, 1e-12, "end_rad()");
        assert_eq!(p.duration_s(), ramp);
        assert_eq!(p.peak_rate_rad_s(), rate);
        assert_close(p.peak_accel_rad_s2(), 2.0 * rate / ramp, 1e-12, "peak accel");
        let jerk = 2.0 * PI * rate / (ramp * ramp);
        assert_close(p.peak_jerk_rad_s3(), jerk, 1e-12 * jerk, "peak jerk");
        assert!(p.rate_jumps().is_empty());
        let scales = [rate, 2.0 * rate / ramp, jerk];
        check_derivatives(&p, 1.5 * ramp, &[0.0, ramp], scales);
        assert_eq!(p.name(), "spin-up");
    }

    #[test]
    fn hold_stays_put() {
        let p = MotionProfile::hold(0.7);
        for t in [-1.0, 0.0, 0.5, 100.0] {
            assert_eq!(p.sample(t), DriveState::at_rest(0.7));
        }
        assert_eq!((p.start_rad(), p.end_rad(), p.duration_s()), (0.7, 0.7, 0.0));
        assert_eq!(p.peak_rate_rad_s(), 0.0);
        assert_eq!(p.peak_jerk_rad_s3(), 0.0);
        assert!(p.rate_jumps().is_empty());
        assert_eq!(p.name(), "hold");
    }

    #[test]
    fn downward_moves_mirror_upward_ones() {
        let (pivot, dist) = (START, END - START);
        let (up_end, down_end) = (pivot + dist, pivot - dist);
        type Build = fn(f64, f64) -> Result<MotionProfile, DriveError>;
        let builders: [Build; 4] = [
            |a, b| MotionProfile::uniform(a, b, DUR),
            |a, b| MotionProfile::trapezoidal(a, b, DUR, TrapezoidLimit::AccelRadS2(2.5)),
            |a, b| {
                let limit = SCurveLimit::AccelJerk { accel_rad_s2: 2.5, jerk_rad_s3: 20.0 };
                MotionProfile::s_curve(a, b, DUR, limit)
            },
            |a, b| {
                let limit = SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.2 };
                MotionProfile::s_curve(a, b, DUR, limit)
            },
        ];
        for build in builders {
            let up = build(pivot, up_end).expect("upward move");
            let down = build(pivot, down_end).expect("downward move");
            check_ends(&down, pivot, down_end, DUR, down.sample(0.0).rate_rad_s);
            check_mirror(&up, &down, pivot, DUR);
            let peak = up.peak_rate_rad_s();
            assert_close(down.peak_rate_rad_s(), peak, 1e-12 * peak, "mirrored peak rate");
        }
        let up = MotionProfile::spin_up(pivot, 3.0, 1.5).expect("spin-up");
        let down = MotionProfile::spin_up(pivot, -3.0, 1.5).expect("spin-down");
        check_mirror(&up, &down, pivot, 3.0);
    }

    #[test]
    fn invalid_inputs_are_rejected_by_name() {
        let nan = f64::NAN;
        let accel_jerk = |accel_rad_s2, jerk_rad_s3| SCurveLimit::AccelJerk { accel_rad_s2, jerk_rad_s3 };
        let fractions = |ramp_fraction, jerk_fraction| SCurveLimit::Fractions { ramp_fraction, jerk_fraction };
        let trap = |limit| MotionProfile::trapezoidal(START, END, DUR, limit);
        let scurve = |limit| MotionProfile::s_curve(START, END, DUR, limit);
        let cases = [
            (MotionProfile::uniform(START, END, 0.0), "duration_s"),
            (MotionProfile::uniform(START, END, -1.0), "duration_s"),
            (MotionProfile::uniform(START, END, nan), "duration_s"),
            (MotionProfile::uniform(START, START, DUR), "end_rad"),
            (MotionProfile::uniform(nan, END, DUR), "start_rad"),
            (MotionProfile::uniform(START, f64::INFINITY, DUR), "end_rad"),
            (trap(TrapezoidLimit::AccelRadS2(-1.0)), "accel_rad_s2"),
            (trap(TrapezoidLimit::AccelRadS2(nan)), "accel_rad_s2"),
            (trap(TrapezoidLimit::AccelRadS2(1.0)), "accel_rad_s2"),
            (trap(TrapezoidLimit::RampFraction(0.0)), "ramp_fraction"),
            (trap(TrapezoidLimit::RampFraction(0.6)), "ramp_fraction"),
            (trap(TrapezoidLimit::RampFraction(nan)), "ramp_fraction"),
            (MotionProfile::trapezoidal(START, END, 0.0, TrapezoidLimit::RampFraction(0.2)), "duration_s"),
            (scurve(fractions(0.6, 0.25)), "ramp_fraction"),
            (scurve(fractions(0.4, 0.0)), "jerk_fraction"),
            (scurve(fractions(0.4, 0.51)), "jerk_fraction"),
            (scurve(fractions(0.4, nan)), "jerk_fraction"),
            (scurve(accel_jerk(-2.5, 20.0)), "accel_rad_s2"),
            (scurve(accel_jerk(2.5, nan)), "jerk_rad_s3"),
            (scurve(accel_jerk(2.5, 0.0)), "jerk_rad_s3"),
            (scurve(accel_jerk(2.5, 5.0)), "jerk_rad_s3"),
            (scurve(accel_jerk(1.4, 100.0)), "accel_rad_s2"),
            (scurve(accel_jerk(100.0, 200.0)), "jerk_rad_s3"),
            (MotionProfile::spin_up(0.0, nan, 1.0), "final_rate_rad_s"),
            (MotionProfile::spin_up(0.0, 1.0, 0.0), "ramp_time_s"),
            (MotionProfile::spin_up(0.0, 1.0, f64::INFINITY), "ramp_time_s"),
            (MotionProfile::spin_up(nan, 1.0, 1.0), "start_rad"),
        ];
        for (i, (result, expected)) in cases.into_iter().enumerate() {
            assert_eq!(err_name(result), expected, "case {i}");
        }
    }

    #[test]
    fn error_message_names_parameter() {
        let err = MotionProfile::uniform(START, END, 0.0).expect_err("zero duration");
        let text = err.to_string();
        assert!(text.contains("`duration_s`"), "{text}");
        assert!(text.contains("> 0"), "{text}");
    }
}
