//! What the sign-off (stress recovery, pin loads, rainflow) costs the default run
//! (docs/sign-off.md, "Cost"), its feature on and off in the same build:
//!
//! - `valgrind --tool=callgrind target/release/examples/signoff_cost with|here|without`: one
//!   run, to count instructions (`with`: the readings completed on a worker thread beside the
//!   step, as a run on its own does; `here`: on the step's thread, as inside a sweep's pool);
//! - `target/release/examples/signoff_cost paired 60`: the simulation alone (`run_with`), the
//!   two alternately 60 times each in one process: the median of the paired ratios;
//! - `target/release/examples/signoff_cost job 60`: the same for the default run as
//!   `pipearm run` does it in process (its `total` line): the scenario read, the run with its
//!   frames, the recording and the summary written (to a temporary folder).

use std::path::{Path, PathBuf};
use std::time::Instant;

use pipearm::record::{write_recording, write_summary};
use pipearm::run::{RunOptions, run_with};
use pipearm::scenario::Scenario;

/// The allocator `pipearm` itself runs on (src/main.rs).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn default_scenario() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")
}

/// Seconds for the simulation alone.
fn simulation(scenario: &Scenario, sign_off: bool) -> f64 {
    let options = RunOptions { sign_off, ..RunOptions::default() };
    let started = Instant::now();
    run_with(&scenario.model, &options).expect("the default scenario runs");
    started.elapsed().as_secs_f64()
}

/// Seconds for the whole job as `pipearm run` does it, files into `out`.
fn job(out: &Path, sign_off: bool) -> f64 {
    let started = Instant::now();
    let scenario = Scenario::load(&default_scenario()).expect("the default scenario loads");
    let options = RunOptions { sign_off, capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_with(&scenario.model, &options).expect("the default scenario runs");
    write_recording(&out.join("default.rrd"), &summary, &series).expect("the recording is written");
    write_summary(&out.join("default.summary.json"), &summary).expect("the summary is written");
    started.elapsed().as_secs_f64()
}

/// The median and quartiles of `pairs` paired ratios with / without, each pair in turn order
/// (so that neither side always runs on the other's leftovers).
fn paired(pairs: usize, mut timed: impl FnMut(bool) -> f64) -> [f64; 3] {
    let mut ratios: Vec<f64> = (0..pairs)
        .map(|i| {
            let with_first = i % 2 == 0;
            let (first, second) = (timed(with_first), timed(!with_first));
            let (with, without) = if with_first { (first, second) } else { (second, first) };
            with / without
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    [0.5, 0.25, 0.75].map(|q| ratios[((pairs - 1) as f64 * q).round() as usize])
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mode = args.next();
    let pairs: usize = args.next().and_then(|n| n.parse().ok()).unwrap_or(40).max(1);
    let [median, low, high] = match mode.as_deref() {
        Some("paired") => {
            let scenario = Scenario::load(&default_scenario()).expect("the default scenario loads");
            paired(pairs, |sign_off| simulation(&scenario, sign_off))
        }
        Some("job") => {
            let out = std::env::temp_dir().join(format!("pipearm-signoff-cost-{}", std::process::id()));
            let ratios = paired(pairs, |sign_off| job(&out, sign_off));
            std::fs::remove_dir_all(&out).ok();
            ratios
        }
        _ => {
            let scenario = Scenario::load(&default_scenario()).expect("the default scenario loads");
            let sign_off = mode.as_deref() != Some("without");
            let options = RunOptions { sign_off, ..RunOptions::default() };
            let run = || run_with(&scenario.model, &options).expect("the default scenario runs");
            // Inside rayon's pool the readings are completed on the step's thread, as in a sweep.
            let (summary, _) = match mode.as_deref() {
                Some("here") => rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a pool").install(run),
                _ => run(),
            };
            let peak = summary.sign_off.map(|s| s.stress.peak_stress_pa);
            println!("sign-off {sign_off}: {} steps, peak stress {peak:?} Pa", summary.steps);
            return;
        }
    };
    println!("with / without the sign-off over {pairs} pairs: median {median:.3}, quartiles {low:.3}–{high:.3}");
}
