//! The coupled scene: arm + rapier + dampeners.

mod common;

use common::{CONTACT_SCENE, FRICTION_CLAMP, TIME_STEP, rel, validated, validated_rel};
use std::path::Path;

use pipearm::arm::{ArmModel, ArmSimulation, Fidelity, HubDrive};
use pipearm::beam::BeamModel;
use pipearm::contact::ForceLaw;
use pipearm::integrate::IntegratorKind;
use pipearm::model::{Clamp, ContactMethod, Model, Structure, StructureShape};
use pipearm::run::run;
use pipearm::scenario::{DriveSpec, Scenario};
use pipearm::scene::Scene;

fn scenario(name: &str) -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"))).unwrap().model
}

#[test]
fn the_default_arm_strikes_its_stop_repeatedly() {
    let s = scenario("default");
    let (summary, _) = run(&s, None).unwrap();
    let pair = &summary.pairs[0];
    assert!(pair.impact_count >= 2, "impacts: {}", pair.impact_count);
    assert!(pair.peak_force_n > 0.0 && pair.peak_time_s >= s.drive_end_s() - 3.0);
    validated(
        &common::SEED,
        "the default lift: largest tip vibration w/L",
        "below 2 % of the arm length (the seed paper, §5)",
        &format!("1/{:.0} of L, {} impacts on the stop", 1.0 / summary.max_w_over_l, pair.impact_count),
        "< 0.02",
    );
    // The seed's §5: the tip vibrates by less than 2 % of the arm length.
    assert!(summary.max_w_over_l < 0.02);
}

/// A rigid arm swinging freely (no gravity) into a pad: the contact sees the arm's effective
/// mass J/r² at the pad's station, so the peak force and contact time follow the closed forms
/// of a mass m_eff striking at v0 = θ̇ r.
#[test]
fn a_rigid_arm_swinging_into_a_pad_follows_the_closed_forms() {
    let mut s = scenario("lowering");
    s.physics.gravity_m_s2 = 0.0;
    // Rigid through and through: the string lumped too.
    s.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    let (k_lin, k_hertz) = (7.5e6, 2.0e9);
    for law in [
        ForceLaw::Linear { stiffness_n_m: k_lin, damping_n_s_m: 0.0 },
        ForceLaw::HuntCrossley { stiffness: k_hertz, exponent: 1.5, restitution: 1.0 },
    ] {
        s.dampeners[0].law = law;
        s.dampeners[0].gap_m = 0.0;
        let mut scene = Scene::with_fidelity(&s, Fidelity::Rigid).unwrap();
        let beam = BeamModel::new(s.beam_spec().unwrap()).unwrap();
        let arm = ArmModel::new(beam, Fidelity::Rigid, s.arm_options()).unwrap();
        let inertia = arm.pivot_inertia_kg_m2;
        let mut sim = ArmSimulation::new(
            arm,
            HubDrive::Free { torque_n_m: 0.0 },
            IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 },
        )
        .unwrap();
        let rate = -0.02;
        sim.set_free_hub_rate(rate).unwrap();
        scene.arm = sim;
        let r = s.dampeners[0].station_m;
        let (m_eff, v0) = (inertia / (r * r), rate.abs() * r);
        let (mut peak, mut t_first, mut t_last) = (0.0_f64, f64::NAN, f64::NAN);
        let h = 2e-5;
        for _ in 0..5000 {
            scene.step(h).unwrap();
            let f = scene.pairs().next().unwrap().force_n;
            let t = scene.arm.time_s();
            if f > 0.0 {
                peak = peak.max(f);
                if t_first.is_nan() {
                    t_first = t - h
                }
                t_last = t;
            }
        }
        let (exact_peak, exact_tc) = match law {
            ForceLaw::Linear { .. } => (v0 * (k_lin * m_eff).sqrt(), std::f64::consts::PI * (m_eff / k_lin).sqrt()),
            _ => {
                let depth = (5.0 * m_eff * v0 * v0 / (4.0 * k_hertz)).powf(0.4);
                (k_hertz * depth.powf(1.5), 3.218 * (m_eff * m_eff / (k_hertz * k_hertz * v0)).powf(0.2))
            }
        };
        let tc = t_last - t_first;
        println!("{law:?}: peak {peak:.1} N vs {exact_peak:.1} N, contact {tc:.5} s vs {exact_tc:.5} s");
        let (name, source) = match law {
            ForceLaw::Linear { .. } => ("linear pad (7.5e6 N/m)", "v₀ √(k m_eff), π √(m_eff/k)"),
            _ => ("Hertz pad (2e9, n = 1.5)", "Hertz: K δ*^1.5, 3.218 (m_eff²/K²v₀)^(1/5)"),
        };
        let case = format!(
            "rigid arm swung freely at 0.02 rad/s into the lowering scene's {name}, through the scene (m_eff = J/r² = {} kg)",
            common::sig(m_eff, 4)
        );
        validated_rel(&CONTACT_SCENE, &format!("{case}: peak force"), exact_peak, source, peak, "N", 0.01);
        validated_rel(&CONTACT_SCENE, &format!("{case}: contact time"), exact_tc, source, tc, "s", 0.02);
        assert!(rel(peak, exact_peak) < 0.01, "peak {peak} vs {exact_peak}");
        assert!(rel(tc, exact_tc) < 0.02, "contact time {tc} vs {exact_tc}");
    }
}

