//! A hub motion through samples of angle against time: the clamped cubic spline through them.
//!
//! # Which spline, and why
//!
//! The samples are joined by the *clamped* cubic spline: one cubic per interval, angle, rate and
//! acceleration continuous at every sample (C² on `[0, T]`), with the rate fixed at both ends —
//! 0 at the first sample, because the hub rests before the table starts, and the table's end
//! rate at the last (0 by default: the hub stops; a spin-up keeps turning at its final rate).
//!
//! A lift starts and stops at rest, and that is what the clamped ends impose. The *natural*
//! spline instead sets the acceleration to 0 at the ends and leaves the rate free: through the
//! samples of a move from rest it starts with a small spurious rate, i.e. a rate jump from rest
//! at `t = 0` — an acceleration impulse that strikes every mode of the arm. Of all C²
//! interpolants with the given end rates, the clamped spline has the least `∫ θ̈² dt` (Holladay's
//! minimum-curvature property; de Boor, *A Practical Guide to Splines*, 2001, ch. IV), so it is
//! the smoothest acceleration through the samples; through samples of a cubic with those end
//! rates it is that cubic exactly.
//!
//! What it does not impose is zero acceleration at the ends: two end conditions are all a cubic
//! spline has. The acceleration steps from 0 to `θ̈(0⁺)` at the start and from `θ̈(T⁻)` to 0 at
//! the end (jerk impulses there, not counted in the peak jerk). Through samples of a motion that
//! itself starts and ends with zero acceleration these steps are of order `h² θ''''` (`h` the
//! sample spacing), small at a fine spacing.
//!
//! # Representation
//!
//! Each interval is stored as a constant-jerk segment (a cubic is exactly that), so a table is
//! sampled, bounded and broken at its samples by the same code as the built-in profiles.

use super::state::{DriveState, Segment};
use super::validate::{DriveError, invalid, require_finite};

/// Fewest samples a table may have: below 4 the motion is fixed by the end conditions more than
/// by the data, which is more likely a truncated file than a plan.
pub const MIN_TABLE_SAMPLES: usize = 4;

/// Checks the samples of a table: at least [`MIN_TABLE_SAMPLES`], as many angles as times, times
/// finite, starting at 0 and strictly increasing, angles finite. Errors name the sample's index.
pub(super) fn check_samples(times_s: &[f64], angles_rad: &[f64]) -> Result<(), DriveError> {
    let n = times_s.len();
    if angles_rad.len() != n {
        return Err(invalid("angles_rad", angles_rad.len() as f64, format!("as many angles as times ({n})")));
    }
    if n < MIN_TABLE_SAMPLES {
        return Err(invalid("times_s", n as f64, format!("at least {MIN_TABLE_SAMPLES} samples")));
    }
    let sample = |name, index, value, allowed: String| DriveError::InvalidSample { name, index, value, allowed };
    if times_s[0] != 0.0 {
        return Err(sample("times_s", 0, times_s[0], "0 (the table starts the motion at t = 0 s)".into()));
    }
    for i in 1..n {
        let (before, t) = (times_s[i - 1], times_s[i]);
        if !t.is_finite() {
            return Err(sample("times_s", i, t, "a finite time".into()));
        }
        if t <= before {
            return Err(sample("times_s", i, t, format!("> {before} (the time before it): strictly increasing")));
        }
    }
    match angles_rad.iter().position(|a| !a.is_finite()) {
        Some(i) => Err(sample("angles_rad", i, angles_rad[i], "a finite angle".into())),
        None => Ok(()),
    }
}

/// The clamped cubic spline through `(times_s, angles_rad)` with rate 0 at the first sample and
/// `end_rate_rad_s` at the last, as one constant-jerk segment per interval. The samples must have
/// passed [`check_samples`].
pub(super) fn clamped_spline(times_s: &[f64], angles_rad: &[f64], end_rate_rad_s: f64) -> Vec<Segment> {
    let n = times_s.len() - 1;
    let h: Vec<f64> = times_s.windows(2).map(|w| w[1] - w[0]).collect();
    let slope: Vec<f64> = (0..n).map(|i| (angles_rad[i + 1] - angles_rad[i]) / h[i]).collect();
    // The accelerations M_i at the samples solve a tridiagonal system (continuity of the rate at
    // the inner samples, the clamped rates at the ends); it is strictly diagonally dominant, so
    // elimination without pivoting is stable.
    let mut sub = vec![0.0; n + 1];
    let mut diag = vec![0.0; n + 1];
    let mut sup = vec![0.0; n + 1];
    let mut rhs = vec![0.0; n + 1];
    (diag[0], sup[0], rhs[0]) = (2.0 * h[0], h[0], 6.0 * slope[0]);
    for i in 1..n {
        (sub[i], diag[i], sup[i]) = (h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i]);
        rhs[i] = 6.0 * (slope[i] - slope[i - 1]);
    }
    (sub[n], diag[n], rhs[n]) = (h[n - 1], 2.0 * h[n - 1], 6.0 * (end_rate_rad_s - slope[n - 1]));
    let accel = solve_tridiagonal(&sub, &mut diag, &sup, &mut rhs);
    (0..n)
        .map(|i| Segment {
            t0_s: times_s[i],
            state: DriveState {
                angle_rad: angles_rad[i],
                rate_rad_s: slope[i] - h[i] * (2.0 * accel[i] + accel[i + 1]) / 6.0,
                accel_rad_s2: accel[i],
                jerk_rad_s3: (accel[i + 1] - accel[i]) / h[i],
            },
        })
        .collect()
}

