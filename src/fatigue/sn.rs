//! S–N curves of welded steel details: cycles to failure N at a constant stress range Δσ.
//!
//! - **EN 1993-1-9:2005** (Eurocode 3, fatigue), §7.1 and Fig. 7.1: a detail category is its
//!   reference strength Δσ_C (MPa) at N_C = 2·10⁶ cycles; slope m = 3 down to the constant
//!   amplitude limit Δσ_D = (2/5)^(1/3) Δσ_C at 5·10⁶, slope m = 5 from there to the cut-off
//!   Δσ_L = (5/100)^(1/5) Δσ_D at 10⁸; no damage below Δσ_L. The categories of its Tables 8.1–8.10:
//!   160, 140, 125, 112, 100, 90, 80, 71, 63, 56, 50, 45, 40, 36.
//! - **DNVGL-RP-C203** (April 2016 edition), Table 2-1, S–N curves in air: log N = log ā₁ − m₁
//!   log Δσ for N ≤ 10⁷, log N = log ā₂ − 5 log Δσ beyond, Δσ in MPa, with no cut-off. The 2024
//!   edition revises B1, B2, C, C1 and C2; these are the 2016 values. The thickness correction
//!   (t/25 mm)^k for walls over 25 mm is not applied.
//!
//! Ranges are in Pa here, as everywhere in pipearm; the standards' MPa are converted once.

use super::FatigueError;

/// EN 1993-1-9's detail categories, Δσ_C in MPa.
pub const EN_DETAIL_CATEGORIES: [f64; 14] =
    [160.0, 140.0, 125.0, 112.0, 100.0, 90.0, 80.0, 71.0, 63.0, 56.0, 50.0, 45.0, 40.0, 36.0];

/// A DNVGL-RP-C203 curve in air: its name and (m₁, log ā₁, log ā₂); m₂ = 5, knee at 10⁷.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DnvCurve {
    /// The curve's letter as the standard names it (`D`, `F1`, `W3`, ...).
    pub name: &'static str,
    /// Slope below 10⁷ cycles.
    pub m1: f64,
    /// log₁₀ ā₁ (Δσ in MPa), N ≤ 10⁷.
    pub log_a1: f64,
    /// log₁₀ ā₂ (Δσ in MPa), N > 10⁷.
    pub log_a2: f64,
}

const fn dnv(name: &'static str, m1: f64, log_a1: f64, log_a2: f64) -> DnvCurve {
    DnvCurve { name, m1, log_a1, log_a2 }
}

/// DNVGL-RP-C203 (2016), Table 2-1: S–N curves in air.
pub const DNV_CURVES_IN_AIR: [DnvCurve; 14] = [
    dnv("B1", 4.0, 15.117, 17.146),
    dnv("B2", 4.0, 14.885, 16.856),
    dnv("C", 3.0, 12.592, 16.320),
    dnv("C1", 3.0, 12.449, 16.081),
    dnv("C2", 3.0, 12.301, 15.835),
    dnv("D", 3.0, 12.164, 15.606),
    dnv("E", 3.0, 12.010, 15.350),
    dnv("F", 3.0, 11.855, 15.091),
    dnv("F1", 3.0, 11.699, 14.832),
    dnv("F3", 3.0, 11.546, 14.576),
    dnv("G", 3.0, 11.398, 14.330),
    dnv("W1", 3.0, 11.261, 14.101),
    dnv("W2", 3.0, 11.107, 13.845),
    dnv("W3", 3.0, 10.970, 13.617),
];

/// DNV's knee: the slope changes at 10⁷ cycles.
const DNV_KNEE_CYCLES: f64 = 1e7;
const DNV_SLOPE_BEYOND_KNEE: f64 = 5.0;

const MPA: f64 = 1e6;

/// An S–N curve a segment or a gauge is checked against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SnCurve {
    /// EN 1993-1-9 detail category, Δσ_C in Pa.
    En1993 { detail_category_pa: f64 },
    /// A DNVGL-RP-C203 curve in air.
    DnvInAir(DnvCurve),
}

