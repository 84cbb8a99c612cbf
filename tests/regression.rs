//! Regression baselines: every shipped scenario against its baseline; the check catches a
//! 10 % stiffer pad and a heavier string; bless; determinism.

use std::path::{Path, PathBuf};

use pipearm::contact::ForceLaw;
use pipearm::regression::{BaselineError, baseline_path, blessed, compare, read_baseline, write_baseline};
use pipearm::run::run;
use pipearm::scenario::{PayloadSpec, Scenario};

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn scenario(name: &str) -> Scenario {
    Scenario::load(&manifest().join(format!("scenarios/{name}.toml"))).unwrap()
}

fn shipped() -> Vec<PathBuf> {
    pipearm::scenario::scenario_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios")).unwrap()
}

/// Failing rows of `scenario` against the shipped baseline of `baseline_of`.
fn failures(s: &Scenario, baseline_of: &str) -> Vec<String> {
    let baseline =
        read_baseline(&baseline_path(&manifest().join("tests/baselines"), baseline_of), baseline_of, &s.path).unwrap();
    let (summary, _) = run(&s.model, None).unwrap();
    compare(&baseline, &summary).into_iter().filter(|r| !r.pass).map(|r| r.name).collect()
}

#[test]
fn every_shipped_scenario_matches_its_baseline() {
    let paths = shipped();
    assert!(paths.len() >= 3);
    for path in paths {
        let s = Scenario::load(&path).unwrap();
        let name = s.model.name.clone();
        let failed = failures(&s, &name);
        assert!(failed.is_empty(), "{name}: outside tolerance: {failed:?}");
    }
}

#[test]
fn a_ten_percent_stiffer_pad_fails_the_check() {
    let mut s = scenario("default");
    let ForceLaw::HuntCrossley { stiffness, .. } = &mut s.model.dampeners[0].law else {
        panic!("default pad law changed")
    };
    *stiffness *= 1.1;
    let failed = failures(&s, "default");
    assert!(failed.contains(&"arm-vertical_stop.peak_force_n".to_string()), "{failed:?}");
}

#[test]
fn a_heavier_string_fails_the_check() {
    let mut s = scenario("default");
    let PayloadSpec::String { string, .. } = &mut s.spec.payload else { panic!("default payload changed") };
    string.size = Some("4-1/2".into());
    let s = Scenario::from_spec(&s.path, s.spec).unwrap();
    let failed = failures(&s, "default");
    assert!(failed.contains(&"arm-vertical_stop.peak_force_n".to_string()), "{failed:?}");
    assert!(failed.contains(&"max_tip_deflection_m".to_string()), "{failed:?}");
}

#[test]
fn a_weaker_steel_fails_the_check_on_utilisation_alone() {
    // The same run against a yield 10 % lower: utilisation = |σ| / yield rises by 1/0.9 (11 %,
    // past its 2 % tolerance), the stress itself is unchanged.
    let mut s = scenario("default");
    for segment in &mut s.model.robot.arm.segments {
        if let Some(y) = &mut segment.checks.yield_strength {
            y.strength_pa *= 0.9;
        }
    }
    let failed = failures(&s, "default");
    assert_eq!(failed, ["stress.utilisation".to_string()], "{failed:?}");
}

