//! `--spread` arguments: the probability distribution of one uncertain scenario key, and its
//! inverse CDF (quantile function), which maps a design's unit sample `u ∈ (0, 1)` to a key value.
//!
//! Forms (`KEY=DIST`, KEY a dotted path into the scenario as for `--vary`):
//! - `uniform:A..B`: uniform on [A, B], A < B;
//! - `normal:MEAN,SD`: normal with standard deviation SD > 0, unbounded;
//! - `normal:MEAN,SD,A..B`: the same normal truncated to [A, B], A < B, A ≤ MEAN ≤ B;
//! - `triangular:A,MODE,B`: triangular on [A, B] with its peak at MODE, A < B, A ≤ MODE ≤ B.
//!
//! All numbers must be finite, in the key's own SI unit.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The forms a `--spread` argument may take, for error messages.
pub const SPREAD_FORMS: &str =
    "KEY=uniform:A..B, KEY=normal:MEAN,SD, KEY=normal:MEAN,SD,A..B (truncated) or KEY=triangular:A,MODE,B";

/// A `--spread` argument that cannot be used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpreadError {
    /// The text does not parse or its numbers break a rule of the form.
    #[error("--spread `{arg}`: {message} (allowed: {forms})", forms = SPREAD_FORMS)]
    Parse {
        /// The argument as given.
        arg: String,
        /// What is wrong with it.
        message: String,
    },
}

/// A probability distribution of one scalar key.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Distribution {
    /// Uniform on [low, high].
    Uniform {
        /// Lower bound.
        low: f64,
        /// Upper bound (> low).
        high: f64,
    },
    /// Normal N(mean, sd²), truncated to `bounds` if given.
    Normal {
        /// Mean of the untruncated normal.
        mean: f64,
        /// Standard deviation of the untruncated normal (> 0).
        sd: f64,
        /// Truncation interval [a, b] (a < b, a ≤ mean ≤ b), or `None` for the full normal.
        bounds: Option<(f64, f64)>,
    },
    /// Triangular on [low, high] with its density peak at `mode`.
    Triangular {
        /// Lower bound.
        low: f64,
        /// Most likely value (low ≤ mode ≤ high).
        mode: f64,
        /// Upper bound (> low).
        high: f64,
    },
}

impl Distribution {
    /// The inverse CDF at `u ∈ (0, 1)`: the value below which a fraction `u` of draws lie.
    ///
    /// A truncated normal maps `u` linearly into [Φ(α), Φ(β)] (α, β the standardized bounds) and
    /// inverts Φ there; it works in the tail nearer the bounds so that two bounds far above the
    /// mean do not cancel to 1 − 1. The result is clamped into the support against rounding.
    /// `u` outside (0, 1) gives the support's ends (±∞ for an untruncated normal).
    pub fn quantile(&self, u: f64) -> f64 {
        match *self {
            Distribution::Uniform { low, high } => (low + u * (high - low)).clamp(low, high),
            Distribution::Normal { mean, sd, bounds: None } => mean + sd * normal_quantile(u),
            Distribution::Normal { bounds: Some((a, b)), .. } if !(u > 0.0 && u < 1.0) => {
                if u <= 0.0 {
                    a
                } else {
                    b
                }
            }
            Distribution::Normal { mean, sd, bounds: Some((a, b)) } => {
                let (alpha, beta) = ((a - mean) / sd, (b - mean) / sd);
                let z = if alpha > 0.0 {
                    // Both bounds above the mean: mirror into the lower tail.
                    -truncated_standard_quantile(1.0 - u, -beta, -alpha)
                } else {
                    truncated_standard_quantile(u, alpha, beta)
                };
                (mean + sd * z).clamp(a, b)
            }
            Distribution::Triangular { low, mode, high } => triangular_quantile(u, low, mode, high),
        }
    }

    /// The mean of the distribution (of the truncated one for a truncated normal).
    pub fn mean(&self) -> f64 {
        match *self {
            Distribution::Uniform { low, high } => 0.5 * (low + high),
            Distribution::Normal { mean, bounds: None, .. } => mean,
            Distribution::Normal { mean, sd, bounds: Some((a, b)) } => {
                // μ + σ (φ(α) − φ(β)) / (Φ(β) − Φ(α)), mirrored like the quantile.
                let (alpha, beta) = ((a - mean) / sd, (b - mean) / sd);
                let shift =
                    if alpha > 0.0 { -truncated_mean_shift(-beta, -alpha) } else { truncated_mean_shift(alpha, beta) };
                (mean + sd * shift).clamp(a, b)
            }
            Distribution::Triangular { low, mode, high } => (low + mode + high) / 3.0,
        }
    }

