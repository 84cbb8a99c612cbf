//! The generalized-α family in the form of Arnold & Brüls (2007): the equations of motion hold
//! exactly at t_{n+1}; a pseudo-acceleration `a` carries the α-weighting,
//!
//! ```text
//! (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) ẍ_{n+1} + α_f ẍ_n
//! x_{n+1} = x_n + h ẋ_n + h² (½ − β) a_n + h² β a_{n+1}
//! ẋ_{n+1} = ẋ_n + h (1 − γ) a_n + h γ a_{n+1}
//! ```
//!
//! Chung–Hulbert, HHT-α (α_m = 0, α_f = −α) and Newmark (α_m = α_f = 0) are parameter choices;
//! on linear problems this form has the same spectral properties as the originals.

use nalgebra::{DMatrix, DVector};

use super::{Dynamics, IntegrateError, Integrator, State, finish_step, solve_in_place};

/// Generalized-α, HHT-α or Newmark, solved by Newton's method on ẍ_{n+1}.
#[derive(Debug, Clone)]
pub struct GeneralizedAlpha {
    name: &'static str,
    alpha_m: f64,
    alpha_f: f64,
    beta: f64,
    gamma: f64,
    /// Relative tolerance on the Newton correction of ẍ.
    pub tolerance: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
    /// Whether `work.a_n` holds the pseudo-acceleration of the last step (else ẍ is used).
    has_history: bool,
    /// `has_history` and `work.a_n` at the last checkpoint.
    saved_history: (bool, DVector<f64>),
    /// Buffers reused from step to step.
    work: Workspace,
}

/// The step's matrices and vectors, kept between steps: the step allocates nothing (on a
/// 3-mode arm an allocation costs more than the arithmetic it serves).
#[derive(Debug, Clone, Default)]
struct Workspace {
    m: DMatrix<f64>,
    kt: DMatrix<f64>,
    ct: DMatrix<f64>,
    jacobian: DMatrix<f64>,
    f: DVector<f64>,
    a_n: DVector<f64>,
    a_rest: DVector<f64>,
    x_base: DVector<f64>,
    v_base: DVector<f64>,
    acc: DVector<f64>,
    /// The last step's local error estimate in x.
    error: DVector<f64>,
    x1: DVector<f64>,
    v1: DVector<f64>,
}

impl Workspace {
    fn resize(&mut self, n: usize) {
        if self.f.len() == n && self.m.nrows() == n {
            return;
        }
        let (m, v) = (DMatrix::zeros(n, n), DVector::zeros(n));
        *self = Workspace {
            kt: m.clone(),
            ct: m.clone(),
            jacobian: m.clone(),
            m,
            f: v.clone(),
            a_n: v.clone(),
            a_rest: v.clone(),
            x_base: v.clone(),
            v_base: v.clone(),
            acc: v.clone(),
            error: v.clone(),
            x1: v.clone(),
            v1: v,
        };
    }
}

impl GeneralizedAlpha {
    fn new(name: &'static str, alpha_m: f64, alpha_f: f64, beta: f64, gamma: f64) -> Self {
        GeneralizedAlpha {
            name,
            alpha_m,
            alpha_f,
            beta,
            gamma,
            tolerance: 1e-10,
            max_iterations: 25,
            has_history: false,
            saved_history: (false, DVector::zeros(0)),
            work: Workspace::default(),
        }
    }