/// The default lift with the pad's law made linear: `rapier` at the scene's own step (3 ms, RK4)
/// with the scene's 1 kg pad body within 10 % of `compliant` converged (the bound;
/// measured 0.5 %), and, at a tenth of the step, converging on the massless pad that `compliant`
/// is as the pad body's mass goes to zero (a 30 kg pad body struck by the arm nearly doubles the
/// peak: a heavy pad is another machine).
#[test]
fn rapier_at_the_scene_step_converges_on_compliant_as_the_pad_mass_goes_to_zero() {
    let mut s = scenario("default");
    s.dampeners[0].law = ForceLaw::Linear { stiffness_n_m: 7.5e6, damping_n_s_m: 2.0e3 };
    s.time.settle_s = 1.0;
    let mut fine = s.clone();
    fine.time.step_s /= 10.0;
    let (compliant, _) = run(&fine, None).unwrap();
    let reference = compliant.pairs[0].peak_force_n;
    s.contact.method = ContactMethod::Rapier;
    let (at_scene_step, _) = run(&s, None).unwrap();
    let peak = at_scene_step.pairs[0].peak_force_n;
    println!("scene step, 1 kg pad: rapier {peak:.1} N vs compliant {reference:.1} N");
    validated_rel(
        &CONTACT_SCENE,
        "default lift, linear pad (7.5e6 N/m, 2e3 N·s/m): `rapier` with its 1 kg pad body at the scene's 3 ms step, peak force",
        reference,
        "`compliant` at 0.3 ms",
        peak,
        "N",
        0.10,
    );
    assert!(rel(peak, reference) < 0.10, "{peak} vs {reference}");
    fine.contact.method = ContactMethod::Rapier;
    let mut differences = Vec::new();
    for mass in [30.0, 3.0, 0.3, 0.03] {
        fine.contact.pad_mass_kg = mass;
        let (rapier, _) = run(&fine, None).unwrap();
        let peak = rapier.pairs[0].peak_force_n;
        println!("pad {mass} kg: rapier {peak:.1} N ({:.3} %)", 100.0 * rel(peak, reference));
        differences.push(rel(peak, reference));
    }
    // It shrinks with the mass down to the two methods' own difference at this step (0.3 %).
    let floor = 0.005;
    validated(
        &CONTACT_SCENE,
        "the same at 0.3 ms, pad bodies of 30, 3, 0.3, 0.03 kg: peak force",
        &format!("`compliant` at 0.3 ms, {} N, approached as the pad's mass goes to zero", common::sig(reference, 5)),
        &differences.iter().map(|d| common::relative(*d)).collect::<Vec<_>>().join(", "),
        "shrinking to below 0.5 %; 30 kg off by more than 5 %",
    );
    assert!(differences.windows(2).all(|d| d[1] < d[0] || d[1] < floor), "{differences:?}");
    assert!(differences[0] > 10.0 * floor && differences[3] < floor, "{differences:?}");
}

