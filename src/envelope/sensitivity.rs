//! Which uncertain key drives a result: Sobol indices from a Saltelli design, standardized
//! regression coefficients from any sample, and order-statistic quantiles of a result.
//!
//! - **Sobol indices** (variance-based, no model assumed): the first-order index S_i is the share of
//!   the result's variance explained by key i alone; the total index S_Ti adds every interaction
//!   with other keys. S_Ti − S_i large means key i acts through interactions; Σ S_i < 1 means
//!   interactions matter. Needs N(k + 2) runs.
//! - **Standardized regression coefficients** (SRC): the slope of the standardized result on the
//!   standardized keys; SRC_i² is key i's share of the variance when the result is close to linear
//!   in the keys (R² near 1); with a low R² they rank the keys' linear trends only. Any sample of
//!   more than k + 1 runs.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::dist::normal_quantile;
use super::sample::{SaltelliDesign, below, stream};

/// An estimate with its 95 % confidence interval [low, high].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Index {
    /// The point estimate.
    pub estimate: f64,
    /// Lower end of the 95 % confidence interval.
    pub low: f64,
    /// Upper end of the 95 % confidence interval.
    pub high: f64,
}

/// First-order and total Sobol indices of each input, in the design's column order.
#[derive(Debug, Clone, PartialEq)]
pub struct SobolIndices {
    /// First-order indices S_i.
    pub first: Vec<Index>,
    /// Total indices S_Ti.
    pub total: Vec<Index>,
}

/// Sobol indices of the result `y` of a [`SaltelliDesign`] (one value per row, in the design's row
/// order A, B, AB_0, ...), with 95 % percentile-bootstrap intervals from `bootstrap` resamples of
/// the N base rows (each resample redraws N base indices with replacement and recomputes V and
/// every index on the same rows), seeded by `seed`.
///
/// Estimators, with V the variance of y over the A and B rows together (divisor 2N):
/// - first order, Saltelli et al. 2010 (Comput. Phys. Commun. 181, 259, table 2 (b)):
///   S_i = mean(y_B · (y_ABi − y_A)) / V;
/// - total, Jansen 1999 (Comput. Phys. Commun. 117, 35): S_Ti = mean((y_A − y_ABi)²) / 2 / V.
///
/// y is first centred on the mean of its A and B rows (as SALib does): the estimators' expectations
/// do not change with a shift of y, but the first-order one's variance grows with the mean².
/// Sampling error shrinks as 1/√N; the intervals say how large it is. Estimates may fall slightly
/// outside [0, 1]. A constant result (V = 0) gives NaN indices; `bootstrap` = 0 gives NaN
/// intervals. `y` must be finite.
///
/// # Panics
/// If `y` does not hold one value per design row.
pub fn sobol(design: &SaltelliDesign, y: &[f64], bootstrap: usize, seed: u64) -> SobolIndices {
    let n = design.base;
    let centre = (design.y_a(y).iter().chain(design.y_b(y)).sum::<f64>()) / (2 * n) as f64;
    let y: Vec<f64> = y.iter().map(|v| v - centre).collect();
    let y = y.as_slice();
    let all: Vec<usize> = (0..n).collect();
    let (first, total) = sobol_on(design, y, &all);
    let mut first_draws = vec![Vec::with_capacity(bootstrap); design.dimensions];
    let mut total_draws = first_draws.clone();
    let mut rng = stream(seed);
    let mut rows = vec![0; n];
    for _ in 0..bootstrap {
        rows.iter_mut().for_each(|r| *r = below(&mut rng, n as u64) as usize);
        let (f, t) = sobol_on(design, y, &rows);
        for i in 0..design.dimensions {
            first_draws[i].push(f[i]);
            total_draws[i].push(t[i]);
        }
    }
    SobolIndices { first: with_intervals(&first, first_draws), total: with_intervals(&total, total_draws) }
}

/// (first-order, total) indices on the base rows `rows` (repeats allowed).
fn sobol_on(design: &SaltelliDesign, y: &[f64], rows: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let (ya, yb) = (design.y_a(y), design.y_b(y));
    let count = rows.len() as f64;
    let mean = rows.iter().map(|&j| ya[j] + yb[j]).sum::<f64>() / (2.0 * count);
    let variance = rows.iter().map(|&j| (ya[j] - mean).powi(2) + (yb[j] - mean).powi(2)).sum::<f64>() / (2.0 * count);
    let indices = (0..design.dimensions).map(|i| {
        let yab = design.y_ab(y, i);
        let first = rows.iter().map(|&j| yb[j] * (yab[j] - ya[j])).sum::<f64>() / count;
        let total = rows.iter().map(|&j| (ya[j] - yab[j]).powi(2)).sum::<f64>() / (2.0 * count);
        (first / variance, total / variance)
    });
    indices.unzip()
}

