//! Planar Euler–Bernoulli finite-element model of the arm, clamped at the hub.
//!
//! The arm lies along the body x axis from the hub (x = 0) to the tip (x = L). Each node past the
//! hub carries three DOFs `[u, v, φ]`: axial stretch (m), transverse deflection in the lift plane
//! (m) and section rotation (rad). The hub node is clamped and carries none, so global DOF
//! `3(i−1) + k` is component `k` of node `i`.
//!
//! Besides the mass and stiffness matrices, [`BeamModel`] holds every integral the
//! floating-frame equations of [`crate::arm`] need (coupling vector, centrifugal and gravity
//! geometric stiffness, gyroscopic matrix, load vectors); `docs/model.md` derives them.

mod element;
mod member;
mod modes;
pub mod section;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use element::{ELEMENT_DOFS, GAUSS_4, ShapeRows, shape_rows};
pub use member::{MemberModel, MemberPiece, MemberSpec};
pub use modes::ModalBasis;
pub(crate) use modes::solve_generalized;
pub use section::{Material, SectionProperties, SectionShape};
use section::{non_negative, positive};

/// DOFs per node: axial stretch, transverse deflection, rotation.
pub const NODE_DOFS: usize = 3;

/// Errors in a beam description or in a request made of a beam model.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BeamError {
    /// A parameter outside its allowed range.
    #[error("beam parameter `{name}` = {value} is invalid: allowed {allowed}")]
    InvalidParameter { name: String, value: f64, allowed: String },
    /// A matrix that should be positive definite is not (e.g. a mechanism or a zero mass).
    #[error("the {matrix} matrix is not positive definite: {why}")]
    NotPositiveDefinite { matrix: &'static str, why: String },
}

impl BeamError {
    pub(crate) fn invalid(name: &str, value: f64, allowed: impl Into<String>) -> Self {
        BeamError::InvalidParameter { name: name.to_string(), value, allowed: allowed.into() }
    }
}

/// A length of uniform section, listed from the hub outwards.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Length of the segment, m.
    pub length_m: f64,
    /// Axial rigidity EA, N.
    pub axial_rigidity_n: f64,
    /// Bending rigidity EI, N·m².
    pub bending_rigidity_n_m2: f64,
    /// Mass per length ρA, kg/m.
    pub mass_per_length_kg_m: f64,
}

impl Segment {
    /// A segment of `length_m` with the given section shape and material.
    pub fn from_shape(length_m: f64, shape: &SectionShape, material: &Material) -> Result<Self, BeamError> {
        material.validate()?;
        let p = shape.properties()?;
        Ok(Segment {
            length_m,
            axial_rigidity_n: material.youngs_modulus_pa * p.area_m2,
            bending_rigidity_n_m2: material.youngs_modulus_pa * p.second_moment_m4,
            mass_per_length_kg_m: p.mass_per_length_kg_m(material),
        })
    }

    pub(crate) fn validate(&self) -> Result<(), BeamError> {
        positive("length_m", self.length_m)?;
        positive("axial_rigidity_n", self.axial_rigidity_n)?;
        positive("bending_rigidity_n_m2", self.bending_rigidity_n_m2)?;
        positive("mass_per_length_kg_m", self.mass_per_length_kg_m)
    }
}

/// A rigid body lumped on the arm's axis: the seed's hand m_n, gripper m_k, string m_p, tip m_l.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConcentratedMass {
    /// Name, for reports.
    pub name: String,
    /// Distance from the hub along the undeformed arm, m (0 ≤ x ≤ L).
    pub position_m: f64,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Rotary inertia about its own centre, normal to the lift plane, kg·m².
    #[serde(default)]
    pub rotary_inertia_kg_m2: f64,
}

/// What the arm is made of, before meshing.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamSpec {
    /// Segments from the hub outwards; their lengths sum to the arm length.
    pub segments: Vec<Segment>,
    /// Concentrated masses.
    pub masses: Vec<ConcentratedMass>,
    /// Target element count; each segment and each gap between masses gets at least one.
    pub elements: usize,
    /// A second beam clamped to the arm (a flexibly modelled pipe string), if any.
    pub member: Option<MemberSpec>,
}

impl BeamSpec {
    /// A uniform arm of one segment.
    pub fn uniform(segment: Segment, elements: usize) -> Self {
        BeamSpec { segments: vec![segment], masses: Vec::new(), elements, member: None }
    }

