//! `pipearm sweep`: results independent of threads and shards, skip-if-current, the errors a bad
//! `--vary` gives, ranges and the chart (docs/sweeps.md). Short lifts of the default scenario
//! (4–8 s, 0.5 s of settling) keep it quick.

use std::path::{Path, PathBuf};

use pipearm::sweep::{Plan, Progress, Report, Request, Shard, SweepError, Vary, merge, sweep};

const RESULTS: [&str; 3] = ["results.json", "results.csv", "force_vs_weight.svg"];

fn scenario() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")
}

/// A fresh output folder for one test.
fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn vary(args: &[&str]) -> Vec<Vary> {
    args.iter().map(|a| a.parse().unwrap()).collect()
}

/// 3 durations × 2 strings = 6 cases (the pipe arm's lift turns at most 0.3 rad/s: its 90°
/// lift takes at least 6.55 s).
fn short_sweep(durations: &str) -> Vec<Vary> {
    vary(&[&format!("drive.duration_s={durations}"), "payload.size=2-7/8,4-1/2", "time.settle_s=0.5"])
}

fn run(vary: Vec<Vary>, out: &Path, threads: Option<usize>, shard: Shard) -> Result<Report, SweepError> {
    let request = Request { scenario: scenario(), vary, out: out.into(), threads, shard };
    sweep(&request, &|_: Progress| {})
}

fn read(dir: &Path, file: &str) -> Vec<u8> {
    std::fs::read(dir.join(file)).unwrap_or_else(|e| panic!("{}: {e}", dir.join(file).display()))
}

