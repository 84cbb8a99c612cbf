//! `pipearm design`: the values of some scenario keys (lift time, acceleration, shaper, ...)
//! that minimise an objective while every limit on the run's figures holds, in the nominal run or
//! at the envelope's 95th percentile (robust: every candidate runs the same spread draws, common
//! random numbers, so candidates differ by their keys alone); and [`table`], the seed's table of
//! the largest start/stop acceleration per drive profile. docs/envelope.md.
//!
//! [`search`] is the optimiser, independent of the simulator; [`Evaluator`] turns a candidate
//! into runs and their figures.

pub mod search;
pub mod table;

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;
use thiserror::Error;

use crate::compile::Compiler;
use crate::envelope::cases::{MethodChoice, Sampling};
use crate::envelope::dist::Spread;
use crate::envelope::sensitivity::quantile;
use crate::envelope::{EnvelopeError, cases::check_spreads};
use crate::robot::Robot;
use crate::run::{RunOptions, run_reusing};
use crate::scenario::{Scenario, ScenarioError};
use crate::sweep::plan::{base_document, get_number, not_a_number, set_key, spec_of};
use crate::sweep::row::Row;
use search::{Evaluation, Outcome, Problem, minimize};

/// Errors of a design; each names the argument, key or figure.
#[derive(Debug, Error)]
pub enum DesignError {
    /// A bad argument.
    #[error("{0}")]
    Argument(String),
    /// A limit or objective on a figure the run's summary does not have.
    #[error(
        "`{figure}` is not a figure of the run's summary; allowed peak_force_n (the largest pair's) or a \
             dotted path of the summary such as {examples}"
    )]
    Figure { figure: String, examples: String },
    /// The spreads or the base scenario.
    #[error(transparent)]
    Envelope(#[from] EnvelopeError),
    /// Writing the result.
    #[error("{path}: {error}")]
    Io { path: PathBuf, error: std::io::Error },
}

impl From<ScenarioError> for DesignError {
    fn from(e: ScenarioError) -> Self {
        DesignError::Envelope(e.into())
    }
}

/// A limit on a figure: `KEY<=VALUE` or `KEY>=VALUE`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Limit {
    /// The figure: `peak_force_n` or a dotted summary path (`residual.amplitude_m`, ...).
    pub figure: String,
    /// Its bound.
    pub bound: f64,
    /// `<=` (an upper bound, held at the envelope's p95) or `>=` (held at its p5).
    pub upper: bool,
}

impl std::str::FromStr for Limit {
    type Err = DesignError;

    fn from_str(text: &str) -> Result<Self, DesignError> {
        let bad =
            || DesignError::Argument(format!("--limit `{text}`: allowed KEY<=VALUE or KEY>=VALUE, VALUE a number"));
        let (figure, bound, upper) = match (text.split_once("<="), text.split_once(">=")) {
            (Some((f, v)), None) => (f, v, true),
            (None, Some((f, v))) => (f, v, false),
            _ => return Err(bad()),
        };
        let bound: f64 = bound.trim().parse().map_err(|_| bad())?;
        if figure.trim().is_empty() || !bound.is_finite() {
            return Err(bad());
        }
        Ok(Limit { figure: figure.trim().into(), bound, upper })
    }
}

/// A searched key and its range: `KEY=A..B`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Over {
    /// The scenario key.
    pub key: String,
    /// Lower end.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

impl std::str::FromStr for Over {
    type Err = DesignError;

    fn from_str(text: &str) -> Result<Self, DesignError> {
        let bad = || DesignError::Argument(format!("--over `{text}`: allowed KEY=A..B with numbers A < B"));
        let (key, range) = text.split_once('=').ok_or_else(bad)?;
        let (a, b) = range.split_once("..").ok_or_else(bad)?;
        let (low, high): (f64, f64) = (a.trim().parse().map_err(|_| bad())?, b.trim().parse().map_err(|_| bad())?);
        if key.trim().is_empty() || !(low.is_finite() && high.is_finite() && low < high) {
            return Err(bad());
        }
        Ok(Over { key: key.trim().into(), low, high })
    }
}

/// Where the limits must hold.
#[derive(Debug, Clone, PartialEq)]
pub enum Robustness {
    /// In the scenario's own run.
    Nominal,
    /// At the envelope's p95 (p5 for a `>=` limit) over `samples` draws of the spreads.
    Envelope { spreads: Vec<Spread>, samples: usize, seed: u64 },
}

/// Turns a candidate (a value per searched key) into runs and their figures.
pub struct Evaluator {
    path: PathBuf,
    document: toml::Value,
    robot: Robot,
    keys: Vec<String>,
    draws: Vec<Vec<(String, toml::Value)>>,
    limits: Vec<Limit>,
    /// Figures reported (the median over the draws) beside the limits.
    reported: Vec<String>,
    pool: rayon::ThreadPool,
}