    /// Adds a member clamped to the arm (builder style).
    pub fn with_member(mut self, member: MemberSpec) -> Self {
        self.member = Some(member);
        self
    }

    /// Adds a concentrated mass (builder style).
    pub fn with_mass(mut self, name: &str, position_m: f64, mass_kg: f64, rotary_inertia_kg_m2: f64) -> Self {
        self.masses.push(ConcentratedMass { name: name.into(), position_m, mass_kg, rotary_inertia_kg_m2 });
        self
    }

    /// Total length L, m.
    pub fn length_m(&self) -> f64 {
        self.segments.iter().map(|s| s.length_m).sum()
    }

    /// Checks every value, naming the offending parameter.
    pub fn validate(&self) -> Result<(), BeamError> {
        if self.segments.is_empty() {
            return Err(BeamError::invalid("segments", 0.0, "at least one segment"));
        }
        if self.elements == 0 || self.elements > 2000 {
            return Err(BeamError::invalid("elements", self.elements as f64, "1 ..= 2000"));
        }
        self.segments.iter().try_for_each(Segment::validate)?;
        let length = self.length_m();
        for m in &self.masses {
            let inside = m.position_m.is_finite() && (0.0..=length).contains(&m.position_m);
            if !inside {
                let name = format!("masses.{}.position_m", m.name);
                return Err(BeamError::invalid(&name, m.position_m, format!("0 ..= {length} (the arm length)")));
            }
            non_negative(&format!("masses.{}.mass_kg", m.name), m.mass_kg)?;
            non_negative(&format!("masses.{}.rotary_inertia_kg_m2", m.name), m.rotary_inertia_kg_m2)?;
        }
        if let Some(member) = &self.member {
            member.validate(length)?;
        }
        Ok(())
    }

    /// Node positions: every segment end and mass position is a node; elements are spread over
    /// the gaps in proportion to their length.
    fn node_positions(&self) -> Vec<f64> {
        let length = self.length_m();
        let mut breaks = vec![0.0];
        let mut x = 0.0;
        for s in &self.segments {
            x += s.length_m;
            breaks.push(x);
        }
        breaks.extend(self.masses.iter().map(|m| m.position_m));
        breaks.extend(self.member.iter().flat_map(|m| m.clamps_m.iter().copied()));
        spread_nodes(breaks, self.elements, length)
    }
}

/// Nodes of a beam over `breaks` (its ends and every point that must be a node, in any order):
/// about `elements` elements spread over the gaps in proportion to their length, at least one a
/// gap; the last node is the last break exactly.
fn spread_nodes(mut breaks: Vec<f64>, elements: usize, length_m: f64) -> Vec<f64> {
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * length_m);
    let mut nodes = vec![breaks[0]];
    for gap in breaks.windows(2) {
        let count = ((elements as f64 * (gap[1] - gap[0]) / length_m).round() as usize).max(1);
        nodes.extend((1..=count).map(|k| gap[0] + (gap[1] - gap[0]) * k as f64 / count as f64));
    }
    *nodes.last_mut().expect("at least one gap") = breaks[breaks.len() - 1];
    nodes
}

/// Shape rows `r` of one element mapped onto `dofs` global DOFs through its element-to-global
/// map: (u, v, φ, curvature) rows.
fn rows_over(map: &[Option<usize>; ELEMENT_DOFS], r: &ShapeRows, dofs: usize) -> [DVector<f64>; 4] {
    let mut rows = [0; 4].map(|_| DVector::zeros(dofs));
    for (i, g) in map.iter().enumerate() {
        if let Some(g) = *g {
            rows[0][g] = r.u[i];
            rows[1][g] = r.v[i];
            rows[2][g] = r.dv[i];
            rows[3][g] = r.ddv[i];
        }
    }
    rows
}

/// One finite element: position and uniform properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Hub-side node x, m.
    pub x0_m: f64,
    /// Length, m.
    pub length_m: f64,
    /// EA, N.
    pub axial_rigidity_n: f64,
    /// EI, N·m².
    pub bending_rigidity_n_m2: f64,
    /// ρA, kg/m.
    pub mass_per_length_kg_m: f64,
}

/// Global DOF indices of an element's six local DOFs (`None` where clamped).
fn element_dofs(element_index: usize) -> [Option<usize>; ELEMENT_DOFS] {
    let node_dof = |node: usize, k: usize| (node > 0).then(|| NODE_DOFS * (node - 1) + k);
    let (a, b) = (element_index, element_index + 1);
    [node_dof(a, 0), node_dof(a, 1), node_dof(a, 2), node_dof(b, 0), node_dof(b, 1), node_dof(b, 2)]
}

