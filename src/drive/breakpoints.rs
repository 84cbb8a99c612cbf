//! Where a [`MotionProfile`] is not smooth: the instants its rate jumps (reported apart, since
//! [`MotionProfile::sample`] is right-continuous) and the instants its acceleration or jerk jumps,
//! which a time step should not straddle.

use super::profile::{Kind, MotionProfile};

impl MotionProfile {
    /// Instants where the rate jumps (uniform profile, shaped or not) as
    /// `(time s, jump in rate rad/s)`; empty for every other profile.
    /// [`Self::sample`] returns the rate just after each instant.
    pub fn rate_jumps(&self) -> Vec<(f64, f64)> {
        match &self.kind {
            Kind::Shaped(shaping) => Self::shaped_rate_jumps(shaping, self.duration_s),
            Kind::Uniform => {
                let rate = (self.end_rad - self.start_rad) / self.duration_s;
                vec![(0.0, rate), (self.duration_s, -rate)]
            }
            _ => Vec::new(),
        }
    }

    /// Instants inside the motion where its acceleration or jerk jumps (the ends of its
    /// constant-jerk pieces — a table's samples, a shaped profile's shifted breakpoints `t_i + b`;
    /// the end of a spin-up's ramp), s, in order. A time step that
    /// straddles one integrates across a kink of the load; fixed steps that divide the pieces land
    /// on them, a controlled step is cut to end there.
    pub fn breakpoints_s(&self) -> Vec<f64> {
        if let Kind::Table { .. } | Kind::Shaped(_) = self.kind {
            let inner = self.segments.iter().skip(1).map(|s| s.t0_s);
            return inner.chain(std::iter::once(self.duration_s)).collect();
        }
        let half = 0.5 * self.duration_s;
        let inner: Vec<f64> = self.segments.iter().map(|s| s.t0_s).filter(|&t| t > 0.0 && t < half).collect();
        // A piece starting at the midpoint: a triangular trapezoid's acceleration reverses there.
        let middle = self.segments.iter().any(|s| (s.t0_s - half).abs() <= 1e-12 * self.duration_s).then_some(half);
        let mirrored = inner.iter().rev().map(|t| self.duration_s - t);
        let end = (self.duration_s > 0.0).then_some(self.duration_s);
        inner.iter().copied().chain(middle).chain(mirrored).chain(end).collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::drive::test_support::{DUR, END, START, assert_close};
    use crate::drive::{MotionProfile, SCurveLimit, TrapezoidLimit};

    /// A triangular trapezoid's acceleration reverses at the midpoint: a breakpoint.
    #[test]
    fn a_triangle_breaks_at_its_midpoint() {
        let triangle = MotionProfile::trapezoidal(0.0, 1.5, 4.0, TrapezoidLimit::RampFraction(0.5)).unwrap();
        assert_eq!(triangle.breakpoints_s(), vec![2.0, 4.0]);
        let (before, after) = (triangle.sample(2.0 - 1e-9), triangle.sample(2.0 + 1e-9));
        assert!(before.accel_rad_s2 > 0.0 && after.accel_rad_s2 < 0.0);
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
}
