//! Dense linear solves for the integrators' small systems, without allocation.

use nalgebra::{DMatrix, DVector};

use super::{Dynamics, IntegrateError};

/// Solves A x = b in place by Gaussian elimination with partial pivoting: `b` becomes x, `a`
/// is destroyed. `false` if A is singular. (nalgebra's LU allocates its permutation and its
/// result; this runs at every Newton iteration.) Column-oriented, as A is stored.
pub(crate) fn solve_in_place(a: &mut DMatrix<f64>, b: &mut DVector<f64>) -> bool {
    let n = b.len();
    let (a, b) = (a.as_mut_slice(), b.as_mut_slice());
    for k in 0..n {
        let column = &a[k * n..(k + 1) * n];
        let pivot = (k..n).max_by(|&i, &j| column[i].abs().total_cmp(&column[j].abs())).unwrap_or(k);
        let diagonal = column[pivot];
        if diagonal == 0.0 || !diagonal.is_finite() {
            return false;
        }
        if pivot != k {
            (0..n).for_each(|j| a.swap(j * n + k, j * n + pivot));
            b.swap(k, pivot);
        }
        // The multipliers replace column k below the diagonal.
        a[k * n + k + 1..(k + 1) * n].iter_mut().for_each(|l| *l /= diagonal);
        let (done, rest) = a.split_at_mut((k + 1) * n);
        let multipliers = &done[k * n + k + 1..];
        for column in rest.chunks_exact_mut(n) {
            let pivot_row = column[k];
            if pivot_row != 0.0 {
                column[k + 1..].iter_mut().zip(multipliers).for_each(|(x, l)| *x -= l * pivot_row);
            }
        }
        let bk = b[k];
        b[k + 1..].iter_mut().zip(multipliers).for_each(|(x, l)| *x -= l * bk);
    }
    for k in (0..n).rev() {
        b[k] /= a[k * n + k];
        let bk = b[k];
        b[..k].iter_mut().zip(&a[k * n..k * n + k]).for_each(|(x, u)| *x -= u * bk);
    }
    true
}

/// Buffers to solve M(t, x) ẍ = f(t, x, ẋ) at every stage without allocating.
#[derive(Debug, Clone, Default)]
pub(crate) struct AccelerationSolver {
    f: DVector<f64>,
    m: DMatrix<f64>,
}

impl AccelerationSolver {
    /// Writes ẍ into `out` (resized to the system if it is not).
    pub(crate) fn solve<S: Dynamics + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        out: &mut DVector<f64>,
    ) -> Result<(), IntegrateError> {
        let n = sys.dofs();
        if self.f.len() != n {
            (self.f, self.m) = (DVector::zeros(n), DMatrix::zeros(n, n));
        }
        if out.len() != n {
            *out = DVector::zeros(n);
        }
        if n == 0 {
            return Ok(());
        }
        sys.forces(t, x, v, &mut self.f);
        if sys.solve_mass(t, x, &self.f, out) {
            return Ok(());
        }
        sys.mass_matrix(t, x, &mut self.m);
        if !solve_in_place(&mut self.m, &mut self.f) {
            return Err(IntegrateError::SingularMatrix { t });
        }
        out.copy_from(&self.f);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_in_place_matches_a_known_solution_with_pivoting() {
        // A zero on the first pivot forces a row swap.
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0]);
        let x = DVector::from_column_slice(&[1.0, -2.0, 3.0]);
        let mut b = &a * &x;
        let mut work = a.clone();
        assert!(solve_in_place(&mut work, &mut b));
        assert!((b - x).norm() < 1e-14);
        let mut singular = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(!solve_in_place(&mut singular, &mut DVector::from_column_slice(&[1.0, 1.0])));
    }

    #[test]
    fn solve_in_place_agrees_with_nalgebra_lu_on_a_larger_unsymmetric_matrix() {
        let n = 12;
        let a = DMatrix::from_fn(n, n, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0 + if i == j { 0.5 } else { 0.0 });
        let b = DVector::from_fn(n, |i, _| (i as f64).sin());
        let expected = a.clone().lu().solve(&b).expect("regular");
        let (mut work, mut x) = (a.clone(), b.clone());
        assert!(solve_in_place(&mut work, &mut x));
        assert!((&x - &expected).norm() < 1e-10 * expected.norm());
    }
}