/// The assembled clamped beam and every integral the floating-frame model uses.
///
/// Notation of `docs/model.md`: μ = ρA, N_u / N_v the axial / transverse shape rows.
#[derive(Debug, Clone)]
pub struct BeamModel {
    /// The description this model was built from.
    pub spec: BeamSpec,
    /// Node positions along the arm, m (node 0 is the hub).
    pub nodes_x_m: Vec<f64>,
    /// Elements, hub outwards.
    pub elements: Vec<Element>,
    /// Mass matrix M (translational + rotary inertia of the masses), kg / kg·m / kg·m².
    pub mass: DMatrix<f64>,
    /// Translational mass M_tr (M without the rotary inertias).
    pub translational_mass: DMatrix<f64>,
    /// Elastic stiffness K.
    pub stiffness: DMatrix<f64>,
    /// Centrifugal geometric stiffness K_c = ∫ P_c v'ᵀv' with P_c(x) = first moment of the mass
    /// outboard of x (kg·m); scaled by θ̇² it is the stiffening of a spinning arm.
    pub centrifugal_stiffness: DMatrix<f64>,
    /// Gravity geometric stiffness K_g = ∫ P_g v'ᵀv' with P_g(x) = mass outboard of x (kg).
    pub gravity_stiffness: DMatrix<f64>,
    /// Gyroscopic matrix C = ∫ μ (N_vᵀN_u − N_uᵀN_v) (skew), kg.
    pub gyroscopic: DMatrix<f64>,
    /// Rigid–elastic coupling S = ∫ μ x N_vᵀ + Σ (m x N_v + J N_φ)ᵀ, kg·m.
    pub coupling: DVector<f64>,
    /// Axial first-moment vector a = ∫ μ x N_uᵀ, kg·m.
    pub axial_moment: DVector<f64>,
    /// Axial mass vector b_u = ∫ μ N_uᵀ, kg.
    pub axial_mass: DVector<f64>,
    /// Transverse mass vector b_v = ∫ μ N_vᵀ, kg.
    pub transverse_mass: DVector<f64>,
    /// Total mass of beam and concentrated masses, kg.
    pub total_mass_kg: f64,
    /// First moment of mass about the hub, kg·m.
    pub first_moment_kg_m: f64,
    /// Moment of inertia of the undeformed arm and its masses about the hub, kg·m².
    pub hub_inertia_kg_m2: f64,
    /// The member clamped to the arm, meshed, if the spec has one.
    pub member: Option<MemberModel>,
    /// The member's static ride on the arm's DOFs, Ψ = −K_ss⁻¹ K_sa (with a member).
    ride: Option<DMatrix<f64>>,
    /// The member's fixed-interface modes over its own DOFs (with a member).
    member_modes: Option<ModalBasis>,
    /// The stiffness's Cholesky factor, once a static displacement has needed it (a run solves
    /// several, and with a flexible string a factorisation of the whole stiffness costs as much
    /// as a thousand steps). The matrices are not changed after [`BeamModel::new`].
    stiffness_factor: std::sync::OnceLock<Option<nalgebra::Cholesky<f64, nalgebra::Dyn>>>,
}

impl BeamModel {
    /// Validates `spec`, meshes it and assembles every matrix.
    pub fn new(spec: BeamSpec) -> Result<Self, BeamError> {
        spec.validate()?;
        let nodes_x_m = spec.node_positions();
        let elements = mesh_elements(&spec, &nodes_x_m);
        let arm_dofs = NODE_DOFS * elements.len();
        let tol = 1e-9 * spec.length_m();
        let member = spec
            .member
            .clone()
            .map(|m| MemberModel::new(m, |x| nodes_x_m.iter().position(|&n| (n - x).abs() <= tol), arm_dofs));
        let n = member.as_ref().map_or(arm_dofs, |m| m.own_dofs.end);
        let mut model = BeamModel {
            spec,
            nodes_x_m,
            elements,
            mass: DMatrix::zeros(n, n),
            translational_mass: DMatrix::zeros(n, n),
            stiffness: DMatrix::zeros(n, n),
            centrifugal_stiffness: DMatrix::zeros(n, n),
            gravity_stiffness: DMatrix::zeros(n, n),
            gyroscopic: DMatrix::zeros(n, n),
            coupling: DVector::zeros(n),
            axial_moment: DVector::zeros(n),
            axial_mass: DVector::zeros(n),
            transverse_mass: DVector::zeros(n),
            total_mass_kg: 0.0,
            first_moment_kg_m: 0.0,
            hub_inertia_kg_m2: 0.0,
            member,
            ride: None,
            member_modes: None,
            stiffness_factor: std::sync::OnceLock::new(),
        };
        model.assemble_elements();
        model.assemble_member();
        model.add_concentrated_masses();
        if let Some(member) = &model.member {
            let own = member.own_dofs.clone();
            model.ride = Some(member::static_ride(&own, arm_dofs, &model.stiffness)?);
            model.member_modes = Some(member::fixed_interface_modes(&own, &model.stiffness, &model.mass)?);
        }
        Ok(model)
    }

