//! Shape functions of the planar frame element and the quadrature used to integrate them.
//!
//! Local DOF order on an element of length `h`: `[u_a, v_a, φ_a, u_b, v_b, φ_b]`, with `u` the
//! axial stretch, `v` the transverse deflection and `φ = ∂v/∂x` the section rotation. Axial
//! interpolation is linear, transverse is Hermite cubic (exact for a uniform Euler–Bernoulli
//! beam under nodal loads).

/// Local DOFs per element.
pub const ELEMENT_DOFS: usize = 6;

/// Gauss–Legendre points on [0, 1] and their weights: 4 points integrate degree 7 exactly, which
/// covers every product formed here (the highest is a quadratic axial force times two
/// quadratic slopes, degree 6).
pub const GAUSS_4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// Shape-function rows at one point of an element, each mapping the 6 local DOFs.
#[derive(Debug, Clone, Copy)]
pub struct ShapeRows {
    /// Axial displacement u.
    pub u: [f64; ELEMENT_DOFS],
    /// Axial strain du/dx, 1/m.
    pub du: [f64; ELEMENT_DOFS],
    /// Transverse deflection v.
    pub v: [f64; ELEMENT_DOFS],
    /// Slope dv/dx.
    pub dv: [f64; ELEMENT_DOFS],
    /// Curvature d²v/dx², 1/m.
    pub ddv: [f64; ELEMENT_DOFS],
}

/// Shape rows at local coordinate `xi` ∈ [0, 1] of an element of length `h_m`.
pub fn shape_rows(xi: f64, h_m: f64) -> ShapeRows {
    let (x, h) = (xi, h_m);
    let (x2, x3) = (x * x, x * x * x);
    let hermite = [1.0 - 3.0 * x2 + 2.0 * x3, h * (x - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, h * (x3 - x2)];
    let d_hermite = [(-6.0 * x + 6.0 * x2) / h, 1.0 - 4.0 * x + 3.0 * x2, (6.0 * x - 6.0 * x2) / h, 3.0 * x2 - 2.0 * x];
    let dd_hermite =
        [(-6.0 + 12.0 * x) / (h * h), (-4.0 + 6.0 * x) / h, (6.0 - 12.0 * x) / (h * h), (6.0 * x - 2.0) / h];
    let spread = |c: [f64; 4]| [0.0, c[0], c[1], 0.0, c[2], c[3]];
    ShapeRows {
        u: [1.0 - x, 0.0, 0.0, x, 0.0, 0.0],
        du: [-1.0 / h, 0.0, 0.0, 1.0 / h, 0.0, 0.0],
        v: spread(hermite),
        dv: spread(d_hermite),
        ddv: spread(dd_hermite),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_reproduces_nodal_values_and_a_cubic() {
        let h = 0.7;
        let ends = [shape_rows(0.0, h), shape_rows(1.0, h)];
        for (node, rows) in ends.iter().enumerate() {
            for dof in 0..ELEMENT_DOFS {
                let is = |k: usize| if dof == 3 * node + k { 1.0 } else { 0.0 };
                assert!((rows.u[dof] - is(0)).abs() < 1e-15);
                assert!((rows.v[dof] - is(1)).abs() < 1e-15);
                assert!((rows.dv[dof] - is(2)).abs() < 1e-14);
            }
        }
        // v(x) = x^3 on [0, h]: nodal DOFs (0, 0, h^3, 3h^2) must reproduce it and v'' = 6x.
        let dofs = [0.0, 0.0, 0.0, 0.0, h * h * h, 3.0 * h * h];
        let xi = 0.37;
        let r = shape_rows(xi, h);
        let dot = |row: [f64; 6]| row.iter().zip(dofs).map(|(a, b)| a * b).sum::<f64>();
        assert!((dot(r.v) - (xi * h).powi(3)).abs() < 1e-14);
        assert!((dot(r.ddv) - 6.0 * xi * h).abs() < 1e-13);
    }
}
