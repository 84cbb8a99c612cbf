//! Least-squares identification of scenario parameters from measured signals (`pipearm fit`).
//!
//! Each named scenario key (the arm's modal damping ratios, a pad law's stiffness, exponent,
//! restitution or damping, the string's length) is a parameter within bounds. The residuals
//! are the simulated signals minus the measured ones at the measured times, each signal divided
//! by its measured peak so that signals of different units weigh alike. With `align` (the CLI's
//! `--shift`) the measured signals are first aligned in time with the simulation at the scenario's
//! own values (the shift of least squared difference, [`alignment_shift`]); that shift is held
//! while the parameters move, and found again from the fitted values until it holds.
//!
//! The uncertainty has two parts. The standard error of each parameter from the Jacobian at the
//! solution, s² (JᵀJ)⁻¹ with s² the residuals' variance, both taken over the residuals' effective
//! number of independent samples (their lag-one autocorrelation accounted for, [`lm`]): what the
//! signals' noise leaves. And the run's own numerical error: the fit is repeated at half the step
//! from its solution, the half-step values are reported, and how far they moved is the numerical
//! uncertainty (the step refinement with which ASME V&V 20 estimates it). The 95 % interval is
//! ± 1.96 √(standard error² + numerical uncertainty²). Neither covers the model's form.

pub mod lm;

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::arm::Fidelity;
use crate::channel::Channel;
use crate::compile::Compiler;
use crate::robot::Robot;
use crate::run::{RunOptions, RunSummary, Series, run_compiled};
use crate::scenario::{Scenario, ScenarioError, ScenarioSpec};
use crate::scene::SceneError;
use crate::sweep::plan::{explicit_damping_ratios, get_number, not_a_number, set_key};

/// Errors of a fit; each names what it concerns.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// A key that cannot be fitted, or is not in the scenario.
    #[error("--params {key}: {message}")]
    Key { key: String, message: String },
    /// The scenario with the parameters set.
    #[error(transparent)]
    Scenario(#[from] Box<ScenarioError>),
    /// A run.
    #[error("a run at {values}: {source}")]
    Run { values: String, source: SceneError },
    /// A measured signal the simulation does not produce.
    #[error("measured column `{0}`: the run has no such signal")]
    Signal(String),
    /// In the measured file.
    #[error(transparent)]
    Measured(#[from] Box<crate::measured::MeasuredError>),
}

/// A parameter to fit: a scenario key and its bounds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// Dotted scenario key, e.g. `arm.damping_ratios.0`, `dampeners.0.law.stiffness`.
    pub key: String,
    /// Its value in the scenario.
    pub initial: f64,
    /// Lower and upper bound.
    pub bounds: (f64, f64),
}

/// The allowed keys and their bounds, given the scenario's value: (key pattern, bounds).
const FITTABLE: &str = "arm.damping_ratios.N, dampeners.N.law.stiffness, dampeners.N.law.stiffness_n_m, \
                        dampeners.N.law.damping_n_s_m, dampeners.N.law.exponent, dampeners.N.law.restitution, \
                        payload.length_m";

/// Bounds of a fittable key around its scenario value, or why it is not fittable.
fn bounds_of(key: &str, initial: f64) -> Result<(f64, f64), String> {
    let key = &crate::sweep::plan::dotted_key(key);
    let last = key.rsplit('.').next().unwrap_or(key);
    let decade = |f: f64| (initial / f, initial * f);
    let bounds = if key.starts_with("arm.damping_ratios.") {
        (1e-4, 0.5)
    } else if key.starts_with("dampeners.") {
        match last {
            "stiffness" | "stiffness_n_m" | "damping_n_s_m" => decade(100.0),
            "exponent" => (1.0, 3.0),
            "restitution" => (0.05, 1.0),
            _ => return Err(format!("not fittable: allowed {FITTABLE}")),
        }
    } else if key == "payload.length_m" {
        decade(3.0)
    } else {
        return Err(format!("not fittable: allowed {FITTABLE}"));
    };
    if !(initial.is_finite() && initial > 0.0) {
        return Err(format!("its value {initial} must be > 0 to be fitted"));
    }
    Ok((bounds.0.min(initial), bounds.1.max(initial)))
}

