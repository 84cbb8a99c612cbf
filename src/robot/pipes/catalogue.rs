//! The catalogue of the tubulars a rig handles, in the units their standards tabulate them
//! (inches, lb/ft), converted to SI where a row is built.
//!
//! Sources, per group (tables of API Spec 5CT 8th ed. / ISO 11960:2004, SI Annex C and US
//! customary Annex E, and of the drilling standards):
//! - tubing: outside diameter, nominal (threaded and coupled) weight and wall from API 5CT
//!   Table C.2 / E.2 (tubing list); couplings' outside diameter and length from 5CT's non-upset
//!   and external-upset tubing coupling tables;
//! - casing: API 5CT Table C.1 / E.1 (casing list); round-thread couplings' outside diameter,
//!   length and mass from 5CT Table E.32 (the long coupling where 5CT has one for the size, else
//!   the short);
//! - drill pipe: API Spec 5DP's drill pipe body table (label weight, wall) with the tool joint
//!   each size is usually run with (API RP 7G / 5DP tool joint outside diameter and bore);
//! - heavy-weight drill pipe: no API table; the common dimensions of the drilling handbooks;
//! - drill collars: API Spec 7-1's drill collar sizes (NCxx-yy: connection and outside diameter,
//!   with its bore); weight w = 2.67 (D² − d²) lb/ft as API RP 7G tabulates it.
//!
//! Outside diameters are the SI tables', to 0.1 mm. Plain-end weights are the standards' formula w_pe = 10.69 (D − t) t lb/ft (5CT; 10.68 in
//! 5DP and RP 7G), D and t in inches, rounded to 0.01 lb/ft as the tables print them. Nominal
//! linear masses in kg/m are the SI tables' where the shared reference gives them, else the
//! weight × 1.48816 rounded to 0.01.
//!
//! Connection masses: the casing couplings' are 5CT's; the others are estimates. A tubing or
//! large-casing coupling is the steel ring of its outside diameter and length on the thread's
//! diameter (the pipe's, or the upset's for external-upset tubing) times 1.19, the mean ratio of
//! 5CT's published coupling masses to that ring for 4-1/2 … 13-3/8 in casing (1.14 … 1.25). A
//! tool joint is the steel ring of its outside diameter and bore over its pin and box tong
//! lengths (typical lengths: the joints' upsets are left out, a few per cent of a joint), less
//! the pipe body it replaces.

use serde::{Deserialize, Serialize};

/// Metres per inch.
pub const INCH_M: f64 = 0.0254;
/// kg/m per lb/ft.
pub const LB_FT_KG_M: f64 = 1.488_164;
/// Steel density of the standards' weight formulas, kg/m³.
pub const STEEL_DENSITY_KG_M3: f64 = 7850.0;
/// The published casing couplings' mass over the plain steel ring of their outside diameter and
/// length on the pipe's diameter (mean of 5CT Table E.32, 4-1/2 … 13-3/8 in).
const COUPLING_RING_FACTOR: f64 = 1.19;

/// What kind of tubular a row is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Product {
    /// API 5CT casing.
    Casing,
    /// API 5CT tubing.
    Tubing,
    /// API 5DP drill pipe with tool joints.
    DrillPipe,
    /// Heavy-weight drill pipe.
    HeavyWeightDrillPipe,
    /// API 7-1 drill collar.
    DrillCollar,
}

impl Product {
    /// Every product, in the order a size alone prefers them.
    pub const ALL: [Product; 5] =
        [Product::Casing, Product::Tubing, Product::DrillPipe, Product::HeavyWeightDrillPipe, Product::DrillCollar];

