//! The front doors under property tests: the scenario TOML, the URDF, the measured CSV and the
//! drive table CSV readers, fed shipped files mutated at random (a number replaced by any other,
//! a line dropped or duplicated, a word misspelt, the text cut short, bytes inserted) and text of
//! their own alphabet, give a result or an error that names the file — never a panic. A scenario
//! that fails to load makes `pipearm run` fail and write nothing.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::Command;

use pipearm::drive::MotionProfile;
use pipearm::measured;
use pipearm::robot::load_robot;
use pipearm::scenario::Scenario;
use proptest::prelude::*;
use proptest::strategy::ValueTree;

/// How a shipped file is changed.
#[derive(Debug, Clone)]
enum Mutation {
    /// The k-th number of the text becomes this text.
    Number(usize, String),
    /// The k-th line is dropped.
    DropLine(usize),
    /// The k-th line is written twice.
    DoubleLine(usize),
    /// The k-th word loses its last character.
    Misspell(usize),
    /// The text ends after this fraction of it.
    Cut(f64),
    /// These characters go in at this fraction of the text.
    Insert(f64, String),
}

fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| format!("{x:e}")),
        (-1e3..1e3f64).prop_map(|x| format!("{x}")),
        Just("0".to_string()),
        Just("-1".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("1e400".to_string()),
        Just("\"\"".to_string()),
        Just("".to_string()),
        (0u64..u64::MAX).prop_map(|n| n.to_string()),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (0usize..400, number_text()).prop_map(|(k, t)| Mutation::Number(k, t)),
        1 => (0usize..200).prop_map(Mutation::DropLine),
        1 => (0usize..200).prop_map(Mutation::DoubleLine),
        1 => (0usize..600).prop_map(Mutation::Misspell),
        1 => (0.0..1.0f64).prop_map(Mutation::Cut),
        1 => (0.0..1.0f64, "[\\[\\]{}=\",<>/#.\\-0-9a-z \\n]{1,6}").prop_map(|(at, s)| Mutation::Insert(at, s)),
    ]
}

fn char_boundary(text: &str, fraction: f64) -> usize {
    let mut at = ((text.len() as f64) * fraction) as usize;
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

fn mutate(text: &str, mutations: &[Mutation]) -> String {
    mutations.iter().fold(text.to_string(), |text, m| match m {
        Mutation::Number(k, new) => {
            let numbers = regex::Regex::new(r"[-+]?\d+(\.\d+)?([eE][-+]?\d+)?").unwrap();
            match numbers.find_iter(&text).nth(k % numbers.find_iter(&text).count().max(1)) {
                Some(m) => format!("{}{new}{}", &text[..m.start()], &text[m.end()..]),
                None => text,
            }
        }
        Mutation::DropLine(k) | Mutation::DoubleLine(k) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return text;
            }
            let k = k % lines.len();
            if matches!(m, Mutation::DropLine(_)) {
                lines.remove(k);
            } else {
                lines.insert(k, lines[k]);
            }
            lines.join("\n")
        }
        Mutation::Misspell(k) => {
            let words = regex::Regex::new(r"[A-Za-z_]{3,}").unwrap();
            let count = words.find_iter(&text).count().max(1);
            match words.find_iter(&text).nth(k % count) {
                Some(m) => format!("{}{}", &text[..m.end() - 1], &text[m.end()..]),
                None => text,
            }
        }
        Mutation::Cut(f) => text[..char_boundary(&text, *f)].to_string(),
        Mutation::Insert(f, s) => {
            let at = char_boundary(&text, *f);
            format!("{}{s}{}", &text[..at], &text[at..])
        }
    })
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch project holding the shipped robots and tables, for mutated scenarios to name.
fn project(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-front-doors-{tag}-{}", std::process::id()));
    if !dir.join("robots").exists() {
        std::fs::create_dir_all(dir.join("robots")).unwrap();
        std::fs::create_dir_all(dir.join("scenarios")).unwrap();
        for entry in std::fs::read_dir(root().join("robots")).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(&path, dir.join("robots").join(path.file_name().unwrap())).unwrap();
            }
        }
        std::fs::copy(root().join("scenarios/spin_up.csv"), dir.join("scenarios/spin_up.csv")).unwrap();
    }
    dir
}

fn shipped(relative: &str) -> String {
    std::fs::read_to_string(root().join(relative)).unwrap()
}

