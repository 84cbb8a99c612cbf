//! A pipe of the user's own (`payload.pipe`): its section, weight and steel.

use serde::{Deserialize, Serialize};

use super::{
    Pipe, PipeString, STEEL_DENSITY_KG_M3, STEEL_YOUNGS_MODULUS_PA, StringSpec, check_uniform_length, invalid,
};
use crate::robot::RobotError;

/// How far below its own plain steel tube a pipe's weight may be: measured weights and the
/// standards' rounding differ by a few per cent; more is a section that is not steel, or a typo.
pub const WEIGHT_SHORTFALL_ALLOWED: f64 = 0.03;

/// A pipe as a scenario describes it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CustomPipeSpec {
    /// Outer diameter, m.
    pub outer_diameter_m: f64,
    /// Wall thickness, m (or `bore_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_m: Option<f64>,
    /// Bore (inner diameter), m (or `wall_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bore_m: Option<f64>,
    /// Linear mass, kg/m (default: the plain steel tube, ρ = 7850 kg/m³).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_per_length_kg_m: Option<f64>,
    /// Young's modulus, Pa (default 206 GPa).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus_pa: Option<f64>,
    /// Minimum yield strength, Pa.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_strength_pa: Option<f64>,
}

const KEY: &str = "payload.pipe";

/// The uniform string of a pipe of the user's own, its keys checked.
pub(super) fn resolve(own: &CustomPipeSpec, spec: &StringSpec) -> Result<PipeString, RobotError> {
    let given = [
        ("size", spec.size.is_some()),
        ("product", spec.product.is_some()),
        ("weight_lb_ft", spec.weight_lb_ft.is_some()),
        ("grade", spec.grade.is_some()),
        ("range", spec.range.is_some()),
        ("joints", spec.joints.is_some()),
        ("joint_length_m", spec.joint_length_m.is_some()),
    ];
    if let Some((key, _)) = given.iter().find(|(_, set)| *set) {
        return Err(invalid(
            &format!("payload.{key}"),
            "describes a catalogue pipe: leave it out with payload.pipe (a pipe of your own, one uniform tube of length_m)",
        ));
    }
    let length_m =
        spec.length_m.ok_or_else(|| invalid("payload.length_m", "required with payload.pipe: 0 < length_m <= 40"))?;
    check_uniform_length(length_m)?;
    Ok(PipeString::uniform(pipe(own)?, length_m))
}

/// The pipe, its values checked.
pub fn pipe(own: &CustomPipeSpec) -> Result<Pipe, RobotError> {
    let key = |k: &str| format!("{KEY}.{k}");
    let d = own.outer_diameter_m;
    if !(d.is_finite() && d > 0.0 && d <= 1.0) {
        return Err(invalid(&key("outer_diameter_m"), format!("{d} is outside 0 < outer_diameter_m <= 1")));
    }
    let wall_m = match (own.wall_m, own.bore_m) {
        (Some(t), None) => {
            if !(t.is_finite() && t > 0.0 && t < 0.5 * d) {
                return Err(invalid(
                    &key("wall_m"),
                    format!("{t} is outside 0 < wall_m < {} (half the outer diameter)", 0.5 * d),
                ));
            }
            t
        }
        (None, Some(bore)) => {
            if !(bore.is_finite() && bore > 0.0 && bore < d) {
                return Err(invalid(
                    &key("bore_m"),
                    format!("{bore} is outside 0 < bore_m < {d} (the outer diameter)"),
                ));
            }
            0.5 * (d - bore)
        }
        _ => return Err(invalid(KEY, "give one of wall_m and bore_m")),
    };
    let inner = d - 2.0 * wall_m;
    let plain_kg_m = STEEL_DENSITY_KG_M3 * std::f64::consts::FRAC_PI_4 * (d * d - inner * inner);
    let least = (1.0 - WEIGHT_SHORTFALL_ALLOWED) * plain_kg_m;
    let mass_per_length_kg_m = own.mass_per_length_kg_m.unwrap_or(plain_kg_m);
    if !(mass_per_length_kg_m.is_finite() && mass_per_length_kg_m >= least) {
        return Err(invalid(
            &key("mass_per_length_kg_m"),
            format!(
                "{mass_per_length_kg_m} kg/m is more than {:.0} % below the plain steel tube of this section \
                 ({plain_kg_m:.3} kg/m at 7850 kg/m³): allowed mass_per_length_kg_m >= {least:.3}",
                100.0 * WEIGHT_SHORTFALL_ALLOWED
            ),
        ));
    }
    let youngs_modulus_pa = own.youngs_modulus_pa.unwrap_or(STEEL_YOUNGS_MODULUS_PA);
    if !(youngs_modulus_pa.is_finite() && youngs_modulus_pa > 0.0) {
        return Err(invalid(
            &key("youngs_modulus_pa"),
            format!("{youngs_modulus_pa} is outside youngs_modulus_pa > 0"),
        ));
    }
    if let Some(y) = own.yield_strength_pa
        && !(y.is_finite() && y > 0.0)
    {
        return Err(invalid(&key("yield_strength_pa"), format!("{y} is outside yield_strength_pa > 0")));
    }
    Ok(Pipe {
        size: "custom".into(),
        label: format!("custom {:.1} x {:.2} mm, {mass_per_length_kg_m:.2} kg/m", 1e3 * d, 1e3 * wall_m),
        outer_diameter_m: d,
        wall_m,
        mass_per_length_kg_m,
        youngs_modulus_pa,
        yield_strength_pa: own.yield_strength_pa,
        grade: None,
        row: None,
    })
}
