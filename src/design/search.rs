//! The search of `pipearm design`, independent of the simulator: minimise an objective over a
//! box subject to limits `g_j(x) <= 0`, where each evaluation is a batch of runs.
//!
//! - **One coordinate, and it is the objective** (the shortest lift time, the largest
//!   acceleration): the limits hold above a boundary. A grid of [`GRID_1D`] points finds the
//!   highest grid point that fails, and bisection between it and the grid point above closes
//!   the bracket to `tolerance` of the range, in `GRID_1D + ⌈log2(1/(8 tolerance))⌉` evaluations. The
//!   answer is conservative where the limits are not monotone: every grid point above it passes.
//! - **Otherwise**: a coarse grid (up to 5 points a coordinate, within half the budget), then
//!   Nelder–Mead (argmin) from the best grid point on the
//!   objective with an exact penalty, `f + PENALTY · Σ max(0, g_j)` (each g scaled by its limit),
//!   the box kept by clamping. The answer is the best *feasible* point evaluated.

use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use serde::Serialize;

/// Grid points of a one-coordinate search.
pub const GRID_1D: usize = 9;
/// Weight of a limit's relative violation against the objective's relative value.
pub const PENALTY: f64 = 1e3;

/// One evaluation: the objective and each limit's margin `g` (<= 0 where it holds), or why the
/// point could not be evaluated (treated as infeasible).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// The point, one value per coordinate.
    pub x: Vec<f64>,
    /// The objective there.
    pub objective: f64,
    /// Each limit's figure there.
    pub figures: Vec<f64>,
    /// Each limit's margin, relative: (figure − limit) / |limit| for `<=`; <= 0 holds.
    pub margins: Vec<f64>,
    /// Whether every limit holds.
    pub feasible: bool,
    /// Figures reported beside the limits (the median over the runs).
    pub reported: Vec<f64>,
}

/// The problem: the box and how to evaluate a point.
pub struct Problem<'a> {
    /// Lower and upper bound of each coordinate.
    pub bounds: Vec<(f64, f64)>,
    /// The coordinate that is itself the objective, if any.
    pub objective_coordinate: Option<usize>,
    /// Relative tolerance on each coordinate (of its range).
    pub tolerance: f64,
    /// Most evaluations.
    pub budget: usize,
    /// The grid of a one-coordinate search, increasing (default [`GRID_1D`] even points).
    pub grid: Option<Vec<f64>>,
    /// Evaluates a point.
    pub evaluate: &'a (dyn Fn(&[f64]) -> Evaluation + Sync),
}

/// What the search found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// The best feasible point, if any was found.
    pub best: Option<Evaluation>,
    /// Every evaluation, in order.
    pub history: Vec<Evaluation>,
    /// `bracket` or `nelder-mead`.
    pub method: &'static str,
}

/// Minimises `problem`'s objective subject to its limits.
pub fn minimize(problem: &Problem) -> Outcome {
    match problem.objective_coordinate {
        Some(0) if problem.bounds.len() == 1 => bracket(problem),
        _ => nelder_mead(problem),
    }
}

/// The best feasible evaluation of `history` (lowest objective).
fn best_feasible(history: &[Evaluation]) -> Option<Evaluation> {
    history.iter().filter(|e| e.feasible).min_by(|a, b| a.objective.total_cmp(&b.objective)).cloned()
}

