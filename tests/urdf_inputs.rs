//! Malformed robot descriptions fail with the file, the key and what is allowed — never a
//! panic — and a failed `pipearm run` writes nothing.

use std::path::{Path, PathBuf};

use pipearm::robot::load_robot;

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The full-scale robot with `edit` applied, written to a temporary file.
fn edited_robot(tag: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let text = std::fs::read_to_string(manifest().join("robots/pipe_arm.urdf")).unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-urdf-{tag}-{}.urdf", std::process::id()));
    let edited = edit(text.clone());
    assert_ne!(edited, text, "{tag}: the edit changed nothing");
    std::fs::write(&path, edited).unwrap();
    path
}

fn robot_error(tag: &str, edit: impl Fn(String) -> String) -> String {
    let path = edited_robot(tag, edit);
    let result = load_robot(&path);
    std::fs::remove_file(&path).ok();
    let message = result.err().unwrap_or_else(|| panic!("{tag}: the edited robot loaded")).to_string();
    assert!(message.contains(&path.display().to_string()), "{tag}: error does not name the file: {message}");
    message
}

#[test]
fn the_shipped_robots_load() {
    for name in ["pipe_arm", "pipe_arm_twin", "pipe_arm_head", "lab_arm1", "lab_arm2", "lab_arm3", "spin_up_beam"] {
        let robot = load_robot(&manifest().join(format!("robots/{name}.urdf"))).unwrap();
        assert!(robot.arm.length_m() > 0.0);
    }
    let robot = load_robot(&manifest().join("robots/pipe_arm.urdf")).unwrap();
    let hand = robot.body("hand").unwrap();
    assert_eq!((hand.station_m, hand.mass_kg, hand.rotary_inertia_kg_m2), (6.0, 180.0, 15.0));
    let jaws: f64 = robot.carried.iter().filter(|b| b.name.starts_with("jaw")).map(|b| b.mass_kg).sum();
    assert_eq!(jaws, 24.0);
    // The lift joint's limit, as the file states it: effort 400000 N·m, velocity 0.3 rad/s.
    assert_eq!((robot.lift.effort_n_m, robot.lift.velocity_rad_s), (400000.0, 0.3));
    // A section written in the snake_case of older files is the same arm.
    let old = edited_robot("snake-section", |t| t.replace("hollow-rectangle", "hollow_rectangle"));
    let old_robot = load_robot(&old).unwrap();
    std::fs::remove_file(&old).ok();
    assert_eq!(old_robot.arm, robot.arm);
    // Two cylinders on one valve, in the file's order.
    let twin = load_robot(&manifest().join("robots/pipe_arm_twin.urdf")).unwrap().lift.cylinders.unwrap();
    assert_eq!(twin.feed, pipearm::actuator::ValveFeed::Shared);
    assert_eq!(twin.each.iter().map(|c| c.arm_pin_m).collect::<Vec<_>>(), [[2.0, -0.7], [2.4, -0.84]]);
}

