//! An envelope's figures per group: percentiles of each pair's peak force, of the largest peak
//! force, of the residual amplitude and of the sign-off's utilisation, peak stress and fatigue
//! damage per lift over the group's runs, and the sensitivity of the largest
//! peak force and of the residual amplitude to each spread key, ranked.

use serde::Serialize;

use super::cases::{Method, Sampling};
use super::dist::Spread;
use super::sample::SaltelliDesign;
use super::sensitivity::{Index, quantile, sobol, standardized_regression};
use crate::arm::STANDARD_GRAVITY_M_S2;
use crate::sweep::row::Row;

/// Bootstrap resamples for the Sobol indices' confidence intervals.
pub const BOOTSTRAP_RESAMPLES: usize = 500;
/// Mixed into the seed for the bootstrap's draws.
const BOOTSTRAP_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// Percentiles of a figure over a group's runs (type 7: linear between order statistics).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Percentiles {
    /// 5th percentile.
    pub p5: f64,
    /// Median.
    pub p50: f64,
    /// 95th percentile: exceeded in 5 % of lifts.
    pub p95: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Largest over the runs.
    pub max: f64,
}

impl Percentiles {
    /// Of `values` (NaN if empty).
    pub fn of(values: &[f64]) -> Self {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let at = |p: f64| if sorted.is_empty() { f64::NAN } else { quantile(&sorted, p) };
        Percentiles { p5: at(0.05), p50: at(0.5), p95: at(0.95), p99: at(0.99), max: at(1.0) }
    }
}

/// One pair's peak force over a group.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairEnvelope {
    /// `arm-<pad>`.
    pub pair: String,
    /// Its peak force, N.
    pub peak_force_n: Percentiles,
}

/// A spread key's share of a figure's variance (Sobol) or its standardized coefficient.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeySensitivity {
    /// The spread key.
    pub key: String,
    /// First-order Sobol index (Sobol method).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first: Option<Index>,
    /// Total Sobol index (Sobol method): the ranking's measure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total: Option<Index>,
    /// Standardized regression coefficient (regression method): the ranking's measure, by size.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficient: Option<Index>,
}

/// The sensitivity of one figure, keys ranked most influential first.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// The figure: `peak_force_n` (largest pair) or `residual_amplitude_m`.
    pub figure: &'static str,
    /// `sobol` (Saltelli 2010 first order, Jansen total, bootstrap 95 % intervals) or
    /// `regression` (standardized coefficients with 95 % intervals).
    pub method: &'static str,
    /// Fraction of the figure's variance a linear model explains (regression only): the
    /// coefficients rank the keys only where it is near 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub r_squared: Option<f64>,
    /// The keys, most influential first.
    pub ranking: Vec<KeySensitivity>,
    /// Why it was not estimated (a diverged run breaks a Saltelli design; a figure that does
    /// not vary has no sensitivity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub not_estimated: Option<String>,
}

/// One group's envelope.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupEnvelope {
    /// The grouping key's value (none without `--per`).
    pub per: Option<String>,
    /// The string's trade size (`string.size` of its runs' summaries), if a string is held.
    pub size: Option<String>,
    /// A catalogue string's nominal weight, lb/ft.
    pub weight_lb_ft: Option<f64>,
    /// Its steel grade (`payload.grade`), if given.
    pub grade: Option<String>,
    /// The mass of one of its joints with its connection, kg, when made of joints.
    pub joint_mass_kg: Option<f64>,
    /// What the string is, as an entry (`9-5/8@47.00`): the chart's label of the group's point.
    pub label: String,
    /// Payload mass, kg (the median over the runs, in case the mass itself is spread).
    pub payload_kg: f64,
    /// Its weight, N.
    pub weight_n: f64,
    /// Runs in the group.
    pub runs: usize,
    /// Runs the divergence guard stopped (left out of the figures).
    pub diverged: usize,
    /// The largest pair's peak force, N.
    pub peak_force_n: Percentiles,
    /// The peak force over the weight, N/N.
    pub peak_force_per_weight: Percentiles,
    /// Each pair's peak force.
    pub pairs: Vec<PairEnvelope>,
    /// The residual tip amplitude after the drive stops, m.
    pub residual_amplitude_m: Percentiles,
    /// The arm's stresses over the runs (absent where no run signed off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<StressEnvelope>,
    /// The fatigue damage of one lift over the runs (absent where no run checked fatigue).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fatigue: Option<FatigueEnvelope>,
    /// Sensitivity of the largest peak force, then of the residual amplitude.
    pub sensitivity: Vec<Sensitivity>,
}