#[test]
fn the_heavy_string_runs_stable_at_the_default_step() {
    // 200 kg of casing on the arm's tip: the added-mass trap of staggered coupling. The
    // compliant contact is implicit in the arm step, so the default step holds; halving it moves
    // the peak force little.
    let s = scenario("string_4half");
    let (coarse, series) = run(&s, None).unwrap();
    assert!(series.tip_deflection_m.iter().all(|d| d[1].is_finite() && d[1].abs() < 0.02 * 9.0));
    let mut fine = s.clone();
    fine.time.step_s /= 4.0;
    let (fine, _) = run(&fine, None).unwrap();
    let (a, b) = (coarse.pairs[0].peak_force_n, fine.pairs[0].peak_force_n);
    println!("4-1/2 in string: peak force {a:.1} N at dt, {b:.1} N at dt/4");
    validated_rel(
        &TIME_STEP,
        "string_4half.toml (200 kg string, both hands) at its own step: peak pad force",
        b,
        "the same scene at a quarter of the step",
        a,
        "N",
        0.1,
    );
    assert!(rel(a, b) < 0.1, "{a} vs {b}");
}

/// The default arm standing at 90° with a friction-clamped 2⅞ in string (`string` its fidelity):
/// the string's weight pulls along the arm toward the hub; the jaws hold it while 2μN exceeds
/// m g, and it slides with a = g − 2μN/m once it does not — a flexible string as a rigid one,
/// since its bending modes are across its axis.
fn friction_hold(squeeze_n: f64, seconds: f64, string: Fidelity) -> (f64, f64) {
    let mut s = scenario("default");
    let mu = 0.3;
    let held = s.payload.string_mut().unwrap();
    held.in_one_hand("gripper", 9.0);
    held.clamp = Clamp::Friction;
    held.model = Some(string);
    held.friction.friction_coefficient = mu;
    held.friction.squeeze_n = Some(squeeze_n);
    s.drive.motion = DriveSpec::Hold { angle_deg: 90.0 }.motion().unwrap();
    s.dampeners.clear();
    // Implicit: the fe string's highest modes are far beyond RK4's limit at this step.
    s.integrator = IntegratorKind::default();
    let mut scene = Scene::new(&s).unwrap();
    let h = 1e-3;
    for _ in 0..(seconds / h) as usize {
        scene.step(h).unwrap();
    }
    let mass = s.payload.mass_kg();
    (scene.grip().unwrap().slip_m, mass)
}

#[test]
fn the_friction_clamp_holds_below_the_slip_load_and_slips_above_it() {
    let (mu, g) = (0.3, 9.80665);
    let weight = 120.875 * g;
    for string in [Fidelity::Rigid, Fidelity::Modal { modes: 3 }, Fidelity::Fe] {
        // Holds with 25 % margin.
        let (slip, _) = friction_hold(1.25 * weight / (2.0 * mu), 1.0, string);
        println!("{string} string, 2μN = 1.25 m g: slip {slip:.6} m in 1 s");
        common::validated_abs(
            &FRICTION_CLAMP,
            &format!("default arm standing at 90°, {string} string in one hand's jaws, 2μN = 1.25 m g: slip in 1 s"),
            0.0,
            "Coulomb: holds while 2μN > m g",
            slip,
            "m",
            1e-3,
        );
        assert!(slip.abs() < 1e-3, "{string} string slipped {slip} m while 2μN > m g");
        // Slides at 25 % short of the load.
        let squeeze = 0.75 * weight / (2.0 * mu);
        let (slip, mass) = friction_hold(squeeze, 1.0, string);
        let accel = g - 2.0 * mu * squeeze / mass;
        let expected = -0.5 * accel;
        println!("{string} string, 2μN = 0.75 m g: slip {slip:.4} m in 1 s, Coulomb {expected:.4} m");
        validated_rel(
            &FRICTION_CLAMP,
            &format!("the same, 2μN = 0.75 m g: slip in 1 s ({string} string)"),
            expected,
            "Coulomb: slides ½ (g − 2μN/m) t²",
            slip,
            "m",
            0.05,
        );
        assert!(rel(slip, expected) < 0.05, "{string} string: slip {slip} m vs {expected} m");
    }
}

