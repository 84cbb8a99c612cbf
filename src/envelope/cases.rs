//! An envelope's cases: each spread key's values drawn from its distribution at the points of a
//! Latin hypercube (or of a Saltelli design, for Sobol indices), the same points for every value
//! of the grouping key (`--per`), so that the groups differ by that key alone (common random
//! numbers). The draw depends on the seed only: any thread count or shard gives the same cases.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::EnvelopeError;
use super::dist::Spread;
use super::sample::{latin_hypercube, saltelli};
use crate::scenario::Scenario;
use crate::sweep::Vary;
use crate::sweep::plan::{base_document, dotted_key, get_number, not_a_number, set_key, spec_of};

/// Fewest Saltelli base rows for which the envelope estimates Sobol indices by default: below it
/// their bootstrap intervals are wider than the indices of a typical ranking.
pub const MIN_SOBOL_BASE: usize = 64;
/// Fewest base rows `--sensitivity sobol` accepts: below it the estimates sit at the edge of
/// their own bootstrap intervals.
pub const MIN_FORCED_SOBOL_BASE: usize = 16;

/// How the sensitivity of the peak force to the spread keys is estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Method {
    /// First-order and total Sobol indices from a Saltelli design of `base` rows per matrix:
    /// `base · (k + 2)` runs per group.
    Sobol { base: usize },
    /// Standardized regression coefficients over a Latin hypercube of `samples` runs per group.
    Regression,
}

/// The sensitivity method asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MethodChoice {
    /// Sobol indices where the runs per group allow [`MIN_SOBOL_BASE`] base rows, else regression.
    #[default]
    Auto,
    /// Sobol indices (at least 2 base rows).
    Sobol,
    /// Standardized regression coefficients.
    Regression,
}

impl std::str::FromStr for MethodChoice {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        match text {
            "auto" => Ok(Self::Auto),
            "sobol" => Ok(Self::Sobol),
            "regression" => Ok(Self::Regression),
            _ => Err(format!("`{text}`: allowed auto, sobol, regression")),
        }
    }
}

/// How an envelope samples: written to `DIR/sampling.json`, read back by the merge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sampling {
    /// The spreads as given, `KEY=DIST`.
    pub spreads: Vec<String>,
    /// Runs per group.
    pub runs_per_group: usize,
    /// The seed of the draw.
    pub seed: u64,
    /// The sensitivity method, and the layout of each group's runs it implies.
    pub method: Method,
    /// The grouping key (`--per`), if any, and its values.
    pub per: Option<Vary>,
}

impl Sampling {
    /// The sampling of `samples` runs per group (`MethodChoice::Sobol` rounds it down to a whole
    /// Saltelli design).
    pub fn new(
        spreads: &[Spread],
        samples: usize,
        seed: u64,
        choice: MethodChoice,
        per: Option<Vary>,
    ) -> Result<Self, EnvelopeError> {
        if samples < 2 {
            return Err(EnvelopeError::Argument(format!("--samples {samples}: allowed 2 or more runs per group")));
        }
        let k = spreads.len();
        let base = samples / (k + 2);
        let method = match choice {
            MethodChoice::Regression | MethodChoice::Auto if samples < k + 2 => {
                return Err(EnvelopeError::Argument(format!(
                    "--samples {samples}: a regression on {k} spread keys needs at least {} runs per group (k + 2)",
                    k + 2
                )));
            }
            MethodChoice::Regression => Method::Regression,
            MethodChoice::Auto if base < MIN_SOBOL_BASE => Method::Regression,
            MethodChoice::Sobol if base < MIN_FORCED_SOBOL_BASE => {
                return Err(EnvelopeError::Argument(format!(
                    "--sensitivity sobol with {k} spread keys needs at least {} runs per group \
                     ({MIN_FORCED_SOBOL_BASE} (k + 2)), --samples is {samples}",
                    MIN_FORCED_SOBOL_BASE * (k + 2)
                )));
            }
            MethodChoice::Auto | MethodChoice::Sobol => Method::Sobol { base },
        };
        let runs_per_group = match method {
            Method::Sobol { base } => base * (spreads.len() + 2),
            Method::Regression => samples,
        };
        let spreads = spreads.iter().map(|s| s.to_string()).collect();
        Ok(Sampling { spreads, runs_per_group, seed, method, per })
    }

    /// The unit-cube points of one group's runs, in run order.
    pub fn unit_rows(&self) -> Vec<Vec<f64>> {
        let k = self.spreads.len();
        match self.method {
            Method::Sobol { base } => saltelli(base, k, self.seed).rows,
            Method::Regression => latin_hypercube(self.runs_per_group, k, self.seed),
        }
    }

    /// The parsed spreads.
    pub fn parsed_spreads(&self) -> Result<Vec<Spread>, EnvelopeError> {
        self.spreads.iter().map(|s| s.parse::<Spread>().map_err(EnvelopeError::from)).collect()
    }

    /// The keys of a case: the grouping key first, then the spread keys. Only the grouping key
    /// lists its values; the spread keys' values are in the cases.
    pub fn vary(&self, spreads: &[Spread]) -> Vec<Vary> {
        let spread_keys = spreads.iter().map(|s| Vary { key: s.key.clone(), values: Vec::new() });
        self.per.iter().cloned().chain(spread_keys).collect()
    }

