//! Pipe strings: a catalogue row or a pipe of the user's own, as one uniform tube or as joints
//! of a range with their couplings or tool joints.
//!
//! A string named by its size alone (`size = "2-7/8"`, a `length_m`) is one uniform tube at the
//! row's nominal weight, which spreads the coupling over the joint. Given `range`, `joints` or
//! `joint_length_m`, it is made of joints: the plain pipe at its plain-end weight, and each
//! connection a short section of its own outside diameter carrying the connection's mass at its
//! station (a casing or tubing coupling on each joint's box end, the far one from the pivot; a
//! tool joint's pin at the near end and its box at the far end, meeting where two joints do).

mod catalogue;
mod custom;
mod entry;
mod grade;

use serde::{Deserialize, Serialize};

pub use catalogue::{
    Connection, INCH_M, LB_FT_KG_M, PIPE_CATALOGUE, PipeSize, Product, Range, RangeLength, STEEL_DENSITY_KG_M3,
};
pub use custom::CustomPipeSpec;
pub use entry::{ENTRY_SEPARATOR, class_rows, entry_row, product_named};
pub use grade::{API_5CT_GRADES, DRILL_PIPE_GRADES, Grade};

use super::RobotError;
use crate::beam::Material;

/// Young's modulus of the catalogue's steel, Pa.
pub const STEEL_YOUNGS_MODULUS_PA: f64 = Material::STEEL.youngs_modulus_pa;

/// Longest uniform string, m (one stand).
const MAX_UNIFORM_LENGTH_M: f64 = 40.0;

/// Most joints in a stand.
pub const MAX_JOINTS: usize = 3;

/// Weights match a row within this, lb/ft (the tables print two decimals).
const WEIGHT_MATCH_LB_FT: f64 = 0.006;

fn invalid(key: &str, message: impl Into<String>) -> RobotError {
    RobotError::Invalid { key: key.into(), message: message.into() }
}

/// The distinct sizes of the catalogue, in its order.
fn sizes() -> Vec<&'static str> {
    let mut sizes: Vec<&str> = Vec::new();
    for row in PIPE_CATALOGUE {
        if !sizes.contains(&row.size) {
            sizes.push(row.size);
        }
    }
    sizes
}

/// The row a size picks: of `product` if given (else the first product, casing, tubing, drill
/// pipe, heavy-weight, collar, that has the size), of `weight_lb_ft` if given (else the
/// product's default weight for the size).
pub fn find_row(
    size: &str,
    product: Option<Product>,
    weight_lb_ft: Option<f64>,
) -> Result<&'static PipeSize, RobotError> {
    let of_size: Vec<&PipeSize> = PIPE_CATALOGUE.iter().filter(|p| p.size == size).collect();
    if of_size.is_empty() {
        return Err(invalid("payload.size", format!("unknown pipe size `{size}`: allowed {}", sizes().join(", "))));
    }
    let made: Vec<Product> = Product::ALL.into_iter().filter(|p| of_size.iter().any(|r| r.product == *p)).collect();
    let names = |products: &[Product]| products.iter().map(|p| p.name()).collect::<Vec<_>>().join(", ");
    if let Some(product) = product
        && !made.contains(&product)
    {
        return Err(invalid(
            "payload.product",
            format!("size {size} is not made as {}: allowed {}", product.name(), names(&made)),
        ));
    }
    let candidates = |p: Product| of_size.iter().copied().filter(move |r| r.product == p);
    let products = product.map_or(made.clone(), |p| vec![p]);
    match weight_lb_ft {
        None => Ok(products
            .iter()
            .find_map(|p| candidates(*p).find(|r| r.default))
            .expect("every size and product has a default row (catalogue test)")),
        Some(w) => products
            .iter()
            .find_map(|p| candidates(*p).find(|r| (r.nominal_weight_lb_ft - w).abs() < WEIGHT_MATCH_LB_FT))
            .ok_or_else(|| {
                let allowed: Vec<String> = products
                    .iter()
                    .flat_map(|p| {
                        candidates(*p).map(|r| format!("{:.2} ({})", r.nominal_weight_lb_ft, r.product.name()))
                    })
                    .collect();
                invalid("payload.weight_lb_ft", format!("no {size} pipe of {w} lb/ft: allowed {}", allowed.join(", ")))
            }),
    }
}

