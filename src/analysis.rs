//! Quantities users judge a run by: peaks, residual vibration, its frequency, and the seed's
//! [w/l] classification.

use crate::arm::ArmSample;

/// Summary of a lift.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftSummary {
    /// Largest |tip deflection| (hub frame, transverse) over the run, m.
    pub peak_tip_deflection_m: f64,
    /// Half the peak-to-peak tip deflection after the drive stopped, m.
    pub residual_amplitude_m: f64,
    /// Residual vibration frequency from zero crossings about the final mean, Hz (NaN if fewer
    /// than two crossings).
    pub residual_frequency_hz: f64,
    /// Largest |drive torque|, N·m.
    pub peak_drive_torque_n_m: f64,
}

/// Summarises `samples`; the residual phase is every sample at or after `drive_end_s`.
pub fn summarize(samples: &[ArmSample], drive_end_s: f64) -> LiftSummary {
    let deflection = |s: &ArmSample| s.tip_deflection_hub_m[1];
    let peak_tip_deflection_m = samples.iter().map(|s| deflection(s).abs()).fold(0.0, f64::max);
    let peak_drive_torque_n_m = samples.iter().map(|s| s.drive_torque_n_m.abs()).fold(0.0, f64::max);
    let residual: Vec<(f64, f64)> =
        samples.iter().filter(|s| s.t_s >= drive_end_s).map(|s| (s.t_s, deflection(s))).collect();
    let (lo, hi) = residual.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(_, v)| (lo.min(v), hi.max(v)));
    let residual_amplitude_m = if residual.is_empty() { 0.0 } else { 0.5 * (hi - lo) };
    LiftSummary {
        peak_tip_deflection_m,
        residual_amplitude_m,
        residual_frequency_hz: crossing_frequency_hz(&residual),
        peak_drive_torque_n_m,
    }
}

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
    fn classes_follow_the_seed_bands() {
        assert_eq!(StiffnessClass::of_ratio(1.0 / 800.0), StiffnessClass::Rigid);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 500.0), StiffnessClass::RigidFlexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 300.0), StiffnessClass::Flexible);
        assert_eq!(StiffnessClass::of_ratio(1.0 / 200.0), StiffnessClass::BeyondYield);
    }
}
