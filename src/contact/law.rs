//! Continuous contact force laws for a rubber dampener: Hunt & Crossley (1975), Lankarani &
//! Nikravesh (1990), Flores et al. (2011) and MSC ADAMS's IMPACT function.
//!
//! Penetration δ ≥ 0 (m) and its rate δ̇ (m/s, positive while closing). The force is the normal
//! push of the pad, N, never a pull: laws whose damping term would pull during separation are
//! clipped at zero, as a real pad cannot hold the arm.

use serde::{Deserialize, Serialize};

/// A force law with its parameters; `stiffness` is in N/m^exponent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ForceLaw {
    /// F = k δ + c δ̇.
    Linear { stiffness_n_m: f64, damping_n_s_m: f64 },
    /// Hunt–Crossley (1975): F = K δⁿ (1 + χ δ̇/v₀), χ = 3(1 − e)/2.
    HuntCrossley { stiffness: f64, exponent: f64, restitution: f64 },
    /// Lankarani–Nikravesh (1990): χ = 3(1 − e²)/4 (valid near e ≈ 1).
    LankaraniNikravesh { stiffness: f64, exponent: f64, restitution: f64 },
    /// Flores et al. (2011): χ = 8(1 − e)/(5e) (tracks soft, rubber-like impacts).
    Flores { stiffness: f64, exponent: f64, restitution: f64 },
    /// MSC ADAMS IMPACT: F = k δᵉ + STEP(δ, 0, 0, d, c_max) δ̇.
    AdamsImpact { stiffness: f64, exponent: f64, max_damping_n_s_m: f64, full_damping_depth_m: f64 },
}

impl ForceLaw {
    /// Normal force, N, at penetration `depth_m`, closing rate `rate_m_s` and first-touch speed
    /// `impact_speed_m_s` (the v₀ of the restitution-based laws).
    pub fn force_n(&self, depth_m: f64, rate_m_s: f64, impact_speed_m_s: f64) -> f64 {
        if depth_m <= 0.0 {
            return 0.0;
        }
        let f = match *self {
            ForceLaw::Linear { stiffness_n_m, damping_n_s_m } => stiffness_n_m * depth_m + damping_n_s_m * rate_m_s,
            ForceLaw::AdamsImpact { stiffness, exponent, max_damping_n_s_m, full_damping_depth_m } => {
                stiffness * depth_m.powf(exponent)
                    + cubic_step(depth_m, full_damping_depth_m) * max_damping_n_s_m * rate_m_s
            }
            _ => {
                let (k, n, chi) = self.dissipative_hertz().expect("restitution laws");
                let v0 = impact_speed_m_s.abs().max(1e-9);
                k * depth_m.powf(n) * (1.0 + chi * rate_m_s / v0)
            }
        };
        f.max(0.0)
    }

    /// ∂F/∂δ and ∂F/∂δ̇ at a state (0 outside contact); the implicit step uses them.
    pub fn derivatives(&self, depth_m: f64, rate_m_s: f64, impact_speed_m_s: f64) -> (f64, f64) {
        if depth_m <= 0.0 || self.force_n(depth_m, rate_m_s, impact_speed_m_s) <= 0.0 {
            return (0.0, 0.0);
        }
        match *self {
            ForceLaw::Linear { stiffness_n_m, damping_n_s_m } => (stiffness_n_m, damping_n_s_m),
            ForceLaw::AdamsImpact { stiffness, exponent, max_damping_n_s_m, full_damping_depth_m } => {
                let d = full_damping_depth_m;
                let step = cubic_step(depth_m, d);
                let dstep = if depth_m < d { 6.0 * depth_m * (d - depth_m) / d.powi(3) } else { 0.0 };
                (
                    stiffness * exponent * depth_m.powf(exponent - 1.0) + dstep * max_damping_n_s_m * rate_m_s,
                    step * max_damping_n_s_m,
                )
            }
            _ => {
                let (k, n, chi) = self.dissipative_hertz().expect("restitution laws");
                let v0 = impact_speed_m_s.abs().max(1e-9);
                (k * n * depth_m.powf(n - 1.0) * (1.0 + chi * rate_m_s / v0), k * depth_m.powf(n) * chi / v0)
            }
        }
    }

