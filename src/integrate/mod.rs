//! Time integrators for second-order systems M(t, x) ẍ = f(t, x, ẋ), behind one trait. A
//! system may end in a block of first-order states (an actuator's pressures and spool), carried
//! as rates of coordinates whose positions are unused ([`Dynamics::first_order_dofs`]): every
//! integrator then advances them with its velocity update, the implicit ones in the same Newton
//! iteration.
//!
//! The implicit family ([`GeneralizedAlpha`]: Chung–Hulbert generalized-α, HHT-α and Newmark)
//! is the default; the explicit ones ([`SymplecticEuler`], [`Rk4`], [`ExplicitEuler`]) exist to
//! compare cost and to show where they fail. Steps are
//! chosen by the caller, fixed or controlled by the implicit methods' local error estimate
//! ([`StepControl`]).

mod alpha;
mod control;
mod dense;
mod explicit;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use alpha::GeneralizedAlpha;
pub use control::StepControl;
pub(crate) use dense::{AccelerationSolver, solve_in_place};
pub use explicit::{ExplicitEuler, Rk4, SymplecticEuler};

/// A mechanical system in generalized coordinates: M(t, x) ẍ = f(t, x, ẋ).
pub trait Dynamics {
    /// Number of generalized coordinates.
    fn dofs(&self) -> usize;
    /// Writes the generalized mass matrix M(t, x) into `m`.
    fn mass_matrix(&self, t: f64, x: &DVector<f64>, m: &mut DMatrix<f64>);
    /// Writes every generalized force except inertia, f(t, x, ẋ), into `f`.
    fn forces(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>, f: &mut DVector<f64>);
    /// Writes the tangents K_t = −∂f/∂x and C_t = −∂f/∂ẋ. The default differentiates
    /// [`Self::forces`] numerically; override with exact tangents where they are cheap.
    fn tangents(&self, t: f64, x: &DVector<f64>, v: &DVector<f64>, k: &mut DMatrix<f64>, c: &mut DMatrix<f64>) {
        finite_difference_tangents(self, t, x, v, k, c);
    }
    /// Solves M(t, x) `out` = `rhs` where the system knows a cheaper way than factorising M
    /// (a constant M inverted once); `false` to let the caller factorise.
    fn solve_mass(&self, _t: f64, _x: &DVector<f64>, _rhs: &DVector<f64>, _out: &mut DVector<f64>) -> bool {
        false
    }
    /// True when f is affine in (x, ẋ) and M is constant, so that one Newton iteration with the
    /// exact tangents solves an implicit step exactly.
    fn is_linear(&self) -> bool {
        false
    }
    /// How many of the last coordinates are first-order states z (ż = g(t, x, ẋ)): carried in
    /// ẋ, with ẍ their rate and a unit mass; their x is unused (no force depends on it) and is
    /// held at zero. Each integrator's velocity update then advances them: the implicit methods
    /// solve them in the same Newton iteration as the second-order coordinates.
    fn first_order_dofs(&self) -> usize {
        0
    }
}

/// Central-difference tangents of `sys.forces`.
pub fn finite_difference_tangents<S: Dynamics + ?Sized>(
    sys: &S,
    t: f64,
    x: &DVector<f64>,
    v: &DVector<f64>,
    k: &mut DMatrix<f64>,
    c: &mut DMatrix<f64>,
) {
    let n = sys.dofs();
    let (mut fp, mut fm) = (DVector::zeros(n), DVector::zeros(n));
    let mut xp = x.clone();
    let mut vp = v.clone();
    for j in 0..n {
        let h = 1e-7 * x[j].abs().max(1e-3);
        xp[j] = x[j] + h;
        sys.forces(t, &xp, v, &mut fp);
        xp[j] = x[j] - h;
        sys.forces(t, &xp, v, &mut fm);
        xp[j] = x[j];
        k.set_column(j, &((&fm - &fp) / (2.0 * h)));
        let h = 1e-7 * v[j].abs().max(1e-3);
        vp[j] = v[j] + h;
        sys.forces(t, x, &vp, &mut fp);
        vp[j] = v[j] - h;
        sys.forces(t, x, &vp, &mut fm);
        vp[j] = v[j];
        c.set_column(j, &((&fm - &fp) / (2.0 * h)));
    }
}

/// The state an integrator advances: time, coordinates, velocities and accelerations.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time, s.
    pub t: f64,
    /// Generalized coordinates x.
    pub x: DVector<f64>,
    /// Generalized velocities ẋ.
    pub v: DVector<f64>,
    /// Generalized accelerations ẍ, consistent with the equations of motion at (t, x, ẋ).
    pub a: DVector<f64>,
}