    /// The smallest and largest values the distribution can draw (±∞ for an untruncated normal).
    pub fn support(&self) -> (f64, f64) {
        match *self {
            Distribution::Uniform { low, high } | Distribution::Triangular { low, high, .. } => (low, high),
            Distribution::Normal { bounds: Some(bounds), .. } => bounds,
            Distribution::Normal { bounds: None, .. } => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// Checks the parameters' rules (finite numbers, A < B, SD > 0, A ≤ MODE ≤ B, A ≤ MEAN ≤ B).
    fn check(&self) -> Result<(), String> {
        let finite = |values: &[f64]| {
            if values.iter().all(|v| v.is_finite()) { Ok(()) } else { Err("every number must be finite".to_string()) }
        };
        let ordered = |a: f64, b: f64| if a < b { Ok(()) } else { Err(format!("needs A < B, got {a}..{b}")) };
        match *self {
            Distribution::Uniform { low, high } => {
                finite(&[low, high])?;
                ordered(low, high)
            }
            Distribution::Normal { mean, sd, bounds } => {
                finite(&[mean, sd])?;
                if sd <= 0.0 {
                    return Err(format!("needs SD > 0, got {sd}"));
                }
                let Some((a, b)) = bounds else { return Ok(()) };
                finite(&[a, b])?;
                ordered(a, b)?;
                if !(a <= mean && mean <= b) {
                    return Err(format!("the bounds {a}..{b} must contain the mean {mean}"));
                }
                Ok(())
            }
            Distribution::Triangular { low, mode, high } => {
                finite(&[low, mode, high])?;
                ordered(low, high)?;
                if !(low <= mode && mode <= high) {
                    return Err(format!("needs A <= MODE <= B, got {low},{mode},{high}"));
                }
                Ok(())
            }
        }
    }
}

impl fmt::Display for Distribution {
    /// The `--spread` text of the distribution (parses back to the same value).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Distribution::Uniform { low, high } => write!(f, "uniform:{low}..{high}"),
            Distribution::Normal { mean, sd, bounds: None } => write!(f, "normal:{mean},{sd}"),
            Distribution::Normal { mean, sd, bounds: Some((a, b)) } => write!(f, "normal:{mean},{sd},{a}..{b}"),
            Distribution::Triangular { low, mode, high } => write!(f, "triangular:{low},{mode},{high}"),
        }
    }
}

impl FromStr for Distribution {
    type Err = String;

    /// Parses `uniform:A..B`, `normal:MEAN,SD`, `normal:MEAN,SD,A..B` or `triangular:A,MODE,B`
    /// and checks the rules; the error is a message without the argument.
    fn from_str(text: &str) -> Result<Self, String> {
        let (kind, params) = text.split_once(':').ok_or("no `:` between the distribution and its numbers")?;
        let params: Vec<&str> = params.split(',').map(str::trim).collect();
        let distribution = match (kind.trim(), params.as_slice()) {
            ("uniform", [range]) => {
                let (low, high) = parse_range(range)?;
                Distribution::Uniform { low, high }
            }
            ("normal", [mean, sd]) => Distribution::Normal { mean: number(mean)?, sd: number(sd)?, bounds: None },
            ("normal", [mean, sd, range]) => {
                Distribution::Normal { mean: number(mean)?, sd: number(sd)?, bounds: Some(parse_range(range)?) }
            }
            ("triangular", [low, mode, high]) => {
                Distribution::Triangular { low: number(low)?, mode: number(mode)?, high: number(high)? }
            }
            ("uniform" | "normal" | "triangular", _) => {
                return Err(format!("`{kind}` does not take the numbers `{}`", params.join(",")));
            }
            _ => return Err(format!("unknown distribution `{kind}`")),
        };
        distribution.check()?;
        Ok(distribution)
    }
}

/// One `--spread` argument: a scenario key and the distribution of its value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    /// Dotted path into the scenario's TOML document (a numeric segment indexes an array).
    pub key: String,
    /// The distribution of the key's value.
    pub distribution: Distribution,
}

