//! The scenario's `[actuator]` table: which machine of the robot's lift joint tracks the drive's
//! profile, how it is operated, and its checks against the robot, the drive and the time step.
//!
//! ```toml
//! [actuator]
//! kind = "hydraulic"                 # "ideal" (the default without the table), "servo", "hydraulic"
//! supply_pressure_pa = 21e6
//! tank_pressure_pa = 0.5e6
//! bulk_modulus_pa = 1.2e9
//! relief_pressure_pa = 23e6
//! valve = { rated_flow_m3_s = 2.5e-3, rated_pressure_drop_pa = 3.5e6, spool_time_constant_s = 0.015 }
//! controller = { kp = 5.0, ki = 0.0, kd = 0.0, velocity_feedforward = 1.0, acceleration_feedforward = 0.0 }
//! ```
//!
//! A servo has only `controller`; its machine is the URDF's `<pipearm:servo>`, a hydraulic
//! drive's the URDF's `<pipearm:cylinder>` ([`crate::robot`]).

use serde::{Deserialize, Serialize};

use super::{Check, ScenarioError, loop_advice};
use crate::actuator::{Actuator, ControllerGains, Cylinder, HydraulicCircuit, HydraulicDrive, ServoDrive, Valve};
use nalgebra::Complex;

use crate::arm::{ArmError, ArmModel, ArmSimulation, HubDrive};
use crate::drive::MotionLaw;
use crate::integrate::IntegratorKind;
use crate::model::Model;
use crate::robot::Robot;

/// Angles sampled along the drive's path when the cylinder's length is checked on it.
const PATH_SAMPLES: usize = 2000;

/// Fraction of an explicit integrator's longest stable step a scene's step may use.
const STEP_MARGIN: f64 = 0.95;

/// Points along the drive's path, besides the start, where the closed loop is linearised at rest.
const LOOP_CHECK_POINTS: usize = 4;

/// The actuator as a scenario states it; the table left out: ideal.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ActuatorSpec {
    /// The hub follows the drive's profile exactly.
    #[default]
    Ideal,
    /// The robot's servo motor and gearbox under a position controller (output: hub torque).
    Servo {
        /// Gains and rate of the position controller.
        controller: ControllerGains,
    },
    /// The robot's cylinder, driven by a proportional valve under a position controller
    /// (output: spool opening).
    Hydraulic {
        /// Supply pressure, Pa.
        supply_pressure_pa: f64,
        /// Tank (return) pressure, Pa.
        tank_pressure_pa: f64,
        /// Effective bulk modulus of oil and hoses, Pa.
        bulk_modulus_pa: f64,
        /// Setting of the chambers' relief valves, Pa.
        relief_pressure_pa: f64,
        /// The proportional valve.
        valve: Valve,
        /// Gains and rate of the position controller.
        controller: ControllerGains,
    },
}

impl ActuatorSpec {
    /// Whether it is the ideal drive (left out of the canonical form).
    pub fn is_ideal(&self) -> bool {
        matches!(self, ActuatorSpec::Ideal)
    }
}