    /// The groups: the grouping key's values (one group of `None` without `--per`).
    pub fn groups(&self) -> Vec<Option<toml::Value>> {
        match &self.per {
            Some(per) => per.values.iter().cloned().map(Some).collect(),
            None => vec![None],
        }
    }

    /// Every case's values, group by group, in run order within a group, each followed by the
    /// `pinned` keys (the nominal shaper tuning).
    pub fn case_rows(&self, spreads: &[Spread], pinned: &[(String, toml::Value)]) -> Vec<Vec<(String, toml::Value)>> {
        let draws: Vec<Vec<(String, toml::Value)>> = self
            .unit_rows()
            .iter()
            .map(|u| {
                spreads
                    .iter()
                    .zip(u)
                    .map(|(s, &u)| (s.key.clone(), toml::Value::Float(s.distribution.quantile(u))))
                    .collect()
            })
            .collect();
        let per_key = self.per.as_ref().map(|p| p.key.clone());
        self.groups()
            .into_iter()
            .flat_map(|group| {
                let head: Vec<(String, toml::Value)> = per_key.iter().cloned().zip(group).collect();
                draws
                    .iter()
                    .map(move |d| head.iter().cloned().chain(d.iter().cloned()).chain(pinned.iter().cloned()).collect())
            })
            .collect()
    }
}

/// Checks the spreads against the scenario at `path`: each key names a number in it (the arm's
/// damping ratios may come from the robot), no key is spread twice or also the grouping key, and
/// the scenario accepts each end of each distribution's support (an unbounded normal only where
/// the key accepts any number: elsewhere it must be given bounds).
pub fn check_spreads(path: &Path, spreads: &[Spread], per: Option<&Vary>) -> Result<(), EnvelopeError> {
    if spreads.is_empty() {
        return Err(EnvelopeError::Argument("no --spread given: allowed one or more KEY=DIST".into()));
    }
    for (i, s) in spreads.iter().enumerate() {
        let same = |key: &str| dotted_key(key) == dotted_key(&s.key);
        if spreads[..i].iter().any(|t| same(&t.key)) || per.is_some_and(|p| same(&p.key)) {
            return Err(EnvelopeError::Argument(format!("--spread `{s}`: `{}` is spread or grouped twice", s.key)));
        }
    }
    let document = base_document(path, spreads.iter().map(|s| s.key.as_str()))?;
    for spread in spreads {
        if get_number(&document, &spread.key).is_none() {
            return Err(EnvelopeError::Spread {
                spread: spread.to_string(),
                message: not_a_number(&document, &spread.key, path),
            });
        }
        check_support(path, &document, spread)?;
    }
    Ok(())
}

/// The scenario accepts both ends of `spread`'s support.
fn check_support(path: &Path, document: &toml::Value, spread: &Spread) -> Result<(), EnvelopeError> {
    let (low, high) = spread.distribution.support();
    for end in [low, high] {
        let value = if end.is_finite() { end } else { end.signum() * 1e300 };
        let mut probe = document.clone();
        set_key(&mut probe, &spread.key, toml::Value::Float(value))
            .map_err(|message| EnvelopeError::Spread { spread: spread.to_string(), message })?;
        let checked = spec_of(path, probe)
            .and_then(|spec| Scenario::from_spec(path, spec))
            .and_then(|scenario| scenario.check_compiled());
        if let Err(error) = checked {
            let message = if end.is_finite() {
                format!("the distribution reaches {end}, which the scenario does not accept: {error}")
            } else {
                "an unbounded normal on a key with a bounded range: give bounds, normal:MEAN,SD,A..B".to_string()
            };
            return Err(EnvelopeError::Spread { spread: spread.to_string(), message });
        }
    }
    Ok(())
}

/// The base scenario's shaper tuning, where `document`'s drive has a shaper and no `shaper_hz`:
/// the keys `drive.shaper_hz` and `drive.shaper_damping_ratio` set to the modes it was tuned to
/// (empty otherwise). Left to itself each run would tune its shaper to its own arm: over spread
/// keys that move the arm's modes (its damping, the payload, a gap that changes nothing but the
/// run), every draw would be shaped with a knowledge of itself that a real drive does not have.
/// An envelope and a design therefore pin the tuning to the nominal arm's.
pub fn nominal_shaper_tuning(path: &Path, document: &toml::Value) -> Result<Vec<(String, toml::Value)>, EnvelopeError> {
    let drive = document.get("drive");
    let shaped = drive.and_then(|d| d.get("shaper")).is_some() && drive.and_then(|d| d.get("shaper_hz")).is_none();
    if !shaped {
        return Ok(Vec::new());
    }
    let scenario = Scenario::from_spec(path, spec_of(path, document.clone())?)?;
    let tuned = scenario.tuned()?;
    let modes = tuned.drive.motion.shaper_modes();
    let list = |pick: fn(&crate::drive::ShaperMode) -> f64| {
        toml::Value::Array(modes.iter().map(|m| toml::Value::Float(pick(m))).collect())
    };
    Ok(vec![
        ("drive.shaper_hz".to_string(), list(|m| m.frequency_hz)),
        ("drive.shaper_damping_ratio".to_string(), list(|m| m.damping_ratio)),
    ])
}
