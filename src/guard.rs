//! The run-time divergence guard: stops a run whose energy grows beyond anything its sources
//! could have put in, instead of letting it write garbage.
//!
//! A stable run cannot hold more kinetic + strain energy than it started with plus the work its
//! drive has done (∫|τ θ̇| dt, counted in absolute value so that no sign error can hide a
//! growth) plus what gravity can release (every mass falling twice the arm's reach). That bound
//! is loose on purpose: a physical run never comes near it, and an unstable one crosses it within
//! a few periods of the mode that grows, because the growth is exponential. Non-finite values are
//! caught at the first step they appear.

use crate::arm::ArmSample;
use crate::integrate::IntegratorKind;

/// What diverged, and when.
#[derive(Debug, Clone, PartialEq)]
pub struct Divergence {
    /// Time at which it was detected, s.
    pub t_s: f64,
    /// What grew, with its value and bound.
    pub what: String,
}

/// Watches a run's energy against its sources, one sample per step.
#[derive(Debug, Clone)]
pub struct DivergenceGuard {
    /// Kinetic + strain energy at the start plus what gravity can release, J.
    fixed_budget_j: f64,
    /// ∫|τ θ̇| dt so far, J.
    drive_work_j: f64,
    /// (t, |τ θ̇|) of the previous sample.
    last: (f64, f64),
}

impl DivergenceGuard {
    /// Starts from the first sample; `gravity_span_j` is total mass × g × twice the reach, J.
    pub fn new(first: &ArmSample, gravity_span_j: f64) -> Self {
        let e = &first.energies;
        DivergenceGuard {
            fixed_budget_j: e.kinetic_j.abs() + e.strain_j.abs() + gravity_span_j.abs(),
            drive_work_j: 0.0,
            last: (first.t_s, drive_power_w(first)),
        }
    }

    /// Energy the run may hold now, J.
    pub fn budget_j(&self) -> f64 {
        // Twice the bound plus 10 J: no physical run comes near it (module doc).
        2.0 * (self.fixed_budget_j + self.drive_work_j) + 10.0
    }

    /// Checks a new sample; `Err` when the run has diverged.
    pub fn check(&mut self, s: &ArmSample) -> Result<(), Divergence> {
        let divergence = |what: String| Divergence { t_s: s.t_s, what };
        if let Some(bad) = non_finite(s) {
            return Err(divergence(format!("{bad} is no longer finite")));
        }
        let power = drive_power_w(s);
        self.drive_work_j += 0.5 * (power + self.last.1) * (s.t_s - self.last.0);
        self.last = (s.t_s, power);
        let held = s.energies.kinetic_j + s.energies.strain_j;
        if held > self.budget_j() {
            return Err(divergence(format!(
                "the arm's kinetic + strain energy grew to {held:.4e} J, beyond the {:.4e} J its drive and gravity \
                 could have put in",
                self.budget_j()
            )));
        }
        Ok(())
    }
}

fn drive_power_w(s: &ArmSample) -> f64 {
    (s.drive_torque_n_m * s.hub.rate_rad_s).abs()
}

fn non_finite(s: &ArmSample) -> Option<String> {
    if !s.q.iter().all(|v| v.is_finite()) {
        return Some("the elastic coordinate vector q".into());
    }
    let named = [
        ("the tip deflection", s.tip_deflection_hub_m[1]),
        ("the tip velocity", s.tip_velocity_hub_m_s[1]),
        ("the drive torque", s.drive_torque_n_m),
        ("the kinetic energy", s.energies.kinetic_j),
        ("the strain energy", s.energies.strain_j),
    ];
    named.iter().find(|(_, v)| !v.is_finite()).map(|(name, _)| name.to_string())
}

/// What to do about a diverged run: a step that would be stable, or another integrator.
///
/// `omega_max_rad_s` is the highest natural frequency the model keeps; `penalty_limit_s` the
/// pad contacts' explicit limit 2√(m_eff/k) (if known), s.
pub fn stability_advice(
    integrator: &IntegratorKind,
    omega_max_rad_s: f64,
    step_s: f64,
    penalty_limit_s: Option<f64>,
) -> String {
    let implicit = "generalized-alpha (stable at any step)";
    let omega_dt = omega_max_rad_s * step_s;
    match integrator.stability_limit_omega_dt() {
        Some(0.0) => {
            format!(
                "explicit Euler amplifies every undamped mode at any step (ω_max·dt = {omega_dt:.3}): use {implicit}"
            )
        }
        Some(limit) if omega_dt > limit => format!(
            "ω_max·dt = {omega_dt:.3} ({omega_max_rad_s:.1} rad/s × {step_s} s) exceeds this integrator's limit \
             {limit:.3}: use step_s <= {:.3e} s (0.9 of the limit), or {implicit}",
            0.9 * limit / omega_max_rad_s
        ),
        Some(limit) => match penalty_limit_s.filter(|&l| step_s > l) {
            Some(l) => format!(
                "ω_max·dt = {omega_dt:.3} is within this integrator's limit {limit:.3}, but the pad's penalty limit \
                 2√(m_eff/k) = {l:.3e} s is not: use step_s <= {:.3e} s, or {implicit}",
                0.9 * l
            ),
            None => format!("halve the step (step_s = {:.3e} s), or use {implicit}", 0.5 * step_s),
        },
        None => format!(
            "the implicit step is stable at any ω_max·dt; what grew is a load it does not see (a contact's \
             kink, a staggered load): halve the step (step_s = {:.3e} s)",
            0.5 * step_s
        ),
    }
}
