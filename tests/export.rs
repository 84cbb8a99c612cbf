//! The tables of `pipearm run --csv` read back, the CSV by hand and the Parquet with parquet's
//! own arrow reader, against the run's series taken field by field: the same headers (name and
//! unit), the same rows, the same `f64` bits.

use std::path::{Path, PathBuf};

use arrow::array::{Array, Float64Array};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use pipearm::export::{ExportError, write_tables};
use pipearm::run::{Series, run};
use pipearm::scenario::Scenario;
use pipearm::stress::Fibre;

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under the temporary directory, removed first if a previous run left it.
fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-export-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

/// The expected table: headers as docs/export.md lists them, values straight from the fields.
fn expected(series: &Series, pads: &[&str], keep_only: bool) -> Vec<(String, Vec<f64>)> {
    let mut columns: Vec<(String, Vec<f64>)> = vec![
        ("t[s]".into(), series.t_s.clone()),
        ("hub.angle[rad]".into(), series.hub_angle_rad.clone()),
        ("hub.rate[rad/s]".into(), series.hub_rate_rad_s.clone()),
        ("hub.accel[rad/s^2]".into(), series.hub_accel_rad_s2.clone()),
        ("tip_deflection.axial[m]".into(), series.tip_deflection_m.iter().map(|d| d[0]).collect()),
        ("tip_deflection.transverse[m]".into(), series.tip_deflection_m.iter().map(|d| d[1]).collect()),
        ("tip_velocity.axial[m/s]".into(), series.tip_velocity_m_s.iter().map(|d| d[0]).collect()),
        ("tip_velocity.transverse[m/s]".into(), series.tip_velocity_m_s.iter().map(|d| d[1]).collect()),
        ("drive_torque[N*m]".into(), series.drive_torque_n_m.clone()),
    ];
    for (pad, forces) in pads.iter().zip(&series.pad_force_n) {
        columns.push((format!("contact_force.{}[N]", pipearm::scene::pair_name(pad)), forces.clone()));
    }
    if !series.head_angle_rad.is_empty() {
        columns.push(("head.angle[rad]".into(), series.head_angle_rad.clone()));
    }
    if !series.string_slip_m.is_empty() {
        columns.push(("string_slip[m]".into(), series.string_slip_m.clone()));
        columns.push(("jaw_sinking[m]".into(), series.jaw_sinking_m.clone()));
    }
    for (k, kind) in ["kinetic", "strain", "gravity"].iter().enumerate() {
        columns.push((format!("energy.{kind}[J]"), series.energies_j.iter().map(|e| e[k]).collect()));
    }
    let n = series.modal_dofs;
    for i in 0..n {
        let q = (0..series.t_s.len()).map(|step| series.modal_q[step * n + i]).collect();
        columns.push((format!("modal.q{}[m*kg^0.5]", i + 1), q));
    }
    sign_off_columns(series, &mut columns);
    if keep_only {
        for (_, values) in &mut columns {
            *values = values.iter().zip(&series.keep).filter(|(_, k)| **k).map(|(v, _)| *v).collect();
        }
    }
    columns
}

/// The sign-off's columns as docs/export.md lists them: σ at the station and fibre of the run's
/// largest |σ| (the last of equals), the pivot's force turned from the hub frame to the world's,
/// the cylinder pin's, and each hand's grip, minus the string's load on it.
fn sign_off_columns(series: &Series, columns: &mut Vec<(String, Vec<f64>)>) {
    let stress = &series.stress;
    let steps = series.t_s.len();
    let value = |k: usize, at: usize| f64::from(stress.values[k * stress.width + at]);
    let mut worst = None;
    let mut largest = f64::MIN;
    for (i, extremes) in stress.extremes().iter().enumerate() {
        for (fibre, e) in [Fibre::Upper, Fibre::Lower].into_iter().zip(extremes) {
            let peak = e.max.abs().max(e.min.abs());
            if peak >= largest {
                (largest, worst) = (peak, Some((i, fibre)));
            }
        }
    }
    let Some((i, fibre)) = worst else { return };
    columns.push(("stress.worst[Pa]".into(), (0..steps).map(|k| stress.stress_pa(i, fibre, k)).collect()));
    let world = |k: usize, axis: usize| {
        let (s, c) = series.hub_angle_rad[k].sin_cos();
        let (x, y) = (value(k, stress.pivot_index), value(k, stress.pivot_index + 1));
        [c * x - s * y, s * x + c * y][axis]
    };
    columns.push(("pivot.force.x[N]".into(), (0..steps).map(|k| world(k, 0)).collect()));
    columns.push(("pivot.force.y[N]".into(), (0..steps).map(|k| world(k, 1)).collect()));
    // One cylinder's pin unnumbered; of several, numbered from 1 (docs/export.md).
    let count = stress.cylinder_indices.len();
    for (i, &at) in stress.cylinder_indices.iter().enumerate() {
        let pin = if count == 1 { "cylinder_pin".to_string() } else { format!("cylinder_pin.{}", i + 1) };
        columns.push((format!("{pin}.force.x[N]"), (0..steps).map(|k| value(k, at)).collect()));
        columns.push((format!("{pin}.force.y[N]"), (0..steps).map(|k| value(k, at + 1)).collect()));
    }
    for (hand, at) in &stress.hands {
        for (j, name) in ["force.axial[N]", "force.transverse[N]", "moment[N*m]"].into_iter().enumerate() {
            columns.push((format!("grip.{hand}.{name}"), (0..steps).map(|k| -value(k, at + j)).collect()));
        }
    }
}

