//! Cost of one time step: the arm alone at each fidelity, and the whole scene (rapier world,
//! pads) with each contact method; and of the speed target's whole run: the default scene read,
//! simulated for its 20 s and recorded, as `pipearm run` does it; and the actuated scenes'
//! whole runs against the same scenes with the ideal drive (`-- actuated_run`); and the default
//! scene with its string as `auto` models it against the string lumped (`-- string_run`); and the
//! default run with and without its sign-off (`-- sign_off`).
//!
//! `cargo bench --bench step` (one core: `taskset -c 0 cargo bench --bench step -- default_run`);
//! the figures are quoted in docs/model.md, docs/accuracy.md and docs/performance.md.

use std::path::Path;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use pipearm::arm::{ArmSimulation, Fidelity};
use pipearm::contact::ForceLaw;
use pipearm::integrate::IntegratorKind;
use pipearm::model::{ContactMethod, Detection, Model};
use pipearm::scenario::Scenario;
use pipearm::scene::Scene;

/// The default scene under generalized-α: stable for every fidelity at the scene's step (its own
/// RK4 is not, for eight modes or the FE arm).
fn default_scenario() -> Model {
    let mut s = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model;
    s.integrator = IntegratorKind::default();
    s
}

const FIDELITIES: [Fidelity; 7] = [
    Fidelity::Rigid,
    Fidelity::Modal { modes: 1 },
    Fidelity::Modal { modes: 2 },
    Fidelity::Modal { modes: 3 },
    Fidelity::Modal { modes: 4 },
    Fidelity::Modal { modes: 8 },
    Fidelity::Fe,
];

fn arm_step(c: &mut Criterion) {
    let scenario = default_scenario();
    let mut group = c.benchmark_group("arm_step");
    for fidelity in FIDELITIES {
        let arm = scenario.arm_model(fidelity).unwrap();
        let mut sim = ArmSimulation::new(arm, scenario.hub_drive(), scenario.integrator).unwrap();
        // Start mid-lift, where every term of the equations is active.
        sim.run_until(5.0, scenario.time.step_s, |_| ()).unwrap();
        group.bench_function(BenchmarkId::from_parameter(fidelity), |b| {
            b.iter(|| sim.step(scenario.time.step_s).unwrap())
        });
    }
    // The shipped default: RK4 on three modes.
    let arm = scenario.arm_model(Fidelity::Modal { modes: 3 }).unwrap();
    let mut sim = ArmSimulation::new(arm, scenario.hub_drive(), IntegratorKind::Rk4).unwrap();
    sim.run_until(5.0, scenario.time.step_s, |_| ()).unwrap();
    group.bench_function("modal(3) rk4", |b| b.iter(|| sim.step(scenario.time.step_s).unwrap()));
    group.finish();
}

/// One step of the whole scene with the arm at its stop, 0.2 mm from its pad: compliant at each
/// fidelity on the pad-face path (the scene's `auto`), compliant through rapier's collision
/// pipeline, and the rapier method (a rapier step every step).
fn scene_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene_step_at_the_stop");
    let base = default_scenario();
    let mut cases: Vec<(String, Model, Fidelity)> = [Fidelity::Rigid, Fidelity::Modal { modes: 3 }, Fidelity::Fe]
        .into_iter()
        .map(|f| (format!("compliant {f}"), base.clone(), f))
        .collect();
    let mut pipeline = base.clone();
    pipeline.contact.detection = Detection::Pipeline;
    cases.push(("compliant modal(3) pipeline".into(), pipeline, Fidelity::Modal { modes: 3 }));
    let mut rapier = base.clone();
    rapier.contact.method = ContactMethod::Rapier;
    rapier.dampeners[0].law = ForceLaw::Linear { stiffness_n_m: 7.5e6, damping_n_s_m: 2.0e3 };
    cases.push(("rapier modal(3)".into(), rapier, Fidelity::Modal { modes: 3 }));
    for (name, scenario, fidelity) in cases {
        let h = scenario.time.step_s;
        let mut scene = Scene::with_fidelity(&scenario, fidelity).unwrap();
        // Up to the stop: from here on the arm stays within reach of its pad.
        while scene.arm.time_s() < 14.9 {
            scene.step(h).unwrap();
        }
        group.bench_function(BenchmarkId::from_parameter(name), |b| b.iter(|| scene.step(h).unwrap()));
    }
    group.finish();
}