    /// The name a scenario writes (`payload.product`).
    pub fn name(self) -> &'static str {
        match self {
            Product::Casing => "casing",
            Product::Tubing => "tubing",
            Product::DrillPipe => "drill-pipe",
            Product::HeavyWeightDrillPipe => "heavy-weight-drill-pipe",
            Product::DrillCollar => "drill-collar",
        }
    }

    /// The joint length classes of the product, R1, R2, R3 (`None`: not made in that range).
    pub fn ranges(self) -> [Option<RangeLength>; 3] {
        let r = |min_m, max_m, default_m| Some(RangeLength { min_m, max_m, default_m });
        match self {
            // API 5CT range lengths; the R3 defaults are the lengths of the reference strings (a
            // 121 kg 2-7/8 in tubing joint, a 200 kg 4-1/2 in casing joint), the others the
            // middle of the range.
            Product::Tubing => [r(6.10, 7.32, 6.71), r(8.53, 9.75, 9.14), r(11.58, 12.80, 12.5)],
            Product::Casing => [r(4.88, 7.62, 6.25), r(7.62, 10.36, 8.99), r(10.36, 14.63, 11.6)],
            // API 5DP: 18–22, 27–30, 38–45 ft.
            Product::DrillPipe => [r(5.49, 6.71, 6.10), r(8.23, 9.14, 8.69), r(11.58, 13.72, 12.65)],
            // 30 ft (31 ft) joints.
            Product::HeavyWeightDrillPipe | Product::DrillCollar => [None, r(9.14, 9.45, 9.14), None],
        }
    }

    /// The range a joint of this product is when none is given: R3, or the only one it has.
    pub fn default_range(self) -> Range {
        match self {
            Product::HeavyWeightDrillPipe | Product::DrillCollar => Range::R2,
            _ => Range::R3,
        }
    }

    /// The steel grades the product is made in (none named for heavy-weight drill pipe and
    /// collars: a collar's steel is fixed by its size, [`PipeSize::yield_strength_pa`]).
    pub fn grades(self) -> &'static [super::grade::Grade] {
        match self {
            Product::Casing | Product::Tubing => &super::grade::API_5CT_GRADES,
            Product::DrillPipe => &super::grade::DRILL_PIPE_GRADES,
            Product::HeavyWeightDrillPipe | Product::DrillCollar => &[],
        }
    }
}

/// A joint length class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Range {
    /// Range 1.
    R1,
    /// Range 2.
    R2,
    /// Range 3.
    R3,
}

impl Range {
    /// Index in [`Product::ranges`].
    pub fn index(self) -> usize {
        match self {
            Range::R1 => 0,
            Range::R2 => 1,
            Range::R3 => 2,
        }
    }

    /// The name a scenario writes (`payload.range`).
    pub fn name(self) -> &'static str {
        ["R1", "R2", "R3"][self.index()]
    }
}

/// The lengths of one range: its limits and the catalogue's default joint length in it, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RangeLength {
    /// Shortest joint, m.
    pub min_m: f64,
    /// Longest joint, m.
    pub max_m: f64,
    /// Length of a joint of the range when none is given, m.
    pub default_m: f64,
}

/// A joint's connection: a coupling on its box end, a tool joint split between its pin and box
/// ends, or none (integral, as on a drill collar).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Connection {
    /// What it is ("EUE coupling", "NC50 tool joint").
    pub name: &'static str,
    /// Outside diameter, m.
    pub outer_diameter_m: f64,
    /// Bore under it, m (the pipe's for a coupling, the tool joint's own).
    pub bore_m: f64,
    /// Length, m (pin and box together for a tool joint).
    pub length_m: f64,
    /// Of the length, the part at the joint's pin end, m (0 for a coupling).
    pub pin_length_m: f64,
    /// Mass it adds to the plain pipe over its length, kg.
    pub added_mass_kg: f64,
    /// Whether `added_mass_kg` is the standard's (else the estimate of the module's notes).
    pub mass_published: bool,
}

impl Connection {
    /// No connection of its own.
    pub const INTEGRAL: Connection = Connection {
        name: "integral",
        outer_diameter_m: 0.0,
        bore_m: 0.0,
        length_m: 0.0,
        pin_length_m: 0.0,
        added_mass_kg: 0.0,
        mass_published: true,
    };

    /// Whether it has a length and mass of its own.
    pub fn is_integral(&self) -> bool {
        self.length_m == 0.0
    }
}

/// One catalogue row: a size, product and weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PipeSize {
    /// Trade size, inches, as written ("2-7/8").
    pub size: &'static str,
    /// What it is.
    pub product: Product,
    /// Outer diameter, m.
    pub outer_diameter_m: f64,
    /// Wall thickness, m.
    pub wall_m: f64,
    /// Nominal weight (threaded and coupled; the label weight of drill pipe), lb/ft.
    pub nominal_weight_lb_ft: f64,
    /// Nominal linear mass, kg/m.
    pub mass_per_length_kg_m: f64,
    /// Plain-end weight, lb/ft.
    pub plain_end_weight_lb_ft: f64,
    /// The joint's connection.
    pub connection: Connection,
    /// Whether a size (and product) given without a weight picks this row.
    pub default: bool,
}

impl PipeSize {
    /// Plain-end linear mass, kg/m.
    pub fn plain_end_kg_m(&self) -> f64 {
        self.plain_end_weight_lb_ft * LB_FT_KG_M
    }

