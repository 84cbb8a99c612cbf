//! API 5CT tubing and casing (API Specification 5CT, Casing and Tubing: outside diameters, nominal
//! weights and walls), and pipe strings made of them.

use serde::{Deserialize, Serialize};

use super::RobotError;

/// One catalogue entry: a pipe size and weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PipeSize {
    /// Trade size, inches, as written ("2-7/8").
    pub size: &'static str,
    /// Tubing or casing, and its connection.
    pub product: &'static str,
    /// Outer diameter, m.
    pub outer_diameter_m: f64,
    /// Wall thickness, m.
    pub wall_m: f64,
    /// Nominal linear mass, kg/m (the API nominal weight).
    pub mass_per_length_kg_m: f64,
    /// Length of one joint of the range this catalogue uses, m.
    pub joint_length_m: f64,
}

const INCH_M: f64 = 0.0254;

/// The catalogue: one nominal weight per size, chosen as the seed's strings (pipes.md).
/// Range-3 joints: tubing 11.58–12.80 m (12.5 m used), casing 10.36–14.63 m (11.6 m used).
pub const PIPE_CATALOGUE: [PipeSize; 4] = [
    PipeSize {
        size: "2-3/8",
        product: "tubing EUE 4.70 lb/ft",
        outer_diameter_m: 0.0603,
        wall_m: 0.190 * INCH_M,
        mass_per_length_kg_m: 7.00,
        joint_length_m: 12.5,
    },
    PipeSize {
        size: "2-7/8",
        product: "tubing EUE 6.50 lb/ft",
        outer_diameter_m: 0.0730,
        wall_m: 0.217 * INCH_M,
        mass_per_length_kg_m: 9.67,
        joint_length_m: 12.5,
    },
    PipeSize {
        size: "3-1/2",
        product: "tubing EUE 9.30 lb/ft",
        outer_diameter_m: 0.0889,
        wall_m: 0.254 * INCH_M,
        mass_per_length_kg_m: 13.84,
        joint_length_m: 12.5,
    },
    PipeSize {
        size: "4-1/2",
        product: "casing 11.60 lb/ft",
        outer_diameter_m: 0.1143,
        wall_m: 0.250 * INCH_M,
        mass_per_length_kg_m: 17.26,
        joint_length_m: 11.6,
    },
];

/// Looks a size up ("2-7/8", "4-1/2", ...).
pub fn pipe_size(size: &str) -> Result<&'static PipeSize, RobotError> {
    PIPE_CATALOGUE.iter().find(|p| p.size == size).ok_or_else(|| RobotError::Invalid {
        key: "payload.size".into(),
        message: format!(
            "unknown pipe size `{size}`: allowed {}",
            PIPE_CATALOGUE.iter().map(|p| p.size).collect::<Vec<_>>().join(", ")
        ),
    })
}

/// A string as a scenario names it: a size and a length (default one Range-3 joint).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringSpec {
    /// Trade size ("2-7/8").
    pub size: String,
    /// Length, m (default: one joint of the catalogue's range).
    pub length_m: Option<f64>,
}

/// A pipe string resolved against the catalogue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PipeString {
    /// The size.
    pub pipe: &'static PipeSize,
    /// Length, m.
    pub length_m: f64,
}

impl PipeString {
    /// Resolves a spec.
    pub fn from_spec(spec: &StringSpec) -> Result<Self, RobotError> {
        let pipe = pipe_size(&spec.size)?;
        let length_m = spec.length_m.unwrap_or(pipe.joint_length_m);
        if !(length_m.is_finite() && length_m > 0.0 && length_m <= 40.0) {
            return Err(RobotError::Invalid {
                key: "payload.length_m".into(),
                message: format!("{length_m} is outside 0 < length_m <= 40 (one stand at most)"),
            });
        }
        Ok(PipeString { pipe, length_m })
    }

    /// Mass, kg.
    pub fn mass_kg(&self) -> f64 {
        self.pipe.mass_per_length_kg_m * self.length_m
    }

    /// Moment of inertia about its centre, normal to its axis, kg·m² (a slender tube: m L²/12
    /// plus the section's m(D² + d²)/16).
    pub fn transverse_inertia_kg_m2(&self) -> f64 {
        let (d_out, d_in) = (self.pipe.outer_diameter_m, self.pipe.outer_diameter_m - 2.0 * self.pipe.wall_m);
        self.mass_kg() * (self.length_m.powi(2) / 12.0 + (d_out * d_out + d_in * d_in) / 16.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_seed_strings_weigh_what_the_paper_says() {
        // The seed: a 2-7/8 in string of about 121 kg and a 4-1/2 in string of about 200 kg.
        let tubing = PipeString::from_spec(&StringSpec { size: "2-7/8".into(), length_m: None }).unwrap();
        let casing = PipeString::from_spec(&StringSpec { size: "4-1/2".into(), length_m: None }).unwrap();
        assert!((tubing.mass_kg() - 121.0).abs() < 1.0, "{}", tubing.mass_kg());
        assert!((casing.mass_kg() - 200.0).abs() < 1.0, "{}", casing.mass_kg());
    }

    #[test]
    fn nominal_weight_matches_steel_of_the_stated_section() {
        // Plain-end steel mass from OD and wall is within 8 % of the nominal weight, which adds
        // the upset ends and the coupling (EUE tubing: 5–7 %).
        for p in PIPE_CATALOGUE {
            let d_in = p.outer_diameter_m - 2.0 * p.wall_m;
            let plain = 7850.0 * std::f64::consts::PI / 4.0 * (p.outer_diameter_m.powi(2) - d_in * d_in);
            assert!(
                (p.mass_per_length_kg_m / plain - 1.0).abs() < 0.08,
                "{}: {plain} vs {}",
                p.size,
                p.mass_per_length_kg_m
            );
        }
    }

    #[test]
    fn unknown_size_lists_the_catalogue() {
        let e = pipe_size("2-1/2").unwrap_err().to_string();
        assert!(e.contains("2-7/8") && e.contains("payload.size"), "{e}");
    }
}