/// The summary's `stress` over a group's runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StressEnvelope {
    /// Largest |σ| along the arm, Pa (`stress.peak_stress_pa`).
    pub peak_stress_pa: Percentiles,
    /// Largest utilisation (`stress.utilisation`), over the runs that give one (absent without
    /// a yield strength).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilisation: Option<Percentiles>,
}

/// The summary's `fatigue` over a group's runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FatigueEnvelope {
    /// Damage of one lift at the worst place (`fatigue.damage_per_lift`).
    pub damage_per_lift: Percentiles,
}

/// Percentiles of the finite values among `values`, `None` if there are none.
fn percentiles_of_some(values: impl Iterator<Item = Option<f64>>) -> Option<Percentiles> {
    let finite: Vec<f64> = values.flatten().filter(|v| v.is_finite()).collect();
    (!finite.is_empty()).then(|| Percentiles::of(&finite))
}

/// What one run gave.
struct RunFigures {
    payload_kg: f64,
    pairs: Vec<(String, f64)>,
    residual_m: f64,
    peak_stress_pa: Option<f64>,
    utilisation: Option<f64>,
    damage_per_lift: Option<f64>,
}

impl RunFigures {
    fn read(row: &Row) -> Option<Self> {
        let number = |path: &str| row.get(path).and_then(|v| v.as_f64());
        let payload_kg = number("summary.payload_kg")?;
        let pairs = (0..)
            .map_while(|i| {
                let name = row.get(&format!("summary.pairs.{i}.pair"))?.as_str()?.to_string();
                Some((name, number(&format!("summary.pairs.{i}.peak_force_n")).unwrap_or(f64::NAN)))
            })
            .collect();
        Some(RunFigures {
            payload_kg,
            pairs,
            residual_m: number("summary.residual.amplitude_m").unwrap_or(f64::NAN),
            peak_stress_pa: number("summary.stress.peak_stress_pa"),
            utilisation: number("summary.stress.utilisation"),
            damage_per_lift: number("summary.fatigue.damage_per_lift"),
        })
    }

    fn peak_force_n(&self) -> f64 {
        self.pairs.iter().map(|p| p.1).fold(f64::NAN, f64::max)
    }
}

/// The envelope of one group: its `rows` (in run order) and their sampled `values` (one row of
/// spread-key values per run).
pub fn group_envelope(
    sampling: &Sampling,
    spreads: &[Spread],
    per: Option<String>,
    rows: &[Row],
    values: &[Vec<f64>],
) -> GroupEnvelope {
    let runs: Vec<Option<RunFigures>> = rows.iter().map(RunFigures::read).collect();
    let ran: Vec<&RunFigures> = runs.iter().flatten().collect();
    let payload_kg = Percentiles::of(&ran.iter().map(|r| r.payload_kg).collect::<Vec<_>>()).p50;
    let weight_n = payload_kg * STANDARD_GRAVITY_M_S2;
    let peaks: Vec<f64> = ran.iter().map(|r| r.peak_force_n()).filter(|f| f.is_finite()).collect();
    let pair_names: Vec<String> =
        ran.first().map(|r| r.pairs.iter().map(|p| p.0.clone()).collect()).unwrap_or_default();
    let pairs = pair_names
        .iter()
        .enumerate()
        .map(|(i, pair)| PairEnvelope {
            pair: pair.clone(),
            peak_force_n: Percentiles::of(&ran.iter().filter_map(|r| r.pairs.get(i).map(|p| p.1)).collect::<Vec<_>>()),
        })
        .collect();
    let per_weight: Vec<f64> = ran.iter().map(|r| r.peak_force_n() / (r.payload_kg * STANDARD_GRAVITY_M_S2)).collect();
    let figure =
        |f: &dyn Fn(&RunFigures) -> f64| -> Vec<Option<f64>> { runs.iter().map(|r| r.as_ref().map(f)).collect() };
    let keys: Vec<String> = spreads.iter().map(|s| s.key.clone()).collect();
    let sensitivity = vec![
        sensitivity("peak_force_n", sampling, &keys, values, figure(&|r| r.peak_force_n())),
        sensitivity("residual_amplitude_m", sampling, &keys, values, figure(&|r| r.residual_m)),
    ];
    let first = rows.first();
    let string = |key: &str| first.and_then(|r| r.get(&format!("summary.string.{key}")));
    GroupEnvelope {
        per,
        size: string("size").and_then(|v| v.as_str()).map(str::to_string),
        weight_lb_ft: string("weight_lb_ft").and_then(|v| v.as_f64()),
        grade: string("grade").and_then(|v| v.as_str()).map(str::to_string),
        joint_mass_kg: string("joint_mass_kg").and_then(|v| v.as_f64()),
        label: first.map(|r| crate::sweep::chart::string_label(r, "summary.")).unwrap_or_default(),
        payload_kg,
        weight_n,
        runs: rows.len(),
        diverged: rows.len() - ran.len(),
        peak_force_n: Percentiles::of(&peaks),
        peak_force_per_weight: Percentiles::of(&per_weight.into_iter().filter(|f| f.is_finite()).collect::<Vec<_>>()),
        pairs,
        residual_amplitude_m: Percentiles::of(
            &ran.iter().map(|r| r.residual_m).filter(|r| r.is_finite()).collect::<Vec<_>>(),
        ),
        stress: percentiles_of_some(ran.iter().map(|r| r.peak_stress_pa)).map(|peak_stress_pa| StressEnvelope {
            peak_stress_pa,
            utilisation: percentiles_of_some(ran.iter().map(|r| r.utilisation)),
        }),
        fatigue: percentiles_of_some(ran.iter().map(|r| r.damage_per_lift))
            .map(|damage_per_lift| FatigueEnvelope { damage_per_lift }),
        sensitivity,
    }
}

