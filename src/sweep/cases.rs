//! Case files: `DIR/cases/<index>-<hash>.json` = `{index, hash, values, summary}`, one per run
//! case, written whole (temporary name, then rename); a case whose run diverged has `summary`
//! null and `diverged: {t_s, what, advice}` instead (the guard's verdict is a result of the
//! sweep, not a failure of it). A case whose file exists with its hash is current and is not
//! run again.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use serde::Serialize;

use super::plan::{Case, Plan};
use super::shard::Shard;
use super::{SweepError, io_error, write_atomic};
use crate::compile::Compiler;
use crate::run::{RunOptions, RunSummary, run_reusing};
use crate::scenario::Scenario;
use crate::scene::SceneError;

/// What one shard has to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Work {
    /// Indices of the shard's cases to run.
    pub todo: Vec<usize>,
    /// How many of the shard's cases are current already.
    pub current: usize,
}

/// A case file as written.
#[derive(Serialize)]
struct CaseFile<'a> {
    index: usize,
    hash: &'a str,
    values: &'a std::collections::BTreeMap<String, toml::Value>,
    summary: Option<&'a RunSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    diverged: Option<Diverged<'a>>,
}

/// Where and why a case's run was stopped, and the guard's advice.
#[derive(Serialize)]
struct Diverged<'a> {
    t_s: f64,
    what: &'a str,
    advice: &'a str,
}

/// The folder of the case files.
pub fn cases_dir(dir: &Path) -> PathBuf {
    dir.join("cases")
}

/// The file of `case` under `dir`.
pub fn case_path(dir: &Path, case: &Case) -> PathBuf {
    cases_dir(dir).join(format!("{}-{}.json", case.index, case.hash))
}

/// Whether `case`'s file exists under `dir` with its index and hash.
pub fn is_current(dir: &Path, case: &Case) -> bool {
    let Ok(text) = std::fs::read_to_string(case_path(dir, case)) else { return false };
    serde_json::from_str::<serde_json::Value>(&text)
        .is_ok_and(|v| v["index"].as_u64() == Some(case.index as u64) && v["hash"].as_str() == Some(case.hash.as_str()))
}

/// Writes `DIR/plan.json`, removes the shard's stale case files (same index, other hash) and
/// lists the shard's cases that are not current.
pub fn prepare(plan: &Plan, dir: &Path, shard: Shard) -> Result<Work, SweepError> {
    let cases = cases_dir(dir);
    std::fs::create_dir_all(&cases).map_err(io_error(&cases))?;
    let json = serde_json::to_string_pretty(plan).expect("a plan serialises") + "\n";
    write_atomic(&dir.join("plan.json"), json.as_bytes(), &format!("shard{}", shard.index))?;
    remove_stale(plan, &cases, shard)?;
    let (current, todo): (Vec<&Case>, Vec<&Case>) =
        plan.cases.iter().filter(|c| shard.contains(c.index)).partition(|c| is_current(dir, c));
    Ok(Work { todo: todo.iter().map(|c| c.index).collect(), current: current.len() })
}

fn remove_stale(plan: &Plan, cases: &Path, shard: Shard) -> Result<(), SweepError> {
    for entry in std::fs::read_dir(cases).map_err(io_error(cases))? {
        let path = entry.map_err(io_error(cases))?.path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let Some((index, hash)) = name.strip_suffix(".json").and_then(|n| n.split_once('-')) else { continue };
        let Ok(index) = index.parse::<usize>() else { continue };
        let stale = plan.cases.get(index).is_some_and(|c| c.hash != hash);
        if stale && shard.contains(index) {
            std::fs::remove_file(&path).map_err(io_error(&path))?;
        }
    }
    Ok(())
}

/// Runs the compile's checks ([`Scenario::check_compiled`]) on `shard`'s cases of `plan` (their
/// `scenarios` by index) on the workers of `pool`: a case its compile refuses fails the sweep
/// before any case is written, the lowest such case named. Nothing compiled is kept (the runs
/// take what their compiler kept).
pub fn check_compiled(
    plan: &Plan,
    scenarios: &[Scenario],
    shard: Shard,
    pool: &rayon::ThreadPool,
) -> Result<(), SweepError> {
    use rayon::prelude::*;
    let keys = plan.keys();
    let checked: Vec<Result<(), SweepError>> = pool.install(|| {
        scenarios
            .par_iter()
            .zip(&plan.cases)
            .filter(|(_, case)| shard.contains(case.index))
            .map(|(scenario, case)| {
                scenario.check_compiled().map_err(|error| SweepError::Case {
                    index: case.index,
                    values: case.describe(&keys),
                    error: Box::new(error),
                })
            })
            .collect()
    });
    checked.into_iter().collect()
}

/// Runs the cases `todo` of `plan` (their `scenarios` by index) on the workers of `pool`,
/// writing each case file as it finishes and calling `done` after it. The
/// longest cases go first and each worker takes the next as it frees up, so the workers finish
/// together to within one of the shortest cases. Stops at the first failure and returns it.
pub fn run_cases(
    plan: &Plan,
    scenarios: &[Scenario],
    dir: &Path,
    todo: &[usize],
    pool: &rayon::ThreadPool,
    done: &(dyn Fn(&Case) + Sync),
) -> Result<(), SweepError> {
    let queue = longest_first(todo, scenarios);
    let next = AtomicUsize::new(0);
    let failure: Mutex<Option<SweepError>> = Mutex::new(None);
    // The cases vary a few keys: most share their beam and reduced arm, compiled once through
    // the compiler their checks shared (`Scenario::compiler`).
    pool.broadcast(|_| {
        while let Some(&i) = queue.get(next.fetch_add(1, Ordering::Relaxed)) {
            match run_case(plan, &plan.cases[i], &scenarios[i], dir, &scenarios[i].compiler) {
                Ok(()) => done(&plan.cases[i]),
                Err(e) => {
                    failure.lock().expect("no worker panics holding it").get_or_insert(e);
                    next.store(queue.len(), Ordering::Relaxed);
                }
            }
        }
    });
    failure.into_inner().expect("no worker panics holding it").map_or(Ok(()), Err)
}

/// `todo` ordered by the steps each case takes (its cost), most first; ties by index.
fn longest_first(todo: &[usize], scenarios: &[Scenario]) -> Vec<usize> {
    let steps = |i: usize| scenarios[i].model.duration_s() / scenarios[i].model.time.step_s;
    let mut queue = todo.to_vec();
    queue.sort_by(|&a, &b| steps(b).total_cmp(&steps(a)).then(a.cmp(&b)));
    queue
}

fn run_case(plan: &Plan, case: &Case, scenario: &Scenario, dir: &Path, compiler: &Compiler) -> Result<(), SweepError> {
    let file =
        |summary, diverged| CaseFile { index: case.index, hash: &case.hash, values: &case.values, summary, diverged };
    let json = match run_reusing(&scenario.model, &RunOptions::default(), compiler) {
        Ok((summary, _)) => serde_json::to_string_pretty(&file(Some(&summary), None)),
        Err(SceneError::Diverged { t_s, what, advice }) => {
            serde_json::to_string_pretty(&file(None, Some(Diverged { t_s, what: &what, advice: &advice })))
        }
        Err(source) => {
            return Err(SweepError::Run {
                index: case.index,
                values: case.describe(&plan.keys()),
                error: Box::new(source),
            });
        }
    }
    .expect("a summary serialises")
        + "\n";
    write_atomic(&case_path(dir, case), json.as_bytes(), "case")
}
