//! Bad input fails with a typed error that names the parameter (and, for files, the file and
//! the key), never a panic.

mod common;

use std::path::{Path, PathBuf};

use common::uniform;
use pipearm::arm::{ArmError, ArmModel, ArmOptions, Fidelity};
use pipearm::beam::{BeamError, BeamModel, Material, SectionShape, Segment};
use pipearm::scenario::Scenario;

fn named(err: &BeamError) -> &str {
    match err {
        BeamError::InvalidParameter { name, .. } => name,
        other => panic!("expected InvalidParameter, got {other}"),
    }
}

#[test]
fn beam_parameters_out_of_range_are_named() {
    let mut spec = uniform(0.0, 1.0, 1.0, 10);
    assert_eq!(named(&BeamModel::new(spec.clone()).unwrap_err()), "length_m");
    spec.segments[0].length_m = -2.0;
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "length_m");
    let mut spec = uniform(1.0, 1.0, 1.0, 10);
    spec.segments[0].mass_per_length_kg_m = 0.0;
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "mass_per_length_kg_m");
    let spec = uniform(1.0, 1.0, 1.0, 0);
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "elements");
    let shape = SectionShape::SolidCircle { diameter_m: 0.1 };
    let e =
        Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: -2e11, density_kg_m3: 7850.0 }).unwrap_err();
    assert_eq!(named(&e), "youngs_modulus_pa");
    let e = Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: 2e11, density_kg_m3: 0.0 }).unwrap_err();
    assert_eq!(named(&e), "density_kg_m3");
    let e =
        Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: f64::NAN, density_kg_m3: 1.0 }).unwrap_err();
    assert_eq!(named(&e), "youngs_modulus_pa");
}

#[test]
fn masses_outside_the_arm_are_named() {
    let spec = uniform(2.0, 1.0, 1.0, 10).with_mass("gripper", 2.5, 10.0, 0.0);
    let e = BeamModel::new(spec).unwrap_err();
    assert_eq!(named(&e), "masses.gripper.position_m");
    assert!(e.to_string().contains("0 ..= 2"), "{e}");
    let spec = uniform(2.0, 1.0, 1.0, 10).with_mass("hand", 1.0, -3.0, 0.0);
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "masses.hand.mass_kg");
}

#[test]
fn more_modes_than_dofs_is_refused() {
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    let dofs = beam.dofs();
    let e = ArmModel::new(beam, Fidelity::Modal { modes: dofs + 1 }, ArmOptions::default()).unwrap_err();
    match &e {
        ArmError::InvalidParameter { name, .. } => assert_eq!(name, "model.modes"),
        other => panic!("unexpected {other}"),
    }
    assert!(e.to_string().contains(&format!("1 ..= {dofs}")), "{e}");
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    assert!(ArmModel::new(beam, Fidelity::Modal { modes: 0 }, ArmOptions::default()).is_err());
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    let options = ArmOptions { damping_ratios: vec![-0.1], ..ArmOptions::default() };
    assert!(matches!(ArmModel::new(beam, Fidelity::Fe, options), Err(ArmError::InvalidParameter { .. })));
}

/// Writes the default scenario with `edit` applied to a temporary file beside it (so that its
/// relative robot path still resolves).
fn edited_default(tag: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let text = std::fs::read_to_string(dir.join("default.toml")).unwrap();
    let path = dir.join(format!(".bad-{tag}-{}.toml", std::process::id()));
    std::fs::write(&path, edit(text)).unwrap();
    path
}

fn load_error(tag: &str, edit: impl Fn(String) -> String) -> String {
    let path = edited_default(tag, edit);
    let result = Scenario::load(&path);
    std::fs::remove_file(&path).ok();
    let message = match result {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{tag}: the edited scenario loaded"),
    };
    assert!(message.contains(&path.display().to_string()), "error does not name the file: {message}");
    message
}

