//! The sign-off's less travelled paths: a rigid arm's stress against its free body by hand, a
//! change of section along the arm (both sides of the joint by hand), a robot without a yield
//! strength (no utilisation, and the summary says why), the stress envelope's chart, and the
//! readings completed beside the step the same as on it.

use std::path::Path;

use pipearm::arm::Fidelity;
use pipearm::beam::SectionShape;
use pipearm::drive::MotionProfile;
use pipearm::model::Model;
use pipearm::run::{RunOptions, run, run_with};
use pipearm::scenario::Scenario;
use pipearm::stress::Fibre;

fn default_model() -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model
}

/// The default machine held still at `angle_deg` under an ideal drive, its string rigid.
fn held_still(angle_deg: f64) -> Model {
    let mut model = default_model();
    model.drive.motion = MotionProfile::hold(angle_deg.to_radians());
    model.dampeners.clear();
    model.time.settle_s = 0.3;
    model.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    model
}

#[test]
fn a_rigid_arm_held_at_an_angle_carries_its_free_bodys_root_moment_exactly() {
    let angle_deg: f64 = 40.0;
    let (s, c) = angle_deg.to_radians().sin_cos();
    let model = held_still(angle_deg);
    let (summary, series) = run(&model, Some(Fidelity::Rigid)).unwrap();
    // By hand: the box (ρ A L, 250 × 500 × 12.5 mm), each carried body and the string at its
    // centre; a rigid arm does not sag, so the root carries N = −W sin θ and M = g cos θ Σ m x.
    let g = model.physics.gravity_m_s2;
    let (b, h, t): (f64, f64, f64) = (0.25, 0.5, 0.0125);
    let (bi, hi) = (b - 2.0 * t, h - 2.0 * t);
    let (area, inertia) = (b * h - bi * hi, (b * h.powi(3) - bi * hi.powi(3)) / 12.0);
    let length = model.robot.arm.length_m();
    let mu = 7850.0 * area;
    let (mut mass, mut first_moment) = (mu * length, mu * length * length / 2.0);
    for body in &model.robot.carried {
        mass += body.mass_kg;
        first_moment += body.mass_kg * body.station_m;
    }
    let held = model.payload.string().unwrap();
    mass += held.pipe.mass_kg();
    first_moment += held.pipe.mass_kg() * held.centre_m();
    let (n, m) = (-mass * g * s, g * c * first_moment);
    let upper = n / area + m * (h / 2.0) / inertia;
    let lower = n / area - m * (h / 2.0) / inertia;
    let stress = &summary.sign_off.as_ref().unwrap().stress;
    let expected = upper.abs().max(lower.abs());
    println!(
        "rigid arm at {angle_deg}°: peak {:.4} MPa, by hand {:.4} MPa",
        1e-6 * stress.peak_stress_pa,
        1e-6 * expected
    );
    // The histories are kept to seven digits.
    assert!((stress.peak_stress_pa / expected - 1.0).abs() < 1e-6, "{} vs {expected}", stress.peak_stress_pa);
    assert_eq!(stress.peak_station_m, 0.0);
    let k = series.t_s.len() - 1;
    let root = series.stress.stations.iter().position(|st| st.station_m == 0.0).unwrap();
    let [axial, moment] = series.stress.section_forces(root, k);
    assert!((axial / n - 1.0).abs() < 1e-6 && (moment / m - 1.0).abs() < 1e-6, "N {axial} vs {n}, M {moment} vs {m}");
}

#[test]
fn without_a_yield_strength_there_is_no_utilisation_and_the_summary_says_why() {
    let mut model = held_still(10.0);
    for segment in &mut model.robot.arm.segments {
        segment.checks.yield_strength = None;
    }
    let (summary, _) = run(&model, None).unwrap();
    let stress = &summary.sign_off.as_ref().unwrap().stress;
    assert_eq!(stress.utilisation, None);
    assert!(stress.utilisation_station_m.is_none() && stress.utilisation_time_s.is_none());
    assert!(stress.segments.iter().all(|s| s.utilisation.is_none() && s.yield_strength_pa.is_none()));
    let note = stress.utilisation_note.as_deref().expect("a note");
    assert!(note.starts_with("no utilisation: segment 0 has no yield strength"), "{note}");
    assert!(stress.peak_stress_pa > 0.0, "the stress is still recovered");
    let json = serde_json::to_value(&summary).unwrap();
    assert!(json["stress"]["utilisation"].is_null() && json["stress"]["utilisation_note"].is_string(), "{json}");
}

