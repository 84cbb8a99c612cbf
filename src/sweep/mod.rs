//! Parameter sweeps: one scenario run over the Cartesian product of varied keys, in parallel,
//! sharded for batch engines (Slurm job arrays, Kubernetes Indexed Jobs), with a results table
//! and a chart of peak contact force against string weight. `pipearm sweep`; docs/sweeps.md.
//!
//! The flow: `--vary` arguments ([`vary`]) → a checked [`plan::Plan`] (every case's scenario
//! built and validated before anything is written) → the cases of one [`shard`] run and stored
//! one file each ([`cases`], skipping those already current) → [`merge`] reads the plan and
//! every case file ([`row`]: its scalars by dotted path) and writes the table ([`table`]) and
//! the chart ([`chart`]). [`compare`] draws several finished sweeps on one chart. Results hold nothing thread- or time-dependent, so a sharded sweep merges
//! to the same bytes as one run in one process.

pub mod cases;
pub mod chart;
pub mod pipes;
pub mod plan;
pub mod row;
pub mod shard;
pub mod table;
pub mod vary;

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::scenario::ScenarioError;
use crate::scene::SceneError;

pub use cases::{Work, check_compiled, prepare, run_cases};
pub use plan::{Case, Plan};
pub use shard::Shard;
pub use table::{Merged, merge, read_results};
pub use vary::Vary;

/// The forms a `--vary` argument may take, for error messages.
pub const VARY_FORMS: &str = "KEY=V1,V2,... (TOML values: 10, 0.5, true, \"2-7/8\" or bare text) or KEY=A..B:STEP \
     (numbers, B included), KEY a dotted path into the scenario such as drive.duration_s, payload.size or \
     dampeners.0.law.stiffness";

/// Errors planning, running or merging a sweep; each names the argument, key, case or file
/// and says the cause itself (the fields are not `source`s, so a report does not repeat them).
#[derive(Debug, Error)]
pub enum SweepError {
    /// A `--vary` argument that does not parse.
    #[error("--vary `{arg}`: {message}; allowed forms: {VARY_FORMS}")]
    Vary { arg: String, message: String },
    /// A varied key that does not lead anywhere in the scenario.
    #[error("--vary key `{key}`: {message}")]
    Key { key: String, message: String },
    /// Reading the base scenario.
    #[error(transparent)]
    Scenario(Box<ScenarioError>),
    /// A case whose scenario does not parse or validate.
    #[error("case {index} ({values}): {error}")]
    Case { index: usize, values: String, error: Box<ScenarioError> },
    /// A case whose run failed.
    #[error("case {index} ({values}): running: {error}")]
    Run { index: usize, values: String, error: Box<SceneError> },
    /// A bad shard selection.
    #[error("shard: {0}")]
    Shard(String),
    /// Reading or writing a file.
    #[error("{path}: {error}")]
    Io { path: PathBuf, error: std::io::Error },
    /// A plan or case file that is not what a sweep writes.
    #[error("{path}: {message}")]
    Format { path: PathBuf, message: String },
    /// Case files missing at a merge.
    #[error("{dir}: {count} case(s) not run yet: {missing}; run their shards, then merge again")]
    Missing { dir: PathBuf, count: usize, missing: String },
    /// Drawing the chart.
    #[error("chart {path}: {message}")]
    Chart { path: PathBuf, message: String },
    /// Building the worker threads.
    #[error("threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
}

/// A sweep as asked for on the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The base scenario file.
    pub scenario: PathBuf,
    /// The varied keys.
    pub vary: Vec<Vary>,
    /// Output folder.
    pub out: PathBuf,
    /// Worker threads (rayon's default if `None`).
    pub threads: Option<usize>,
    /// The shard to run ([`Shard::ALL`]: the whole sweep, merged at the end).
    pub shard: Shard,
}

/// What a sweep did.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Cases in the plan.
    pub cases: usize,
    /// Cases of this shard run now.
    pub ran: usize,
    /// Cases of this shard skipped as current.
    pub current: usize,
    /// The merged results (whole sweeps only).
    pub merged: Option<Merged>,
}

/// Progress of a sweep, for a progress bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Progress {
    /// About to run this many cases.
    Start { todo: usize },
    /// A case finished (by index).
    Done { index: usize },
}

/// Plans and checks every case, runs the compile's checks on this shard's (writing nothing if
/// one fails), runs this shard's cases that are not current, and merges if the shard is the
/// whole sweep.
pub fn sweep(request: &Request, progress: &(dyn Fn(Progress) + Sync)) -> Result<Report, SweepError> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(request.threads.unwrap_or(0)).build()?;
    let vary =
        request.vary.iter().map(|v| pipes::expand(&request.scenario, v.clone())).collect::<Result<Vec<_>, _>>()?;
    let (plan, scenarios) = pool.install(|| Plan::build(&request.scenario, vary))?;
    check_compiled(&plan, &scenarios, request.shard, &pool)?;
    let work = prepare(&plan, &request.out, request.shard)?;
    progress(Progress::Start { todo: work.todo.len() });
    run_cases(&plan, &scenarios, &request.out, &work.todo, &pool, &|case| {
        progress(Progress::Done { index: case.index })
    })?;
    let merged = if request.shard == Shard::ALL { Some(pool.install(|| merge(&request.out))?) } else { None };
    Ok(Report { cases: plan.cases.len(), ran: work.todo.len(), current: work.current, merged })
}

/// Draws the finished sweeps in `dirs` (each a sweep's output folder, with its label) on one
/// chart of peak contact force against string weight, at `out`.
pub fn compare(out: &Path, caption: &str, dirs: &[(String, PathBuf)]) -> Result<(), SweepError> {
    let sweeps = dirs
        .iter()
        .map(|(label, dir)| read_results(dir).map(|(plan, rows)| (label.clone(), plan, rows)))
        .collect::<Result<Vec<_>, _>>()?;
    chart::compare(out, caption, &sweeps)
}

impl From<ScenarioError> for SweepError {
    fn from(e: ScenarioError) -> Self {
        SweepError::Scenario(Box::new(e))
    }
}

/// An I/O error naming `path`.
pub(crate) fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> SweepError + '_ {
    move |error| SweepError::Io { path: path.into(), error }
}

/// Writes `bytes` to a temporary name beside `path` (`tag` keeps concurrent writers apart), then
/// renames it over `path`, so a reader never sees half a file.
pub(crate) fn write_atomic(path: &Path, bytes: &[u8], tag: &str) -> Result<(), SweepError> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let temp = path.with_file_name(format!(".{name}.{tag}-{}.tmp", std::process::id()));
    std::fs::write(&temp, bytes).map_err(io_error(&temp))?;
    std::fs::rename(&temp, path).map_err(io_error(path))
}
