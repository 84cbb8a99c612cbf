//! Quantities users judge a run by: residual vibration, its frequency and decay, and the seed's
//! [w/l] classification.

/// Frequency of a decaying oscillation from its up-crossings of the mean of its last half, Hz.
pub fn crossing_frequency_hz(series: &[(f64, f64)]) -> f64 {
    let tail = &series[series.len() / 2..];
    if tail.len() < 3 {
        return f64::NAN;
    }
    let mean = tail.iter().map(|p| p.1).sum::<f64>() / tail.len() as f64;
    let crossings: Vec<f64> = series
        .windows(2)
        .filter(|w| w[0].1 < mean && w[1].1 >= mean)
        .map(|w| w[0].0 + (mean - w[0].1) / (w[1].1 - w[0].1) * (w[1].0 - w[0].0))
        .collect();
    match crossings.as_slice() {
        [first, .., last] => (crossings.len() - 1) as f64 / (last - first),
        _ => f64::NAN,
    }
}

/// Residual vibration of a signal after the drive stopped.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Residual {
    /// Half the peak-to-peak excursion, m.
    pub amplitude_m: f64,
    /// Dominant frequency from zero crossings, Hz (NaN if it does not oscillate).
    pub frequency_hz: f64,
    /// Logarithmic decrement between successive peaks (NaN if fewer than two peaks).
    pub log_decrement: f64,
    /// Damping ratio from it, ζ = δ / √(4π² + δ²).
    pub damping_ratio: f64,
    /// Time after the drive stops until the signal stays within 5 % of its largest excursion
    /// about the final mean, s.
    pub settling_time_s: f64,
    /// Whether it settled before the run's end (else `settling_time_s` is the whole window).
    pub settled: bool,
}

/// Residual vibration of `series` (time, value) from `from_s` on.
pub fn residual(series: &[(f64, f64)], from_s: f64) -> Residual {
    let tail: Vec<(f64, f64)> = series.iter().copied().filter(|p| p.0 >= from_s).collect();
    if tail.len() < 3 {
        return Residual {
            amplitude_m: 0.0,
            frequency_hz: f64::NAN,
            log_decrement: f64::NAN,
            damping_ratio: f64::NAN,
            settling_time_s: 0.0,
            settled: true,
        };
    }
    let (lo, hi) = tail.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
    let last_half = &tail[tail.len() / 2..];
    let mean = last_half.iter().map(|p| p.1).sum::<f64>() / last_half.len() as f64;
    let peaks: Vec<f64> = tail
        .windows(3)
        .filter(|w| w[1].1 > w[0].1 && w[1].1 >= w[2].1 && w[1].1 > mean)
        .map(|w| w[1].1 - mean)
        .collect();
    // Peaks well above the resolution of the final mean: down to a tenth of the first.
    let first_peak = peaks.first().copied().unwrap_or(0.0);
    let peaks: Vec<f64> = peaks.into_iter().take_while(|p| *p >= 0.1 * first_peak).collect();
    let log_decrement = match peaks.as_slice() {
        [first, .., last] if *last > 0.0 => (first / last).ln() / (peaks.len() - 1) as f64,
        _ => f64::NAN,
    };
    let damping_ratio = log_decrement / (4.0 * std::f64::consts::PI.powi(2) + log_decrement.powi(2)).sqrt();
    let excursion = tail.iter().map(|p| (p.1 - mean).abs()).fold(0.0, f64::max);
    let last_out = tail.iter().rev().find(|p| (p.1 - mean).abs() > 0.05 * excursion).map_or(from_s, |p| p.0);
    Residual {
        amplitude_m: 0.5 * (hi - lo),
        frequency_hz: crossing_frequency_hz(&tail),
        log_decrement,
        damping_ratio,
        settling_time_s: last_out - from_s,
        settled: tail.last().is_some_and(|p| last_out < p.0),
    }
}

/// The seed's §4 classes of an arm by its static [w/l] under load.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StiffnessClass {
    /// w/l ≤ 1/650: may be modelled rigid (the seed's band reaches down to 1/1000).
    Rigid,
    /// 1/650 < w/l ≤ 1/400: rigid–flexible coupling.
    RigidFlexible,
    /// 1/400 < w/l ≤ 1/250: flexible; mind the control.
    Flexible,
    /// w/l > 1/250: beyond the seed's bands; the arm risks yield.
    BeyondYield,
}

impl StiffnessClass {
    /// Class of a static deflection ratio w/l.
    pub fn of_ratio(w_over_l: f64) -> Self {
        match w_over_l {
            r if r <= 1.0 / 650.0 => StiffnessClass::Rigid,
            r if r <= 1.0 / 400.0 => StiffnessClass::RigidFlexible,
            r if r <= 1.0 / 250.0 => StiffnessClass::Flexible,
            _ => StiffnessClass::BeyondYield,
        }
    }

    /// Description with the seed's band.
    pub fn describe(&self) -> &'static str {
        match self {
            StiffnessClass::Rigid => "rigid (w/l <= 1/650)",
            StiffnessClass::RigidFlexible => "rigid-flexible coupling (1/650 < w/l <= 1/400)",
            StiffnessClass::Flexible => "flexible (1/400 < w/l <= 1/250)",
            StiffnessClass::BeyondYield => "beyond the seed's bands (w/l > 1/250): check yield",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_frequency_of_a_sine() {
        let f = 1.7;
        let s: Vec<(f64, f64)> =
            (0..5000).map(|i| i as f64 * 1e-3).map(|t| (t, (std::f64::consts::TAU * f * t).sin() + 0.3)).collect();
        assert!((crossing_frequency_hz(&s) - f).abs() < 1e-3);
    }

    #[test]
    fn residual_of_a_damped_sine() {
        // x = A e^{-ζωt} sin(ω_d t): log decrement 2πζ/√(1−ζ²), frequency ω_d/2π.
        let (zeta, f) = (0.02_f64, 3.0);
        let w = std::f64::consts::TAU * f;
        let wd = w * (1.0 - zeta * zeta).sqrt();
        let s: Vec<(f64, f64)> =
            (0..200_000).map(|i| i as f64 * 1e-4).map(|t| (t, (-zeta * w * t).exp() * (wd * t).sin())).collect();
        let r = residual(&s, 0.0);
        let exact = std::f64::consts::TAU * zeta / (1.0 - zeta * zeta).sqrt();
        assert!((r.log_decrement / exact - 1.0).abs() < 1e-3, "{} vs {exact}", r.log_decrement);
        assert!((r.damping_ratio / zeta - 1.0).abs() < 1e-3);
        assert!((r.frequency_hz / (wd / std::f64::consts::TAU) - 1.0).abs() < 1e-3);
        // e^{-ζωt} = 0.05 at t = ln 20 / ζω.
        let settle = 20f64.ln() / (zeta * w);
        assert!((r.settling_time_s - settle).abs() < 1.0 / f, "{} vs {settle}", r.settling_time_s);
    }

    #[test]
    fn classes_follow_the_seed_bands() {
        assert_eq!(StiffnessClass::of_ratio(1.0 / 800.0), StiffnessClass::Rigid);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 500.0), StiffnessClass::RigidFlexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 300.0), StiffnessClass::Flexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 200.0), StiffnessClass::BeyondYield);
    }
}