/// The same standing arm and sliding string (2μN = 0.75 m g), with a frictionless block 0.1 m
/// below the string's lower end: the string slides ½ a t² onto it, a = g − 2μN/m, and stops
/// there — the block's force reaches the string's slip, whatever the string's fidelity: it sinks
/// into the block no deeper than twice a mass striking a spring at v₀ would, v₀√(m/k), and rests
/// on it with the jaws' static friction within ±2μN (the block carries m g ∓ 2μN).
#[test]
fn a_string_sliding_in_a_friction_clamp_lands_on_a_structure_and_stops() {
    let (mu, g, gap, stiffness) = (0.3, 9.80665, 0.1, 1e7);
    for string in [Fidelity::Rigid, Fidelity::Modal { modes: 3 }] {
        let mut s = scenario("default");
        let held = s.payload.string_mut().unwrap();
        held.in_one_hand("gripper", 9.0);
        held.clamp = Clamp::Friction;
        held.model = Some(string);
        held.friction.friction_coefficient = mu;
        let mass = s.payload.mass_kg();
        let squeeze = 0.75 * mass * g / (2.0 * mu);
        s.payload.string_mut().unwrap().friction.squeeze_n = Some(squeeze);
        s.drive.motion = DriveSpec::Hold { angle_deg: 90.0 }.motion().unwrap();
        s.dampeners.clear();
        s.integrator = IntegratorKind::default();
        // Where the string's lower end is: the lumped string's drawn piece, standing along world y.
        let end = {
            let mut probe = s.clone();
            probe.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
            let scene = Scene::new(&probe).unwrap();
            let layout = scene.layout();
            let i = layout.pieces.iter().position(|(name, _)| name == "string").unwrap();
            let (pose, half) = (scene.frame().pieces[i], layout.pieces[i].1);
            // A cylinder runs along its own y.
            let axis = pose.rotation * rapier3d_f64::prelude::Vector::Y * half[1];
            let ends = [pose.translation - axis, pose.translation + axis];
            if ends[0].y < ends[1].y { ends[0] } else { ends[1] }
        };
        let block_half = [0.15, 0.1, 0.15];
        s.structures.push(Structure {
            name: "block".into(),
            shape: StructureShape::Box { half_extents_m: block_half },
            position_m: [end.x, end.y - gap - block_half[1], end.z],
            angle_rad: 0.0,
            law: ForceLaw::Linear { stiffness_n_m: stiffness, damping_n_s_m: 2e4 },
            friction: 0.0,
        });
        let mut scene = Scene::new(&s).unwrap();
        let h = 1e-3;
        let (mut lowest, mut landed_s) = (0.0_f64, None);
        for k in 1..=1500 {
            scene.step(h).unwrap();
            let slip = scene.grip().unwrap().slip_m;
            lowest = lowest.min(slip);
            if landed_s.is_none() && slip <= -gap {
                landed_s = Some(k as f64 * h);
            }
        }
        let slip = scene.grip().unwrap().slip_m;
        let on_block: f64 = scene.pairs().filter(|p| p.name == "string-block").map(|p| p.force_n).sum();
        let accel = g - 2.0 * mu * squeeze / mass;
        let arrival_s = (2.0 * gap / accel).sqrt();
        let impact_depth_m = accel * arrival_s * (mass / stiffness).sqrt();
        let friction_n = 2.0 * mu * squeeze;
        println!(
            "{string} string: landed at {:.3} s (½ a t²: {arrival_s:.3} s), {:.2} mm into the block (v₀√(m/k) = \
             {:.2} mm), rests at {slip:.4} m, the block carrying {on_block:.1} N (m g ∓ 2μN: {:.1} ..= {:.1} N)",
            landed_s.unwrap_or(f64::NAN),
            1e3 * (-gap - lowest),
            1e3 * impact_depth_m,
            mass * g - friction_n,
            mass * g + friction_n
        );
        let case = format!("the sliding {string} string onto a frictionless block 0.1 m below (1e7 N/m)");
        validated_rel(
            &FRICTION_CLAMP,
            &format!("{case}: landing time"),
            arrival_s,
            "√(2d/a), a = g − 2μN/m",
            landed_s.unwrap_or(f64::NAN),
            "s",
            0.05,
        );
        validated(
            &FRICTION_CLAMP,
            &format!("{case}: depth into the block"),
            &format!("at most twice v₀ √(m/k) = 2 × {} mm", common::sig(1e3 * impact_depth_m, 3)),
            &format!("{} mm", common::sig(1e3 * (-gap - lowest), 3)),
            "< 2 v₀ √(m/k)",
        );
        validated(
            &FRICTION_CLAMP,
            &format!("{case}: force on the block at rest"),
            &format!(
                "m g ∓ 2μN = {} ..= {} N (the jaws' static friction)",
                common::sig(mass * g - friction_n, 4),
                common::sig(mass * g + friction_n, 4)
            ),
            &format!(
                "{} N, resting {} mm into the block",
                common::sig(on_block, 4),
                common::sig(-1e3 * (slip + gap), 2)
            ),
            "within the band (±1 %); rest within 1 mm",
        );
        assert!(rel(landed_s.expect("the string reaches the block"), arrival_s) < 0.05);
        assert!(-gap - lowest < 2.0 * impact_depth_m, "the string went {} m past the block's face", -gap - lowest);
        assert!((slip + gap).abs() < 1e-3, "the string rests {slip} m from its grip, the block at {gap} m");
        let statics = (mass * g - friction_n) * 0.99..=(mass * g + friction_n) * 1.01;
        assert!(statics.contains(&on_block), "block force {on_block} N outside {statics:?}");
    }
}

