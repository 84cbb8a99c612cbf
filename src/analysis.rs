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

/// The signal a residual's frequency, decay and settling are read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResidualSignal {
    /// The tip's deflection in the hub frame (an ideal drive: the hub holds still).
    TipDeflection,
    /// The hub's rate (under an actuator the hub itself rings on its drive: a rigid arm on its
    /// cylinder's oil column has no deflection to read).
    HubRate,
}

/// Residual vibration of a signal after the drive stopped.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Residual {
    /// Half the peak-to-peak excursion of the tip deflection, m.
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
    /// The signal the frequency, decrement and settling are read from.
    pub signal: ResidualSignal,
    /// Half the peak-to-peak excursion of the hub rate, rad/s, where that is the signal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hub_rate_amplitude_rad_s: Option<f64>,
}

/// The residual vibration of a run after `from_s`: the tip deflection's amplitude (`tip`, m), and
/// the frequency, decay and settling of the signal that moves — the hub rate (`hub_rate`, rad/s)
/// where one is given (under an actuator), else the tip deflection.
pub fn residual_of_run(tip: &[(f64, f64)], hub_rate: Option<&[(f64, f64)]>, from_s: f64) -> Residual {
    let at_tip = residual(tip, from_s);
    match hub_rate {
        None => at_tip,
        Some(rate) => {
            let at_hub = residual(rate, from_s);
            let tail: Vec<(f64, f64)> = rate.iter().copied().filter(|p| p.0 >= from_s).collect();
            let (frequency_hz, log_decrement) = swings(&tail);
            Residual {
                amplitude_m: at_tip.amplitude_m,
                frequency_hz,
                log_decrement,
                damping_ratio: log_decrement / (4.0 * std::f64::consts::PI.powi(2) + log_decrement.powi(2)).sqrt(),
                signal: ResidualSignal::HubRate,
                hub_rate_amplitude_rad_s: Some(at_hub.amplitude_m),
                ..at_hub
            }
        }
    }
}

/// Frequency (Hz) and logarithmic decrement of a vibration riding on a slow drift (a hub settling
/// under its controller while it rings), from its swings: the changes between successive
/// extrema, an extremum taken once the signal has turned back from it by 5 % of its range. From
/// the largest swing on, its cycles: the sum of a swing and the next (in which a drift's rise and
/// fall cancel), while they stay above a tenth of the first. A cycle is a period; its sum falls by
/// e^{−δ} per cycle. NaN where no whole cycle (two for δ) rings.
fn swings(tail: &[(f64, f64)]) -> (f64, f64) {
    let (lo, hi) = tail.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
    let turn = 0.05 * (hi - lo);
    // Indices of the extrema; `candidate` the one being followed, `rising` the way it goes.
    let mut at: Vec<usize> = Vec::new();
    let (mut candidate, mut rising) = (0, None::<bool>);
    for (i, p) in tail.iter().enumerate().skip(1) {
        let (value, held) = (p.1, tail[candidate].1);
        let up = value > held;
        match rising {
            None if (value - held).abs() > turn => (rising, candidate) = (Some(up), i),
            Some(r) if up == r => candidate = i,
            Some(_) if (value - held).abs() > turn => {
                at.push(candidate);
                (rising, candidate) = (Some(up), i);
            }
            _ => {}
        }
    }
    let extrema: Vec<(f64, f64)> = at.into_iter().map(|i| vertex(tail, i)).collect();
    let swing: Vec<(f64, f64)> = extrema.windows(2).map(|w| (w[1].0, (w[1].1 - w[0].1).abs())).collect();
    let largest = (0..swing.len()).max_by(|&i, &j| swing[i].1.total_cmp(&swing[j].1)).unwrap_or(0);
    let ringing = swing.get(largest..).unwrap_or_default();
    let cycles: Vec<f64> = ringing.chunks_exact(2).map(|c| c[0].1 + c[1].1).collect();
    let first = cycles.first().copied().unwrap_or(0.0);
    let cycles: Vec<f64> = cycles.into_iter().take_while(|c| *c >= 0.1 * first).collect();
    // 2n swings from the extremum the largest starts at: n periods.
    let frequency_hz = match cycles.len() {
        0 => f64::NAN,
        n => n as f64 / (ringing[2 * n - 1].0 - extrema[largest].0),
    };
    let log_decrement = match cycles.as_slice() {
        [first, .., last] if *last > 0.0 => (first / last).ln() / (cycles.len() - 1) as f64,
        _ => f64::NAN,
    };
    (frequency_hz, log_decrement)
}

