//! `pipearm run`'s recordings as a user meets them: a run the guard stops leaves its recording up
//! to the divergence and no summary; `--connect` and `--spawn` without a viewer fail at once,
//! with the address or the executable they looked for.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn pipearm(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("pipearm runs")
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

/// The texts of the recording store's `events`, in the order of the file.
fn events(path: &Path) -> Vec<String> {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut texts = Vec::new();
    for msg in re_log_encoding::DecoderApp::decode_eager(file).unwrap() {
        let re_log_types::LogMsg::ArrowMsg(store, arrow) = msg.unwrap() else { continue };
        let chunk = re_chunk::Chunk::from_arrow_msg(&arrow).unwrap();
        if store.kind() != re_log_types::StoreKind::Recording || chunk.entity_path().to_string() != "/events" {
            continue;
        }
        let text = chunk.component_descriptors().map(|d| d.component).find(|c| c.as_str() == "TextLog:text");
        for batch in chunk.iter_slices::<String>(text.expect("a text column")) {
            texts.extend(batch.iter().map(|s| s.to_string()));
        }
    }
    texts
}

#[test]
fn a_diverged_run_keeps_its_recording_up_to_the_divergence_and_writes_no_summary() {
    let out = scratch("diverged");
    // Eight modes at RK4's 3 ms step: ω_max·dt past RK4's limit (docs/performance.md).
    let output = pipearm(&["run", "scenarios/default.toml", "--model", "modal(8)", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "the guard stops the run: {stderr}");
    assert!(stderr.contains("diverged at t ="), "{stderr}");
    let recording = out.join("default.diverged.rrd");
    assert!(recording.exists(), "{recording:?}");
    assert!(!out.join("default.summary.json").exists() && !out.join("default.rrd").exists());
    let texts = events(&recording);
    std::fs::remove_dir_all(&out).ok();
    let last = texts.last().expect("events");
    // The guard's message as the command printed it: its time, what grew, the advice.
    let guard = stderr.lines().find(|l| l.contains("diverged at t =")).unwrap();
    let what = guard.split("diverged at t = ").nth(1).unwrap().split(". Advice").next().unwrap();
    assert!(last.contains(what), "last event {last:?} against the error {guard:?}");
    assert!(last.contains("Advice:"), "{last}");
}

#[test]
fn connect_to_a_closed_port_fails_at_once_naming_the_url() {
    // A port just freed: nothing listens there.
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let url = format!("rerun+http://127.0.0.1:{port}/proxy");
    let started = Instant::now();
    let output = pipearm(&["run", "--no-record", "--connect", &url]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains(&url) && stderr.contains("no rerun viewer"), "{stderr}");
    assert!(started.elapsed() < Duration::from_secs(5), "{:?}", started.elapsed());
}

#[test]
fn connect_takes_a_url_only() {
    let output = pipearm(&["run", "--no-record", "--connect", "scenarios/default.toml"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("expected a URL such as rerun+http://127.0.0.1:9876/proxy"), "{stderr}");
    let output = pipearm(&["run", "--connect", "--spawn"]);
    assert!(String::from_utf8_lossy(&output.stderr).contains("cannot be used with"));
}

#[test]
fn spawn_without_a_viewer_on_the_path_names_what_it_looked_for() {
    if std::net::TcpStream::connect("127.0.0.1:9876").is_ok() {
        // A viewer already listens on rerun's port: --spawn would stream to it.
        return;
    }
    let empty = scratch("empty-path");
    std::fs::create_dir_all(&empty).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_pipearm"))
        .args(["run", "--no-record", "--spawn"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("PATH", &empty)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&empty).ok();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("Rerun Viewer executable"), "{stderr}");
}

/// `run --step` and `--integrator` override the file's before its checks: the summary runs them;
/// an RK4 step beyond the arm's explicit limit is refused as the file would be; an unknown
/// method is named. `check --model` runs another model than the baseline's and fails naming it.
#[test]
fn run_and_check_take_their_overrides_through_the_scenarios_checks() {
    let run = |extra: &[&str]| {
        let mut args = vec!["run", "scenarios/default.toml", "--no-record"];
        args.extend_from_slice(extra);
        pipearm(&args)
    };
    let out = run(&["--step", "0.0015", "--integrator", "generalized-alpha"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("generalized-alpha") && stdout.contains("steps of 0.0015 s"), "{stdout}");
    // The file's RK4 at 3 ms would be refused at 30 ms; generalized-alpha there is not.
    let out = run(&["--step", "0.03", "--integrator", "generalized-alpha"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run(&["--step", "0.05"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("step_s") && !stderr.contains("panicked"), "{stderr}");
    let out = run(&["--integrator", "warp-drive"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("--integrator") && stderr.contains("rk4"), "{stderr}");
    let out = pipearm(&["check", "scenarios/default.toml", "--model", "modal(2)"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success() && stdout.contains("model") && stdout.contains("modal(2)"), "{stdout}");
}

/// `--model` reaches an actuated scenario's checks as `--step` does: its closed loop's poles, and
/// with them the RK4 step it allows, are the requested model's. `hydraulic.toml` (modal(5), its
/// fastest coupled pole about 1418 rad/s: RK4's limit |λ| dt <= 2.785 allows about 1.9 ms) runs
/// modal(3) at 2.5 ms, whose poles are slower, and refuses modal(8) there, whose are faster.
#[test]
fn the_model_override_reaches_the_actuators_checks() {
    let run = |model: &str| {
        pipearm(&["run", "scenarios/hydraulic.toml", "--no-record", "--step", "0.0025", "--model", model])
    };
    let out = run("modal(3)");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("modal(3)") && stdout.contains("steps of 0.0025 s"), "{stdout}");
    let out = run("modal(8)");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let fastest = stderr.split("fastest ").nth(1).and_then(|s| s.split(' ').next()).and_then(|s| s.parse::<f64>().ok());
    assert!(!out.status.success() && stderr.contains("time.step_s"), "{stderr}");
    assert!(fastest.is_some_and(|w| w * 0.0025 > 2.785), "{stderr}");
}

/// One spelling per idea: `kind` chooses the variant in every table. A scenario written with the
/// old spellings (`[drive] profile`, `[integrator] method`, `[contact] method`) runs the same,
/// with a note naming each old key and the key it was read as.
#[test]
fn old_spellings_run_the_same_with_a_note() {
    let dir = scratch("old-spellings");
    std::fs::create_dir_all(&dir).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenarios/default.toml")).unwrap();
    let old = text
        .replace("kind = \"trapezoidal\"", "profile = \"trapezoidal\"")
        .replace("kind = \"rk4\"", "method = \"rk4\"")
        .replace("kind = \"compliant\"", "method = \"compliant\"")
        .replace("../robots/", &format!("{}/robots/", root.display()));
    let path = dir.join("old.toml");
    std::fs::write(&path, old).unwrap();
    let old_run = pipearm(&["run", path.to_str().unwrap(), "--no-record"]);
    let new_run = pipearm(&["run", "scenarios/default.toml", "--no-record"]);
    let stderr = String::from_utf8_lossy(&old_run.stderr);
    assert!(old_run.status.success(), "{stderr}");
    for (old, new) in
        [("drive.profile", "drive.kind"), ("integrator.method", "integrator.kind"), ("contact.method", "contact.kind")]
    {
        assert!(stderr.contains(&format!("`{old}` is the old spelling of `{new}`")), "{stderr}");
    }
    let peak = |out: &Output| {
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        text.lines().find(|l| l.starts_with("contact arm")).map(str::to_string).unwrap_or_default()
    };
    assert_eq!(peak(&old_run), peak(&new_run));
    assert!(!peak(&new_run).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}