    /// Number of free DOFs: 3 per arm node past the hub, and the member's own.
    pub fn dofs(&self) -> usize {
        self.mass.nrows()
    }

    /// Number of the arm's own DOFs (the first ones).
    pub fn arm_dofs(&self) -> usize {
        NODE_DOFS * self.elements.len()
    }

    /// The arm's DOFs with the member riding statically on them: T = [I; Ψ] (every DOF × the
    /// arm's); the identity without a member.
    pub fn arm_ride(&self) -> DMatrix<f64> {
        let (n, a) = (self.dofs(), self.arm_dofs());
        let mut t = DMatrix::zeros(n, a);
        t.view_mut((0, 0), (a, a)).fill_with_identity();
        if let Some(ride) = &self.ride {
            t.view_mut((a, 0), (n - a, a)).copy_from(ride);
        }
        t
    }

    /// Keeps `kept` of the member's fixed-interface modes in the models reduced from this one
    /// (the spec's and the meshed member's descriptions both say so).
    pub fn keep_member_modes(&mut self, kept: Option<usize>) {
        for spec in [self.spec.member.as_mut(), self.member.as_mut().map(|m| &mut m.spec)].into_iter().flatten() {
            spec.kept_modes = kept;
        }
    }

    /// The member's fixed-interface modes (clamped at its hands, over its own DOFs), if any.
    pub fn member_modes(&self) -> Option<&ModalBasis> {
        self.member_modes.as_ref()
    }

    /// The member's first `kept` fixed-interface modes as columns over every DOF (zero on the
    /// arm's); every one when `kept` is `None`. Empty without a member.
    pub fn member_basis(&self, kept: Option<usize>) -> DMatrix<f64> {
        let (Some(member), Some(modes)) = (&self.member, &self.member_modes) else {
            return DMatrix::zeros(self.dofs(), 0);
        };
        let k = kept.unwrap_or(modes.len()).min(modes.len());
        let mut basis = DMatrix::zeros(self.dofs(), k);
        let own = &member.own_dofs;
        basis.view_mut((own.start, 0), (own.len(), k)).copy_from(&modes.shapes.columns(0, k));
        basis
    }

    /// Arm length L, m.
    pub fn length_m(&self) -> f64 {
        *self.nodes_x_m.last().expect("a mesh has nodes")
    }

    fn assemble_elements(&mut self) {
        let clamp_loads = self.spec.member.as_ref().map(|m| m.clamp_loads()).unwrap_or_default();
        let outboard = OutboardLoads::new(self, &clamp_loads);
        for (e, el) in self.elements.clone().iter().enumerate() {
            self.assemble_element(el, element_dofs(e), |x| (outboard.first_moment(e, x), outboard.mass(e, x)));
        }
    }

    fn assemble_member(&mut self) {
        let Some(member) = self.member.clone() else { return };
        for (el, dofs) in member.elements.iter().zip(&member.element_dofs) {
            self.assemble_element(el, *dofs, |x| {
                let (mass, first_moment) = member.spec.axial_load(x);
                (first_moment, mass)
            });
        }
    }