    /// Inner diameter, m.
    pub fn inner_diameter_m(&self) -> f64 {
        self.outer_diameter_m - 2.0 * self.wall_m
    }

    /// What the row is, as reports write it ("9-5/8 casing 47.00 lb/ft").
    pub fn label(&self) -> String {
        format!("{} {} {:.2} lb/ft", self.size, self.product.name(), self.nominal_weight_lb_ft)
    }

    /// The yield strength its size fixes without a grade: API 7-1's drill collar steel, 758 MPa
    /// (110 ksi) up to 6-7/8 in, 689 MPa (100 ksi) above; `None` for the other products.
    pub fn yield_strength_pa(&self) -> Option<f64> {
        (self.product == Product::DrillCollar)
            .then(|| if self.outer_diameter_m <= 6.875 * INCH_M + 1e-9 { 758e6 } else { 689e6 })
    }

    /// Mass of one joint of `length_m`: the plain pipe and its connection, kg.
    pub fn joint_mass_kg(&self, length_m: f64) -> f64 {
        self.plain_end_kg_m() * length_m + self.connection.added_mass_kg
    }
}

/// Mass of a steel ring, kg (diameters and length in inches).
const fn ring_kg(outer_in: f64, inner_in: f64, length_in: f64) -> f64 {
    std::f64::consts::FRAC_PI_4
        * (outer_in * outer_in - inner_in * inner_in)
        * INCH_M
        * INCH_M
        * length_in
        * INCH_M
        * STEEL_DENSITY_KG_M3
}

/// A coupling whose mass the standard gives (lb).
const fn coupling(
    name: &'static str,
    od_in: f64,
    pipe_od_in: f64,
    wall_in: f64,
    length_in: f64,
    lb: f64,
) -> Connection {
    Connection {
        name,
        outer_diameter_m: od_in * INCH_M,
        bore_m: (pipe_od_in - 2.0 * wall_in) * INCH_M,
        length_m: length_in * INCH_M,
        pin_length_m: 0.0,
        added_mass_kg: lb * 0.453_592_37,
        mass_published: true,
    }
}

/// A coupling whose mass is estimated from its ring on the thread's diameter `thread_in`.
const fn coupling_estimated(
    name: &'static str,
    od_in: f64,
    thread_in: f64,
    pipe_od_in: f64,
    wall_in: f64,
    length_in: f64,
) -> Connection {
    Connection {
        name,
        outer_diameter_m: od_in * INCH_M,
        bore_m: (pipe_od_in - 2.0 * wall_in) * INCH_M,
        length_m: length_in * INCH_M,
        pin_length_m: 0.0,
        added_mass_kg: COUPLING_RING_FACTOR * ring_kg(od_in, thread_in, length_in),
        mass_published: false,
    }
}

/// A tool joint: its outside diameter and bore over its pin and box tong lengths, less the body.
const fn tool_joint(
    name: &'static str,
    (od_in, bore_in): (f64, f64),
    (pin_in, box_in): (f64, f64),
    (pipe_od_in, wall_in): (f64, f64),
) -> Connection {
    let length_in = pin_in + box_in;
    let body = ring_kg(pipe_od_in, pipe_od_in - 2.0 * wall_in, length_in);
    Connection {
        name,
        outer_diameter_m: od_in * INCH_M,
        bore_m: bore_in * INCH_M,
        length_m: length_in * INCH_M,
        pin_length_m: pin_in * INCH_M,
        added_mass_kg: ring_kg(od_in, bore_in, length_in) - body,
        mass_published: false,
    }
}

/// The outside diameter as the SI tables print it, to 0.1 mm (9-5/8 in: 244.5 mm), m.
const fn si_outer_diameter_m(od_in: f64) -> f64 {
    let tenths_mm = (od_in * 254.0 + 0.5) as i64;
    tenths_mm as f64 / 10_000.0
}

/// A row from the standard's inch columns.
#[allow(clippy::too_many_arguments)]
const fn row(
    size: &'static str,
    product: Product,
    od_in: f64,
    (lb_ft, kg_m): (f64, f64),
    wall_in: f64,
    plain_end_lb_ft: f64,
    connection: Connection,
    default: bool,
) -> PipeSize {
    PipeSize {
        size,
        product,
        outer_diameter_m: si_outer_diameter_m(od_in),
        wall_m: wall_in * INCH_M,
        nominal_weight_lb_ft: lb_ft,
        mass_per_length_kg_m: kg_m,
        plain_end_weight_lb_ft: plain_end_lb_ft,
        connection,
        default,
    }
}

