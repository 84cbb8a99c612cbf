//! The default run with or without its sign-off, to count the sign-off's instructions in
//! process (docs/sign-off.md, "Cost"):
//! `valgrind --tool=callgrind target/release/examples/signoff_cost with|without`.

use std::path::Path;

use pipearm::run::{RunOptions, run_with};
use pipearm::scenario::Scenario;

fn main() {
    let sign_off = std::env::args().nth(1).as_deref() != Some("without");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let scenario = Scenario::load(&path).expect("the default scenario loads");
    let options = RunOptions { sign_off, ..RunOptions::default() };
    let (summary, _) = run_with(&scenario.model, &options).expect("the default scenario runs");
    let peak = summary.sign_off.map(|s| s.stress.peak_stress_pa);
    println!("sign-off {sign_off}: {} steps, peak stress {peak:?} Pa", summary.steps);
}
