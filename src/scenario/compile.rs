//! The scenario compiled for its runs ([`Scenario::compile`]): the checks that need what only
//! compiling derives — the shaper's tuning (the arm's modes), the arm at its fidelity — run here,
//! once, on the model the run takes; reading a scenario solves no eigenproblem and simulates
//! nothing.
//!
//! A drive whose shaper is tuned by default has its motion only once compiled: its limits (the
//! joint's velocity, the motor's speed, the cylinder's stroke) are checked again on the shaped
//! move. Under a controller the arm the run takes is linearised with its actuator at rest along
//! the drive's path: every pole must decay, and an explicit integrator's step must keep each
//! inside its stability region.

use std::borrow::Cow;

use nalgebra::Complex;

use super::{Check, Scenario, ScenarioError, loop_advice};
use crate::actuator::Actuator;
use crate::arm::{ArmError, ArmModel, ArmSimulation, Fidelity, HubDrive};
use crate::integrate::IntegratorKind;
use crate::model::Model;
use crate::run::CompiledModel;
use crate::scene::SceneError;

/// Fraction of an explicit integrator's longest stable step a scene's step may use.
const STEP_MARGIN: f64 = 0.95;

/// Points along the drive's path, besides the start, where the closed loop is linearised at rest.
const LOOP_CHECK_POINTS: usize = 4;

impl Scenario {
    /// The scenario compiled for its runs at `fidelity` (`auto`'s choice if `None`), through
    /// its compiler (which keeps what a sweep's scenarios share), and checked as compiled
    /// (module doc).
    ///
    /// # Errors
    /// The shaper cannot be tuned, the arm not compiled, or the compiled scene fails a check:
    /// each names the file, and the key where one settles it.
    pub fn compile(&self, fidelity: Option<Fidelity>) -> Result<CompiledModel<'_>, ScenarioError> {
        let compiled = CompiledModel::new(&self.model, fidelity, &self.compiler).map_err(|e| self.compile_error(e))?;
        let check = self.check();
        if self.model.drive.untuned_shaper.is_some() {
            let tuned = &compiled.model;
            let limits = check.drive_limits(tuned).and_then(|()| check.actuator_in_scene(tuned));
            limits.map_err(|e| shaped_by_tuning(e, tuned))?;
        }
        check.closed_loop_on_path(&compiled)?;
        Ok(compiled)
    }

    /// Whether its compile checks anything its reading could not (a closed loop, a shaper's
    /// move tuned to the arm's modes): a sweep compiles such cases before it writes any.
    pub fn compile_checks(&self) -> bool {
        self.model.drive.untuned_shaper.is_some() || self.model.drive.actuator.controller().is_some()
    }

    /// The compile's checks ([`Self::compile`]) where it has any ([`Self::compile_checks`]),
    /// the compiled model dropped: what a sweep, an envelope or a design runs on every case
    /// before any runs.
    ///
    /// # Errors
    /// As [`Self::compile`].
    pub fn check_compiled(&self) -> Result<(), ScenarioError> {
        if self.compile_checks() { self.compile(None).map(|_| ()) } else { Ok(()) }
    }

    /// The scenario's model with its shaper tuned ([`crate::tuning::tuned`]), without the rest of
    /// the compile (the arm at its fidelity) or its checks.
    ///
    /// # Errors
    /// The shaper cannot be tuned (the file and `drive.shaper` or `drive.duration_s`).
    pub fn tuned(&self) -> Result<Cow<'_, Model>, ScenarioError> {
        crate::tuning::tuned(&self.model, &self.compiler).map_err(|e| self.compile_error(e.into()))
    }

    fn check(&self) -> Check<'_> {
        Check { path: &self.path, capacity: false }
    }

    fn compile_error(&self, error: SceneError) -> ScenarioError {
        ScenarioError::Compile { path: self.path.clone(), error }
    }
}