#[test]
fn the_friction_clamped_heavy_string_lifts_stable_at_the_default_step() {
    let mut s = scenario("string_4half");
    s.payload.string_mut().unwrap().in_one_hand("gripper", 9.0);
    // Held fast by its jaws, a string in a friction clamp is the rigid clamp's string: lumped,
    // or a beam clamped at the hand with its bending modes (what `auto` picks here).
    for string in [Some(Fidelity::Rigid), None] {
        let mut rigid_clamp = s.clone();
        rigid_clamp.payload.string_mut().unwrap().model = string;
        let mut friction_clamp = rigid_clamp.clone();
        friction_clamp.payload.string_mut().unwrap().clamp = Clamp::Friction;
        let (friction, series) = run(&friction_clamp, None).unwrap();
        let (rigid, _) = run(&rigid_clamp, None).unwrap();
        let slip = friction.string_slip.unwrap();
        let (held, fast) = (friction.string.unwrap(), rigid.string.unwrap());
        println!(
            "{} string: slip {:.3e} m, peak force {:.1} N vs rigid clamp {:.1} N, stress at the hand {:.2} MPa vs {:.2} MPa",
            held.model,
            slip.max_slip_m,
            friction.pairs[0].peak_force_n,
            rigid.pairs[0].peak_force_n,
            1e-6 * held.max_bending_stress_pa,
            1e-6 * fast.max_bending_stress_pa
        );
        let case =
            format!("200 kg string held by friction in the gripper through the default lift, {} string", held.model);
        validated_rel(
            &FRICTION_CLAMP,
            &format!("{case}: peak pad force"),
            rigid.pairs[0].peak_force_n,
            "the rigid clamp, same string and step",
            friction.pairs[0].peak_force_n,
            "N",
            0.05,
        );
        validated_rel(
            &FRICTION_CLAMP,
            &format!("{case}: largest bending stress at the hand"),
            fast.max_bending_stress_pa,
            "the rigid clamp",
            held.max_bending_stress_pa,
            "Pa",
            0.05,
        );
        assert!(series.tip_deflection_m.iter().all(|d| d[1].is_finite()));
        assert_eq!(held.model, fast.model, "the clamp does not change the string's fidelity");
        assert_eq!(string.is_none(), held.model.starts_with("modal"), "auto keeps the 4½ in string's modes");
        // Held: what moves is rapier's friction creep, millimetres that change with the step and
        // the order of floating-point operations (1.2–8.4 mm, docs/accuracy.md), not a slide.
        assert!(slip.max_slip_m < 1e-2, "40 kN jaws let 200 kg slip {} m", slip.max_slip_m);
        assert!(rel(friction.pairs[0].peak_force_n, rigid.pairs[0].peak_force_n) < 0.05);
        assert!(rel(held.max_bending_stress_pa, fast.max_bending_stress_pa) < 0.05);
    }
}
