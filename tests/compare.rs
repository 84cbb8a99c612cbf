//! `pipearm compare`: a run against its own channels shifted by a known time (the shift is
//! recovered and the errors vanish), the overlay's entities, and bad measured files (an error
//! naming the column and line, nothing written).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use pipearm::compare::align::interpolate;
use pipearm::compare::overlay::measured_chunks;
use pipearm::compare::{CompareOptions, compare, measurable_channels};
use pipearm::compile::Compiler;
use pipearm::model::Model;
use pipearm::run::{CompiledModel, run};
use pipearm::scenario::Scenario;
use pipearm::sensor::SensorSpec;

const SENSORS: &str = "
[[sensors]]
name = \"hand\"
kind = \"accelerometer\"
station_m = 8.2

[[sensors]]
name = \"root\"
kind = \"strain-gauge\"
station_m = 0.0
";

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn model_with_sensors() -> Model {
    let mut model = Scenario::load(&manifest().join("scenarios/default.toml")).unwrap().model;
    // The string lumped: held flexibly its mode beats with the arm's, and a frequency counted
    // from crossings of a beat depends on where the window starts.
    model.payload.string_mut().unwrap().model = Some(pipearm::arm::Fidelity::Rigid);
    for (name, kind, station) in [("hand", "accelerometer", 8.2), ("root", "strain-gauge", 0.0)] {
        let spec = SensorSpec { name: name.into(), kind: kind.into(), station_m: Some(station) };
        model.sensors.push(spec.resolve(&model.robot).unwrap());
    }
    model
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-compare-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The run's own channels as a rig's logger would write them (kN·m, mm), on its own clock: a
/// sample every 5 ms from t = 0, late by `shift_s` (before the run, the machine at rest: its
/// first state).
fn own_channels_csv(model: &Model, shift_s: f64) -> String {
    let (_, series) = run(model, None).unwrap();
    let t = &series.t_s;
    let columns: Vec<Vec<f64>> = vec![
        series.sensors[0].values.iter().map(|v| v[1]).collect(),
        series.sensors[1].values.iter().map(|v| v[0] / 1e3).collect(),
        series.tip_deflection_m.iter().map(|d| d[1] * 1e3).collect(),
    ];
    let mut text = String::from("t[s],hand.transverse[m/s^2],root.moment[kN*m],tip_deflection.transverse[mm]\n");
    let end = t[t.len() - 1] + shift_s;
    for j in 0..=((end / 0.005) as usize) {
        let logged = j as f64 * 0.005;
        let at = (logged - shift_s).max(0.0);
        let values: Vec<String> =
            columns.iter().map(|c| interpolate(t, c, at).expect("within the run").to_string()).collect();
        text += &format!("{logged},{}\n", values.join(","));
    }
    text
}

#[test]
fn a_run_against_its_own_shifted_channels() {
    let model = model_with_sensors();
    let shift_s = 0.1234; // 41.13 steps of 3 ms, 24.68 logger samples
    let dir = scratch("own");
    let csv = dir.join("rig.csv");
    std::fs::write(&csv, own_channels_csv(&model, shift_s)).unwrap();
    let measured = pipearm::measured::read(&csv).unwrap();
    let compiled = CompiledModel::new(&model, None, &Compiler::new()).unwrap();
    let aligned = compare(&compiled, &measured, &CompareOptions { shift: true, ..CompareOptions::default() }).unwrap();
    let c = &aligned.comparison;
    let found = c.shift_s.unwrap();
    common::validated_abs(
        &common::FIT,
        "`pipearm compare --shift` on a run's own channels logged every 5 ms on a clock 0.1234 s late: shift found",
        shift_s,
        "the known lag",
        found,
        "s",
        0.2e-3,
    );
    let worst = c.signals.iter().map(|s| s.rms_error_over_peak.max(s.peak_error_relative.abs())).fold(0.0, f64::max);
    common::validated_row(
        &common::FIT,
        "the same, aligned: RMS error over peak and peak error of each of the 3 channels",
        "0 (the run's own channels)",
        &format!("largest {}", common::relative(worst)),
        &common::relative(worst),
        "< 0.2 %",
    );
    assert!((found - shift_s).abs() < 0.2e-3, "shift {found} s, expected {shift_s} s");
    for s in &c.signals {
        assert!(s.rms_error_over_peak < 2e-3, "{}: rms/peak {}", s.signal, s.rms_error_over_peak);
        assert!(s.peak_error_relative.abs() < 2e-3, "{}: peak error {}", s.signal, s.peak_error_relative);
        assert!(s.frequency_difference_hz.abs() < 2e-3 * s.frequency_measured_hz, "{}: {s:?}", s.signal);
        assert!(s.log_decrement_difference.abs() < 0.02 * s.log_decrement_measured.abs(), "{}: {s:?}", s.signal);
    }
    // The tip's residual vibration rings near the arm's first clamped mode (4.2 Hz,
    // docs/model.md), stiffened by the pad it strikes, and decays.
    let tip = c.signals.iter().find(|s| s.signal == "tip_deflection.transverse").unwrap();
    assert!((3.5..5.5).contains(&tip.frequency_measured_hz) && tip.log_decrement_measured > 0.0, "{tip:?}");
    eprintln!("shift found {found} s (true {shift_s} s)\n{}", pipearm::compare::table(c));
    // Unshifted, the same file is off by the shift: the errors show it.
    let unshifted = compare(&compiled, &measured, &CompareOptions::default()).unwrap().comparison;
    assert_eq!(unshifted.shift_s, None);
    let hand = unshifted.signals.iter().find(|s| s.signal == "hand.transverse").unwrap();
    assert!(hand.rms_error_over_peak > 100.0 * c.signals[0].rms_error_over_peak, "{hand:?}");
    // The overlay: one chunk per column under its plot, `/measured`, every sample from t = 0.
    let defs = measurable_channels(&model);
    let chunks = measured_chunks(&measured, &aligned.columns, c, &defs).unwrap();
    let entities: Vec<String> = chunks.iter().map(|c| c.entity_path().to_string()).collect();
    assert_eq!(
        entities,
        [
            "/plots/sensors/hand/transverse/measured",
            "/plots/sensors/root/moment/measured",
            "/plots/tip_deflection/transverse/measured"
        ]
    );
    let from_start = measured.t_s.iter().filter(|t| **t - found >= 0.0).count();
    assert!(chunks.iter().all(|c| c.num_rows() == from_start));
    std::fs::remove_dir_all(&dir).ok();
}

/// Runs the binary's compare on `csv` text with `scenario`; returns (success, stderr, whether a
/// report was written).
fn cli_compare(name: &str, scenario: &Path, csv: &str) -> (bool, String, bool) {
    let dir = scratch(name);
    let file = dir.join("rig.csv");
    std::fs::write(&file, csv).unwrap();
    let out = dir.join("out");
    let output = Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["compare", scenario.to_str().unwrap(), "--measured", file.to_str().unwrap(), "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let written = out.exists();
    std::fs::remove_dir_all(&dir).ok();
    (output.status.success(), String::from_utf8_lossy(&output.stderr).into_owned(), written)
}

#[test]
fn bad_measured_files_name_the_column_and_line_and_write_nothing() {
    let dir = scratch("scenario");
    let robot = manifest().join("robots/pipe_arm.urdf");
    let base = std::fs::read_to_string(manifest().join("scenarios/default.toml"))
        .unwrap()
        .replace("\"../robots/pipe_arm.urdf\"", &format!("{:?}", robot.display().to_string()));
    let scenario = dir.join("sensors.toml");
    std::fs::write(&scenario, format!("{base}\n{SENSORS}")).unwrap();
    let rows = "0,9.8\n0.01,9.8\n0.02,9.8\n0.03,9.8\n0.04,9.8\n0.05,9.8\n";
    let cases = [
        (format!("t[s],hand.across[m/s^2]\n{rows}"), "column 2 `hand.across[m/s^2]`: no signal `hand.across`"),
        (format!("t[s],hand.transverse\n{rows}"), "column 2 `hand.transverse`: no unit"),
        (format!("t[s],hand.transverse[m/s]\n{rows}"), "unit `m/s`: allowed m/s^2"),
        (format!("time,hand.transverse[m/s^2]\n{rows}"), "column 1 `time`"),
        (
            "t[s],hand.transverse[m/s^2]\n0,9.8\n0.02,9.8\n0.01,9.8\n0.03,9.8\n0.04,9.8\n".into(),
            "line 4, column `t[s]`",
        ),
        ("t[s],hand.transverse[m/s^2]\n0,9.8\n0.01,nan\n0.02,9.8\n0.03,9.8\n0.04,9.8\n".into(), "line 3, column `hand"),
        ("t[s],hand.transverse[m/s^2]\n0,9.8\n0.01,\n0.02,9.8\n0.03,9.8\n0.04,9.8\n".into(), "line 3, column `hand"),
        ("t[s],hand.transverse[m/s^2]\n0,9.8\n0.01,9.8\n".into(), "2 samples: allowed at least 5"),
        (format!("t[s],hand.transverse[m/s^2]\n{}", rows.replace("0.0", "100.0")), "within the run"),
    ];
    for (k, (csv, expected)) in cases.iter().enumerate() {
        let (ok, stderr, written) = cli_compare(&format!("bad{k}"), &scenario, csv);
        assert!(!ok && stderr.contains("rig.csv") && stderr.contains(expected), "{csv}\n{stderr}");
        assert!(!written, "{csv}: a report was written");
    }
    let (ok, stderr, written) = cli_compare("good", &scenario, &format!("t[s],hand.transverse[m/s^2]\n{rows}"));
    assert!(ok && written, "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A compare that succeeds writes its report and a recording of the run with the measured series
/// drawn over the simulated one (under `<plot>/measured`).
#[test]
fn a_compare_writes_the_run_with_the_measured_series_over_it() {
    let scenario = manifest().join("scenarios/default.toml");
    let model = Scenario::load(&scenario).unwrap().model;
    let (_, series) = run(&model, None).unwrap();
    let mut csv = String::from("t[s],tip_deflection.transverse[mm]\n");
    for (t, d) in series.t_s.iter().zip(&series.tip_deflection_m).step_by(3) {
        csv += &format!("{t},{}\n", 1e3 * d[1]);
    }
    let dir = scratch("overlay");
    std::fs::write(dir.join("rig.csv"), csv).unwrap();
    let out = dir.join("out");
    let output = Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["compare", scenario.to_str().unwrap(), "--measured"])
        .arg(dir.join("rig.csv"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(out.join("default.compare.json").exists());
    // The writer does not compress: the entity path is in the file as text.
    let rrd = std::fs::read(out.join("default.compare.rrd")).unwrap();
    let needle = b"plots/tip_deflection/transverse/measured";
    assert!(rrd.windows(needle.len()).any(|w| w == needle), "no measured overlay in the recording");
    std::fs::remove_dir_all(&dir).ok();
}

/// A pair has one name: the summary's (`arm-<pad>`) is its force channel's in the tables and in
/// a measured file. A measured column in the former spelling, `contact_force.<pad>`, is still
/// read, as the same signal, and the command says so.
#[test]
fn a_pads_force_column_is_named_as_the_summary_names_the_pair() {
    let model = Scenario::load(&manifest().join("scenarios/default.toml")).unwrap().model;
    let (summary, _) = run(&model, Some(pipearm::arm::Fidelity::Modal { modes: 1 })).unwrap();
    let defs = measurable_channels(&model);
    for pair in &summary.pairs {
        let name = format!("contact_force.{}", pair.pair);
        assert!(defs.iter().any(|d| d.name == name), "no channel {name}");
    }
    let known: Vec<pipearm::measured::Known> = defs.iter().map(pipearm::measured::Known::from).collect();
    let rows = "0,1\n0.1,2\n0.2,3\n0.3,4\n0.4,5\n";
    let read =
        |header: &str| pipearm::measured::parse(Path::new("rig.csv"), &format!("t[s],{header}\n{rows}")).unwrap();
    for header in ["contact_force.arm-vertical_stop[kN]", "contact_force.vertical_stop[kN]"] {
        let columns = read(header).to_si(&known).unwrap();
        assert_eq!(columns[0].name, "contact_force.arm-vertical_stop", "{header}");
        assert_eq!(columns[0].values, [1e3, 2e3, 3e3, 4e3, 5e3], "{header}");
    }
    assert!(read("contact_force.arm-vertical_stop[kN]").renamed(&known).is_empty());
    assert_eq!(
        read("contact_force.vertical_stop[kN]").renamed(&known),
        [("contact_force.vertical_stop".to_string(), "contact_force.arm-vertical_stop")]
    );
    assert!(read("contact_force.nowhere[kN]").to_si(&known).is_err());

    let dir = scratch("former-spelling");
    let csv = dir.join("rig.csv");
    let shipped = std::fs::read_to_string(manifest().join("measurements/rig.csv")).unwrap();
    std::fs::write(&csv, shipped.replacen("contact_force.arm-vertical_stop", "contact_force.vertical_stop", 1))
        .unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args([
            "compare",
            "scenarios/default.toml",
            "--model",
            "modal(1)",
            "--measured",
            csv.to_str().unwrap(),
            "--out",
        ])
        .arg(dir.join("out"))
        .current_dir(manifest())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(
        stdout.contains("note: the column `contact_force.vertical_stop` is read as `contact_force.arm-vertical_stop`"),
        "{stdout}"
    );
    assert!(stdout.lines().any(|l| l.starts_with("contact_force.arm-vertical_stop ")), "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}