/// The default row of a size ("2-7/8", "9-5/8", ...).
pub fn pipe_size(size: &str) -> Result<&'static PipeSize, RobotError> {
    find_row(size, None, None)
}

/// A string as a scenario names it (the keys of `[payload]` with `kind = "string"`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringSpec {
    /// Trade size ("2-7/8"); required unless `pipe` describes the pipe.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<String>,
    /// Casing, tubing, drill pipe, ... (default: the first the size is made as).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub product: Option<Product>,
    /// Nominal weight, lb/ft (default: the catalogue's default weight for the size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weight_lb_ft: Option<f64>,
    /// Steel grade ("L80", "G105").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grade: Option<String>,
    /// A pipe of the user's own, instead of a catalogue row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pipe: Option<Box<CustomPipeSpec>>,
    /// Length of a uniform string, m (default: one joint of the size's default range).
    pub length_m: Option<f64>,
    /// The joints' length class, R1, R2 or R3 (default: R3, or the only range the product has).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<Range>,
    /// Joints in the string, 1 ..= 3 (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joints: Option<usize>,
    /// Length of each joint, m (default: the range's default length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint_length_m: Option<f64>,
}

impl StringSpec {
    /// A uniform string of a catalogue size at its default weight and length.
    pub fn of_size(size: &str) -> Self {
        StringSpec { size: Some(size.into()), ..StringSpec::default() }
    }

    /// Whether it asks for joints with their connections.
    fn has_joints(&self) -> bool {
        self.range.is_some() || self.joints.is_some() || self.joint_length_m.is_some()
    }
}

/// A pipe's section and steel, from the catalogue or the user's own.
#[derive(Debug, Clone, PartialEq)]
pub struct Pipe {
    /// Trade size, or `custom`.
    pub size: String,
    /// What it is, as reports write it ("9-5/8 casing 47.00 lb/ft").
    pub label: String,
    /// Outer diameter, m.
    pub outer_diameter_m: f64,
    /// Wall thickness, m.
    pub wall_m: f64,
    /// Linear mass of the pipe's body, kg/m: the nominal weight for a uniform string (its
    /// couplings spread over it), the plain-end weight between the connections of joints.
    pub mass_per_length_kg_m: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
    /// Minimum yield strength, Pa, where a grade (or the user) gives it.
    pub yield_strength_pa: Option<f64>,
    /// The grade, if one was chosen.
    pub grade: Option<&'static str>,
    /// The catalogue row, if it is one.
    pub row: Option<&'static PipeSize>,
}

impl Pipe {
    /// Inner diameter, m.
    pub fn inner_diameter_m(&self) -> f64 {
        self.outer_diameter_m - 2.0 * self.wall_m
    }

    /// The steel of its models: its modulus, steel's density.
    pub fn material(&self) -> Material {
        Material { youngs_modulus_pa: self.youngs_modulus_pa, density_kg_m3: STEEL_DENSITY_KG_M3 }
    }
}

/// How a string made of joints is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joints {
    /// Number of joints.
    pub count: usize,
    /// Their range.
    pub range: Range,
    /// Length of each, m.
    pub joint_length_m: f64,
}

/// A connection (or one part of a tool joint) on the string: where it lies and what it adds.
#[derive(Debug, Clone, PartialEq)]
pub struct ConnectionPiece {
    /// What it is.
    pub name: &'static str,
    /// Its start along the string, from the end nearest the pivot, m.
    pub from_m: f64,
    /// Its end, m.
    pub to_m: f64,
    /// Outside diameter, m.
    pub outer_diameter_m: f64,
    /// Bore, m.
    pub bore_m: f64,
    /// Mass it adds to the pipe body over its length, kg.
    pub added_mass_kg: f64,
}