/// A CSV table read back: its header fields and its columns, each value parsed as `f64`.
fn read_csv(path: &Path) -> Vec<(String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut columns: Vec<(String, Vec<f64>)> =
        lines.next().unwrap().split(',').map(|h| (h.to_string(), Vec::new())).collect();
    for (row, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), columns.len(), "{}: row {row}", path.display());
        for (column, field) in columns.iter_mut().zip(fields) {
            column.1.push(field.parse().unwrap_or_else(|e| panic!("{}: row {row}: `{field}`: {e}", path.display())));
        }
    }
    columns
}

/// A Parquet table read back with parquet's arrow reader: its field names and columns.
fn read_parquet(path: &Path) -> Vec<(String, Vec<f64>)> {
    let reader = ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(path).unwrap()).unwrap().build().unwrap();
    let mut columns: Vec<(String, Vec<f64>)> = Vec::new();
    for batch in reader {
        let batch = batch.unwrap();
        if columns.is_empty() {
            columns = batch.schema().fields().iter().map(|f| (f.name().clone(), Vec::new())).collect();
        }
        for (column, array) in columns.iter_mut().zip(batch.columns()) {
            let array = array.as_any().downcast_ref::<Float64Array>().expect("a DOUBLE column");
            assert_eq!(array.null_count(), 0);
            column.1.extend(array.values().iter());
        }
    }
    columns
}

/// Same headers in the same order, and every value bit for bit.
fn assert_same(file: &Path, read: &[(String, Vec<f64>)], want: &[(String, Vec<f64>)]) {
    let headers = |t: &[(String, Vec<f64>)]| t.iter().map(|c| c.0.clone()).collect::<Vec<_>>();
    assert_eq!(headers(read), headers(want), "{}", file.display());
    for ((name, got), (_, want)) in read.iter().zip(want) {
        assert_eq!(got.len(), want.len(), "{}: {name}: rows", file.display());
        let differs = got.iter().zip(want).position(|(a, b)| a.to_bits() != b.to_bits());
        assert!(differs.is_none(), "{}: {name}: row {differs:?} differs", file.display());
    }
}

