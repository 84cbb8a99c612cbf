//! Contact through rapier's collision pipeline: manifolds spread a pair's law over their points,
//! rig structure struck by the arm and the string.

mod common;

use std::path::Path;

use common::{CONTACT_SCENE, MODEL_CHOICE, rel, validated_rel};
use pipearm::arm::{ArmModel, ArmSimulation, Fidelity, HubDrive};
use pipearm::beam::BeamModel;
use pipearm::contact::ForceLaw;
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;
use pipearm::model::{Detection, Model, Structure, StructureShape};
use pipearm::run::run;
use pipearm::scenario::Scenario;
use pipearm::scene::{Scene, manifold_between};
use rapier3d_f64::prelude::*;

fn scenario(name: &str) -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"))).unwrap().model
}

/// A bar lying on a pad, its weight off the pad's centre: at the pose where the pad's law,
/// spread over the manifold's points (1/N each), holds it, the points' forces sum to its weight
/// and their moment balances its weight's. With the pad's length L, two points of equal depth
/// across each end: end forces W/2 ± W e / L, so the bar sinks W/k at the pad's centre and tilts
/// by 4 W e / (k L²) (statics of a bar on two springs of k/2).
#[test]
fn a_bar_lying_on_a_pad_is_held_by_the_manifold_points() {
    let (k, weight_n, e, length) = (1.0e7, 500.0, 0.05, 0.3);
    let (pad_half, bar_half) = ([0.5 * length, 0.0125, 0.0375], [1.0, 0.05, 0.05]);
    let pad = SharedShape::cuboid(pad_half[0], pad_half[1], pad_half[2]);
    let bar = SharedShape::cuboid(bar_half[0], bar_half[1], bar_half[2]);
    let sink = weight_n / k;
    let slope: f64 = 4.0 * weight_n * e / (k * length * length);
    let phi = slope.atan();
    let h = bar_half[1];
    // The bar's bottom face passes 'sink' below the pad's top at the pad's centre, falling toward
    // +x; its centre of mass stands at x = e.
    let y0 = pad_half[1] - sink;
    let centre_y = y0 - slope * (e - h * phi.sin()) + h * phi.cos();
    let bar_pose = Pose::from_parts(Vector::new(e, centre_y, 0.0), Rotation::from_rotation_z(-phi));
    let points = manifold_between((&bar, bar_pose), (&pad, Pose::IDENTITY), 1e-3);
    let law = ForceLaw::Linear { stiffness_n_m: k, damping_n_s_m: 0.0 };
    let share = 1.0 / points.len() as f64;
    let forces: Vec<([f64; 3], f64)> =
        points.iter().map(|p| (p.point_m, share * law.force_n(p.depth_m, 0.0, 1.0) * p.normal_world[1])).collect();
    let lift: f64 = forces.iter().map(|f| f.1).sum();
    let moment: f64 = forces.iter().map(|f| f.1 * f.0[0]).sum();
    println!(
        "{} points: lift {lift:.2} N vs {weight_n} N, moment {moment:.4} N·m vs {:.4}",
        points.len(),
        weight_n * e
    );
    let case = format!(
        "a bar lying on a linear pad (1e7 N/m), its 500 N weight 0.05 m off centre, the law spread over rapier's {} manifold points",
        points.len()
    );
    let source = "statics of a bar on two springs of k/2";
    validated_rel(&CONTACT_SCENE, &format!("{case}: lift"), weight_n, source, lift, "N", 0.01);
    validated_rel(&CONTACT_SCENE, &format!("{case}: moment"), weight_n * e, source, moment, "N·m", 0.01);
    assert_eq!(points.len(), 4, "a box on a box face: the four corners of the pad's face");
    assert!(rel(lift, weight_n) < 0.01, "lift {lift} vs weight {weight_n}");
    assert!(rel(moment, weight_n * e) < 0.01, "moment {moment} vs {}", weight_n * e);
}