#[test]
fn one_and_two_threads_give_the_same_bytes_and_a_chart() {
    let (one, two) = (out_dir("threads1"), out_dir("threads2"));
    let report = run(short_sweep("7..11:2"), &one, Some(1), Shard::ALL).unwrap();
    run(short_sweep("7..11:2"), &two, Some(2), Shard::ALL).unwrap();
    assert_eq!((report.cases, report.ran, report.current), (6, 6, 0));
    for file in RESULTS {
        assert_eq!(read(&one, file), read(&two, file), "{file}");
    }
    let csv = String::from_utf8(read(&one, "results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 7);
    assert!(csv.starts_with("index,hash,drive.duration_s,payload.size,time.settle_s,outcome,scenario,"));
    let header = csv.lines().next().unwrap();
    assert!(header.contains(",pairs.0.peak_force_n,") && !header.contains(".impacts"), "{header}");
    let svg = String::from_utf8(read(&one, "force_vs_weight.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("drive.duration_s=7, time.settle_s=0.5"));
}

#[test]
fn three_shards_merged_give_the_bytes_of_one_run() {
    let (whole, sharded) = (out_dir("whole"), out_dir("sharded"));
    run(short_sweep("7..11:2"), &whole, None, Shard::ALL).unwrap();
    for i in 0..3 {
        let report = run(short_sweep("7..11:2"), &sharded, Some(1), Shard::new(i, 3).unwrap()).unwrap();
        assert_eq!((report.ran, report.merged), (2, None));
        if i == 0 {
            let missing = merge(&sharded).unwrap_err().to_string();
            assert!(missing.contains("4 case(s) not run yet: 1 (") && missing.contains("; 5 ("), "{missing}");
        }
    }
    merge(&sharded).unwrap();
    for file in RESULTS {
        assert_eq!(read(&whole, file), read(&sharded, file), "{file}");
    }
}

#[test]
fn a_rerun_skips_current_cases_and_reruns_a_changed_one() {
    let out = out_dir("rerun");
    run(short_sweep("7,9,11"), &out, None, Shard::ALL).unwrap();
    let again = run(short_sweep("7,9,11"), &out, None, Shard::ALL).unwrap();
    assert_eq!((again.ran, again.current), (0, 6));
    let changed = run(short_sweep("7,9,10"), &out, None, Shard::ALL).unwrap();
    assert_eq!((changed.ran, changed.current), (2, 4));
    let files = std::fs::read_dir(out.join("cases")).unwrap().count();
    assert_eq!(files, 6, "the stale case files of 11 s are gone");
    let csv = String::from_utf8(read(&out, "results.csv")).unwrap();
    assert!(csv.lines().nth(5).unwrap().starts_with("4,") && csv.contains(",10,4-1/2,"), "{csv}");
}

/// The shipped RK4 at 10 ms is past its limit on the default arm (ω_max·dt = 3.4 > 2.83): that
/// case's run is stopped by the guard, and the sweep records it beside the case that ran.
#[test]
fn a_case_the_guard_stops_is_a_result_not_a_failed_sweep() {
    let out = out_dir("diverged");
    let report =
        run(vary(&["time.step_s=0.003,0.01", "drive.duration_s=7", "time.settle_s=0.5"]), &out, None, Shard::ALL)
            .unwrap();
    assert_eq!(report.ran, 2);
    let csv = String::from_utf8(read(&out, "results.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("index,hash,time.step_s,drive.duration_s,time.settle_s,outcome,"), "{}", rows[0]);
    assert!(rows[1].contains(",ran,"), "{}", rows[1]);
    assert!(rows[2].contains(",diverged at "), "{}", rows[2]);
    let json = String::from_utf8(read(&out, "results.json")).unwrap();
    assert!(json.contains("\"summary\": null") && json.contains("use step_s <= "), "{json}");
}

#[test]
fn bad_vary_input_names_the_key_and_writes_nothing() {
    let out = out_dir("bad");
    let cases: [(&[&str], &[&str]); 8] = [
        (&["drive.nope.x=1"], &["drive.nope.x", "`nope` does not exist under `drive`", "duration_s"]),
        (&["dampeners.3.law.stiffness=1e6"], &["dampeners.3.law.stiffness", "outside the array `dampeners`"]),
        // A value of payload.size outside the catalogue is refused before any case is planned.
        (
            &["payload.size=2-7/8,9-9/9"],
            &["payload.size", "`9-9/9` is not in the catalogue", "9-5/8@47.00", "liftable"],
        ),
        (&["time.step_s=0.001,0.5"], &["time.step_s=0.5", "key `time.step_s`"]),
        (&["drive.durationn_s=10"], &["drive.durationn_s=10", "unknown field"]),
        (&["payload.size=2-7/8", "payload.size=4-1/2"], &["payload.size", "varied twice"]),
        (&["robot=../robots/pipe_arm.urdf,nope.urdf"], &["case 1 (robot=nope.urdf)", "nope.urdf", "cannot read"]),
        // Refused by its compile: ZVD tuned to the arm's modes speeds the 7 s lift's base move past
        // the joint's velocity limit (tests/bad_input.rs), which only the compile can know.
        (&["drive.shaper=zvd", "drive.duration_s=15,7"], &["case 1 (", "drive.duration_s", "velocity limit"]),
    ];
    for (args, expected) in cases {
        let error = run(vary(args), &out, None, Shard::ALL).unwrap_err().to_string();
        for part in expected {
            assert!(error.contains(part), "{args:?}: `{error}` lacks `{part}`");
        }
    }
    for arg in ["drive.duration_s", "drive.duration_s=10..20", "drive..x=1", "x=1,,2"] {
        let error = arg.parse::<Vary>().unwrap_err().to_string();
        assert!(error.contains(&format!("`{arg}`")) && error.contains("allowed forms"), "{error}");
    }
    assert!(!out.exists(), "an invalid plan writes nothing");
}

#[test]
fn a_range_expands_as_documented() {
    let values = |arg: &str| arg.parse::<Vary>().unwrap().values;
    assert_eq!(values("drive.duration_s=10..20:5"), values("drive.duration_s=10,15,20"));
    assert_eq!(values("integrator.rho_inf=0.6..0.8:0.1"), values("integrator.rho_inf=0.6,0.7,0.8"));
    assert_eq!(values("time.step_s=0.001..0.0025:0.0005"), values("time.step_s=0.001,0.0015,0.002,0.0025"));
    let (plan, _) = Plan::build(&scenario(), vary(&["drive.duration_s=10..20:5", "payload.size=2-7/8,4-1/2"])).unwrap();
    let order: Vec<String> = plan.cases.iter().map(|c| c.describe(&plan.keys())).collect();
    assert_eq!(
        order[..3],
        [
            "drive.duration_s=10, payload.size=2-7/8",
            "drive.duration_s=10, payload.size=4-1/2",
            "drive.duration_s=15, payload.size=2-7/8"
        ]
    );
    assert_eq!(plan.cases.len(), 6);
}