impl State {
    /// A state at (t, x, ẋ) whose acceleration solves M ẍ = f.
    pub fn consistent<S: Dynamics + ?Sized>(
        sys: &S,
        t: f64,
        x: DVector<f64>,
        v: DVector<f64>,
    ) -> Result<Self, IntegrateError> {
        let mut a = DVector::zeros(sys.dofs());
        solve_acceleration(sys, t, &x, &v, &mut a)?;
        Ok(State { t, x, v, a })
    }

    /// Recomputes the acceleration after x or ẋ was changed from outside (an impulse).
    pub fn refresh_acceleration<S: Dynamics + ?Sized>(&mut self, sys: &S) -> Result<(), IntegrateError> {
        solve_acceleration(sys, self.t, &self.x, &self.v, &mut self.a)
    }
}

/// Solves M(t, x) ẍ = f(t, x, ẋ) for ẍ (once; the integrators keep an [`AccelerationSolver`]).
pub fn solve_acceleration<S: Dynamics + ?Sized>(
    sys: &S,
    t: f64,
    x: &DVector<f64>,
    v: &DVector<f64>,
    a: &mut DVector<f64>,
) -> Result<(), IntegrateError> {
    AccelerationSolver::default().solve(sys, t, x, v, a)
}

/// What went wrong in a step.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IntegrateError {
    /// The mass or iteration matrix could not be factorised.
    #[error("singular matrix at t = {t} s")]
    SingularMatrix { t: f64 },
    /// Newton's iteration did not converge.
    #[error("Newton iteration did not converge at t = {t} s (residual {residual:.3e})")]
    NoConvergence { t: f64, residual: f64 },
    /// The state blew up (NaN or infinity): the step is beyond the method's stability limit.
    #[error("state is no longer finite at t = {t} s: the step is beyond the method's stability limit")]
    NonFinite { t: f64 },
    /// A parameter of the method outside its range.
    #[error("integrator parameter `{name}` = {value} is invalid: allowed {allowed}")]
    InvalidParameter { name: &'static str, value: f64, allowed: &'static str },
}

/// One time-stepping method.
pub trait Integrator: Send {
    /// Short name, as written in scenarios.
    fn name(&self) -> &'static str;
    /// Advances `state` by `h` seconds.
    fn step(&mut self, sys: &dyn Dynamics, state: &mut State, h: f64) -> Result<(), IntegrateError>;
    /// Forgets any history (call after an impulse changed the state from outside).
    fn reset(&mut self) {}
    /// The leading term of the last step's local error in x, if the method estimates it.
    fn local_error(&self) -> Option<&DVector<f64>> {
        None
    }
    /// Remembers the method's history, so that a step can be taken back ([`Self::rollback`]).
    fn checkpoint(&mut self) {}
    /// Restores the history remembered by the last [`Self::checkpoint`].
    fn rollback(&mut self) {}
}

/// The integrators a scenario can name, with their parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum IntegratorKind {
    /// Chung–Hulbert generalized-α with spectral radius at infinity `rho_inf` ∈ [0, 1] (default
    /// [`DEFAULT_RHO_INF`] where a scenario leaves it out).
    GeneralizedAlpha {
        #[serde(default = "default_rho_inf")]
        rho_inf: f64,
    },
    /// Newmark-β with the given β and γ (default β = 1/4, γ = 1/2: average acceleration, the
    /// trapezoidal rule, unconditionally stable and undamped).
    Newmark {
        #[serde(default = "default_newmark_beta")]
        beta: f64,
        #[serde(default = "default_newmark_gamma")]
        gamma: f64,
    },
    /// Hilber–Hughes–Taylor α ∈ [−1/3, 0] (default −0.05: light damping of what the step cannot
    /// resolve, Hilber, Hughes & Taylor 1977).
    Hht {
        #[serde(default = "default_hht_alpha")]
        alpha: f64,
    },
    /// Semi-implicit (symplectic) Euler.
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta.
    Rk4,
    /// Forward Euler: unstable on every undamped oscillation, kept as a failure case.
    ExplicitEuler,
}

/// Generalized-α's spectral radius at infinity where a scenario gives none: damps only what the
/// step cannot resolve.
pub const DEFAULT_RHO_INF: f64 = 0.8;

fn default_rho_inf() -> f64 {
    DEFAULT_RHO_INF
}

fn default_newmark_beta() -> f64 {
    0.25
}

fn default_newmark_gamma() -> f64 {
    0.5
}

fn default_hht_alpha() -> f64 {
    -0.05
}

impl Default for IntegratorKind {
    /// Generalized-α with ρ∞ = 0.8: second order, damps only what the step cannot resolve.
    fn default() -> Self {
        IntegratorKind::GeneralizedAlpha { rho_inf: DEFAULT_RHO_INF }
    }
}

