//! Lifts of the default full-scale arm: modal reduction converging to the fe reference under
//! each drive profile, and the drive torque against the energy balance.

mod common;

use std::path::Path;

use pipearm::arm::{ArmModel, ArmOptions, ArmSample, ArmSimulation, Fidelity, HubDrive};
use pipearm::beam::BeamModel;
use pipearm::drive::{MotionProfile, SCurveLimit, TrapezoidLimit};
use pipearm::integrate::IntegratorKind;
use pipearm::model::Model;
use pipearm::scenario::Scenario;

fn default_scenario() -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model
}

fn profiles() -> Vec<MotionProfile> {
    let quarter = std::f64::consts::FRAC_PI_2;
    vec![
        MotionProfile::uniform(0.0, quarter, 15.0).unwrap(),
        MotionProfile::trapezoidal(0.0, quarter, 15.0, TrapezoidLimit::RampFraction(0.2)).unwrap(),
        MotionProfile::s_curve(0.0, quarter, 15.0, SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.25 })
            .unwrap(),
    ]
}

fn arm(scenario: &Model, fidelity: Fidelity, options: ArmOptions) -> ArmModel {
    ArmModel::new(BeamModel::new(scenario.beam_spec().unwrap()).unwrap(), fidelity, options).unwrap()
}

fn lift(
    scenario: &Model,
    fidelity: Fidelity,
    options: ArmOptions,
    profile: &MotionProfile,
    end_s: f64,
) -> Vec<ArmSample> {
    let arm = arm(scenario, fidelity, options);
    let mut sim = ArmSimulation::new(arm, HubDrive::Prescribed(profile.clone()), IntegratorKind::default()).unwrap();
    let mut out = Vec::new();
    sim.run_until(end_s, 0.002, |s| out.push(s.clone())).unwrap();
    out
}

/// max |a − b| / max |b| over a history of one scalar.
fn history_error(a: &[ArmSample], b: &[ArmSample], pick: impl Fn(&ArmSample) -> f64) -> f64 {
    let scale = b.iter().map(|s| pick(s).abs()).fold(0.0, f64::max);
    a.iter().zip(b).map(|(x, y)| (pick(x) - pick(y)).abs()).fold(0.0, f64::max) / scale
}

#[test]
fn modal_converges_to_fe_under_every_drive_profile() {
    let scenario = default_scenario();
    let options = scenario.arm_options();
    println!("| profile | n | tip deflection error | tip velocity error | torque error |");
    println!("|---|---|---|---|---|");
    for profile in profiles() {
        let reference = lift(&scenario, Fidelity::Fe, options.clone(), &profile, 18.0);
        let mut deflection_errors = Vec::new();
        let (mut velocity_errors, mut torque_errors) = (Vec::new(), Vec::new());
        for n in [1, 2, 3, 4, 6] {
            let run = lift(&scenario, Fidelity::Modal { modes: n }, options.clone(), &profile, 18.0);
            let e_w = history_error(&run, &reference, |s| s.tip_deflection_hub_m[1]);
            let e_v = history_error(&run, &reference, |s| s.tip_velocity_hub_m_s[1]);
            let e_t = history_error(&run, &reference, |s| s.drive_torque_n_m);
            println!("| {} | {n} | {e_w:.2e} | {e_v:.2e} | {e_t:.2e} |", profile.name());
            deflection_errors.push(e_w);
            velocity_errors.push(common::sig(e_v, 2));
            torque_errors.push(common::sig(e_t, 2));
        }
        // Each mode added brings the history closer, down to 1e-4 of its peak, where the step's
        // own error and the string's truncation (the same in both) are of the same size.
        for pair in deflection_errors.windows(2) {
            let closer = pair[1] <= pair[0] * 1.05 || pair[1] < 1e-4;
            assert!(closer, "{}: error rose with n: {deflection_errors:?}", profile.name());
        }
        let rigid = lift(&scenario, Fidelity::Rigid, options.clone(), &profile, 18.0);
        let e_rigid = history_error(&rigid, &reference, |s| s.tip_deflection_hub_m[1]);
        common::validated_row(
            &common::ARM_DYNAMICS,
            &format!(
                "default arm, {} lift 0 → 90° in 15 s + 3 s: tip-deflection history of modal(1, 2, 3, 4, 6) and rigid",
                profile.name()
            ),
            "the fe arm (every DOF), same lift; error max |w − w_fe| / max |w_fe|",
            &format!(
                "{}; rigid {}",
                deflection_errors.iter().map(|e| common::sig(*e, 2)).collect::<Vec<_>>().join(", "),
                common::sig(e_rigid, 3)
            ),
            &common::sig(deflection_errors[4], 2),
            "modal(6) < 5e-3; each mode added closer (within 5 %, or below 1e-4); rigid > 0.99",
        );
        common::validated(
            &common::ARM_DYNAMICS,
            &format!("the same, {}: tip-velocity and drive-torque histories of modal(1, 2, 3, 4, 6)", profile.name()),
            "the fe arm, same lift; error max |x − x_fe| / max |x_fe|",
            &format!("velocity {}; torque {}", velocity_errors.join(", "), torque_errors.join(", ")),
            "reported, not asserted",
        );
        assert!(e_rigid > 0.99, "a rigid arm has no deflection: error {e_rigid}");
        assert!(deflection_errors[4] < 5e-3, "{}: 6 modes still off by {}", profile.name(), deflection_errors[4]);
    }
}

#[test]
fn drive_work_equals_the_change_of_energy() {
    // Undamped arm, gravity on: ∫ τ θ̇ dt = ΔE (kinetic + strain + gravity) at every fidelity.
    let scenario = default_scenario();
    let options = ArmOptions { damping_ratios: vec![0.0], ..scenario.arm_options() };
    let profile = &profiles()[1];
    for fidelity in [Fidelity::Rigid, Fidelity::Modal { modes: 4 }, Fidelity::Fe] {
        let arm = arm(&scenario, fidelity, options.clone());
        let mut sim = ArmSimulation::new(
            arm,
            HubDrive::Prescribed(profile.clone()),
            pipearm::integrate::IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 },
        )
        .unwrap();
        let mut samples = Vec::new();
        sim.run_until(16.0, 5e-4, |s| {
            samples.push((s.t_s, s.drive_torque_n_m * s.hub.rate_rad_s, s.energies.total_j()))
        })
        .unwrap();
        let work: f64 = samples.windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum();
        let delta_e = samples.last().unwrap().2 - samples[0].2;
        common::validated_rel(
            &common::ARM_DYNAMICS,
            &format!("default arm at {fidelity}, undamped, trapezoidal lift 0 → 90° in 15 s: energy gained"),
            work,
            "∫ τ θ̇ dt, the drive's work",
            delta_e,
            "J",
            1e-4,
        );
        assert!((work - delta_e).abs() < 1e-4 * delta_e.abs(), "{fidelity}: work {work} J vs ΔE {delta_e} J");
    }
}