/// Estimates with the 2.5 % and 97.5 % quantiles of their bootstrap draws.
fn with_intervals(estimates: &[f64], draws: Vec<Vec<f64>>) -> Vec<Index> {
    estimates
        .iter()
        .zip(draws)
        .map(|(&estimate, mut draws)| {
            draws.sort_by(f64::total_cmp);
            Index { estimate, low: quantile(&draws, 0.025), high: quantile(&draws, 0.975) }
        })
        .collect()
}

/// Standardized regression coefficients with their 95 % intervals, and the fit's R².
#[derive(Debug, Clone, PartialEq)]
pub struct Regression {
    /// One per input column, in order.
    pub coefficients: Vec<Index>,
    /// Share of the result's variance the linear fit explains.
    pub r_squared: f64,
}

/// Standardized regression coefficients of `y` on the columns of `x` (`x[run][input]`): ordinary
/// least squares of the standardized result on the standardized inputs, with an intercept.
///
/// Intervals: estimate ± t · standard error, the standard errors from the OLS covariance
/// σ̂² (ZᵀZ)⁻¹ with σ̂² = RSS / (n − q − 1) (q the inputs fitted), and t the Student quantile at
/// 0.975 for n − q − 1 degrees of freedom ([`student_t_quantile`]). They treat the sample's
/// standard deviations as exact, which holds to O(1/√n).
///
/// Degenerate data does not panic: an input column that does not vary gets a NaN coefficient
/// and is left out of the fit; a result that does not vary, or fewer runs than the fitted inputs
/// plus one, gives NaN for every coefficient and R²; exactly q + 1 runs give estimates with NaN
/// intervals. Values must be finite.
///
/// # Panics
/// If `x` and `y` differ in length or the rows of `x` differ in length.
pub fn standardized_regression(x: &[Vec<f64>], y: &[f64]) -> Regression {
    assert_eq!(x.len(), y.len(), "one result per sample");
    let inputs = x.first().map_or(0, Vec::len);
    assert!(x.iter().all(|row| row.len() == inputs), "every sample has the same inputs");
    let n = y.len();
    let nan = Index { estimate: f64::NAN, low: f64::NAN, high: f64::NAN };
    let mut coefficients = vec![nan; inputs];
    let failed = |coefficients| Regression { coefficients, r_squared: f64::NAN };
    let Some(ys) = standardized(y.iter().copied()) else { return failed(coefficients) };
    let columns: Vec<(usize, Vec<f64>)> =
        (0..inputs).filter_map(|i| standardized(x.iter().map(|row| row[i])).map(|z| (i, z))).collect();
    let q = columns.len();
    if n < q + 1 {
        return failed(coefficients);
    }
    let z = DMatrix::from_fn(n, q, |r, c| columns[c].1[r]);
    let ys = DVector::from_vec(ys);
    let Some(inverse) = (z.transpose() * &z).cholesky().map(|c| c.inverse()) else { return failed(coefficients) };
    let beta = &inverse * (z.transpose() * &ys);
    let rss = (&ys - &z * &beta).norm_squared();
    // Σ ys² = n − 1 for a standardized result.
    let r_squared = 1.0 - rss / (n - 1) as f64;
    let dof = n - q - 1;
    let half_width = |c: usize| {
        if dof == 0 { f64::NAN } else { student_t_quantile(0.975, dof) * (rss / dof as f64 * inverse[(c, c)]).sqrt() }
    };
    for (c, &(i, _)) in columns.iter().enumerate() {
        let h = half_width(c);
        coefficients[i] = Index { estimate: beta[c], low: beta[c] - h, high: beta[c] + h };
    }
    Regression { coefficients, r_squared }
}

/// (v − mean) / sd with the sample standard deviation (divisor n − 1); `None` if it is 0 or not
/// finite.
fn standardized(values: impl Iterator<Item = f64> + Clone) -> Option<Vec<f64>> {
    let n = values.clone().count();
    let mean = values.clone().sum::<f64>() / n as f64;
    let sd = (values.clone().map(|v| (v - mean).powi(2)).sum::<f64>() / (n as f64 - 1.0)).sqrt();
    // A column equal to its mean up to rounding does not vary.
    let spread = values.clone().fold(0.0_f64, |m, v| m.max((v - mean).abs()));
    (sd.is_finite() && sd > 0.0 && spread > 1e-13 * mean.abs()).then(|| values.map(|v| (v - mean) / sd).collect())
}