use Product::{Casing, DrillCollar, DrillPipe, HeavyWeightDrillPipe, Tubing};

// Tubing couplings (non-upset on the pipe's diameter, external-upset on the upset's).
const fn nu(od_in: f64, pipe_od_in: f64, wall_in: f64, length_in: f64) -> Connection {
    coupling_estimated("NU coupling", od_in, pipe_od_in, pipe_od_in, wall_in, length_in)
}
const fn eue(od_in: f64, upset_od_in: f64, pipe_od_in: f64, wall_in: f64, length_in: f64) -> Connection {
    coupling_estimated("EUE coupling", od_in, upset_od_in, pipe_od_in, wall_in, length_in)
}

/// A tubing row: size, outside diameter, (lb/ft, kg/m), wall, plain-end lb/ft, coupling.
const fn tubing(
    size: &'static str,
    od_in: f64,
    weight: (f64, f64),
    wall_in: f64,
    plain_end_lb_ft: f64,
    c: Connection,
    default: bool,
) -> PipeSize {
    row(size, Tubing, od_in, weight, wall_in, plain_end_lb_ft, c, default)
}

/// A casing row with its round-thread coupling (outside diameter, length in, mass lb).
const fn casing(
    size: &'static str,
    od_in: f64,
    weight: (f64, f64),
    wall_in: f64,
    plain_end_lb_ft: f64,
    (coupling_od_in, length_in, mass_lb): (f64, f64, f64),
    default: bool,
) -> PipeSize {
    let c = if mass_lb > 0.0 {
        coupling(
            if length_in >= 8.75 { "LTC coupling" } else { "STC coupling" },
            coupling_od_in,
            od_in,
            wall_in,
            length_in,
            mass_lb,
        )
    } else {
        coupling_estimated("STC coupling", coupling_od_in, od_in, od_in, wall_in, length_in)
    };
    row(size, Casing, od_in, weight, wall_in, plain_end_lb_ft, c, default)
}

