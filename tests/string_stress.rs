//! The stress along a held string against its static bending moment diagram by hand: a string
//! in one hand, the arm held level, is two cantilevers under their own weight w = μ g, whose
//! moment at distance t from a free end is w t²/2 (σ = M c / I, the axial force nil), at every
//! station the model reads, flexible (`fe`, a beam clamped at the hand) or rigid.

use std::path::Path;

use pipearm::arm::{ArmModel, Fidelity};
use pipearm::beam::BeamModel;
use pipearm::drive::DriveState;
use pipearm::model::Model;
use pipearm::scenario::Scenario;
use pipearm::sensor::probe::ArmState;
use pipearm::sensor::string::StringProbe;

/// The 4½ in string of `string_4half` in the gripper at 9 m, its middle held, without the
/// connections' masses (a uniform beam).
fn held_in_one_hand() -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/string_4half.toml");
    let mut model = Scenario::load(&path).unwrap().model;
    let held = model.payload.string_mut().unwrap();
    held.in_one_hand("gripper", 9.0);
    held.pipe.connections.clear();
    model
}

/// Every station's σ against w t²/2 c/I, t from the nearer free end; returns the largest
/// error over the root value and the station of the largest σ.
fn against_the_cantilevers(model: &Model, arm: &ArmModel) -> (f64, f64) {
    let held = model.payload.string().unwrap();
    let p = &held.pipe.pipe;
    let (r_out, r_in) = (0.5 * p.outer_diameter_m, 0.5 * p.outer_diameter_m - p.wall_m);
    let c_over_i = r_out / (std::f64::consts::FRAC_PI_4 * (r_out.powi(4) - r_in.powi(4)));
    let g = model.physics.gravity_m_s2;
    let w = p.mass_per_length_kg_m * g;
    let (length, hand) = (held.pipe.length_m, held.grips[0].at_m);
    let root = w * hand.max(length - hand).powi(2) / 2.0 * c_over_i;
    let q = arm.static_deflection(0.0).unwrap();
    let zero = nalgebra::DVector::zeros(q.len());
    let hub = DriveState { angle_rad: 0.0, rate_rad_s: 0.0, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 };
    let probe = StringProbe::new(held, arm);
    let stresses = probe.stresses_pa(&ArmState { hub, q: &q, qd: &zero, qdd: &zero }, g);
    assert!(stresses.len() >= 10, "{} stations", stresses.len());
    let mut worst = 0.0_f64;
    for &(x, sigma) in &stresses {
        let t = if x <= hand { x } else { length - x };
        let expected = w * t * t / 2.0 * c_over_i;
        worst = worst.max((sigma - expected).abs() / root);
    }
    let [peak, station] = probe.peak_stress(&ArmState { hub, q: &q, qd: &zero, qdd: &zero }, g);
    assert!((peak - root).abs() <= 0.01 * root, "peak {peak} vs {root} Pa");
    // Read many steps at once from a history of q, a flexible string gives the same.
    if let Some(peaks) = probe.peaks_over(&[q.as_slice(), q.as_slice()].concat(), q.len()) {
        assert_eq!(peaks.len(), 2);
        for p in peaks {
            assert!((p[0] - peak).abs() <= 1e-12 * peak && p[1] == station, "{p:?} vs {peak}, {station}");
        }
    }
    (worst, station)
}

#[test]
fn a_flexible_strings_stress_follows_its_cantilevers_moment_diagram() {
    let model = held_in_one_hand();
    let beam = BeamModel::new(model.beam_spec_with_string(Some(Fidelity::Fe)).unwrap()).unwrap();
    let arm = ArmModel::new(beam, Fidelity::Fe, model.arm_options()).unwrap();
    let (worst, station) = against_the_cantilevers(&model, &arm);
    println!("fe string: largest error {:.3} % of the root stress, peak at {station:.3} m", 100.0 * worst);
    // Cubic elements interpolate the quadratic moment linearly within each element: w h²/12 off
    // at an element's end (0.12 % of the root's w a²/2 with twelve elements a side), well
    // under 1 %.
    assert!(worst < 0.01, "largest error {worst} of the root stress");
    let hand = model.payload.string().unwrap().grips[0].at_m;
    assert!((station - hand).abs() < 1e-9, "the peak is at the hand ({hand} m), not {station} m");
}

#[test]
fn a_rigid_strings_overhangs_follow_the_same_diagram() {
    let mut model = held_in_one_hand();
    model.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    let arm = model.arm_model(Fidelity::Fe).unwrap();
    let (worst, station) = against_the_cantilevers(&model, &arm);
    println!("rigid string: largest error {:.2e} of the root stress", worst);
    // Quasi-static and exact but for the arm's slope at the hand (cos φ).
    assert!(worst < 1e-3, "largest error {worst} of the root stress");
    let hand = model.payload.string().unwrap().grips[0].at_m;
    assert!((station - hand).abs() < 1e-9, "the peak is at the hand ({hand} m), not {station} m");
}