/// The extremum at sample `i` refined by the parabola through it and its neighbours (time,
/// value): finer than the sampling, so that a frequency read off a few cycles is not rounded to
/// whole steps.
fn vertex(series: &[(f64, f64)], i: usize) -> (f64, f64) {
    let (Some(before), Some(after)) = (i.checked_sub(1).map(|j| series[j]), series.get(i + 1)) else {
        return series[i];
    };
    let (y0, y1, y2) = (before.1, series[i].1, after.1);
    let curvature = y0 - 2.0 * y1 + y2;
    let h = 0.5 * (after.0 - before.0);
    if curvature == 0.0 {
        return series[i];
    }
    let shift = 0.5 * (y0 - y2) / curvature;
    (series[i].0 + shift * h, y1 - 0.25 * (y0 - y2) * shift)
}

/// Residual vibration of `series` (time, value) from `from_s` on, read as a tip deflection (its
/// `amplitude_m` is in the series' unit).
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
            signal: ResidualSignal::TipDeflection,
            hub_rate_amplitude_rad_s: None,
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
        signal: ResidualSignal::TipDeflection,
        hub_rate_amplitude_rad_s: None,
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

    /// Under an actuator the frequency and decay are the hub rate's, the amplitude the tip's.
    #[test]
    fn a_run_under_an_actuator_reads_the_hub_rate() {
        let (tip_hz, hub_hz) = (9.0, 3.8);
        let wave = |f: f64, a: f64| -> Vec<(f64, f64)> {
            (0..100_000).map(|i| i as f64 * 1e-4).map(|t| (t, a * (std::f64::consts::TAU * f * t).sin())).collect()
        };
        let (tip, hub) = (wave(tip_hz, 1e-4), wave(hub_hz, 0.02));
        let ideal = residual_of_run(&tip, None, 0.0);
        assert_eq!(ideal.signal, ResidualSignal::TipDeflection);
        assert!((ideal.frequency_hz - tip_hz).abs() < 1e-2 && ideal.hub_rate_amplitude_rad_s.is_none());
        let actuated = residual_of_run(&tip, Some(&hub), 0.0);
        assert_eq!(actuated.signal, ResidualSignal::HubRate);
        assert!((actuated.frequency_hz - hub_hz).abs() < 1e-2, "{}", actuated.frequency_hz);
        assert!((actuated.amplitude_m - 1e-4).abs() < 1e-7);
        assert!((actuated.hub_rate_amplitude_rad_s.unwrap() - 0.02).abs() < 1e-5);
    }

    /// A well damped ring on a slow drift (a hub settling under its controller): the swings give
    /// its damped frequency and decrement where the mean's crossings cannot.
    #[test]
    fn a_damped_ring_on_a_drift_is_read_from_its_swings() {
        let (zeta, f) = (0.17_f64, 3.9);
        let w = std::f64::consts::TAU * f;
        let wd = w * (1.0 - zeta * zeta).sqrt();
        let s: Vec<(f64, f64)> = (0..50_000)
            .map(|i| i as f64 * 1e-4)
            .map(|t| (t, (-zeta * w * t).exp() * (wd * t).sin() + 0.15 * (-1.5 * t).exp()))
            .collect();
        let (frequency_hz, log_decrement) = swings(&s);
        let exact = std::f64::consts::TAU * zeta / (1.0 - zeta * zeta).sqrt();
        assert!((frequency_hz / (wd / std::f64::consts::TAU) - 1.0).abs() < 0.03, "{frequency_hz}");
        assert!((log_decrement / exact - 1.0).abs() < 0.1, "{log_decrement} vs {exact}");
    }

    #[test]
    fn classes_follow_the_seed_bands() {
        assert_eq!(StiffnessClass::of_ratio(1.0 / 800.0), StiffnessClass::Rigid);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 500.0), StiffnessClass::RigidFlexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 300.0), StiffnessClass::Flexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 200.0), StiffnessClass::BeyondYield);
    }
}
