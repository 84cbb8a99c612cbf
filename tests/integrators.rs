//! Integrator stability and accuracy against closed-form facts: the stability intervals and
//! orders of Hairer & Wanner, Solving Ordinary Differential Equations I–II.

mod common;

use common::{INTEGRATORS, validated_abs, validated_rel};
use nalgebra::{DMatrix, DVector};
use pipearm::integrate::{Dynamics, ExplicitEuler, GeneralizedAlpha, Integrator, Rk4, State, SymplecticEuler};

/// ẍ + ω² x = 0 with unit mass.
struct Oscillator {
    omega: f64,
}

impl Dynamics for Oscillator {
    fn dofs(&self) -> usize {
        1
    }
    fn mass_matrix(&self, _t: f64, _x: &DVector<f64>, m: &mut DMatrix<f64>) {
        m[(0, 0)] = 1.0;
    }
    fn forces(&self, _t: f64, x: &DVector<f64>, _v: &DVector<f64>, f: &mut DVector<f64>) {
        f[0] = -self.omega * self.omega * x[0];
    }
    fn is_linear(&self) -> bool {
        true
    }
    fn tangents(&self, _t: f64, _x: &DVector<f64>, _v: &DVector<f64>, k: &mut DMatrix<f64>, c: &mut DMatrix<f64>) {
        k[(0, 0)] = self.omega * self.omega;
        c[(0, 0)] = 0.0;
    }
}

fn energy(s: &State, omega: f64) -> f64 {
    0.5 * (s.v[0] * s.v[0] + omega * omega * s.x[0] * s.x[0])
}

/// Energy ratio after `steps` steps of size `omega_h / omega` from x = 1, v = 0.
fn energy_growth(integrator: &mut dyn Integrator, omega_h: f64, steps: usize) -> f64 {
    let omega = 1.0;
    let sys = Oscillator { omega };
    let mut s = State::consistent(&sys, 0.0, DVector::from_element(1, 1.0), DVector::zeros(1)).unwrap();
    let e0 = energy(&s, omega);
    for _ in 0..steps {
        if integrator.step(&sys, &mut s, omega_h / omega).is_err() {
            return f64::INFINITY;
        }
    }
    energy(&s, omega) / e0
}

/// Largest energy in the last 400 of 4000 steps over the largest in the first 400: bounded
/// for a stable step (however eccentric its discrete orbit), astronomically large past the limit.
fn late_over_early_energy(integrator: &mut dyn Integrator, omega_h: f64) -> f64 {
    let sys = Oscillator { omega: 1.0 };
    let mut s = State::consistent(&sys, 0.0, DVector::from_element(1, 1.0), DVector::zeros(1)).unwrap();
    let (mut early, mut late) = (0.0_f64, 0.0_f64);
    for i in 0..4000 {
        if integrator.step(&sys, &mut s, omega_h).is_err() {
            return f64::INFINITY;
        }
        let e = energy(&s, 1.0);
        if i < 400 {
            early = early.max(e);
        } else if i >= 3600 {
            late = late.max(e);
        }
    }
    late / early
}

