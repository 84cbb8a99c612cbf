//! Drives from a table: the spline through a law's samples reproduces that law's runs; bad tables
//! are refused naming the file, the column and the row, with nothing written; a drive faster
//! than the lift joint's URDF velocity is refused, and a torque beyond its effort is flagged.

mod common;

use std::path::{Path, PathBuf};

use pipearm::drive::MotionProfile;
use pipearm::run::{RunSummary, run};
use pipearm::scenario::{DriveSpec, Scenario, ScenarioError};

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn shipped(name: &str) -> Scenario {
    Scenario::load(&manifest().join(format!("scenarios/{name}.toml"))).unwrap()
}

/// A fresh temporary folder for one test.
fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-table-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `profile` sampled every `step_s` over its duration, as a table file's text.
fn table_text(profile: &MotionProfile, step_s: f64) -> String {
    let rows = (profile.duration_s() / step_s).round() as usize;
    let mut text = String::from("t[s],angle[deg]\n");
    for i in 0..=rows {
        let t = i as f64 * step_s;
        text += &format!("{t},{}\n", profile.sample(t).angle_rad.to_degrees());
    }
    text
}

/// `scenario` driven by the table file at `csv` instead of its own drive.
fn driven_by(scenario: &Scenario, csv: &Path, end_rate_deg_s: Option<f64>) -> Result<Scenario, ScenarioError> {
    let mut spec = scenario.spec.clone();
    spec.drive = DriveSpec::Table { file: csv.into(), end_rate_deg_s };
    Scenario::from_spec(&scenario.path, spec)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A table of the shipped S-curve (the lowering onto the rest pad) at 10 ms
/// gives the S-curve run's peak tip deflection within 0.5 % and its peak drive torque within 1 %.
#[test]
fn a_table_of_the_s_curve_reproduces_its_run() {
    let s_curve = shipped("lowering");
    assert_eq!(s_curve.model.drive.motion.name(), "s-curve");
    let dir = temp_dir("s-curve");
    let csv = dir.join("lowering.csv");
    std::fs::write(&csv, table_text(&s_curve.model.drive.motion, 0.01)).unwrap();
    let table = driven_by(&s_curve, &csv, None).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(table.model.drive.motion.name(), "table");
    let (law, _) = run(&s_curve.model, None).unwrap();
    let (from_table, _) = run(&table.model, None).unwrap();
    let deflection = rel(from_table.max_tip_deflection_m, law.max_tip_deflection_m);
    let torque = rel(from_table.peak_drive_torque_n_m, law.peak_drive_torque_n_m);
    println!("lowering from a 10 ms table: tip deflection {deflection:.2e}, drive torque {torque:.2e} relative");
    let case = "lowering.toml driven from a 10 ms table of its own S-curve";
    common::validated_rel(
        &common::DRIVES,
        &format!("{case}: peak tip deflection"),
        law.max_tip_deflection_m,
        "the S-curve run",
        from_table.max_tip_deflection_m,
        "m",
        5e-3,
    );
    common::validated_rel(
        &common::DRIVES,
        &format!("{case}: peak drive torque"),
        law.peak_drive_torque_n_m,
        "the S-curve run",
        from_table.peak_drive_torque_n_m,
        "N·m",
        1e-2,
    );
    assert!(deflection < 5e-3, "tip deflection {} vs {}", from_table.max_tip_deflection_m, law.max_tip_deflection_m);
    // The peak torque falls in the S-curve's deceleration, 13.7 s in, where the 10 ms table's
    // acceleration departs from the S-curve's at its jerk corners: 0.66 % measured.
    assert!(torque < 1e-2, "drive torque {} vs {}", from_table.peak_drive_torque_n_m, law.peak_drive_torque_n_m);
}

/// Largest |tip deflection| and largest difference between two runs' tip deflections, m.
fn tip_difference(a: &pipearm::run::Series, b: &pipearm::run::Series) -> (f64, f64) {
    assert_eq!(a.t_s, b.t_s);
    let peak = a.tip_deflection_m.iter().map(|d| d[1].abs()).fold(0.0, f64::max);
    let diff = a.tip_deflection_m.iter().zip(&b.tip_deflection_m).map(|(x, y)| (x[1] - y[1]).abs()).fold(0.0, f64::max);
    (peak, diff)
}

/// The shipped spin-up scenario drives the Kane–Ryan–Banerjee beam from its 10 ms table; the
/// library's closed-form spin-up is the truth. The clamped spline's acceleration error is at
/// most h²/12 · max|θ''''| = (0.01 s)²/12 · (w/Ts)(2π/Ts)² ≈ 6e-7 rad/s², 1e-6 of the peak
/// acceleration 2w/Ts = 0.8 rad/s², and its ends are exact (rate 0, then w); the beam's response
/// is linear in that forcing to first order, so the runs agree to about 1e-6 of the peak tip
/// deflection — checked at 1e-4, with room for the steps' sampling of the peak.
#[test]
fn the_spin_up_from_a_table_follows_the_closed_form_spin_up() {
    let table = shipped("spin_up");
    let motion = &table.model.drive.motion;
    assert_eq!((motion.name(), motion.duration_s()), ("table", 15.0));
    // The spline's rate is within h³/24 · max|θ''''| ≈ 3e-9 rad/s of the law's (which ends at w).
    assert!((motion.peak_rate_rad_s() - 6.0).abs() < 3e-9, "{}", motion.peak_rate_rad_s());
    assert!(rel(motion.peak_accel_rad_s2(), 0.8) < 1e-5, "{}", motion.peak_accel_rad_s2());
    // The clamped spline's acceleration steps at its ends: the law starts and ends its ramp with
    // zero acceleration, the spline within the same h² θ'''' of it.
    let steps = [motion.sample(0.0).accel_rad_s2, motion.sample(15.0 - 1e-12).accel_rad_s2];
    println!("spin-up table: acceleration steps at the ends {:.2e}, {:.2e} rad/s²", steps[0], steps[1]);
    assert!(steps.iter().all(|a| a.abs() < 1e-5 * 0.8), "{steps:?}");
    let mut closed_form = table.model.clone();
    closed_form.drive.motion = MotionProfile::spin_up(0.0, 6.0, 15.0).unwrap();
    let (summary, series) = run(&table.model, None).unwrap();
    let (law_summary, law_series) = run(&closed_form, None).unwrap();
    let (peak, diff) = tip_difference(&law_series, &series);
    println!(
        "spin-up from a table: peak tip deflection {:.6} m, largest difference {diff:.3e} m ({:.2e} of the peak)",
        peak,
        diff / peak
    );
    common::validated_row(
        &common::DRIVES,
        "spin_up.toml, the Kane–Ryan–Banerjee beam driven from a 10 ms table: tip deflection over 30 s",
        &format!("the run under the closed-form spin-up law (peak {} m)", common::sig(peak, 4)),
        &format!("largest difference {} m", common::sig(diff, 2)),
        &common::relative(diff / peak),
        "< 1e-4 of the peak",
    );
    common::validated_rel(
        &common::DRIVES,
        "spin_up.toml from its table: peak drive torque",
        law_summary.peak_drive_torque_n_m,
        "the closed-form law's run",
        summary.peak_drive_torque_n_m,
        "N·m",
        1e-4,
    );
    assert!(peak > 0.1, "the spin-up bends the beam: {peak} m");
    assert!(diff < 1e-4 * peak, "tip deflection differs by {diff} m of {peak} m");
    assert!(rel(summary.peak_drive_torque_n_m, law_summary.peak_drive_torque_n_m) < 1e-4);
    let hub_angle_end = series.hub_angle_rad.last().unwrap();
    assert!((hub_angle_end - 6.0 * (30.0 - 7.5)).abs() < 1e-9, "keeps turning at 6 rad/s: {hub_angle_end}");
}

/// A bad table's error, read through a scenario, and the run's summary is never reached.
fn table_error(tag: &str, text: &str) -> String {
    let dir = temp_dir(tag);
    let csv = dir.join(format!("{tag}.csv"));
    std::fs::write(&csv, text).unwrap();
    let result = driven_by(&shipped("spin_up"), &csv, None);
    std::fs::remove_dir_all(&dir).ok();
    let message = result.err().unwrap_or_else(|| panic!("{tag}: the table was accepted")).to_string();
    assert!(message.contains(&csv.display().to_string()), "{tag}: the file is not named: {message}");
    assert!(message.contains("drive.file"), "{tag}: the key is not named: {message}");
    message
}

#[test]
fn bad_tables_name_the_column_and_the_row() {
    let rows = "0,0\n0.1,1\n0.2,3\n0.3,4\n";
    let cases: [(&str, String, &[&str]); 12] = [
        ("no-angle", "t[s]\n0\n0.1\n0.2\n0.3\n".into(), &["header (line 1)", "no column `angle[deg]`"]),
        ("no-unit", format!("t,angle[deg]\n{rows}"), &["column `t` has no unit", "allowed `t[s]`"]),
        ("wrong-unit", format!("t[s],angle[rad]\n{rows}"), &["column `angle[rad]`", "unit `rad`", "`angle[deg]`"]),
        ("unknown", format!("t[s],angle[deg],rate[deg/s]\n{rows}"), &["column `rate[deg/s]` is unknown"]),
        ("twice", format!("t[s],t[s]\n{rows}"), &["column `t[s]` appears twice"]),
        (
            "unsorted",
            "# comment\nt[s],angle[deg]\n0,0\n0.2,1\n0.1,3\n0.3,4\n".into(),
            &["column `t[s]`, row 3 (line 5)", "`0.1`", "strictly increasing"],
        ),
        (
            "nan",
            "t[s],angle[deg]\n0,0\n0.1,NaN\n0.2,3\n0.3,4\n".into(),
            &["column `angle[deg]`, row 2 (line 3)", "finite"],
        ),
        (
            "text",
            "angle[deg],t[s]\n0,0\n1,0.1\nabc,0.2\n4,0.3\n".into(),
            &["column `angle[deg]`, row 3 (line 4)", "`abc`"],
        ),
        ("start", "t[s],angle[deg]\n0.5,0\n1,1\n2,3\n3,4\n".into(), &["column `t[s]`, row 1 (line 2)", "0 (the table"]),
        ("few", "t[s],angle[deg]\n0,0\n0.1,1\n0.2,2\n".into(), &["3 row(s)", "at least 4"]),
        (
            "fields",
            "t[s],angle[deg]\n0,0\n0.1,1,7\n0.2,2\n0.3,3\n".into(),
            &["row 2 (line 3)", "3 field(s)", "allowed 2"],
        ),
        ("empty", "# nothing but a comment\n".into(), &["header", "none"]),
    ];
    for (tag, text, needles) in cases {
        let message = table_error(tag, &text);
        for needle in needles {
            assert!(message.contains(needle), "{tag}: `{needle}` missing from: {message}");
        }
    }
    let missing = driven_by(&shipped("spin_up"), Path::new("no-such-table.csv"), None).unwrap_err().to_string();
    assert!(missing.contains("no-such-table.csv") && missing.contains("cannot read"), "{missing}");
    let end_rate = driven_by(&shipped("spin_up"), Path::new("spin_up.csv"), Some(f64::NAN)).unwrap_err().to_string();
    assert!(end_rate.contains("drive.end_rate_deg_s"), "{end_rate}");
}

/// `pipearm run` on a scenario with a bad table fails naming the column and row, writes nothing.
#[test]
fn a_run_with_a_bad_table_writes_nothing() {
    let dir = temp_dir("cli");
    let out = dir.join("out");
    std::fs::write(dir.join("bad.csv"), "t[s],angle[deg]\n0,0\n0.1,1\n0.1,2\n0.3,3\n").unwrap();
    let text = std::fs::read_to_string(manifest().join("scenarios/spin_up.toml")).unwrap();
    let robot = manifest().join("robots/spin_up_beam.urdf");
    let text = text
        .replace("\"spin_up.csv\"", "\"bad.csv\"")
        .replace("\"../robots/spin_up_beam.urdf\"", &format!("{robot:?}"));
    std::fs::write(dir.join("bad.toml"), text).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["run", dir.join("bad.toml").to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    let wrote = out.exists();
    std::fs::remove_dir_all(&dir).ok();
    assert!(!output.status.success());
    assert!(stderr.contains("bad.csv") && stderr.contains("column `t[s]`, row 3 (line 4)"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!wrote, "a failed run created its output folder");
}

/// The pipe arm's lift joint turns at most 0.3 rad/s (17.19 °/s, robots/pipe_arm.urdf): a 90°
/// trapezoidal lift with a 20 % ramp peaks at 90° / (0.8 T), over it for T < 6.54 s.
#[test]
fn a_drive_faster_than_the_urdf_velocity_limit_is_refused() {
    let default = shipped("default");
    assert_eq!(default.model.robot.lift.velocity_rad_s, 0.3);
    let mut spec = default.spec.clone();
    let DriveSpec::Trapezoidal { duration_s, .. } = &mut spec.drive else { panic!("default drive changed") };
    *duration_s = 6.6;
    Scenario::from_spec(&default.path, spec.clone()).expect("17.05 °/s is within the limit");
    let DriveSpec::Trapezoidal { duration_s, .. } = &mut spec.drive else { unreachable!() };
    *duration_s = 6.5;
    let message = Scenario::from_spec(&default.path, spec).unwrap_err().to_string();
    for needle in ["drive.duration_s", "17.308 deg/s", "velocity limit", "`lift`", "17.189 deg/s"] {
        assert!(message.contains(needle), "`{needle}` missing from: {message}");
    }
    // A table is held to the same limit: the spin-up beam's hub turns at most 10 rad/s.
    let spin_up = shipped("spin_up");
    let csv = manifest().join("scenarios/spin_up.csv");
    driven_by(&spin_up, &csv, Some(10.0_f64.to_degrees())).expect("10 rad/s is the limit");
    let message = driven_by(&spin_up, &csv, Some(11.0_f64.to_degrees())).unwrap_err().to_string();
    assert!(message.contains("drive.file") && message.contains("velocity limit"), "{message}");
}

/// A table whose spline leaves the lift joint's range between its rows is refused, though every
/// row is within it.
#[test]
fn a_table_overshooting_the_joint_limits_is_refused() {
    let default = shipped("default");
    let dir = temp_dir("overshoot");
    let csv = dir.join("overshoot.csv");
    // 92.5° is within the pipe arm's 92.82° limit; arriving at it fast and stopping overshoots.
    std::fs::write(&csv, "t[s],angle[deg]\n0,0\n10,30\n14,90\n15,92.5\n").unwrap();
    let result = driven_by(&default, &csv, None);
    std::fs::remove_dir_all(&dir).ok();
    let message = result.unwrap_err().to_string();
    assert!(message.contains("drive.file") && message.contains("spline spans"), "{message}");
}

fn flagged(summary: &RunSummary) -> bool {
    !summary.drive.torque_within_effort
}

/// The run's peak drive torque against the joint's effort: the spin-up needs about
/// J θ̈max = (ρA L³/3)(2w/Ts) = 400 kg·m² × 0.8 rad/s² = 320 N·m, within its 1000 N·m drive,
/// beyond a 300 N·m one.
#[test]
fn a_torque_beyond_the_joint_effort_is_flagged() {
    let mut model = shipped("spin_up").model;
    model.time.settle_s = 0.0;
    let (summary, _) = run(&model, None).unwrap();
    common::validated_rel(
        &common::DRIVES,
        "spin_up.toml without settling: peak drive torque",
        320.0,
        "J θ̈_max = (ρAL³/3)(2ω_s/T_s) = 400 kg·m² × 0.8 rad/s²",
        summary.peak_drive_torque_n_m,
        "N·m",
        0.05,
    );
    assert!(rel(summary.peak_drive_torque_n_m, 320.0) < 0.05, "{}", summary.peak_drive_torque_n_m);
    assert!(!flagged(&summary));
    assert_eq!((summary.drive.kind.as_str(), summary.drive.effort_n_m), ("table", 1000.0));
    assert!(rel(summary.drive.peak_rate_deg_s, 6.0_f64.to_degrees()) < 1e-9);
    model.robot.lift.effort_n_m = 300.0;
    let (summary, _) = run(&model, None).unwrap();
    assert!(flagged(&summary));
}
