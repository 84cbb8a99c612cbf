//! Steel grades of oilfield tubulars and their specified minimum yield strength.

/// A steel grade.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grade {
    /// Its name ("L80", "G105").
    pub name: &'static str,
    /// Specified minimum yield strength, Pa.
    pub yield_strength_pa: f64,
}

const fn grade(name: &'static str, yield_mpa: f64) -> Grade {
    Grade { name, yield_strength_pa: yield_mpa * 1e6 }
}

/// API 5CT casing and tubing grades (Table C.5 / E.5: 40 … 125 ksi, its SI values).
pub const API_5CT_GRADES: [Grade; 11] = [
    grade("H40", 276.0),
    grade("J55", 379.0),
    grade("K55", 379.0),
    grade("N80", 552.0),
    grade("L80", 552.0),
    grade("C90", 621.0),
    grade("R95", 655.0),
    grade("T95", 655.0),
    grade("C110", 758.0),
    grade("P110", 758.0),
    grade("Q125", 862.0),
];

/// API 5DP drill pipe grades (75, 95, 105, 135 ksi).
pub const DRILL_PIPE_GRADES: [Grade; 4] =
    [grade("E75", 517.0), grade("X95", 655.0), grade("G105", 724.0), grade("S135", 931.0)];

/// The grade `name` of `product`, or an error listing the product's grades.
pub(super) fn find(product: super::Product, name: &str) -> Result<Grade, super::RobotError> {
    let grades = product.grades();
    grades.iter().copied().find(|g| g.name == name).ok_or_else(|| {
        let allowed = if grades.is_empty() {
            format!("none: {} has no named grades", product.name())
        } else {
            grades.iter().map(|g| g.name).collect::<Vec<_>>().join(", ")
        };
        super::invalid("payload.grade", format!("`{name}` is not a grade of {}: allowed {allowed}", product.name()))
    })
}