#[test]
fn scenario_errors_name_file_key_and_range() {
    let m = load_error("unknown", |t| t.replace("step_s = 0.003", "step_s = 0.003\nstep_count = 3"));
    assert!(m.contains("step_count"), "{m}");
    let m = load_error("missing", |t| t.replace("step_s = 0.003\n", ""));
    assert!(m.contains("step_s"), "{m}");
    let m = load_error("negative-step", |t| t.replace("step_s = 0.003", "step_s = -0.003"));
    assert!(m.contains("time.step_s") && m.contains("0 < step_s"), "{m}");
    let m = load_error("accel", |t| t.replace("ramp_fraction = 0.2", "ramp_fraction = 0.9"));
    assert!(m.contains("drive.ramp_fraction"), "{m}");
    let m = load_error("both-limits", |t| t.replace("ramp_fraction = 0.2", "ramp_fraction = 0.2\naccel_deg_s2 = 3.0"));
    assert!(m.contains("drive.limit") && m.contains("exactly one"), "{m}");
    let generalized_alpha = |rho: &str| format!("kind = \"generalized-alpha\"\nrho_inf = {rho}");
    let m = load_error("integrator", |t| t.replace("kind = \"rk4\"", &generalized_alpha("1.5")));
    assert!(m.contains("integrator") && m.contains("rho_inf"), "{m}");
    // Controlled free steps: a tolerance needs a free step, a free step an implicit method.
    let m = load_error("tolerance", |t| t.replace("step_s = 0.003", "step_s = 0.003\ntolerance_m = 1e-6"));
    assert!(m.contains("time.tolerance_m") && m.contains("free_step_s"), "{m}");
    let m = load_error("free-explicit", |t| t.replace("step_s = 0.003", "step_s = 0.003\nfree_step_s = 0.01"));
    assert!(m.contains("time.free_step_s") && m.contains("implicit"), "{m}");
    let m = load_error("bad-tolerance", |t| {
        t.replace("kind = \"rk4\"", &generalized_alpha("0.8"))
            .replace("step_s = 0.003", "step_s = 0.003\nfree_step_s = 0.01\ntolerance_m = -1.0")
    });
    assert!(m.contains("time.tolerance_m") && m.contains("0 < tolerance_m"), "{m}");
    for bad in ["0.0", "-0.01", "1.0"] {
        let m = load_error("model-tolerance", |t| {
            t.replace("kind = \"auto\"", &format!("kind = \"auto\"\ntolerance = {bad}"))
        });
        assert!(m.contains("model.tolerance") && m.contains("0 < tolerance < 1") && m.contains(".toml"), "{m}");
    }
    let m = load_error("modes", |t| t.replace("kind = \"auto\"", "kind = \"modal\"\nmodes = 500"));
    assert!(m.contains("model.modes") && m.contains("1 ..= 72"), "{m}");
    let m = load_error("beyond-limit", |t| t.replace("end_deg = 90.0", "end_deg = 120.0"));
    assert!(m.contains("drive.end_deg") && m.contains("limits"), "{m}");
    let m = load_error("pipe", |t| t.replace("size = \"2-7/8\"", "size = \"2-1/2\""));
    assert!(m.contains("payload.size") && m.contains("2-3/8"), "{m}");
    let m = load_error("pad-station", |t| t.replace("station_m = 8.2", "station_m = 12.0"));
    assert!(m.contains("dampeners[0].station_m") && m.contains("0 ..= 9"), "{m}");
    let m = load_error("pad-law", |t| t.replace("restitution = 0.6", "restitution = 1.6"));
    assert!(m.contains("dampeners[0].law.restitution") && m.contains("0 < e <= 1"), "{m}");
    let m = load_error("pad-gap", |t| t.replace("gap_m = 0.0002", "gap_m = -0.001"));
    assert!(m.contains("dampeners[0].gap_m"), "{m}");
    let m = load_error("damping", |t| format!("{t}\n[arm]\ndamping_ratios = [0.01, -0.1]\n"));
    assert!(m.contains("arm.damping_ratios[1]") && m.contains("0 <= ratio < 2"), "{m}");
    let m = load_error("law-kind", |t| t.replace("kind = \"hunt-crossley\"", "kind = \"hertz\""));
    assert!(m.contains("hertz") && m.contains("hunt-crossley"), "{m}");
    let m = load_error("robot-missing", |t| t.replace("pipe_arm.urdf", "no_such_arm.urdf"));
    assert!(m.contains("no_such_arm.urdf") && m.contains("cannot read"), "{m}");
    let m = load_error("block", |t| {
        let grips = t.lines().find(|l| l.starts_with("grips = ")).unwrap_or_default().to_string();
        t.replace(&format!("kind = \"string\"\nsize = \"2-7/8\"\n{grips}"), "kind = \"block\"\nblock = 4")
    });
    assert!(m.contains("payload.block") && m.contains("1, 2, 3"), "{m}");
}

