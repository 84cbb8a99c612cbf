//! Envelopes: a scenario run over spread keys (pad gap, pad stiffness, damping, lift time, ...)
//! drawn from their distributions, per string size, in parallel and sharded like a sweep; the
//! percentiles of each pair's peak force and of the residual amplitude, a chart of peak force
//! against string weight with its p5–p95 band, and the sensitivity of the peak force to each
//! spread key. `pipearm envelope`; docs/envelope.md.
//!
//! The flow: `--spread` arguments ([`dist`]) → a [`cases::Sampling`] (a Latin hypercube, or a
//! Saltelli design for Sobol indices, [`sample`]) → the sweep's plan, shards and case files
//! ([`crate::sweep`]) → [`merge`]: the sweep's results table, then per group the figures of
//! [`stats`] (percentiles; the sensitivity of [`sensitivity`]) and the chart of [`chart`].

pub mod cases;
pub mod chart;
pub mod dist;
pub mod sample;
pub mod sensitivity;
pub mod stats;

use std::path::{Path, PathBuf};

use serde::Serialize;
use thiserror::Error;

use crate::scenario::ScenarioError;
use crate::sweep::row::Row;
use crate::sweep::{Plan, Shard, SweepError, Vary, check_compiled, prepare, read_results, run_cases};
use cases::{MethodChoice, Sampling, check_spreads};
use dist::{Spread, SpreadError};
use stats::{GroupEnvelope, group_envelope};

/// Errors planning, running or merging an envelope; each names the argument, key or file.
#[derive(Debug, Error)]
pub enum EnvelopeError {
    /// A bad command-line argument.
    #[error("{0}")]
    Argument(String),
    /// A `--spread` that does not parse.
    #[error(transparent)]
    Parse(#[from] SpreadError),
    /// A spread the scenario does not accept.
    #[error("--spread `{spread}`: {message}")]
    Spread { spread: String, message: String },
    /// Reading the base scenario.
    #[error(transparent)]
    Scenario(Box<ScenarioError>),
    /// Planning, running or merging the cases.
    #[error(transparent)]
    Sweep(Box<SweepError>),
    /// Drawing the chart.
    #[error("chart {path}: {message}")]
    Chart { path: PathBuf, message: String },
}

impl From<ScenarioError> for EnvelopeError {
    fn from(e: ScenarioError) -> Self {
        EnvelopeError::Scenario(Box::new(e))
    }
}

impl From<SweepError> for EnvelopeError {
    fn from(e: SweepError) -> Self {
        EnvelopeError::Sweep(Box::new(e))
    }
}

/// An envelope as asked for on the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The base scenario file.
    pub scenario: PathBuf,
    /// The spreads, `KEY=DIST`.
    pub spreads: Vec<Spread>,
    /// Runs per group.
    pub samples: usize,
    /// The grouping key and its values (`--per payload.size=...`).
    pub per: Option<Vary>,
    /// Seed of the draw.
    pub seed: u64,
    /// The sensitivity method.
    pub method: MethodChoice,
    /// Output folder.
    pub out: PathBuf,
    /// Worker threads (rayon's default if `None`).
    pub threads: Option<usize>,
    /// The shard to run.
    pub shard: Shard,
}

/// What an envelope did.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Runs in the plan.
    pub cases: usize,
    /// Runs of this shard run now.
    pub ran: usize,
    /// Runs of this shard skipped as current.
    pub current: usize,
    /// The sampling.
    pub sampling: Sampling,
    /// The merged envelope (whole envelopes only).
    pub merged: Option<Merged>,
}

/// The envelope's figures, as `DIR/envelope.json` holds them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Envelope {
    /// The scenario's name.
    pub scenario: String,
    /// The spreads, `KEY=DIST`.
    pub spreads: Vec<String>,
    /// Runs per group.
    pub runs_per_group: usize,
    /// Seed of the draw.
    pub seed: u64,
    /// The grouping key, if any.
    pub per: Option<String>,
    /// Each group's figures.
    pub groups: Vec<GroupEnvelope>,
}