impl Check<'_> {
    /// `[actuator]` resolved on the robot's machines, its values checked (those that need the
    /// rest of the scene: [`Check::actuator_in_scene`]).
    pub(super) fn actuator(&self, spec: &ActuatorSpec, robot: &Robot) -> Result<Actuator, ScenarioError> {
        Ok(match *spec {
            ActuatorSpec::Ideal => Actuator::Ideal,
            ActuatorSpec::Servo { controller } => {
                let machine = robot.lift.servo.ok_or_else(|| self.missing_machine(robot, "servo", "servo"))?;
                Actuator::Servo(ServoDrive { machine, controller: self.controller(controller)? })
            }
            ActuatorSpec::Hydraulic {
                supply_pressure_pa,
                tank_pressure_pa,
                bulk_modulus_pa,
                relief_pressure_pa,
                valve,
                controller,
            } => {
                let cylinders =
                    robot.lift.cylinders.clone().ok_or_else(|| self.missing_machine(robot, "hydraulic", "cylinder"))?;
                let circuit = HydraulicCircuit {
                    supply_pressure_pa,
                    tank_pressure_pa,
                    bulk_modulus_pa,
                    relief_pressure_pa,
                    valve,
                };
                self.circuit(&circuit)?;
                Actuator::Hydraulic(HydraulicDrive { cylinders, circuit, controller: self.controller(controller)? })
            }
        })
    }

    fn missing_machine(&self, robot: &Robot, kind: &str, element: &str) -> ScenarioError {
        self.invalid(
            "actuator.kind",
            format!(
                "`{kind}` drives the robot's {element}, but {} has no <pipearm:{element}> on joint `{}`: allowed \
                 the kinds whose machine the URDF describes (ideal needs none)",
                robot.source.display(),
                robot.lift.name
            ),
        )
    }

    fn controller(&self, gains: ControllerGains) -> Result<ControllerGains, ScenarioError> {
        let key = |name: &str| format!("actuator.controller.{name}");
        if !(gains.kp.is_finite() && gains.kp > 0.0) {
            return Err(self.invalid(&key("kp"), format!("{} is outside kp > 0", gains.kp)));
        }
        for (name, value) in [
            ("ki", gains.ki),
            ("kd", gains.kd),
            ("velocity_feedforward", gains.velocity_feedforward),
            ("acceleration_feedforward", gains.acceleration_feedforward),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(self.invalid(&key(name), format!("{value} is outside {name} >= 0")));
            }
        }
        if let Some(hz) = gains.rate_hz
            && !(hz.is_finite() && hz > 0.0)
        {
            return Err(self.invalid(&key("rate_hz"), format!("{hz} is outside rate_hz > 0")));
        }
        Ok(gains)
    }

    /// Pressures ordered tank < supply < relief; bulk modulus and valve ratings positive.
    fn circuit(&self, c: &HydraulicCircuit) -> Result<(), ScenarioError> {
        let (pt, ps, pr) = (c.tank_pressure_pa, c.supply_pressure_pa, c.relief_pressure_pa);
        if !(pt.is_finite() && pt >= 0.0) {
            return Err(self.invalid("actuator.tank_pressure_pa", format!("{pt} is outside tank_pressure_pa >= 0")));
        }
        if !(ps.is_finite() && ps > pt) {
            return Err(self.invalid(
                "actuator.supply_pressure_pa",
                format!("{ps} is outside supply_pressure_pa > tank_pressure_pa ({pt})"),
            ));
        }
        if !(pr.is_finite() && pr > ps) {
            return Err(self.invalid(
                "actuator.relief_pressure_pa",
                format!("{pr} is outside relief_pressure_pa > supply_pressure_pa ({ps})"),
            ));
        }
        let v = &c.valve;
        for (key, value) in [
            ("bulk_modulus_pa", c.bulk_modulus_pa),
            ("valve.rated_flow_m3_s", v.rated_flow_m3_s),
            ("valve.rated_pressure_drop_pa", v.rated_pressure_drop_pa),
            ("valve.spool_time_constant_s", v.spool_time_constant_s),
        ] {
            if !(value.is_finite() && value > 0.0) {
                let name = key.rsplit('.').next().unwrap_or(key);
                return Err(self.invalid(&format!("actuator.{key}"), format!("{value} is outside {name} > 0")));
            }
        }
        let leakage = v.leakage_m3_s_per_pa;
        if !(leakage.is_finite() && leakage >= 0.0) {
            return Err(self.invalid(
                "actuator.valve.leakage_m3_s_per_pa",
                format!("{leakage} is outside leakage_m3_s_per_pa >= 0"),
            ));
        }
        Ok(())
    }

    /// The actuator against the rest of the scene: its controller no faster than the scene's
    /// step, fixed steps, the cylinder within its stroke and the motor within its speed on the
    /// drive's path, and the arm held at the start.
    pub(super) fn actuator_in_scene(&self, model: &Model) -> Result<(), ScenarioError> {
        let actuator = &model.drive.actuator;
        let Some(gains) = actuator.controller() else { return Ok(()) };
        let step = model.time.step_s;
        if let Some(hz) = gains.rate_hz
            && 1.0 / hz < step * (1.0 - 1e-9)
        {
            return Err(self.invalid(
                "actuator.controller.rate_hz",
                format!(
                    "{hz} Hz samples every {:.6} s, more often than the scene steps (time.step_s = {step} s): allowed \
                     rate_hz <= {:.6} Hz (1 / step_s)",
                    1.0 / hz,
                    1.0 / step
                ),
            ));
        }
        if model.time.free_step_s.is_some() {
            return Err(self.invalid(
                "time.free_step_s",
                format!(
                    "controlled free steps are not supported with an actuator (actuator.kind = \"{}\"): allowed \
                     fixed steps of time.step_s (leave free_step_s out)",
                    actuator.kind()
                ),
            ));
        }
        match actuator {
            Actuator::Ideal => {}
            Actuator::Servo(servo) => self.servo_speed(model, servo)?,
            Actuator::Hydraulic(drive) => {
                for (k, cylinder) in drive.cylinders.each.iter().enumerate() {
                    let element = crate::robot::cylinder_element(&model.robot.lift.name, k, drive.cylinders.each.len());
                    self.cylinder_on_path(model, cylinder, &element)?;
                }
            }
        }
        self.closed_loop_on_path(model)
    }

    /// The arm the run takes (compiled as the run compiles it, and kept for it), held by its drive
    /// at the start ([`Self::holding`]) and at rest at points along the drive's path, linearised
    /// there (the controller sampling continuously): every pole must decay, and an explicit
    /// integrator's step must keep each inside its stability region.
    fn closed_loop_on_path(&self, model: &Model) -> Result<(), ScenarioError> {
        // The model the run compiles (through the shared compiler, which keeps it for the run).
        let compiled = crate::run::CompiledModel::new(model, None, self.compiler)
            .map_err(|e| self.invalid("payload", e.to_string()))?;
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

    /// The motor's speed at the reference's peak rate within its limit.
    fn servo_speed(&self, model: &Model, servo: &ServoDrive) -> Result<(), ScenarioError> {
        let motion = &model.drive.motion;
        let (rate, hub_limit) = (motion.peak_rate_rad_s(), servo.machine.hub_speed_limit_rad_s());
        if rate <= hub_limit * (1.0 + 1e-9) {
            return Ok(());
        }
        let (key, remedy) = if motion.law() == MotionLaw::Table {
            ("drive.file", "a slower table")
        } else {
            ("drive.duration_s", "a longer move")
        };
        Err(self.invalid(
            key,
            format!(
                "the drive's peak rate {:.3} deg/s turns the servo motor at {:.1} rad/s (gear_ratio {} x the rate), \
                 above its speed_limit_rad_s {} (joint[{}].pipearm:servo in {}): allowed a peak rate up to {:.3} deg/s \
                 ({remedy})",
                rate.to_degrees(),
                rate * servo.machine.gear_ratio,
                servo.machine.gear_ratio,
                servo.machine.speed_limit_rad_s,
                model.robot.lift.name,
                model.robot.source.display(),
                hub_limit.to_degrees()
            ),
        ))
    }

    /// The cylinder's pin-to-pin length within [closed, closed + stroke] and its moment arm
    /// positive (it extends as the arm lifts) at every angle the drive's reference passes;
    /// `element` names it in the URDF.
    fn cylinder_on_path(&self, model: &Model, cylinder: &Cylinder, element: &str) -> Result<(), ScenarioError> {
        let (lo, hi) = model.drive.motion.angle_range_rad(model.duration_s());
        let angles = (0..=PATH_SAMPLES).map(|i| lo + (hi - lo) * i as f64 / PATH_SAMPLES as f64);
        let samples: Vec<(f64, f64, f64)> = angles
            .map(|angle| {
                let (length, arm) = cylinder.length_and_arm(angle);
                (angle, length, arm)
            })
            .collect();
        let by = |f: fn(&(f64, f64, f64)) -> f64| {
            samples.iter().copied().min_by(|a, b| f(a).total_cmp(&f(b))).expect("one sample at least")
        };
        let (shortest, longest, least_arm) = (by(|s| s.1), by(|s| -s.1), by(|s| s.2));
        let (closed, open) = (cylinder.closed_length_m, cylinder.closed_length_m + cylinder.stroke_m);
        let deg = f64::to_degrees;
        let place = format!(
            "on the drive's path ({:.2} ..= {:.2} deg) the cylinder of {} ({element})",
            deg(lo),
            deg(hi),
            model.robot.source.display(),
        );
        let stroke = format!(
            "allowed pin-to-pin lengths closed_length_m ..= closed_length_m + stroke_m ({closed} ..= {open} m) \
             everywhere on the path (other pins or a shorter path)"
        );
        let problem = if shortest.1 < closed {
            format!(
                "{place} is {:.1} mm shorter than its closed length at {:.2} deg ({:.4} m): {stroke}",
                (closed - shortest.1) * 1e3,
                deg(shortest.0),
                shortest.1
            )
        } else if longest.1 > open {
            format!(
                "{place} is {:.1} mm longer than closed length + stroke at {:.2} deg ({:.4} m): {stroke}",
                (longest.1 - open) * 1e3,
                deg(longest.0),
                longest.1
            )
        } else if least_arm.2 <= 0.0 {
            format!(
                "{place} has a moment arm ds/dθ of {:.4} m at {:.2} deg: allowed ds/dθ > 0 everywhere on the path \
                 (the cylinder extends as the arm lifts)",
                least_arm.2,
                deg(least_arm.0)
            )
        } else {
            return Ok(());
        };
        Err(self.invalid("actuator.kind", problem))
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

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;
    use crate::scenario::{Scenario, ScenarioSpec};

    fn default_path() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")
    }

    /// The default scenario with `table` appended, its string lumped as the drive scenes' are.
    fn default_with(table: &str) -> ScenarioSpec {
        let text = std::fs::read_to_string(default_path()).unwrap();
        let mut spec: ScenarioSpec = toml::from_str(&(text + table)).unwrap();
        if let crate::scenario::PayloadSpec::String { model, .. } = &mut spec.payload {
            *model = crate::scenario::ModelSpec::Rigid;
        }
        spec
    }

    #[test]
    fn an_ideal_drive_leaves_the_canonical_form_as_it_was() {
        let absent = toml::to_string(&default_with("")).unwrap();
        let ideal = toml::to_string(&default_with("\n[actuator]\nkind = \"ideal\"\n")).unwrap();
        assert_eq!(absent, ideal);
        assert!(!absent.contains("actuator"), "{absent}");
    }

    #[test]
    fn a_hydraulic_table_resolves_on_the_robots_cylinder_and_keeps_its_canonical_form() {
        let table = "\n[actuator]\nkind = \"hydraulic\"\nsupply_pressure_pa = 21e6\ntank_pressure_pa = 5e5\n\
                     bulk_modulus_pa = 1.2e9\nrelief_pressure_pa = 23e6\nvalve = { rated_flow_m3_s = 2.5e-3, \
                     rated_pressure_drop_pa = 3.5e6, spool_time_constant_s = 0.015, leakage_m3_s_per_pa = 1e-11 }\n\
                     controller = { kp = 5, rate_hz = 250 }\n";
        let mut spec = default_with(table);
        // The hydraulic scenes' step: with the five modes `auto` keeps on a cylinder, RK4 at a
        // longer step would pass the limit the drive's fastest pole sets (a checked error).
        spec.time.step_s = 0.0015;
        let canonical = toml::to_string(&spec).unwrap();
        assert_eq!(toml::from_str::<ScenarioSpec>(&canonical).unwrap(), spec, "{canonical}");
        let scenario = Scenario::from_spec(&default_path(), spec).unwrap();
        let Actuator::Hydraulic(drive) = &scenario.model.drive.actuator else { panic!("not hydraulic") };
        assert_eq!(Some(&drive.cylinders), scenario.model.robot.lift.cylinders.as_ref());
        assert_eq!((drive.circuit.supply_pressure_pa, drive.circuit.tank_pressure_pa), (21e6, 5e5));
        assert_eq!((drive.controller.kp, drive.controller.ki, drive.controller.rate_hz), (5.0, 0.0, Some(250.0)));
    }

    #[test]
    fn a_servo_table_resolves_on_the_robots_servo() {
        let mut spec = default_with("\n[actuator]\nkind = \"servo\"\ncontroller = { kp = 2e6, ki = 2e6, kd = 5e5 }\n");
        spec.time.step_s = 0.002;
        let scenario = Scenario::from_spec(&default_path(), spec).unwrap();
        let Actuator::Servo(drive) = &scenario.model.drive.actuator else { panic!("not a servo") };
        assert_eq!(Some(drive.machine), scenario.model.robot.lift.servo);
        assert_eq!((drive.controller.kp, drive.controller.kd, drive.controller.rate_hz), (2e6, 5e5, None));
    }
}
