//! Evaluating a [`MotionProfile`] at a time: the exact angle, rate, acceleration and jerk, in
//! closed form (a cubic per constant-jerk segment, mirrored for the second half; the spin-up's
//! trigonometric formula).

use std::f64::consts::PI;

use super::profile::{Kind, MotionProfile};
use super::state::DriveState;

impl MotionProfile {
    /// Exact state at time `t_s` (s; 0 = start of motion). At a discontinuity
    /// the value just after `t_s` is returned.
    pub fn sample(&self, t_s: f64) -> DriveState {
        match self.kind {
            Kind::SpinUp { final_rate_rad_s } => return self.sample_spin_up(final_rate_rad_s, t_s),
            Kind::Table { end_rate_rad_s } => return self.sample_table(end_rate_rad_s, t_s),
            Kind::Shaped(_) => return self.sample_table(0.0, t_s),
            _ => {}
        }
        if t_s < 0.0 {
            DriveState::at_rest(self.start_rad)
        } else if t_s >= self.duration_s {
            DriveState::at_rest(self.end_rad)
        } else if t_s < 0.5 * self.duration_s {
            self.segment_state(t_s, true)
        } else {
            self.segment_state(self.duration_s - t_s, false).point_mirrored(self.start_rad + self.end_rad)
        }
    }

    /// State at `s` (s) from the precomputed segments (`[0, T/2]` of a symmetric
    /// profile, `[0, T]` of a table). With `right_limit` a segment boundary
    /// belongs to the later segment, otherwise to the earlier one (used for the
    /// mirrored half, where time runs backwards).
    pub(super) fn segment_state(&self, s: f64, right_limit: bool) -> DriveState {
        let after = if right_limit {
            self.segments.partition_point(|seg| seg.t0_s <= s)
        } else {
            self.segments.partition_point(|seg| seg.t0_s < s)
        };
        match self.segments.get(after.saturating_sub(1)) {
            Some(seg) => seg.state.advanced(s - seg.t0_s),
            None => DriveState::at_rest(self.start_rad),
        }
    }

    /// A table's (or shaped profile's) state at `t_s` (s): at rest at its start before 0, its
    /// segments on `[0, T)`, its end rate `end_rate` (rad/s; 0 when shaped) from `T` on.
    fn sample_table(&self, end_rate: f64, t_s: f64) -> DriveState {
        if t_s < 0.0 {
            DriveState::at_rest(self.start_rad)
        } else if t_s < self.duration_s {
            self.segment_state(t_s, true)
        } else {
            let angle_rad = self.end_rad + end_rate * (t_s - self.duration_s);
            DriveState { angle_rad, rate_rad_s: end_rate, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 }
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

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use crate::drive::test_support::{
        DUR, END, START, assert_close, check_derivatives, check_ends, check_midpoint, dense_times,
    };
    use crate::drive::{DriveError, DriveState, MotionProfile, SCurveLimit, TrapezoidLimit};

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
}