/// The files a merge wrote, and the figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged {
    /// The figures.
    pub envelope: Envelope,
    /// `envelope.json`, `envelope.csv`, `results.csv`, `results.json`, `force_vs_weight.svg`.
    pub files: Vec<PathBuf>,
}

/// Progress, as the sweep reports it.
pub use crate::sweep::Progress;

/// Checks the spreads, samples and plans every run (writing nothing if one fails), runs this
/// shard's runs that are not current, and merges if the shard is the whole envelope.
pub fn envelope(request: &Request, progress: &(dyn Fn(Progress) + Sync)) -> Result<Report, EnvelopeError> {
    check_spreads(&request.scenario, &request.spreads, request.per.as_ref())?;
    let per = request.per.clone().map(|p| crate::sweep::pipes::expand(&request.scenario, p)).transpose()?;
    let sampling = Sampling::new(&request.spreads, request.samples, request.seed, request.method, per)?;
    let pool =
        rayon::ThreadPoolBuilder::new().num_threads(request.threads.unwrap_or(0)).build().map_err(SweepError::from)?;
    let vary = sampling.vary(&request.spreads);
    let rows = sampling.case_rows(&request.spreads, &pinned_keys(&request.scenario, &request.spreads)?);
    let (plan, scenarios) = pool.install(|| Plan::build_cases(&request.scenario, vary, rows))?;
    check_compiled(&plan, &scenarios, request.shard, &pool)?;
    let work = prepare(&plan, &request.out, request.shard)?;
    let json = serde_json::to_string_pretty(&sampling).expect("a sampling serialises") + "\n";
    crate::sweep::write_atomic(
        &request.out.join(SAMPLING_FILE),
        json.as_bytes(),
        &format!("shard{}", request.shard.index),
    )?;
    progress(Progress::Start { todo: work.todo.len() });
    run_cases(&plan, &scenarios, &request.out, &work.todo, &pool, &|case| {
        progress(Progress::Done { index: case.index })
    })?;
    let merged = if request.shard == Shard::ALL { Some(pool.install(|| merge(&request.out))?) } else { None };
    Ok(Report { cases: plan.cases.len(), ran: work.todo.len(), current: work.current, sampling, merged })
}

/// The keys every run shares beyond the base scenario: the nominal arm's shaper tuning, unless
/// its frequencies are spread (a spread damping ratio is left to the spread).
fn pinned_keys(path: &Path, spreads: &[Spread]) -> Result<Vec<(String, toml::Value)>, EnvelopeError> {
    if spreads.iter().any(|s| s.key == "drive.shaper_hz") {
        return Ok(Vec::new());
    }
    let document = crate::sweep::plan::read_document(path)?;
    let mut pinned = cases::nominal_shaper_tuning(path, &document)?;
    pinned.retain(|(key, _)| !spreads.iter().any(|s| s.key == *key));
    Ok(pinned)
}

/// The file of an envelope's sampling, beside the sweep's `plan.json`.
pub const SAMPLING_FILE: &str = "sampling.json";

/// Reads an envelope's plan, sampling and every run, and writes its results and figures.
pub fn merge(dir: &Path) -> Result<Merged, EnvelopeError> {
    let sampling_path = dir.join(SAMPLING_FILE);
    let text = std::fs::read_to_string(&sampling_path).map_err(crate::sweep::io_error(&sampling_path))?;
    let sampling: Sampling = serde_json::from_str(&text).map_err(|e| SweepError::Format {
        path: sampling_path.clone(),
        message: format!("not an envelope's sampling: {e}"),
    })?;
    let spreads = sampling.parsed_spreads()?;
    let (plan, rows) = read_results(dir)?;
    let envelope = figures(&sampling, &spreads, &plan, &rows)?;
    let files = write(dir, &plan, &rows, &envelope)?;
    Ok(Merged { envelope, files })
}