impl ConnectionPiece {
    /// Its middle along the string, m.
    pub fn centre_m(&self) -> f64 {
        0.5 * (self.from_m + self.to_m)
    }

    /// Its length, m.
    pub fn length_m(&self) -> f64 {
        self.to_m - self.from_m
    }
}

/// A pipe string resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct PipeString {
    /// The pipe.
    pub pipe: Box<Pipe>,
    /// Length, m.
    pub length_m: f64,
    /// Its joints (`None`: one uniform tube).
    pub joints: Option<Joints>,
    /// Its connections, from the pivot's end outwards (none on a uniform tube).
    pub connections: Vec<ConnectionPiece>,
}

impl PipeString {
    /// Resolves a spec against the catalogue, or its own pipe.
    pub fn from_spec(spec: &StringSpec) -> Result<Self, RobotError> {
        let pipe = match &spec.pipe {
            Some(own) => return custom::resolve(own, spec),
            None => {
                let size = spec.size.as_deref().ok_or_else(|| {
                    invalid(
                        "payload.size",
                        "missing: give a catalogue size (`pipearm pipes` lists them) or payload.pipe (a pipe of your own)",
                    )
                })?;
                find_row(size, spec.product, spec.weight_lb_ft)?
            }
        };
        let (grade, yield_strength_pa) = match &spec.grade {
            None => (None, pipe.yield_strength_pa()),
            Some(name) => {
                let g = grade::find(pipe.product, name)?;
                (Some(g.name), Some(g.yield_strength_pa))
            }
        };
        let body = |mass_per_length_kg_m| Pipe {
            size: pipe.size.into(),
            label: pipe.label(),
            outer_diameter_m: pipe.outer_diameter_m,
            wall_m: pipe.wall_m,
            mass_per_length_kg_m,
            youngs_modulus_pa: STEEL_YOUNGS_MODULUS_PA,
            yield_strength_pa,
            grade,
            row: Some(pipe),
        };
        if !spec.has_joints() {
            let length_m = spec.length_m.unwrap_or_else(|| default_range(pipe.product).default_m);
            check_uniform_length(length_m)?;
            return Ok(PipeString::uniform(body(pipe.mass_per_length_kg_m), length_m));
        }
        if spec.length_m.is_some() {
            return Err(invalid(
                "payload.length_m",
                "give either length_m (one uniform tube) or range / joints / joint_length_m (joints with their connections)",
            ));
        }
        let joints = joints_of(pipe.product, spec)?;
        Ok(PipeString::of_joints(body(pipe.plain_end_kg_m()), &pipe.connection, joints))
    }

    /// One uniform tube.
    pub fn uniform(pipe: Pipe, length_m: f64) -> Self {
        PipeString { pipe: Box::new(pipe), length_m, joints: None, connections: Vec::new() }
    }

    /// Joints of `pipe` (its body at plain-end weight) with `connection` on each.
    pub fn of_joints(pipe: Pipe, connection: &Connection, joints: Joints) -> Self {
        let length_m = joints.count as f64 * joints.joint_length_m;
        PipeString {
            pipe: Box::new(pipe),
            length_m,
            joints: Some(joints),
            connections: place_connections(connection, joints),
        }
    }

    /// Mass, kg.
    pub fn mass_kg(&self) -> f64 {
        self.pipe.mass_per_length_kg_m * self.length_m + self.connections.iter().map(|c| c.added_mass_kg).sum::<f64>()
    }

    /// Its centre of mass along it from the end nearest the pivot, m.
    pub fn mass_centre_m(&self) -> f64 {
        if self.connections.is_empty() {
            return 0.5 * self.length_m;
        }
        let body = self.pipe.mass_per_length_kg_m * self.length_m;
        let moment =
            body * 0.5 * self.length_m + self.connections.iter().map(|c| c.added_mass_kg * c.centre_m()).sum::<f64>();
        moment / self.mass_kg()
    }