    /// Chung–Hulbert generalized-α with spectral radius `rho_inf` ∈ [0, 1] at infinite ωh.
    pub fn chung_hulbert(rho_inf: f64) -> Result<Self, IntegrateError> {
        if !(0.0..=1.0).contains(&rho_inf) {
            return Err(IntegrateError::InvalidParameter { name: "rho_inf", value: rho_inf, allowed: "0 ..= 1" });
        }
        let alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let alpha_f = rho_inf / (rho_inf + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
        Ok(Self::new("generalized-alpha", alpha_m, alpha_f, beta, gamma))
    }

    /// Hilber–Hughes–Taylor with `alpha` ∈ [−1/3, 0] (0 is average-acceleration Newmark).
    pub fn hht(alpha: f64) -> Result<Self, IntegrateError> {
        if !(-1.0 / 3.0..=0.0).contains(&alpha) {
            return Err(IntegrateError::InvalidParameter { name: "alpha", value: alpha, allowed: "-1/3 ..= 0" });
        }
        Ok(Self::new("hht", 0.0, -alpha, 0.25 * (1.0 - alpha).powi(2), 0.5 - alpha))
    }

    /// Newmark-β; average acceleration is β = 1/4, γ = 1/2; linear acceleration β = 1/6.
    pub fn newmark(beta: f64, gamma: f64) -> Result<Self, IntegrateError> {
        if !(beta > 0.0 && beta <= 0.5) {
            return Err(IntegrateError::InvalidParameter { name: "beta", value: beta, allowed: "0 < beta <= 1/2" });
        }
        if !(0.5..=1.0).contains(&gamma) {
            return Err(IntegrateError::InvalidParameter { name: "gamma", value: gamma, allowed: "1/2 ..= 1" });
        }
        Ok(Self::new("newmark", 0.0, 0.0, beta, gamma))
    }

    /// Average-acceleration Newmark (trapezoidal rule): unconditionally stable, no damping.
    pub fn average_acceleration() -> Self {
        Self::new("newmark", 0.0, 0.0, 0.25, 0.5)
    }

    /// c in the local error estimate e ≈ c h² (a_{n+1} − a_n) of x_{n+1}.
    ///
    /// The pseudo-acceleration lags ẍ by a shift δ = α_m − α_f of a step, a_n ≈ ẍ(t_n + δh), so
    /// x_{n+1} = x_n + h ẋ_n + h²[(½ − β) a_n + β a_{n+1}] = … + h³ (β + δ/2) x⃛ + O(h⁴), against
    /// the exact h³/6 x⃛, and a_{n+1} − a_n ≈ h x⃛: c = β + δ/2 − 1/6 (β − 1/6 for Newmark).
    fn error_coefficient(&self) -> f64 {
        self.beta + 0.5 * (self.alpha_m - self.alpha_f) - 1.0 / 6.0
    }
}

impl Integrator for GeneralizedAlpha {
    fn name(&self) -> &'static str {
        self.name
    }

    fn reset(&mut self) {
        self.has_history = false;
    }

    fn local_error(&self) -> Option<&DVector<f64>> {
        self.has_history.then_some(&self.work.error)
    }

    fn checkpoint(&mut self) {
        self.saved_history.0 = self.has_history;
        self.saved_history.1.clone_from(&self.work.a_n);
    }

