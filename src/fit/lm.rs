//! Levenberg–Marquardt for a few bounded, positive parameters, with the covariance of the
//! estimate from the Jacobian.
//!
//! The parameters are searched in log space (u = ln p: stiffnesses span decades, damping ratios
//! are small) and kept within their bounds by projection. The Jacobian is taken by forward
//! differences of the residuals: each residual evaluation is a whole simulation, and a few
//! parameters make that cheaper than any analytic route. The damping follows Marquardt's scaling,
//! (JᵀJ + λ diag JᵀJ) δ = −Jᵀr.
//!
//! Written here rather than taken from `levenberg-marquardt` or `argmin`: both are built on
//! nalgebra 0.34, and this crate is on 0.35; for a handful of parameters the algorithm is shorter
//! than the glue between two nalgebras.

use nalgebra::{DMatrix, DVector};

/// How the search stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Most iterations (each costs one evaluation per parameter for the Jacobian, plus one or
    /// more trial steps).
    pub max_iterations: usize,
    /// Stop when the sum of squares falls by less than this fraction in an accepted step.
    pub relative_tolerance: f64,
    /// Forward-difference step in log space (a relative change of the parameter).
    pub difference_step: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions { max_iterations: 40, relative_tolerance: 1e-9, difference_step: 1e-4 }
    }
}

/// The least-squares solution and what it cost.
#[derive(Debug, Clone, PartialEq)]
pub struct LmSolution {
    /// The parameters found.
    pub parameters: Vec<f64>,
    /// Their standard errors from the Jacobian at the solution (module doc of [`super`]).
    pub standard_errors: Vec<f64>,
    /// Sum of squared residuals at the start and at the solution.
    pub sum_of_squares: [f64; 2],
    /// Residual evaluations spent.
    pub evaluations: usize,
    /// Iterations taken.
    pub iterations: usize,
    /// Whether it stopped on the tolerance (not on the iteration limit).
    pub converged: bool,
    /// Number of residuals.
    pub residuals: usize,
    /// The residuals' effective number of independent samples (their lag-one autocorrelation
    /// taken into account), used for the standard errors.
    pub effective_samples: f64,
}

/// Minimises Σ rᵢ(p)² over `lower ≤ p ≤ upper` (every bound > 0) from `initial`.
pub fn minimize<E>(
    mut residuals: impl FnMut(&[f64]) -> Result<Vec<f64>, E>,
    initial: &[f64],
    bounds: &[(f64, f64)],
    options: &LmOptions,
) -> Result<LmSolution, E> {
    let n = initial.len();
    let log_bounds: Vec<(f64, f64)> = bounds.iter().map(|&(lo, hi)| (lo.ln(), hi.ln())).collect();
    let project = |u: &mut DVector<f64>| {
        for (x, &(lo, hi)) in u.iter_mut().zip(&log_bounds) {
            *x = x.clamp(lo, hi);
        }
    };
    let params = |u: &DVector<f64>| u.iter().map(|x| x.exp()).collect::<Vec<f64>>();
    let mut u = DVector::from_iterator(n, initial.iter().map(|p| p.ln()));
    project(&mut u);
    let mut evaluations = 0;
    let mut evaluate = |u: &DVector<f64>| {
        evaluations += 1;
        residuals(&params(u)).map(DVector::from_vec)
    };
    let mut r = evaluate(&u)?;
    let start_ssr = r.norm_squared();
    let mut lambda = 1e-3;
    let (mut iterations, mut converged) = (0, false);
    let mut jacobian = DMatrix::zeros(r.len(), n);
    while iterations < options.max_iterations && !converged {
        iterations += 1;
        jacobian = forward_differences(&mut evaluate, &u, &r, options.difference_step, &log_bounds)?;
        let gradient = jacobian.transpose() * &r;
        let normal = jacobian.transpose() * &jacobian;
        let ssr = r.norm_squared();
        loop {
            let mut damped = normal.clone();
            for i in 0..n {
                damped[(i, i)] += lambda * normal[(i, i)].max(1e-12);
            }
            let Some(step) = damped.lu().solve(&(-&gradient)) else {
                lambda *= 10.0;
                continue;
            };
            let mut trial = &u + step;
            project(&mut trial);
            let trial_r = evaluate(&trial)?;
            let trial_ssr = trial_r.norm_squared();
            if trial_ssr < ssr {
                converged = (ssr - trial_ssr) <= options.relative_tolerance * ssr;
                u = trial;
                r = trial_r;
                lambda = (lambda / 3.0).max(1e-12);
                break;
            }
            lambda *= 4.0;
            if lambda > 1e12 {
                // No step lowers the sum: at a minimum to the resolution of the residuals.
                converged = true;
                break;
            }
        }
    }
    let p = params(&u);
    let effective_samples = effective_samples(&r);
    let standard_errors = standard_errors(&jacobian, &r, &p, effective_samples);
    Ok(LmSolution {
        parameters: p,
        standard_errors,
        sum_of_squares: [start_ssr, r.norm_squared()],
        evaluations,
        iterations,
        converged,
        residuals: r.len(),
        effective_samples,
    })
}

