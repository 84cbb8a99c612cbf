//! Dense products over the elastic coordinates, as plain loops over nalgebra's column-major
//! storage: they run several times a step on matrices of a few rows, where nalgebra's
//! general-size kernels spend more on set-up than on arithmetic.

use nalgebra::{DMatrix, DVector};

/// xᵀ y.
pub(super) fn dot(x: &DVector<f64>, y: &[f64]) -> f64 {
    x.as_slice().iter().zip(y).map(|(a, b)| a * b).sum()
}

/// xᵀ A y for a square A. Up to [`STACK_DOFS`] coordinates as x · (A y), A y summed column by
/// column on the stack: those sums run down a column and vectorise, where dotting each column
/// with x is a chain of dependent additions the compiler may not reorder.
pub(super) fn bilinear(a: &DMatrix<f64>, x: &DVector<f64>, y: &DVector<f64>) -> f64 {
    let (x, n) = (x.as_slice(), x.len());
    let columns = a.as_slice().chunks_exact(n.max(1));
    if n > STACK_DOFS {
        return columns
            .zip(y.as_slice())
            .map(|(column, yj)| yj * column.iter().zip(x).map(|(aij, xi)| aij * xi).sum::<f64>())
            .sum();
    }
    let mut product = [0.0; STACK_DOFS];
    let product = &mut product[..n];
    for (column, yj) in columns.zip(y.as_slice()) {
        product.iter_mut().zip(column).for_each(|(p, aij)| *p += aij * yj);
    }
    product.iter().zip(x).map(|(a, b)| a * b).sum()
}

/// Coordinates up to which [`bilinear`] works on the stack (a modal arm and string).
const STACK_DOFS: usize = 32;

/// A x for a square A.
pub(super) fn product(a: &DMatrix<f64>, x: &DVector<f64>) -> DVector<f64> {
    let mut out = DVector::zeros(x.len());
    add_product(out.as_mut_slice(), 1.0, a, x.as_slice());
    out
}

/// f += α A x for a square A.
pub(super) fn add_product(f: &mut [f64], alpha: f64, a: &DMatrix<f64>, x: &[f64]) {
    for (column, xj) in a.as_slice().chunks_exact(f.len().max(1)).zip(x) {
        let scale = alpha * xj;
        f.iter_mut().zip(column).for_each(|(fi, aij)| *fi += scale * aij);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_products_are_the_matrix_algebra() {
        for n in [3, 40] {
            let a = DMatrix::from_fn(n, n, |i, j| (i as f64 + 1.0) * 0.5 - j as f64 * 0.25);
            let x = DVector::from_fn(n, |i, _| (i as f64).sin());
            let y = DVector::from_fn(n, |i, _| 1.0 + (i as f64).cos());
            let exact = x.dot(&(&a * &y));
            assert!((bilinear(&a, &x, &y) - exact).abs() <= 1e-12 * exact.abs().max(1.0), "n = {n}");
            assert!((product(&a, &y) - &a * &y).amax() < 1e-12);
        }
    }
}
