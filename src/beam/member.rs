//! A second beam carried by the arm: a pipe string held by the hands.
//!
//! The member lies along the arm's axis (the string's axis runs parallel to the arm, out of the
//! lift plane, which a planar model does not see) from `start_m` to `start_m + length`, in the
//! same hub frame and with the same `[u, v, φ]` nodes as the arm. Each clamp is a hand: the
//! member's node there *is* the arm's node (they share DOFs), so the string follows the hand's
//! stretch, deflection and slope exactly. The member's other nodes carry DOFs of their own,
//! numbered after the arm's.
//!
//! Reduction (Craig–Bampton, `docs/model.md`): the member's own DOFs are the static ride on the
//! clamps, `Ψ u_arm` with `Ψ = −K_ss⁻¹ K_sa`, plus its fixed-interface modes `Φ_s η` (the string
//! clamped at its hands). The arm's modes are computed with the string riding statically
//! ([`super::BeamModel::modes`]), so with no string mode kept the arm carries the string's mass
//! and its stiffening of the span between the hands.
//!
//! Axial load for geometric stiffening: the member's weight and centrifugal load reach the arm at
//! the clamp nearest each point (between two hands the load divides at the midpoint; an overhang
//! hangs on its own hand). That is exact for the overhangs and for a single clamp, and an
//! approximation of the statically indeterminate span, where the string's axial load is a small
//! part of the arm's.

use std::ops::Range;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::{BeamError, ELEMENT_DOFS, Element, ModalBasis, NODE_DOFS, Segment, shape_rows};

/// A stretch of a member with a section of its own: a pipe's coupling or tool joint, short and
/// stiff, carrying its mass where it lies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberPiece {
    /// Its start, measured from the member's start, m.
    pub from_m: f64,
    /// Its section; `length_m` is the piece's.
    pub segment: Segment,
}

impl MemberPiece {
    /// Its end, measured from the member's start, m.
    pub fn to_m(&self) -> f64 {
        self.from_m + self.segment.length_m
    }
}

/// A member along the arm's axis, clamped to the arm at one or more stations: uniform but for
/// its pieces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberSpec {
    /// Name, for reports.
    pub name: String,
    /// Hub-frame x of the member's end nearest the pivot, m.
    pub start_m: f64,
    /// The member's section and length.
    pub segment: Segment,
    /// Stretches with a section of their own, ascending and apart (none: uniform).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pieces: Vec<MemberPiece>,
    /// Hub-frame x of each clamp (a station on the arm and on the member), m, ascending.
    pub clamps_m: Vec<f64>,
    /// Finite elements along the member (each piece between clamps and ends gets at least one).
    pub elements: usize,
    /// Fixed-interface modes kept in a reduced model (`None`: every DOF, the reference).
    pub kept_modes: Option<usize>,
    /// Damping ratio of the member's fixed-interface modes.
    pub damping_ratio: f64,
}

impl MemberSpec {
    /// Hub-frame x of the member's far end, m.
    pub fn end_m(&self) -> f64 {
        self.start_m + self.segment.length_m
    }

    /// Checks the member against an arm of `arm_length_m`, naming the offending parameter.
    pub fn validate(&self, arm_length_m: f64) -> Result<(), BeamError> {
        self.segment.validate()?;
        if !self.start_m.is_finite() {
            return Err(BeamError::invalid("member.start_m", self.start_m, "a finite position"));
        }
        if self.clamps_m.is_empty() {
            return Err(BeamError::invalid("member.clamps_m", 0.0, "at least one clamp"));
        }
        if self.elements == 0 || self.elements > 2000 {
            return Err(BeamError::invalid("member.elements", self.elements as f64, "1 ..= 2000"));
        }
        if !(self.damping_ratio.is_finite() && (0.0..2.0).contains(&self.damping_ratio)) {
            return Err(BeamError::invalid("member.damping_ratio", self.damping_ratio, "0 <= ratio < 2"));
        }
        let tol = 1e-9 * arm_length_m.max(self.segment.length_m);
        for &x in &self.clamps_m {
            if !(x.is_finite() && (tol..=arm_length_m + tol).contains(&x)) {
                return Err(BeamError::invalid("member.clamps_m", x, format!("0 < x <= {arm_length_m} (on the arm)")));
            }
            if !(self.start_m - tol..=self.end_m() + tol).contains(&x) {
                let allowed = format!("{} ..= {} (on the member)", self.start_m, self.end_m());
                return Err(BeamError::invalid("member.clamps_m", x, allowed));
            }
        }
        if self.clamps_m.windows(2).any(|w| w[1] - w[0] <= tol) {
            return Err(BeamError::invalid("member.clamps_m", self.clamps_m[0], "distinct stations, ascending"));
        }
        let mut last_end = 0.0;
        for piece in &self.pieces {
            piece.segment.validate()?;
            if !(piece.from_m >= last_end - tol && piece.to_m() <= self.segment.length_m + tol) {
                let allowed = format!("pieces ascending and apart within 0 ..= {} m", self.segment.length_m);
                return Err(BeamError::invalid("member.pieces.from_m", piece.from_m, allowed));
            }
            last_end = piece.to_m();
        }
        Ok(())
    }