/// ∂r/∂u by forward differences, stepping inward at an upper bound.
fn forward_differences<E>(
    evaluate: &mut impl FnMut(&DVector<f64>) -> Result<DVector<f64>, E>,
    u: &DVector<f64>,
    r: &DVector<f64>,
    step: f64,
    log_bounds: &[(f64, f64)],
) -> Result<DMatrix<f64>, E> {
    let mut jacobian = DMatrix::zeros(r.len(), u.len());
    for j in 0..u.len() {
        let h = if u[j] + step > log_bounds[j].1 { -step } else { step };
        let mut shifted = u.clone();
        shifted[j] += h;
        let rj = evaluate(&shifted)?;
        jacobian.set_column(j, &((rj - r) / h));
    }
    Ok(jacobian)
}

/// Independent samples worth of `r`: n (1 − ρ₁) / (1 + ρ₁), ρ₁ its lag-one autocorrelation
/// (the AR(1) correction; model error, smooth in time, makes residuals correlated and the plain
/// count of samples would overstate what they tell).
fn effective_samples(r: &DVector<f64>) -> f64 {
    let n = r.len() as f64;
    let (sum0, sum1) = r.iter().zip(r.iter().skip(1)).fold((0.0, 0.0), |(s0, s1), (a, b)| (s0 + a * a, s1 + a * b));
    let rho = if sum0 > 0.0 { (sum1 / sum0).clamp(0.0, 0.999) } else { 0.0 };
    (n * (1.0 - rho) / (1.0 + rho)).max(2.0)
}

/// √diag(s² (JₚᵀJₚ)⁻¹) with Jₚ = J_u / p and s² = SSR / (n_eff − k): the parameters' standard
/// errors (NaN where the Jacobian does not determine them).
fn standard_errors(jacobian_u: &DMatrix<f64>, r: &DVector<f64>, p: &[f64], effective_samples: f64) -> Vec<f64> {
    let k = p.len();
    let mut jp = jacobian_u.clone();
    for (j, pj) in p.iter().enumerate() {
        jp.column_mut(j).unscale_mut(*pj);
    }
    // The residuals stand for `effective_samples` independent ones: scale the information.
    let information = (jp.transpose() * &jp) * (effective_samples / r.len() as f64);
    let s2 = r.norm_squared() / r.len() as f64 * effective_samples / (effective_samples - k as f64).max(1.0);
    match information.try_inverse() {
        Some(cov) => (0..k).map(|i| (s2 * cov[(i, i)]).max(0.0).sqrt()).collect(),
        None => vec![f64::NAN; k],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y = a e^{−b t} sampled without noise: the fit finds (a, b) from a start off by 2×.
    #[test]
    fn an_exponential_decay_is_recovered_from_a_distant_start() {
        let t: Vec<f64> = (0..50).map(|i| 0.1 * i as f64).collect();
        let (a, b) = (3.0, 0.7);
        let mut residuals =
            |p: &[f64]| Ok::<_, ()>(t.iter().map(|&t| p[0] * (-p[1] * t).exp() - a * (-b * t).exp()).collect());
        let solution =
            minimize(&mut residuals, &[6.0, 0.35], &[(0.1, 100.0), (0.01, 10.0)], &LmOptions::default()).unwrap();
        assert!(solution.converged, "{solution:?}");
        assert!((solution.parameters[0] - a).abs() < 1e-6 && (solution.parameters[1] - b).abs() < 1e-6, "{solution:?}");
    }

    /// With noise of known σ on independent samples, the standard errors match the textbook
    /// least-squares ones: for y = c (one parameter), σ/√n.
    #[test]
    fn the_standard_error_of_a_mean_is_sigma_over_root_n() {
        // Alternating ±σ: independent-looking (lag-one autocorrelation −1, clamped to 0).
        let (c, sigma, n) = (2.0, 0.1, 400);
        let y: Vec<f64> = (0..n).map(|i| c + if i % 2 == 0 { sigma } else { -sigma }).collect();
        let mut residuals = |p: &[f64]| Ok::<_, ()>(y.iter().map(|y| p[0] - y).collect());
        let solution = minimize(&mut residuals, &[1.0], &[(0.1, 10.0)], &LmOptions::default()).unwrap();
        assert!((solution.parameters[0] - c).abs() < 1e-9);
        let expected = sigma / ((n - 1) as f64).sqrt();
        assert!((solution.standard_errors[0] / expected - 1.0).abs() < 0.01, "{solution:?} vs {expected}");
    }

    /// A bound the optimum lies beyond holds the parameter on it.
    #[test]
    fn a_bound_holds() {
        let mut residuals = |p: &[f64]| Ok::<_, ()>(vec![p[0] - 5.0]);
        let solution = minimize(&mut residuals, &[1.0], &[(0.5, 2.0)], &LmOptions::default()).unwrap();
        assert!((solution.parameters[0] - 2.0).abs() < 1e-12, "{solution:?}");
    }

    /// Smooth (correlated) residuals count as fewer samples than their number.
    #[test]
    fn correlated_residuals_count_as_fewer_samples() {
        let smooth = DVector::from_iterator(1000, (0..1000).map(|i| (i as f64 * 0.01).sin()));
        let rough = DVector::from_iterator(1000, (0..1000).map(|i| if i % 2 == 0 { 1.0 } else { -1.0 }));
        assert!(effective_samples(&smooth) < 10.0);
        assert_eq!(effective_samples(&rough), 1000.0);
    }
}