/// The Student t quantile t_ν(p) for ν ≥ 1 degrees of freedom: exact for ν = 1 (tan(π(p − ½))) and
/// ν = 2 ((2p − 1)/√(2p(1 − p))); from ν = 3 the Cornish–Fisher expansion in the normal quantile
/// x = Φ⁻¹(p) to 1/ν⁴ (Abramowitz & Stegun 26.7.5), within 0.13 % of the exact value at ν = 3,
/// 1.1e-4 at ν = 5 and 4e-6 at ν = 10 for p = 0.975 (smaller for p nearer ½).
pub fn student_t_quantile(p: f64, dof: usize) -> f64 {
    match dof {
        0 => f64::NAN,
        1 => (std::f64::consts::PI * (p - 0.5)).tan(),
        2 => (2.0 * p - 1.0) / (2.0 * p * (1.0 - p)).sqrt(),
        _ => {
            let x = normal_quantile(p);
            let (x2, nu) = (x * x, dof as f64);
            let g1 = x * (x2 + 1.0) / 4.0;
            let g2 = x * ((5.0 * x2 + 16.0) * x2 + 3.0) / 96.0;
            let g3 = x * (((3.0 * x2 + 19.0) * x2 + 17.0) * x2 - 15.0) / 384.0;
            let g4 = x * ((((79.0 * x2 + 776.0) * x2 + 1482.0) * x2 - 1920.0) * x2 - 945.0) / 92160.0;
            x + (g1 + (g2 + (g3 + g4 / nu) / nu) / nu) / nu
        }
    }
}