/// A measured signal.
#[derive(Debug, Clone, PartialEq)]
pub struct Signal {
    /// The simulated signal it is compared with (a name of [`crate::run::measurable_channels`]).
    pub name: String,
    /// Times, s, increasing.
    pub t_s: Vec<f64>,
    /// Values, in the signal's unit.
    pub values: Vec<f64>,
}

/// How the fit runs the scenario: its own fidelity and step unless set.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RunSettings {
    /// The arm's fidelity (`None`: the scenario's).
    pub fidelity: Option<Fidelity>,
    /// The time step, s (`None`: the scenario's). Measured signals are compared with the run
    /// interpolated linearly between its steps: a step well below the measured signal's
    /// shortest feature (an impact's duration / 20) keeps that interpolation out of the fit.
    pub step_s: Option<f64>,
}

/// The measured file's columns as signals to fit, checked against the signals a run of `model`
/// gives (names and units, converted to SI).
pub fn signals_of(measured: &crate::measured::Measured, model: &crate::model::Model) -> Result<Vec<Signal>, FitError> {
    let defs = crate::run::measurable_channels(model);
    let known: Vec<crate::measured::Known> = defs.iter().map(crate::measured::Known::from).collect();
    let columns = measured.to_si(&known).map_err(Box::new)?;
    Ok(columns.into_iter().map(|c| Signal { name: c.name, t_s: measured.t_s.clone(), values: c.values }).collect())
}

/// A scenario and the parameters to fit in it.
#[derive(Clone)]
pub struct Problem {
    path: PathBuf,
    document: toml::Value,
    robot: Robot,
    settings: RunSettings,
    /// The signals a run of the scenario gives.
    defs: Vec<Channel>,
    /// The parameters, in `--params` order.
    pub parameters: Vec<Parameter>,
    /// The beams and arms compiled so far: a fit's runs vary a few keys, which seldom touch them.
    compiler: std::sync::Arc<Compiler>,
}

impl Problem {
    /// The scenario with `keys` to fit, run with `settings`.
    pub fn new(scenario: &Scenario, keys: &[String], settings: RunSettings) -> Result<Self, FitError> {
        let path = &scenario.path;
        let mut document = toml::Value::try_from(&scenario.spec).map_err(|e| {
            Box::new(ScenarioError::Parse { path: path.into(), message: format!("canonical form: {e}") })
        })?;
        // The damping ratios live in the URDF unless the scenario overrides them: make the
        // override explicit, so that its entries can be set.
        if keys.iter().any(|k| crate::sweep::plan::dotted_key(k).starts_with("arm.damping_ratios.")) {
            explicit_damping_ratios(&mut document, &scenario.model.robot);
        }
        let parameters = keys
            .iter()
            .map(|key| {
                let initial = get_number(&document, key)
                    .ok_or_else(|| FitError::Key { key: key.clone(), message: not_a_number(&document, key, path) })?;
                let bounds = bounds_of(key, initial).map_err(|message| FitError::Key { key: key.clone(), message })?;
                Ok(Parameter { key: key.clone(), initial, bounds })
            })
            .collect::<Result<Vec<_>, FitError>>()?;
        let defs = crate::run::measurable_channels(&scenario.model);
        let robot = scenario.model.robot.clone();
        let compiler = std::sync::Arc::new(Compiler::new());
        Ok(Problem { path: path.clone(), document, robot, settings, defs, parameters, compiler })
    }

    /// The step the runs take, s.
    pub fn step_s(&self) -> f64 {
        self.settings.step_s.or_else(|| get_number(&self.document, "time.step_s")).unwrap_or(f64::NAN)
    }