/// The default arm, rigid and held at its stop, pressed `depth` into its pad: the pair's force is
/// the law's at that depth whether the pipeline finds four points on one arm element or eight on
/// two, and the pad-face path without a query gives the same.
#[test]
fn a_flat_press_gives_the_law_whatever_the_number_of_points() {
    let mut s = scenario("default");
    s.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    s.drive.motion = MotionProfile::hold(std::f64::consts::FRAC_PI_2);
    let (k, depth) = (7.5e6, 2e-4);
    s.dampeners[0].law = ForceLaw::Linear { stiffness_n_m: k, damping_n_s_m: 0.0 };
    s.dampeners[0].gap_m = -depth;
    let beam = BeamModel::new(s.beam_spec().unwrap()).unwrap();
    let boundary = beam.elements.iter().map(|el| el.x0_m).min_by(|a, b| (a - 8.2).abs().total_cmp(&(b - 8.2).abs()));
    let mut totals = Vec::new();
    for (detection, station, length) in [
        (Detection::Pipeline, 8.2, 0.075),
        (Detection::Pipeline, boundary.unwrap(), 0.3),
        (Detection::PadFace, 8.2, 0.075),
        (Detection::PadFace, boundary.unwrap(), 0.3),
    ] {
        s.contact.detection = detection;
        s.dampeners[0].station_m = station;
        s.dampeners[0].length_m = length;
        let mut scene = Scene::with_fidelity(&s, Fidelity::Rigid).unwrap();
        scene.step(1e-3).unwrap();
        let pair = scene.pairs().next().unwrap();
        println!(
            "{detection:?} at {station:.3} m, {length} m long: {:.2} N from {} points",
            pair.force_n,
            pair.points.len()
        );
        validated_rel(
            &CONTACT_SCENE,
            &format!(
                "default arm, rigid, pressed 0.2 mm into a linear pad (7.5e6 N/m) {} m long at {station:.3} m, {}: {} points",
                length,
                if detection == Detection::Pipeline { "pipeline" } else { "pad-face" },
                pair.points.len()
            ),
            k * depth,
            "k δ, whatever the number of points",
            pair.force_n,
            "N",
            0.01,
        );
        assert!(rel(pair.force_n, k * depth) < 0.01, "{detection:?}: {} N vs {} N", pair.force_n, k * depth);
        totals.push((pair.points.len(), pair.force_n));
    }
    assert!(totals[1].0 > totals[0].0, "the pad across two elements gives more points: {totals:?}");
}

/// A rigid arm swinging freely (no gravity) into a structure: as for a pad, the contact sees the
/// arm's effective mass J/r² at the contact's station, and the peak force follows the closed
/// form of a mass m_eff striking a linear spring at v0 = θ̇ r, v0 √(k m_eff).
#[test]
fn a_rigid_arm_swung_into_a_structure_follows_the_closed_form() {
    let mut s = scenario("lowering");
    s.physics.gravity_m_s2 = 0.0;
    s.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    let k = 7.5e6;
    let law = ForceLaw::Linear { stiffness_n_m: k, damping_n_s_m: 0.0 };
    // The structure where the scene's pad is, the same block: the pad taken away.
    s.dampeners[0].law = law;
    s.dampeners[0].gap_m = 0.0;
    let pad = Scene::with_fidelity(&s, Fidelity::Rigid).unwrap().pairs().next().unwrap().clone();
    let d = s.dampeners.remove(0);
    let t = pad.pose.translation;
    s.structures.push(Structure {
        name: "block".into(),
        shape: StructureShape::Box { half_extents_m: [0.5 * d.length_m, 0.5 * d.thickness_m, 0.5 * d.width_m] },
        position_m: [t.x, t.y, t.z],
        angle_rad: d.angle_rad,
        law,
        friction: 0.0,
    });
    let mut scene = Scene::with_fidelity(&s, Fidelity::Rigid).unwrap();
    assert_eq!(scene.detection(), Detection::Pipeline);
    let beam = BeamModel::new(s.beam_spec().unwrap()).unwrap();
    let arm = ArmModel::new(beam, Fidelity::Rigid, s.arm_options()).unwrap();
    let inertia = arm.pivot_inertia_kg_m2;
    let mut sim =
        ArmSimulation::new(arm, HubDrive::Free { torque_n_m: 0.0 }, IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 })
            .unwrap();
    let rate = -0.02;
    sim.set_free_hub_rate(rate).unwrap();
    scene.arm = sim;
    let mut peak = (0.0_f64, 0.0_f64);
    for _ in 0..5000 {
        scene.step(2e-5).unwrap();
        let pair = scene.pairs().find(|p| p.name == "arm-block").unwrap();
        if pair.force_n > peak.0 {
            peak = (pair.force_n, pair.station_m);
        }
    }
    let (peak, r) = peak;
    let (m_eff, v0) = (inertia / (r * r), rate.abs() * r);
    let exact = v0 * (k * m_eff).sqrt();
    println!("peak {peak:.1} N at {r:.3} m vs {exact:.1} N");
    validated_rel(
        &CONTACT_SCENE,
        &format!(
            "rigid arm swung at 0.02 rad/s into a structure (a box, linear 7.5e6 N/m) through the pipeline: peak force (m_eff = J/r² = {} kg)",
            common::sig(m_eff, 4)
        ),
        exact,
        "v₀ √(k m_eff), v₀ = θ̇ r",
        peak,
        "N",
        0.01,
    );
    assert!(rel(peak, exact) < 0.01, "peak {peak} vs {exact}");
}

