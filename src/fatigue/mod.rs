//! Fatigue of a stress history: rainflow cycles ([`rainflow`], ASTM E1049-85), an S–N curve of
//! the welded detail ([`sn`], EN 1993-1-9 or DNVGL-RP-C203 in air), and Palmgren–Miner's linear
//! damage sum D = Σ nᵢ / Nᵢ, a half cycle counting one half.
//!
//! A run is one lift, so the damage of its history is the damage per lift and 1/D the lifts to
//! failure. Mean stress is not corrected for (welded details: the standards' curves hold at any
//! mean, residual stresses being near yield).

pub mod rainflow;
pub mod sn;

use serde::Serialize;
use thiserror::Error;

pub use rainflow::Cycle;
pub use sn::SnCurve;

/// A detail or curve name outside the tables.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FatigueError {
    /// Not an EN 1993-1-9 detail category.
    #[error("`{detail}` is not an EN 1993-1-9 detail category: allowed {allowed}")]
    UnknownDetail { detail: String, allowed: String },
    /// Not a DNVGL-RP-C203 curve in air.
    #[error("`{curve}` is not a DNVGL-RP-C203 curve in air: allowed {allowed}")]
    UnknownCurve { curve: String, allowed: String },
}

/// Palmgren–Miner damage of `cycles` (ranges in Pa) on `curve`, each range multiplied by
/// `stress_factor` first.
pub fn miner_damage(cycles: &[Cycle], curve: &SnCurve, stress_factor: f64) -> f64 {
    cycles.iter().map(|c| c.count / curve.cycles_to_failure(stress_factor * c.range)).sum()
}

/// What one lift does to a detail.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LiftDamage {
    /// Palmgren–Miner damage of the lift.
    pub damage_per_lift: f64,
    /// 1 / damage (`None` when the lift does no damage: every range below the cut-off).
    pub lifts_to_failure: Option<f64>,
    /// Largest stress range counted, Pa (before the stress factor).
    pub max_range_pa: f64,
    /// Cycles counted (a half cycle counts one half).
    pub cycles: f64,
}

impl LiftDamage {
    /// The damage of one lift's stress `history` (Pa) on `curve`, ranges × `stress_factor`.
    pub fn of(history: &[f64], curve: &SnCurve, stress_factor: f64) -> Self {
        let cycles = rainflow::count(history);
        let damage = miner_damage(&cycles, curve, stress_factor);
        LiftDamage {
            damage_per_lift: damage,
            lifts_to_failure: (damage > 0.0).then(|| 1.0 / damage),
            max_range_pa: cycles.iter().map(|c| c.range).fold(0.0, f64::max),
            cycles: cycles.iter().map(|c| c.count).sum(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `periods` cycles between `low` and `high`, starting and ending on `high`.
    fn block(high: f64, low: f64, periods: usize) -> Vec<f64> {
        let mut out = vec![high];
        for _ in 0..periods {
            out.extend([low, high]);
        }
        out
    }

    #[test]
    fn a_two_level_block_history_sums_as_miner_by_hand() {
        // 400 cycles of 150 MPa, then 30 000 of 45 MPa oscillating below the peak, on detail 71.
        // By hand (EN 1993-1-9): N1 = 2e6 (71/150)^3; 45 MPa lies between Δσ_L = 28.7 and
        // Δσ_D = 52.3 MPa, so N2 = 5e6 (Δσ_D / 45)^5 with Δσ_D = (2/5)^(1/3) 71.
        let mut history = block(75e6, -75e6, 400);
        history.extend(block(75e6, 30e6, 30_000).into_iter().skip(1));
        let n1 = 2e6 * (71.0f64 / 150.0).powi(3);
        let delta_d = 0.4f64.powf(1.0 / 3.0) * 71.0;
        let n2 = 5e6 * (delta_d / 45.0).powi(5);
        let by_hand = 400.0 / n1 + 30_000.0 / n2;
        let lift = LiftDamage::of(&history, &SnCurve::en1993("71").unwrap(), 1.0);
        assert!((lift.damage_per_lift / by_hand - 1.0).abs() < 1e-12, "{} vs {by_hand}", lift.damage_per_lift);
        assert!((lift.lifts_to_failure.unwrap() * by_hand - 1.0).abs() < 1e-12);
        assert_eq!(lift.cycles, 30_400.0);
        assert_eq!(lift.max_range_pa, 150e6);
    }

    #[test]
    fn a_constant_amplitude_sine_fails_at_the_curves_count() {
        // k cycles at Δσ use up k / N(Δσ): N(Δσ) of them is one failure, on both standards.
        for curve in [SnCurve::en1993("90").unwrap(), SnCurve::dnv("dnv-f").unwrap()] {
            let range = 120e6;
            let history: Vec<f64> =
                (0..=24 * 50).map(|i| 0.5 * range * (std::f64::consts::PI * i as f64 / 12.0).cos()).collect();
            let lift = LiftDamage::of(&history, &curve, 1.0);
            assert!((lift.damage_per_lift * curve.cycles_to_failure(range) / 50.0 - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn stress_below_the_cut_off_does_no_damage() {
        let curve = SnCurve::en1993("80").unwrap();
        let below = 0.99 * curve.cut_off_pa();
        let lift = LiftDamage::of(&block(below, 0.0, 10_000), &curve, 1.0);
        assert_eq!(lift.damage_per_lift, 0.0);
        assert_eq!(lift.lifts_to_failure, None);
        assert_eq!(lift.cycles, 10_000.0);
        // The same history factored past the cut-off does damage.
        assert!(LiftDamage::of(&block(below, 0.0, 10_000), &curve, 1.05).damage_per_lift > 0.0);
    }

    #[test]
    fn the_stress_factor_scales_damage_by_its_slope_power() {
        // Above Δσ_D, EN's slope is 3: a factor γ multiplies the damage by γ^3.
        let curve = SnCurve::en1993("71").unwrap();
        let history = block(100e6, -100e6, 50);
        let (one, more) = (LiftDamage::of(&history, &curve, 1.0), LiftDamage::of(&history, &curve, 1.35));
        assert!((more.damage_per_lift / one.damage_per_lift - 1.35f64.powi(3)).abs() < 1e-12);
    }
}