/// Thomas elimination of a tridiagonal system (`sub[0]` and `sup[last]` unused); overwrites
/// `diag` and `rhs` and returns the solution.
fn solve_tridiagonal(sub: &[f64], diag: &mut [f64], sup: &[f64], rhs: &mut [f64]) -> Vec<f64> {
    let n = diag.len();
    for i in 1..n {
        let factor = sub[i] / diag[i - 1];
        diag[i] -= factor * sup[i - 1];
        rhs[i] -= factor * rhs[i - 1];
    }
    let mut x = vec![0.0; n];
    x[n - 1] = rhs[n - 1] / diag[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = (rhs[i] - sup[i] * x[i + 1]) / diag[i];
    }
    x
}

/// Each segment with its length, the last ending at `end_s`.
fn with_lengths(segments: &[Segment], end_s: f64) -> impl Iterator<Item = (&Segment, f64)> {
    let ends = segments.iter().skip(1).map(|s| s.t0_s).chain(std::iter::once(end_s));
    segments.iter().zip(ends).map(|(s, end)| (s, end - s.t0_s))
}

/// Exact peak |rate|, |accel| and |jerk| (rad/s, rad/s², rad/s³) over the segments up to
/// `end_s`, and of the constant `end_rate_rad_s` after: the rate is quadratic on a segment
/// (extreme at its ends or where the acceleration crosses 0), the acceleration linear, the jerk
/// constant.
pub(super) fn peaks(segments: &[Segment], end_s: f64, end_rate_rad_s: f64) -> (f64, f64, f64) {
    let mut peak = (end_rate_rad_s.abs(), 0.0_f64, 0.0_f64);
    for (seg, length) in with_lengths(segments, end_s) {
        let s = seg.state;
        let at_end = s.advanced(length);
        let mut rate = s.rate_rad_s.abs().max(at_end.rate_rad_s.abs());
        if s.jerk_rad_s3 != 0.0 {
            let turn = -s.accel_rad_s2 / s.jerk_rad_s3;
            if turn > 0.0 && turn < length {
                rate = rate.max(s.advanced(turn).rate_rad_s.abs());
            }
        }
        peak.0 = peak.0.max(rate);
        peak.1 = peak.1.max(s.accel_rad_s2.abs()).max(at_end.accel_rad_s2.abs());
        peak.2 = peak.2.max(s.jerk_rad_s3.abs());
    }
    peak
}

/// Smallest and largest angle (rad) over the segments up to `end_s`: the ends of each segment
/// and where its rate crosses 0.
pub(super) fn angle_range(segments: &[Segment], end_s: f64) -> (f64, f64) {
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    let mut include = |angle: f64| range = (range.0.min(angle), range.1.max(angle));
    for (seg, length) in with_lengths(segments, end_s) {
        let s = seg.state;
        include(s.angle_rad);
        include(s.advanced(length).angle_rad);
        for dt in rate_roots(s.rate_rad_s, s.accel_rad_s2, 0.5 * s.jerk_rad_s3) {
            if dt > 0.0 && dt < length {
                include(s.advanced(dt).angle_rad);
            }
        }
    }
    range
}

/// Real roots of `c + b x + a x²` (none if it is identically 0).
fn rate_roots(c: f64, b: f64, a: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return Vec::new();
    }
    // The root of the larger magnitude first, the other from the product c / a (no cancellation).
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 { vec![0.0] } else { vec![q / a, c / q] }
}

/// The end rate of a table, checked.
pub(super) fn end_rate(end_rate_rad_s: f64) -> Result<f64, DriveError> {
    require_finite("end_rate_rad_s", end_rate_rad_s)
}

#[cfg(test)]
mod tests {
    use crate::drive::test_support::{assert_close, check_derivatives};
    use crate::drive::{DriveError, MotionProfile};

    /// θ(t) = 0.3 + 0.5 t² − 0.2 t³ on [0, 2]: rate 0 at 0, −0.4 rad/s at 2.
    fn cubic(t: f64) -> [f64; 4] {
        [0.3 + 0.5 * t * t - 0.2 * t.powi(3), t - 0.6 * t * t, 1.0 - 1.2 * t, -1.2]
    }

