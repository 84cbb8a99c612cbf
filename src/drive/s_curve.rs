//! Timing of the jerk-limited symmetric 7-segment S-curve: the length of its accel phase and of
//! each jerk ramp, and its peak acceleration and jerk, from the limit it is given, with the bounds
//! a limit must meet for the move to be feasible.

use super::validate::{DriveError, FEASIBILITY_SLACK, Move, invalid, require_fraction, require_positive};

/// How a [`MotionProfile::s_curve`](super::MotionProfile::s_curve) profile is limited.
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

/// S-curve shape `(t_a s, t_j s, peak accel rad/s², peak jerk rad/s³)`.
pub(super) fn s_curve_shape(mv: &Move, limit: SCurveLimit) -> Result<(f64, f64, f64, f64), DriveError> {
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

#[cfg(test)]
mod tests {
    use super::SCurveLimit;
    use crate::drive::MotionProfile;
    use crate::drive::test_support::{
        DUR, END, START, allowed_bound, assert_close, check_derivatives, check_ends, check_midpoint, dense_times,
        max_abs,
    };

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
}