/// The sensitivity of `figure` (`y`, one per run; `None` where a run diverged) to the keys.
fn sensitivity(
    figure: &'static str,
    sampling: &Sampling,
    keys: &[String],
    values: &[Vec<f64>],
    y: Vec<Option<f64>>,
) -> Sensitivity {
    let method = match sampling.method {
        Method::Sobol { .. } => "sobol",
        Method::Regression => "regression",
    };
    let skipped = |why: &str| Sensitivity {
        figure,
        method,
        r_squared: None,
        ranking: Vec::new(),
        not_estimated: Some(why.into()),
    };
    // A Saltelli design needs every run; a regression fits the runs there are.
    let (values, y): (Vec<Vec<f64>>, Vec<f64>) = match sampling.method {
        Method::Sobol { .. } if y.iter().any(Option::is_none) => return skipped("a run diverged"),
        _ => values.iter().cloned().zip(y).filter_map(|(x, y)| Some((x, y?))).unzip(),
    };
    let values = &values;
    if y.iter().any(|v| !v.is_finite()) {
        return skipped("the figure is missing in some runs (no contact pair)");
    }
    if y.len() < keys.len() + 2 {
        return skipped("fewer runs than the keys + 2 a regression needs");
    }
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    if y.iter().all(|v| (v - mean).abs() <= 1e-12 * mean.abs().max(1e-300)) {
        return skipped("the figure does not vary over the runs");
    }
    let (mut ranking, r_squared) = match sampling.method {
        Method::Sobol { base } => {
            let design = SaltelliDesign { base, dimensions: keys.len(), rows: Vec::new() };
            // The bootstrap's own stream, apart from the one that drew the design.
            let indices = sobol(&design, &y, BOOTSTRAP_RESAMPLES, sampling.seed ^ BOOTSTRAP_SEED);
            let ranking = keys
                .iter()
                .enumerate()
                .map(|(i, key)| KeySensitivity {
                    key: key.clone(),
                    first: Some(indices.first[i]),
                    total: Some(indices.total[i]),
                    coefficient: None,
                })
                .collect::<Vec<_>>();
            (ranking, None)
        }
        Method::Regression => {
            let fit = standardized_regression(values, &y);
            let ranking = keys
                .iter()
                .zip(&fit.coefficients)
                .map(|(key, c)| KeySensitivity { key: key.clone(), first: None, total: None, coefficient: Some(*c) })
                .collect::<Vec<_>>();
            (ranking, Some(fit.r_squared))
        }
    };
    let measure = |k: &KeySensitivity| {
        let m = k.total.as_ref().or(k.coefficient.as_ref()).map_or(f64::NAN, |i| i.estimate.abs());
        if m.is_nan() { f64::NEG_INFINITY } else { m }
    };
    ranking.sort_by(|a, b| measure(b).total_cmp(&measure(a)));
    Sensitivity { figure, method, r_squared, ranking, not_estimated: None }
}