/// The speed target (docs/performance.md): `pipearm run` on the default scene in-process, from
/// reading the scenario to the recording and summary written (20 s simulated, so 1000× real time
/// is 20 ms a run).
fn default_run(c: &mut Criterion) {
    use pipearm::run::{RunOptions, run_with};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let out = std::env::temp_dir().join(format!("pipearm-bench-{}", std::process::id()));
    let mut group = c.benchmark_group("default_run");
    group.sample_size(40);
    group.bench_function("with recording", |b| b.iter(|| run_and_record(&Scenario::load(&path).unwrap(), &out)));
    group.bench_function("without recording", |b| {
        b.iter(|| run_with(&Scenario::load(&path).unwrap().model, &RunOptions::default()).unwrap())
    });
    group.finish();
    std::fs::remove_dir_all(&out).ok();
}

/// The default run (without recording) with its contacts found by rapier's collision pipeline
/// against the pad-face path `auto` picks for it: the pipeline's price, timed in one run.
fn detection_run(c: &mut Criterion) {
    use pipearm::run::{RunOptions, run_with};
    let mut group = c.benchmark_group("detection_run");
    group.sample_size(40);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    for detection in [Detection::PadFace, Detection::Pipeline] {
        let mut model = Scenario::load(&path).unwrap().model;
        model.contact.detection = detection;
        group.bench_function(detection.name(), |b| b.iter(|| run_with(&model, &RunOptions::default()).unwrap()));
    }
    group.finish();
}

/// The actuated scenes against their ideal twins (the same file without its `[actuator]` table),
/// each in-process from reading the scenario to the recording and summary written.
fn actuated_run(c: &mut Criterion) {
    use pipearm::scenario::ScenarioSpec;
    let out = std::env::temp_dir().join(format!("pipearm-bench-actuated-{}", std::process::id()));
    let mut group = c.benchmark_group("actuated_run");
    group.sample_size(20);
    for name in ["hydraulic", "servo"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"));
        let load = |ideal: bool| {
            if !ideal {
                return Scenario::load(&path).unwrap();
            }
            let mut table: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
            table.remove("actuator");
            let spec: ScenarioSpec = table.try_into().unwrap();
            Scenario::from_spec(&path, spec).unwrap()
        };
        for ideal in [false, true] {
            let label = if ideal { format!("{name}, ideal drive") } else { name.to_string() };
            group.bench_function(label, |b| b.iter(|| run_and_record(&load(ideal), &out)));
        }
    }
    group.finish();
    std::fs::remove_dir_all(&out).ok();
}

/// The default scene with the string `auto` models (a beam of its own) against the same scene
/// with the string lumped (`rigid`), each in-process from reading the scenario to the recording
/// and summary written: the string's price (`-- string_run`; goal ≤ 1.5×).
fn string_run(c: &mut Criterion) {
    use pipearm::scenario::{ModelSpec, PayloadSpec};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let out = std::env::temp_dir().join(format!("pipearm-bench-string-{}", std::process::id()));
    let mut group = c.benchmark_group("string_run");
    group.sample_size(40);
    for (label, string) in [("auto", ModelSpec::default()), ("rigid", ModelSpec::Rigid)] {
        let load = || {
            let mut spec = Scenario::load(&path).unwrap().spec;
            if let PayloadSpec::String { model, .. } = &mut spec.payload {
                *model = string;
            }
            Scenario::from_spec(&path, spec).unwrap()
        };
        group.bench_function(label, |b| b.iter(|| run_and_record(&load(), &out)));
    }
    group.finish();
    std::fs::remove_dir_all(&out).ok();
}

/// What `pipearm run` does after reading the scenario: the run with its 3D frames, then its
/// recording and summary written to `out/<name>.{rrd, summary.json}`.
fn run_and_record(scenario: &Scenario, out: &Path) {
    use pipearm::record::{write_recording, write_summary};
    use pipearm::run::{RunOptions, run_with};
    let options = RunOptions { capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_with(&scenario.model, &options).unwrap();
    let name = &scenario.model.name;
    write_recording(&out.join(format!("{name}.rrd")), &summary, &series).unwrap();
    write_summary(&out.join(format!("{name}.summary.json")), &summary).unwrap();
}

/// The default run in process with the sign-off (stress along the arm, pin loads, rainflow) and
/// without it, the same build (`-- sign_off`; goal ≤ 1.15×, docs/sign-off.md).
fn sign_off(c: &mut Criterion) {
    use pipearm::run::{RunOptions, run_with};
    let model = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model;
    let mut group = c.benchmark_group("sign_off");
    group.sample_size(40);
    for (label, sign_off) in [("with", true), ("without", false)] {
        let options = RunOptions { sign_off, ..RunOptions::default() };
        group.bench_function(label, |b| b.iter(|| run_with(&model, &options).unwrap()));
    }
    group.finish();
}

criterion_group!(benches, arm_step, scene_step, default_run, detection_run, actuated_run, string_run, sign_off);
criterion_main!(benches);