/// The figures of every group.
fn figures(sampling: &Sampling, spreads: &[Spread], plan: &Plan, rows: &[Row]) -> Result<Envelope, EnvelopeError> {
    let n = sampling.runs_per_group;
    let groups = sampling.groups();
    if plan.cases.len() != n * groups.len() {
        let path = PathBuf::from("plan.json");
        return Err(SweepError::Format { path, message: "the plan does not match sampling.json".into() }.into());
    }
    let values: Vec<Vec<f64>> = plan
        .cases
        .iter()
        .map(|c| spreads.iter().map(|s| c.values.get(&s.key).and_then(|v| v.as_float()).unwrap_or(f64::NAN)).collect())
        .collect();
    let scenario =
        rows.first().and_then(|r| r.get("summary.scenario")).map(crate::sweep::row::cell).unwrap_or_default();
    let groups = groups
        .iter()
        .enumerate()
        .map(|(g, value)| {
            let range = g * n..(g + 1) * n;
            let per = value.as_ref().map(crate::sweep::vary::show);
            group_envelope(sampling, spreads, per, &rows[range.clone()], &values[range])
        })
        .collect();
    Ok(Envelope {
        scenario,
        spreads: sampling.spreads.clone(),
        runs_per_group: n,
        seed: sampling.seed,
        per: sampling.per.as_ref().map(|p| p.key.clone()),
        groups,
    })
}

fn write(dir: &Path, plan: &Plan, rows: &[Row], envelope: &Envelope) -> Result<Vec<PathBuf>, EnvelopeError> {
    let files: Vec<PathBuf> = ["envelope.json", "envelope.csv", "results.json", "results.csv", "force_vs_weight.svg"]
        .map(|f| dir.join(f))
        .into();
    let json = serde_json::to_string_pretty(envelope).expect("an envelope serialises") + "\n";
    crate::sweep::write_atomic(&files[0], json.as_bytes(), "merge")?;
    crate::sweep::write_atomic(&files[1], table(envelope).as_bytes(), "merge")?;
    crate::sweep::write_atomic(&files[2], crate::sweep::table::json(rows).as_bytes(), "merge")?;
    crate::sweep::write_atomic(&files[3], crate::sweep::table::csv(plan, rows).as_bytes(), "merge")?;
    let caption = format!(
        "{}: peak contact force against string weight, {} runs each",
        envelope.scenario, envelope.runs_per_group
    );
    chart::force_vs_weight(&files[4], &caption, &envelope.groups)?;
    Ok(files)
}

/// `envelope.csv`: a row per group and figure, its percentiles.
fn table(envelope: &Envelope) -> String {
    let mut out = String::from(
        "group,size,weight_lb_ft,grade,joint_mass_kg,payload_kg,weight_n,runs,diverged,figure,p5,p50,p95,p99,max\n",
    );
    let number = |x: Option<f64>| x.map(|x| x.to_string()).unwrap_or_default();
    for g in &envelope.groups {
        let figures =
            [("peak_force_n".to_string(), g.peak_force_n), ("peak_force_per_weight".into(), g.peak_force_per_weight)]
                .into_iter()
                .chain(g.pairs.iter().map(|p| (format!("{}.peak_force_n", p.pair), p.peak_force_n)))
                .chain([("residual_amplitude_m".to_string(), g.residual_amplitude_m)])
                .chain(g.stress.iter().flat_map(|s| {
                    std::iter::once(("stress.peak_stress_pa".to_string(), s.peak_stress_pa))
                        .chain(s.utilisation.map(|u| ("stress.utilisation".to_string(), u)))
                }))
                .chain(g.fatigue.map(|f| ("fatigue.damage_per_lift".to_string(), f.damage_per_lift)));
        for (figure, p) in figures {
            out += &format!(
                "{},{},{},{},{},{},{},{},{},{figure},{},{},{},{},{}\n",
                g.per.as_deref().unwrap_or("all"),
                g.size.as_deref().unwrap_or_default(),
                number(g.weight_lb_ft),
                g.grade.as_deref().unwrap_or_default(),
                number(g.joint_mass_kg),
                g.payload_kg,
                g.weight_n,
                g.runs,
                g.diverged,
                p.p5,
                p.p50,
                p.p95,
                p.p99,
                p.max
            );
        }
    }
    out
}