    /// Number of the member's own DOFs (its nodes off the clamps), without meshing the arm.
    pub fn own_dofs(&self) -> usize {
        NODE_DOFS * (self.node_positions().len() - self.clamps_m.len())
    }

    /// Member node positions: its ends and clamps, elements spread over the pieces between them
    /// in proportion to their length.
    fn node_positions(&self) -> Vec<f64> {
        let mut breaks = vec![self.start_m, self.end_m()];
        breaks.extend(&self.clamps_m);
        breaks.extend(self.pieces.iter().flat_map(|p| [self.start_m + p.from_m, self.start_m + p.to_m()]));
        super::spread_nodes(breaks, self.elements, self.segment.length_m)
    }

    /// The part of the member whose axial load reaches the arm through clamp `c`: from the
    /// midpoint to the previous clamp (or the member's start) to the midpoint to the next (or
    /// its end), m.
    fn region(&self, c: usize) -> (f64, f64) {
        let x = &self.clamps_m;
        let lo = if c == 0 { self.start_m } else { 0.5 * (x[c - 1] + x[c]) };
        let hi = if c + 1 == x.len() { self.end_m() } else { 0.5 * (x[c] + x[c + 1]) };
        (lo, hi)
    }

    /// The clamp whose region holds `x`.
    fn clamp_of(&self, x: f64) -> usize {
        (0..self.clamps_m.len()).find(|&c| x <= self.region(c).1).unwrap_or(self.clamps_m.len() - 1)
    }

    /// The section at hub-frame `x` (a piece's where one lies, else the member's).
    pub fn section_at(&self, x: f64) -> &Segment {
        let along = x - self.start_m;
        self.pieces.iter().find(|p| (p.from_m..=p.to_m()).contains(&along)).map_or(&self.segment, |p| &p.segment)
    }

    /// Mass (kg) and first moment about the hub (kg·m) of the member between hub-frame `a` and
    /// `b` (a <= b).
    fn mass_between(&self, a: f64, b: f64) -> (f64, f64) {
        let mu = self.segment.mass_per_length_kg_m;
        let mut mass = (mu * (b - a), mu * (b * b - a * a) / 2.0);
        for piece in &self.pieces {
            let (lo, hi) = ((self.start_m + piece.from_m).max(a), (self.start_m + piece.to_m()).min(b));
            if hi > lo {
                let extra = piece.segment.mass_per_length_kg_m - mu;
                mass.0 += extra * (hi - lo);
                mass.1 += extra * (hi * hi - lo * lo) / 2.0;
            }
        }
        mass
    }

    /// Mass (kg) and first moment about the hub (kg·m) that reach the arm at each clamp.
    pub(super) fn clamp_loads(&self) -> Vec<(f64, f64, f64)> {
        (0..self.clamps_m.len())
            .map(|c| {
                let (lo, hi) = self.region(c);
                let (mass, first_moment) = self.mass_between(lo, hi);
                (self.clamps_m[c], mass, first_moment)
            })
            .collect()
    }

    /// Axial load at `x` per unit g (kg) and per unit θ̇² (kg·m), with the arm's sign: positive
    /// where the load beyond `x` pulls away from the hub (the material between `x` and the
    /// region's outer end hangs outward through `x`), negative on the hub side of a clamp (the
    /// material between the region's inner end and `x` pushes outward through it).
    pub(super) fn axial_load(&self, x: f64) -> (f64, f64) {
        let c = self.clamp_of(x);
        let (lo, hi) = self.region(c);
        if x >= self.clamps_m[c] {
            self.mass_between(x, hi)
        } else {
            let (mass, first_moment) = self.mass_between(lo, x);
            (-mass, -first_moment)
        }
    }
}

/// The member meshed and numbered.
#[derive(Debug, Clone)]
pub struct MemberModel {
    /// Its description.
    pub spec: MemberSpec,
    /// Node positions along the hub frame's x, m.
    pub nodes_x_m: Vec<f64>,
    /// Elements, from `start_m` outwards.
    pub elements: Vec<Element>,
    /// Global DOFs of each element's six local DOFs (`None` where a clamp sits on the hub).
    pub element_dofs: Vec<[Option<usize>; ELEMENT_DOFS]>,
    /// The member's own DOFs (not shared with the arm), a contiguous range after the arm's.
    pub own_dofs: Range<usize>,
    /// Member node index of each clamp, in the order of `spec.clamps_m`.
    pub clamp_nodes: Vec<usize>,
}

