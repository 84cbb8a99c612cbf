//! Input shapers: short sequences of impulses which, convolved with a motion, leave a
//! second-order mode of known frequency and damping without residual vibration.
//!
//! Each impulse of the sequence starts a copy of the mode's vibration; the shaper chooses the
//! times and amplitudes so that the copies cancel at the design frequency (and, for the robust
//! shapers, stay small around it). The amplitudes are positive and sum to 1, so a shaped motion
//! reaches the same end angle; it lasts longer by the shaper's length.
//!
//! Several modes are cancelled by the convolution of one shaper per mode
//! ([`Shaper::impulses_for`]): the residual vibration of a convolution is the product of its
//! factors' at every frequency (their sums of rotating vectors multiply), so it vanishes wherever
//! one factor's does (Singer and Seering 1990; J. M. Hyde and W. P. Seering, "Using input command
//! pre-shaping to suppress multiple mode vibration", Proc. IEEE ICRA 1991, 2604–2609).
//!
//! Sources: N. C. Singer and W. P. Seering, "Preshaping command inputs to reduce system
//! vibration", ASME J. Dyn. Sys. Meas. Control 112 (1990) 76–82 (ZV, ZVD and the residual
//! vibration `V(ω, ζ)`); W. Singhose, W. Seering and N. Singer, "Residual vibration reduction
//! using vector diagrams to generate shaping inputs", ASME J. Mech. Design 116 (1994) 654–659
//! (EI).

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

/// Vibration the EI shaper tolerates at its design frequency, as a fraction of the unshaped
/// step's (Singhose et al. 1994 use 5 %).
pub const EI_TOLERANCE: f64 = 0.05;

/// A mode a shaper is tuned to: its natural frequency, Hz (> 0), and damping ratio (0 ≤ ζ < 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShaperMode {
    /// Natural frequency, Hz.
    pub frequency_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
}

/// An input shaper, tuned to one mode by [`Shaper::impulses`], to several by
/// [`Shaper::impulses_for`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Shaper {
    /// Zero vibration (Singer & Seering 1990): two impulses half a damped period apart; zero
    /// residual vibration at the design frequency, sensitive to an error in it.
    Zv,
    /// Zero vibration and derivative (Singer & Seering 1990): three impulses over one damped
    /// period; the residual vibration and its slope in frequency vanish at the design
    /// frequency, so a frequency error of ±20 % leaves under 10 %.
    Zvd,
    /// Extra insensitive (Singhose, Seering & Singer 1994): three impulses over one damped
    /// period that leave [`EI_TOLERANCE`] (5 %) at the design frequency, in exchange for a
    /// wider band below 5 % than ZVD's.
    Ei,
}

impl Shaper {
    /// Every shaper, in the order of their length and robustness.
    pub const ALL: [Shaper; 3] = [Shaper::Zv, Shaper::Zvd, Shaper::Ei];