    /// The same problem run at half its step.
    fn refined(&self) -> Problem {
        let settings = RunSettings { step_s: Some(0.5 * self.step_s()), ..self.settings };
        Problem { settings, ..self.clone() }
    }

    /// The scenario file's text with the parameters at `values`, to be written into `folder`:
    /// its relative paths (the robot, a drive table) rewritten to reach the same files from there.
    pub fn scenario_text(&self, values: &[f64], folder: &Path) -> Result<String, FitError> {
        let mut document = self.document_at(values)?;
        let base = self.path.parent().unwrap_or(Path::new("."));
        for key in ["robot", "drive.file"] {
            if let Some(relative) = get_text(&document, key) {
                let target = std::path::absolute(base.join(relative)).unwrap_or_else(|_| base.join(relative));
                let from = std::path::absolute(folder).unwrap_or_else(|_| folder.to_path_buf());
                let path = relative_path(&from, &target).to_string_lossy().into_owned();
                set_key(&mut document, key, toml::Value::String(path))
                    .map_err(|message| FitError::Key { key: key.into(), message })?;
            }
        }
        toml::to_string(&document).map_err(|e| {
            Box::new(ScenarioError::Parse { path: self.path.clone(), message: format!("writing: {e}") }).into()
        })
    }

    fn document_at(&self, values: &[f64]) -> Result<toml::Value, FitError> {
        let mut document = self.document.clone();
        for (p, v) in self.parameters.iter().zip(values) {
            set_key(&mut document, &p.key, toml::Value::Float(*v))
                .map_err(|message| FitError::Key { key: p.key.clone(), message })?;
        }
        Ok(document)
    }

    /// A run of the scenario with the parameters at `values`.
    pub fn run_at(&self, values: &[f64]) -> Result<(RunSummary, Series), FitError> {
        let mut spec: ScenarioSpec = self.document_at(values)?.try_into().map_err(|e: toml::de::Error| {
            Box::new(ScenarioError::Parse { path: self.path.clone(), message: e.to_string() })
        })?;
        // Before the scenario's checks and compile, as `run`'s overrides: an actuator's loop and
        // the step it allows are checked at the model and step that run.
        if let Some(step_s) = self.settings.step_s {
            spec.time.step_s = step_s;
        }
        if let Some(fidelity) = self.settings.fidelity {
            spec.model = fidelity.into();
        }
        let scenario = Scenario::from_spec_and_robot_sharing(&self.path, spec, self.robot.clone(), &self.compiler)
            .map_err(Box::new)?;
        let compiled = scenario.compile(self.settings.fidelity).map_err(Box::new)?;
        let options = RunOptions { fidelity: self.settings.fidelity, ..RunOptions::default() };
        let (summary, series) = run_compiled(&compiled, &options);
        let summary = summary.map_err(|source| FitError::Run { values: show(&self.parameters, values), source })?;
        Ok((summary, series))
    }
}

fn show(parameters: &[Parameter], values: &[f64]) -> String {
    parameters.iter().zip(values).map(|(p, v)| format!("{}={v:.6e}", p.key)).collect::<Vec<_>>().join(", ")
}

/// The text at dotted `key` of a TOML document.
fn get_text<'a>(document: &'a toml::Value, key: &str) -> Option<&'a str> {
    key.split('.').try_fold(document, |node, segment| node.get(segment))?.as_str()
}

/// `target` as a path from the folder `from` (both absolute): `..` up to their common part.
fn relative_path(from: &Path, target: &Path) -> PathBuf {
    let (from, to): (Vec<_>, Vec<_>) = (from.components().collect(), target.components().collect());
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut path: PathBuf = from[common..].iter().map(|_| "..").collect();
    path.extend(&to[common..]);
    path
}

