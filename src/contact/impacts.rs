//! Per-pair bookkeeping of contact force over time: impacts (start, peak, end), impulse.

use serde::Serialize;

/// One impact: from the step the force first exceeds zero to the step it returns to zero.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Impact {
    /// First step with force, s.
    pub start_s: f64,
    /// Time of the peak force, s (of the interpolated peak, see `peak_force_n`).
    pub peak_time_s: f64,
    /// Peak force, N: the vertex of the parabola through the largest force at a step and its two
    /// neighbours, where both are in contact (else that largest sample). Sampled at steps, a peak
    /// of an impact resolved by n steps is missed by up to ≈ (π/n)²/8 (0.5 % at 18 steps); the
    /// parabola leaves ≈ (π/n)⁴/100 of it.
    pub peak_force_n: f64,
    /// The largest force at a step, N (what a plot of the steps shows).
    pub peak_sample_n: f64,
    /// Last step with force, s (the run's end if still in contact).
    pub end_s: f64,
    /// ∫ F dt over the impact, N·s.
    pub impulse_n_s: f64,
}

impl Impact {
    fn starting(t_s: f64, force_n: f64, impulse_n_s: f64) -> Self {
        Impact {
            start_s: t_s,
            peak_time_s: t_s,
            peak_force_n: force_n,
            peak_sample_n: force_n,
            end_s: t_s,
            impulse_n_s,
        }
    }

    /// Duration, s.
    pub fn duration_s(&self) -> f64 {
        self.end_s - self.start_s
    }
}

/// The force history of one contact pair, reduced to its impacts as it is fed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ImpactTracker {
    impacts: Vec<Impact>,
    open: Option<Impact>,
    last: Option<(f64, f64)>,
    /// The sample before the open impact's largest one, while the one after it is awaited.
    before_peak: Option<(f64, f64)>,
}

/// Vertex of the parabola through three samples, the middle one the largest: (t, f).
fn parabola_peak(before: (f64, f64), peak: (f64, f64), after: (f64, f64)) -> (f64, f64) {
    let (d0, d2) = (before.0 - peak.0, after.0 - peak.0);
    let (s0, s2) = ((before.1 - peak.1) / d0, (after.1 - peak.1) / d2);
    let c = (s0 - s2) / (d0 - d2);
    let b = s0 - c * d0;
    let concave_around_peak = c < 0.0 && d0 < 0.0 && d2 > 0.0;
    if !concave_around_peak {
        return peak;
    }
    let tau = (-b / (2.0 * c)).clamp(d0, d2);
    (peak.0 + tau, peak.1 + b * tau + c * tau * tau)
}

impl ImpactTracker {
    /// Feeds the force `force_n` (N) at time `t_s` (s); samples come in time order.
    pub fn push(&mut self, t_s: f64, force_n: f64) {
        if let Some((t0, f0)) = self.last {
            if let Some(open) = self.open.as_mut() {
                open.impulse_n_s += 0.5 * (f0 + force_n) * (t_s - t0);
            } else if force_n > 0.0 {
                // The impulse of the rising edge from the zero sample before it.
                let rising = 0.5 * force_n * (t_s - t0);
                self.open = Some(Impact::starting(t_s, force_n, rising));
            }
        } else if force_n > 0.0 {
            self.open = Some(Impact::starting(t_s, force_n, 0.0));
        }
        if let Some(open) = self.open.as_mut() {
            if let Some(before) = self.before_peak.take() {
                // The sample after the largest: interpolate if all three are in contact.
                let peak = (open.peak_time_s, open.peak_sample_n);
                if before.1 > 0.0 && force_n > 0.0 {
                    (open.peak_time_s, open.peak_force_n) = parabola_peak(before, peak, (t_s, force_n));
                }
            }
            if force_n > open.peak_sample_n {
                open.peak_sample_n = force_n;
                open.peak_force_n = force_n;
                open.peak_time_s = t_s;
                self.before_peak = Some(self.last.unwrap_or((t_s, 0.0)));
            }
            if force_n > 0.0 {
                open.end_s = t_s;
            } else {
                self.impacts.push(*open);
                self.open = None;
            }
        }
        self.last = Some((t_s, force_n));
    }

    /// Every impact so far, the open one included.
    pub fn impacts(&self) -> Vec<Impact> {
        self.impacts.iter().copied().chain(self.open).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_half_sines_make_two_impacts_with_their_impulse() {
        let mut tracker = ImpactTracker::default();
        let dt = 1e-4;
        for i in 0..=30_000 {
            let t = i as f64 * dt;
            // Impacts of 0.1 s at t = 1 s (peak 100 N) and t = 2 s (peak 50 N).
            let pulse = |start: f64, peak: f64| {
                if t > start && t < start + 0.1 { peak * (std::f64::consts::PI * (t - start) / 0.1).sin() } else { 0.0 }
            };
            tracker.push(t, pulse(1.0, 100.0) + pulse(2.0, 50.0));
        }
        let impacts = tracker.impacts();
        assert_eq!(impacts.len(), 2);
        // ∫ A sin(πt/T) dt = 2AT/π.
        assert!((impacts[0].impulse_n_s - 2.0 * 100.0 * 0.1 / std::f64::consts::PI).abs() < 1e-4);
        assert!((impacts[1].peak_force_n - 50.0).abs() < 1e-3);
        assert!((impacts[0].peak_time_s - 1.05).abs() < 1e-3);
        assert!((impacts[1].duration_s() - 0.1).abs() < 2.0 * dt);
    }

    /// A half-sine of 30 ms sampled every 2 ms, its peak between two samples: the largest sample
    /// misses ≈ (π/15)²/8 of it, the parabola a small fraction of that.
    #[test]
    fn the_parabola_recovers_a_peak_between_samples() {
        let (duration, peak, dt) = (0.03, 1500.0, 2e-3);
        let mut tracker = ImpactTracker::default();
        for i in 0..40 {
            let t = i as f64 * dt;
            let s = t - 0.012;
            let f = if s > 0.0 && s < duration { peak * (std::f64::consts::PI * s / duration).sin() } else { 0.0 };
            tracker.push(t, f);
        }
        let impact = tracker.impacts()[0];
        let sampled_error = 1.0 - impact.peak_sample_n / peak;
        let interpolated_error = (impact.peak_force_n / peak - 1.0).abs();
        assert!(sampled_error > 1e-3, "the samples should straddle the peak: {sampled_error}");
        assert!(interpolated_error < 0.05 * sampled_error, "{interpolated_error} vs {sampled_error}");
        assert!((impact.peak_time_s - (0.012 + 0.5 * duration)).abs() < 0.1 * dt);
    }
}