/// One coordinate that is the objective: grid, then bisection at the feasibility boundary next
/// to the lowest feasible grid point.
fn bracket(problem: &Problem) -> Outcome {
    let (lo, hi) = problem.bounds[0];
    let grid: Vec<f64> = match &problem.grid {
        Some(points) => points.clone(),
        None => (0..GRID_1D).map(|i| lo + (hi - lo) * i as f64 / (GRID_1D - 1) as f64).collect(),
    };
    let mut history: Vec<Evaluation> = grid.iter().map(|x| (problem.evaluate)(&[*x])).collect();
    // The highest infeasible grid point: the answer is above it, so that every grid point above
    // the answer passes too (a limit that passes again below a failing point is not trusted).
    let Some(i) = history.iter().rposition(|e| !e.feasible) else {
        return Outcome { best: best_feasible(&history), history, method: "bracket" };
    };
    if i + 1 == grid.len() {
        return Outcome { best: None, history, method: "bracket" };
    }
    let (mut bad, mut good) = (history[i].x[0], history[i + 1].x[0]);
    while (good - bad).abs() > problem.tolerance * (hi - lo) && history.len() < problem.budget {
        let mid = 0.5 * (bad + good);
        let e = (problem.evaluate)(&[mid]);
        if e.feasible {
            good = mid
        } else {
            bad = mid
        }
        history.push(e);
    }
    let above: Vec<Evaluation> = history.iter().filter(|e| e.x[0] > bad).cloned().collect();
    Outcome { best: best_feasible(&above), history, method: "bracket" }
}

/// The penalised objective over the box (clamped), recording every evaluation.
struct Penalised<'a, 'p> {
    problem: &'a Problem<'p>,
    scale: f64,
    /// Evaluations spent before the simplex (the grid).
    spent: usize,
    history: &'a std::sync::Mutex<Vec<Evaluation>>,
}

impl Penalised<'_, '_> {
    fn clamp(&self, x: &[f64]) -> Vec<f64> {
        x.iter().zip(&self.problem.bounds).map(|(v, (lo, hi))| v.clamp(*lo, *hi)).collect()
    }
}

impl CostFunction for Penalised<'_, '_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let clamped = self.clamp(x);
        let outside: f64 = x.iter().zip(&clamped).map(|(a, b)| (a - b).abs()).sum();
        let mut history = self.history.lock().expect("no evaluation panics holding it");
        if self.spent + history.len() >= self.problem.budget {
            return Ok(f64::INFINITY);
        }
        let e = (self.problem.evaluate)(&clamped);
        let violation: f64 = e.margins.iter().map(|g| if g.is_finite() { g.max(0.0) } else { 1e6 }).sum();
        let cost = e.objective / self.scale + PENALTY * (violation + outside);
        history.push(e);
        Ok(if cost.is_finite() { cost } else { f64::INFINITY })
    }
}