    #[test]
    fn the_spline_through_samples_of_a_cubic_is_that_cubic() {
        let times = [0.0, 0.13, 0.5, 0.61, 1.2, 1.7, 2.0];
        let angles: Vec<f64> = times.iter().map(|&t| cubic(t)[0]).collect();
        let p = MotionProfile::table(&times, &angles, cubic(2.0)[1]).expect("valid table");
        for i in 0..=400 {
            let t = 2.0 * f64::from(i) / 400.0;
            let s = p.sample(t);
            let [angle, rate, accel, jerk] = cubic(t);
            assert_close(s.angle_rad, angle, 1e-13, "angle");
            assert_close(s.rate_rad_s, rate, 1e-12, "rate");
            if i < 400 {
                assert_close(s.accel_rad_s2, accel, 1e-11, "accel");
                assert_close(s.jerk_rad_s3, jerk, 1e-10, "jerk");
            }
        }
        // The cubic's rate t − 0.6 t² peaks at t = 5/6 (5/12 rad/s) and ends at −0.4; its
        // acceleration is largest at t = 2 (|1 − 2.4| = 1.4).
        assert_close(p.peak_rate_rad_s(), 5.0 / 12.0, 1e-12, "peak rate");
        assert_close(p.peak_accel_rad_s2(), 1.4, 1e-11, "peak accel");
        assert_close(p.peak_jerk_rad_s3(), 1.2, 1e-10, "peak jerk");
        // Its largest angle: where the rate crosses 0 at t = 5/3.
        let (lo, hi) = p.angle_range_rad(2.0);
        assert_close(lo, 0.3, 1e-13, "lowest angle");
        assert_close(hi, cubic(5.0 / 3.0)[0], 1e-13, "highest angle");
        assert_eq!(p.name(), "table");
        assert_eq!(p.breakpoints_s(), times[1..].to_vec());
    }

    #[test]
    fn a_table_rests_before_and_keeps_its_end_rate_after() {
        let times = [0.0, 1.0, 2.0, 3.0];
        let angles = [0.1, 0.2, 0.5, 0.6];
        let stops = MotionProfile::table(&times, &angles, 0.0).unwrap();
        let before = stops.sample(-1.0);
        assert_eq!((before.angle_rad, before.rate_rad_s, before.accel_rad_s2), (0.1, 0.0, 0.0));
        assert_close(stops.sample(0.0).rate_rad_s, 0.0, 1e-15, "at rest at the start");
        assert_close(stops.sample(3.0 - 1e-9).rate_rad_s, 0.0, 1e-9, "at rest at the end");
        let after = stops.sample(5.0);
        assert_eq!((after.angle_rad, after.rate_rad_s), (0.6, 0.0));
        let spins = MotionProfile::table(&times, &angles, 0.4).unwrap();
        assert_close(spins.sample(3.0 - 1e-9).rate_rad_s, 0.4, 1e-8, "end rate reached");
        let later = spins.sample(5.0);
        assert_close(later.angle_rad, 0.6 + 0.4 * 2.0, 1e-15, "keeps turning");
        assert_eq!((later.rate_rad_s, later.accel_rad_s2), (0.4, 0.0));
        assert_eq!((spins.start_rad(), spins.end_rad(), spins.duration_s()), (0.1, 0.6, 3.0));
        let scales = [spins.peak_rate_rad_s(), spins.peak_accel_rad_s2(), spins.peak_jerk_rad_s3()];
        check_derivatives(&spins, 3.0, &times, scales);
    }

    #[test]
    fn bad_samples_are_refused_by_index() {
        let ok = [0.0, 1.0, 2.0, 3.0];
        let sample = |result: Result<MotionProfile, DriveError>| match result {
            Err(DriveError::InvalidSample { name, index, .. }) => (name, index),
            other => panic!("expected a bad sample, got {other:?}"),
        };
        assert_eq!(sample(MotionProfile::table(&[0.1, 1.0, 2.0, 3.0], &ok, 0.0)), ("times_s", 0));
        assert_eq!(sample(MotionProfile::table(&[0.0, 1.0, 1.0, 3.0], &ok, 0.0)), ("times_s", 2));
        assert_eq!(sample(MotionProfile::table(&[0.0, 2.0, 1.0, 3.0], &ok, 0.0)), ("times_s", 2));
        assert_eq!(sample(MotionProfile::table(&[0.0, 1.0, f64::NAN, 3.0], &ok, 0.0)), ("times_s", 2));
        assert_eq!(sample(MotionProfile::table(&ok, &[0.0, 1.0, 2.0, f64::INFINITY], 0.0)), ("angles_rad", 3));
        let parameter = |result: Result<MotionProfile, DriveError>| match result {
            Err(DriveError::InvalidParameter { name, .. }) => name,
            other => panic!("expected a bad parameter, got {other:?}"),
        };
        assert_eq!(parameter(MotionProfile::table(&ok[..3], &ok[..3], 0.0)), "times_s");
        assert_eq!(parameter(MotionProfile::table(&ok, &ok[..3], 0.0)), "angles_rad");
        assert_eq!(parameter(MotionProfile::table(&ok, &ok, f64::NAN)), "end_rate_rad_s");
    }
}