/// A hydraulic `[actuator]` table for the full-scale arm (plausible values; the checks are
/// what these tests exercise).
const HYDRAULIC: &str = "
[actuator]
kind = \"hydraulic\"
supply_pressure_pa = 21e6
tank_pressure_pa = 0.5e6
bulk_modulus_pa = 1.2e9
relief_pressure_pa = 23e6
valve = { rated_flow_m3_s = 2.5e-3, rated_pressure_drop_pa = 3.5e6, spool_time_constant_s = 0.015 }
controller = { kp = 5.0, velocity_feedforward = 1.0 }
";

/// A servo `[actuator]` table.
const SERVO: &str = "
[actuator]
kind = \"servo\"
controller = { kp = 2e7, kd = 1e6, velocity_feedforward = 0.0 }
";

/// `pipearm run` on the default scenario with `edit` applied, beside the full-scale robot with
/// `robot_edit` applied, in a fresh folder: it must fail naming the scenario file, without a
/// panic, and write nothing. Returns its error output.
fn refused_run(tag: &str, edit: impl Fn(String) -> String, robot_edit: impl Fn(String) -> String) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("pipearm-bad-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let robot = std::fs::read_to_string(root.join("robots/pipe_arm.urdf")).unwrap();
    std::fs::write(dir.join("arm.urdf"), robot_edit(robot)).unwrap();
    let scenario = std::fs::read_to_string(root.join("scenarios/default.toml")).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(&path, edit(scenario.replace("../robots/pipe_arm.urdf", "arm.urdf"))).unwrap();
    let out = dir.join("out");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["run", path.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    let wrote = out.exists();
    std::fs::remove_dir_all(&dir).ok();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(!output.status.success(), "{tag}: the run succeeded");
    assert!(!wrote, "{tag}: a refused run wrote {}", out.display());
    assert!(!stderr.contains("panicked"), "{tag}: {stderr}");
    assert!(stderr.contains(&path.display().to_string()), "{tag}: the error does not name the file: {stderr}");
    stderr
}

/// Appends `table` to the scenario.
fn with(table: impl Into<String>) -> impl Fn(String) -> String {
    let table = table.into();
    move |t| t + &table
}

fn same(t: String) -> String {
    t
}

#[test]
fn actuator_tables_are_checked_naming_the_key() {
    let m = refused_run("kind", with("\n[actuator]\nkind = \"pneumatic\"\n"), same);
    assert!(m.contains("pneumatic") && m.contains("`ideal`, `servo`, `hydraulic`"), "{m}");
    let m = refused_run("typo", with(HYDRAULIC.replace("supply_pressure_pa", "supply_presure_pa")), same);
    assert!(m.contains("supply_presure_pa") && m.contains("[actuator]"), "{m}");
    let m = refused_run("bulk", with(HYDRAULIC.replace("bulk_modulus_pa = 1.2e9", "bulk_modulus_pa = 0")), same);
    assert!(m.contains("key `actuator.bulk_modulus_pa`") && m.contains("bulk_modulus_pa > 0"), "{m}");
    let m = refused_run("tank", with(HYDRAULIC.replace("tank_pressure_pa = 0.5e6", "tank_pressure_pa = 22e6")), same);
    assert!(m.contains("key `actuator.supply_pressure_pa`") && m.contains("> tank_pressure_pa"), "{m}");
    let m =
        refused_run("relief", with(HYDRAULIC.replace("relief_pressure_pa = 23e6", "relief_pressure_pa = 20e6")), same);
    assert!(m.contains("key `actuator.relief_pressure_pa`") && m.contains("> supply_pressure_pa"), "{m}");
    let m = refused_run(
        "spool",
        with(HYDRAULIC.replace("spool_time_constant_s = 0.015", "spool_time_constant_s = -0.01")),
        same,
    );
    assert!(m.contains("key `actuator.valve.spool_time_constant_s`"), "{m}");
    let leaky = "spool_time_constant_s = 0.015, leakage_m3_s_per_pa = -1e-11";
    let m = refused_run("leakage", with(HYDRAULIC.replace("spool_time_constant_s = 0.015", leaky)), same);
    assert!(m.contains("key `actuator.valve.leakage_m3_s_per_pa`") && m.contains(">= 0"), "{m}");
    let m = refused_run("kp", with(SERVO.replace("kp = 2e7", "kp = 0")), same);
    assert!(m.contains("key `actuator.controller.kp`") && m.contains("kp > 0"), "{m}");
    let m = refused_run("kd", with(SERVO.replace("kd = 1e6", "kd = -1e6")), same);
    assert!(m.contains("key `actuator.controller.kd`") && m.contains("kd >= 0"), "{m}");
    // The default scene steps every 3 ms: a controller cannot sample faster than that.
    let m = refused_run("rate", with(SERVO.replace("kd = 1e6", "kd = 1e6, rate_hz = 1000.0")), same);
    assert!(m.contains("key `actuator.controller.rate_hz`") && m.contains("time.step_s = 0.003"), "{m}");
    let m = refused_run(
        "free-step",
        |t| {
            t.replace("kind = \"rk4\"", "kind = \"generalized-alpha\"\nrho_inf = 0.8")
                .replace("step_s = 0.003", "step_s = 0.003\nfree_step_s = 0.01")
                + HYDRAULIC
        },
        same,
    );
    assert!(m.contains("key `time.free_step_s`") && m.contains("hydraulic"), "{m}");
}

#[test]
fn an_actuator_the_robot_lacks_is_named() {
    let drop = |element: &'static str| {
        move |t: String| {
            let a = t.find(&format!("<pipearm:{element} ")).unwrap();
            let b = a + t[a..].find("/>").unwrap() + 2;
            format!("{}{}", &t[..a], &t[b..])
        }
    };
    let m = refused_run("no-cylinder", with(HYDRAULIC), drop("cylinder"));
    assert!(m.contains("key `actuator.kind`") && m.contains("<pipearm:cylinder>") && m.contains("joint `lift`"), "{m}");
    assert!(m.contains("arm.urdf"), "the error names the robot file: {m}");
    let m = refused_run("no-servo", with(SERVO), drop("servo"));
    assert!(m.contains("key `actuator.kind`") && m.contains("<pipearm:servo>"), "{m}");
}

