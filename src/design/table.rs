//! The seed's table of acceleration limits (Wang et al. 2022, §4: "the acceleration value in the
//! start and stop process should not be greater than 7~8°/s²" for a trapezoid on a stiff arm,
//! "about 9°/s²" under an S-curve, ...), computed for the user's own arm: for each drive profile
//! — trapezoidal, S-curve, and the trapezoid under each input shaper — the largest start/stop
//! acceleration at which the residual tip amplitude (and, if given, the peak contact force)
//! stays within its limit.
//!
//! The lift keeps the scenario's start, end and duration; the search runs over the ramp
//! fraction (accel phase over lift time, the acceleration falls as it grows) from
//! [`MIN_RAMP_FRACTION`] to 0.5 with the bracketing search of [`super::search`] on a grid of
//! [`TABLE_GRID`] ramps, so the answer is the boundary above which every ramp on the grid passes. The acceleration reported is the
//! hub's peak under the profile as run (a shaper lowers the base profile's).

use std::path::Path;

use serde::Serialize;

use super::search::{Problem, minimize};
use super::{DesignError, Evaluator, Limit, Objective, Robustness};

/// The sharpest ramp searched: an accel phase of 0.2 % of the lift time (on a 15 s lift of 90°,
/// 200 °/s²: beyond what a pipe-handling arm's drive gives).
pub const MIN_RAMP_FRACTION: f64 = 0.002;
/// The S-curve's jerk phases, as a fraction of its accel phase (0.5: no constant-accel part).
pub const S_CURVE_JERK_FRACTION: f64 = 0.25;

/// Ramp fractions tried before bisection, evenly spaced in their logarithm: the acceleration
/// goes as 1/(f (1 − f)), so even steps in log f are near-even steps in log acceleration (23 %
/// apart). Where a limit is not monotone in the ramp (the arrival phase of the arm's mode), the
/// answer is the boundary above the sharpest failing point of this grid.
pub const TABLE_GRID: usize = 25;

fn ramp_grid() -> Vec<f64> {
    let (lo, hi) = (MIN_RAMP_FRACTION.ln(), 0.5_f64.ln());
    (0..TABLE_GRID).map(|i| (lo + (hi - lo) * i as f64 / (TABLE_GRID - 1) as f64).exp()).collect()
}

/// The profiles of the table: (profile, shaper).
pub const PROFILES: [(&str, Option<&str>); 5] = [
    ("trapezoidal", None),
    ("s-curve", None),
    ("trapezoidal", Some("zv")),
    ("trapezoidal", Some("zvd")),
    ("trapezoidal", Some("ei")),
];

/// One row of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TableRow {
    /// The drive profile.
    pub profile: String,
    /// Its input shaper, if any.
    pub shaper: Option<String>,
    /// The largest start/stop acceleration within the limits, deg/s² (none: even a ramp of half
    /// the lift fails; `at_least` when the sharpest ramp searched passes).
    pub largest_accel_deg_s2: Option<f64>,
    /// Whether the sharpest ramp searched passed (the limit lies beyond the search).
    pub at_least: bool,
    /// The ramp fraction there.
    pub ramp_fraction: Option<f64>,
    /// The limited figures there (p95 over the draws, or the nominal run's).
    pub figures: Vec<f64>,
    /// Candidates evaluated.
    pub candidates: usize,
}

/// The table: its limits and rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AccelerationTable {
    /// The limits each row holds.
    pub limits: Vec<Limit>,
    /// Runs per candidate.
    pub runs_per_candidate: usize,
    /// A row per profile.
    pub rows: Vec<TableRow>,
}

/// The table for the scenario at `path`.
pub fn acceleration_table(
    path: &Path,
    limits: &[Limit],
    robustness: &Robustness,
    tolerance: f64,
    threads: Option<usize>,
) -> Result<AccelerationTable, DesignError> {
    let keys = vec!["drive.ramp_fraction".to_string()];
    let reported = vec!["drive.peak_accel_deg_s2".to_string()];
    let mut evaluator = Evaluator::new(path, keys, limits.to_vec(), reported, robustness, threads)?;
    let mut rows = Vec::new();
    for (profile, shaper) in PROFILES {
        // The whole drive table is replaced for each profile (a pinned shaper tuning with it).
        evaluator.set_base("drive", drive_table(&evaluator, profile, shaper)?)?;
        evaluator.pin_shaper()?;
        let objective = Objective::Coordinate(0);
        if rows.is_empty() {
            evaluator.check_figures(&[0.25], &objective)?;
        }
        let evaluate = |x: &[f64]| evaluator.evaluate(x, &objective);
        let problem = Problem {
            bounds: vec![(MIN_RAMP_FRACTION, 0.5)],
            objective_coordinate: Some(0),
            tolerance,
            budget: TABLE_GRID + 20,
            grid: Some(ramp_grid()),
            evaluate: &evaluate,
        };
        let outcome = minimize(&problem);
        let best = outcome.best.as_ref();
        rows.push(TableRow {
            profile: profile.into(),
            shaper: shaper.map(Into::into),
            largest_accel_deg_s2: best.map(|b| b.reported[0]),
            at_least: best.is_some_and(|b| b.x[0] <= MIN_RAMP_FRACTION * (1.0 + 1e-9)),
            ramp_fraction: best.map(|b| b.x[0]),
            figures: best.map(|b| b.figures.clone()).unwrap_or_default(),
            candidates: outcome.history.len(),
        });
    }
    Ok(AccelerationTable { limits: limits.to_vec(), runs_per_candidate: evaluator.runs_per_candidate(), rows })
}

/// The scenario's lift as `profile` (under `shaper`), its ramp fraction to be set.
fn drive_table(evaluator: &Evaluator, profile: &str, shaper: Option<&str>) -> Result<toml::Value, DesignError> {
    let number = |key: &str| {
        evaluator.base_number(&format!("drive.{key}")).ok_or_else(|| {
            DesignError::Argument(format!(
                "the acceleration table needs a drive with start_deg, end_deg and duration_s; the scenario's \
                 drive has no `drive.{key}`"
            ))
        })
    };
    let mut table = toml::Table::new();
    table.insert("kind".into(), profile.into());
    for key in ["start_deg", "end_deg", "duration_s"] {
        table.insert(key.into(), number(key)?.into());
    }
    table.insert("ramp_fraction".into(), 0.25.into());
    if profile == "s-curve" {
        table.insert("jerk_fraction".into(), S_CURVE_JERK_FRACTION.into());
    }
    if let Some(shaper) = shaper {
        table.insert("shaper".into(), shaper.into());
    }
    Ok(toml::Value::Table(table))
}