/// The `p`-quantile of ascending `sorted` values by linear interpolation between order statistics
/// (Hyndman & Fan 1996 type 7, the default of numpy's `quantile` and R's `quantile`): with
/// h = (n − 1)p, x₍⌊h⌋₎ + (h − ⌊h⌋)(x₍⌊h⌋+1₎ − x₍⌊h⌋₎), 0-based. p = 0 is the minimum, p = 1 the
/// maximum. NaN for an empty slice or p outside [0, 1].
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    debug_assert!(sorted.is_sorted_by(|a, b| a <= b), "quantile of unsorted values");
    if sorted.is_empty() || !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    let h = (sorted.len() - 1) as f64 * p;
    let low = h.floor() as usize;
    let high = (low + 1).min(sorted.len() - 1);
    sorted[low] + (h - low as f64) * (sorted[high] - sorted[low])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envelope::dist::Distribution;
    use crate::envelope::sample::{latin_hypercube, saltelli};
    use std::f64::consts::PI;

    #[test]
    fn quantile_type_7_matches_numpy() {
        // numpy.quantile([1, 3, 4, 7, 10], p): h = 4p; 0.1 → 1 + 0.4·2 = 1.8; 0.25 → 3;
        // 0.5 → 4; 0.9 → 7 + 0.6·3 = 8.8; 0.95 → 7 + 0.8·3 = 9.4.
        let x = [1.0, 3.0, 4.0, 7.0, 10.0];
        for (p, expected) in [(0.0, 1.0), (0.1, 1.8), (0.25, 3.0), (0.5, 4.0), (0.9, 8.8), (0.95, 9.4), (1.0, 10.0)] {
            assert!((quantile(&x, p) - expected).abs() < 1e-12, "p = {p}: {}", quantile(&x, p));
        }
        // Even count: numpy.quantile([2, 4, 6, 8], 0.5) = 5, 0.99 → h = 2.97 → 6 + 0.97·2 = 7.94.
        assert!((quantile(&[2.0, 4.0, 6.0, 8.0], 0.5) - 5.0).abs() < 1e-12);
        assert!((quantile(&[2.0, 4.0, 6.0, 8.0], 0.99) - 7.94).abs() < 1e-12);
        assert_eq!(quantile(&[5.0], 0.3), 5.0);
        assert!(quantile(&[], 0.5).is_nan());
        assert!(quantile(&x, 1.5).is_nan());
    }

    #[test]
    fn student_t_quantile_matches_the_table() {
        // t_ν(0.975) from standard tables (e.g. Abramowitz & Stegun table 26.10).
        let table = [
            (1, 12.706204736, 1e-8),
            (2, 4.302652730, 1e-8),
            (3, 3.182446305, 1.3e-3),
            (5, 2.570581836, 1.1e-4),
            (10, 2.228138852, 4e-6),
            (30, 2.042272456, 1e-7),
            (120, 1.979930405, 1e-8),
        ];
        for (dof, expected, tolerance) in table {
            let got = student_t_quantile(0.975, dof);
            assert!((got / expected - 1.0).abs() < tolerance, "ν = {dof}: {got} vs {expected}");
        }
    }

    /// Ishigami function, a = 7, b = 0.1, on x ∈ [−π, π]³.
    fn ishigami(x: &[f64]) -> f64 {
        x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
    }

    /// The Ishigami function at each row of a design, x_i = −π + 2π u_i.
    fn ishigami_results(design: &SaltelliDesign) -> Vec<f64> {
        let uniform = Distribution::Uniform { low: -PI, high: PI };
        design.rows.iter().map(|u| ishigami(&u.iter().map(|&u| uniform.quantile(u)).collect::<Vec<_>>())).collect()
    }

    #[test]
    fn sobol_indices_of_the_ishigami_function() {
        // Published values (e.g. Saltelli et al. 2008, Global Sensitivity Analysis: The Primer,
        // §2.9; Sobol' & Levitan 1999): V = 13.8446; S = 0.3139, 0.4424, 0; S_T = 0.5576, 0.4424, 0.2437.
        let first = [0.3139, 0.4424, 0.0];
        let total = [0.5576, 0.4424, 0.2437];
        let design = saltelli(8192, 3, 1);
        let indices = sobol(&design, &ishigami_results(&design), 500, 2);
        for (kind, got, truth) in [("S", &indices.first, first), ("S_T", &indices.total, total)] {
            for (i, (index, truth)) in got.iter().zip(truth).enumerate() {
                eprintln!(
                    "{kind}{}: {:.4} [{:.4}, {:.4}] (truth {truth})",
                    i + 1,
                    index.estimate,
                    index.low,
                    index.high
                );
                assert!(index.low <= truth && truth <= index.high, "{kind}{} = {index:?}, truth {truth}", i + 1);
                assert!(index.low <= index.estimate && index.estimate <= index.high);
                assert!(index.high - index.low < 0.1, "{kind}{} interval too wide: {index:?}", i + 1);
                assert!(index.high - index.low > 1e-4, "{kind}{} interval implausibly narrow: {index:?}", i + 1);
            }
        }
    }

    #[test]
    fn sobol_intervals_cover_the_ishigami_truth_at_their_level() {
        // 95 % intervals on 40 independent designs: each index's truth inside at least 34 times
        // (P(X ≤ 33) ≈ 0.3 % for X ~ Binomial(40, 0.95)). Intervals too wide would pass here;
        // the width bound of the test above catches those.
        let truth = [0.3139, 0.4424, 0.0, 0.5576, 0.4424, 0.2437];
        let mut covered = [0; 6];
        for seed in 0..40 {
            let design = saltelli(2048, 3, 100 + seed);
            let indices = sobol(&design, &ishigami_results(&design), 200, seed);
            for (k, index) in indices.first.iter().chain(&indices.total).enumerate() {
                covered[k] += usize::from(index.low <= truth[k] && truth[k] <= index.high);
            }
        }
        eprintln!("intervals covering the truth, of 40 (S1 S2 S3 S_T1 S_T2 S_T3): {covered:?}");
        assert!(covered.iter().all(|&c| c >= 34), "intervals covering the truth, of 40: {covered:?}");
    }

    #[test]
    fn sobol_of_a_constant_result_is_nan() {
        let design = saltelli(8, 2, 1);
        let indices = sobol(&design, &vec![4.0; design.runs()], 10, 1);
        assert!(indices.first.iter().chain(&indices.total).all(|i| i.estimate.is_nan()));
    }

    #[test]
    fn sobol_of_an_additive_function_is_its_variance_shares() {
        // y = x1 + 2 x2 on U(0,1)²: V_i ∝ c_i², so S = S_T = (1/5, 4/5) with no interaction.
        let design = saltelli(4096, 2, 3);
        let y: Vec<f64> = design.rows.iter().map(|u| u[0] + 2.0 * u[1]).collect();
        let indices = sobol(&design, &y, 200, 3);
        for (i, truth) in [0.2, 0.8].into_iter().enumerate() {
            for index in [indices.first[i], indices.total[i]] {
                assert!(index.low <= truth && truth <= index.high, "input {i}: {index:?}, truth {truth}");
            }
        }
    }

    /// x uniform on [0, 1]³ by Latin hypercube (σ_i = 1/√12), noise e ~ N(0, noise²) from a fourth column.
    fn linear_sample(n: usize, noise: f64, seed: u64) -> (Vec<Vec<f64>>, Vec<f64>) {
        let rows = latin_hypercube(n, 4, seed);
        let x: Vec<Vec<f64>> = rows.iter().map(|r| r[..3].to_vec()).collect();
        let y = rows.iter().map(|r| 3.0 * r[0] - 2.0 * r[1] + 0.0 * r[2] + noise * normal_quantile(r[3])).collect();
        (x, y)
    }

    #[test]
    fn src_of_a_noisy_linear_model_contain_the_analytic_values() {
        // SRC_i = b_i σ_i / σ_y with σ_y² = (9 + 4)/12 + noise²; R² = (13/12) / σ_y².
        let noise: f64 = 1.0;
        let var_y = 13.0 / 12.0 + noise * noise;
        let sigma = (1.0_f64 / 12.0).sqrt();
        let truth = [3.0 * sigma / var_y.sqrt(), -2.0 * sigma / var_y.sqrt(), 0.0];
        let (x, y) = linear_sample(2000, noise, 17);
        let fit = standardized_regression(&x, &y);
        for (i, (c, truth)) in fit.coefficients.iter().zip(truth).enumerate() {
            eprintln!("SRC{}: {:.4} [{:.4}, {:.4}] (truth {truth:.4})", i + 1, c.estimate, c.low, c.high);
            assert!(c.low <= truth && truth <= c.high, "SRC{} = {c:?}, truth {truth}", i + 1);
            assert!(c.high - c.low < 0.1);
        }
        assert!((fit.r_squared - 13.0 / 12.0 / var_y).abs() < 0.03, "R² = {}", fit.r_squared);
    }

    #[test]
    fn src_of_a_noiseless_linear_model() {
        // Exactly linear: R² = 1 and SRC_i = b_i s_i / s_y with the sample's own standard deviations;
        // a Latin hypercube keeps those within a few % of the analytic 3σ/σ_y, −2σ/σ_y, 0.
        let (x, y) = linear_sample(500, 0.0, 5);
        let fit = standardized_regression(&x, &y);
        assert!((fit.r_squared - 1.0).abs() < 1e-12, "R² = {}", fit.r_squared);
        let sd = |v: &mut dyn Iterator<Item = f64>| {
            let v: Vec<f64> = v.collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            (v.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
        };
        let sy = sd(&mut y.iter().copied());
        for (i, b) in [3.0, -2.0, 0.0].into_iter().enumerate() {
            let expected = b * sd(&mut x.iter().map(|r| r[i])) / sy;
            let c = fit.coefficients[i];
            assert!((c.estimate - expected).abs() < 1e-10, "SRC{} = {c:?}, expected {expected}", i + 1);
            assert!(c.high - c.low < 1e-6);
        }
        let analytic = 3.0 / 13.0_f64.sqrt();
        assert!((fit.coefficients[0].estimate - analytic).abs() < 0.03);
    }

    #[test]
    fn src_with_degenerate_data_does_not_panic() {
        let x: Vec<Vec<f64>> = (0..10).map(|i| vec![i as f64, 5.0]).collect();
        let y: Vec<f64> = (0..10).map(|i| 2.0 * i as f64 + 1.0).collect();
        let fit = standardized_regression(&x, &y);
        assert!((fit.coefficients[0].estimate - 1.0).abs() < 1e-12);
        assert!(fit.coefficients[1].estimate.is_nan(), "a constant input has no coefficient");
        let fit = standardized_regression(&x, &[3.0; 10]);
        assert!(fit.coefficients.iter().all(|c| c.estimate.is_nan()) && fit.r_squared.is_nan());
        // Two runs for one input: an exact fit with no degrees of freedom left.
        let fit = standardized_regression(&[vec![0.0], vec![1.0]], &[1.0, 3.0]);
        assert!((fit.coefficients[0].estimate - 1.0).abs() < 1e-12 && fit.coefficients[0].low.is_nan());
        let fit = standardized_regression(&[], &[]);
        assert!(fit.coefficients.is_empty());
    }
}