#[test]
fn a_cylinder_out_of_its_stroke_on_the_path_is_named() {
    // At 0 deg the pins are 1.6125 m apart (robots/README.md): a closed length of 1.65 m is
    // 37.5 mm too long for the lift's start.
    let m = refused_run("too-short", with(HYDRAULIC), |t| {
        t.replace("closed_length_m=\"1.56\" stroke_m=\"1.00\"", "closed_length_m=\"1.65\" stroke_m=\"1.00\"")
    });
    assert!(m.contains("key `actuator.kind`") && m.contains("37.5 mm shorter than its closed length"), "{m}");
    assert!(m.contains("at 0.00 deg") && m.contains("arm.urdf") && m.contains("1.65 ..= 2.65 m"), "{m}");
    // At 90 deg they are 2.5179 m apart: a 0.9 m stroke ends at 2.46 m, 57.9 mm short.
    let m = refused_run("too-long", with(HYDRAULIC), |t| t.replace("stroke_m=\"1.00\"", "stroke_m=\"0.90\""));
    assert!(m.contains("key `actuator.kind`") && m.contains("57.9 mm longer than closed length + stroke"), "{m}");
    assert!(m.contains("at 90.00 deg"), "{m}");
    // Of two cylinders, the second out of its stroke is the one named.
    let m = refused_run("second-too-short", with(HYDRAULIC), |t| {
        let a = t.find("<pipearm:cylinder ").unwrap();
        let b = a + t[a..].find("/>").unwrap() + 2;
        let second = t[a..b].replace("closed_length_m=\"1.56\"", "closed_length_m=\"1.65\"");
        format!("{}\n    {second}{}", &t[..b], &t[b..])
    });
    assert!(m.contains("joint[lift].pipearm:cylinder[2]") && m.contains("37.5 mm shorter"), "{m}");
}