/// Writes the tables of `series` and checks all four against the series.
fn check_round_trip(name: &str, series: &Series, pads: &[&str]) {
    let dir = scratch(name);
    let written = write_tables(&dir, name, series).unwrap();
    assert_eq!(written.paths.len(), 4);
    for (tag, keep_only) in [("steps", false), ("decimated", true)] {
        let want = expected(series, pads, keep_only);
        for (extension, read) in [("csv", read_csv as fn(&Path) -> _), ("parquet", read_parquet)] {
            let file = dir.join(format!("{name}.{tag}.{extension}"));
            assert_same(&file, &read(&file), &want);
        }
    }
    let mut left: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    let files = ["decimated.csv", "decimated.parquet", "steps.csv", "steps.parquet"].map(|f| format!("{name}.{f}"));
    assert_eq!(left, files, "the four tables and no temporary file");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_default_runs_tables_read_back_equal_to_its_series() {
    let scenario = Scenario::load(&manifest().join("scenarios/default.toml")).unwrap();
    let (summary, series) = run(&scenario.model, None).unwrap();
    // The decimated table is a true subset: fewer rows, yet every contact's first step.
    let kept: Vec<bool> = series.keep.clone();
    let forces = &series.pad_force_n[0];
    let starts = (1..forces.len()).filter(|&i| forces[i] > 0.0 && forces[i - 1] <= 0.0);
    assert!(summary.pairs[0].impact_count > 0 && kept.iter().filter(|k| **k).count() < series.t_s.len() / 4);
    assert!(starts.into_iter().all(|i| kept[i]), "a contact's first step was dropped");
    assert!(series.modal_dofs > 0, "the default scene's model is modal: its q columns are tested");
    check_round_trip("default", &series, &["vertical_stop"]);
}

#[test]
fn a_hydraulic_runs_tables_hold_its_actuators_channels_after_the_drive_torque() {
    // Two cylinders on one valve (hydraulic_twin): docs/export.md's actuator columns, each
    // cylinder's rod force numbered, the one valve's pressures not.
    let scenario = Scenario::load(&manifest().join("scenarios/hydraulic_twin.toml")).unwrap();
    let (_, series) = run(&scenario.model, None).unwrap();
    let each = |f: &dyn Fn(&pipearm::actuator::ActuatorOutputs) -> f64| series.actuator.iter().map(f).collect();
    let actuator: Vec<(String, Vec<f64>)> = vec![
        ("actuator.tracking_error[rad]".into(), each(&|o| o.tracking_error_rad)),
        ("actuator.command[1]".into(), each(&|o| o.command)),
        ("actuator.rod_force.1[N]".into(), each(&|o| o.cylinders[0].rod_force_n)),
        ("actuator.rod_force.2[N]".into(), each(&|o| o.cylinders[1].rod_force_n)),
        ("actuator.pressure.cap[Pa]".into(), each(&|o| o.cylinders[0].pressures_pa[0])),
        ("actuator.pressure.rod[Pa]".into(), each(&|o| o.cylinders[0].pressures_pa[1])),
    ];
    let mut want = expected(&series, &["vertical_stop"], false);
    let at = want.iter().position(|(name, _)| name == "drive_torque[N*m]").unwrap() + 1;
    want.splice(at..at, actuator);
    let dir = scratch("twin");
    write_tables(&dir, "twin", &series).unwrap();
    let file = dir.join("twin.steps.csv");
    assert_same(&file, &read_csv(&file), &want);
    std::fs::remove_dir_all(&dir).ok();
}

/// The shipped scenario `name` run, and its tables checked against its series; returns the series.
fn shipped_round_trip(name: &str) -> Series {
    let scenario = Scenario::load(&manifest().join(format!("scenarios/{name}.toml"))).unwrap();
    let (_, series) = run(&scenario.model, None).unwrap();
    let pads: Vec<&str> = scenario.model.dampeners.iter().map(|d| d.name.as_str()).collect();
    check_round_trip(name, &series, &pads);
    series
}

#[test]
fn a_friction_clamped_run_has_its_slip_columns() {
    assert!(!shipped_round_trip("friction_clamp").string_slip_m.is_empty());
}

#[test]
fn a_tilting_heads_run_has_its_angle_column() {
    assert!(!shipped_round_trip("tilting_head").head_angle_rad.is_empty());
}

#[test]
fn two_pads_give_one_force_column_each() {
    let scenario = Scenario::load(&manifest().join("scenarios/default.toml")).unwrap();
    let mut model = scenario.model.clone();
    let mut second = model.dampeners[0].clone();
    second.name = "inner_stop".into();
    second.station_m -= 1.0;
    model.dampeners.push(second);
    let (_, series) = run(&model, None).unwrap();
    assert_eq!(series.pad_force_n.len(), 2);
    let dir = scratch("two-pads");
    write_tables(&dir, "two", &series).unwrap();
    let csv = read_csv(&dir.join("two.steps.csv"));
    let forces: Vec<&str> = csv.iter().map(|c| c.0.as_str()).filter(|h| h.starts_with("contact_force")).collect();
    assert_eq!(forces, ["contact_force.arm-vertical_stop[N]", "contact_force.arm-inner_stop[N]"]);
    std::fs::remove_dir_all(&dir).ok();
    check_round_trip("two", &series, &["vertical_stop", "inner_stop"]);
}

#[test]
fn a_file_where_the_folder_should_be_is_named_and_nothing_is_written() {
    let scenario = Scenario::load(&manifest().join("scenarios/default.toml")).unwrap();
    let (_, series) = run(&scenario.model, None).unwrap();
    let dir = scratch("bad-out");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("recordings");
    std::fs::write(&file, "a file").unwrap();
    for out in [file.clone(), file.join("nested")] {
        let error = write_tables(&out, "default", &series).unwrap_err();
        assert!(matches!(&error, ExportError::NotAFolder { file: f, .. } if *f == file), "{error}");
        assert!(error.to_string().contains("is a file, not a folder"), "{error}");
    }
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["recordings"], "only the file put there");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "a file");
    std::fs::remove_dir_all(&dir).ok();
}

/// The command line: `--csv --no-record` writes the four tables and nothing else, and prints
/// them; a file as `--out` stops the run before it starts, naming the file.
#[test]
fn run_csv_on_the_command_line() {
    let out = scratch("cli");
    let run = |out: &Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
            .args(["run", "--csv", "--no-record", "--out", out.to_str().unwrap()])
            .current_dir(manifest())
            .output()
            .unwrap()
    };
    let output = run(&out);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(stdout.contains("wrote tables") && stdout.contains("default.steps.{csv,parquet}"), "{stdout}");
    let mut left: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    assert_eq!(
        left,
        [
            "default.decimated.csv",
            "default.decimated.parquet",
            "default.steps.csv",
            "default.steps.parquet",
            "default.stress.svg"
        ],
        "the tables and, beside them, the stress envelope's chart"
    );
    std::fs::remove_dir_all(&out).ok();

    std::fs::create_dir_all(&out).unwrap();
    let file = out.join("taken");
    std::fs::write(&file, "").unwrap();
    let output = run(&file);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("--out") && stderr.contains("is a file, not a folder"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1, "nothing written beside the file");
    std::fs::remove_dir_all(&out).ok();
}
