//! A tilting head: a rigid body on a spring hinge on the arm, its angle ψ one more coordinate
//! of the arm's equations. Held to the compound pendulum, to a finite-element model of arm and
//! head built here from the beam's own matrices, and to the energy it must keep.

mod common;

use std::path::PathBuf;

use common::{TILTING_HEAD, rel, validated_rel};
use nalgebra::{DMatrix, DVector};
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, HeadState, HubDrive};
use pipearm::beam::BeamModel;
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;
use pipearm::robot::{Robot, load_robot};

/// A 4 m solid steel arm, 100 × 100 mm, with a head on joint `wrist` at station `hinge_m`: the
/// joint's type and `<pipearm:hinge>` as given, the head's centre of mass at `centre` from
/// the hinge, mass `mass_kg` and inertia `izz` about its centre.
fn head_robot(tag: &str, joint: &str, hinge: &str, hinge_m: f64, centre: [f64; 2], mass_kg: f64, izz: f64) -> PathBuf {
    let text = format!(
        r#"<?xml version="1.0"?>
<robot name="head_test" xmlns:pipearm="https://pipearm.dev/urdf/1">
  <link name="base"/>
  <joint name="lift" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="2" effort="1e6" velocity="1"/>
  </joint>
  <link name="arm" pipearm:flexible="true">
    <pipearm:flexible elements="12" damping_ratios="0" hub_inertia_kg_m2="0">
      <pipearm:segment length_m="4.0" youngs_modulus_pa="2.06e11" density_kg_m3="7850"
                       section="solid-rectangle" width_m="0.1" depth_m="0.1"/>
    </pipearm:flexible>
  </link>
  <joint name="wrist" type="{joint}">
    <parent link="arm"/><child link="head"/>
    <origin xyz="{hinge_m} 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1e4" velocity="1"/>
    {hinge}
  </joint>
  <link name="head">
    <inertial>
      <origin xyz="{} {} 0" rpy="0 0 0"/><mass value="{mass_kg}"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="{izz}"/>
    </inertial>
  </link>
</robot>
"#,
        centre[0], centre[1]
    );
    let path = std::env::temp_dir().join(format!("pipearm-head-{tag}-{}.urdf", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

fn load(path: PathBuf) -> Robot {
    let robot = load_robot(&path);
    std::fs::remove_file(&path).ok();
    robot.unwrap()
}

fn spring(stiffness: f64) -> String {
    format!(r#"<pipearm:hinge kind="spring" stiffness_n_m_per_rad="{stiffness}"/>"#)
}

fn arm(robot: &Robot, fidelity: Fidelity, gravity_m_s2: f64) -> ArmModel {
    let beam = BeamModel::new(robot.beam_spec(&[]).unwrap()).unwrap();
    let options = ArmOptions { damping_ratios: vec![0.0], gravity_m_s2, ..ArmOptions::default() };
    ArmModel::new(beam, fidelity, options).unwrap().with_head(robot.head.as_ref()).unwrap()
}

/// Times of ψ's upward zero crossings, interpolated, s.
fn crossings(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

/// The head's swing frequency (rad/s) once released 0.01 rad from its rest in `sim`, over
/// `duration_s` in steps of `step_s`: from ψ's upward zero crossings.
fn swing_rad_s(sim: &mut ArmSimulation, duration_s: f64, step_s: f64) -> f64 {
    sim.set_head_state(HeadState { angle_rad: 0.01, rate_rad_s: 0.0 }).unwrap();
    let mut psi = Vec::new();
    while sim.time_s() < duration_s {
        sim.step(step_s).unwrap();
        psi.push((sim.time_s(), sim.head_state().unwrap().angle_rad));
    }
    let ups = crossings(&psi);
    std::f64::consts::TAU * (ups.len() - 1) as f64 / (ups[ups.len() - 1] - ups[0])
}

/// A head hanging below the tip of a rigid arm held still swings as a compound pendulum on a
/// torsion spring: ω² = (m g d + k) / (J + m d²).
#[test]
fn a_head_below_a_rigid_arm_swings_as_a_compound_pendulum() {
    let (m, d, j, k, g) = (50.0, 0.3, 2.0, 1.0, 9.80665);
    let robot = load(head_robot("pendulum", "revolute", &spring(k), 4.0, [0.0, -d], m, j));
    let head = robot.head.as_ref().expect("a spring hinge makes a tilting head");
    assert_eq!((head.mass_kg, head.centre_of_mass_m, head.inertia_kg_m2), (m, [0.0, -d], j));
    let arm = arm(&robot, Fidelity::Rigid, g);
    let drive = HubDrive::Prescribed(MotionProfile::hold(0.0));
    let mut sim = ArmSimulation::new(arm, drive, IntegratorKind::Rk4).unwrap();
    assert!(sim.head_state().unwrap().angle_rad.abs() < 1e-12, "hanging straight down is its rest");
    let measured = swing_rad_s(&mut sim, 14.0, 1e-3);
    let exact = ((m * g * d + k) / (j + m * d * d)).sqrt();
    let case = "head hanging 0.3 m below a rigid arm's tip, arm held still, swung 0.01 rad";
    validated_rel(&TILTING_HEAD, case, exact, "√((m g d + k)/(J + m d²))", measured, "rad/s", 1e-4);
    assert!(rel(measured, exact) < 1e-4, "{measured} against {exact}");

    // Held at 0.5 rad, the head rests where its spring balances its weight's moment about the
    // hinge: k ψ = −m g d sin(θ + ψ).
    let rest = |psi: f64| k * psi + m * g * d * (0.5 + psi).sin();
    let (mut lo, mut hi) = (-0.6, 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if rest(mid) > 0.0 { hi = mid } else { lo = mid }
    }
    let robot = load(head_robot("pendulum-tilted", "revolute", &spring(k), 4.0, [0.0, -d], m, j));
    let sim = ArmSimulation::new(
        self::arm(&robot, Fidelity::Rigid, g),
        HubDrive::Prescribed(MotionProfile::hold(0.5)),
        IntegratorKind::Rk4,
    )
    .unwrap();
    let psi = sim.head_state().unwrap().angle_rad;
    assert!((psi - lo).abs() < 1e-9, "rest {psi} rad against {lo} rad");
}

/// A head on a torsion spring beyond the tip of a flexible cantilever (no gravity, hub held):
/// the coupled frequencies against an eigen-solve of the arm's unreduced beam matrices plus the
/// head as a rigid body, its centre a lever d beyond the hinge.
#[test]
fn a_head_on_a_spring_at_a_cantilevers_tip_rings_with_it_as_a_finite_element_model_says() {
    let (m, d, j, k) = (40.0, 0.25, 1.5, 4.0e3);
    let robot = load(head_robot("cantilever", "revolute", &spring(k), 4.0, [d, 0.0], m, j));
    let sim = ArmSimulation::new(
        arm(&robot, Fidelity::Fe, 0.0),
        HubDrive::Prescribed(MotionProfile::hold(0.0)),
        IntegratorKind::Rk4,
    )
    .unwrap();
    let mut measured: Vec<f64> = sim.linear_poles().unwrap().iter().map(|p| p.im).filter(|w| *w > 0.0).collect();
    measured.sort_by(f64::total_cmp);

    // The truth: the bare arm's matrices, and the head's kinetic energy through the hinge's rows
    // (u, v, φ at the tip): its centre moves by (u, v + d β), β = φ + ψ.
    let mut bare = robot.clone();
    bare.head = None;
    bare.carried.retain(|b| !b.tilts);
    let beam = BeamModel::new(bare.beam_spec(&[]).unwrap()).unwrap();
    let dofs = beam.dofs();
    let [nu, nv, nphi] = beam.point_rows(4.0);
    let row =
        |beam_row: DVector<f64>, head: f64| DVector::from_iterator(dofs + 1, beam_row.iter().copied().chain([head]));
    let (along, across, turn) = (row(nu, 0.0), row(&nv + d * &nphi, d), row(nphi, 1.0));
    let mut mass = DMatrix::zeros(dofs + 1, dofs + 1);
    mass.view_mut((0, 0), (dofs, dofs)).copy_from(&beam.mass);
    mass += m * (&along * along.transpose() + &across * across.transpose()) + j * &turn * turn.transpose();
    let mut stiffness = DMatrix::zeros(dofs + 1, dofs + 1);
    stiffness.view_mut((0, 0), (dofs, dofs)).copy_from(&beam.stiffness);
    stiffness[(dofs, dofs)] = k;
    let l_inv = mass.cholesky().unwrap().l().try_inverse().unwrap();
    let symmetric = &l_inv * stiffness * l_inv.transpose();
    let mut exact: Vec<f64> = symmetric.symmetric_eigenvalues().iter().map(|l| l.sqrt()).collect();
    exact.sort_by(f64::total_cmp);

    let case = "head on a 4 kN·m/rad hinge 0.25 m beyond a 4 m cantilever's tip: first three coupled frequencies";
    let source = "eigen-solve of the beam's matrices with the head as a rigid body";
    common::validated_rel_all(&TILTING_HEAD, case, &exact[..3], source, &measured[..3], "rad/s", 1e-6);
    for (w, e) in measured.iter().zip(&exact).take(3) {
        assert!(rel(*w, *e) < 1e-6, "{w} rad/s against {e} rad/s");
    }
}

/// A head released 0.3 rad off its rest on a flexible arm held still under gravity, nothing
/// damped: the energy of arm and head together stays what it was.
#[test]
fn a_swinging_head_keeps_the_energy_of_arm_and_head() {
    let robot = load(head_robot("energy", "revolute", &spring(2.0e3), 3.5, [0.4, -0.2], 60.0, 2.0));
    let arm = arm(&robot, Fidelity::Modal { modes: 4 }, 9.80665);
    let h = 0.1 / arm.highest_omega_rad_s;
    let mut sim = ArmSimulation::new(arm, HubDrive::Prescribed(MotionProfile::hold(0.3)), IntegratorKind::Rk4).unwrap();
    let rest = sim.sample().energies.total_j();
    let psi = sim.head_state().unwrap().angle_rad;
    sim.set_head_state(HeadState { angle_rad: psi + 0.3, rate_rad_s: 0.0 }).unwrap();
    let start = sim.sample().energies.total_j();
    let (mut worst, mut swing) = (0.0f64, 0.0f64);
    while sim.time_s() < 3.0 {
        sim.step(h).unwrap();
        let sample = sim.sample();
        worst = worst.max((sample.energies.total_j() - start).abs());
        swing = swing.max((sim.head_state().unwrap().angle_rad - psi).abs());
    }
    let drift = worst / (start - rest);
    common::validated_row(
        &TILTING_HEAD,
        "head released 0.3 rad off its rest on a modal(4) arm held at 0.3 rad, undamped, 3 s: energy",
        "conserved",
        &format!("drift {} of the energy it was released with", common::relative(drift)),
        &common::relative(drift),
        "< 1e-6",
    );
    assert!(swing > 0.25, "the head swung {swing} rad");
    assert!(drift < 1e-6, "energy drifted {drift} of the release energy");
}

/// A locked hinge is a fixed joint: the same robot, the same arm, the same run to the last bit.
#[test]
fn a_locked_head_is_the_fixed_head() {
    let locked =
        load(head_robot("locked", "revolute", r#"<pipearm:hinge kind="locked"/>"#, 3.8, [0.2, 0.0], 60.0, 2.0));
    let fixed = load(head_robot("fixed", "fixed", "", 3.8, [0.2, 0.0], 60.0, 2.0));
    assert!(locked.head.is_none());
    assert_eq!(locked.carried, fixed.carried);
    let run = |robot: &Robot| {
        let drive = HubDrive::Prescribed(MotionProfile::hold(0.2));
        let mut sim =
            ArmSimulation::new(arm(robot, Fidelity::Modal { modes: 3 }, 9.80665), drive, IntegratorKind::Rk4).unwrap();
        sim.set_free_hub_rate(0.0).ok();
        (0..200)
            .map(|_| {
                sim.step(1e-3).unwrap();
                sim.sample().tip_deflection_hub_m[1]
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(run(&locked), run(&fixed));
}

/// A head the file gets wrong fails with the file, the element and what is allowed.
#[test]
fn a_bad_hinge_is_named() {
    let cases: [(&str, &str, &str, f64, &[&str]); 6] = [
        ("no-hinge", "revolute", "", 3.8, &["joint[wrist].pipearm:hinge", "missing", "kind=\"spring\""]),
        ("off-arm", "revolute", &spring(1e3), 4.5, &["joint[wrist].origin", "off the arm", "0 ..= 4 m"]),
        (
            "kind",
            "revolute",
            r#"<pipearm:hinge kind="floppy"/>"#,
            3.8,
            &["@kind", "`floppy`", "\"spring\" or \"driven\""],
        ),
        (
            "damping",
            "revolute",
            r#"<pipearm:hinge kind="spring" stiffness_n_m_per_rad="1e3" damping_n_m_s_per_rad="-2"/>"#,
            3.8,
            &["@damping_n_m_s_per_rad", ">= 0"],
        ),
        ("stiffness", "revolute", &spring(0.0), 3.8, &["@stiffness_n_m_per_rad", "allowed > 0"]),
        (
            "unknown",
            "revolute",
            r#"<pipearm:hinge kind="locked" stiffness="3"/>"#,
            3.8,
            &["@stiffness", "unknown attribute"],
        ),
    ];
    for (tag, joint, hinge, at, needles) in cases {
        let path = head_robot(tag, joint, hinge, at, [0.2, 0.0], 50.0, 1.0);
        let error = load_robot(&path).err().unwrap_or_else(|| panic!("{tag}: loaded")).to_string();
        std::fs::remove_file(&path).ok();
        assert!(error.contains(&path.display().to_string()), "{tag}: no file in: {error}");
        for needle in needles {
            assert!(error.contains(needle), "{tag}: `{needle}` missing from: {error}");
        }
    }
    // The hinge's axis must be normal to the lift plane.
    let path = head_robot("axis", "revolute", &spring(1e3), 3.8, [0.2, 0.0], 50.0, 1.0);
    let text = std::fs::read_to_string(&path).unwrap();
    let at = text.rfind(r#"<axis xyz="0 0 1"/>"#).unwrap();
    std::fs::write(&path, format!("{}<axis xyz=\"0 1 0\"/>{}", &text[..at], &text[at + 19..])).unwrap();
    let error = load_robot(&path).expect_err("a hinge about y loaded").to_string();
    std::fs::remove_file(&path).ok();
    assert!(error.contains("joint[wrist].axis") && error.contains("normal to the lift"), "{error}");
}

/// `scenarios/tilting_head.toml` as `edit` rewrites its text, loaded.
fn edited_head_scenario(tag: &str, edit: impl FnOnce(String) -> String) -> Result<pipearm::model::Model, String> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenarios/tilting_head.toml")).unwrap();
    let path = root.join(format!("scenarios/.head-{tag}-{}.toml", std::process::id()));
    std::fs::write(&path, edit(text)).unwrap();
    let loaded = pipearm::scenario::Scenario::load(&path).map(|s| s.model).map_err(|e| e.to_string());
    std::fs::remove_file(&path).ok();
    loaded
}

/// `scenarios/tilting_head.toml` with its payload `payload` and, appended, `extra`, loaded.
fn head_scenario(tag: &str, payload: &str, extra: &str) -> Result<pipearm::model::Model, String> {
    edited_head_scenario(tag, |text| text.replace("kind = \"none\"", payload) + extra)
}

/// A string in the gripper on the tilting head is rigid with the head: on a rigid arm held still,
/// without gravity, the head swings on its spring at √(k / J), J the head's inertia about its
/// hinge (the URDF's links) plus the string's about its own centre (the pipe's, from the
/// catalogue) and its mass times the square of its centre's distance from the hinge.
#[test]
fn a_string_in_the_heads_gripper_swings_with_the_head() {
    let string = "kind = \"string\"\nsize = \"2-7/8\"\nat = \"gripper\"\nmodel = { kind = \"rigid\" }";
    let model = head_scenario("string", string, "").expect("a string on the head loads");
    let pipearm::model::Payload::StringOnHead(held) = &model.payload else { panic!("{:?}", model.payload) };
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let bare = load_robot(&root.join("robots/pipe_arm_head.urdf")).unwrap().head.unwrap();
    let head = model.robot.head.as_ref().unwrap();
    let (m, d) = (held.pipe.mass_kg(), held.mass_centre_m() - bare.hinge_station_m);
    let j = bare.inertia_about_hinge_kg_m2() + held.pipe.transverse_inertia_kg_m2() + m * d * d;
    assert!(rel(head.mass_kg, bare.mass_kg + m) < 1e-12, "the head carries the string's mass");
    let k = head.stiffness_n_m_per_rad();
    let exact = (k / j).sqrt();
    let drive = HubDrive::Prescribed(MotionProfile::hold(0.0));
    let mut sim = ArmSimulation::new(arm(&model.robot, Fidelity::Rigid, 0.0), drive, IntegratorKind::Rk4).unwrap();
    let measured = swing_rad_s(&mut sim, 20.0, 2e-3);
    let case = "2-7/8 string in the head's gripper, rigid arm held still, no gravity, swung 0.01 rad";
    let truth = "√(k / (J_head + J_string + m d²)) about the hinge";
    validated_rel(&TILTING_HEAD, case, exact, truth, measured, "rad/s", 1e-4);
    assert!(rel(measured, exact) < 1e-4, "{measured} against {exact}");
}

/// A string on the tilting head is held fast, rigid, by hands all on the head, and strikes no
/// structure: anything else is refused before the run with the scenario's key.
#[test]
fn a_string_on_the_head_otherwise_held_is_refused_by_key() {
    let string = |rest: &str| format!("kind = \"string\"\nsize = \"2-7/8\"\n{rest}");
    let structure = "\n[[structures]]\nname = \"guide\"\nshape = { kind = \"box\", size_m = [0.2, 0.6, 0.3] }\n\
                     position_m = [-0.1335, 2.6, 0.65]\nlaw = { kind = \"hunt-crossley\", stiffness = 2.0e7, exponent = 1.5, \
                     restitution = 0.5 }\n";
    for (tag, payload, extra, key, says) in [
        (
            "mixed",
            string("grips = [{ hand = \"hand\", at_m = 4.75 }, { hand = \"gripper\", at_m = 8.05 }]"),
            "",
            "payload.grips",
            "every hand on the head or none",
        ),
        ("friction", string("at = \"gripper\"\nclamp = \"friction\""), "", "payload.clamp", "held fast"),
        (
            "modal",
            string("at = \"gripper\"\nmodel = { kind = \"modal\", modes = 3 }"),
            "",
            "payload.model",
            "rigid with it",
        ),
        ("structure", string("at = \"gripper\""), structure, "structures", "takes no part in contact"),
    ] {
        let error = head_scenario(tag, &payload, extra).err().unwrap_or_else(|| panic!("{tag}: loaded"));
        assert!(error.contains(&format!("`{key}`")) && error.contains(says), "{tag}: {error}");
    }
}

/// The worst gap over a run between the root moment the section forces sum (Newton–Euler, the
/// head's load at its hinge in it) and the drive's torque on the hub less the hub's own inertia
/// J_hub θ̈ (Lagrange's θ equation, the head's share through its θ row), and the peak torque.
fn root_moment_gap(model: &pipearm::model::Model) -> (f64, f64, pipearm::run::RunSummary) {
    let (summary, series) = pipearm::run::run(model, None).unwrap();
    let j_hub = model.robot.arm.hub_inertia_kg_m2;
    let root = series.stress.stations.iter().position(|s| s.station_m == 0.0).unwrap();
    let worst = (0..series.t_s.len())
        .map(|k| {
            let [_, m] = series.stress.section_forces(root, k);
            (m - (series.drive_torque_n_m[k] - j_hub * series.hub_accel_rad_s2[k])).abs()
        })
        .fold(0.0, f64::max);
    let peak = series.drive_torque_n_m.iter().fold(0.0_f64, |p, t| p.max(t.abs()));
    (worst, peak, summary)
}

/// Runs `model` and holds its root moment to `torque` less J_hub θ̈ within 1e-4 of the peak
/// torque at every step ([`root_moment_gap`]), reported as `case`; returns the run's summary.
fn assert_root_moment_balance(model: &pipearm::model::Model, case: &str, torque: &str) -> pipearm::run::RunSummary {
    let (worst, peak, summary) = root_moment_gap(model);
    common::validated_row(
        &TILTING_HEAD,
        case,
        &format!("{torque} − J_hub θ̈ (Lagrange's θ equation)"),
        &format!("worst {worst:.1} N·m"),
        &common::relative(worst / peak),
        "< 1e-4 of the peak torque",
    );
    assert!(worst < 1e-4 * peak, "{case}: worst {worst} N·m against a peak of {peak}");
    summary
}

/// Lagrange's θ equation gives the drive torque (the head's share through its θ row); the
/// section forces sum Newton–Euler on what is outboard of the root, the head's load on the arm
/// at its hinge included: through the shipped lift, whose head swings on its mount and whose
/// arm strikes the pad, they differ by the hub's own inertia J_hub θ̈ and second-order terms.
#[test]
fn with_a_swinging_head_the_root_moment_is_the_drive_torque_less_the_hubs_inertia() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/tilting_head.toml");
    let model = pipearm::scenario::Scenario::load(&path).unwrap().model;
    let case = "tilting_head.toml (head swinging on its mount, pad struck): root moment at every step";
    let summary = assert_root_moment_balance(&model, case, "drive torque");
    let swing = summary.head.as_ref().unwrap();
    assert!(swing.max_angle_deg - swing.min_angle_deg > 5.0, "the head swung: {swing:?}");
}

/// The same balance with a string in the head's gripper: its weight and inertia reach the arm
/// through the head's hinge, in the section forces as in the drive's torque.
#[test]
fn with_a_string_on_the_head_the_root_moment_is_the_drive_torque_less_the_hubs_inertia() {
    let string = "kind = \"string\"\nsize = \"2-7/8\"\nat = \"gripper\"";
    let model = head_scenario("string-lift", string, "").unwrap();
    let case = "tilting_head.toml with a 2-7/8 string in the head's gripper: root moment at every step";
    let summary = assert_root_moment_balance(&model, case, "drive torque");
    assert!(summary.pairs[0].peak_force_n > 0.0 && summary.head.is_some());
}

/// The same balance with the servo driving the hub (its torque from the motor through the drive
/// train, the hub free): the actuator holds arm and head at rest at the start and lifts them.
#[test]
fn under_a_servo_the_head_keeps_the_root_moment_balance() {
    let servo = "[actuator]\nkind = \"servo\"\ncontroller = { kp = 2.0e6, ki = 2.0e6, kd = 5.0e5 }\n\n[contact]";
    let model = edited_head_scenario("servo", |text| {
        text.replace("[contact]", servo).replace("step_s = 0.003", "step_s = 0.002")
    })
    .unwrap();
    let case = "tilting_head.toml under the servo (hub free, held at rest by the motor at the start): root moment at \
                every step";
    let summary = assert_root_moment_balance(&model, case, "hub torque");
    let head = summary.head.as_ref().unwrap();
    assert!(head.max_angle_deg - head.min_angle_deg > 5.0, "the head swung: {head:?}");
}

/// A driven head below a rigid arm held still follows its profile exactly; its drive gives
/// J_h ψ̈ + m g d cos ψ (the head's centre a lever d beyond the hinge, along the arm at ψ = 0).
#[test]
fn a_driven_head_on_a_still_arm_takes_the_torque_of_a_driven_rigid_body() {
    let (m, d, j, g) = (50.0, 0.3, 2.0, 9.80665);
    let mut robot = load(head_robot("driven", "revolute", r#"<pipearm:hinge kind="driven"/>"#, 4.0, [d, 0.0], m, j));
    let limit = pipearm::drive::TrapezoidLimit::AccelRadS2(1.0);
    let profile = MotionProfile::trapezoidal(0.0, 0.8, 2.0, limit).unwrap();
    robot.head.as_mut().unwrap().law = pipearm::robot::HingeLaw::Driven { profile: Some(profile.clone()) };
    let arm = arm(&robot, Fidelity::Rigid, g);
    let mut sim = ArmSimulation::new(arm, HubDrive::Prescribed(MotionProfile::hold(0.0)), IntegratorKind::Rk4).unwrap();
    let (mut worst, mut peak, mut off_profile) = (0.0_f64, 0.0_f64, 0.0_f64);
    while sim.time_s() < 2.5 {
        sim.step(1e-3).unwrap();
        let want = profile.sample(sim.time_s());
        off_profile = off_profile.max((sim.head_state().unwrap().angle_rad - want.angle_rad).abs());
        let exact = (j + m * d * d) * want.accel_rad_s2 + m * g * d * want.angle_rad.cos();
        worst = worst.max((sim.head_drive_torque_n_m().unwrap() - exact).abs());
        peak = peak.max(exact.abs());
    }
    common::validated_row(
        &TILTING_HEAD,
        "head driven 0 → 0.8 rad in 2 s (trapezoidal) on a rigid arm held still: its drive's torque",
        "(J + m d²) ψ̈ + m g d cos ψ",
        &format!("worst {worst:.2e} N·m of a peak {peak:.1} N·m"),
        &common::relative(worst / peak),
        "< 1e-9",
    );
    assert_eq!(off_profile, 0.0, "a driven head follows its profile");
    assert!(worst < 1e-9 * peak, "worst {worst} N·m against a peak of {peak}");
}

/// The shipped lift with the head driven through a tilt of its own: the root moment balance of
/// Newton–Euler against Lagrange holds with the wrist drive's reaction on the arm.
#[test]
fn a_driven_head_keeps_the_root_moment_balance_through_a_lift() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let urdf = std::fs::read_to_string(root.join("robots/pipe_arm_head.urdf")).unwrap();
    let driven = urdf.replace(
        r#"<pipearm:hinge kind="spring" stiffness_n_m_per_rad="3000" damping_n_m_s_per_rad="30"/>"#,
        r#"<pipearm:hinge kind="driven"/>"#,
    );
    let tag = std::process::id();
    let robot = root.join(format!("robots/.head-driven-{tag}.urdf"));
    std::fs::write(&robot, driven).unwrap();
    let text = std::fs::read_to_string(root.join("scenarios/tilting_head.toml")).unwrap();
    let head = "[head]\ndrive = { kind = \"trapezoidal\", start_deg = 0.0, end_deg = 30.0, duration_s = 12.0, ramp_fraction = 0.2 }\n\n[contact]";
    let scenario = text.replace("pipe_arm_head.urdf", &format!(".head-driven-{tag}.urdf")).replace("[contact]", head);
    let path = root.join(format!("scenarios/.head-driven-{tag}.toml"));
    std::fs::write(&path, &scenario).unwrap();
    let model = pipearm::scenario::Scenario::load(&path);
    // Without its drive the driven hinge is refused by key; a bad value in it is named there.
    std::fs::write(&path, scenario.replace(head, "[contact]")).unwrap();
    let missing = pipearm::scenario::Scenario::load(&path).err().map(|e| e.to_string());
    std::fs::write(&path, scenario.replace("duration_s = 12.0,", "duration_s = -1.0,")).unwrap();
    let negative = pipearm::scenario::Scenario::load(&path).err().map(|e| e.to_string());
    std::fs::remove_file(&path).ok();
    std::fs::remove_file(&robot).ok();
    let missing = missing.expect("a driven hinge without its drive loaded");
    assert!(missing.contains("head.drive") && missing.contains("missing"), "{missing}");
    let negative = negative.expect("a negative head drive loaded");
    assert!(negative.contains("head.drive.duration_s"), "{negative}");
    let case = "tilting_head.toml with the head driven 0 → 30° (trapezoidal, 12 s) during the lift: root moment at \
                every step";
    let summary = assert_root_moment_balance(&model.unwrap().model, case, "drive torque");
    let head = summary.head.as_ref().unwrap();
    assert!((head.max_angle_deg - 30.0).abs() < 1e-9, "the head ends at its profile's 30°: {head:?}");
    assert!(head.peak_drive_torque_n_m.unwrap() > 300.0, "{head:?}");
}
