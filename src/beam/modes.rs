//! Clamped-hub eigenmodes: K φ = ω² M φ, optionally at a steady spin rate Ω.

use nalgebra::DMatrix;

use super::{BeamError, BeamModel};

/// Mass-normalised eigenmodes of the clamped arm, ascending in frequency.
#[derive(Debug, Clone)]
pub struct ModalBasis {
    /// Natural circular frequencies ω_i, rad/s.
    pub omegas_rad_s: Vec<f64>,
    /// Mode shapes as columns over the beam DOFs, scaled so that Φᵀ M Φ = I.
    pub shapes: DMatrix<f64>,
}

impl ModalBasis {
    /// Number of modes.
    pub fn len(&self) -> usize {
        self.omegas_rad_s.len()
    }

    /// True if there are no modes.
    pub fn is_empty(&self) -> bool {
        self.omegas_rad_s.is_empty()
    }

    /// Natural frequencies in Hz.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omegas_rad_s.iter().map(|w| w / std::f64::consts::TAU).collect()
    }

    /// The first `n` modes.
    pub fn truncated(&self, n: usize) -> ModalBasis {
        ModalBasis { omegas_rad_s: self.omegas_rad_s[..n].to_vec(), shapes: self.shapes.columns(0, n).into_owned() }
    }
}

impl BeamModel {
    /// All eigenmodes of the arm clamped at a hub at rest, without gravity. With a member (a
    /// flexibly modelled string) these are the arm's modes with the member riding statically on
    /// its clamps (the Craig–Bampton boundary set, [`BeamModel::arm_ride`]), one per arm DOF, as
    /// columns over every DOF; the member's own modes are [`BeamModel::member_modes`].
    pub fn modes(&self) -> Result<ModalBasis, BeamError> {
        if self.member.is_none() {
            return solve_generalized(&self.stiffness, &self.mass);
        }
        let ride = self.arm_ride();
        let project = |m: &DMatrix<f64>| ride.transpose() * m * &ride;
        let modes = solve_generalized(&project(&self.stiffness), &project(&self.mass))?;
        Ok(ModalBasis { shapes: &ride * modes.shapes, omegas_rad_s: modes.omegas_rad_s })
    }

    /// Eigenmodes of the arm on a hub spinning steadily at `spin_rad_s` (no gravity):
    /// (K + Ω²(K_c − M_tr)) φ = ω² M φ, centrifugal stiffening included when `stiffening`.
    /// Errors when the spin makes the arm unstable (a negative ω²).
    pub fn modes_spinning(&self, spin_rad_s: f64, stiffening: bool) -> Result<ModalBasis, BeamError> {
        let w2 = spin_rad_s * spin_rad_s;
        let mut k = &self.stiffness - w2 * &self.translational_mass;
        if stiffening {
            k += w2 * &self.centrifugal_stiffness;
        }
        solve_generalized(&k, &self.mass)
    }
}

impl BeamModel {
    /// Eigenmodes of the arm on a hub that turns freely, with `hub_inertia_kg_m2` of its own
    /// (no gravity). The hub's equation J θ̈ + Sᵀq̈ = 0 eliminates θ, leaving
    /// K φ = ω² (M − S Sᵀ / J) φ with J the pivot inertia of hub, arm and masses.
    /// The rigid rotation (ω = 0) is not among the modes.
    pub fn modes_free_hub(&self, hub_inertia_kg_m2: f64) -> Result<ModalBasis, BeamError> {
        let j = self.hub_inertia_kg_m2 + hub_inertia_kg_m2;
        let condensed = &self.mass - (&self.coupling * self.coupling.transpose()) / j;
        solve_generalized(&self.stiffness, &condensed)
    }
}