/// A grid of up to 5 points per coordinate (within half the budget), then Nelder–Mead from the
/// best, the whole search within the budget.
fn nelder_mead(problem: &Problem) -> Outcome {
    let d = problem.bounds.len();
    // Up to 5 points a key, fewer where the budget keeps at least half of it for the simplex.
    let per_axis = (2..=5).rev().find(|n: &usize| n.pow(d as u32) <= problem.budget / 2).unwrap_or(2);
    let grid: Vec<Vec<f64>> = (0..per_axis.pow(d as u32))
        .map(|mut n| {
            problem
                .bounds
                .iter()
                .map(|(lo, hi)| {
                    let i = n % per_axis;
                    n /= per_axis;
                    lo + (hi - lo) * i as f64 / (per_axis - 1) as f64
                })
                .collect()
        })
        .collect();
    let mut history: Vec<Evaluation> = grid.iter().map(|x| (problem.evaluate)(x)).collect();
    let score = |e: &Evaluation| e.margins.iter().map(|g| g.max(0.0)).sum::<f64>() * 1e9 + e.objective;
    let start = history.iter().min_by(|a, b| score(a).total_cmp(&score(b))).expect("a grid").clone();
    let scale = start.objective.abs().max(1e-12);
    // The simplex: the start and a step of a quarter of the range along each coordinate, inward.
    let simplex: Vec<Vec<f64>> = std::iter::once(start.x.clone())
        .chain((0..d).map(|k| {
            let mut x = start.x.clone();
            let (lo, hi) = problem.bounds[k];
            let step = 0.25 * (hi - lo);
            x[k] = if x[k] + step <= hi { x[k] + step } else { x[k] - step };
            x
        }))
        .collect();
    let searched = std::sync::Mutex::new(Vec::new());
    let cost = Penalised { problem, scale, spent: history.len(), history: &searched };
    let solver = NelderMead::new(simplex).with_sd_tolerance(1e-9 * scale.max(1.0)).expect("a positive tolerance");
    let iterations = (problem.budget.saturating_sub(history.len())) as u64;
    // A failed run of the solver leaves the evaluations it made, which are all the answer needs.
    let _ = Executor::new(cost, solver).configure(|s| s.max_iters(iterations)).run();
    history.extend(searched.into_inner().expect("no evaluation panics holding it"));
    Outcome { best: best_feasible(&history), history, method: "nelder-mead" }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn evaluation(x: &[f64], objective: f64, figures: &[(f64, f64)]) -> Evaluation {
        let margins: Vec<f64> = figures.iter().map(|(f, limit)| (f - limit) / limit.abs()).collect();
        Evaluation {
            x: x.to_vec(),
            objective,
            figures: figures.iter().map(|f| f.0).collect(),
            feasible: margins.iter().all(|g| *g <= 0.0),
            margins,
            reported: Vec::new(),
        }
    }

    /// The shortest x in [1, 10] with 1/x <= 0.25: x = 4.
    #[test]
    fn bracketing_finds_the_boundary_of_a_monotone_limit() {
        let evaluate = |x: &[f64]| evaluation(x, x[0], &[(1.0 / x[0], 0.25)]);
        let problem = Problem {
            bounds: vec![(1.0, 10.0)],
            objective_coordinate: Some(0),
            tolerance: 1e-4,
            budget: 50,
            grid: None,
            evaluate: &evaluate,
        };
        let outcome = minimize(&problem);
        let best = outcome.best.unwrap();
        assert!((best.x[0] - 4.0).abs() < 1e-3 && best.feasible, "{best:?}");
        assert!(outcome.history.len() <= GRID_1D + 17, "{}", outcome.history.len());
    }

    /// min (x − 2)² + (y − 1)² subject to x + y <= 2 on [0, 3]²: the optimum is the projection
    /// of (2, 1) on the line, (1.5, 0.5), with objective 0.5.
    #[test]
    fn nelder_mead_finds_the_constrained_optimum_on_its_boundary() {
        let evaluate = |x: &[f64]| evaluation(x, (x[0] - 2.0).powi(2) + (x[1] - 1.0).powi(2), &[(x[0] + x[1], 2.0)]);
        let problem = Problem {
            bounds: vec![(0.0, 3.0), (0.0, 3.0)],
            objective_coordinate: None,
            tolerance: 1e-4,
            budget: 400,
            grid: None,
            evaluate: &evaluate,
        };
        let best = minimize(&problem).best.unwrap();
        assert!((best.x[0] - 1.5).abs() < 0.02 && (best.x[1] - 0.5).abs() < 0.02, "{best:?}");
        assert!((best.objective - 0.5).abs() < 0.02 && best.feasible, "{best:?}");
    }

    /// The grid and the simplex together keep to the budget, in any number of coordinates.
    #[test]
    fn the_search_keeps_to_its_budget() {
        let evaluate = |x: &[f64]| evaluation(x, x.iter().map(|v| (v - 0.3).powi(2)).sum(), &[(x[0], 2.0)]);
        for (d, budget) in [(2, 12), (3, 20), (4, 40)] {
            let problem = Problem {
                bounds: vec![(0.0, 1.0); d],
                objective_coordinate: None,
                tolerance: 1e-4,
                budget,
                grid: None,
                evaluate: &evaluate,
            };
            let outcome = minimize(&problem);
            assert!(outcome.history.len() <= budget, "{d} coordinates: {} > {budget}", outcome.history.len());
            assert!(outcome.best.is_some());
        }
    }

    /// Nothing feasible in the box: no answer, and the budget is kept.
    #[test]
    fn an_infeasible_box_gives_no_answer() {
        let evaluate = |x: &[f64]| evaluation(x, x[0], &[(x[0], -1.0)]);
        let problem = Problem {
            bounds: vec![(0.0, 1.0)],
            objective_coordinate: Some(0),
            tolerance: 1e-3,
            budget: 20,
            grid: None,
            evaluate: &evaluate,
        };
        let outcome = minimize(&problem);
        assert!(outcome.best.is_none() && outcome.history.len() == GRID_1D);
    }
}
