//! The static flexibility a reduced arm leaves out at a point where a concentrated force acts:
//! the truncated modes' share, added back as a massless spring (the mode-acceleration or static
//! correction of Craig and Kurdila, *Fundamentals of Structural Dynamics*, 2nd ed., §14.5).
//!
//! A force F on the clamped arm at a point with FE rows R (hub-frame axial and transverse
//! displacement over the FE DOFs) moves the point statically by G F, G = R K⁻¹ Rᵀ. The kept
//! coordinates give Gₙ = Rₙ Kₙ⁻¹ Rₙᵀ (Rₙ = R Φ, Kₙ = Φᵀ K Φ: Σ φᵢ φᵢᵀ / ωᵢ² over mass-normalised
//! modes). The rest, G − Gₙ, is what the modes above n would contribute quasi-statically: they
//! are stiff against the forcing, so their response follows the force without inertia.

use nalgebra::DVector;

use super::{ArmError, ArmModel, Fidelity};
use crate::actuator::PinCoupling;
use crate::beam::BeamError;

impl ArmModel {
    /// A cylinder's arm pin at (x, y) in the hub frame (m; y across the arm, joined to the
    /// section at x by a rigid bracket): its rows over q and the residual flexibility there.
    pub fn pin_coupling(&self, pin_m: [f64; 2]) -> Result<PinCoupling, ArmError> {
        let [x, y] = pin_m;
        let [u, v, slope] = self.beam.point_rows(x);
        let full = [u - y * slope, v];
        let rows = full.each_ref().map(|r| self.basis.tr_mul(r));
        let residual_flexibility_m_per_n = self.residual_flexibility_m_per_n(&full, &rows)?;
        Ok(PinCoupling { rows, residual_flexibility_m_per_n })
    }

    /// G − Gₙ (module doc) for the FE rows `full` and their projections `rows` on q, m/N. Zero
    /// for the FE arm, which keeps every DOF, and for the rigid arm, which keeps no elasticity.
    fn residual_flexibility_m_per_n(
        &self,
        full: &[DVector<f64>; 2],
        rows: &[DVector<f64>; 2],
    ) -> Result<[[f64; 2]; 2], ArmError> {
        if !matches!(self.fidelity, Fidelity::Modal { .. }) {
            return Ok([[0.0; 2]; 2]);
        }
        let clamped = self.beam.stiffness.clone().cholesky().ok_or(BeamError::NotPositiveDefinite {
            matrix: "stiffness",
            why: "the clamped arm must be a structure".into(),
        })?;
        let static_full = full.each_ref().map(|r| clamped.solve(r));
        let k = self.stiffness.clone().cholesky().ok_or(ArmError::InvalidParameter {
            name: "stiffness".into(),
            value: f64::NAN,
            allowed: "a positive definite reduced stiffness".into(),
        })?;
        let kept = rows.each_ref().map(|r| k.solve(r));
        let entry = |i: usize, j: usize| full[i].dot(&static_full[j]) - rows[i].dot(&kept[j]);
        let cross = 0.5 * (entry(0, 1) + entry(1, 0));
        Ok([[entry(0, 0), cross], [cross, entry(1, 1)]])
    }
}