/// A fitted parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fitted {
    /// The scenario key.
    pub key: String,
    /// Its value in the scenario.
    pub initial: f64,
    /// The value found.
    pub value: f64,
    /// Its standard error from the Jacobian (the fit to the signals' noise).
    pub standard_error: f64,
    /// How far the value moved when the step was halved: the run's own numerical error in it.
    pub numerical_uncertainty: f64,
    /// The 95 % interval, value ± 1.96 √(standard error² + numerical uncertainty²).
    pub interval_95: [f64; 2],
    /// The bounds searched.
    pub bounds: [f64; 2],
}

/// What a fit found and what it cost.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReport {
    /// Each parameter.
    pub parameters: Vec<Fitted>,
    /// The measured signals' time shift applied (added to the measured times), s.
    pub shift_s: f64,
    /// RMS of the normalized residuals at the scenario's values and at the fitted ones.
    pub rms_residual: [f64; 2],
    /// Runs spent.
    pub evaluations: usize,
    /// Iterations of Levenberg–Marquardt.
    pub iterations: usize,
    /// Whether it converged to its tolerance.
    pub converged: bool,
    /// Residuals, and how many independent samples they are worth.
    pub residuals: usize,
    /// The residuals' effective number of independent samples.
    pub effective_samples: f64,
}

/// Fits the problem's parameters to `signals`; `align`: shift the measured times to the run
/// first ([`alignment_shift`], re-done after each fit until it holds), else take them as they are.
pub fn fit(problem: &Problem, signals: &[Signal], align: bool, options: &lm::LmOptions) -> Result<FitReport, FitError> {
    let initial: Vec<f64> = problem.parameters.iter().map(|p| p.initial).collect();
    let bounds: Vec<(f64, f64)> = problem.parameters.iter().map(|p| p.bounds).collect();
    let defs = &problem.defs;
    let (_, series) = problem.run_at(&initial)?;
    let start = simulated(signals, &series, defs)?;
    let mut shift_s = if align { alignment_shift(signals, &series.t_s, &start) } else { 0.0 };
    let start_ssr = residuals(signals, &series.t_s, &start, shift_s).iter().map(|r| r * r).sum::<f64>();
    let (mut values, mut evaluations) = (initial.clone(), 1);
    // The shift found with the scenario's values is biased by their error: fit, re-align with the
    // fitted values, and fit again until the shift holds to a tenth of a sample.
    let resolution = sample_interval_s(signals) / 10.0;
    let solution = loop {
        let mut objective = |values: &[f64]| {
            let (_, series) = problem.run_at(values)?;
            Ok::<_, FitError>(residuals(signals, &series.t_s, &simulated(signals, &series, defs)?, shift_s))
        };
        let solution = lm::minimize(&mut objective, &values, &bounds, options)?;
        evaluations += solution.evaluations;
        if !align {
            break solution;
        }
        let (_, series) = problem.run_at(&solution.parameters)?;
        evaluations += 1;
        let aligned = alignment_shift(signals, &series.t_s, &simulated(signals, &series, defs)?);
        let settled = (aligned - shift_s).abs() <= resolution;
        values.clone_from(&solution.parameters);
        shift_s = aligned;
        if settled || evaluations > 20 * options.max_iterations {
            break solution;
        }
    };
    // The same fit at half the step, from this solution: what the value owes to the step.
    let refined = problem.refined();
    let mut objective = |values: &[f64]| {
        let (_, series) = refined.run_at(values)?;
        Ok::<_, FitError>(residuals(signals, &series.t_s, &simulated(signals, &series, defs)?, shift_s))
    };
    let fine = lm::minimize(&mut objective, &solution.parameters, &bounds, options)?;
    evaluations += fine.evaluations;
    let n = fine.residuals as f64;
    let parameters = problem
        .parameters
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (value, se) = (fine.parameters[i], fine.standard_errors[i]);
            let numerical = (value - solution.parameters[i]).abs();
            let half = 1.96 * se.hypot(numerical);
            Fitted {
                key: p.key.clone(),
                initial: p.initial,
                value,
                standard_error: se,
                numerical_uncertainty: numerical,
                interval_95: [value - half, value + half],
                bounds: [p.bounds.0, p.bounds.1],
            }
        })
        .collect();
    let solution = fine;
    Ok(FitReport {
        parameters,
        shift_s,
        rms_residual: [start_ssr, solution.sum_of_squares[1]].map(|s| (s / n).sqrt()),
        evaluations,
        iterations: solution.iterations,
        converged: solution.converged,
        residuals: solution.residuals,
        effective_samples: solution.effective_samples,
    })
}

