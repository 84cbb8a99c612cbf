//! Floating-frame dynamics of the arm: hub angle θ plus elastic coordinates q.
//!
//! The arm's deformation is measured in a frame that turns with the hub ("floating frame"),
//! clamped at the pivot. The elastic displacement field is `Φ q` over the beam DOFs of
//! [`crate::beam`], and one reduced model serves all three fidelities:
//!
//! | fidelity | Φ | coordinates |
//! |---|---|---|
//! | [`Fidelity::Rigid`] | none | θ only |
//! | [`Fidelity::Modal`] | the first n clamped eigenmodes, mass-normalised | θ, q₁…q_n |
//! | [`Fidelity::Fe`] | identity | θ and every FE DOF (the reference) |
//!
//! Equations (derived in `docs/model.md`; g is gravity, s = sin θ, c = cos θ):
//!
//! ```text
//! M q̈ + S̃ θ̈ + (D + 2θ̇C) q̇ + (K − θ̇² W − g s K_g) q = θ̇² a − g s b_u − g c b_v + Q_q
//! Ĵ θ̈ + S̃ᵀ q̈ + 2θ̇ (a + W q)ᵀ q̇ = τ − g c (m₁ + b_uᵀq) + g s b_vᵀq + ½ g c qᵀK_g q + Q_θ
//! S̃ = S + C q,   Ĵ = J₀ + 2aᵀq + qᵀWq,   W = M_tr − K_c
//! ```
//!
//! Without geometric stiffening K_c and K_g are dropped (W = M_tr): the classic model that goes
//! unstable once the spin rate exceeds the first frequency.

mod channels;
mod contact;
mod dynamics;
mod head;
mod linear;
mod pin;
mod products;
mod residual;
mod sim;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::beam::{BeamError, BeamModel, ModalBasis};
use crate::drive::DriveError;
use crate::integrate::IntegrateError;

pub use channels::{ENERGY_ENTITY, MODAL_ENTITY, TIP_DEFLECTION_ENTITY, channels, head_channels, state_channels};
pub use contact::{ArmContact, ContactState, PointContact};
pub use dynamics::{ArmSystem, GeneralizedLoad, HubCache, HubDrive};
pub use head::{HeadModel, HeadState};
pub use linear::LinearSystem;
pub(crate) use pin::ArmPin;
pub use sim::{ArmSample, ArmSimulation, Energies};

/// Standard gravity, m/s².
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;

/// Default modal damping ratio: 1 %, MSC ADAMS' default for flexible-body modes below 100 Hz
/// and typical of a welded steel structure.
pub const DEFAULT_DAMPING_RATIO: f64 = 0.01;

/// How much of the arm's elasticity a model keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Fidelity {
    /// Rigid arm: θ only.
    Rigid,
    /// The first `modes` clamped eigenmodes.
    Modal { modes: usize },
    /// Every finite-element DOF: the reference.
    Fe,
}

impl std::fmt::Display for Fidelity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Fidelity::Rigid => write!(f, "rigid"),
            Fidelity::Modal { modes } => write!(f, "modal({modes})"),
            Fidelity::Fe => write!(f, "fe"),
        }
    }
}

/// Physical options of the arm model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ArmOptions {
    /// Damping ratio ζ per clamped mode, lowest first; the last value applies to every higher
    /// mode. Default [`DEFAULT_DAMPING_RATIO`] for all.
    pub damping_ratios: Vec<f64>,
    /// Geometric stiffening from the axial centrifugal and gravity load (default on).
    pub geometric_stiffening: bool,
    /// Gravity, m/s², acting in the lift plane towards −Y (θ = 0 is horizontal).
    pub gravity_m_s2: f64,
    /// Inertia of the hub and drive train about the pivot, kg·m².
    pub hub_inertia_kg_m2: f64,
}