    /// The name a scenario uses: `"zv"`, `"zvd"` or `"ei"`.
    pub fn name(self) -> &'static str {
        match self {
            Shaper::Zv => "zv",
            Shaper::Zvd => "zvd",
            Shaper::Ei => "ei",
        }
    }

    /// The impulses `(t_i s, A_i)` tuned to a mode of natural frequency `frequency_hz` (Hz, > 0)
    /// and damping ratio `damping_ratio` (0 ≤ ζ < 1), first at `t = 0`, amplitudes summing to 1.
    ///
    /// With the damped period `T_d = 1 / (f √(1 − ζ²))` and `K = exp(−ζπ / √(1 − ζ²))`:
    /// * ZV: times `[0, T_d/2]`, amplitudes `[1, K] / (1 + K)`;
    /// * ZVD: times `[0, T_d/2, T_d]`, amplitudes `[1, 2K, K²] / (1 + K)²`;
    /// * EI: times `[0, T_d/2, T_d]`, amplitudes `[(1 + V)/4, (1 − V)K/2, (1 + V)K²/4]`
    ///   normalised to sum 1, `V` = [`EI_TOLERANCE`]: Singhose et al.'s closed form, exact for an
    ///   undamped mode, with each impulse weighted by the decay over its delay as ZVD's are. For
    ///   damped modes Singhose et al. give curve fits of the optimal times and amplitudes; the
    ///   weighted form leaves a little less than `V` at the design frequency of a damped mode
    ///   (4.8 % at ζ = 0.01, 4.2 % at ζ = 0.05), which keeps its band below `V` about as wide.
    pub fn impulses(self, frequency_hz: f64, damping_ratio: f64) -> Vec<(f64, f64)> {
        let root = (1.0 - damping_ratio * damping_ratio).sqrt();
        let period_s = 1.0 / (frequency_hz * root);
        let k = (-damping_ratio * PI / root).exp();
        let weights: Vec<(f64, f64)> = match self {
            Shaper::Zv => vec![(0.0, 1.0), (0.5 * period_s, k)],
            Shaper::Zvd => vec![(0.0, 1.0), (0.5 * period_s, 2.0 * k), (period_s, k * k)],
            Shaper::Ei => {
                let v = EI_TOLERANCE;
                vec![
                    (0.0, 0.25 * (1.0 + v)),
                    (0.5 * period_s, 0.5 * (1.0 - v) * k),
                    (period_s, 0.25 * (1.0 + v) * k * k),
                ]
            }
        };
        let total: f64 = weights.iter().map(|w| w.1).sum();
        weights.into_iter().map(|(t, a)| (t, a / total)).collect()
    }

    /// How long the shaper lengthens a motion, s: its last impulse's time (`T_d/2` for ZV, `T_d`
    /// for ZVD and EI) at `frequency_hz` (Hz) and `damping_ratio`.
    pub fn length_s(self, frequency_hz: f64, damping_ratio: f64) -> f64 {
        self.impulses(frequency_hz, damping_ratio).last().map_or(0.0, |i| i.0)
    }

    /// The impulses cancelling every one of `modes`: the convolution of this shaper tuned to each
    /// ([`convolve`]). First at 0, amplitudes positive and summing to 1; as long as the modes'
    /// shapers together. A single impulse at 0 for no mode.
    pub fn impulses_for(self, modes: &[ShaperMode]) -> Vec<(f64, f64)> {
        modes.iter().fold(vec![(0.0, 1.0)], |product, mode| {
            convolve(&product, &self.impulses(mode.frequency_hz, mode.damping_ratio))
        })
    }

    /// How long the shaper tuned to every one of `modes` lengthens a motion, s: the sum of its
    /// lengths at each.
    pub fn length_for_s(self, modes: &[ShaperMode]) -> f64 {
        modes.iter().map(|m| self.length_s(m.frequency_hz, m.damping_ratio)).sum()
    }
}

/// Impulses closer than this fraction of the sequence's length are one.
const COINCIDENT_FRACTION: f64 = 1e-9;

/// The convolution of two impulse sequences `(t s, A)`: an impulse at `t_i + s_j` of amplitude
/// `A_i B_j` for every pair, coincident ones merged (amplitudes summed), in time order. Amplitudes
/// summing to 1 in each give a product summing to 1; its residual vibration at any mode is the
/// product of the two's ([`residual_vibration`]).
pub fn convolve(a: &[(f64, f64)], b: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut pairs: Vec<(f64, f64)> = a.iter().flat_map(|&(t, x)| b.iter().map(move |&(s, y)| (t + s, x * y))).collect();
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let length = pairs.last().map_or(0.0, |p| p.0);
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(pairs.len());
    for (t, amplitude) in pairs {
        match merged.last_mut() {
            Some(last) if t - last.0 <= COINCIDENT_FRACTION * length => last.1 += amplitude,
            _ => merged.push((t, amplitude)),
        }
    }
    merged
}