/// `read` on `text` written to `path` returns, or errs naming the file; a panic fails the case.
fn holds<T, E: std::fmt::Display>(
    path: &Path,
    text: &str,
    read: impl FnOnce(&Path) -> Result<T, E>,
) -> Result<(), String> {
    std::fs::write(path, text).unwrap();
    match catch_unwind(AssertUnwindSafe(|| read(path))) {
        Ok(Ok(_)) => Ok(()),
        Ok(Err(e)) => {
            let message = e.to_string();
            let file = path.file_name().unwrap().to_str().unwrap();
            if message.contains(file) { Ok(()) } else { Err(format!("the error does not name the file: {message}")) }
        }
        Err(_) => Err(format!("panicked on:\n{text}")),
    }
}

const SCENARIOS: &[&str] = &[
    "scenarios/default.toml",
    "scenarios/hydraulic.toml",
    "scenarios/servo.toml",
    "scenarios/spin_up.toml",
    "scenarios/lab.toml",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_mutated_scenario_loads_or_says_why(which in 0..SCENARIOS.len(), mutations in prop::collection::vec(mutation(), 1..4)) {
        let dir = project("scenario");
        let text = mutate(&shipped(SCENARIOS[which]), &mutations);
        let path = dir.join("scenarios").join(format!("mutated-{which}.toml"));
        holds(&path, &text, Scenario::load).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn a_mutated_urdf_loads_or_says_why(which in 0..5usize, mutations in prop::collection::vec(mutation(), 1..4)) {
        let dir = project("urdf");
        let file = ["robots/pipe_arm.urdf", "robots/lab_arm1.urdf", "robots/spin_up_beam.urdf", "robots/pipe_arm_twin.urdf", "robots/pipe_arm_head.urdf"][which];
        let text = mutate(&shipped(file), &mutations);
        holds(&dir.join("robots").join(format!("mutated-{which}.urdf")), &text, load_robot).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn a_mutated_measured_csv_reads_or_says_why(mutations in prop::collection::vec(mutation(), 1..4)) {
        let dir = project("measured");
        let text: String = shipped("measurements/rig.csv").lines().take(60).collect::<Vec<_>>().join("\n");
        let text = mutate(&text, &mutations);
        holds(&dir.join("mutated.csv"), &text, measured::read).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn a_mutated_drive_table_reads_or_says_why(mutations in prop::collection::vec(mutation(), 1..4)) {
        let dir = project("table");
        let text = mutate(&shipped("scenarios/spin_up.csv"), &mutations);
        holds(&dir.join("mutated.csv"), &text, |p| MotionProfile::from_csv(p, 0.0)).map_err(TestCaseError::fail)?;
    }

    #[test]
    fn any_text_in_a_reader_gives_a_result_or_an_error(text in "[\\[\\]{}=\",<>/#.\\-0-9a-z_ \\n]{0,300}") {
        let dir = project("any");
        holds(&dir.join("any.toml"), &text, Scenario::load).map_err(TestCaseError::fail)?;
        holds(&dir.join("any.urdf"), &text, load_robot).map_err(TestCaseError::fail)?;
        holds(&dir.join("any.csv"), &text, measured::read).map_err(TestCaseError::fail)?;
        holds(&dir.join("any-table.csv"), &text, |p| MotionProfile::from_csv(p, 0.0)).map_err(TestCaseError::fail)?;
    }
}

/// Mutated scenarios that do not load make `pipearm run` fail, naming the file, and write nothing.
#[test]
fn a_scenario_that_fails_to_load_writes_nothing() {
    let dir = project("cli");
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = prop::collection::vec(mutation(), 1..4);
    let mut refused = 0;
    for case in 0..200 {
        let mutations = strategy.new_tree(&mut runner).unwrap().current();
        let text = mutate(&shipped("scenarios/default.toml"), &mutations);
        let path = dir.join("scenarios").join(format!("cli-{case}.toml"));
        std::fs::write(&path, &text).unwrap();
        if Scenario::load(&path).is_ok() {
            continue;
        }
        let out = dir.join(format!("out-{case}"));
        let run = Command::new(env!("CARGO_BIN_EXE_pipearm"))
            .args(["run", path.to_str().unwrap(), "--csv", "--out", out.to_str().unwrap()])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{text}");
        assert!(stderr.contains(&format!("cli-{case}.toml")) && !stderr.contains("panicked"), "{stderr}");
        let written = std::fs::read_dir(&out).map(|d| d.count()).unwrap_or(0);
        assert_eq!(written, 0, "a refused scenario wrote {written} files: {stderr}");
        refused += 1;
        if refused == 12 {
            break;
        }
    }
    assert_eq!(refused, 12, "the mutations should break the scenario often");
}