#[test]
fn an_actuator_too_weak_or_too_slow_for_the_drive_is_named() {
    // The default lift peaks at 90 deg / 12 s = 7.5 deg/s = 0.131 rad/s; a motor limited to
    // 100 rad/s behind 1000:1 turns the hub at 0.1 rad/s at most.
    let m =
        refused_run("slow", with(SERVO), |t| t.replace("speed_limit_rad_s=\"314.16\"", "speed_limit_rad_s=\"100\""));
    assert!(m.contains("key `drive.duration_s`") && m.contains("speed_limit_rad_s 100"), "{m}");
    assert!(m.contains("up to 5.730 deg/s"), "{m}");
    // Holding the arm and the 2-7/8 in string level takes 92 kN·m: 206 kN on the cylinder's
    // 0.4465 m lever, more than 5 MPa on its 0.0254 m² cap side can give (127 kN).
    let weak = HYDRAULIC.replace("supply_pressure_pa = 21e6", "supply_pressure_pa = 5e6").replace("23e6", "6e6");
    let m = refused_run("weak", with(weak), same);
    assert!(m.contains("key `actuator.supply_pressure_pa`") && m.contains("outside tank to supply"), "{m}");
    // A motor of 50 N·m behind 1000:1 gives 50 kN·m at the hub.
    let m =
        refused_run("weak-servo", with(SERVO), |t| t.replace("torque_limit_n_m=\"160\"", "torque_limit_n_m=\"50\""));
    assert!(m.contains("key `actuator.kind`") && m.contains("torque_limit_n_m"), "{m}");
}

/// `drive.shaper` and `drive.shaper_hz`: a shaper only on a point-to-point move, a positive
/// frequency, a known name, a lift longer than the shaper.
#[test]
fn shaper_keys_are_checked_naming_the_key() {
    let hold = "kind = \"hold\"\nangle_deg = 0.0\nshaper = \"zv\"\n";
    let m = load_error("shaper-hold", |t| {
        let start = t.find("kind = \"trapezoidal\"").unwrap();
        let end = t.find("ramp_fraction = 0.2\n").unwrap() + "ramp_fraction = 0.2\n".len();
        format!("{}{hold}{}", &t[..start], &t[end..])
    });
    assert!(m.contains("drive.shaper") && m.contains("uniform, trapezoidal and s-curve"), "{m}");
    let shaped = |extra: &'static str| {
        move |t: String| t.replace("ramp_fraction = 0.2", &format!("ramp_fraction = 0.2\n{extra}"))
    };
    let m = load_error("shaper-hz", shaped("shaper = \"zvd\"\nshaper_hz = -1.0"));
    assert!(m.contains("drive.shaper_hz") && m.contains("> 0"), "{m}");
    let m = load_error("shaper-hz-nan", shaped("shaper = \"zvd\"\nshaper_hz = nan"));
    assert!(m.contains("drive.shaper_hz"), "{m}");
    let m = load_error("shaper-name", shaped("shaper = \"zvdd\""));
    assert!(m.contains("zvdd") && m.contains("zvd") && m.contains("ei"), "{m}");
    let m = load_error("shaper-alone", shaped("shaper_hz = 0.5"));
    assert!(m.contains("drive.shaper_hz") && m.contains("drive.shaper"), "{m}");
    // ZVD at 0.05 Hz lasts 20 s, longer than the 15 s lift.
    let m = load_error("shaper-long", shaped("shaper = \"zvd\"\nshaper_hz = 0.05"));
    assert!(m.contains("drive.duration_s") && m.contains("shaper's length"), "{m}");
    // A list: each frequency checked, the damping ratios one for all or one each.
    let m = load_error("shaper-hz-list", shaped("shaper = \"zvd\"\nshaper_hz = [2.85, 0.0]"));
    assert!(m.contains("drive.shaper_hz") && m.contains("> 0"), "{m}");
    let m = load_error("shaper-hz-empty", shaped("shaper = \"zvd\"\nshaper_hz = []"));
    assert!(m.contains("drive.shaper_hz") && m.contains("empty"), "{m}");
    let m = load_error("shaper-hz-text", shaped("shaper = \"zvd\"\nshaper_hz = \"fast\""));
    assert!(m.contains("drive.shaper_hz") && m.contains("a number or a list of numbers"), "{m}");
    let m = load_error(
        "shaper-damping-count",
        shaped("shaper = \"zvd\"\nshaper_hz = [2.85, 5.1]\nshaper_damping_ratio = [0.01, 0.02, 0.03]"),
    );
    assert!(m.contains("drive.shaper_damping_ratio") && m.contains("one per frequency"), "{m}");
    let m = load_error(
        "shaper-damping-range",
        shaped("shaper = \"zvd\"\nshaper_hz = [2.85, 5.1]\nshaper_damping_ratio = 1.0"),
    );
    assert!(m.contains("drive.shaper_damping_ratio") && m.contains("0 <= ratio < 1"), "{m}");
    let m = load_error("shaper-damping-alone", shaped("shaper = \"zvd\"\nshaper_damping_ratio = 0.02"));
    assert!(m.contains("drive.shaper_damping_ratio") && m.contains("drive.shaper_hz"), "{m}");
}

