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

use super::{Dynamics, IntegrateError, Integrator, State, check_finite};

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
    pseudo_acceleration: Option<DVector<f64>>,
    /// Buffers reused from step to step.
    work: Option<Workspace>,
}

/// The Newton iteration's matrices and vectors, kept between steps (no allocation per iteration).
#[derive(Debug, Clone)]
struct Workspace {
    m: DMatrix<f64>,
    kt: DMatrix<f64>,
    ct: DMatrix<f64>,
    jacobian: DMatrix<f64>,
    f: DVector<f64>,
    a1: DVector<f64>,
    x1: DVector<f64>,
    v1: DVector<f64>,
}

impl Workspace {
    fn new(n: usize) -> Self {
        let (m, v) = (DMatrix::zeros(n, n), DVector::zeros(n));
        Workspace {
            kt: m.clone(),
            ct: m.clone(),
            jacobian: m.clone(),
            m,
            f: v.clone(),
            a1: v.clone(),
            x1: v.clone(),
            v1: v,
        }
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
            pseudo_acceleration: None,
            work: None,
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
}

impl Integrator for GeneralizedAlpha {
    fn name(&self) -> &'static str {
        self.name
    }

    fn reset(&mut self) {
        self.pseudo_acceleration = None;
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        let n = sys.dofs();
        let a_n = self.pseudo_acceleration.take().unwrap_or_else(|| s.a.clone());
        let t1 = s.t + h;
        let ratio = (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        // x_{n+1}, ẋ_{n+1} and a_{n+1} are affine in the unknown ẍ_{n+1}:
        // a₁ = ratio ẍ + a_rest, x₁ = x_base + h²β a₁, ẋ₁ = v_base + hγ a₁.
        let a_rest = (self.alpha_f * &s.a - self.alpha_m * &a_n) / (1.0 - self.alpha_m);
        let dx_dacc = h * h * self.beta * ratio;
        let dv_dacc = h * self.gamma * ratio;
        let x_base = &s.x + h * &s.v + h * h * (0.5 - self.beta) * &a_n;
        let v_base = &s.v + h * (1.0 - self.gamma) * &a_n;

        let w = self.work.get_or_insert_with(|| Workspace::new(n));
        if w.f.len() != n {
            *w = Workspace::new(n);
        }
        let mut acc = s.a.clone();
        let mut residual_norm = f64::INFINITY;
        for _ in 0..self.max_iterations {
            // a₁, x₁, ẋ₁ at this iterate, in place.
            w.a1.copy_from(&a_rest);
            w.a1.axpy(ratio, &acc, 1.0);
            w.x1.copy_from(&x_base);
            w.x1.axpy(h * h * self.beta, &w.a1, 1.0);
            w.v1.copy_from(&v_base);
            w.v1.axpy(h * self.gamma, &w.a1, 1.0);
            sys.mass_matrix(t1, &w.x1, &mut w.m);
            sys.forces(t1, &w.x1, &w.v1, &mut w.f);
            // residual = M ẍ − f, into f.
            w.f.gemv(1.0, &w.m, &acc, -1.0);
            sys.tangents(t1, &w.x1, &w.v1, &mut w.kt, &mut w.ct);
            w.jacobian.copy_from(&w.m);
            w.jacobian.zip_zip_apply(&w.ct, &w.kt, |j, c, k| *j += dv_dacc * c + dx_dacc * k);
            let delta = w.jacobian.clone().lu().solve(&w.f).ok_or(IntegrateError::SingularMatrix { t: t1 })?;
            acc -= &delta;
            residual_norm = delta.norm();
            // Converged when the correction is small against the acceleration, or when what it
            // would still move the coordinates is (an arm at rest on a pad has ẍ ≈ 0).
            let small_acc = residual_norm <= self.tolerance * acc.norm();
            let small_move = dx_dacc * residual_norm <= self.tolerance * w.x1.norm().max(1e-300);
            if sys.is_linear() || small_acc || small_move || residual_norm == 0.0 {
                let mut a1 = a_rest;
                a1.axpy(ratio, &acc, 1.0);
                s.x = x_base;
                s.x.axpy(h * h * self.beta, &a1, 1.0);
                s.v = v_base;
                s.v.axpy(h * self.gamma, &a1, 1.0);
                s.a = acc;
                s.t = t1;
                self.pseudo_acceleration = Some(a1);
                return check_finite(s);
            }
        }
        Err(IntegrateError::NoConvergence { t: t1, residual: residual_norm })
    }
}