/// A drill pipe row with its tool joint (name, outside diameter and bore, pin and box lengths).
const fn drill_pipe(
    size: &'static str,
    od_in: f64,
    weight: (f64, f64),
    wall_in: f64,
    plain_end_lb_ft: f64,
    (name, od_bore, tongs): (&'static str, (f64, f64), (f64, f64)),
    default: bool,
) -> PipeSize {
    let c = tool_joint(name, od_bore, tongs, (od_in, wall_in));
    row(size, DrillPipe, od_in, weight, wall_in, plain_end_lb_ft, c, default)
}

/// A heavy-weight drill pipe row: its tool joints and centre pad add what its nominal weight
/// adds to the plain tube over a 30 ft joint, at its tool joints (24 in pin, 30 in box).
const fn heavy_weight(
    size: &'static str,
    od_in: f64,
    bore_in: f64,
    weight: (f64, f64),
    plain_end_lb_ft: f64,
    (name, tool_joint_od_in): (&'static str, f64),
) -> PipeSize {
    let c = Connection {
        name,
        outer_diameter_m: tool_joint_od_in * INCH_M,
        bore_m: bore_in * INCH_M,
        length_m: 54.0 * INCH_M,
        pin_length_m: 24.0 * INCH_M,
        added_mass_kg: (weight.0 - plain_end_lb_ft) * 30.0 * 0.453_592_37,
        mass_published: false,
    };
    row(size, HeavyWeightDrillPipe, od_in, weight, 0.5 * (od_in - bore_in), plain_end_lb_ft, c, true)
}

/// A drill collar row: outside diameter and bore (in), weight (lb/ft, RP 7G's rounding; kg/m)
/// and plain-end weight.
const fn collar(
    size: &'static str,
    od_in: f64,
    bore_in: f64,
    weight: (f64, f64),
    plain_end_lb_ft: f64,
    default: bool,
) -> PipeSize {
    row(size, DrillCollar, od_in, weight, 0.5 * (od_in - bore_in), plain_end_lb_ft, Connection::INTEGRAL, default)
}

/// Typical tool joint tong lengths (pin, box), in.
const TONGS_SMALL: (f64, f64) = (7.0, 10.0);
const TONGS_MEDIUM: (f64, f64) = (9.0, 12.0);
const TONGS_LARGE: (f64, f64) = (10.0, 13.0);

/// The catalogue.
pub const PIPE_CATALOGUE: &[PipeSize] = &[
    // API 5CT Table C.2 / E.2: tubing.
    tubing("2-3/8", 2.375, (4.00, 5.95), 0.167, 3.94, nu(2.875, 2.375, 0.167, 4.25), false),
    tubing("2-3/8", 2.375, (4.60, 6.84), 0.190, 4.44, nu(2.875, 2.375, 0.190, 4.25), false),
    tubing("2-3/8", 2.375, (4.70, 7.00), 0.190, 4.44, eue(3.063, 2.594, 2.375, 0.190, 4.875), true),
    tubing("2-3/8", 2.375, (5.80, 8.63), 0.254, 5.76, nu(2.875, 2.375, 0.254, 4.25), false),
    tubing("2-3/8", 2.375, (5.95, 8.85), 0.254, 5.76, eue(3.063, 2.594, 2.375, 0.254, 4.875), false),
    tubing("2-7/8", 2.875, (6.40, 9.52), 0.217, 6.17, nu(3.500, 2.875, 0.217, 5.125), false),
    tubing("2-7/8", 2.875, (6.50, 9.67), 0.217, 6.17, eue(3.668, 3.094, 2.875, 0.217, 5.25), true),
    tubing("2-7/8", 2.875, (7.80, 11.61), 0.276, 7.67, nu(3.500, 2.875, 0.276, 5.125), false),
    tubing("2-7/8", 2.875, (7.90, 11.75), 0.276, 7.67, eue(3.668, 3.094, 2.875, 0.276, 5.25), false),
    tubing("2-7/8", 2.875, (8.60, 12.80), 0.308, 8.45, nu(3.500, 2.875, 0.308, 5.125), false),
    tubing("2-7/8", 2.875, (8.70, 12.94), 0.308, 8.45, eue(3.668, 3.094, 2.875, 0.308, 5.25), false),
    tubing("3-1/2", 3.500, (7.70, 11.46), 0.216, 7.58, nu(4.250, 3.500, 0.216, 5.625), false),
    tubing("3-1/2", 3.500, (9.20, 13.69), 0.254, 8.81, nu(4.250, 3.500, 0.254, 5.625), false),
    tubing("3-1/2", 3.500, (9.30, 13.84), 0.254, 8.81, eue(4.500, 3.750, 3.500, 0.254, 5.75), true),
    tubing("3-1/2", 3.500, (10.20, 15.18), 0.289, 9.92, nu(4.250, 3.500, 0.289, 5.625), false),
    tubing("3-1/2", 3.500, (12.70, 18.90), 0.375, 12.53, nu(4.250, 3.500, 0.375, 5.625), false),
    tubing("3-1/2", 3.500, (12.95, 19.27), 0.375, 12.53, eue(4.500, 3.750, 3.500, 0.375, 5.75), false),
    tubing("4", 4.000, (9.50, 14.14), 0.226, 9.12, nu(4.750, 4.000, 0.226, 5.75), false),
    tubing("4", 4.000, (11.00, 16.37), 0.262, 10.47, eue(5.000, 4.250, 4.000, 0.262, 6.0), true),
    tubing("4-1/2", 4.500, (12.60, 18.75), 0.271, 12.25, nu(5.200, 4.500, 0.271, 6.125), false),
    tubing("4-1/2", 4.500, (12.75, 18.97), 0.271, 12.25, eue(5.563, 4.750, 4.500, 0.271, 6.25), true),
    // API 5CT Table C.1 / E.1: casing; couplings: 5CT Table E.32 (16, 18-5/8, 20 in estimated).
    casing("4-1/2", 4.500, (9.50, 14.14), 0.205, 9.41, (5.000, 7.0, 9.16), false),
    casing("4-1/2", 4.500, (10.50, 15.63), 0.224, 10.24, (5.000, 7.0, 9.16), false),
    casing("4-1/2", 4.500, (11.60, 17.26), 0.250, 11.36, (5.000, 7.0, 9.16), true),
    casing("4-1/2", 4.500, (13.50, 20.09), 0.290, 13.05, (5.000, 7.0, 9.16), false),
    casing("4-1/2", 4.500, (15.10, 22.47), 0.337, 15.00, (5.000, 7.0, 9.16), false),
    casing("5", 5.000, (11.50, 17.11), 0.220, 11.24, (5.563, 7.75, 12.68), false),
    casing("5", 5.000, (13.00, 19.35), 0.253, 12.84, (5.563, 7.75, 12.68), false),
    casing("5", 5.000, (15.00, 22.32), 0.296, 14.88, (5.563, 7.75, 12.68), false),
    casing("5", 5.000, (18.00, 26.79), 0.362, 17.95, (5.563, 7.75, 12.68), true),
    casing("5", 5.000, (21.40, 31.85), 0.437, 21.32, (5.563, 7.75, 12.68), false),
    casing("5", 5.000, (23.20, 34.53), 0.478, 23.11, (5.563, 7.75, 12.68), false),
    casing("5", 5.000, (24.10, 35.86), 0.500, 24.05, (5.563, 7.75, 12.68), false),
    casing("5-1/2", 5.500, (14.00, 20.83), 0.244, 13.71, (6.050, 8.0, 14.15), false),
    casing("5-1/2", 5.500, (15.50, 23.07), 0.275, 15.36, (6.050, 8.0, 14.15), false),
    casing("5-1/2", 5.500, (17.00, 25.30), 0.304, 16.89, (6.050, 8.0, 14.15), true),
    casing("5-1/2", 5.500, (20.00, 29.76), 0.361, 19.83, (6.050, 8.0, 14.15), false),
    casing("5-1/2", 5.500, (23.00, 34.23), 0.415, 22.56, (6.050, 8.0, 14.15), false),
    casing("6-5/8", 6.625, (20.00, 29.76), 0.288, 19.51, (7.390, 8.75, 25.01), false),
    casing("6-5/8", 6.625, (24.00, 35.72), 0.352, 23.60, (7.390, 8.75, 25.01), true),
    casing("6-5/8", 6.625, (28.00, 41.67), 0.417, 27.67, (7.390, 8.75, 25.01), false),
    casing("6-5/8", 6.625, (32.00, 47.62), 0.475, 31.23, (7.390, 8.75, 25.01), false),
    casing("7", 7.000, (17.00, 25.30), 0.231, 16.72, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (20.00, 29.76), 0.272, 19.56, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (23.00, 34.23), 0.317, 22.65, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (26.00, 38.69), 0.362, 25.69, (7.656, 9.0, 23.87), true),
    casing("7", 7.000, (29.00, 43.16), 0.408, 28.75, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (32.00, 47.62), 0.453, 31.70, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (35.00, 52.09), 0.498, 34.61, (7.656, 9.0, 23.87), false),
    casing("7", 7.000, (38.00, 56.55), 0.540, 37.29, (7.656, 9.0, 23.87), false),
    casing("7-5/8", 7.625, (24.00, 35.72), 0.300, 23.49, (8.500, 9.25, 34.46), false),
    casing("7-5/8", 7.625, (26.40, 39.29), 0.328, 25.59, (8.500, 9.25, 34.46), false),
    casing("7-5/8", 7.625, (29.70, 44.20), 0.375, 29.06, (8.500, 9.25, 34.46), true),
    casing("7-5/8", 7.625, (33.70, 50.15), 0.430, 33.07, (8.500, 9.25, 34.46), false),
    casing("7-5/8", 7.625, (39.00, 58.04), 0.500, 38.08, (8.500, 9.25, 34.46), false),
    casing("8-5/8", 8.625, (24.00, 35.72), 0.264, 23.60, (9.625, 10.0, 47.77), false),
    casing("8-5/8", 8.625, (28.00, 41.67), 0.304, 27.04, (9.625, 10.0, 47.77), false),
    casing("8-5/8", 8.625, (32.00, 47.62), 0.352, 31.13, (9.625, 10.0, 47.77), true),
    casing("8-5/8", 8.625, (36.00, 53.57), 0.400, 35.17, (9.625, 10.0, 47.77), false),
    casing("8-5/8", 8.625, (40.00, 59.53), 0.450, 39.33, (9.625, 10.0, 47.77), false),
    casing("8-5/8", 8.625, (44.00, 65.48), 0.500, 43.43, (9.625, 10.0, 47.77), false),
    casing("8-5/8", 8.625, (49.00, 72.92), 0.557, 48.04, (9.625, 10.0, 47.77), false),
    casing("9-5/8", 9.625, (32.30, 48.07), 0.312, 31.06, (10.625, 10.5, 56.11), false),
    casing("9-5/8", 9.625, (36.00, 53.57), 0.352, 34.89, (10.625, 10.5, 56.11), false),
    casing("9-5/8", 9.625, (40.00, 59.53), 0.395, 38.97, (10.625, 10.5, 56.11), false),
    casing("9-5/8", 9.625, (43.50, 64.74), 0.435, 42.73, (10.625, 10.5, 56.11), false),
    casing("9-5/8", 9.625, (47.00, 69.94), 0.472, 46.18, (10.625, 10.5, 56.11), true),
    casing("9-5/8", 9.625, (53.50, 79.62), 0.545, 52.90, (10.625, 10.5, 56.11), false),
    casing("10-3/4", 10.750, (32.75, 48.74), 0.279, 31.23, (11.750, 8.0, 45.81), false),
    casing("10-3/4", 10.750, (40.50, 60.27), 0.350, 38.91, (11.750, 8.0, 45.81), false),
    casing("10-3/4", 10.750, (45.50, 67.71), 0.400, 44.26, (11.750, 8.0, 45.81), true),
    casing("10-3/4", 10.750, (51.00, 75.90), 0.450, 49.55, (11.750, 8.0, 45.81), false),
    casing("10-3/4", 10.750, (55.50, 82.59), 0.495, 54.26, (11.750, 8.0, 45.81), false),
    casing("10-3/4", 10.750, (60.70, 90.33), 0.545, 59.45, (11.750, 8.0, 45.81), false),
    casing("10-3/4", 10.750, (65.70, 97.77), 0.595, 64.59, (11.750, 8.0, 45.81), false),
    casing("11-3/4", 11.750, (42.00, 62.50), 0.333, 40.64, (12.750, 8.0, 49.91), false),
    casing("11-3/4", 11.750, (47.00, 69.94), 0.375, 45.60, (12.750, 8.0, 49.91), false),
    casing("11-3/4", 11.750, (54.00, 80.36), 0.435, 52.62, (12.750, 8.0, 49.91), true),
    casing("11-3/4", 11.750, (60.00, 89.29), 0.489, 58.87, (12.750, 8.0, 49.91), false),
    casing("13-3/8", 13.375, (48.00, 71.43), 0.330, 46.02, (14.375, 8.0, 56.57), false),
    casing("13-3/8", 13.375, (54.50, 81.10), 0.380, 52.79, (14.375, 8.0, 56.57), false),
    casing("13-3/8", 13.375, (61.00, 90.78), 0.430, 59.50, (14.375, 8.0, 56.57), false),
    casing("13-3/8", 13.375, (68.00, 101.20), 0.480, 66.17, (14.375, 8.0, 56.57), true),
    casing("13-3/8", 13.375, (72.00, 107.15), 0.514, 70.67, (14.375, 8.0, 56.57), false),
    casing("16", 16.000, (65.00, 96.73), 0.375, 62.64, (17.000, 9.0, 0.0), false),
    casing("16", 16.000, (75.00, 111.61), 0.438, 72.86, (17.000, 9.0, 0.0), false),
    casing("16", 16.000, (84.00, 125.01), 0.495, 82.05, (17.000, 9.0, 0.0), true),
    casing("18-5/8", 18.625, (87.50, 130.21), 0.435, 84.59, (20.000, 9.0, 0.0), true),
    casing("20", 20.000, (94.00, 139.89), 0.438, 91.59, (21.000, 9.0, 0.0), true),
    casing("20", 20.000, (106.50, 158.49), 0.500, 104.23, (21.000, 9.0, 0.0), false),
    casing("20", 20.000, (133.00, 197.93), 0.635, 131.45, (21.000, 9.0, 0.0), false),
    // API 5DP: drill pipe (label weight, wall), with the tool joint each size usually carries.
    drill_pipe("2-3/8", 2.375, (4.85, 7.22), 0.190, 4.43, ("NC26 tool joint", (3.375, 1.75), TONGS_SMALL), false),
    drill_pipe("2-3/8", 2.375, (6.65, 9.90), 0.280, 6.26, ("NC26 tool joint", (3.375, 1.75), TONGS_SMALL), true),
    drill_pipe("2-7/8", 2.875, (6.85, 10.19), 0.217, 6.16, ("NC31 tool joint", (4.125, 2.125), TONGS_SMALL), false),
    drill_pipe("2-7/8", 2.875, (10.40, 15.48), 0.362, 9.72, ("NC31 tool joint", (4.125, 2.125), TONGS_SMALL), true),
    drill_pipe("3-1/2", 3.500, (9.50, 14.14), 0.254, 8.81, ("NC38 tool joint", (4.75, 2.6875), TONGS_SMALL), false),
    drill_pipe("3-1/2", 3.500, (13.30, 19.79), 0.368, 12.31, ("NC38 tool joint", (4.75, 2.6875), TONGS_SMALL), true),
    drill_pipe("3-1/2", 3.500, (15.50, 23.07), 0.449, 14.63, ("NC38 tool joint", (5.0, 2.5625), TONGS_SMALL), false),
    drill_pipe("4", 4.000, (14.00, 20.83), 0.330, 12.93, ("NC40 tool joint", (5.25, 2.8125), TONGS_SMALL), true),
    drill_pipe("4-1/2", 4.500, (16.60, 24.70), 0.337, 14.98, ("NC46 tool joint", (6.25, 3.25), TONGS_MEDIUM), true),
    drill_pipe("4-1/2", 4.500, (20.00, 29.76), 0.430, 18.69, ("NC46 tool joint", (6.25, 3.0), TONGS_MEDIUM), false),
    drill_pipe("5", 5.000, (19.50, 29.02), 0.362, 17.93, ("NC50 tool joint", (6.625, 3.75), TONGS_MEDIUM), true),
    drill_pipe("5", 5.000, (25.60, 38.10), 0.500, 24.03, ("NC50 tool joint", (6.625, 3.5), TONGS_MEDIUM), false),
    drill_pipe("5-1/2", 5.500, (21.90, 32.59), 0.361, 19.81, ("5-1/2 FH tool joint", (7.0, 4.0), TONGS_LARGE), true),
    drill_pipe("5-1/2", 5.500, (24.70, 36.76), 0.415, 22.54, ("5-1/2 FH tool joint", (7.0, 4.0), TONGS_LARGE), false),
    drill_pipe("6-5/8", 6.625, (25.20, 37.50), 0.330, 22.19, ("6-5/8 FH tool joint", (8.0, 5.0), TONGS_LARGE), true),
    drill_pipe("6-5/8", 6.625, (27.70, 41.22), 0.362, 24.21, ("6-5/8 FH tool joint", (8.0, 5.0), TONGS_LARGE), false),
    // Heavy-weight drill pipe: outside diameter, bore, nominal weight (tool joints and centre
    // pad included), tool joint.
    heavy_weight("3-1/2", 3.500, 2.0625, (25.30, 37.65), 21.35, ("NC38 tool joint", 4.75)),
    heavy_weight("4", 4.000, 2.5625, (29.70, 44.20), 25.19, ("NC40 tool joint", 5.25)),
    heavy_weight("4-1/2", 4.500, 2.75, (41.00, 61.01), 33.88, ("NC46 tool joint", 6.25)),
    heavy_weight("5", 5.000, 3.0, (49.30, 73.37), 42.72, ("NC50 tool joint", 6.625)),
    heavy_weight("5-1/2", 5.500, 3.375, (57.00, 84.83), 50.35, ("5-1/2 FH tool joint", 7.0)),
    heavy_weight("6-5/8", 6.625, 4.5, (70.50, 104.92), 63.12, ("6-5/8 FH tool joint", 8.0)),
    // API 7-1 drill collars (NCxx-yy), weight 2.67 (D² − d²) lb/ft (RP 7G).
    collar("3-1/8", 3.125, 1.25, (22.0, 32.74), 21.90, true),
    collar("3-1/2", 3.5, 1.5, (27.0, 40.18), 26.70, true),
    collar("4-1/8", 4.125, 2.0, (35.0, 52.09), 34.75, true),
    collar("4-3/4", 4.75, 2.0, (50.0, 74.41), 49.56, true),
    collar("5", 5.0, 2.25, (53.0, 78.87), 53.23, true),
    collar("6", 6.0, 2.25, (83.0, 123.52), 82.60, true),
    collar("6-1/4", 6.25, 2.25, (91.0, 135.42), 90.78, true),
    collar("6-1/4", 6.25, 2.8125, (83.0, 123.52), 83.18, false),
    collar("6-1/2", 6.5, 2.8125, (92.0, 136.91), 91.69, true),
    collar("6-3/4", 6.75, 2.25, (108.0, 160.72), 108.13, true),
    collar("7", 7.0, 2.8125, (110.0, 163.70), 109.71, true),
    collar("7-1/4", 7.25, 2.8125, (119.0, 177.09), 119.22, true),
    collar("7-3/4", 7.75, 2.8125, (139.0, 206.86), 139.25, true),
    collar("8", 8.0, 2.8125, (150.0, 223.22), 149.76, true),
    collar("9", 9.0, 2.8125, (195.0, 290.19), 195.15, true),
    collar("9-3/4", 9.75, 3.0, (230.0, 342.28), 229.79, true),
    collar("10", 10.0, 3.0, (243.0, 361.62), 242.97, true),
    collar("11", 11.0, 3.0, (299.0, 444.96), 299.04, true),
];
