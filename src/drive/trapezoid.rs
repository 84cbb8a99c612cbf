//! Timing of the acceleration-limited (trapezoidal-rate) move: the length of its accel phase and
//! its acceleration, from the limit it is given.

use super::validate::{DriveError, FEASIBILITY_SLACK, Move, invalid, require_fraction, require_positive};

/// How the acceleration of a [`MotionProfile::trapezoidal`](super::MotionProfile::trapezoidal)
/// profile is limited.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrapezoidLimit {
    /// Acceleration (and deceleration) magnitude, rad/s²; must be at least
    /// `4|B − A|/T²`. The profile uses exactly this acceleration.
    AccelRadS2(f64),
    /// Accel-phase duration divided by `T` (dimensionless), in `(0, 0.5]`;
    /// 0.5 gives a triangular rate profile.
    RampFraction(f64),
}

/// Trapezoid shape `(t_a s, accel rad/s²)`: accel-phase length and acceleration magnitude.
pub(super) fn trapezoid_shape(mv: &Move, limit: TrapezoidLimit) -> Result<(f64, f64), DriveError> {
    match limit {
        TrapezoidLimit::AccelRadS2(accel) => Ok((trapezoid_ramp_time(mv, accel)?, accel)),
        TrapezoidLimit::RampFraction(fraction) => {
            let t_a = require_fraction("ramp_fraction", fraction)? * mv.duration_s;
            Ok((t_a, mv.distance() / (t_a * (mv.duration_s - t_a))))
        }
    }
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

#[cfg(test)]
mod tests {
    use super::TrapezoidLimit;
    use crate::drive::MotionProfile;
    use crate::drive::test_support::{
        DUR, END, START, allowed_bound, assert_close, check_derivatives, check_ends, check_midpoint, max_abs,
    };

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

    #[test]
    fn trapezoid_minimum_accel_is_reported() {
        let result = MotionProfile::trapezoidal(START, END, DUR, TrapezoidLimit::AccelRadS2(1.0));
        let expected = 4.0 * (END - START) / (DUR * DUR);
        assert_close(allowed_bound(result), expected, 1e-12 * expected, "minimum accel");
    }
}