/// The full-scale arm's cylinder and servo, as sized in robots/README.md ("Drives"): checked
/// against what they must do, not against the numbers in the file.
#[test]
fn the_full_scale_arm_carries_a_cylinder_and_a_servo_that_can_lift_it() {
    let robot = load_robot(&manifest().join("robots/pipe_arm.urdf")).unwrap();
    let cylinder = robot.lift.cylinders.expect("<pipearm:cylinder> on joint lift").each[0];
    let servo = robot.lift.servo.expect("<pipearm:servo> on joint lift");
    // Over the lift (0..90 deg) the cylinder keeps a lever of 0.3 m at least, and over the
    // joint's whole range it stays inside its stroke.
    for i in 0..=900 {
        let theta = (i as f64 / 10.0).to_radians();
        let (_, arm) = cylinder.length_and_arm(theta);
        assert!(arm >= 0.3, "moment arm {arm} m at {} deg", i as f64 / 10.0);
    }
    let (lo, hi) = robot.lift.limits_rad;
    for i in 0..=1000 {
        let (length, _) = cylinder.length_and_arm(lo + (hi - lo) * i as f64 / 1000.0);
        let extension = length - cylinder.closed_length_m;
        assert!(extension > 0.0 && extension < cylinder.stroke_m, "extension {extension} m of {}", cylinder.stroke_m);
    }
    // The base pin sits in the base's 1.2 m box (centred 0.6 m below the pivot).
    let [bx, by] = cylinder.base_pin_m;
    assert!(bx.abs() <= 0.6 && (-1.2..=0.0).contains(&by), "base pin {:?}", cylinder.base_pin_m);
    // Gravity moment of the arm with the 4-1/2 in string (200 kg at the gripper, 9 m) held
    // horizontal, summed by hand from the URDF: box 0.018125 m² x 7850 kg/m³ x 9 m at 4.5 m,
    // hand 180 kg at 6.0 m, palm 96 kg and jaws 24 kg at 9 m.
    let moment = 9.80665 * (0.018125 * 7850.0 * 9.0 * 4.5 + 180.0 * 6.0 + 120.0 * 9.0 + 200.2 * 9.0);
    // A 21 MPa supply holds it with the cap side below supply, the rod side above tank, each
    // with a fifth of the supply in hand: p1 A1 - p2 A2 = F, p1 + p2 = ps (tank at 0).
    let force = moment / cylinder.length_and_arm(0.0).1;
    let (a1, a2) = (cylinder.cap_area_m2(), cylinder.rod_area_m2());
    let p1 = (force + a2 * 21e6) / (a1 + a2);
    assert!(p1 < 0.8 * 21e6 && 21e6 - p1 > 0.2 * 21e6, "p1 {p1} Pa for {force} N");
    // The servo lifts it with half as much again and turns the joint at its velocity limit.
    assert!(servo.hub_torque_limit_n_m() >= 1.5 * moment, "{} N·m", servo.hub_torque_limit_n_m());
    assert!(servo.hub_speed_limit_rad_s() >= robot.lift.velocity_rad_s, "{} rad/s", servo.hub_speed_limit_rad_s());
}