#[test]
fn bless_accepts_a_change_and_keeps_the_tolerances() {
    let dir = std::env::temp_dir().join(format!("pipearm-bless-{}", std::process::id()));
    let mut s = scenario("default");
    let ForceLaw::HuntCrossley { stiffness, .. } = &mut s.model.dampeners[0].law else { panic!() };
    *stiffness *= 1.1;
    let (summary, _) = run(&s.model, None).unwrap();
    let shipped =
        read_baseline(&baseline_path(&manifest().join("tests/baselines"), "default"), "default", &s.path).unwrap();
    let path = baseline_path(&dir, "default");
    write_baseline(&path, &blessed(&summary, Some(&shipped))).unwrap();
    let reread = read_baseline(&path, "default", &s.path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert!(compare(&reread, &summary).iter().all(|r| r.pass));
    for (new, old) in reread.quantities.iter().zip(&shipped.quantities) {
        assert_eq!((new.relative_tolerance, new.absolute_tolerance), (old.relative_tolerance, old.absolute_tolerance));
    }
}

#[test]
fn missing_and_malformed_baselines_say_how_to_make_one() {
    let s = scenario("default");
    let dir = std::env::temp_dir().join(format!("pipearm-baselines-{}", std::process::id()));
    let path = baseline_path(&dir, "default");
    let missing = read_baseline(&path, "default", &s.path).unwrap_err();
    assert!(matches!(missing, BaselineError::Missing { .. }));
    assert!(missing.to_string().contains("--bless"), "{missing}");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(&path, "pipearm_version = 1\n").unwrap();
    let malformed = read_baseline(&path, "default", &s.path).unwrap_err();
    std::fs::remove_dir_all(&dir).ok();
    assert!(matches!(malformed, BaselineError::Malformed { .. }));
    assert!(malformed.to_string().contains("--bless") && malformed.to_string().contains("default.toml"), "{malformed}");
}

#[test]
fn runs_are_bit_identical_on_rerun_and_across_threads() {
    let s = scenario("default");
    let json = |s: &Scenario| serde_json::to_string(&run(&s.model, None).unwrap().0).unwrap();
    let first = json(&s);
    assert_eq!(first, json(&s), "a rerun changed the summary");
    // Two runs at once on two threads: no shared state between runs.
    let parallel: Vec<String> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2).map(|_| scope.spawn(|| json(&s))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(parallel.iter().all(|p| *p == first), "a run on another thread differs");
    let (_, a) = run(&s.model, None).unwrap();
    let (_, b) = run(&s.model, None).unwrap();
    assert!(a == b, "the recorded series differ between runs");
}

#[test]
fn pipearm_check_prints_a_failing_row_and_exits_non_zero() {
    let path = manifest().join(format!("scenarios/.stiffer-{}.toml", std::process::id()));
    let text = std::fs::read_to_string(manifest().join("scenarios/default.toml")).unwrap();
    std::fs::write(&path, text.replace("stiffness = 7.5e6", "stiffness = 8.25e6")).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["check", path.to_str().unwrap(), "--baselines", manifest().join("tests/baselines").to_str().unwrap()])
        .output()
        .unwrap();
    std::fs::remove_file(&path).ok();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!output.status.success());
    let row = stdout.lines().find(|l| l.contains("peak_force_n")).unwrap_or_default();
    // The row shows the blessed value it failed against.
    let baseline = std::fs::read_to_string(manifest().join("tests/baselines/default.toml")).unwrap();
    let blessed = baseline.lines().skip_while(|l| !l.contains("peak_force_n")).find(|l| l.starts_with("value"));
    let blessed: f64 = blessed.and_then(|l| l.split('=').nth(1)).and_then(|v| v.trim().parse().ok()).unwrap();
    assert!(row.contains("FAIL") && row.contains(&format!("{blessed:.6}")), "{stdout}");
}

#[test]
fn a_family_gives_the_same_results_on_one_or_two_worker_threads() {
    let files = pipearm::scenario::scenario_files(&manifest().join("scenarios/seed/3.1.1-drive")).unwrap();
    let summaries = |threads: usize| -> Vec<String> {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| pipearm::seed::run_family(&files, false).unwrap())
            .iter()
            .map(|v| serde_json::to_string(&v.summary).unwrap())
            .collect()
    };
    assert_eq!(summaries(1), summaries(2));
}

/// A baseline holds for the settings it was blessed under: the same scene under another
/// integrator or step is a changed setting, named, until blessed.
#[test]
fn a_run_under_other_settings_than_its_baseline_names_them() {
    use pipearm::integrate::IntegratorKind;
    use pipearm::regression::setting_changes;
    let s = scenario("default");
    let baseline =
        read_baseline(&baseline_path(&manifest().join("tests/baselines"), "default"), "default", &s.path).unwrap();
    let (summary, _) = run(&s.model, None).unwrap();
    assert!(setting_changes(&baseline, &summary).is_empty(), "as blessed");
    let mut model = s.model.clone();
    model.integrator = IntegratorKind::GeneralizedAlpha { rho_inf: 0.8 };
    model.time.step_s = 0.002;
    let (other, _) = run(&model, None).unwrap();
    let changed: Vec<&str> = setting_changes(&baseline, &other).iter().map(|c| c.setting).collect();
    assert_eq!(changed, ["integrator", "step_s"]);
}