/// Bisects the ωh at which the energy grows by more than 10³ between the start and the end of
/// 4000 steps.
fn stability_limit(make: &dyn Fn() -> Box<dyn Integrator>, lo: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let mut integ = make();
        if late_over_early_energy(integ.as_mut(), mid) > 1e3 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn symplectic_euler_limit_is_omega_h_2() {
    let limit = stability_limit(&|| Box::new(SymplecticEuler), 1.0, 3.0);
    println!("symplectic Euler: measured limit ωh = {limit:.5} (theory 2)");
    validated_rel(
        &INTEGRATORS,
        "symplectic Euler: stability limit ωh, oscillator",
        2.0,
        "Hairer & Wanner",
        limit,
        "",
        0.02,
    );
    assert!((limit / 2.0 - 1.0).abs() < 0.02, "measured {limit}");
}

#[test]
fn linear_acceleration_newmark_limit_is_2_sqrt_3() {
    let limit = stability_limit(&|| Box::new(GeneralizedAlpha::newmark(1.0 / 6.0, 0.5).unwrap()), 2.0, 5.0);
    println!("Newmark β = 1/6: measured limit ωh = {limit:.5} (theory 2√3 = 3.46410)");
    validated_rel(
        &INTEGRATORS,
        "Newmark β = 1/6, γ = 1/2: stability limit ωh, oscillator",
        12f64.sqrt(),
        "2√3, Hairer & Wanner",
        limit,
        "",
        0.02,
    );
    assert!((limit / 12f64.sqrt() - 1.0).abs() < 0.02, "measured {limit}");
}

#[test]
fn rk4_limit_is_2_sqrt_2() {
    let limit = stability_limit(&|| Box::new(Rk4::default()), 2.0, 4.0);
    println!("RK4: measured limit ωh = {limit:.5} (theory 2√2 = 2.82843)");
    validated_rel(
        &INTEGRATORS,
        "RK4: stability limit ωh, oscillator",
        8f64.sqrt(),
        "2√2, Hairer & Wanner",
        limit,
        "",
        0.02,
    );
    assert!((limit / 8f64.sqrt() - 1.0).abs() < 0.02, "measured {limit}");
}

#[test]
fn explicit_euler_grows_at_every_step_size() {
    let omega_hs = [1e-3, 1e-2, 0.1, 1.0];
    let steps = 100;
    let growths: Vec<f64> = omega_hs.iter().map(|&omega_h| energy_growth(&mut ExplicitEuler, omega_h, steps)).collect();
    // Spectral radius sqrt(1 + ω²h²) per step: energy grows by (1 + ω²h²)^steps exactly.
    let exacts: Vec<f64> = omega_hs.iter().map(|omega_h| (1.0 + omega_h * omega_h).powi(steps as i32)).collect();
    common::validated_rel_all(
        &INTEGRATORS,
        "explicit Euler: energy growth over 100 steps at ωh = 0.001, 0.01, 0.1, 1",
        &exacts,
        "(1 + ω²h²)¹⁰⁰, the spectral radius √(1 + ω²h²) per step",
        &growths,
        "",
        1e-9,
    );
    for ((omega_h, growth), exact) in omega_hs.into_iter().zip(growths).zip(exacts) {
        assert!(growth > 1.0, "ωh = {omega_h}: no growth");
        assert!((growth / exact - 1.0).abs() < 1e-9, "ωh = {omega_h}: {growth} vs {exact}");
    }
}

#[test]
fn average_acceleration_is_unconditionally_stable_and_conserves_energy() {
    let omega_hs = [0.1, 1.0, 10.0, 1e3];
    let growths: Vec<f64> = omega_hs
        .iter()
        .map(|&omega_h| energy_growth(&mut GeneralizedAlpha::average_acceleration(), omega_h, 10_000))
        .collect();
    let worst = growths.iter().map(|g| (g - 1.0).abs()).fold(0.0, f64::max);
    common::validated_row(
        &INTEGRATORS,
        "Newmark average acceleration: energy ratio after 10 000 steps at ωh = 0.1, 1, 10, 1000",
        "1: unconditionally stable, no numerical damping",
        &growths.iter().map(|g| common::sig(*g, 12)).collect::<Vec<_>>().join(", "),
        &common::relative(worst),
        "< 1e-10",
    );
    for (omega_h, growth) in omega_hs.into_iter().zip(growths) {
        assert!((growth - 1.0).abs() < 1e-10, "ωh = {omega_h}: energy ratio {growth}");
    }
}

/// Spectral radius at ωh = 10⁶, measured from the energy decay between steps 200 and 400
/// (late enough that the polynomial factor of a repeated eigenvalue no longer matters).
fn high_frequency_radius(integrator: &mut dyn Integrator) -> f64 {
    let sys = Oscillator { omega: 1.0 };
    let mut s = State::consistent(&sys, 0.0, DVector::from_element(1, 1.0), DVector::zeros(1)).unwrap();
    let mut energies = Vec::new();
    for _ in 0..400 {
        integrator.step(&sys, &mut s, 1e6).unwrap();
        energies.push(energy(&s, 1.0));
    }
    if energies[399] == 0.0 {
        return 0.0;
    }
    (energies[399] / energies[199]).powf(0.5 / 200.0)
}

#[test]
fn generalized_alpha_and_hht_damp_infinite_frequencies_to_rho_inf() {
    for rho in [0.0, 0.5, 0.8, 1.0] {
        let measured = high_frequency_radius(&mut GeneralizedAlpha::chung_hulbert(rho).unwrap());
        validated_abs(
            &INTEGRATORS,
            &format!("generalized-α, ρ∞ = {rho}: spectral radius at ωh = 10⁶"),
            rho,
            "ρ∞, Chung & Hulbert 1993",
            measured,
            "",
            0.01,
        );
        assert!((measured - rho).abs() < 0.01, "rho_inf {rho}: measured {measured}");
    }
    for alpha in [-0.3, -0.1] {
        let rho = (1.0 + alpha) / (1.0 - alpha);
        let measured = high_frequency_radius(&mut GeneralizedAlpha::hht(alpha).unwrap());
        validated_abs(
            &INTEGRATORS,
            &format!("HHT-α, α = {alpha}: spectral radius at ωh = 10⁶"),
            rho,
            "(1 + α)/(1 − α), Hilber, Hughes & Taylor 1977",
            measured,
            "",
            0.02,
        );
        assert!((measured - rho).abs() < 0.02, "HHT alpha {alpha}: measured {measured} vs {rho}");
    }
}

#[test]
fn generalized_alpha_is_second_order() {
    // Error of x(T) against cos(ωT) after one period, halving h: ratio → 4.
    let err = |steps: usize| {
        let sys = Oscillator { omega: 1.0 };
        let mut s = State::consistent(&sys, 0.0, DVector::from_element(1, 1.0), DVector::zeros(1)).unwrap();
        let mut integ = GeneralizedAlpha::chung_hulbert(0.8).unwrap();
        let h = std::f64::consts::TAU / steps as f64;
        for _ in 0..steps {
            integ.step(&sys, &mut s, h).unwrap();
        }
        (s.x[0] - 1.0).abs() + s.v[0].abs()
    };
    let (e1, e2, e3) = (err(100), err(200), err(400));
    let orders = [(e1 / e2).log2(), (e2 / e3).log2()];
    common::validated_row(
        &INTEGRATORS,
        "generalized-α (ρ∞ = 0.8): order from the error after one period at 100, 200, 400 steps",
        "2 (Chung & Hulbert 1993)",
        &format!(
            "errors {}, {}, {}: orders {}, {}",
            common::sig(e1, 2),
            common::sig(e2, 2),
            common::sig(e3, 2),
            common::sig(orders[0], 3),
            common::sig(orders[1], 3)
        ),
        &common::sig(orders.iter().map(|o| (o - 2.0).abs()).fold(0.0, f64::max), 2),
        "< 0.15",
    );
    for ratio in [e1 / e2, e2 / e3] {
        assert!((ratio.log2() - 2.0).abs() < 0.15, "order {} from {e1} {e2} {e3}", ratio.log2());
    }
}