#[test]
fn malformed_lift_machines_are_named() {
    type Edit = Box<dyn Fn(String) -> String>;
    let cylinder = "joint[lift].pipearm:cylinder";
    let servo = "joint[lift].pipearm:servo";
    let cases: Vec<(&str, Edit, Vec<String>)> = vec![
        (
            "negative-volume",
            Box::new(|t: String| t.replace("cap_dead_volume_m3=\"1.65e-3\"", "cap_dead_volume_m3=\"-1.65e-3\"")),
            vec![format!("{cylinder}@cap_dead_volume_m3"), "allowed > 0".into()],
        ),
        (
            "zero-volume",
            Box::new(|t: String| t.replace("rod_dead_volume_m3=\"1.45e-3\"", "rod_dead_volume_m3=\"0\"")),
            vec![format!("{cylinder}@rod_dead_volume_m3"), "allowed > 0".into()],
        ),
        (
            "rod-as-bore",
            Box::new(|t: String| t.replace("rod_m=\"0.100\"", "rod_m=\"0.180\"")),
            vec![format!("{cylinder}@rod_m"), "rod_m < bore_m".into()],
        ),
        (
            "stroke-longer-than-closed",
            Box::new(|t: String| t.replace("stroke_m=\"1.00\"", "stroke_m=\"1.60\"")),
            vec![format!("{cylinder}@closed_length_m"), "closed_length_m > stroke_m".into()],
        ),
        (
            "pin-of-three",
            Box::new(|t: String| t.replace("base_pin_m=\"0.40 -0.50\"", "base_pin_m=\"0.40 -0.50 0\"")),
            vec![format!("{cylinder}@base_pin_m"), "two numbers".into()],
        ),
        (
            "cylinder-typo",
            Box::new(|t: String| t.replace("bore_m=", "bore_mm=")),
            vec![format!("{cylinder}@bore_mm"), "unknown attribute".into(), "bore_m".into()],
        ),
        (
            "missing-stroke",
            Box::new(|t: String| t.replace("stroke_m=\"1.00\"", "")),
            vec![format!("{cylinder}@stroke_m"), "missing".into()],
        ),
        (
            "no-damping",
            Box::new(|t: String| t.replace("damping_n_m_s_per_rad=\"5.0e4\"", "damping_n_m_s_per_rad=\"-1\"")),
            vec![format!("{servo}@damping_n_m_s_per_rad"), "allowed >= 0".into()],
        ),
        (
            "zero-ratio",
            Box::new(|t: String| t.replace("gear_ratio=\"1000\"", "gear_ratio=\"0\"")),
            vec![format!("{servo}@gear_ratio"), "allowed > 0".into()],
        ),
        (
            "nan-inertia",
            Box::new(|t: String| t.replace("rotor_inertia_kg_m2=\"0.025\"", "rotor_inertia_kg_m2=\"NaN\"")),
            vec![format!("{servo}@rotor_inertia_kg_m2"), "not a finite number".into()],
        ),
        (
            "twice",
            Box::new(|t: String| {
                let a = t.find("<pipearm:servo ").unwrap();
                let b = a + t[a..].find("/>").unwrap() + 2;
                format!("{}{}{}", &t[..b], &t[a..b], &t[b..])
            }),
            vec![servo.into(), "given twice".into()],
        ),
        (
            "valves-disagree",
            Box::new(|t: String| {
                let a = t.find("<pipearm:cylinder ").unwrap();
                let b = a + t[a..].find("/>").unwrap();
                let second = t[a..b].replace("arm_pin_m=\"2.00 -0.70\"", "arm_pin_m=\"2.20 -0.70\"");
                format!(
                    "{}{} valve=\"own\"/>{}{} valve=\"shared\"/>{}",
                    &t[..a],
                    &t[a..b],
                    "\n    ",
                    second,
                    &t[b + 2..]
                )
            }),
            vec![
                format!("{cylinder}[2]@valve"),
                "\"shared\" where the first".into(),
                "\"own\" (one valve each)".into(),
            ],
        ),
        (
            "valve-typo",
            Box::new(|t: String| {
                t.replace("rod_dead_volume_m3=\"1.45e-3\"", "rod_dead_volume_m3=\"1.45e-3\" valve=\"each\"")
            }),
            vec![format!("{cylinder}@valve"), "\"each\"".into(), "\"shared\"".into(), "\"own\"".into()],
        ),
        (
            "unknown-element",
            Box::new(|t: String| t.replace("<pipearm:servo ", "<pipearm:motor ")),
            vec!["joint[lift]".into(), "<pipearm:motor>".into(), "<pipearm:servo>".into()],
        ),
    ];
    for (tag, edit, needles) in cases {
        let m = robot_error(tag, edit);
        for needle in needles {
            assert!(m.contains(&needle), "{tag}: `{needle}` missing from: {m}");
        }
    }
}