impl fmt::Display for Spread {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.key, self.distribution)
    }
}

impl FromStr for Spread {
    type Err = SpreadError;

    fn from_str(arg: &str) -> Result<Self, SpreadError> {
        let bad = |message: String| SpreadError::Parse { arg: arg.into(), message };
        let (key, dist) =
            arg.split_once('=').ok_or_else(|| bad("no `=` between the key and its distribution".into()))?;
        let key = key.trim();
        crate::sweep::vary::check_key(key).map_err(bad)?;
        let distribution = dist.trim().parse().map_err(bad)?;
        Ok(Spread { key: key.into(), distribution })
    }
}

fn number(text: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| format!("`{text}` is not a number"))?;
    if value.is_finite() { Ok(value) } else { Err(format!("`{text}` is not a finite number")) }
}

/// `A..B` → (A, B); the order is checked with the distribution.
fn parse_range(text: &str) -> Result<(f64, f64), String> {
    let (a, b) = text.split_once("..").ok_or_else(|| format!("`{text}` is not a range A..B"))?;
    Ok((number(a)?, number(b)?))
}

/// The standard normal quantile Φ⁻¹ restricted to [α, β] (α ≤ 0, so Φ(α) ≤ ½ keeps its digits).
fn truncated_standard_quantile(u: f64, alpha: f64, beta: f64) -> f64 {
    let (pa, pb) = (normal_cdf(alpha), normal_cdf(beta));
    normal_quantile(pa + u.clamp(0.0, 1.0) * (pb - pa)).clamp(alpha, beta)
}

