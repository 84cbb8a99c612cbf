//! Shared builders for the integration tests.
#![allow(dead_code)]

use pipearm::beam::{BeamModel, BeamSpec, Segment};
use pipearm::scenario::DriveSpec;

/// A uniform arm with EI, ρA, length; EA stiff enough that the first axial mode sits far above
/// the bending modes tested.
pub fn uniform(length_m: f64, ei: f64, rho_a: f64, elements: usize) -> BeamSpec {
    BeamSpec::uniform(
        Segment {
            length_m,
            axial_rigidity_n: 1e6 * ei / (length_m * length_m),
            bending_rigidity_n_m2: ei,
            mass_per_length_kg_m: rho_a,
        },
        elements,
    )
}

/// λ_i = L (ω_i² ρA / EI)^(1/4) of the first `n` modes of a model.
pub fn lambdas(omegas: &[f64], length_m: f64, ei: f64, rho_a: f64, n: usize) -> Vec<f64> {
    omegas[..n].iter().map(|w| length_m * (w * w * rho_a / ei).powf(0.25)).collect()
}

/// Builds the model, panicking with the error (tests only).
pub fn model(spec: BeamSpec) -> BeamModel {
    BeamModel::new(spec).expect("valid beam")
}

/// Relative error.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// First root λ of the hub-inertia characteristic equation (reference table):
/// (sin λ cosh λ − cos λ sinh λ) + γ λ³ (1 + cos λ cosh λ) = 0, γ = J_h/(ρAL³),
/// bracketed between the clamped-free (γ→∞) and pinned-free (γ→0) first roots.
pub fn hub_inertia_lambda(gamma: f64) -> f64 {
    let f = |l: f64| (l.sin() * l.cosh() - l.cos() * l.sinh()) + gamma * l.powi(3) * (1.0 + l.cos() * l.cosh());
    let (mut lo, mut hi) = (1.8751, 3.9266);
    assert!(f(lo) * f(hi) < 0.0, "root not bracketed for gamma {gamma}");
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(lo) * f(mid) <= 0.0 { hi = mid } else { lo = mid }
    }
    0.5 * (lo + hi)
}

/// The shipped lifts' drive, 0 → 90° trapezoidal with a 20 % ramp, over `duration_s`.
pub fn lift_to_vertical(duration_s: f64) -> DriveSpec {
    DriveSpec::Trapezoidal {
        start_deg: 0.0,
        end_deg: 90.0,
        duration_s,
        accel_deg_s2: None,
        ramp_fraction: Some(0.2),
        shaper: None,
        shaper_hz: None,
        shaper_damping_ratio: None,
    }
}
