//! Cost of one time step of the default arm at each fidelity (generalized-α, prescribed hub).
//!
//! `cargo bench --bench step`; the figures are quoted in docs/model.md.

use std::path::Path;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use pipearm::arm::{ArmSimulation, Fidelity};
use pipearm::scenario::Scenario;

fn step_cost(c: &mut Criterion) {
    let scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    let mut group = c.benchmark_group("arm_step");
    let fidelities = [
        Fidelity::Rigid,
        Fidelity::Modal { modes: 1 },
        Fidelity::Modal { modes: 4 },
        Fidelity::Modal { modes: 8 },
        Fidelity::Fe,
    ];
    for fidelity in fidelities {
        let arm = scenario.arm_model(fidelity).unwrap();
        let mut sim = ArmSimulation::new(arm, scenario.hub_drive(), scenario.spec.integrator).unwrap();
        // Start mid-lift, where every term of the equations is active.
        sim.run_until(5.0, scenario.spec.time.step_s, |_| ()).unwrap();
        group.bench_function(BenchmarkId::from_parameter(fidelity), |b| {
            b.iter(|| sim.step(scenario.spec.time.step_s).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
