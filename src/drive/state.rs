//! The hub's kinematic state at one instant, and motion at constant jerk: advancing a state,
//! mirroring it, and chaining constant-jerk pieces into the segments a profile is stored as.

/// Kinematic state of the hub at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    pub(super) const fn at_rest(angle_rad: f64) -> Self {
        Self { angle_rad, rate_rad_s: 0.0, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 }
    }

    /// State after `dt` seconds of constant jerk `self.jerk_rad_s3`.
    pub(super) fn advanced(&self, dt: f64) -> Self {
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
    pub(super) fn point_mirrored(&self, angle_sum_rad: f64) -> Self {
        Self {
            angle_rad: angle_sum_rad - self.angle_rad,
            rate_rad_s: self.rate_rad_s,
            accel_rad_s2: -self.accel_rad_s2,
            jerk_rad_s3: self.jerk_rad_s3,
        }
    }
}

/// One constant-jerk segment: the full state (including its constant jerk)
/// at its start time `t0_s` (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Segment {
    pub(super) t0_s: f64,
    pub(super) state: DriveState,
}

/// Segment specification before integration: start time (s), acceleration
/// at the start (rad/s²) and constant jerk (rad/s³).
#[derive(Debug, Clone, Copy)]
pub(super) struct Piece {
    t0_s: f64,
    accel_rad_s2: f64,
    jerk_rad_s3: f64,
}

impl Piece {
    pub(super) const fn new(t0_s: f64, accel_rad_s2: f64, jerk_rad_s3: f64) -> Self {
        Self { t0_s, accel_rad_s2, jerk_rad_s3 }
    }
}

/// Integrates constant-jerk pieces from `initial` (at `t = 0`): each piece
/// starts from the state reached at its start time, with its own acceleration
/// and jerk imposed exactly.
pub(super) fn chain(initial: DriveState, pieces: &[Piece]) -> Vec<Segment> {
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