/// `error`, from a drive limit checked on the move `tuned`'s shaper shaped, saying so: the file's
/// own move passes them, and the shaper is what sped it up.
fn shaped_by_tuning(error: ScenarioError, tuned: &Model) -> ScenarioError {
    let ScenarioError::Invalid { path, key, message } = error else { return error };
    let modes: Vec<String> =
        tuned.drive.motion.shaper_modes().iter().map(|m| format!("{:.3}", m.frequency_hz)).collect();
    let shaper = tuned.drive.motion.shaper().map_or("", |s| s.name());
    let message = format!(
        "{message}; with the {shaper} shaper tuned to the arm's modes at [{}] Hz, the base move lasts duration_s minus \
         the shaper's length",
        modes.join(", ")
    );
    ScenarioError::Invalid { path, key, message }
}

impl Check<'_> {
    /// The arm the run takes, held by its drive
    /// at the start ([`Self::holding`]) and at rest at points along the drive's path, linearised
    /// there (the controller sampling continuously): every pole must decay, and an explicit
    /// integrator's step must keep each inside its stability region.
    fn closed_loop_on_path(&self, compiled: &CompiledModel) -> Result<(), ScenarioError> {
        let model: &Model = &compiled.model;
        if model.drive.actuator.controller().is_none() {
            return Ok(());
        }
        let arm = compiled.arm.model.clone();
        let start = self.holding(model, ArmSimulation::new(arm.clone(), model.hub_drive(), model.integrator))?;
        let mut poles = self.decaying_poles(model, &arm, &start, &|m: &Model| m.hub_drive(), "at the start")?;
        let (lo, hi) = model.drive.motion.angle_range_rad(model.duration_s());
        for k in 1..=LOOP_CHECK_POINTS {
            let angle = lo + (hi - lo) * k as f64 / LOOP_CHECK_POINTS as f64;
            let held = model.hub_drive_held_at(angle);
            let at = format!("at rest at {:.1} deg on the drive's path", angle.to_degrees());
            let sim = self.holding(model, ArmSimulation::new(arm.clone(), held, model.integrator))?;
            poles.extend(self.decaying_poles(model, &arm, &sim, &|m: &Model| m.hub_drive_held_at(angle), &at)?);
        }
        self.explicit_step_resolves(model, &poles)
    }

    /// The poles of `sim` (the arm `arm` held by `drive_of` the model) linearised, or an error
    /// naming the growing one, `at` where, with the settings that move it and which way
    /// ([`loop_advice`]).
    fn decaying_poles(
        &self,
        model: &Model,
        arm: &ArmModel,
        sim: &ArmSimulation,
        drive_of: &dyn Fn(&Model) -> HubDrive,
        at: &str,
    ) -> Result<Vec<Complex<f64>>, ScenarioError> {
        let poles = sim
            .linear_poles()
            .map_err(|e| self.invalid("actuator.kind", format!("linearising the arm {at} fails: {e}")))?;
        let growing = poles.iter().copied().filter(|p| loop_advice::grows(*p)).max_by(|a, b| a.re.total_cmp(&b.re));
        let Some(p) = growing else { return Ok(poles) };
        let (key, advice) = loop_advice::advice(model, arm, drive_of, p);
        Err(self.invalid(
            key,
            format!(
                "the closed loop linearised {at} has a growing mode: pole {:.3} ± {:.3}i rad/s ({:.2} Hz, doubling \
                 every {:.2} s); {advice}",
                p.re,
                p.im.abs(),
                p.im.abs() / std::f64::consts::TAU,
                std::f64::consts::LN_2 / p.re
            ),
        ))
    }

    /// An explicit integrator's step keeps every pole inside its stability region, with a
    /// margin: at most [`STEP_MARGIN`] of the longest step that does.
    fn explicit_step_resolves(&self, model: &Model, poles: &[Complex<f64>]) -> Result<(), ScenarioError> {
        let (integrator, step) = (&model.integrator, model.time.step_s);
        if integrator.stability_limit_omega_dt().is_none() {
            return Ok(());
        }
        // The longest stable step, by bisection (stability regions are intervals in h along a ray).
        let (mut stable_h, mut unstable_h) = (0.0, 100.0 * step);
        for _ in 0..80 {
            let h = 0.5 * (stable_h + unstable_h);
            if poles.iter().all(|p| stable(integrator, *p, h)) { stable_h = h } else { unstable_h = h }
        }
        if step <= STEP_MARGIN * stable_h {
            return Ok(());
        }
        let fastest = poles.iter().map(|p| p.norm()).fold(0.0, f64::max);
        let implicit = "or integrator.kind = \"generalized-alpha\" (stable at any step)";
        let remedy = if stable_h > 0.0 {
            format!(
                "allowed step_s <= {:.3e} s ({STEP_MARGIN} of the longest stable step), {implicit}",
                STEP_MARGIN * stable_h
            )
        } else {
            format!("no step is stable for it: use {implicit}")
        };
        Err(self.invalid(
            "time.step_s",
            format!(
                "{} is explicit and the arm with its actuator has poles its step {step} s does not keep in its stability \
                 region with a margin (fastest {fastest:.1} rad/s, |λ|·dt = {:.3}): {remedy}",
                integrator.name(),
                fastest * step
            ),
        ))
    }

    /// The actuator holds the arm at rest at the drive's start (the arm waits on it before the
    /// lift): a hydraulic drive within tank..supply pressure, a servo within its torque. `started`
    /// is the simulation built at the start.
    fn holding(&self, model: &Model, started: Result<ArmSimulation, ArmError>) -> Result<ArmSimulation, ScenarioError> {
        let why = match started {
            Ok(sim) => return Ok(sim),
            Err(ArmError::ActuatorCannotHold { why, .. }) => why,
            Err(e) => return Err(self.invalid("actuator.kind", format!("the actuated start fails: {e}"))),
        };
        let source = model.robot.source.display();
        let (key, remedy) = match &model.drive.actuator {
            Actuator::Hydraulic(_) => (
                "actuator.supply_pressure_pa",
                format!(
                    "a supply pressure that holds it with both chambers between tank and supply (or a larger bore or \
                     lever: joint[{}].pipearm:cylinder in {source})",
                    model.robot.lift.name
                ),
            ),
            _ => (
                "actuator.kind",
                format!(
                    "a servo whose gear_ratio x torque_limit_n_m holds it (joint[{}].pipearm:servo in {source})",
                    model.robot.lift.name
                ),
            ),
        };
        Err(self.invalid(key, format!("{why}: allowed {remedy}")))
    }
}