impl SnCurve {
    /// The EN 1993-1-9 detail category written as `detail` (`"71"`).
    pub fn en1993(detail: &str) -> Result<Self, FatigueError> {
        let allowed = || EN_DETAIL_CATEGORIES.map(|c| format!("\"{c}\"")).join(", ");
        let value: f64 = detail
            .trim()
            .parse()
            .map_err(|_| FatigueError::UnknownDetail { detail: detail.into(), allowed: allowed() })?;
        if EN_DETAIL_CATEGORIES.contains(&value) {
            Ok(SnCurve::En1993 { detail_category_pa: value * MPA })
        } else {
            Err(FatigueError::UnknownDetail { detail: detail.into(), allowed: allowed() })
        }
    }

    /// The DNVGL-RP-C203 curve in air written as `curve` (`"dnv-d"`, case-insensitive).
    pub fn dnv(curve: &str) -> Result<Self, FatigueError> {
        let allowed = || DNV_CURVES_IN_AIR.map(|c| format!("\"dnv-{}\"", c.name.to_lowercase())).join(", ");
        curve
            .trim()
            .to_ascii_lowercase()
            .strip_prefix("dnv-")
            .and_then(|letter| DNV_CURVES_IN_AIR.iter().find(|c| c.name.eq_ignore_ascii_case(letter)))
            .map(|c| SnCurve::DnvInAir(*c))
            .ok_or_else(|| FatigueError::UnknownCurve { curve: curve.into(), allowed: allowed() })
    }

    /// How a summary names it: `EN 1993-1-9 detail 71`, `DNVGL-RP-C203 D in air`.
    pub fn describe(&self) -> String {
        match self {
            SnCurve::En1993 { detail_category_pa } => format!("EN 1993-1-9 detail {}", detail_category_pa / MPA),
            SnCurve::DnvInAir(c) => format!("DNVGL-RP-C203 {} in air", c.name),
        }
    }

    /// The range below which a cycle does no damage, Pa (0 for a DNV curve in air, which has
    /// none).
    pub fn cut_off_pa(&self) -> f64 {
        match *self {
            SnCurve::En1993 { detail_category_pa } => en_limits(detail_category_pa).1,
            SnCurve::DnvInAir(_) => 0.0,
        }
    }

    /// Cycles to failure at a constant range `range_pa` (infinite below a cut-off, and for a
    /// zero range).
    pub fn cycles_to_failure(&self, range_pa: f64) -> f64 {
        if range_pa.is_nan() || range_pa <= 0.0 {
            return f64::INFINITY;
        }
        match *self {
            SnCurve::En1993 { detail_category_pa: c } => {
                let (d, l) = en_limits(c);
                if range_pa >= d {
                    2e6 * (c / range_pa).powi(3)
                } else if range_pa >= l {
                    5e6 * (d / range_pa).powi(5)
                } else {
                    f64::INFINITY
                }
            }
            SnCurve::DnvInAir(curve) => {
                let log_range = (range_pa / MPA).log10();
                let n1 = 10f64.powf(curve.log_a1 - curve.m1 * log_range);
                if n1 <= DNV_KNEE_CYCLES { n1 } else { 10f64.powf(curve.log_a2 - DNV_SLOPE_BEYOND_KNEE * log_range) }
            }
        }
    }
}

