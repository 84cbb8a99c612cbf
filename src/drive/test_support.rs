//! Shared checks for the drive's unit tests: a reference move and the properties every profile
//! must have (ends, midpoint, derivatives consistent with the sampled state).

use super::{DriveError, DriveState, MotionProfile};

pub(super) const START: f64 = 0.25;
pub(super) const END: f64 = 1.75;
pub(super) const DUR: f64 = 2.0;

pub(super) fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!((actual - expected).abs() <= tol, "{what}: got {actual}, expected {expected} (tol {tol})");
}

/// `n + 1` evenly spaced times over `[-0.05 T, 1.05 T]`.
pub(super) fn dense_times(duration: f64, n: u32) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| duration * (-0.05 + 1.1 * f64::from(i) / f64::from(n)))
}

/// Parses the bound `x` out of an `allowed` text of the form ">= x ...".
pub(super) fn allowed_bound(result: Result<MotionProfile, DriveError>) -> f64 {
    match result {
        Err(DriveError::InvalidParameter { allowed, .. }) => {
            allowed.split_whitespace().nth(1).and_then(|s| s.parse().ok()).unwrap_or(f64::NAN)
        }
        other => panic!("expected an invalid parameter, got {other:?}"),
    }
}

/// Start at `start` with rate `start_rate`, exact end at `end` at rest,
/// holds outside `[0, T]`; the left limit at T must approach the end
/// (at rest unless the profile starts moving, i.e. uniform).
pub(super) fn check_ends(p: &MotionProfile, start: f64, end: f64, duration: f64, start_rate: f64) {
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
pub(super) fn check_midpoint(p: &MotionProfile, start: f64, end: f64, duration: f64, peak_rate: f64) {
    let dist = (end - start).abs();
    let mid = 0.5 * (start + end);
    let dt = 1e-9 * duration;
    let expected = mid - (end - start).signum() * peak_rate * dt;
    assert_close(p.sample(0.5 * duration).angle_rad, mid, 1e-12 * dist, "angle at T/2");
    assert_close(p.sample(0.5 * duration - dt).angle_rad, expected, 1e-11 * dist, "angle just before T/2");
}

/// Central differences of angle, rate and accel against rate, accel and
/// jerk, at points at least 4h away from `boundaries`.
pub(super) fn check_derivatives(p: &MotionProfile, t_end: f64, boundaries: &[f64], scales: [f64; 3]) {
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

/// Largest magnitude of `pick` over the sampled state on [`dense_times`].
pub(super) fn max_abs(p: &MotionProfile, duration: f64, pick: fn(&DriveState) -> f64) -> f64 {
    dense_times(duration, 100_000).map(|t| pick(&p.sample(t)).abs()).fold(0.0_f64, f64::max)
}