/// The simulated signal at times `t_s` (linear between steps, held beyond the ends).
fn resample(t_sim: &[f64], values: &[f64], t_s: &[f64]) -> Vec<f64> {
    let mut j = 0;
    t_s.iter()
        .map(|&t| {
            while j + 2 < t_sim.len() && t_sim[j + 1] < t {
                j += 1;
            }
            let (a, b) = (j, (j + 1).min(t_sim.len() - 1));
            let w = if t_sim[b] > t_sim[a] { ((t - t_sim[a]) / (t_sim[b] - t_sim[a])).clamp(0.0, 1.0) } else { 0.0 };
            values[a] + w * (values[b] - values[a])
        })
        .collect()
}

/// Each measured signal's simulated twin at every step of `series`.
fn simulated(signals: &[Signal], series: &Series, defs: &[Channel]) -> Result<Vec<Vec<f64>>, FitError> {
    signals
        .iter()
        .map(|signal| {
            let def = defs.iter().find(|d| d.name == signal.name);
            def.map(|d| series.values(d)).ok_or_else(|| FitError::Signal(signal.name.clone()))
        })
        .collect()
}

/// Every signal's residuals at its times shifted by `shift_s`, over its measured peak, against
/// its `simulated` values at the run's times `t_sim`.
fn residuals(signals: &[Signal], t_sim: &[f64], simulated: &[Vec<f64>], shift_s: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for (signal, values) in signals.iter().zip(simulated) {
        let times: Vec<f64> = signal.t_s.iter().map(|t| t + shift_s).collect();
        let sim = resample(t_sim, values, &times);
        let peak = signal.values.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(1e-300);
        out.extend(sim.iter().zip(&signal.values).map(|(s, m)| (s - m) / peak));
    }
    out
}

/// The first signal's mean sample interval, s (0 without samples).
fn sample_interval_s(signals: &[Signal]) -> f64 {
    signals
        .first()
        .filter(|s| s.t_s.len() >= 2)
        .map_or(0.0, |s| (s.t_s[s.t_s.len() - 1] - s.t_s[0]) / (s.t_s.len() - 1) as f64)
}

/// The shift of the measured times that best aligns the signals with the run: the least summed
/// squared difference (the cross-correlation's peak, for signals of equal energy) over shifts of
/// whole samples within a tenth of the record, refined by a parabola through the best and its
/// neighbours.
fn alignment_shift(signals: &[Signal], t_sim: &[f64], simulated: &[Vec<f64>]) -> f64 {
    let Some(first) = signals.first().filter(|s| s.t_s.len() >= 2) else { return 0.0 };
    let dt = sample_interval_s(signals);
    let reach = (first.t_s.len() / 10) as i64;
    let score = |k: i64| -residuals(signals, t_sim, simulated, k as f64 * dt).iter().map(|x| x * x).sum::<f64>();
    let mut best = (0, score(0));
    for k in -reach..=reach {
        let s = score(k);
        if s > best.1 {
            best = (k, s);
        }
    }
    let (k, s0) = best;
    let (sm, sp) = (score(k - 1), score(k + 1));
    let curvature = sm - 2.0 * s0 + sp;
    let offset = if curvature < 0.0 { 0.5 * (sm - sp) / curvature } else { 0.0 };
    (k as f64 + offset.clamp(-0.5, 0.5)) * dt
}