/// EN 1993-1-9's constant amplitude limit Δσ_D and cut-off Δσ_L of category Δσ_C, Pa.
fn en_limits(detail_category_pa: f64) -> (f64, f64) {
    let d = (0.4f64).powf(1.0 / 3.0) * detail_category_pa;
    (d, (0.05f64).powf(0.2) * d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn en_curve_passes_through_its_published_points() {
        // EN 1993-1-9 §7.1: detail 71 fails at 2e6 cycles of 71 MPa; Δσ_D = 0.737 Δσ_C at 5e6;
        // Δσ_L = 0.549 Δσ_D at 1e8 (the standard's rounded factors).
        let c = SnCurve::en1993("71").unwrap();
        assert!((c.cycles_to_failure(71e6) / 2e6 - 1.0).abs() < 1e-12);
        let d = 71e6 * 0.4f64.powf(1.0 / 3.0);
        assert!((d / 71e6 - 0.737).abs() < 5e-4);
        assert!((c.cycles_to_failure(d) / 5e6 - 1.0).abs() < 1e-9);
        let l = c.cut_off_pa();
        assert!((l / d - 0.549).abs() < 5e-4);
        assert!((c.cycles_to_failure(l) / 1e8 - 1.0).abs() < 1e-9);
        // Slope 3 above the knee, 5 between knee and cut-off.
        let ratio = c.cycles_to_failure(100e6) / c.cycles_to_failure(200e6);
        assert!((ratio - 8.0).abs() < 1e-9);
        let (a, b) = (0.99 * d, 0.99 * d / 1.2);
        assert!((c.cycles_to_failure(b) / c.cycles_to_failure(a) - 1.2f64.powi(5)).abs() < 1e-9);
    }

    #[test]
    fn below_the_cut_off_a_cycle_does_no_damage() {
        let c = SnCurve::en1993("36").unwrap();
        let l = c.cut_off_pa();
        assert!(c.cycles_to_failure(l * (1.0 - 1e-9)).is_infinite());
        assert!(c.cycles_to_failure(l * (1.0 + 1e-9)).is_finite());
        assert!(c.cycles_to_failure(0.0).is_infinite());
    }

    #[test]
    fn dnv_table_is_continuous_at_its_knee_with_its_published_fatigue_limits() {
        // Table 2-1's last column: the range at 1e7 cycles, MPa. Both of each curve's lines must
        // meet there: a check of every transcribed log ā (to the table's rounding: log ā to three
        // decimals moves the range by 10^(0.0005/3) - 1 = 4e-4, the limits to two decimals).
        let limits =
            [106.97, 93.59, 73.10, 65.50, 58.48, 52.63, 46.78, 41.52, 36.84, 32.75, 29.24, 26.32, 23.39, 21.05];
        for (curve, limit) in DNV_CURVES_IN_AIR.iter().zip(limits) {
            let at_knee = 10f64.powf((curve.log_a1 - 7.0) / curve.m1);
            assert!((at_knee / limit - 1.0).abs() < 6e-4, "{}: {at_knee} vs {limit}", curve.name);
            let second = 10f64.powf((curve.log_a2 - 7.0) / 5.0);
            assert!((second / limit - 1.0).abs() < 6e-4, "{}: {second} vs {limit}", curve.name);
            // Either side of the knee the curve gives 1e7 cycles, to that rounding times the slope.
            let c = SnCurve::DnvInAir(*curve);
            assert!((c.cycles_to_failure(1.0001 * limit * 1e6) / 1e7 - 1.0).abs() < 4e-3);
            assert!((c.cycles_to_failure(0.9999 * limit * 1e6) / 1e7 - 1.0).abs() < 4e-3);
        }
        // D at 100 MPa: 10^(12.164 - 6) = 1.459e6 cycles.
        let d = SnCurve::dnv("dnv-d").unwrap();
        assert!((d.cycles_to_failure(100e6) / 10f64.powf(6.164) - 1.0).abs() < 1e-12);
        // Below the knee slope 5, no cut-off: 20 MPa on D gives 10^(15.606 - 5 log 20).
        assert!((d.cycles_to_failure(20e6) / 10f64.powf(15.606 - 5.0 * 20f64.log10()) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn unknown_names_say_what_is_allowed() {
        let e = SnCurve::en1993("70").unwrap_err().to_string();
        assert!(e.contains("\"71\"") && e.contains("\"36\""), "{e}");
        let e = SnCurve::dnv("dnv-x").unwrap_err().to_string();
        assert!(e.contains("\"dnv-d\"") && e.contains("\"dnv-w3\""), "{e}");
        assert!(SnCurve::dnv("d").is_err());
        assert_eq!(SnCurve::dnv("DNV-F1").unwrap().describe(), "DNVGL-RP-C203 F1 in air");
        assert_eq!(SnCurve::en1993("112").unwrap().describe(), "EN 1993-1-9 detail 112");
    }
}
