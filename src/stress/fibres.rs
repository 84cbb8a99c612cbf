//! The normal stress at a section's outer fibres in the lift plane: σ = N/A ± M c/I, with N the
//! axial force (tension positive), M the bending moment (upper face in tension positive), c the
//! half depth and I the second moment about the axis normal to the lift plane.
//!
//! Every section of the catalogue is symmetric about that axis, so its upper and lower fibres
//! sit at ±c: the upper and lower flange faces of a rectangle (hollow or solid), the top and
//! bottom of a tube's or a solid circle's outer fibre. Shear stress, torsion and bending out of
//! the lift plane are not in a planar model.

use serde::Serialize;

use crate::beam::SectionShape;
use crate::robot::section_extent;

/// A fibre of a section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Fibre {
    /// The face at +y (the arm's upper face at θ = 0).
    Upper,
    /// The face at −y.
    Lower,
}

impl Fibre {
    /// Both, upper first.
    pub const BOTH: [Fibre; 2] = [Fibre::Upper, Fibre::Lower];

    /// Its name as a summary writes it.
    pub fn name(self) -> &'static str {
        match self {
            Fibre::Upper => "upper",
            Fibre::Lower => "lower",
        }
    }
}

/// A section's stress per unit axial force and per unit moment at its outer fibres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fibres {
    /// 1/A, 1/m².
    pub per_axial_force_per_m2: f64,
    /// c/I, 1/m³ (1/W, the elastic section modulus's inverse).
    pub per_moment_per_m3: f64,
}

impl Fibres {
    /// The fibres of `section` (its dimensions already checked).
    pub fn of(section: &SectionShape) -> Self {
        let p = section.properties().expect("a robot's sections are checked when it is read");
        let half_depth_m = 0.5 * section_extent(section).1;
        Fibres { per_axial_force_per_m2: 1.0 / p.area_m2, per_moment_per_m3: half_depth_m / p.second_moment_m4 }
    }

    /// σ at `fibre` under axial force `axial_n` and bending moment `moment_n_m`, Pa.
    pub fn stress_pa(&self, fibre: Fibre, axial_n: f64, moment_n_m: f64) -> f64 {
        let axial = axial_n * self.per_axial_force_per_m2;
        let bending = moment_n_m * self.per_moment_per_m3;
        match fibre {
            Fibre::Upper => axial + bending,
            Fibre::Lower => axial - bending,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_section_kind_gives_its_textbook_fibre_stress() {
        use std::f64::consts::PI;
        let (n, m) = (2.0e4, 3.0e3);
        // (section, A, I, c) by hand.
        let (b, h, t, d) = (0.1, 0.2, 0.01, 0.15);
        let cases = [
            (SectionShape::SolidRectangle { width_m: b, depth_m: h }, b * h, b * h.powi(3) / 12.0, h / 2.0),
            (
                SectionShape::HollowRectangle { width_m: b, depth_m: h, wall_m: t },
                b * h - (b - 2.0 * t) * (h - 2.0 * t),
                (b * h.powi(3) - (b - 2.0 * t) * (h - 2.0 * t).powi(3)) / 12.0,
                h / 2.0,
            ),
            (SectionShape::SolidCircle { diameter_m: d }, PI * d * d / 4.0, PI * d.powi(4) / 64.0, d / 2.0),
            (
                SectionShape::Tube { outer_diameter_m: d, wall_m: t },
                PI * (d * d - (d - 2.0 * t).powi(2)) / 4.0,
                PI * (d.powi(4) - (d - 2.0 * t).powi(4)) / 64.0,
                d / 2.0,
            ),
        ];
        for (section, area, inertia, c) in cases {
            let f = Fibres::of(&section);
            let upper = n / area + m * c / inertia;
            let lower = n / area - m * c / inertia;
            assert!((f.stress_pa(Fibre::Upper, n, m) / upper - 1.0).abs() < 1e-12, "{section:?}");
            assert!((f.stress_pa(Fibre::Lower, n, m) / lower - 1.0).abs() < 1e-12, "{section:?}");
        }
    }
}
