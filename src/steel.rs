//! Structural steels by name, with their minimum yield strength by thickness.
//!
//! - EN 10025-2:2019, Table 7 (non-alloy structural steels, hot rolled): S235, S275, S355;
//!   nominal thickness ≤ 16, ≤ 40, ≤ 63, ≤ 80, ≤ 100 mm.
//! - EN 10025-6:2019, Table 4 (quenched and tempered high-yield plates): S460Q, S690Q (written
//!   `S460`, `S690`); thickness ≤ 50, ≤ 100 mm.
//!
//! The thickness is the section's wall (hollow sections), its smaller side (a solid rectangle)
//! or its diameter (a solid circle).

use crate::beam::SectionShape;

/// A steel grade and its minimum yield strength by nominal thickness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteelGrade {
    /// Its name as a URDF writes it (`S355`).
    pub name: &'static str,
    /// The standard that tables it.
    pub standard: &'static str,
    /// (thickness up to, m; minimum yield strength, Pa), ascending.
    pub yield_by_thickness: &'static [(f64, f64)],
}

const MM: f64 = 1e-3;
const MPA: f64 = 1e6;

/// The grades a segment may name.
pub const GRADES: [SteelGrade; 5] = [
    SteelGrade {
        name: "S235",
        standard: "EN 10025-2",
        yield_by_thickness: &[
            (16.0 * MM, 235.0 * MPA),
            (40.0 * MM, 225.0 * MPA),
            (63.0 * MM, 215.0 * MPA),
            (80.0 * MM, 215.0 * MPA),
            (100.0 * MM, 215.0 * MPA),
        ],
    },
    SteelGrade {
        name: "S275",
        standard: "EN 10025-2",
        yield_by_thickness: &[
            (16.0 * MM, 275.0 * MPA),
            (40.0 * MM, 265.0 * MPA),
            (63.0 * MM, 255.0 * MPA),
            (80.0 * MM, 245.0 * MPA),
            (100.0 * MM, 235.0 * MPA),
        ],
    },
    SteelGrade {
        name: "S355",
        standard: "EN 10025-2",
        yield_by_thickness: &[
            (16.0 * MM, 355.0 * MPA),
            (40.0 * MM, 345.0 * MPA),
            (63.0 * MM, 335.0 * MPA),
            (80.0 * MM, 325.0 * MPA),
            (100.0 * MM, 315.0 * MPA),
        ],
    },
    SteelGrade {
        name: "S460",
        standard: "EN 10025-6 (S460Q)",
        yield_by_thickness: &[(50.0 * MM, 460.0 * MPA), (100.0 * MM, 440.0 * MPA)],
    },
    SteelGrade {
        name: "S690",
        standard: "EN 10025-6 (S690Q)",
        yield_by_thickness: &[(50.0 * MM, 690.0 * MPA), (100.0 * MM, 650.0 * MPA)],
    },
];

/// The grades' names, for messages.
pub fn grade_names() -> String {
    GRADES.map(|g| g.name).join(", ")
}

/// The grade named `name` (case-insensitive).
pub fn grade(name: &str) -> Option<&'static SteelGrade> {
    GRADES.iter().find(|g| g.name.eq_ignore_ascii_case(name.trim()))
}

/// The nominal thickness the yield tables go by, m.
pub fn nominal_thickness_m(section: &SectionShape) -> f64 {
    match *section {
        SectionShape::SolidCircle { diameter_m } => diameter_m,
        SectionShape::SolidRectangle { width_m, depth_m } => width_m.min(depth_m),
        SectionShape::HollowRectangle { wall_m, .. } | SectionShape::Tube { wall_m, .. } => wall_m,
    }
}

impl SteelGrade {
    /// Minimum yield strength at nominal thickness `thickness_m`, Pa (`None` beyond the table).
    pub fn yield_strength_pa(&self, thickness_m: f64) -> Option<f64> {
        self.yield_by_thickness.iter().find(|(up_to, _)| thickness_m <= up_to + 1e-12).map(|(_, fy)| *fy)
    }

    /// The largest thickness the table covers, m.
    pub fn max_thickness_m(&self) -> f64 {
        self.yield_by_thickness.last().map_or(0.0, |(t, _)| *t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yield_falls_with_thickness_as_tabled() {
        let s355 = grade("s355").unwrap();
        assert_eq!(s355.yield_strength_pa(0.0125), Some(355e6));
        assert_eq!(s355.yield_strength_pa(0.016), Some(355e6));
        assert_eq!(s355.yield_strength_pa(0.020), Some(345e6));
        assert_eq!(s355.yield_strength_pa(0.2), None);
        assert_eq!(grade("S690").unwrap().yield_strength_pa(0.06), Some(650e6));
        assert!(grade("S420").is_none());
        for g in GRADES {
            assert!(g.yield_by_thickness.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 >= w[1].1), "{}", g.name);
        }
        let box_section = SectionShape::HollowRectangle { width_m: 0.25, depth_m: 0.5, wall_m: 0.0125 };
        assert_eq!(nominal_thickness_m(&box_section), 0.0125);
    }
}
