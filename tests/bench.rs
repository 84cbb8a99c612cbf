//! `pipearm bench` on a short lab scene: the reference converges, the grid's points land where
//! the theory puts them, and the CLI writes its files.

mod common;

use std::path::Path;

use common::rel;
use pipearm::bench::stability::Limit;
use pipearm::bench::{BenchOptions, Outcome, bench, points_csv, report_markdown};
use pipearm::integrate::IntegratorKind;
use pipearm::model::Model;
use pipearm::scenario::Scenario;

fn short_lab() -> Model {
    let mut s = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/lab.toml")).unwrap();
    s.spec.drive = common::lift_to_vertical(2.0);
    s.spec.time.settle_s = 0.5;
    Scenario::from_spec(&s.path, s.spec).unwrap().model
}

#[test]
fn a_quick_bench_of_the_lab_scene_agrees_with_its_reference_and_the_theory() {
    let scenario = short_lab();
    let options = BenchOptions { repeats: 1, quick: true, mesh_check: false };
    let result = bench(&scenario, &options, &mut |_, _, _| ()).unwrap();
    let reference = &result.references[0];
    println!("reference: {} N, convergence {:?}", reference.peak_force_n, reference.convergence);
    assert!(reference.peak_force_n > 0.0, "the short lab lift must strike its bumper");
    assert!(reference.convergence.peak_force_error < 0.02);
    for p in &result.points {
        let explicit_euler = p.variant.integrator == IntegratorKind::ExplicitEuler;
        match &p.outcome {
            // The rapier method diverges where its pad body outweighs the arm's effective mass
            // at the pad (1.0 kg on this lab arm): the pad mass axis goes there.
            Outcome::Diverged { .. } => assert!(
                explicit_euler || p.variant.contact == pipearm::model::ContactMethod::Rapier,
                "{}",
                p.variant.label()
            ),
            Outcome::Ran(m) => {
                assert!(!explicit_euler, "explicit Euler must diverge: {}", p.variant.label());
                // Every flexible model resolves the tip history to a few per cent of its peak.
                if p.variant.fidelity != pipearm::arm::Fidelity::Rigid
                    && p.variant.contact != pipearm::model::ContactMethod::Rapier
                {
                    assert!(m.tip_rms_error < 0.05, "{}: {}", p.variant.label(), m.tip_rms_error);
                }
            }
        }
    }
    // This short lift strikes at 27 N over ≈ 10 ms: generalized-α resolves it to 1 % at every step
    // of the quick grid (measured 0.1–0.3 %, not monotone at that level: the peak's sampling).
    let ga: Vec<f64> = result
        .points
        .iter()
        .filter(|p| p.variant.axis == "step: generalized-alpha")
        .filter_map(|p| p.measured().map(|m| m.peak_force_error))
        .collect();
    assert!(ga.len() == 3 && ga.iter().all(|&e| e < 0.01), "errors at h/2, h, 2h: {ga:?}");
    let row = result.stability.arm.iter().find(|r| r.integrator == IntegratorKind::SymplecticEuler).unwrap();
    let Limit::Step(h) = row.measured else { panic!("symplectic Euler must have a finite limit") };
    common::validated_rel(
        &common::INTEGRATORS,
        "`pipearm bench` stability map, lab scene: symplectic Euler's largest stable step as ω_max·dt",
        2.0,
        "the single-mode limit on the arm's highest mode",
        h * row.omega_max_rad_s,
        "",
        0.01,
    );
    assert!(rel(h * row.omega_max_rad_s, 2.0) < 0.01);
    let csv = points_csv(&result);
    assert_eq!(csv.lines().count(), result.points.len() + 1);
    assert!(report_markdown(&result, "test").contains("## Stability map"));
}

/// The stability map's FE arm carrying the default's flexible string (its own DOFs beyond the
/// arm's): generalized-α is unconditionally stable (Chung & Hulbert 1993), at the scene's step
/// and at a hundred times it.
#[test]
fn the_fe_arm_carrying_a_flexible_string_is_mapped_stable_under_generalized_alpha() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let s = Scenario::load(&path).unwrap().model;
    let arm = pipearm::bench::stability::undamped_arm(&s, pipearm::arm::Fidelity::Fe).unwrap();
    assert!(arm.beam.member.is_some(), "the default's string is a beam of its own");
    for step in [s.time.step_s, 100.0 * s.time.step_s] {
        assert!(pipearm::bench::stability::arm_is_stable(&arm, IntegratorKind::default(), step), "at {step} s");
    }
}