/// A candidate's runs, read back.
struct Runs {
    rows: Vec<Row>,
    diverged: usize,
}

impl Evaluator {
    /// An evaluator of `keys` over the scenario at `path`, with `limits`, and `reported` figures
    /// beside them.
    pub fn new(
        path: &Path,
        keys: Vec<String>,
        limits: Vec<Limit>,
        reported: Vec<String>,
        robustness: &Robustness,
        threads: Option<usize>,
    ) -> Result<Self, DesignError> {
        let draws = match robustness {
            Robustness::Nominal => vec![Vec::new()],
            Robustness::Envelope { spreads, samples, seed } => {
                check_spreads(path, spreads, None)?;
                let sampling = Sampling::new(spreads, *samples, *seed, MethodChoice::Regression, None)?;
                sampling.case_rows(spreads, &[])
            }
        };
        if let Some(key) = draws.first().into_iter().flatten().map(|(k, _)| k).find(|k| keys.contains(k)) {
            return Err(DesignError::Argument(format!(
                "`{key}` is both searched (--over) and spread (--spread): allowed in one of them"
            )));
        }
        let all_keys = keys.iter().chain(draws.first().into_iter().flatten().map(|(k, _)| k));
        let document = base_document(path, all_keys.map(String::as_str))?;
        // Every candidate's runs share the robot: its file is read once, not once a run.
        let robot = Scenario::load_robot(path, &spec_of(path, document.clone())?)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| DesignError::Argument(format!("threads: {e}")))?;
        Ok(Evaluator { path: path.into(), document, robot, keys, draws, limits, reported, pool })
    }

    /// Replaces the whole table at `key` of the base document (the design table's drive).
    pub fn set_base(&mut self, key: &str, value: toml::Value) -> Result<(), DesignError> {
        set_key(&mut self.document, key, value).map_err(|m| DesignError::Argument(format!("`{key}`: {m}")))
    }

    /// Pins the base document's shaper to the nominal arm's tuning (see
    /// [`crate::envelope::cases::nominal_shaper_tuning`]), unless its frequencies are drawn.
    pub fn pin_shaper(&mut self) -> Result<(), DesignError> {
        let drawn = |key: &str| self.draws.iter().flatten().any(|(k, _)| k == key);
        if drawn("drive.shaper_hz") {
            return Ok(());
        }
        let pinned: Vec<(String, toml::Value)> =
            crate::envelope::cases::nominal_shaper_tuning(&self.path, &self.document)?
                .into_iter()
                .filter(|(key, _)| !drawn(key))
                .collect();
        for (key, value) in pinned {
            self.set_base(&key, value)?;
        }
        Ok(())
    }

    /// The base document's number at `key`.
    pub fn base_number(&self, key: &str) -> Option<f64> {
        get_number(&self.document, key)
    }

    /// Why `key` is no number of the base document, with the numeric keys near it.
    pub fn not_a_number(&self, key: &str) -> String {
        not_a_number(&self.document, key, &self.path)
    }

    /// Runs per candidate.
    pub fn runs_per_candidate(&self) -> usize {
        self.draws.len()
    }

    /// Runs the draws at `x`; `Err` with why the candidate's scenario is not valid.
    fn runs(&self, x: &[f64]) -> Result<Runs, String> {
        // Built on the workers too: a scenario's checks (its beam and path, and its compile's
        // where it has any: an actuator's loop) cost about as much as a short run. The draws'
        // checks and runs share one compiler.
        let compiler = std::sync::Arc::new(Compiler::new());
        let scenarios: Vec<Scenario> = self.pool.install(|| {
            self.draws
                .par_iter()
                .map(|draw| {
                    let mut document = self.document.clone();
                    let values = self
                        .keys
                        .iter()
                        .cloned()
                        .zip(x.iter().map(|v| toml::Value::Float(*v)))
                        .chain(draw.iter().cloned());
                    for (key, value) in values {
                        set_key(&mut document, &key, value).map_err(|m| format!("`{key}`: {m}"))?;
                    }
                    let spec = spec_of(&self.path, document).map_err(|e| e.to_string())?;
                    Scenario::from_spec_and_robot_sharing(&self.path, spec, self.robot.clone(), &compiler)
                        .and_then(|scenario| scenario.check_compiled().map(|()| scenario))
                        .map_err(|e| e.to_string())
                })
                .collect::<Result<_, String>>()
        })?;
        let results: Vec<Option<Row>> = self.pool.install(|| {
            scenarios
                .par_iter()
                .map(|s| {
                    let (summary, _) = run_reusing(&s.model, &RunOptions::default(), &compiler).ok()?;
                    Row::read(serde_json::to_string(&summary).expect("a summary serialises"), &["impacts"]).ok()
                })
                .collect()
        });
        let diverged = results.iter().filter(|r| r.is_none()).count();
        Ok(Runs { rows: results.into_iter().flatten().collect(), diverged })
    }

    /// Evaluates `x`: the objective (`objective_key` a searched key, or a figure at the p95) and
    /// each limit's figure at its percentile.
    pub fn evaluate(&self, x: &[f64], objective: &Objective) -> Evaluation {
        let infeasible = |objective: f64| Evaluation {
            x: x.to_vec(),
            objective,
            figures: vec![f64::NAN; self.limits.len()],
            margins: vec![f64::INFINITY; self.limits.len()],
            feasible: false,
            reported: vec![f64::NAN; self.reported.len()],
        };
        let coordinate = match objective {
            Objective::Coordinate(i) => x[*i],
            Objective::Figure(_) => f64::NAN,
        };
        let runs = match self.runs(x) {
            Ok(runs) if runs.diverged == 0 && !runs.rows.is_empty() => runs,
            _ => return infeasible(coordinate),
        };
        let figures: Vec<f64> =
            self.limits.iter().map(|l| percentile(&runs.rows, &l.figure, if l.upper { 0.95 } else { 0.05 })).collect();
        let margins: Vec<f64> = figures
            .iter()
            .zip(&self.limits)
            .map(|(f, l)| {
                let g = (f - l.bound) / l.bound.abs().max(1e-300);
                if l.upper { g } else { -g }
            })
            .map(|g| if g.is_nan() { f64::INFINITY } else { g })
            .collect();
        let objective = match objective {
            Objective::Coordinate(_) => coordinate,
            Objective::Figure(figure) => percentile(&runs.rows, figure, 0.95),
        };
        Evaluation {
            x: x.to_vec(),
            objective,
            feasible: margins.iter().all(|g| *g <= 0.0),
            figures,
            margins,
            reported: self.reported.iter().map(|f| percentile(&runs.rows, f, 0.5)).collect(),
        }
    }

    /// Checks that every limit's and the objective's figure is in the summary of a run at `x`.
    pub fn check_figures(&self, x: &[f64], objective: &Objective) -> Result<(), DesignError> {
        let runs =
            self.runs(x).map_err(|m| DesignError::Argument(format!("--over at the centre of its ranges: {m}")))?;
        let Some(row) = runs.rows.first() else {
            return Err(DesignError::Argument(
                "the run at the centre of the --over ranges diverged: its figures cannot be checked; narrow the ranges"
                    .into(),
            ));
        };
        let objective_figure = match objective {
            Objective::Figure(f) => Some(f.as_str()),
            Objective::Coordinate(_) => None,
        };
        let figures = self
            .limits
            .iter()
            .map(|l| l.figure.as_str())
            .chain(objective_figure)
            .chain(self.reported.iter().map(String::as_str));
        for figure in figures {
            if figure_of(row, figure).is_none() {
                let examples = row
                    .scalars
                    .iter()
                    .filter(|(_, v)| v.is_number())
                    .map(|(k, _)| k.as_str())
                    .filter(|k| {
                        [
                            "pairs.0.peak_force_n",
                            "residual.amplitude_m",
                            "max_tip_deflection_m",
                            "actuator.peak_pressure_pa",
                            "peak_drive_torque_n_m",
                        ]
                        .contains(k)
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(DesignError::Figure { figure: figure.into(), examples });
            }
        }
        Ok(())
    }
}

/// What the design minimises.
#[derive(Debug, Clone, PartialEq)]
pub enum Objective {
    /// A searched key itself (by its index among them).
    Coordinate(usize),
    /// A figure of the summary, at the envelope's p95.
    Figure(String),
}

/// `figure` of a run: `peak_force_n` is the largest pair's peak force; otherwise a dotted path
/// of the summary.
fn figure_of(row: &Row, figure: &str) -> Option<f64> {
    if figure == "peak_force_n" {
        return row.largest_peak_force_n("");
    }
    row.get(figure).and_then(|v| v.as_f64())
}

/// The `p` quantile of `figure` over `rows` (NaN if a run lacks it).
fn percentile(rows: &[Row], figure: &str, p: f64) -> f64 {
    let values: Option<Vec<f64>> = rows.iter().map(|r| figure_of(r, figure)).collect();
    let Some(mut values) = values else { return f64::NAN };
    values.sort_by(f64::total_cmp);
    quantile(&values, p)
}

/// A design as asked for on the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The scenario file.
    pub scenario: PathBuf,
    /// The limits.
    pub limits: Vec<Limit>,
    /// The objective: a searched key or a figure (at the envelope's p95).
    pub objective: String,
    /// Maximise it instead of minimising.
    pub maximize: bool,
    /// The searched keys.
    pub over: Vec<Over>,
    /// Where the limits must hold.
    pub robustness: Robustness,
    /// Relative tolerance on each searched key (of its range).
    pub tolerance: f64,
    /// Most candidates.
    pub budget: usize,
    /// Worker threads.
    pub threads: Option<usize>,
}

