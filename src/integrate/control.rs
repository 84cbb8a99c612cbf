//! Step-size control from a local error estimate.
//!
//! The implicit methods' local error in displacement is O(h³) ([`super::Integrator::local_error`]),
//! so a step that made an error `e` against a tolerance `tol` is followed by
//! `h · 0.9 (tol / e)^{1/3}`, growing at most 2× and shrinking at most 4× at a time, within
//! [`StepControl::min_step_s`, `StepControl::max_step_s`]. A step whose error exceeds the
//! tolerance is taken again, shorter (unless it is already the shortest allowed).

/// Bounds and tolerance of a controlled step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// Local error allowed per step, in the caller's measure (metres of tip displacement for the
    /// arm).
    pub tolerance: f64,
    /// Shortest step, s.
    pub min_step_s: f64,
    /// Longest step, s.
    pub max_step_s: f64,
}

impl StepControl {
    /// Whether a step of `h_s` that made `error` is accepted.
    pub fn accepts(&self, h_s: f64, error: f64) -> bool {
        error <= self.tolerance || h_s <= self.min_step_s * (1.0 + 1e-9)
    }

    /// The step to try after a step of `h_s` that made `error`, s.
    pub fn next_step_s(&self, h_s: f64, error: f64) -> f64 {
        let factor = if error > 0.0 { (0.9 * (self.tolerance / error).cbrt()).clamp(0.25, 2.0) } else { 2.0 };
        (h_s * factor).clamp(self.min_step_s, self.max_step_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_step_follows_the_cube_root_of_the_error_within_its_bounds() {
        let control = StepControl { tolerance: 1e-6, min_step_s: 1e-3, max_step_s: 1e-2 };
        // An error 8× the tolerance halves the step (× 0.9), one 1/8 of it doubles it (capped).
        assert!((control.next_step_s(4e-3, 8e-6) - 4e-3 * 0.45).abs() < 1e-12);
        assert_eq!(control.next_step_s(4e-3, 1e-9), 8e-3);
        assert_eq!(control.next_step_s(8e-3, 0.0), 1e-2);
        assert_eq!(control.next_step_s(1e-3, 1.0), 1e-3);
        assert!(!control.accepts(4e-3, 2e-6));
        assert!(control.accepts(1e-3, 2e-6), "the shortest step is always accepted");
    }
}