#[test]
fn the_stress_envelope_chart_is_written_with_its_yield_lines() {
    let model = default_model();
    let (_, series) = run(&model, None).unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-stress-{}.svg", std::process::id()));
    pipearm::stress::chart::envelope(&path, "default", &series.stress, &model.robot.arm.segments, 1.0).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    assert!(svg.contains("yield / stress factor"), "the yield lines' legend");
    // Two envelope lines (max, min) and, per segment, ± yield and a boundary.
    let lines = svg.matches("<polyline").count();
    assert!(lines >= 2 + 3 * model.robot.arm.segments.len(), "{lines} lines");
}

#[test]
fn both_sides_of_a_change_of_section_carry_the_joints_moment_over_their_own_modulus() {
    // The default arm split at mid-length, its inner half's walls 20 mm instead of 12.5 mm, held
    // level and rigid: at the joint M = g Σ m (x − x_j) of what lies outboard (the outer box, the
    // carried bodies beyond, the string at its centre), N = 0, and σ = M c / I on either side
    // with that side's I.
    let mut model = held_still(0.0);
    let segment = model.robot.arm.segments[0];
    let (b, h, length): (f64, f64, f64) = (0.25, 0.5, segment.length_m);
    let joint = length / 2.0;
    let mut inner = segment;
    inner.length_m = joint;
    inner.section = SectionShape::HollowRectangle { width_m: b, depth_m: h, wall_m: 0.02 };
    let mut outer = segment;
    outer.length_m = length - joint;
    model.robot.arm.segments = vec![inner, outer];
    let (summary, series) = run(&model, Some(Fidelity::Rigid)).unwrap();
    let inertia = |t: f64| (b * h.powi(3) - (b - 2.0 * t) * (h - 2.0 * t).powi(3)) / 12.0;
    let outer_area = b * h - (b - 0.025) * (h - 0.025);
    let g = model.physics.gravity_m_s2;
    let mut moment = g * 7850.0 * outer_area * (length - joint).powi(2) / 2.0;
    for body in model.robot.carried.iter().filter(|c| c.station_m > joint) {
        moment += g * body.mass_kg * (body.station_m - joint);
    }
    let held = model.payload.string().unwrap();
    assert!(held.centre_m() > joint);
    moment += g * held.pipe.mass_kg() * (held.centre_m() - joint);
    let k = series.t_s.len() - 1;
    let at_joint: Vec<usize> = (0..series.stress.stations.len())
        .filter(|&i| (series.stress.stations[i].station_m - joint).abs() < 1e-9)
        .collect();
    assert_eq!(at_joint.len(), 2, "both sides of the joint");
    for (i, wall) in at_joint.into_iter().zip([0.02, 0.0125]) {
        let expected = moment * (h / 2.0) / inertia(wall);
        let sigma = series.stress.stress_pa(i, Fibre::Upper, k).abs();
        println!("joint, {} mm walls: σ {:.4} MPa, by hand {:.4} MPa", 1e3 * wall, 1e-6 * sigma, 1e-6 * expected);
        assert!((sigma / expected - 1.0).abs() < 1e-6, "{wall} m walls: {sigma} vs {expected}");
        assert_eq!(series.stress.stations[i].segment, usize::from(wall < 0.02));
    }
    assert_eq!(summary.sign_off.unwrap().stress.segments.len(), 2);
}

/// A run on its own completes its stress readings on a worker thread beside the step; inside
/// rayon's pool (as a sweep's cases run) on the step's thread. Both do the same arithmetic in
/// the same order: the series must agree to the bit.
#[test]
fn the_readings_completed_beside_the_step_equal_those_completed_on_it() {
    let model = default_model();
    let options = RunOptions::default();
    let (_, beside) = run_with(&model, &options).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let (_, here) = pool.install(|| run_with(&model, &options)).unwrap();
    let (beside, here) = (&beside.stress, &here.stress);
    assert!(beside.steps() > 1000, "{} steps", beside.steps());
    assert_eq!(beside.steps(), here.steps());
    assert!(beside.values.iter().zip(&here.values).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert_eq!(beside.extremes(), here.extremes());
}