/// Whether `integrator` at step `h` keeps the mode of pole `pole` from growing: the amplification
/// of the test equation y' = λy for the Runge–Kutta methods, of the damped oscillator with
/// ω = |λ| and ζ = −Re λ / |λ| for symplectic Euler, the undamped limit for Newmark's explicit
/// range; the implicit methods at any step.
fn stable(integrator: &IntegratorKind, pole: Complex<f64>, h: f64) -> bool {
    let z = pole * h;
    let one = Complex::new(1.0, 0.0);
    match integrator {
        IntegratorKind::Rk4 => (one + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0).norm() <= 1.0 + 1e-12,
        IntegratorKind::ExplicitEuler => (one + z).norm() <= 1.0 + 1e-12,
        IntegratorKind::SymplecticEuler if pole.im == 0.0 => (one + z).norm() <= 1.0 + 1e-12,
        IntegratorKind::SymplecticEuler => {
            let (w, zeta) = (pole.norm(), -pole.re / pole.norm());
            let (a, b, c, d) =
                (1.0 - w * w * h * h, h * (1.0 - 2.0 * zeta * w * h), -w * w * h, 1.0 - 2.0 * zeta * w * h);
            let eigen = nalgebra::Matrix2::new(a, b, c, d).complex_eigenvalues();
            eigen.iter().all(|e| e.norm() <= 1.0 + 1e-12)
        }
        other => other.stability_limit_omega_dt().is_none_or(|limit| pole.norm() * h <= limit),
    }
}