/// (φ(α) − φ(β)) / (Φ(β) − Φ(α)), the standardized mean of N(0, 1) truncated to [α, β], α ≤ 0.
fn truncated_mean_shift(alpha: f64, beta: f64) -> f64 {
    let density = |z: f64| (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let mass = normal_cdf(beta) - normal_cdf(alpha);
    if mass > 0.0 { (density(alpha) - density(beta)) / mass } else { 0.5 * (alpha + beta) }
}

/// Closed-form inverse of the triangular CDF: F(x) = (x − a)² / ((b − a)(c − a)) up to the mode c,
/// 1 − (b − x)² / ((b − a)(b − c)) above it.
fn triangular_quantile(u: f64, low: f64, mode: f64, high: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    let width = high - low;
    let x = if u * width < mode - low {
        low + (u * width * (mode - low)).sqrt()
    } else {
        high - ((1.0 - u) * width * (high - mode)).sqrt()
    };
    x.clamp(low, high)
}

/// The standard normal CDF Φ(x), by Hart's double-precision rational approximation (Hart et al.,
/// *Computer Approximations*, 1968, algorithm 5666; as given by G. West, Wilmott Magazine 2005,
/// "Better approximations to cumulative normal functions"): relative error below 2e-14 for
/// |x| ≤ 3 and below 1e-8 in the far tails (checked against 40-digit arithmetic).
pub fn normal_cdf(x: f64) -> f64 {
    const NUM: [f64; 7] = [
        220.206867912376,
        221.213596169931,
        112.079291497871,
        33.912866078383,
        6.37396220353165,
        0.700383064443688,
        3.52624965998911e-2,
    ];
    const DEN: [f64; 8] = [
        440.413735824752,
        793.826512519948,
        637.333633378831,
        296.564248779674,
        86.7807322029461,
        16.064177579207,
        1.75566716318264,
        8.83883476483184e-2,
    ];
    let z = x.abs();
    let tail = if x.is_nan() {
        f64::NAN
    } else if z > 37.0 {
        0.0
    } else if z < 7.07106781186547 {
        (-0.5 * z * z).exp() * polynomial(&NUM, z) / polynomial(&DEN, z)
    } else {
        // Continued fraction of the Mills ratio.
        let fraction = z + 1.0 / (z + 2.0 / (z + 3.0 / (z + 4.0 / (z + 0.65))));
        (-0.5 * z * z).exp() / fraction / (2.0 * std::f64::consts::PI).sqrt()
    };
    if x > 0.0 { 1.0 - tail } else { tail }
}

/// The standard normal quantile Φ⁻¹(p) by Wichura's algorithm AS 241 (PPND16; M. J. Wichura,
/// "The percentage points of the normal distribution", Applied Statistics 37(3), 477–484, 1988):
/// rational approximations in three ranges, relative error about 1e-16. `p` ≤ 0 gives −∞, `p` ≥ 1
/// gives +∞, NaN gives NaN.
// The coefficients as published (20 digits), so they can be checked against the paper.
#[allow(clippy::excessive_precision)]
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 8] = [
        3.387_132_872_796_366_608,
        1.331_416_678_917_843_774_5e2,
        1.971_590_950_306_551_442_7e3,
        1.373_169_376_550_946_112_5e4,
        4.592_195_393_154_987_145_7e4,
        6.726_577_092_700_870_085_3e4,
        3.343_057_558_358_812_810_5e4,
        2.509_080_928_730_122_672_7e3,
    ];
    const B: [f64; 8] = [
        1.0,
        4.231_333_070_160_091_125_2e1,
        6.871_870_074_920_579_083e2,
        5.394_196_021_424_751_107_7e3,
        2.121_379_430_158_659_586_7e4,
        3.930_789_580_009_271_061e4,
        2.872_908_573_572_194_267_4e4,
        5.226_495_278_852_854_561e3,
    ];
    const C: [f64; 8] = [
        1.423_437_110_749_683_577_34,
        4.630_337_846_156_545_295_9,
        5.769_497_221_460_691_405_5,
        3.647_848_324_763_204_605_04,
        1.270_458_252_452_368_382_58,
        2.417_807_251_774_506_117_7e-1,
        2.272_384_498_926_918_458_33e-2,
        7.745_450_142_783_414_076_4e-4,
    ];
    const D: [f64; 8] = [
        1.0,
        2.053_191_626_637_758_821_87,
        1.676_384_830_183_803_849_4,
        6.897_673_349_851_000_045_5e-1,
        1.481_039_764_274_800_745_9e-1,
        1.519_866_656_361_645_719_66e-2,
        5.475_938_084_995_344_946e-4,
        1.050_750_071_644_416_843_24e-9,
    ];
    const E: [f64; 8] = [
        6.657_904_643_501_103_777_2,
        5.463_784_911_164_114_369_9,
        1.784_826_539_917_291_335_8,
        2.965_605_718_285_048_912_3e-1,
        2.653_218_952_657_612_309_3e-2,
        1.242_660_947_388_078_438_6e-3,
        2.711_555_568_743_487_578_15e-5,
        2.010_334_399_292_288_132_65e-7,
    ];
    const F: [f64; 8] = [
        1.0,
        5.998_322_065_558_879_376_9e-1,
        1.369_298_809_227_358_053_1e-1,
        1.487_536_129_085_061_485_25e-2,
        7.868_691_311_456_132_591e-4,
        1.846_318_317_510_054_681_8e-5,
        1.421_511_758_316_445_888_7e-7,
        2.044_263_103_389_939_785_64e-15,
    ];
    if p.is_nan() {
        return f64::NAN;
    }
    if p <= 0.0 {
        return f64::NEG_INFINITY;
    }
    if p >= 1.0 {
        return f64::INFINITY;
    }
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180625 - q * q;
        return q * polynomial(&A, r) / polynomial(&B, r);
    }
    let r = (-p.min(1.0 - p).ln()).sqrt();
    let value = if r <= 5.0 {
        let r = r - 1.6;
        polynomial(&C, r) / polynomial(&D, r)
    } else {
        let r = r - 5.0;
        polynomial(&E, r) / polynomial(&F, r)
    };
    if q < 0.0 { -value } else { value }
}

