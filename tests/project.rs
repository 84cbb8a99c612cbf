//! A project as a user meets it: commands given a scenario find its project from the scenario's
//! path, `--project` names one for the commands that take none, and `pipearm init` writes a
//! starter project that runs; all from a folder that is not the project.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn pipearm_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pipearm")).args(args).current_dir(dir).output().expect("pipearm runs")
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-project-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn succeeds(out: &Output, what: &str) -> String {
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{what}: {stderr}\n{stdout}");
    stdout.into_owned()
}

#[test]
fn the_shipped_project_runs_checks_and_seeds_from_another_folder() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let elsewhere = scratch("elsewhere");
    let default = root.join("scenarios/default.toml");
    let default = default.to_str().unwrap();
    let out = elsewhere.join("out");
    succeeds(&pipearm_in(&elsewhere, &["run", default, "--out", out.to_str().unwrap()]), "run");
    assert!(out.join("default.rrd").exists() && out.join("default.summary.json").exists());
    // The baselines are the scenario's project's, not the working folder's.
    let stdout = succeeds(&pipearm_in(&elsewhere, &["check", default]), "check");
    assert!(stdout.contains("default"), "{stdout}");
    let project = root.to_str().unwrap();
    let seed_out = elsewhere.join("seed");
    let args = ["seed", "3.1.2-speed", "--project", project, "--out", seed_out.to_str().unwrap()];
    let stdout = succeeds(&pipearm_in(&elsewhere, &args), "seed");
    assert!(stdout.contains("3.1.2-speed") && seed_out.join("seed/3.1.2-speed.svg").exists(), "{stdout}");
    // Without --project, the working folder is the project: it has no scenarios/.
    let refused = pipearm_in(&elsewhere, &["check"]);
    assert!(!refused.status.success() && String::from_utf8_lossy(&refused.stderr).contains("scenarios"));
    std::fs::remove_dir_all(&elsewhere).ok();
}

#[test]
fn init_writes_a_starter_project_that_runs_and_blesses() {
    let dir = scratch("init").join("my_arm");
    let parent = dir.parent().unwrap();
    let stdout = succeeds(&pipearm_in(parent, &["init", dir.to_str().unwrap()]), "init");
    assert!(stdout.contains("pipearm run"), "{stdout}");
    let stdout = succeeds(&pipearm_in(&dir, &["run", "--no-record"]), "run in the new project");
    assert!(stdout.contains("contact arm-vertical_stop"), "{stdout}");
    succeeds(&pipearm_in(&dir, &["check", "--bless"]), "bless");
    assert!(dir.join("tests/baselines/default.toml").exists());
    succeeds(&pipearm_in(&dir, &["check"]), "check against its own baselines");
    // A second init over it is refused, writing nothing.
    let again = pipearm_in(parent, &["init", dir.to_str().unwrap()]);
    assert!(!again.status.success() && String::from_utf8_lossy(&again.stderr).contains("already holds"));
    std::fs::remove_dir_all(parent).ok();
}