#[test]
fn malformed_urdf_is_named() {
    type Edit = Box<dyn Fn(String) -> String>;
    let cases: Vec<(&str, Edit, &[&str])> = vec![
        ("truncated", Box::new(|t: String| t[..t.len() / 2].to_string()), &["not"]),
        (
            "no-params",
            Box::new(|t: String| {
                let a = t.find("<pipearm:flexible elements").unwrap();
                let b = t.find("</pipearm:flexible>").unwrap() + "</pipearm:flexible>".len();
                format!("{}{}", &t[..a], &t[b..])
            }),
            &["link[arm].pipearm:flexible", "no <pipearm:flexible>"],
        ),
        ("unmarked", Box::new(|t: String| t.replace(" pipearm:flexible=\"true\"", "")), &["link[arm]", "not marked"]),
        (
            "no-modulus",
            Box::new(|t: String| t.replace("youngs_modulus_pa=\"2.06e11\" ", "")),
            &["youngs_modulus_pa", "missing"],
        ),
        (
            "negative-density",
            Box::new(|t: String| t.replace("density_kg_m3=\"7850\"", "density_kg_m3=\"-7850\"")),
            &["density_kg_m3"],
        ),
        (
            "typo",
            Box::new(|t: String| t.replace("wall_m=\"0.0125\"", "wal_m=\"0.0125\"")),
            &["wal_m", "unknown attribute", "wall_m"],
        ),
        (
            "section-kind",
            Box::new(|t: String| t.replace("section=\"hollow-rectangle\"", "section=\"i_beam\"")),
            &["i_beam", "solid-circle"],
        ),
        ("thick-wall", Box::new(|t: String| t.replace("wall_m=\"0.0125\"", "wall_m=\"0.2\"")), &["wall_m", "0.125"]),
        (
            "axis",
            Box::new(|t: String| t.replacen("<axis xyz=\"0 0 1\"/>", "<axis xyz=\"1 0 0\"/>", 1)),
            &["joint[lift].axis"],
        ),
        (
            "negative-mass",
            Box::new(|t: String| t.replace("<mass value=\"180\"/>", "<mass value=\"-180\"/>")),
            &["link[hand].inertial.mass"],
        ),
        (
            "off-arm",
            Box::new(|t: String| t.replace("<origin xyz=\"6.0 0 0\"", "<origin xyz=\"12.2 0 0\"")),
            &["link[hand]", "off the arm"],
        ),
        (
            "namespace",
            Box::new(|t: String| t.replace(" xmlns:pipearm=\"https://pipearm.dev/urdf/1\"", "")),
            &["Unbound namespace prefix"],
        ),
        ("elements", Box::new(|t: String| t.replace("elements=\"24\"", "elements=\"0\"")), &["elements", "1 ..= 2000"]),
        (
            "jaw-travel",
            Box::new(|t: String| t.replacen("lower=\"-0.05\" upper=\"0.05\"", "lower=\"0.05\" upper=\"0.05\"", 1)),
            &["joint[jaw_upper].limit", "lower < upper"],
        ),
        (
            "damping",
            Box::new(|t: String| t.replace("damping_ratios=\"0.01\"", "damping_ratios=\"abc\"")),
            &["damping_ratios", "not a list"],
        ),
        (
            "mesh",
            Box::new(|t: String| t.replace("<box size=\"0.6 0.5 0.5\"/>", "<mesh filename=\"hand.stl\"/>")),
            &["link[hand].collision", "box, cylinder, sphere"],
        ),
        (
            "joint-type",
            Box::new(|t: String| t.replace("name=\"wrist\" type=\"fixed\"", "name=\"wrist\" type=\"revolute\"")),
            &["joint[wrist].pipearm:hinge", "missing", "kind=\"locked\""],
        ),
        (
            "limits",
            Box::new(|t: String| t.replace("lower=\"-0.05\" upper=\"1.62\"", "lower=\"1.62\" upper=\"-0.05\"")),
            &["joint[lift].limit"],
        ),
        (
            "velocity",
            Box::new(|t: String| t.replace("effort=\"400000\" velocity=\"0.3\"", "effort=\"400000\" velocity=\"0\"")),
            &["joint[lift].limit", "velocity = 0", "velocity > 0 (rad/s)"],
        ),
        (
            "no-velocity",
            Box::new(|t: String| t.replace("effort=\"400000\" velocity=\"0.3\"", "effort=\"400000\"")),
            &["not valid URDF"],
        ),
    ];
    for (tag, edit, needles) in cases {
        let m = robot_error(tag, edit);
        for needle in needles {
            assert!(m.contains(needle), "{tag}: `{needle}` missing from: {m}");
        }
    }
}

#[test]
fn a_failed_run_writes_nothing() {
    let out = std::env::temp_dir().join(format!("pipearm-out-{}", std::process::id()));
    let bad = manifest().join(format!("scenarios/.bad-cli-{}.toml", std::process::id()));
    let text = std::fs::read_to_string(manifest().join("scenarios/default.toml")).unwrap();
    std::fs::write(&bad, text.replace("gap_m = 0.0002", "gap_m = -1.0")).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["run", bad.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    std::fs::remove_file(&bad).ok();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("dampeners[0].gap_m") && stderr.contains(".bad-cli"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists(), "a failed run created {}", out.display());
}

/// `pipearm run | head`: the reader gone before the first line ends the run by SIGPIPE, as for
/// any Unix tool, not by a panic on the closed pipe.
#[cfg(unix)]
#[test]
fn a_closed_stdout_ends_a_run_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["run", "--no-record"])
        .current_dir(manifest())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(output.status.signal(), Some(libc::SIGPIPE), "{:?}: {stderr}", output.status);
}