/// Σ c_k x^k by Horner's rule, coefficients from the constant term up.
fn polynomial(coefficients: &[f64], x: f64) -> f64 {
    coefficients.iter().rev().fold(0.0, |sum, &c| sum * x + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spread(text: &str) -> Spread {
        text.parse().unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    fn message(text: &str) -> String {
        text.parse::<Spread>().expect_err(text).to_string()
    }

    #[test]
    fn inverse_normal_matches_published_values() {
        // Φ⁻¹(0.975), Φ⁻¹(1e-10) and Φ⁻¹(0.95) to 16 digits (e.g. Wichura 1988's test values,
        // reproduced by any 40-digit erfinv).
        let cases = [(0.975, 1.959963984540054), (1e-10, -6.361340902404056), (0.95, 1.6448536269514722), (0.5, 0.0)];
        for (p, expected) in cases {
            let got = normal_quantile(p);
            assert!((got - expected).abs() <= 2e-15 * expected.abs().max(1.0), "Φ⁻¹({p}) = {got}, expected {expected}");
        }
        assert_eq!(normal_quantile(0.0), f64::NEG_INFINITY);
        assert_eq!(normal_quantile(1.0), f64::INFINITY);
    }

    #[test]
    fn normal_cdf_inverts_the_quantile() {
        // Φ(1.959963984540054) = 0.975 and Φ(−6.361340902404056) = 1e-10 (same published pairs).
        assert!((normal_cdf(1.959963984540054) - 0.975).abs() < 1e-15);
        assert!((normal_cdf(-6.361340902404056) / 1e-10 - 1.0).abs() < 1e-8);
        assert_eq!(normal_cdf(0.0), 0.5);
        // Within the accuracy stated for Φ: 2e-14 relative for |x| ≤ 3, 1e-8 beyond.
        for (p, tolerance) in [(1e-6, 1e-8), (0.01, 2e-14), (0.2, 2e-14), (0.5, 2e-14), (0.7, 2e-14), (0.99, 2e-14)] {
            let error = (normal_cdf(normal_quantile(p)) / p - 1.0).abs();
            assert!(error < tolerance, "p = {p}: relative error {error}");
        }
    }

    #[test]
    fn truncated_normal_stays_in_bounds_and_follows_the_truncated_cdf() {
        let cases = [(0.0, 1.0, -0.5, 2.0), (10.0, 2.0, 9.0, 10.5), (0.05, 0.02, 0.0, 0.1), (0.0, 1.0, 0.0, 8.0)];
        for (mean, sd, a, b) in cases {
            let d = Distribution::Normal { mean, sd, bounds: Some((a, b)) };
            let cdf = |x: f64| normal_cdf((x - mean) / sd);
            let (pa, pb) = (cdf(a), cdf(b));
            for k in 0..=1000 {
                let u = k as f64 / 1000.0;
                let x = d.quantile(u);
                assert!(a <= x && x <= b, "{d}: quantile({u}) = {x} outside [{a}, {b}]");
                // The truncated CDF at x, (Φ(x) − Φ(a)) / (Φ(b) − Φ(a)), gives u back.
                let back = (cdf(x) - pa) / (pb - pa);
                assert!((back - u).abs() < 1e-9, "{d}: F(quantile({u})) = {back}");
            }
            assert_eq!(d.quantile(0.0), a);
            assert_eq!(d.quantile(1.0), b);
        }
    }

    #[test]
    fn truncated_normal_far_above_the_mean_keeps_its_digits() {
        // Both bounds above the mean: N(0,1) on [3, 4]. Its median solves Φ(x) = (Φ(3) + Φ(4)) / 2,
        // i.e. x = Φ⁻¹((Q(3) + Q(4)) / 2) mirrored, Q the upper tail, with Q(3) = 1.3498980316301e-3
        // and Q(4) = 3.1671241833120e-5 (standard tables).
        let d = Distribution::Normal { mean: 0.0, sd: 1.0, bounds: Some((3.0, 4.0)) };
        let expected = -normal_quantile(0.5 * (1.3498980316301e-3 + 3.1671241833120e-5));
        assert!((d.quantile(0.5) - expected).abs() < 1e-9, "{} vs {expected}", d.quantile(0.5));
        assert!(d.quantile(0.5) > 3.0 && d.quantile(0.5) < 4.0);
    }

    #[test]
    fn truncated_normal_mean_matches_the_closed_form() {
        // N(0,1) on [0, ∞)-like bounds [0, 40]: mean √(2/π) (half-normal).
        let d = Distribution::Normal { mean: 0.0, sd: 1.0, bounds: Some((0.0, 40.0)) };
        assert!((d.mean() - (2.0 / std::f64::consts::PI).sqrt()).abs() < 1e-12);
        // Symmetric bounds keep the mean.
        let d = Distribution::Normal { mean: 3.0, sd: 0.5, bounds: Some((2.0, 4.0)) };
        assert!((d.mean() - 3.0).abs() < 1e-15);
    }

    #[test]
    fn triangular_quantile_is_the_closed_form() {
        let (a, c, b) = (1.0, 2.0, 5.0);
        let d = Distribution::Triangular { low: a, mode: c, high: b };
        // F(c) = (c − a)/(b − a) = 0.25: the mode is the 25 % quantile.
        assert!((d.quantile(0.25) - c).abs() < 1e-15);
        // Below the mode F(x) = (x − a)²/((b − a)(c − a)) = (x − 1)²/4: F(1.5) = 1/16.
        assert!((d.quantile(1.0 / 16.0) - 1.5).abs() < 1e-15);
        // Above it 1 − F(x) = (b − x)²/((b − a)(b − c)) = (5 − x)²/12: 1 − F(3) = 1/3.
        assert!((d.quantile(2.0 / 3.0) - 3.0).abs() < 1e-14);
        assert_eq!((d.quantile(0.0), d.quantile(1.0)), (a, b));
        assert!((d.mean() - 8.0 / 3.0).abs() < 1e-15);
        // A right-angled triangle (mode at the lower end): F(x) = 1 − (b − x)²/(b − a)².
        let d = Distribution::Triangular { low: 0.0, mode: 0.0, high: 2.0 };
        assert!((d.quantile(0.75) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn uniform_quantile_and_mean() {
        let d = Distribution::Uniform { low: -2.0, high: 6.0 };
        assert_eq!(d.quantile(0.25), 0.0);
        assert_eq!(d.mean(), 2.0);
        assert_eq!(d.support(), (-2.0, 6.0));
    }

    #[test]
    fn good_forms_parse() {
        let s = spread("pad.stiffness_n_per_m=uniform:8e5..1.2e6");
        assert_eq!(s.key, "pad.stiffness_n_per_m");
        assert_eq!(s.distribution, Distribution::Uniform { low: 8e5, high: 1.2e6 });
        assert_eq!(
            spread("arm.damping_ratios.0=normal:0.02,0.005").distribution,
            Distribution::Normal { mean: 0.02, sd: 0.005, bounds: None }
        );
        assert_eq!(
            spread("arm.damping_ratios.0 = normal: 0.02, 0.005, 0.0..0.05").distribution,
            Distribution::Normal { mean: 0.02, sd: 0.005, bounds: Some((0.0, 0.05)) }
        );
        assert_eq!(
            spread("pad.gap_m=triangular:-0.01,0,0.02").distribution,
            Distribution::Triangular { low: -0.01, mode: 0.0, high: 0.02 }
        );
        for text in ["a.b=uniform:-1..2", "a=normal:1,2", "a.0=normal:1,2,0.5..3", "x=triangular:0,0,1"] {
            let s = spread(text);
            assert_eq!(spread(&s.to_string()), s, "{text} does not round-trip");
        }
    }

    #[test]
    fn each_bad_form_names_the_argument_and_the_rule() {
        let cases = [
            ("pad.gap_m", "no `=`"),
            ("pad gap=uniform:0..1", "not a path of names and indices"),
            ("a..b=uniform:0..1", "not a path of names and indices"),
            ("a=uniform 0..1", "no `:`"),
            ("a=lognormal:0,1", "unknown distribution `lognormal`"),
            ("a=uniform:1..1", "A < B"),
            ("a=uniform:2..1", "A < B"),
            ("a=uniform:0", "not a range"),
            ("a=uniform:0,1", "does not take"),
            ("a=uniform:0..x", "`x` is not a number"),
            ("a=uniform:0..inf", "not a finite number"),
            ("a=normal:0,NaN", "not a finite number"),
            ("a=normal:1,0", "SD > 0"),
            ("a=normal:1,-1", "SD > 0"),
            ("a=normal:1", "does not take"),
            ("a=normal:1,0.1,2..0", "A < B"),
            ("a=normal:1,0.1,2..3", "must contain the mean"),
            ("a=triangular:0,2,1", "A <= MODE <= B"),
            ("a=triangular:1,1,1", "A < B"),
            ("a=triangular:0,1", "does not take"),
        ];
        for (text, expected) in cases {
            let m = message(text);
            assert!(m.contains(&format!("`{text}`")), "{m} does not name {text}");
            assert!(m.contains(expected), "{m} does not say {expected}");
            assert!(m.contains("uniform:A..B") && m.contains("triangular:A,MODE,B"), "{m} does not list the forms");
        }
    }
}