/// The string strike scene: the guide catches the string near the end of the lift, and once the
/// arm stands still at 90° the string rests on the guide's upper edge. That edge, a = 4.3 m below
/// the lower hand, holds the string's overhang as a cantilever pushed 3 mm less the guide's own
/// penetration: F = 3 E I (δ − δ_g) / a³ (the string's end, 0.45 m further out, stands off).
#[test]
fn the_guide_holds_the_string_as_a_cantilever_from_its_hand() {
    let s = scenario("string_strike");
    let (summary, series) = run(&s, None).unwrap();
    let names = s.pair_series_names();
    let k = names.iter().position(|n| n == "string-well_guide").unwrap();
    let pair = summary.pairs.iter().find(|p| p.pair == "string-well_guide").unwrap();
    assert!(pair.impact_count >= 1 && pair.peak_force_n > 0.0);
    let arm_guide = summary.pairs.iter().find(|p| p.pair == "arm-well_guide").unwrap();
    assert_eq!(arm_guide.impact_count, 0, "the arm passes clear of the guide");
    let final_force = *series.pad_force_n[k].last().unwrap();
    let held = s.payload.string().unwrap();
    let pipe = &held.pipe.pipe;
    let (r_out, r_in) = (0.5 * pipe.outer_diameter_m, 0.5 * pipe.outer_diameter_m - pipe.wall_m);
    // Steel at 206 GPa, as the string model takes it.
    let ei = 2.06e11 * std::f64::consts::FRAC_PI_4 * (r_out.powi(4) - r_in.powi(4));
    let a = held.grips[0].station_m - (2.9 - 1.2);
    let ForceLaw::HuntCrossley { stiffness, exponent, .. } = s.structures[0].law else {
        panic!("a Hunt–Crossley guide")
    };
    let guide_depth = (final_force / stiffness).powf(1.0 / exponent);
    let exact = 3.0 * ei * (3e-3 - guide_depth) / a.powi(3);
    println!("string on the guide: {final_force:.2} N vs {exact:.2} N (a = {a:.2} m)");
    validated_rel(
        &CONTACT_SCENE,
        &format!("string_strike.toml, the arm at rest at 90°: the guide's force on the flexible string (a = {a:.2} m)"),
        exact,
        "the overhang as a cantilever from its hand, 3EI(δ − δ_g)/a³",
        final_force,
        "N",
        0.03,
    );
    assert!(rel(final_force, exact) < 0.03, "{final_force} N vs {exact} N");
}

/// `auto` takes the pad-face path only where it holds the pipeline's peak force to 0.1 %: on
/// every shipped scene where it picks it, both are run and compared (the structures' scene takes
/// the pipeline).
#[test]
fn auto_picks_the_pad_face_path_only_within_a_tenth_of_a_percent_of_the_pipeline() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    for path in pipearm::scenario::scenario_files(&folder).unwrap() {
        let mut s = Scenario::load(&path).unwrap().model;
        if s.dampeners.is_empty() || s.contact.method != pipearm::model::ContactMethod::Compliant {
            continue;
        }
        let fidelity = pipearm::select::fidelity(&s).unwrap().fidelity;
        let picked = Scene::with_fidelity(&s, fidelity).unwrap().detection();
        if !s.structures.is_empty() {
            assert_eq!(picked, Detection::Pipeline, "{}", s.name);
            continue;
        }
        assert_eq!(picked, Detection::PadFace, "{}", s.name);
        let peak = |s: &Model| run(s, None).unwrap().0.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max);
        let pad_face = peak(&s);
        s.contact.detection = Detection::Pipeline;
        let pipeline = peak(&s);
        println!("{}: pad-face {pad_face:.2} N, pipeline {pipeline:.2} N", s.name);
        validated_rel(
            &MODEL_CHOICE,
            &format!("{}: peak force by the pad-face path `auto` picks", s.name),
            pipeline,
            "rapier's collision pipeline, same scene",
            pad_face,
            "N",
            1e-3,
        );
        assert!(rel(pad_face, pipeline) < 1e-3, "{}: {pad_face} vs {pipeline}", s.name);
    }
}