/// Residual vibration left by the impulses `(t_i s, A_i)` on a second-order mode of natural
/// frequency `frequency_hz` (Hz) and damping ratio `damping_ratio` (0 ≤ ζ < 1), as a fraction of
/// a single unit impulse's (1 = 100 %, what an unshaped step leaves):
/// `V = e^{−ζω t_N} √(C² + S²)`, `C = Σ A_i e^{ζω t_i} cos(ω_d t_i)`,
/// `S = Σ A_i e^{ζω t_i} sin(ω_d t_i)`, `ω = 2πf`, `ω_d = ω√(1 − ζ²)`, `t_N` the last impulse's
/// time (Singer & Seering 1990). The same ratio holds for any motion convolved with the
/// impulses: it is the residual amplitude of the shaped motion over the unshaped one's.
pub fn residual_vibration(impulses: &[(f64, f64)], frequency_hz: f64, damping_ratio: f64) -> f64 {
    let omega = 2.0 * PI * frequency_hz;
    let omega_d = omega * (1.0 - damping_ratio * damping_ratio).sqrt();
    let decay = damping_ratio * omega;
    let t_last = impulses.last().map_or(0.0, |i| i.0);
    let (c, s) = impulses.iter().fold((0.0, 0.0), |(c, s), &(t, a)| {
        // Relative to the last impulse, so the exponentials stay ≤ 1.
        let w = a * (decay * (t - t_last)).exp();
        (c + w * (omega_d * t).cos(), s + w * (omega_d * t).sin())
    });
    c.hypot(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64, what: &str) {
        assert!((a - b).abs() <= tol, "{what}: got {a}, expected {b}");
    }

    /// At ζ = 0 the textbook closed forms (Singer & Seering 1990; Singhose et al. 1994).
    #[test]
    fn undamped_shapers_are_the_textbook_closed_forms() {
        let f = 0.8;
        let t = 1.0 / f;
        let v = EI_TOLERANCE;
        let expected: [(Shaper, Vec<(f64, f64)>); 3] = [
            (Shaper::Zv, vec![(0.0, 0.5), (t / 2.0, 0.5)]),
            (Shaper::Zvd, vec![(0.0, 0.25), (t / 2.0, 0.5), (t, 0.25)]),
            (Shaper::Ei, vec![(0.0, (1.0 + v) / 4.0), (t / 2.0, (1.0 - v) / 2.0), (t, (1.0 + v) / 4.0)]),
        ];
        for (shaper, want) in expected {
            let got = shaper.impulses(f, 0.0);
            assert_eq!(got.len(), want.len(), "{shaper:?}");
            for ((tg, ag), (tw, aw)) in got.iter().zip(&want) {
                close(*tg, *tw, 1e-14, "time");
                close(*ag, *aw, 1e-14, "amplitude");
            }
            close(shaper.length_s(f, 0.0), want.last().unwrap().0, 1e-14, "length");
        }
    }

    #[test]
    fn amplitudes_sum_to_one_and_times_use_the_damped_period() {
        for shaper in Shaper::ALL {
            for zeta in [0.0, 0.02, 0.1, 0.3] {
                let impulses = shaper.impulses(1.3, zeta);
                close(impulses.iter().map(|i| i.1).sum(), 1.0, 1e-14, "sum");
                assert!(impulses.iter().all(|i| i.1 > 0.0));
                let period = 1.0 / (1.3 * (1.0 - zeta * zeta).sqrt());
                close(impulses[1].0, 0.5 * period, 1e-14, "second impulse at T_d/2");
            }
        }
    }

    /// ZV and ZVD cancel a damped mode exactly at their design frequency; EI leaves its
    /// tolerance V = 5 % (exactly when undamped).
    #[test]
    fn residual_at_the_design_frequency() {
        for zeta in [0.0, 0.05, 0.2] {
            for shaper in [Shaper::Zv, Shaper::Zvd] {
                let v = residual_vibration(&shaper.impulses(2.0, zeta), 2.0, zeta);
                assert!(v < 1e-14, "{shaper:?} at ζ = {zeta}: {v}");
            }
        }
        close(residual_vibration(&Shaper::Ei.impulses(2.0, 0.0), 2.0, 0.0), EI_TOLERANCE, 1e-14, "EI at ζ = 0");
        // The damped approximation leaves a little less than V at the design frequency.
        for zeta in [0.01, 0.05] {
            let damped = residual_vibration(&Shaper::Ei.impulses(2.0, zeta), 2.0, zeta);
            assert!(damped > 0.8 * EI_TOLERANCE && damped <= EI_TOLERANCE, "EI at ζ = {zeta}: {damped}");
        }
    }

    /// Undamped: V = |cos(πr/2)| for ZV and cos²(πr/2) for ZVD at r = ω/ω_design (the textbook
    /// sensitivity curves); a single impulse leaves 1.
    #[test]
    fn undamped_sensitivity_curves() {
        for r in [0.5, 0.7, 0.9, 1.1, 1.3, 1.5] {
            let c = (0.5 * PI * r).cos();
            close(residual_vibration(&Shaper::Zv.impulses(1.0, 0.0), r, 0.0), c.abs(), 1e-13, "ZV");
            close(residual_vibration(&Shaper::Zvd.impulses(1.0, 0.0), r, 0.0), c * c, 1e-13, "ZVD");
        }
        close(residual_vibration(&[(0.0, 1.0)], 1.0, 0.1), 1.0, 1e-15, "single impulse");
    }

    /// Two modes: ZVD per mode convolved leaves nothing at either design frequency, its residual
    /// is the product of the factors' everywhere, and it keeps sum 1 and positive amplitudes.
    #[test]
    fn convolved_shapers_cancel_every_mode() {
        let modes = [
            ShaperMode { frequency_hz: 2.85, damping_ratio: 0.01 },
            ShaperMode { frequency_hz: 5.1, damping_ratio: 0.03 },
        ];
        for shaper in [Shaper::Zv, Shaper::Zvd] {
            let product = shaper.impulses_for(&modes);
            close(product.iter().map(|i| i.1).sum(), 1.0, 1e-14, "sum");
            assert!(product.iter().all(|i| i.1 > 0.0) && product[0].0 == 0.0);
            close(product.last().unwrap().0, shaper.length_for_s(&modes), 1e-14, "length");
            for m in modes {
                let v = residual_vibration(&product, m.frequency_hz, m.damping_ratio);
                assert!(v < 1e-13, "{shaper:?} at {} Hz: {v}", m.frequency_hz);
            }
            for (f, zeta) in [(1.0, 0.0), (3.7, 0.02), (9.0, 0.05)] {
                let each: f64 = modes
                    .iter()
                    .map(|m| residual_vibration(&shaper.impulses(m.frequency_hz, m.damping_ratio), f, zeta))
                    .product();
                close(residual_vibration(&product, f, zeta), each, 1e-13, "product of the factors'");
            }
        }
    }

    /// Modes an octave apart: ZVD's impulses at 0, T/4, T/2 (2f) and 0, T/2, T (f) sum to
    /// coincident times, merged; undamped, the seven impulses at kT/4 are [1, 2, 3, 4, 3, 2, 1]/16.
    #[test]
    fn coincident_impulses_are_merged() {
        let modes = [
            ShaperMode { frequency_hz: 1.0, damping_ratio: 0.0 },
            ShaperMode { frequency_hz: 2.0, damping_ratio: 0.0 },
        ];
        let product = Shaper::Zvd.impulses_for(&modes);
        assert_eq!(product.len(), 7, "{product:?}");
        for (k, (t, a)) in product.iter().enumerate() {
            close(*t, 0.25 * k as f64, 1e-14, "time");
            close(*a, [1.0, 2.0, 3.0, 4.0, 3.0, 2.0, 1.0][k] / 16.0, 1e-14, "amplitude");
        }
        assert_eq!(Shaper::Zvd.impulses_for(&[]), vec![(0.0, 1.0)]);
    }

    #[test]
    fn names_round_trip_through_serde() {
        for shaper in Shaper::ALL {
            let text = format!("\"{}\"", shaper.name());
            assert_eq!(serde_json::from_str::<Shaper>(&text).unwrap(), shaper);
        }
    }
}
