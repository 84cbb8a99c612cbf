//! Per-pair bookkeeping of contact force over time: impacts (start, peak, end), impulse.

use serde::Serialize;

/// One impact: from the step the force first exceeds zero to the step it returns to zero.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Impact {
    /// First step with force, s.
    pub start_s: f64,
    /// Time of the peak force, s.
    pub peak_time_s: f64,
    /// Peak force, N.
    pub peak_force_n: f64,
    /// Last step with force, s (the run's end if still in contact).
    pub end_s: f64,
    /// ∫ F dt over the impact, N·s.
    pub impulse_n_s: f64,
}

impl Impact {
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
                self.open = Some(Impact {
                    start_s: t_s,
                    peak_time_s: t_s,
                    peak_force_n: force_n,
                    end_s: t_s,
                    impulse_n_s: rising,
                });
            }
        } else if force_n > 0.0 {
            self.open =
                Some(Impact { start_s: t_s, peak_time_s: t_s, peak_force_n: force_n, end_s: t_s, impulse_n_s: 0.0 });
        }
        if let Some(open) = self.open.as_mut() {
            if force_n > open.peak_force_n {
                open.peak_force_n = force_n;
                open.peak_time_s = t_s;
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
}