    /// Moment of inertia about its centre of mass, normal to its axis, kg·m² (a slender tube:
    /// m L²/12 plus the section's m(D² + d²)/16, and each connection's mass at its place).
    pub fn transverse_inertia_kg_m2(&self) -> f64 {
        let (d_out, d_in) = (self.pipe.outer_diameter_m, self.pipe.inner_diameter_m());
        let centre = self.mass_centre_m();
        let body = self.pipe.mass_per_length_kg_m * self.length_m;
        let body_offset = 0.5 * self.length_m - centre;
        let own = body * (self.length_m.powi(2) / 12.0 + (d_out * d_out + d_in * d_in) / 16.0);
        let connections: f64 = self
            .connections
            .iter()
            .map(|c| c.added_mass_kg * ((c.centre_m() - centre).powi(2) + c.length_m().powi(2) / 12.0))
            .sum();
        own + body * body_offset * body_offset + connections
    }
}

/// The range a product's uniform string takes its default length from.
fn default_range(product: Product) -> RangeLength {
    product.ranges()[product.default_range().index()].expect("a product's default range exists")
}

fn check_uniform_length(length_m: f64) -> Result<(), RobotError> {
    if length_m.is_finite() && length_m > 0.0 && length_m <= MAX_UNIFORM_LENGTH_M {
        Ok(())
    } else {
        Err(invalid(
            "payload.length_m",
            format!("{length_m} is outside 0 < length_m <= {MAX_UNIFORM_LENGTH_M} (one stand at most)"),
        ))
    }
}

/// The joints a spec asks for, checked against the product's ranges.
fn joints_of(product: Product, spec: &StringSpec) -> Result<Joints, RobotError> {
    let range = spec.range.unwrap_or(product.default_range());
    let ranges = product.ranges();
    let Some(lengths) = ranges[range.index()] else {
        let made: Vec<&str> = [Range::R1, Range::R2, Range::R3]
            .into_iter()
            .filter(|r| ranges[r.index()].is_some())
            .map(Range::name)
            .collect();
        return Err(invalid(
            "payload.range",
            format!("{} is not made in {}: allowed {}", product.name(), range.name(), made.join(", ")),
        ));
    };
    let count = spec.joints.unwrap_or(1);
    if !(1..=MAX_JOINTS).contains(&count) {
        return Err(invalid("payload.joints", format!("{count} is outside 1 ..= {MAX_JOINTS} (a stand at most)")));
    }
    let joint_length_m = spec.joint_length_m.unwrap_or(lengths.default_m);
    if !(joint_length_m.is_finite() && (lengths.min_m..=lengths.max_m).contains(&joint_length_m)) {
        return Err(invalid(
            "payload.joint_length_m",
            format!(
                "{joint_length_m} is outside {} ..= {} m ({} {})",
                lengths.min_m,
                lengths.max_m,
                product.name(),
                range.name()
            ),
        ));
    }
    Ok(Joints { count, range, joint_length_m })
}

/// Each joint's connection along the string: a coupling on each joint's far (box) end; a tool
/// joint's pin part on the near end and its box part on the far end, one piece where two joints
/// meet.
fn place_connections(connection: &Connection, joints: Joints) -> Vec<ConnectionPiece> {
    if connection.is_integral() {
        return Vec::new();
    }
    let (pin, length) = (connection.pin_length_m, connection.length_m);
    let mass_per_m = connection.added_mass_kg / length;
    let piece = |from_m: f64, to_m: f64| ConnectionPiece {
        name: connection.name,
        from_m,
        to_m,
        outer_diameter_m: connection.outer_diameter_m,
        bore_m: connection.bore_m,
        added_mass_kg: mass_per_m * (to_m - from_m),
    };
    let l = joints.joint_length_m;
    let mut pieces = Vec::new();
    if pin > 0.0 {
        pieces.push(piece(0.0, pin));
    }
    for k in 1..=joints.count {
        let end = k as f64 * l;
        let beyond = if k < joints.count { pin } else { 0.0 };
        pieces.push(piece(end - (length - pin), end + beyond));
    }
    pieces
}

#[cfg(test)]
mod tests;
