//! Explicit integrators. Each solves M ẍ = f once per stage.

use nalgebra::DVector;

use super::{Dynamics, IntegrateError, Integrator, State, check_finite, solve_acceleration};

/// Semi-implicit Euler: ẋ_{n+1} = ẋ_n + h ẍ(x_n, ẋ_n), x_{n+1} = x_n + h ẋ_{n+1}.
/// Symplectic; stable on an undamped mode while ωh ≤ 2.
#[derive(Debug, Clone, Copy, Default)]
pub struct SymplecticEuler;

/// Classical fourth-order Runge–Kutta on (x, ẋ). Stable on an undamped mode while ωh ≲ 2√2.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rk4;

/// Forward Euler: amplifies every undamped oscillation by √(1 + ω²h²) per step.
#[derive(Debug, Clone, Copy, Default)]
pub struct ExplicitEuler;

impl Integrator for SymplecticEuler {
    fn name(&self) -> &'static str {
        "symplectic-euler"
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        s.v += h * &s.a;
        s.x += h * &s.v;
        s.t += h;
        check_finite(s)?;
        s.refresh_acceleration(sys)
    }
}

impl Integrator for ExplicitEuler {
    fn name(&self) -> &'static str {
        "explicit-euler"
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        s.x += h * &s.v;
        s.v += h * &s.a;
        s.t += h;
        check_finite(s)?;
        s.refresh_acceleration(sys)
    }
}

impl Integrator for Rk4 {
    fn name(&self) -> &'static str {
        "rk4"
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        let n = sys.dofs();
        let stage = |t: f64, x: &DVector<f64>, v: &DVector<f64>| -> Result<DVector<f64>, IntegrateError> {
            let mut a = DVector::zeros(n);
            solve_acceleration(sys, t, x, v, &mut a)?;
            Ok(a)
        };
        let (x0, v0, t0) = (&s.x, &s.v, s.t);
        let (k1x, k1v) = (v0.clone(), s.a.clone());
        let (x2, v2) = (x0 + 0.5 * h * &k1x, v0 + 0.5 * h * &k1v);
        let k2v = stage(t0 + 0.5 * h, &x2, &v2)?;
        let (x3, v3) = (x0 + 0.5 * h * &v2, v0 + 0.5 * h * &k2v);
        let k3v = stage(t0 + 0.5 * h, &x3, &v3)?;
        let (x4, v4) = (x0 + h * &v3, v0 + h * &k3v);
        let k4v = stage(t0 + h, &x4, &v4)?;
        s.x = x0 + (h / 6.0) * (&k1x + 2.0 * &v2 + 2.0 * &v3 + &v4);
        s.v = v0 + (h / 6.0) * (&k1v + 2.0 * &k2v + 2.0 * &k3v + &k4v);
        s.t = t0 + h;
        check_finite(s)?;
        s.refresh_acceleration(sys)
    }
}
