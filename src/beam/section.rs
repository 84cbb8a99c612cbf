//! Cross-sections and materials of the arm, and the section catalogue.
//!
//! Bending is in the lift plane: `depth_m` is the section's extent in that plane (the direction
//! of the arm's deflection), `width_m` the extent across it. Second moments are about the axis
//! normal to the lift plane.

use serde::{Deserialize, Serialize};

use super::BeamError;

/// Isotropic linear-elastic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus_pa: f64,
    /// Density ρ, kg/m³.
    pub density_kg_m3: f64,
}

impl Material {
    /// Structural steel (E = 206 GPa, ρ = 7850 kg/m³), the seed's arm material.
    pub const STEEL: Material = Material { youngs_modulus_pa: 2.06e11, density_kg_m3: 7850.0 };

    /// Checks that E and ρ are finite and positive.
    pub fn validate(&self) -> Result<(), BeamError> {
        positive("youngs_modulus_pa", self.youngs_modulus_pa)?;
        positive("density_kg_m3", self.density_kg_m3)
    }
}

/// Section shapes of the catalogue; dimensions in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SectionShape {
    /// Solid circle of diameter `diameter_m`.
    SolidCircle { diameter_m: f64 },
    /// Solid rectangle `width_m` × `depth_m` (depth in the bending plane).
    SolidRectangle { width_m: f64, depth_m: f64 },
    /// Rectangular hollow section with uniform wall `wall_m`.
    HollowRectangle { width_m: f64, depth_m: f64, wall_m: f64 },
    /// Circular tube of outer diameter `outer_diameter_m` and wall `wall_m`.
    Tube { outer_diameter_m: f64, wall_m: f64 },
}

/// Area and second moment of a section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionProperties {
    /// Cross-section area A, m².
    pub area_m2: f64,
    /// Second moment of area I about the axis normal to the lift plane, m⁴.
    pub second_moment_m4: f64,
}

impl SectionProperties {
    /// Mass per unit length ρA of this section in `material`, kg/m.
    pub fn mass_per_length_kg_m(&self, material: &Material) -> f64 {
        material.density_kg_m3 * self.area_m2
    }
}

impl SectionShape {
    /// Area and second moment, after checking every dimension is positive and walls fit.
    pub fn properties(&self) -> Result<SectionProperties, BeamError> {
        use std::f64::consts::PI;
        let (area_m2, second_moment_m4) = match *self {
            SectionShape::SolidCircle { diameter_m: d } => {
                positive("diameter_m", d)?;
                (PI * d * d / 4.0, PI * d.powi(4) / 64.0)
            }
            SectionShape::SolidRectangle { width_m: b, depth_m: h } => {
                positive("width_m", b)?;
                positive("depth_m", h)?;
                (b * h, b * h.powi(3) / 12.0)
            }
            SectionShape::HollowRectangle { width_m: b, depth_m: h, wall_m: t } => {
                positive("width_m", b)?;
                positive("depth_m", h)?;
                wall_fits(t, b.min(h))?;
                let (bi, hi) = (b - 2.0 * t, h - 2.0 * t);
                (b * h - bi * hi, (b * h.powi(3) - bi * hi.powi(3)) / 12.0)
            }
            SectionShape::Tube { outer_diameter_m: d, wall_m: t } => {
                positive("outer_diameter_m", d)?;
                wall_fits(t, d)?;
                let di = d - 2.0 * t;
                (PI * (d * d - di * di) / 4.0, PI * (d.powi(4) - di.powi(4)) / 64.0)
            }
        };
        Ok(SectionProperties { area_m2, second_moment_m4 })
    }
}

/// A wall must be positive and leave a hollow: 0 < t < extent/2.
fn wall_fits(wall_m: f64, extent_m: f64) -> Result<(), BeamError> {
    if wall_m.is_finite() && wall_m > 0.0 && 2.0 * wall_m < extent_m {
        Ok(())
    } else {
        Err(BeamError::invalid("wall_m", wall_m, format!("0 < wall_m < {}", extent_m / 2.0)))
    }
}

/// Checks `value` is finite and > 0.
pub(crate) fn positive(name: &str, value: f64) -> Result<(), BeamError> {
    if value.is_finite() && value > 0.0 { Ok(()) } else { Err(BeamError::invalid(name, value, "a finite value > 0")) }
}

/// Checks `value` is finite and ≥ 0.
pub(crate) fn non_negative(name: &str, value: f64) -> Result<(), BeamError> {
    if value.is_finite() && value >= 0.0 { Ok(()) } else { Err(BeamError::invalid(name, value, "a finite value >= 0")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catalogue_matches_textbook_formulas() {
        // Hollow rectangle 100 x 200 x 10: A = 100*200 - 80*180, I = (100*200^3 - 80*180^3)/12 (mm).
        let p = SectionShape::HollowRectangle { width_m: 0.1, depth_m: 0.2, wall_m: 0.01 }.properties().unwrap();
        assert!((p.area_m2 - 5.6e-3).abs() < 1e-15);
        assert!((p.second_moment_m4 - (0.1 * 0.008 - 0.08 * 0.005832) / 12.0).abs() < 1e-18);
        // A tube with a vanishing wall tends to pi d t and pi d^3 t / 8.
        let (d, t) = (0.3, 1e-6);
        let p = SectionShape::Tube { outer_diameter_m: d, wall_m: t }.properties().unwrap();
        assert!((p.area_m2 / (std::f64::consts::PI * d * t) - 1.0).abs() < 1e-4);
        assert!((p.second_moment_m4 / (std::f64::consts::PI * d.powi(3) * t / 8.0) - 1.0).abs() < 1e-4);
    }

    #[test]
    fn bad_dimensions_name_the_parameter() {
        let e = SectionShape::Tube { outer_diameter_m: 0.1, wall_m: 0.06 }.properties().unwrap_err();
        assert!(e.to_string().contains("wall_m"), "{e}");
        let e = SectionShape::SolidCircle { diameter_m: -1.0 }.properties().unwrap_err();
        assert!(e.to_string().contains("diameter_m"), "{e}");
    }
}