    fn rollback(&mut self) {
        self.has_history = self.saved_history.0;
        self.work.a_n.clone_from(&self.saved_history.1);
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        let n = sys.dofs();
        // The first-order states' positions are unused: left out of the convergence test's scale.
        let second_order = n - sys.first_order_dofs().min(n);
        let error_factor = self.error_coefficient() * h * h;
        let w = &mut self.work;
        w.resize(n);
        if !self.has_history {
            w.a_n.copy_from(&s.a);
        }
        let t1 = s.t + h;
        let ratio = (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        // x_{n+1}, ẋ_{n+1} and a_{n+1} are affine in the unknown ẍ_{n+1}:
        // a₁ = ratio ẍ + a_rest, x₁ = x_base + h²β a₁, ẋ₁ = v_base + hγ a₁.
        let (dx_da1, dv_da1) = (h * h * self.beta, h * self.gamma);
        let (dx_dacc, dv_dacc) = (dx_da1 * ratio, dv_da1 * ratio);
        // One pass over the coordinates per update, on slices: n is a few here, and nalgebra's
        // per-call set-up would cost more than the arithmetic.
        let (c_a, c_an) = (self.alpha_f / (1.0 - self.alpha_m), -self.alpha_m / (1.0 - self.alpha_m));
        let (c_xa, c_va) = (h * h * (0.5 - self.beta), h * (1.0 - self.gamma));
        for i in 0..n {
            let a_n = w.a_n[i];
            w.a_rest[i] = c_a * s.a[i] + c_an * a_n;
            w.x_base[i] = s.x[i] + h * s.v[i] + c_xa * a_n;
            w.v_base[i] = s.v[i] + c_va * a_n;
        }
        w.acc.copy_from(&s.a);
        let mut residual_norm = f64::INFINITY;
        for _ in 0..self.max_iterations {
            // a₁, x₁, ẋ₁ at this iterate.
            for i in 0..n {
                let a1 = w.a_rest[i] + ratio * w.acc[i];
                w.x1[i] = w.x_base[i] + dx_da1 * a1;
                w.v1[i] = w.v_base[i] + dv_da1 * a1;
            }
            sys.mass_matrix(t1, &w.x1, &mut w.m);
            sys.forces(t1, &w.x1, &w.v1, &mut w.f);
            sys.tangents(t1, &w.x1, &w.v1, &mut w.kt, &mut w.ct);
            // residual = M ẍ − f, into f; the iteration matrix M + hγ' C_t + h²β' K_t.
            let (m, ct, kt) = (w.m.as_slice(), w.ct.as_slice(), w.kt.as_slice());
            for (i, j) in w.jacobian.as_mut_slice().iter_mut().enumerate() {
                *j = m[i] + dv_dacc * ct[i] + dx_dacc * kt[i];
            }
            for (column, acc) in m.chunks_exact(n).zip(w.acc.iter()) {
                w.f.iter_mut().zip(column).for_each(|(f, mij)| *f -= mij * acc);
            }
            w.f.neg_mut();
            // The correction overwrites the residual.
            if !solve_in_place(&mut w.jacobian, &mut w.f) {
                return Err(IntegrateError::SingularMatrix { t: t1 });
            }
            let (mut correction_sq, mut acc_sq, mut x_sq) = (0.0, 0.0, 0.0);
            for i in 0..n {
                w.acc[i] -= w.f[i];
                correction_sq += w.f[i] * w.f[i];
                acc_sq += w.acc[i] * w.acc[i];
                if i < second_order {
                    x_sq += w.x1[i] * w.x1[i];
                }
            }
            residual_norm = correction_sq.sqrt();
            // Converged when the correction is small against the acceleration, or when what it
            // would still move the coordinates is (an arm at rest on a pad has ẍ ≈ 0).
            let small_acc = residual_norm <= self.tolerance * acc_sq.sqrt();
            let small_move = dx_dacc * residual_norm <= self.tolerance * x_sq.sqrt().max(1e-300);
            if sys.is_linear() || small_acc || small_move || residual_norm == 0.0 {
                for i in 0..n {
                    let a1 = w.a_rest[i] + ratio * w.acc[i];
                    w.error[i] = error_factor * (a1 - w.a_n[i]);
                    w.a_n[i] = a1;
                    s.x[i] = w.x_base[i] + dx_da1 * a1;
                    s.v[i] = w.v_base[i] + dv_da1 * a1;
                }
                s.a.copy_from(&w.acc);
                s.t = t1;
                self.has_history = true;
                return finish_step(sys, s);
            }
        }
        Err(IntegrateError::NoConvergence { t: t1, residual: residual_norm })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ẍ = −x, one step from the exact solution (with the pseudo-acceleration at its steady
    /// lag): the step's true error over its estimate tends to 1 as h → 0.
    #[test]
    fn local_error_estimate_matches_the_true_local_error() {
        struct Oscillator;
        impl Dynamics for Oscillator {
            fn dofs(&self) -> usize {
                1
            }
            fn mass_matrix(&self, _t: f64, _x: &DVector<f64>, m: &mut DMatrix<f64>) {
                m[(0, 0)] = 1.0;
            }
            fn forces(&self, _t: f64, x: &DVector<f64>, _v: &DVector<f64>, f: &mut DVector<f64>) {
                f[0] = -x[0];
            }
            fn tangents(
                &self,
                _t: f64,
                _x: &DVector<f64>,
                _v: &DVector<f64>,
                k: &mut DMatrix<f64>,
                c: &mut DMatrix<f64>,
            ) {
                k[(0, 0)] = 1.0;
                c[(0, 0)] = 0.0;
            }
            fn is_linear(&self) -> bool {
                true
            }
        }
        for integrator in [GeneralizedAlpha::chung_hulbert(0.8).unwrap(), GeneralizedAlpha::hht(-0.1).unwrap()] {
            let mut ratios = Vec::new();
            for h in [1e-2, 3e-3, 1e-3] {
                let mut ga = integrator.clone();
                let t = 1.0;
                let lag = ga.alpha_m - ga.alpha_f;
                ga.work.resize(1);
                ga.work.a_n[0] = -(t + lag * h).cos();
                ga.has_history = true;
                let v = |x: f64| DVector::from_element(1, x);
                let mut state = State { t, x: v(t.cos()), v: v(-t.sin()), a: v(-t.cos()) };
                ga.step(&Oscillator, &mut state, h).unwrap();
                let true_error = state.x[0] - (t + h).cos();
                ratios.push(true_error / ga.local_error().unwrap()[0]);
            }
            // Converging on 1 at first order in h.
            assert!((ratios[2] - 1.0).abs() < 0.02, "{} ratios {ratios:?}", integrator.name);
            assert!((ratios[2] - 1.0).abs() < (ratios[0] - 1.0).abs(), "{ratios:?}");
        }
    }
}