    /// Adds one element's integrals; `axial(x)` gives the axial load at x per unit θ̇² (kg·m)
    /// and per unit g (kg).
    fn assemble_element(
        &mut self,
        el: &Element,
        dofs: [Option<usize>; ELEMENT_DOFS],
        axial: impl Fn(f64) -> (f64, f64),
    ) {
        let mu = el.mass_per_length_kg_m;
        for (xi, w) in GAUSS_4 {
            let r = shape_rows(xi, el.length_m);
            let x = el.x0_m + xi * el.length_m;
            let dx = w * el.length_m;
            let (pc, pg) = axial(x);
            for i in 0..ELEMENT_DOFS {
                let Some(gi) = dofs[i] else { continue };
                self.coupling[gi] += dx * mu * x * r.v[i];
                self.axial_moment[gi] += dx * mu * x * r.u[i];
                self.axial_mass[gi] += dx * mu * r.u[i];
                self.transverse_mass[gi] += dx * mu * r.v[i];
                for (j, gj) in dofs.iter().enumerate() {
                    let Some(gj) = *gj else { continue };
                    let m = mu * (r.u[i] * r.u[j] + r.v[i] * r.v[j]);
                    self.translational_mass[(gi, gj)] += dx * m;
                    self.stiffness[(gi, gj)] +=
                        dx * (el.axial_rigidity_n * r.du[i] * r.du[j] + el.bending_rigidity_n_m2 * r.ddv[i] * r.ddv[j]);
                    self.centrifugal_stiffness[(gi, gj)] += dx * pc * r.dv[i] * r.dv[j];
                    self.gravity_stiffness[(gi, gj)] += dx * pg * r.dv[i] * r.dv[j];
                    self.gyroscopic[(gi, gj)] += dx * mu * (r.v[i] * r.u[j] - r.u[i] * r.v[j]);
                }
            }
        }
        let (x0, x1) = (el.x0_m, el.x0_m + el.length_m);
        self.total_mass_kg += mu * (x1 - x0);
        self.first_moment_kg_m += mu * (x1 * x1 - x0 * x0) / 2.0;
        self.hub_inertia_kg_m2 += mu * (x1.powi(3) - x0.powi(3)) / 3.0;
    }

    fn add_concentrated_masses(&mut self) {
        for m in self.spec.masses.clone() {
            let (x, mass, inertia) = (m.position_m, m.mass_kg, m.rotary_inertia_kg_m2);
            self.total_mass_kg += mass;
            self.first_moment_kg_m += mass * x;
            self.hub_inertia_kg_m2 += mass * x * x + inertia;
            let Some(node) = self.node_index(x) else {
                continue;
            };
            if node == 0 {
                continue; // on the clamp: only the hub inertia sees it
            }
            let (u, v, phi) = (NODE_DOFS * (node - 1), NODE_DOFS * (node - 1) + 1, NODE_DOFS * (node - 1) + 2);
            for d in [u, v] {
                self.translational_mass[(d, d)] += mass;
            }
            self.coupling[v] += mass * x;
            self.coupling[phi] += inertia;
            self.axial_moment[u] += mass * x;
            self.axial_mass[u] += mass;
            self.transverse_mass[v] += mass;
            self.gyroscopic[(v, u)] += mass;
            self.gyroscopic[(u, v)] -= mass;
            self.mass[(phi, phi)] += inertia;
        }
        self.mass += &self.translational_mass;
    }

    /// Index of the node at `x_m` (masses always sit on nodes).
    fn node_index(&self, x_m: f64) -> Option<usize> {
        let tol = 1e-9 * self.length_m();
        self.nodes_x_m.iter().position(|&n| (n - x_m).abs() <= tol)
    }

    /// Shape rows of the point at `x_m` mapped onto global DOFs: (u, v, φ) rows, each of length
    /// [`Self::dofs`]. `x_m` is clamped into [0, L].
    pub fn point_rows(&self, x_m: f64) -> [DVector<f64>; 3] {
        let x = x_m.clamp(0.0, self.length_m());
        let e = self.elements.iter().position(|el| x <= el.x0_m + el.length_m).unwrap_or(self.elements.len() - 1);
        let el = &self.elements[e];
        let r = shape_rows((x - el.x0_m) / el.length_m, el.length_m);
        let [u, v, slope, _] = rows_over(&element_dofs(e), &r, self.dofs());
        [u, v, slope]
    }

    /// The element holding station `x_m` (clamped into [0, L]), its global DOFs (`None` at the
    /// clamped hub) and its shape rows there: a point's rows without forming them over every DOF.
    pub fn point_shape(&self, x_m: f64) -> ([Option<usize>; ELEMENT_DOFS], ShapeRows) {
        let x = x_m.clamp(0.0, self.length_m());
        let e = self.elements.iter().position(|el| x <= el.x0_m + el.length_m).unwrap_or(self.elements.len() - 1);
        let el = &self.elements[e];
        (element_dofs(e), shape_rows((x - el.x0_m) / el.length_m, el.length_m))
    }

