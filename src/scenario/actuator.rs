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

use super::{Check, ScenarioError};
use crate::actuator::{Actuator, ControllerGains, Cylinder, HydraulicCircuit, HydraulicDrive, ServoDrive, Valve};

use crate::drive::MotionLaw;
use crate::model::Model;
use crate::robot::Robot;

/// Angles sampled along the drive's path when the cylinder's length is checked on it.
const PATH_SAMPLES: usize = 2000;

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
    /// drive's path (the closed loop, which needs the compiled arm, is checked when the scenario
    /// is compiled: [`super::compile`]).
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
        Ok(())
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
        // longer step would pass the limit the drive's fastest pole sets (an error of its compile).
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
