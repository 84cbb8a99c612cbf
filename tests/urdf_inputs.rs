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
    for name in ["pipe_arm", "lab_arm1", "lab_arm2", "lab_arm3", "spin_up_beam"] {
        let robot = load_robot(&manifest().join(format!("robots/{name}.urdf"))).unwrap();
        assert!(robot.arm.length_m() > 0.0);
    }
    let robot = load_robot(&manifest().join("robots/pipe_arm.urdf")).unwrap();
    let hand = robot.body("hand").unwrap();
    assert_eq!((hand.station_m, hand.mass_kg, hand.rotary_inertia_kg_m2), (8.2, 180.0, 15.0));
    let jaws: f64 = robot.carried.iter().filter(|b| b.name.starts_with("jaw")).map(|b| b.mass_kg).sum();
    assert_eq!(jaws, 24.0);
    // The lift joint's limit, as the file states it: effort 400000 N·m, velocity 0.3 rad/s.
    assert_eq!((robot.lift.effort_n_m, robot.lift.velocity_rad_s), (400000.0, 0.3));
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
            Box::new(|t: String| t.replace("section=\"hollow_rectangle\"", "section=\"i_beam\"")),
            &["i_beam", "solid_circle"],
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
            Box::new(|t: String| t.replace("<origin xyz=\"8.2 0 0\"", "<origin xyz=\"12.2 0 0\"")),
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
            &["joint[wrist]", "fixed or prismatic"],
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
