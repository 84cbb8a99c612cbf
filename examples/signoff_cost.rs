//! The default run with or without its sign-off, to count the sign-off's instructions in
//! process (docs/sign-off.md, "Cost"):
//! `valgrind --tool=callgrind target/release/examples/signoff_cost with|without`;
//! or to time it: `target/release/examples/signoff_cost paired 40` runs the two alternately 40
//! times each in one process and prints the median of the paired ratios (with / without).

use std::path::Path;
use std::time::Instant;

use pipearm::model::Model;
use pipearm::run::{RunOptions, run_with};
use pipearm::scenario::Scenario;

/// The allocator `pipearm` itself runs on (src/main.rs).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn timed(model: &Model, sign_off: bool) -> f64 {
    let options = RunOptions { sign_off, ..RunOptions::default() };
    let started = Instant::now();
    run_with(model, &options).expect("the default scenario runs");
    started.elapsed().as_secs_f64()
}

fn main() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let scenario = Scenario::load(&path).expect("the default scenario loads");
    let mut args = std::env::args().skip(1);
    let mode = args.next();
    if mode.as_deref() == Some("paired") {
        let pairs: usize = args.next().and_then(|n| n.parse().ok()).unwrap_or(40).max(1);
        // Each pair in turn order, so that neither side always runs on the other's leftovers.
        let mut ratios: Vec<f64> = (0..pairs)
            .map(|i| {
                let with_first = i % 2 == 0;
                let (first, second) = (timed(&scenario.model, with_first), timed(&scenario.model, !with_first));
                let (with, without) = if with_first { (first, second) } else { (second, first) };
                with / without
            })
            .collect();
        ratios.sort_by(f64::total_cmp);
        let quartile = |q: f64| ratios[((pairs - 1) as f64 * q).round() as usize];
        println!(
            "with / without the sign-off over {pairs} pairs: median {:.3}, quartiles {:.3}–{:.3}",
            quartile(0.5),
            quartile(0.25),
            quartile(0.75)
        );
        return;
    }
    let sign_off = mode.as_deref() != Some("without");
    let options = RunOptions { sign_off, ..RunOptions::default() };
    let (summary, _) = run_with(&scenario.model, &options).expect("the default scenario runs");
    let peak = summary.sign_off.map(|s| s.stress.peak_stress_pa);
    println!("sign-off {sign_off}: {} steps, peak stress {peak:?} Pa", summary.steps);
}