/// A shaper tuned by default finds its modes when the scenario is compiled, and shortens the
/// base move by its length: the joint's velocity limit is checked again on the shaped move,
/// before the run, naming the file and the key, writing nothing.
#[test]
fn a_tuned_shaper_that_speeds_the_move_past_the_joints_limit_is_refused_before_the_run() {
    // 90 deg in 7 s with ramps of a fifth peaks at 16.1 deg/s, inside the joint's 0.3 rad/s
    // (17.2 deg/s); ZVD on the arm's 2.85 and 5.1 Hz modes lasts about 0.55 s, and the base move
    // in the 6.45 s left peaks at 17.4 deg/s.
    let seven = |shaper: &'static str| {
        move |t: String| t.replace("duration_s = 15.0\n", &format!("duration_s = 7.0\n{shaper}"))
    };
    let unshaped = edited_default("tuned-speed-unshaped", seven(""));
    let loaded = Scenario::load(&unshaped);
    std::fs::remove_file(&unshaped).ok();
    assert!(loaded.is_ok(), "{:?}", loaded.err());
    let m = refused_run("tuned-speed", seven("shaper = \"zvd\"\n"), same);
    assert!(m.contains("drive.duration_s") && m.contains("velocity limit") && m.contains("zvd shaper tuned"), "{m}");
}

#[test]
fn grips_off_the_string_beyond_the_arm_or_on_one_another_are_named() {
    let grips = |g: &'static str| {
        move |t: String| {
            let line = t.lines().find(|l| l.starts_with("grips = ")).expect("the default names its grips").to_string();
            t.replace(&line, &format!("grips = {g}"))
        }
    };
    // A grip outside the string.
    let e =
        refused_run("grip-off", grips("[{ hand = \"hand\", at_m = 14.0 }, { hand = \"gripper\", at_m = 17.0 }]"), same);
    assert!(e.contains("payload.grips[0].at_m") && e.contains("0 ..= 12.5"), "{e}");
    // Grips whose spacing along the string is not the hands' along the arm.
    let e = refused_run(
        "grip-spacing",
        grips("[{ hand = \"hand\", at_m = 4.75 }, { hand = \"gripper\", at_m = 9.0 }]"),
        same,
    );
    assert!(e.contains("payload.grips[1].at_m") && e.contains("3.000 m apart"), "{e}");
    // Two grips by one hand: overlapping hands.
    let e = refused_run(
        "grip-twice",
        grips("[{ hand = \"gripper\", at_m = 4.75 }, { hand = \"gripper\", at_m = 7.75 }]"),
        same,
    );
    assert!(e.contains("payload.grips[1].hand") && e.contains("overlaps"), "{e}");
    // A link that is not on the arm.
    let e = refused_run("grip-link", grips("[{ hand = \"base\" }]"), same);
    assert!(e.contains("payload.grips[0].hand") && e.contains("gripper"), "{e}");
    // A hand beyond the arm's 9 m.
    let beyond =
        |r: String| r.replace("<origin xyz=\"6.0 0 0\" rpy=\"0 0 0\"/>", "<origin xyz=\"9.6 0 0\" rpy=\"0 0 0\"/>");
    let e = refused_run("grip-beyond", same, beyond);
    assert!(e.contains("hand") && e.contains("9.6"), "{e}");
    // A friction clamp on a string in two hands, and too many string modes.
    let e =
        refused_run("grip-friction", |t| t.replace("size = \"2-7/8\"", "size = \"2-7/8\"\nclamp = \"friction\""), same);
    assert!(e.contains("payload.grips") && e.contains("one grip"), "{e}");
    let e = refused_run(
        "string-modes",
        |t| t.replace("size = \"2-7/8\"", "size = \"2-7/8\"\nmodel = { kind = \"modal\", modes = 500 }"),
        same,
    );
    assert!(e.contains("payload.model.modes") && e.contains("1 ..="), "{e}");
}

