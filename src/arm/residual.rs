//! The static flexibility a reduced arm leaves out at a point where a concentrated force acts:
//! the truncated modes' share, added back as a massless spring (the mode-acceleration or static
//! correction of Craig and Kurdila, *Fundamentals of Structural Dynamics*, 2nd ed., §14.5).
//!
//! A force F on the clamped arm at a point with FE rows R (hub-frame axial and transverse
//! displacement over the FE DOFs) moves the point statically by G F, G = R K⁻¹ Rᵀ. The kept
//! coordinates give Gₙ = Rₙ Kₙ⁻¹ Rₙᵀ (Rₙ = R Φ, Kₙ = Φᵀ K Φ: Σ φᵢ φᵢᵀ / ωᵢ² over mass-normalised
//! modes). The rest, G − Gₙ, is what the modes above n would contribute quasi-statically: they
//! are stiff against the forcing, so their response follows the force without inertia.

use nalgebra::{DMatrix, DVector};

use super::{ArmError, ArmModel, Fidelity};
use crate::actuator::PinCouplings;
use crate::beam::BeamError;

impl ArmModel {
    /// Cylinders' arm pins at (x, y) in the hub frame (m; y across the arm, joined to the
    /// section at x by a rigid bracket): their rows over q and the residual flexibility between
    /// them (a force on one pin moves the others too).
    pub fn pin_couplings(&self, pins_m: &[[f64; 2]]) -> Result<PinCouplings, ArmError> {
        let full: Vec<DVector<f64>> = pins_m
            .iter()
            .flat_map(|&[x, y]| {
                let [u, v, slope] = self.beam.point_rows(x);
                [u - y * slope, v]
            })
            .collect();
        let projected: Vec<DVector<f64>> = full.iter().map(|r| self.basis.tr_mul(r)).collect();
        let residual_flexibility_m_per_n = self.residual_flexibility_m_per_n(&full, &projected)?;
        let rows = projected.chunks(2).map(|pair| [pair[0].clone(), pair[1].clone()]).collect();
        Ok(PinCouplings { rows, residual_flexibility_m_per_n })
    }

    /// G − Gₙ (module doc) for the FE rows `full` and their projections `rows` on q, m/N,
    /// symmetrised. Zero for the FE arm, which keeps every DOF, and for the rigid arm, which
    /// keeps no elasticity.
    fn residual_flexibility_m_per_n(
        &self,
        full: &[DVector<f64>],
        rows: &[DVector<f64>],
    ) -> Result<DMatrix<f64>, ArmError> {
        let m = full.len();
        if !matches!(self.fidelity, Fidelity::Modal { .. }) {
            return Ok(DMatrix::zeros(m, m));
        }
        let clamped = self.beam.stiffness.clone().cholesky().ok_or(BeamError::NotPositiveDefinite {
            matrix: "stiffness",
            why: "the clamped arm must be a structure".into(),
        })?;
        let static_full: Vec<DVector<f64>> = full.iter().map(|r| clamped.solve(r)).collect();
        let k = self.stiffness.clone().cholesky().ok_or(ArmError::InvalidParameter {
            name: "stiffness".into(),
            value: f64::NAN,
            allowed: "a positive definite reduced stiffness".into(),
        })?;
        let kept: Vec<DVector<f64>> = rows.iter().map(|r| k.solve(r)).collect();
        let entry = |i: usize, j: usize| full[i].dot(&static_full[j]) - rows[i].dot(&kept[j]);
        Ok(DMatrix::from_fn(m, m, |i, j| 0.5 * (entry(i, j) + entry(j, i))))
    }
}
