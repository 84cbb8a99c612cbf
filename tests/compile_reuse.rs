//! Runs that share a `Compiler` take the beam, the reduced arm and `auto`'s choice an earlier
//! run compiled where their keys do not touch them, compile their own where they do, and give
//! the numbers a run compiling everything itself gives, to the bit.

use std::path::Path;

use pipearm::compile::{Compilations, Compiler};
use pipearm::model::Model;
use pipearm::run::{RunOptions, RunSummary, run_reusing, run_with};
use pipearm::scenario::Scenario;

fn default_model() -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model
}

/// Everything a run reports but its timing, as JSON.
fn numbers(summary: &RunSummary) -> serde_json::Value {
    let mut json = serde_json::to_value(summary).unwrap();
    json.as_object_mut().unwrap().retain(|key, _| !key.contains("wall"));
    json
}

#[test]
fn runs_share_what_their_keys_leave_alone_and_match_runs_that_compile_it_themselves() {
    let base = default_model();
    let mut wider_gap = base.clone();
    wider_gap.dampeners[0].gap_m *= 2.0;
    let mut damped = base.clone();
    damped.robot.arm.damping_ratios = vec![0.03];
    let mut heavier_gripper = base.clone();
    heavier_gripper.robot.carried[0].mass_kg *= 1.5;
    let mut judged_stricter = base.clone();
    judged_stricter.checks.stress_factor = 1.5;
    let options = RunOptions::default();
    let compiler = Compiler::new();
    let mut expected = Compilations { beams: 0, arms: 0, choices: 0 };
    // The default holds its string flexibly: auto compiles the beam with a one-mode string to
    // choose, then that beam keeping the modes it chose; then the reduced arm. The arm's choice
    // reads the pads and the damping (the band, the bound), not the sign-off's factor.
    for (name, model, new_beams, new_arms, new_choices) in [
        ("default", &base, 2, 1, 1),
        ("the pad's gap doubled (the pad is no part of the beam)", &wider_gap, 0, 0, 1),
        ("damping 3 % (the beam's modes stand; the arm's damping does not)", &damped, 0, 1, 1),
        ("the gripper 50 % heavier (a mass on the beam)", &heavier_gripper, 2, 1, 1),
        ("default again", &base, 0, 0, 0),
        ("the sign-off's stress factor 1.5 (no part of the arm or its choice)", &judged_stricter, 0, 0, 0),
    ] {
        let (reusing, _) = run_reusing(model, &options, &compiler).unwrap();
        let (alone, _) = run_with(model, &options).unwrap();
        assert_eq!(numbers(&reusing), numbers(&alone), "{name}: the numbers moved");
        expected.beams += new_beams;
        expected.arms += new_arms;
        expected.choices += new_choices;
        assert_eq!(compiler.compilations(), expected, "{name}");
    }
}

#[test]
fn reading_a_scenario_compiles_nothing_and_its_run_takes_what_its_compile_checked() {
    // Reading solves no eigenproblem and builds no arm, even where the shaper is tuned to the
    // arm's modes or a closed loop must be checked; compiling checks the loop on the arm the run
    // takes, and the run compiles none of it again: its numbers are those of a run that compiles
    // it itself.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let none = Compilations { beams: 0, arms: 0, choices: 0 };
    for name in ["hydraulic", "servo", "default"] {
        let path = root.join(format!("scenarios/{name}.toml"));
        let mut document = pipearm::sweep::plan::read_document(&path).unwrap();
        if name == "default" {
            pipearm::sweep::plan::set_key(&mut document, "drive.shaper", toml::Value::String("zvd".into())).unwrap();
        }
        let scenario = Scenario::from_spec(&path, pipearm::sweep::plan::spec_of(&path, document).unwrap()).unwrap();
        assert_eq!(scenario.compiler.compilations(), none, "{name}: reading compiled");
        let compiled = scenario.compile(None).unwrap();
        let checked = scenario.compiler.compilations();
        assert!(checked.beams >= 1 && checked.arms >= 1, "{name}: the compile compiled {checked:?}");
        let (shared, _) = pipearm::run::run_compiled(&compiled, &RunOptions::default());
        assert_eq!(scenario.compiler.compilations(), checked, "{name}: the run compiled again");
        let (own, _) = run_with(&scenario.model, &RunOptions::default()).unwrap();
        assert_eq!(numbers(&shared.unwrap()), numbers(&own), "{name}");
    }
}

/// Compiled once, stepped twice: a `CompiledModel` is not changed by the runs it starts, each of
/// which steps a fresh scene into a fresh series, equal to the bit to a run that compiles its own.
#[test]
fn a_compiled_model_steps_the_same_run_every_time() {
    use pipearm::run::{CompiledModel, run_compiled};
    let model = default_model();
    let compiler = Compiler::new();
    let compiled = CompiledModel::new(&model, None, &compiler).unwrap();
    let options = RunOptions::default();
    let (first, first_series) = run_compiled(&compiled, &options);
    let (second, second_series) = run_compiled(&compiled, &options);
    let (alone, alone_series) = run_with(&model, &options).unwrap();
    let (first, second) = (first.unwrap(), second.unwrap());
    assert_eq!(numbers(&first), numbers(&second));
    assert_eq!(numbers(&first), numbers(&alone));
    assert!(first_series == second_series && first_series == alone_series, "the series differ");
    // The default's flexible string: two beams (auto's choice, then the run's) and one arm,
    // for both runs.
    assert_eq!(compiler.compilations(), Compilations { beams: 2, arms: 1, choices: 1 }, "compiled once");
}
