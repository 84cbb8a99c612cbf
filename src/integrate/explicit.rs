//! Explicit integrators. Each solves M ẍ = f once per stage.

use nalgebra::DVector;

use super::{AccelerationSolver, Dynamics, IntegrateError, Integrator, State, finish_step};

/// Semi-implicit Euler: ẋ_{n+1} = ẋ_n + h ẍ(x_n, ẋ_n), x_{n+1} = x_n + h ẋ_{n+1}.
/// Symplectic; stable on an undamped mode while ωh ≤ 2.
#[derive(Debug, Clone, Copy, Default)]
pub struct SymplecticEuler;

/// Classical fourth-order Runge–Kutta on (x, ẋ). Stable on an undamped mode while ωh ≲ 2√2.
#[derive(Debug, Clone, Default)]
pub struct Rk4 {
    /// Stage buffers, kept between steps (the step allocates nothing).
    work: Rk4Work,
}

#[derive(Debug, Clone, Default)]
struct Rk4Work {
    solver: AccelerationSolver,
    /// Stage positions and velocities.
    xs: DVector<f64>,
    vs: DVector<f64>,
    /// Stage accelerations k2, k3, k4.
    k: [DVector<f64>; 3],
    /// Stage velocities v2, v3, v4 (the position slopes).
    v: [DVector<f64>; 3],
}

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
        finish_step(sys, s)?;
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
        finish_step(sys, s)?;
        s.refresh_acceleration(sys)
    }
}

impl Integrator for Rk4 {
    fn name(&self) -> &'static str {
        "rk4"
    }

    fn step(&mut self, sys: &dyn Dynamics, s: &mut State, h: f64) -> Result<(), IntegrateError> {
        let n = sys.dofs();
        let w = &mut self.work;
        if w.xs.len() != n {
            let z = DVector::zeros(n);
            (w.xs, w.vs) = (z.clone(), z.clone());
            w.k = [z.clone(), z.clone(), z.clone()];
            w.v = [z.clone(), z.clone(), z];
        }
        // Stage i + 1 starts from stage i's slopes, a fraction of the step along them.
        for (stage, (fraction, t)) in
            [(0.5, s.t + 0.5 * h), (0.5, s.t + 0.5 * h), (1.0, s.t + h)].into_iter().enumerate()
        {
            let (slope_x, slope_v) = if stage == 0 { (&s.v, &s.a) } else { (&w.v[stage - 1], &w.k[stage - 1]) };
            for i in 0..n {
                w.xs[i] = s.x[i] + fraction * h * slope_x[i];
                w.vs[i] = s.v[i] + fraction * h * slope_v[i];
            }
            w.v[stage].copy_from(&w.vs);
            w.solver.solve(sys, t, &w.xs, &w.vs, &mut w.k[stage])?;
        }
        let c = h / 6.0;
        for i in 0..n {
            s.x[i] += c * (s.v[i] + 2.0 * w.v[0][i] + 2.0 * w.v[1][i] + w.v[2][i]);
            s.v[i] += c * (s.a[i] + 2.0 * w.k[0][i] + 2.0 * w.k[1][i] + w.k[2][i]);
        }
        s.t += h;
        finish_step(sys, s)?;
        w.solver.solve(sys, s.t, &s.x, &s.v, &mut s.a)
    }
}