/// What a design found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Design {
    /// The searched keys.
    pub keys: Vec<String>,
    /// The objective.
    pub objective: String,
    /// Whether it was maximised.
    pub maximize: bool,
    /// The limits.
    pub limits: Vec<Limit>,
    /// Runs per candidate (1: nominal).
    pub runs_per_candidate: usize,
    /// Candidates evaluated.
    pub candidates: usize,
    /// Runs spent.
    pub runs: usize,
    /// The search.
    pub outcome: Outcome,
}

/// Runs the design search of `request`.
pub fn design(request: &Request) -> Result<Design, DesignError> {
    if request.over.is_empty() {
        return Err(DesignError::Argument("no --over given: allowed one or more KEY=A..B".into()));
    }
    if request.limits.is_empty() {
        return Err(DesignError::Argument("no --limit given: allowed one or more KEY<=VALUE or KEY>=VALUE".into()));
    }
    let keys: Vec<String> = request.over.iter().map(|o| o.key.clone()).collect();
    let objective = match keys.iter().position(|k| *k == request.objective) {
        Some(i) => Objective::Coordinate(i),
        None => Objective::Figure(request.objective.clone()),
    };
    if let Some(key) = keys.iter().enumerate().find(|(i, k)| keys[..*i].contains(k)).map(|(_, k)| k) {
        return Err(DesignError::Argument(format!("--over `{key}` given twice: allowed once per key")));
    }
    let mut evaluator = Evaluator::new(
        &request.scenario,
        keys.clone(),
        request.limits.clone(),
        Vec::new(),
        &request.robustness,
        request.threads,
    )?;
    for over in &request.over {
        if evaluator.base_number(&over.key).is_none() && !over.key.starts_with("drive.") {
            return Err(DesignError::Argument(format!("--over `{}`: {}", over.key, evaluator.not_a_number(&over.key))));
        }
    }
    evaluator.pin_shaper()?;
    let evaluator = evaluator;
    let centre: Vec<f64> = request.over.iter().map(|o| 0.5 * (o.low + o.high)).collect();
    evaluator.check_figures(&centre, &objective)?;
    // Maximising searches the mirrored problem: the objective negated, and a searched key that
    // is the objective on its mirrored axis, so that its limits hold above a boundary there too.
    let sign = if request.maximize { -1.0 } else { 1.0 };
    let mirrored = |i: usize| request.maximize && objective == Objective::Coordinate(i);
    let real =
        |x: &[f64]| -> Vec<f64> { x.iter().enumerate().map(|(i, v)| if mirrored(i) { -v } else { *v }).collect() };
    let evaluate = |x: &[f64]| {
        let e = evaluator.evaluate(&real(x), &objective);
        Evaluation { x: x.to_vec(), objective: sign * e.objective, ..e }
    };
    let problem = Problem {
        bounds: request
            .over
            .iter()
            .enumerate()
            .map(|(i, o)| if mirrored(i) { (-o.high, -o.low) } else { (o.low, o.high) })
            .collect(),
        objective_coordinate: match objective {
            Objective::Coordinate(i) => Some(i),
            Objective::Figure(_) => None,
        },
        tolerance: request.tolerance,
        budget: request.budget,
        grid: None,
        evaluate: &evaluate,
    };
    let mut outcome = minimize(&problem);
    for e in outcome.history.iter_mut().chain(outcome.best.as_mut()) {
        e.x = real(&e.x);
        e.objective *= sign;
    }
    let candidates = outcome.history.len() + 1;
    Ok(Design {
        keys,
        objective: request.objective.clone(),
        maximize: request.maximize,
        limits: request.limits.clone(),
        runs_per_candidate: evaluator.runs_per_candidate(),
        candidates,
        runs: candidates * evaluator.runs_per_candidate(),
        outcome,
    })
}

/// Writes `value` as pretty JSON to `path`.
pub fn write_json(path: &Path, value: &impl Serialize) -> Result<(), DesignError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|error| DesignError::Io { path: dir.into(), error })?;
    }
    let json = serde_json::to_string_pretty(value).expect("a design serialises") + "\n";
    std::fs::write(path, json).map_err(|error| DesignError::Io { path: path.into(), error })
}