impl MemberModel {
    /// Meshes `spec`; `arm_node` gives the arm's node index at a clamp station (0: the hub, which
    /// carries no DOF) and `first_dof` is where the member's own DOFs start.
    pub(super) fn new(spec: MemberSpec, arm_node: impl Fn(f64) -> Option<usize>, first_dof: usize) -> Self {
        let nodes_x_m = spec.node_positions();
        let tol = 1e-9 * spec.segment.length_m;
        let clamp_nodes: Vec<usize> = spec
            .clamps_m
            .iter()
            .map(|&c| nodes_x_m.iter().position(|&x| (x - c).abs() <= tol).expect("clamps are member nodes"))
            .collect();
        let mut next = first_dof;
        let node_dofs: Vec<[Option<usize>; NODE_DOFS]> = nodes_x_m
            .iter()
            .enumerate()
            .map(|(j, &x)| {
                if clamp_nodes.contains(&j) {
                    let arm = arm_node(x).expect("clamps are arm nodes");
                    [0, 1, 2].map(|k| (arm > 0).then(|| NODE_DOFS * (arm - 1) + k))
                } else {
                    next += NODE_DOFS;
                    [0, 1, 2].map(|k| Some(next - NODE_DOFS + k))
                }
            })
            .collect();
        let elements = nodes_x_m
            .windows(2)
            .map(|w| {
                let s = spec.section_at(0.5 * (w[0] + w[1]));
                Element {
                    x0_m: w[0],
                    length_m: w[1] - w[0],
                    axial_rigidity_n: s.axial_rigidity_n,
                    bending_rigidity_n_m2: s.bending_rigidity_n_m2,
                    mass_per_length_kg_m: s.mass_per_length_kg_m,
                }
            })
            .collect();
        let element_dofs = (0..nodes_x_m.len() - 1)
            .map(|e| {
                let (a, b) = (node_dofs[e], node_dofs[e + 1]);
                [a[0], a[1], a[2], b[0], b[1], b[2]]
            })
            .collect();
        MemberModel { spec, nodes_x_m, elements, element_dofs, own_dofs: first_dof..next, clamp_nodes }
    }

    /// Shape rows (u, v, φ, curvature) of the member's point at hub-frame `x_m` over the model's
    /// `dofs` global DOFs; `x_m` is clamped onto the member.
    pub fn point_rows(&self, x_m: f64, dofs: usize) -> [DVector<f64>; 4] {
        let x = x_m.clamp(self.spec.start_m, self.spec.end_m());
        let e = self.elements.iter().position(|el| x <= el.x0_m + el.length_m).unwrap_or(self.elements.len() - 1);
        self.element_rows(e, (x - self.elements[e].x0_m) / self.elements[e].length_m, dofs)
    }

    /// Shape rows (u, v, φ, curvature) at local coordinate `xi` of element `e`.
    pub fn element_rows(&self, e: usize, xi: f64, dofs: usize) -> [DVector<f64>; 4] {
        super::rows_over(&self.element_dofs[e], &shape_rows(xi, self.elements[e].length_m), dofs)
    }

    /// Curvature rows on both sides of each clamp (the string's root sections, where its
    /// bending moment peaks): `[(clamp index, rows)]`, hub side first.
    pub fn clamp_curvature_rows(&self, dofs: usize) -> Vec<(usize, DVector<f64>)> {
        let mut rows = Vec::new();
        for (c, &node) in self.clamp_nodes.iter().enumerate() {
            if node > 0 {
                rows.push((c, self.element_rows(node - 1, 1.0, dofs)[3].clone()));
            }
            if node < self.elements.len() {
                rows.push((c, self.element_rows(node, 0.0, dofs)[3].clone()));
            }
        }
        rows
    }
}

/// The fixed-interface modes of the member (its own DOFs, the clamps held): ascending,
/// mass-normalised over the member's own block of `mass`.
pub(super) fn fixed_interface_modes(
    own: &Range<usize>,
    stiffness: &DMatrix<f64>,
    mass: &DMatrix<f64>,
) -> Result<ModalBasis, BeamError> {
    let n = own.len();
    let k = stiffness.view((own.start, own.start), (n, n)).into_owned();
    let m = mass.view((own.start, own.start), (n, n)).into_owned();
    super::modes::solve_generalized_in_blocks(&k, &m)
}

/// The static ride of the member's own DOFs on the arm's: Ψ = −K_ss⁻¹ K_sa (own DOFs × arm DOFs).
pub(super) fn static_ride(
    own: &Range<usize>,
    arm_dofs: usize,
    stiffness: &DMatrix<f64>,
) -> Result<DMatrix<f64>, BeamError> {
    let n = own.len();
    let k_ss = stiffness.view((own.start, own.start), (n, n)).into_owned();
    let k_sa = stiffness.view((own.start, 0), (n, arm_dofs)).into_owned();
    let chol = k_ss.cholesky().ok_or(BeamError::NotPositiveDefinite {
        matrix: "stiffness",
        why: "the member must be held by its clamps".into(),
    })?;
    Ok(-chol.solve(&k_sa))
}