#[test]
fn a_bad_structure_is_named() {
    let guide = |shape: &str, position: &str, law: &str| {
        format!("\n[[structures]]\nname = \"guide\"\nshape = {shape}\nposition_m = {position}\nlaw = {law}\n")
    };
    let (boxed, clear, law) = (
        "{ kind = \"box\", size_m = [0.2, 0.6, 0.3] }",
        "[-0.1335, 2.6, 0.65]",
        "{ kind = \"linear\", stiffness_n_m = 1e7, damping_n_s_m = 0.0 }",
    );
    // An unknown shape.
    let e = refused_run("structure-shape", with(guide("{ kind = \"sphere\", radius_m = 0.2 }", clear, law)), same);
    assert!(e.contains("shape = ") && e.contains("sphere") && e.contains("box") && e.contains("cylinder"), "{e}");
    // A structure inside the arm lying on the catwalk at the drive's start (the arm's box runs
    // along x from the pivot at y = 1.2 m).
    let e = refused_run("structure-inside", with(guide(boxed, "[4.0, 1.2, 0.0]", law)), same);
    assert!(e.contains("structures[0].position_m") && e.contains("overlaps the arm"), "{e}");
    // A law without its parameters.
    let e = refused_run("structure-law", with(guide(boxed, clear, "{ kind = \"linear\", stiffness_n_m = 1e7 }")), same);
    assert!(e.contains("law = ") && e.contains("missing field `damping_n_s_m`"), "{e}");
    // Structures with the rapier method, or with the pad-face path.
    let with_method = |line: &'static str| {
        let structure = guide(boxed, clear, law);
        move |t: String| t.replace("kind = \"compliant\"", line) + &structure
    };
    let e = refused_run("structure-rapier", with_method("kind = \"rapier\""), same);
    assert!(e.contains("key `contact.kind`") && e.contains("[[structures]]"), "{e}");
    let e = refused_run("structure-pad-face", with_method("kind = \"compliant\"\ndetection = \"pad-face\""), same);
    assert!(e.contains("key `contact.detection`") && e.contains("[[structures]]"), "{e}");
    // A negative size.
    let e =
        refused_run("structure-size", with(guide("{ kind = \"box\", size_m = [0.2, -0.6, 0.3] }", clear, law)), same);
    assert!(e.contains("structures[0].shape.size_m") && e.contains("0 < size"), "{e}");
}

#[test]
fn sign_off_keys_are_checked_naming_the_key() {
    let no_yield = |t: String| t.replace(" steel=\"S355\"", "");
    let m = refused_run("checks-no-yield", with("\n[checks]\nstress_factor = 1.0\n"), no_yield);
    assert!(m.contains("`checks`") && m.contains("yield_strength_pa") && m.contains("S355"), "{m}");
    let m = refused_run("checks-factor", with("\n[checks]\nstress_factor = -1.5\n"), same);
    assert!(m.contains("checks.stress_factor") && m.contains("> 0"), "{m}");
    let m = refused_run("detail", same, |t| t.replace("detail=\"71\"", "detail=\"70\""));
    assert!(m.contains("@detail") && m.contains("\"71\"") && m.contains("\"36\""), "{m}");
    let m = refused_run("curve", same, |t| t.replace("detail=\"71\"", "curve=\"dnv-x\""));
    assert!(m.contains("@curve") && m.contains("\"dnv-d\"") && m.contains("\"dnv-w3\""), "{m}");
    let m = refused_run("steel", same, |t| t.replace("steel=\"S355\"", "steel=\"S420\""));
    assert!(m.contains("@steel") && m.contains("S235, S275, S355, S460, S690"), "{m}");
    let m = refused_run("yield-and-steel", same, |t| {
        t.replace("steel=\"S355\"", "steel=\"S355\" yield_strength_pa=\"355e6\"")
    });
    assert!(m.contains("@steel") && m.contains("not both"), "{m}");
}