impl Default for ArmOptions {
    fn default() -> Self {
        ArmOptions {
            damping_ratios: vec![DEFAULT_DAMPING_RATIO],
            geometric_stiffening: true,
            gravity_m_s2: STANDARD_GRAVITY_M_S2,
            hub_inertia_kg_m2: 0.0,
        }
    }
}

/// Shape rows (axial u, deflection v, slope φ) of one station over the elastic coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct StationRows(pub [DVector<f64>; 3]);

impl StationRows {
    /// [u (m), v (m), φ (rad)] at `q`.
    pub fn displacement(&self, q: &DVector<f64>) -> [f64; 3] {
        // Slices: a few coordinates, called per shape per step.
        self.0.each_ref().map(|row| products::dot(row, q.as_slice()))
    }
}

/// Errors building or running an arm model.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ArmError {
    /// In the beam description.
    #[error(transparent)]
    Beam(#[from] BeamError),
    /// In the drive.
    #[error(transparent)]
    Drive(#[from] DriveError),
    /// In time integration.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// An arm option outside its range.
    #[error("arm parameter `{name}` = {value} is invalid: allowed {allowed}")]
    InvalidParameter { name: String, value: f64, allowed: String },
    /// The actuator cannot hold the arm at rest under its load at the start.
    #[error("the actuator cannot hold the arm at rest under {load} N·m: {why}")]
    ActuatorCannotHold { load: f64, why: String },
}

/// The reduced floating-frame arm model (notation of the module doc).
#[derive(Debug, Clone)]
pub struct ArmModel {
    /// The finite-element beam it was reduced from.
    pub beam: BeamModel,
    /// The fidelity this model was built at.
    pub fidelity: Fidelity,
    /// The options it was built with.
    pub options: ArmOptions,
    /// Basis Φ: beam DOFs × elastic coordinates.
    pub basis: DMatrix<f64>,
    /// Clamped natural frequencies of the kept modes, rad/s (empty for rigid and fe): the arm's,
    /// then a member's fixed-interface ones.
    pub modal_omegas_rad_s: Vec<f64>,
    /// Highest natural frequency the model keeps, rad/s (0 for rigid): what limits an explicit
    /// integrator's step.
    pub highest_omega_rad_s: f64,
    pub(crate) mass: DMatrix<f64>,
    /// M⁻¹ (the mass is constant under a prescribed hub: factorised once, not every step).
    pub(crate) mass_inverse: DMatrix<f64>,
    pub(crate) stiffness: DMatrix<f64>,
    pub(crate) damping: DMatrix<f64>,
    pub(crate) gyroscopic: DMatrix<f64>,
    pub(crate) spin_mass: DMatrix<f64>,
    pub(crate) gravity_stiffness: DMatrix<f64>,
    pub(crate) coupling: DVector<f64>,
    pub(crate) axial_moment: DVector<f64>,
    pub(crate) axial_mass: DVector<f64>,
    pub(crate) transverse_mass: DVector<f64>,
    /// Inertia about the pivot of hub, undeformed arm and masses, kg·m².
    pub pivot_inertia_kg_m2: f64,
    /// First moment of mass about the pivot, kg·m.
    pub first_moment_kg_m: f64,
    tip_rows: [DVector<f64>; 3],
    /// The tilting head turning on the arm, if the robot has one ([`Self::with_head`]).
    pub head: Option<HeadModel>,
}

impl ArmModel {
    /// Reduces `beam` to `fidelity` with `options`.
    pub fn new(beam: BeamModel, fidelity: Fidelity, options: ArmOptions) -> Result<Self, ArmError> {
        let modes = beam.modes()?;
        Self::with_modes(beam, modes, fidelity, options)
    }

    /// [`Self::new`] with `beam`'s clamped modes already solved (`beam.modes()`).
    pub fn with_modes(
        beam: BeamModel,
        modes: ModalBasis,
        fidelity: Fidelity,
        options: ArmOptions,
    ) -> Result<Self, ArmError> {
        validate_options(&options)?;
        let (arm_basis, mut modal_omegas_rad_s) = match fidelity {
            Fidelity::Rigid => (DMatrix::zeros(beam.dofs(), 0), Vec::new()),
            Fidelity::Modal { modes: n } => {
                if n == 0 || n > modes.len() {
                    return Err(ArmError::InvalidParameter {
                        name: "model.modes".into(),
                        value: n as f64,
                        allowed: format!("1 ..= {} (the FE DOFs of this arm)", modes.len()),
                    });
                }
                let kept = modes.truncated(n);
                (kept.shapes, kept.omegas_rad_s)
            }
            Fidelity::Fe => (beam.arm_ride(), Vec::new()),
        };
        // A member (a flexible string) adds its kept fixed-interface modes (Craig–Bampton).
        let kept_member = beam.spec.member.as_ref().and_then(|m| m.kept_modes);
        let member_basis = beam.member_basis(kept_member);
        let member_omegas: Vec<f64> =
            beam.member_modes().map(|m| m.omegas_rad_s[..member_basis.ncols()].to_vec()).unwrap_or_default();
        let basis = if member_basis.ncols() == 0 {
            arm_basis
        } else {
            let mut both = DMatrix::zeros(beam.dofs(), arm_basis.ncols() + member_basis.ncols());
            both.columns_mut(0, arm_basis.ncols()).copy_from(&arm_basis);
            both.columns_mut(arm_basis.ncols(), member_basis.ncols()).copy_from(&member_basis);
            both
        };
        if fidelity != Fidelity::Fe {
            modal_omegas_rad_s.extend(&member_omegas);
        }
        let member_highest = member_omegas.last().copied().unwrap_or(0.0);
        let damping = modal_damping(&beam, &modes, &options.damping_ratios, &basis);
        let project = |m: &DMatrix<f64>| basis.transpose() * m * &basis;
        let project_v = |v: &DVector<f64>| basis.transpose() * v;
        let stiffening = if options.geometric_stiffening { 1.0 } else { 0.0 };
        let g = options.gravity_m_s2;
        let l = beam.length_m();
        let tip_rows = beam.point_rows(l).map(|r| project_v(&r));
        let mass = project(&beam.mass);
        let mass_inverse = if mass.is_empty() { Some(mass.clone()) } else { mass.clone().try_inverse() };
        let mass_inverse = mass_inverse.ok_or(ArmError::InvalidParameter {
            name: "mass matrix".into(),
            value: f64::NAN,
            allowed: "a positive definite reduced mass".into(),
        })?;
        let stiffness = project(&beam.stiffness);
        // With a member the basis is not the eigenbasis: its coupled modes ring above the highest
        // kept frequency of either part (they repel), and that is what limits an explicit step.
        let coupled_highest = if beam.member.is_some() && !mass.is_empty() {
            crate::beam::solve_generalized(&stiffness, &mass)?.omegas_rad_s.last().copied().unwrap_or(0.0)
        } else {
            0.0
        };
        Ok(ArmModel {
            mass,
            mass_inverse,
            stiffness,
            damping,
            gyroscopic: project(&beam.gyroscopic),
            spin_mass: project(&(&beam.translational_mass - stiffening * &beam.centrifugal_stiffness)),
            gravity_stiffness: project(&(stiffening * g * &beam.gravity_stiffness)),
            coupling: project_v(&beam.coupling),
            axial_moment: project_v(&beam.axial_moment),
            axial_mass: project_v(&beam.axial_mass),
            transverse_mass: project_v(&beam.transverse_mass),
            pivot_inertia_kg_m2: beam.hub_inertia_kg_m2 + options.hub_inertia_kg_m2,
            first_moment_kg_m: beam.first_moment_kg_m,
            tip_rows,
            basis,
            highest_omega_rad_s: coupled_highest.max(member_highest).max(match fidelity {
                Fidelity::Rigid => 0.0,
                Fidelity::Modal { modes: n } => modes.omegas_rad_s[n - 1],
                Fidelity::Fe => modes.omegas_rad_s.last().copied().unwrap_or(0.0),
            }),
            modal_omegas_rad_s,
            fidelity,
            options,
            beam,
            head: None,
        })
    }

    /// Number of elastic coordinates q.
    pub fn elastic_dofs(&self) -> usize {
        self.basis.ncols()
    }

    /// Arm length, m.
    pub fn length_m(&self) -> f64 {
        self.beam.length_m()
    }

    /// Displacement (axial stretch u, deflection v) in the hub frame of the point at `x_m`, m.
    pub fn deflection_at(&self, x_m: f64, q: &DVector<f64>) -> [f64; 2] {
        let [u, v, _] = self.station_rows(x_m).displacement(q);
        [u, v]
    }

    /// The shape rows of station `x_m` projected on q: compute once, evaluate per step.
    pub fn station_rows(&self, x_m: f64) -> StationRows {
        StationRows(self.beam.point_rows(x_m).map(|r| self.basis.tr_mul(&r)))
    }

    /// The shape rows of a flexible string's station `x_m` (hub-frame x, clamped onto the string)
    /// projected on q; `None` without a string of its own.
    pub fn string_station_rows(&self, x_m: f64) -> Option<StationRows> {
        let member = self.beam.member.as_ref()?;
        let [u, v, phi, _] = member.point_rows(x_m, self.beam.dofs());
        Some(StationRows([u, v, phi].map(|r| self.basis.tr_mul(&r))))
    }

    /// Static elastic coordinates under gravity with the hub held at `angle_rad`:
    /// (K − g sin θ K_g) q = −g (sin θ b_u + cos θ b_v).
    pub fn static_deflection(&self, angle_rad: f64) -> Result<DVector<f64>, ArmError> {
        self.static_deflection_under(angle_rad, &DVector::zeros(self.elastic_dofs()))
    }

    /// [`Self::static_deflection`] with generalized forces `extra` on q besides gravity (a
    /// cylinder holding the arm).
    pub fn static_deflection_under(&self, angle_rad: f64, extra: &DVector<f64>) -> Result<DVector<f64>, ArmError> {
        let g = self.options.gravity_m_s2;
        let (s, c) = angle_rad.sin_cos();
        let k = &self.stiffness - s * &self.gravity_stiffness;
        let load = -g * (s * &self.axial_mass + c * &self.transverse_mass) + extra;
        if load.is_empty() {
            return Ok(load);
        }
        k.lu().solve(&load).ok_or_else(|| {
            ArmError::Beam(BeamError::NotPositiveDefinite {
                matrix: "stiffness",
                why: format!("the arm buckles under its own weight at {:.1} deg", angle_rad.to_degrees()),
            })
        })
    }

    /// Slope (section rotation) at station `x_m`, rad.
    pub fn slope_at(&self, x_m: f64, q: &DVector<f64>) -> f64 {
        self.station_rows(x_m).displacement(q)[2]
    }

    /// Tip (u, v, slope) rows over q.
    pub(crate) fn tip_rows(&self) -> &[DVector<f64>; 3] {
        &self.tip_rows
    }

    /// Generalized forces of a force `force_n` (world X, Y, N) applied at arm station `x_m` of
    /// the deformed arm in configuration (θ, q): Q_θ is its moment about the pivot (N·m),
    /// Q_q = Φᵀ Nᵀ Rᵀ F (the virtual work of F through the elastic coordinates).
    pub fn point_force(&self, x_m: f64, force_n: [f64; 2], theta_rad: f64, q: &DVector<f64>) -> GeneralizedLoad {
        let [u, v] = self.deflection_at(x_m, q);
        let (s, c) = theta_rad.sin_cos();
        let r_world = [c * (x_m + u) - s * v, s * (x_m + u) + c * v];
        let f_body = [c * force_n[0] + s * force_n[1], -s * force_n[0] + c * force_n[1]];
        let [nu, nv, _] = self.beam.point_rows(x_m);
        let modal = self.basis.tr_mul(&(f_body[0] * nu + f_body[1] * nv));
        GeneralizedLoad { hub_torque_n_m: r_world[0] * force_n[1] - r_world[1] * force_n[0], modal }
    }
}

fn validate_options(o: &ArmOptions) -> Result<(), ArmError> {
    let bad = |name: &str, value: f64, allowed: &str| ArmError::InvalidParameter {
        name: name.into(),
        value,
        allowed: allowed.into(),
    };
    if o.damping_ratios.is_empty() {
        return Err(bad("damping_ratios", 0.0, "at least one ratio"));
    }
    if let Some(z) = o.damping_ratios.iter().find(|z| !(z.is_finite() && (0.0..2.0).contains(*z))) {
        return Err(bad("damping_ratios", *z, "0 <= ratio < 2"));
    }
    if !(o.gravity_m_s2.is_finite() && o.gravity_m_s2 >= 0.0) {
        return Err(bad("gravity_m_s2", o.gravity_m_s2, "a finite value >= 0"));
    }
    if !(o.hub_inertia_kg_m2.is_finite() && o.hub_inertia_kg_m2 >= 0.0) {
        return Err(bad("hub_inertia_kg_m2", o.hub_inertia_kg_m2, "a finite value >= 0"));
    }
    Ok(())
}

/// Modal damping over every clamped mode, projected on `basis` (B): D = M Φ diag(2 ζ_i ω_i) Φᵀ M,
/// so that each fidelity damps each kept mode at its own ζ_i and modal(n) converges to fe. As
/// Bᵀ D B = (Φᵀ M B)ᵀ diag (Φᵀ M B) it is formed on B's few columns, never over every DOF.
///
/// With a member (a flexible string) each part damps its own modal coordinates only: the arm's,
/// q_a = Φ_aᵀ M_g d_a (M_g = Tᵀ M T the arm's mass with the member riding on it), and the
/// member's deformation relative to that ride, η = Φ_sᵀ M_ss (d_s − Ψ d_a) — never the member's
/// rigid ride on the hands, which a damping of all its DOFs would brake.
fn modal_damping(beam: &BeamModel, modes: &ModalBasis, ratios: &[f64], basis: &DMatrix<f64>) -> DMatrix<f64> {
    let zeta = |i: usize| ratios[i.min(ratios.len() - 1)];
    let arm_rates =
        DVector::from_iterator(modes.len(), (0..modes.len()).map(|i| 2.0 * zeta(i) * modes.omegas_rad_s[i]));
    let weighted = |rows: &DMatrix<f64>, rates: &DVector<f64>| rows.transpose() * DMatrix::from_diagonal(rates) * rows;
    let (Some(member), Some(member_modes)) = (&beam.member, beam.member_modes()) else {
        // Φᵀ M B.
        let rows = modes.shapes.transpose() * (&beam.mass * basis);
        return weighted(&rows, &arm_rates);
    };
    let a = beam.arm_dofs();
    let own = member.own_dofs.clone();
    let ride = beam.arm_ride();
    // q_a over B: Φ_aᵀ M_g (E B) = (T Φ_a)ᵀ M T (E B), T Φ_a being the modes' columns.
    let arm_part = basis.rows(0, a);
    let arm_rows = modes.shapes.transpose() * (&beam.mass * (&ride * arm_part));
    // η over B: Φ_sᵀ M_ss (B_s − Ψ B_a).
    let m_ss = beam.mass.view((own.start, own.start), (own.len(), own.len()));
    let relative = basis.rows(own.start, own.len()) - ride.rows(a, own.len()) * arm_part;
    let member_rows = member_modes.shapes.transpose() * (m_ss * relative);
    let zeta_s = member.spec.damping_ratio;
    let member_rates = member_modes.omegas_rad_s.iter().map(|w| 2.0 * zeta_s * w);
    weighted(&arm_rows, &arm_rates) + weighted(&member_rows, &DVector::from_iterator(member_modes.len(), member_rates))
}