    /// The elastic part's tangent stiffness dF/dδ where the elastic force equals `force_n`, N/m
    /// (what the explicit penalty limit 2√(m_eff/k) needs).
    pub fn tangent_stiffness_at_force(&self, force_n: f64) -> f64 {
        let (k, n) = match *self {
            ForceLaw::Linear { stiffness_n_m, .. } => return stiffness_n_m,
            ForceLaw::AdamsImpact { stiffness, exponent, .. } => (stiffness, exponent),
            ForceLaw::HuntCrossley { stiffness, exponent, .. }
            | ForceLaw::LankaraniNikravesh { stiffness, exponent, .. }
            | ForceLaw::Flores { stiffness, exponent, .. } => (stiffness, exponent),
        };
        let depth_m = (force_n.max(0.0) / k).powf(1.0 / n);
        k * n * depth_m.powf(n - 1.0)
    }

    /// The coefficient of restitution the law is set for, if it is one of the restitution-based
    /// laws.
    pub fn restitution(&self) -> Option<f64> {
        match *self {
            ForceLaw::HuntCrossley { restitution, .. }
            | ForceLaw::LankaraniNikravesh { restitution, .. }
            | ForceLaw::Flores { restitution, .. } => Some(restitution),
            _ => None,
        }
    }

    /// (K, n, χ) of the three restitution-based laws.
    fn dissipative_hertz(&self) -> Option<(f64, f64, f64)> {
        match *self {
            ForceLaw::HuntCrossley { stiffness, exponent, restitution: e } => {
                Some((stiffness, exponent, 1.5 * (1.0 - e)))
            }
            ForceLaw::LankaraniNikravesh { stiffness, exponent, restitution: e } => {
                Some((stiffness, exponent, 0.75 * (1.0 - e * e)))
            }
            ForceLaw::Flores { stiffness, exponent, restitution: e } => {
                Some((stiffness, exponent, 8.0 * (1.0 - e) / (5.0 * e)))
            }
            _ => None,
        }
    }

    /// Checks the parameters; the error names the key and its allowed range.
    pub fn validate(&self) -> Result<(), (&'static str, f64, &'static str)> {
        let positive = |name, v: f64| if v.is_finite() && v > 0.0 { Ok(()) } else { Err((name, v, "> 0")) };
        let non_negative = |name, v: f64| if v.is_finite() && v >= 0.0 { Ok(()) } else { Err((name, v, ">= 0")) };
        let exponent =
            |v: f64| if v.is_finite() && (1.0..=4.0).contains(&v) { Ok(()) } else { Err(("exponent", v, "1 ..= 4")) };
        let restitution =
            |v: f64| if v.is_finite() && v > 0.0 && v <= 1.0 { Ok(()) } else { Err(("restitution", v, "0 < e <= 1")) };
        match *self {
            ForceLaw::Linear { stiffness_n_m, damping_n_s_m } => {
                positive("stiffness_n_m", stiffness_n_m)?;
                non_negative("damping_n_s_m", damping_n_s_m)
            }
            ForceLaw::HuntCrossley { stiffness, exponent: n, restitution: e }
            | ForceLaw::LankaraniNikravesh { stiffness, exponent: n, restitution: e }
            | ForceLaw::Flores { stiffness, exponent: n, restitution: e } => {
                positive("stiffness", stiffness)?;
                exponent(n)?;
                restitution(e)
            }
            ForceLaw::AdamsImpact { stiffness, exponent: n, max_damping_n_s_m, full_damping_depth_m } => {
                positive("stiffness", stiffness)?;
                exponent(n)?;
                non_negative("max_damping_n_s_m", max_damping_n_s_m)?;
                positive("full_damping_depth_m", full_damping_depth_m)
            }
        }
    }
}

/// ADAMS' cubic STEP from 0 at δ = 0 to 1 at δ = d.
fn cubic_step(depth_m: f64, full_depth_m: f64) -> f64 {
    let s = (depth_m / full_depth_m).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}