/// Solves K φ = λ M φ for symmetric K and positive-definite M through M = L Lᵀ.
pub(crate) fn solve_generalized(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Result<ModalBasis, BeamError> {
    let chol = m
        .clone()
        .cholesky()
        .ok_or(BeamError::NotPositiveDefinite { matrix: "mass", why: "every DOF needs mass or inertia".into() })?;
    let l = chol.l();
    // A = L⁻¹ K L⁻ᵀ by two triangular solves (K symmetric: L⁻¹ K L⁻ᵀ = L⁻¹ (L⁻¹ K)ᵀ), not an
    // explicit inverse and two products: this runs once per run, a quarter of its start-up.
    let singular = || BeamError::NotPositiveDefinite { matrix: "mass", why: "singular Cholesky factor".into() };
    let half = l.solve_lower_triangular(k).ok_or_else(singular)?;
    let mut a = l.solve_lower_triangular(&half.transpose()).ok_or_else(singular)?;
    a = 0.5 * (&a + a.transpose());
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    if let Some(&lowest) = order.first()
        && eig.eigenvalues[lowest] <= 0.0
    {
        return Err(BeamError::NotPositiveDefinite {
            matrix: "stiffness",
            why: format!("lowest eigenvalue ω² = {:.4e} (the arm is unstable in this state)", eig.eigenvalues[lowest]),
        });
    }
    // φ = L⁻ᵀ y for every eigenvector at once.
    let all_shapes = l.transpose().solve_upper_triangular(&eig.eigenvectors).ok_or_else(singular)?;
    let mut shapes = DMatrix::zeros(k.nrows(), order.len());
    for (col, &i) in order.iter().enumerate() {
        let mut phi = all_shapes.column(i).into_owned();
        // Sign convention: the largest component is positive, so runs are reproducible.
        if phi.iter().copied().max_by(|a, b| a.abs().total_cmp(&b.abs())).unwrap_or(0.0) < 0.0 {
            phi.neg_mut();
        }
        shapes.set_column(col, &phi);
    }
    let omegas_rad_s = order.iter().map(|&i| eig.eigenvalues[i].sqrt()).collect();
    Ok(ModalBasis { omegas_rad_s, shapes })
}

/// [`solve_generalized`] over the independent blocks of (K, M): DOFs coupled by a non-zero term
/// of either matrix, each block solved on its own and the modes merged in ascending order (ties
/// in block order). A string clamped at its hands falls apart into its overhangs and the spans
/// between hands, so the work is the blocks' n³, not the whole's; and two equal overhangs get
/// one mode each, not an arbitrary mix of the two that rounding picks.
pub(crate) fn solve_generalized_in_blocks(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Result<ModalBasis, BeamError> {
    let n = k.nrows();
    let mut modes: Vec<(f64, Vec<usize>, nalgebra::DVector<f64>)> = Vec::with_capacity(n);
    for block in coupled_blocks(k, m) {
        let pick = |a: &DMatrix<f64>| DMatrix::from_fn(block.len(), block.len(), |i, j| a[(block[i], block[j])]);
        let solved = solve_generalized(&pick(k), &pick(m))?;
        for (col, omega) in solved.omegas_rad_s.iter().enumerate() {
            modes.push((*omega, block.clone(), solved.shapes.column(col).into_owned()));
        }
    }
    modes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut shapes = DMatrix::zeros(n, modes.len());
    for (col, (_, rows, shape)) in modes.iter().enumerate() {
        for (&row, value) in rows.iter().zip(shape.iter()) {
            shapes[(row, col)] = *value;
        }
    }
    Ok(ModalBasis { omegas_rad_s: modes.iter().map(|m| m.0).collect(), shapes })
}

/// The DOFs of (K, M) in groups joined by a non-zero coupling in either matrix, each ascending,
/// the groups ordered by their first DOF.
fn coupled_blocks(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Vec<Vec<usize>> {
    let n = k.nrows();
    let mut root: Vec<usize> = (0..n).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for j in 0..n {
        for i in 0..j {
            if k[(i, j)] != 0.0 || m[(i, j)] != 0.0 {
                let (a, b) = (find(&mut root, i), find(&mut root, j));
                root[a.max(b)] = a.min(b);
            }
        }
    }
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut block_of_root = vec![usize::MAX; n];
    for i in 0..n {
        let r = find(&mut root, i);
        if block_of_root[r] == usize::MAX {
            block_of_root[r] = blocks.len();
            blocks.push(Vec::new());
        }
        blocks[block_of_root[r]].push(i);
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two springs k on masses m in series (ω² = (3 ∓ √5)/2 · k/m) beside one mass 4m on 9k
    /// (ω² = 9k/4m), uncoupled: three blocks' modes in ascending order, mass-normalised.
    #[test]
    fn blocks_give_the_whole_pencils_modes() {
        let (k, m) = (2.0, 3.0);
        let stiffness = DMatrix::from_row_slice(3, 3, &[2.0 * k, 0.0, -k, 0.0, 9.0 * k, 0.0, -k, 0.0, k]);
        let mass = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![m, 4.0 * m, m]));
        let modes = solve_generalized_in_blocks(&stiffness, &mass).unwrap();
        let s5 = 5.0_f64.sqrt();
        let exact = [(3.0 - s5) / 2.0 * k / m, 9.0 * k / (4.0 * m), (3.0 + s5) / 2.0 * k / m];
        for (omega, exact) in modes.omegas_rad_s.iter().zip(exact) {
            assert!((omega * omega / exact - 1.0).abs() < 1e-12, "{} vs {exact}", omega * omega);
        }
        let orthonormal = modes.shapes.transpose() * &mass * &modes.shapes;
        assert!((orthonormal - DMatrix::identity(3, 3)).amax() < 1e-12);
        assert_eq!(coupled_blocks(&stiffness, &mass), vec![vec![0, 2], vec![1]]);
    }
}
