//! Floating-frame arm dynamics against conservation laws, closed forms and exact rotating-beam
//! frequencies.

mod common;

use common::{ARM_DYNAMICS, model, rel, uniform, validated_rel};
use nalgebra::DVector;
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, GeneralizedLoad, HubDrive};
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;

fn undamped(gravity_m_s2: f64) -> ArmOptions {
    ArmOptions { damping_ratios: vec![0.0], gravity_m_s2, ..ArmOptions::default() }
}

const NEWMARK: IntegratorKind = IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 };

#[test]
fn newmark_free_vibration_conserves_energy_over_1000_periods() {
    // Clamped hub, no gravity, undamped: the fe arm released from a static tip-load shape.
    let beam = model(uniform(4.0, 5e5, 20.0, 20).with_mass("tip", 4.0, 30.0, 0.5));
    let arm = ArmModel::new(beam, Fidelity::Fe, undamped(0.0)).unwrap();
    let [_, v, _] = arm.beam.point_rows(4.0);
    let q0 = arm.beam.static_displacement(&(1e3 * v)).unwrap();
    let omega1 = arm.beam.modes().unwrap().omegas_rad_s[0];
    let period = std::f64::consts::TAU / omega1;
    let n = arm.elastic_dofs();
    let mut sim = ArmSimulation::with_initial(
        arm,
        HubDrive::Prescribed(MotionProfile::hold(0.0)),
        NEWMARK,
        q0,
        DVector::zeros(n),
    )
    .unwrap();
    let e0 = sim.sample().energies.total_j();
    let (mut worst, steps_per_period) = (0.0_f64, 40);
    for _ in 0..1000 {
        for _ in 0..steps_per_period {
            sim.step(period / steps_per_period as f64).unwrap();
        }
        worst = worst.max((sim.sample().energies.total_j() / e0 - 1.0).abs());
    }
    common::validated_row(
        &ARM_DYNAMICS,
        "fe arm, clamped hub, undamped, released from a static tip-load shape: 1000 periods of mode 1 at 40 steps each (Newmark ¼)",
        "total energy conserved (average acceleration has no numerical damping)",
        &format!("largest drift {}", common::relative(worst)),
        &common::relative(worst),
        "< 1e-6",
    );
    assert!(worst < 1e-6, "relative energy drift {worst:e}");
}

#[test]
fn free_hub_conserves_angular_momentum_and_rings_at_the_pinned_free_frequency() {
    // No gravity, no torque; the fe arm is released bent in its first free-hub mode on a hub of
    // inertia γρAL³: θ oscillates at the root of the hub-inertia characteristic equation and
    // the angular momentum stays zero. (With γ = 0 the fe mass matrix is nearly singular near
    // the hub and the free-hub fe model fails; docs/model.md records it.)
    let (l, ei, rho_a, gamma) = (2.0_f64, 800.0, 3.0, 0.5);
    let hub_inertia_kg_m2 = gamma * rho_a * l.powi(3);
    let beam = model(uniform(l, ei, rho_a, 12));
    let shape = beam.modes_free_hub(hub_inertia_kg_m2).unwrap().shapes.column(0).into_owned();
    let [_, tip, _] = beam.point_rows(l);
    let q0 = 0.02 / tip.dot(&shape) * shape;
    let arm = ArmModel::new(beam, Fidelity::Fe, ArmOptions { hub_inertia_kg_m2, ..undamped(0.0) }).unwrap();
    let n = arm.elastic_dofs();
    let mut sim =
        ArmSimulation::with_initial(arm, HubDrive::Free { torque_n_m: 0.0 }, NEWMARK, q0, DVector::zeros(n)).unwrap();
    let exact_omega = common::hub_inertia_lambda(gamma).powi(2) * (ei / (rho_a * l.powi(4))).sqrt();
    let period = std::f64::consts::TAU / exact_omega;
    let h = period / 200.0;
    let mut theta = Vec::new();
    let e0 = sim.sample().energies.total_j();
    let (mut worst_momentum, mut momentum_scale) = (0.0_f64, 0.0_f64);
    for _ in 0..(20.0 * period / h) as usize {
        sim.step(h).unwrap();
        let s = sim.state();
        theta.push((s.t, s.x[0]));
        worst_momentum = worst_momentum.max(angular_momentum(&sim).abs());
        momentum_scale = momentum_scale.max(sim.arm.pivot_inertia_kg_m2 * s.v[0].abs());
    }
    let measured = std::f64::consts::TAU * pipearm::analysis::crossing_frequency_hz(&theta);
    let drift = (sim.sample().energies.total_j() / e0 - 1.0).abs();
    let case = "fe arm on a free hub (γ = 0.5), no torque, released bent in its first free-hub mode";
    common::validated_row(
        &ARM_DYNAMICS,
        &format!("{case}: angular momentum over 20 periods"),
        "0, conserved",
        &format!("largest |H| {} of its scale", common::relative(worst_momentum / momentum_scale)),
        &common::relative(worst_momentum / momentum_scale),
        "< 1e-4",
    );
    validated_rel(
        &ARM_DYNAMICS,
        &format!("{case}: frequency of θ"),
        exact_omega,
        "λ² √(EI/ρAL⁴), λ the root of the hub-inertia characteristic equation",
        measured,
        "rad/s",
        5e-3,
    );
    common::validated_row(
        &ARM_DYNAMICS,
        &format!("{case}: energy"),
        "conserved",
        &format!("drift {}", common::relative(drift)),
        &common::relative(drift),
        "< 1e-3",
    );
    // H = 0 initially; the trapezoidal rule keeps it to second order in h, not exactly.
    assert!(worst_momentum < 1e-4 * momentum_scale, "angular momentum {worst_momentum} vs scale {momentum_scale}");
    assert!(rel(measured, exact_omega) < 5e-3, "{measured} vs {exact_omega}");
    assert!(drift < 1e-3, "energy drift {drift}");
}