    /// Static displacement under a load vector `f` (N and N·m on the DOFs), clamped hub.
    pub fn static_displacement(&self, load: &DVector<f64>) -> Result<DVector<f64>, BeamError> {
        let factor = self.stiffness_factor.get_or_init(|| self.stiffness.clone().cholesky());
        let chol = factor.as_ref().ok_or(BeamError::NotPositiveDefinite {
            matrix: "stiffness",
            why: "the clamped arm must be a structure".into(),
        })?;
        Ok(chol.solve(load))
    }

    /// Tip deflection of the horizontal arm under its own weight and its masses, m (positive down).
    pub fn gravity_tip_deflection_m(&self, gravity_m_s2: f64) -> Result<f64, BeamError> {
        let load = -gravity_m_s2 * &self.transverse_mass;
        let d = self.static_displacement(&load)?;
        let [_, v, _] = self.point_rows(self.length_m());
        Ok(-v.dot(&d))
    }
}

fn mesh_elements(spec: &BeamSpec, nodes: &[f64]) -> Vec<Element> {
    let mut ends = Vec::with_capacity(spec.segments.len());
    let mut x = 0.0;
    for s in &spec.segments {
        x += s.length_m;
        ends.push((x, *s));
    }
    nodes
        .windows(2)
        .map(|w| {
            let mid = 0.5 * (w[0] + w[1]);
            let seg = ends.iter().find(|(end, _)| mid <= *end).map_or(ends[ends.len() - 1].1, |e| e.1);
            Element {
                x0_m: w[0],
                length_m: w[1] - w[0],
                axial_rigidity_n: seg.axial_rigidity_n,
                bending_rigidity_n_m2: seg.bending_rigidity_n_m2,
                mass_per_length_kg_m: seg.mass_per_length_kg_m,
            }
        })
        .collect()
}

/// Mass and first moment outboard of a point: the axial force per unit g and per unit θ̇².
struct OutboardLoads {
    /// Per element: (mass, first moment) outboard of its tip node, masses at that node included.
    beyond_element: Vec<(f64, f64)>,
    mass_per_length: Vec<(f64, f64)>,
}

impl OutboardLoads {
    /// `point_loads`: (x, mass, first moment) delivered to the arm's nodes besides its masses
    /// (a member's load at its clamps).
    fn new(model: &BeamModel, point_loads: &[(f64, f64, f64)]) -> Self {
        let n = model.elements.len();
        let mut beyond = vec![(0.0, 0.0); n];
        let mut acc = (0.0, 0.0);
        for e in (0..n).rev() {
            let tip = model.elements[e].x0_m + model.elements[e].length_m;
            for m in model.spec.masses.iter().filter(|m| (m.position_m - tip).abs() <= 1e-9 * model.length_m()) {
                acc.0 += m.mass_kg;
                acc.1 += m.mass_kg * m.position_m;
            }
            for (_, mass, first_moment) in
                point_loads.iter().filter(|(x, ..)| (x - tip).abs() <= 1e-9 * model.length_m())
            {
                acc.0 += mass;
                acc.1 += first_moment;
            }
            beyond[e] = acc;
            let el = &model.elements[e];
            let x0 = el.x0_m;
            acc.0 += el.mass_per_length_kg_m * (tip - x0);
            acc.1 += el.mass_per_length_kg_m * (tip * tip - x0 * x0) / 2.0;
        }
        let mass_per_length =
            model.elements.iter().map(|el| (el.x0_m + el.length_m, el.mass_per_length_kg_m)).collect();
        OutboardLoads { beyond_element: beyond, mass_per_length }
    }

    /// Mass outboard of `x` inside element `e`, kg.
    fn mass(&self, e: usize, x: f64) -> f64 {
        let (x1, mu) = self.mass_per_length[e];
        self.beyond_element[e].0 + mu * (x1 - x)
    }

    /// First moment about the hub of the mass outboard of `x` inside element `e`, kg·m.
    fn first_moment(&self, e: usize, x: f64) -> f64 {
        let (x1, mu) = self.mass_per_length[e];
        self.beyond_element[e].1 + mu * (x1 * x1 - x * x) / 2.0
    }
}