impl std::fmt::Display for IntegratorKind {
    /// As a scenario names it, with its parameters: `rk4`, `generalized-alpha (rho_inf 0.8)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            IntegratorKind::GeneralizedAlpha { rho_inf } => write!(f, "{} (rho_inf {rho_inf})", self.name()),
            IntegratorKind::Newmark { beta, gamma } => write!(f, "{} (beta {beta}, gamma {gamma})", self.name()),
            IntegratorKind::Hht { alpha } => write!(f, "{} (alpha {alpha})", self.name()),
            _ => f.write_str(self.name()),
        }
    }
}

impl IntegratorKind {
    /// The largest stable ω·dt on an undamped mode: `None` for the unconditionally stable ones,
    /// `Some(0)` for explicit Euler (unstable at every step); the intervals of Hairer & Wanner,
    /// Solving Ordinary Differential Equations II (1996), and Hughes, The Finite Element Method
    /// (1987), for the central difference.
    pub fn stability_limit_omega_dt(&self) -> Option<f64> {
        match *self {
            IntegratorKind::GeneralizedAlpha { .. } | IntegratorKind::Hht { .. } => None,
            // Unconditional for 2β ≥ γ ≥ 1/2; otherwise Ω = 1/√(γ/2 − β) (1/√(1/12) = 2√3 at β = 1/6).
            IntegratorKind::Newmark { beta, gamma } => (2.0 * beta < gamma).then(|| 1.0 / (0.5 * gamma - beta).sqrt()),
            IntegratorKind::SymplecticEuler => Some(2.0),
            // Where RK4's stability region crosses the imaginary axis.
            IntegratorKind::Rk4 => Some(8f64.sqrt()),
            IntegratorKind::ExplicitEuler => Some(0.0),
        }
    }

    /// Short name, as written in scenarios.
    pub fn name(&self) -> &'static str {
        match self {
            IntegratorKind::GeneralizedAlpha { .. } => "generalized-alpha",
            IntegratorKind::Newmark { .. } => "newmark",
            IntegratorKind::Hht { .. } => "hht",
            IntegratorKind::SymplecticEuler => "symplectic-euler",
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::ExplicitEuler => "explicit-euler",
        }
    }

    /// Builds the integrator, checking its parameters.
    pub fn build(&self) -> Result<Box<dyn Integrator>, IntegrateError> {
        Ok(match *self {
            IntegratorKind::GeneralizedAlpha { rho_inf } => Box::new(GeneralizedAlpha::chung_hulbert(rho_inf)?),
            IntegratorKind::Newmark { beta, gamma } => Box::new(GeneralizedAlpha::newmark(beta, gamma)?),
            IntegratorKind::Hht { alpha } => Box::new(GeneralizedAlpha::hht(alpha)?),
            IntegratorKind::SymplecticEuler => Box::new(SymplecticEuler),
            IntegratorKind::Rk4 => Box::new(Rk4::default()),
            IntegratorKind::ExplicitEuler => Box::new(ExplicitEuler),
        })
    }
}

/// Ends a step: the first-order states' unused positions back to zero (they would otherwise
/// accumulate the states' integrals), then [`check_finite`].
pub(crate) fn finish_step(sys: &dyn Dynamics, state: &mut State) -> Result<(), IntegrateError> {
    let n = state.x.len();
    let first_order = sys.first_order_dofs().min(n);
    state.x.as_mut_slice()[n - first_order..].fill(0.0);
    check_finite(state)
}

pub(crate) fn check_finite(state: &State) -> Result<(), IntegrateError> {
    let finite = state.x.iter().chain(state.v.iter()).all(|v| v.is_finite());
    if finite { Ok(()) } else { Err(IntegrateError::NonFinite { t: state.t }) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every parameter with a documented default takes it where a scenario leaves it out.
    #[test]
    fn newmark_and_hht_default_their_parameters() {
        let newmark: IntegratorKind = toml::from_str("kind = \"newmark\"").unwrap();
        assert_eq!(newmark, IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 });
        let hht: IntegratorKind = toml::from_str("kind = \"hht\"").unwrap();
        assert_eq!(hht, IntegratorKind::Hht { alpha: -0.05 });
    }

    /// A documented default is taken where a scenario leaves the parameter out, and the name
    /// printed is the one a scenario writes.
    #[test]
    fn generalized_alpha_defaults_its_rho_inf_and_prints_as_written() {
        let kind: IntegratorKind = toml::from_str("kind = \"generalized-alpha\"").unwrap();
        assert_eq!(kind, IntegratorKind::GeneralizedAlpha { rho_inf: 0.8 });
        assert_eq!(kind.to_string(), "generalized-alpha (rho_inf 0.8)");
        let rk4: IntegratorKind = toml::from_str("kind = \"rk4\"").unwrap();
        assert_eq!(rk4.to_string(), "rk4");
    }
}