/// H = Ĵθ̇ + S̃ᵀq̇ from the kinetic energy: ∂T/∂θ̇.
fn angular_momentum(sim: &ArmSimulation) -> f64 {
    let rate = sim.state().v[0];
    // ∂T/∂θ̇ by a central difference of the kinetic energy in θ̇ at fixed q, q̇:
    // T(θ̇) is quadratic, so (T(w+d) − T(w−d)) / 2d is exact.
    let t = |rate: f64| {
        let mut x = sim.state().clone();
        x.v[0] = rate;
        kinetic(sim, &x)
    };
    let d = 1e-3;
    (t(rate + d) - t(rate - d)) / (2.0 * d)
}

fn kinetic(sim: &ArmSimulation, state: &pipearm::integrate::State) -> f64 {
    let (load, hub) = (GeneralizedLoad::zero(sim.arm.elastic_dofs()), pipearm::arm::HubCache::default());
    let system = pipearm::arm::ArmSystem::new(&sim.arm, &sim.drive, &load, &[], &hub);
    let (hub, q, qd) = system.split_free_hub(&state.x, &state.v);
    system.energies(&hub, &q, &qd).kinetic_j
}

#[test]
fn rigid_arm_under_constant_torque_follows_the_closed_form() {
    let beam = model(uniform(3.0, 1e6, 10.0, 6).with_mass("tip", 3.0, 20.0, 0.0));
    let inertia = 10.0 * 27.0 / 3.0 + 20.0 * 9.0 + 5.0;
    let options = ArmOptions { hub_inertia_kg_m2: 5.0, ..undamped(0.0) };
    let arm = ArmModel::new(beam, Fidelity::Rigid, options).unwrap();
    let torque = 250.0;
    let mut sim = ArmSimulation::new(arm, HubDrive::Free { torque_n_m: torque }, NEWMARK).unwrap();
    sim.run_until(2.0, 0.01, |_| ()).unwrap();
    let theta = sim.state().x[0];
    let exact = torque * 4.0 / (2.0 * inertia);
    validated_rel(
        &ARM_DYNAMICS,
        "rigid arm on a free hub under 250 N·m for 2 s: hub angle",
        exact,
        "τ t² / 2J",
        theta,
        "rad",
        1e-12,
    );
    assert!(rel(theta, exact) < 1e-12, "{theta} vs {exact}");
}

#[test]
fn rigid_arm_drive_torque_is_inertia_plus_gravity() {
    // τ = J θ̈ + g m₁ cos θ for a rigid arm.
    let beam = model(uniform(3.0, 1e6, 10.0, 6).with_mass("tip", 3.0, 20.0, 0.5));
    let (inertia, first_moment) = (10.0 * 27.0 / 3.0 + 20.0 * 9.0 + 0.5 + 5.0, 10.0 * 4.5 + 60.0);
    let options = ArmOptions { hub_inertia_kg_m2: 5.0, ..ArmOptions::default() };
    let arm = ArmModel::new(beam, Fidelity::Rigid, options).unwrap();
    let profile =
        MotionProfile::trapezoidal(0.0, 1.5, 4.0, pipearm::drive::TrapezoidLimit::RampFraction(0.25)).unwrap();
    let mut sim = ArmSimulation::new(arm, HubDrive::Prescribed(profile), IntegratorKind::default()).unwrap();
    let mut worst = 0.0_f64;
    sim.run_until(4.0, 0.01, |s| {
        let exact = inertia * s.hub.accel_rad_s2 + 9.80665 * first_moment * s.hub.angle_rad.cos();
        worst = worst.max((s.drive_torque_n_m - exact).abs() / exact.abs().max(1.0));
        assert!(
            (s.drive_torque_n_m - exact).abs() < 1e-9 * exact.abs().max(1.0),
            "t {}: {} vs {exact}",
            s.t_s,
            s.drive_torque_n_m
        );
    })
    .unwrap();
    common::validated_row(
        &ARM_DYNAMICS,
        "rigid arm on a trapezoidal lift of 1.5 rad in 4 s under gravity: drive torque at every step",
        "J θ̈ + g m₁ cos θ",
        &format!("largest difference {} of the torque", common::relative(worst)),
        &common::relative(worst),
        "< 1e-9",
    );
}
