//! What the machine can hold and lift: the outer diameters its jaws close on, and the heaviest
//! string each of its lift drives holds against gravity at each lift angle.
//!
//! - **Jaws**: each jaw is a carried link on a prismatic joint, a box whose face nearest the
//!   string's axis (midway between the jaws, as the scene places the string) lies at
//!   `d₀ − h − q` from it, d₀ the joint origin's distance from the axis along the closing axis,
//!   h the box's half thickness along it and q the joint position within its URDF limits. The
//!   jaws close on outer diameters from 2 (d₀ − h − upper) to 2 (d₀ − h − lower), the narrowest
//!   jaw's range.
//! - **Lift**: the static moment balance about the pivot, the arm undeformed: holding the arm at
//!   lift angle θ takes τ(θ) = g cos θ (S₀ + m x_c), S₀ the first moment of the arm and its
//!   carried links about the pivot and m x_c the string's (mass m, centre of mass x_c out along
//!   the arm). Each drive gives at most a torque T(θ) lifting and T⁻(θ) holding back (past the
//!   vertical): the lift joint's URDF `effort` under the ideal drive, the servo's motor torque
//!   through its gear, the cylinder's force at relief pressure (cap side, the rod side at tank
//!   pressure; the reverse pulling) times its moment arm ds/dθ. The heaviest string at θ is
//!   m(θ) = (T(θ) / (g |cos θ|) − S₀) / x_c. Dynamic torque (the drive's acceleration, the
//!   impacts) comes on top; a run reports its peak drive torque against the effort.

use thiserror::Error;

use crate::actuator::{Actuator, Cylinders, HydraulicCircuit};
use crate::beam::{BeamError, BeamSpec};
use crate::model::{Model, Payload};
use crate::robot::{Mount, Robot, Shape};

/// Angles sampled along a drive's path for the lift check.
const PATH_SAMPLES: usize = 720;

/// The outer diameters a robot's jaws close on.
#[derive(Debug, Clone, PartialEq)]
pub struct JawRange {
    /// Smallest outer diameter, m (the jaws at their closing limit).
    pub min_diameter_m: f64,
    /// Largest, m (the jaws at their opening limit).
    pub max_diameter_m: f64,
    /// The jaws' links.
    pub jaws: Vec<String>,
}

impl JawRange {
    /// Whether the jaws close on a pipe of outer diameter `d` (m).
    pub fn holds(&self, d: f64) -> bool {
        (self.min_diameter_m - 1e-9..=self.max_diameter_m + 1e-9).contains(&d)
    }
}

/// The jaws' range, for a robot with two or more jaws (carried links on prismatic joints).
pub fn jaw_range(robot: &Robot) -> Option<JawRange> {
    let jaws: Vec<_> = robot.carried.iter().filter(|b| b.mount.is_prismatic()).collect();
    if jaws.len() < 2 {
        return None;
    }
    let n = jaws.len() as f64;
    let axis_point =
        [jaws.iter().map(|j| j.lateral_m).sum::<f64>() / n, jaws.iter().map(|j| j.normal_offset_m).sum::<f64>() / n];
    let (mut min_d, mut max_d) = (0.0_f64, f64::INFINITY);
    for jaw in &jaws {
        let Mount::Prismatic { axis, travel_m, .. } = jaw.mount else { continue };
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        let closing = [axis[0] / norm, axis[1] / norm, axis[2] / norm];
        // Distance from the jaw's origin to the axis along its closing direction.
        let d0 = (axis_point[0] - jaw.lateral_m) * closing[1] + (axis_point[1] - jaw.normal_offset_m) * closing[2];
        let half = match jaw.shapes.first().map(|s| s.shape) {
            Some(Shape::Box { half_extents_m: h }) => {
                (closing[0] * h[0]).abs() + (closing[1] * h[1]).abs() + (closing[2] * h[2]).abs()
            }
            Some(Shape::Cylinder { radius_m, .. }) | Some(Shape::Sphere { radius_m }) => radius_m,
            None => 0.0,
        };
        min_d = min_d.max(2.0 * (d0 - half - travel_m[1]));
        max_d = max_d.min(2.0 * (d0 - half - travel_m[0]));
    }
    Some(JawRange {
        min_diameter_m: min_d.max(0.0),
        max_diameter_m: max_d,
        jaws: jaws.iter().map(|j| j.name.clone()).collect(),
    })
}

/// A drive's torque limit on the lift joint.
#[derive(Debug, Clone, PartialEq)]
pub enum LiftLimit {
    /// The lift joint's URDF `effort` (the ideal drive), N·m.
    Effort { torque_n_m: f64 },
    /// The servo's motor torque limit through its gear, N·m at the hub.
    Servo { torque_n_m: f64 },
    /// The cylinders at the circuit's relief pressure (every cap side at relief pushing, every
    /// rod side pulling, the other side at tank).
    Cylinder { cylinders: Cylinders, relief_pressure_pa: f64, tank_pressure_pa: f64 },
}

impl LiftLimit {
    /// What it is, as the capacity table heads its column.
    pub fn name(&self) -> String {
        match self {
            LiftLimit::Effort { torque_n_m } => format!("joint effort {:.0} kN·m", torque_n_m / 1e3),
            LiftLimit::Servo { torque_n_m } => format!("servo {:.0} kN·m", torque_n_m / 1e3),
            LiftLimit::Cylinder { cylinders, relief_pressure_pa, .. } => match cylinders.each.len() {
                1 => format!("cylinder at {:.1} MPa relief", relief_pressure_pa / 1e6),
                n => format!("{n} cylinders at {:.1} MPa relief", relief_pressure_pa / 1e6),
            },
        }
    }

    /// The largest torque it gives at lift angle `angle_rad` (N·m): lifting (positive) and
    /// holding back (negative), as magnitudes.
    pub fn torque_n_m(&self, angle_rad: f64) -> (f64, f64) {
        match self {
            LiftLimit::Effort { torque_n_m } | LiftLimit::Servo { torque_n_m } => (*torque_n_m, *torque_n_m),
            LiftLimit::Cylinder { cylinders, relief_pressure_pa, tank_pressure_pa } => {
                // Areas times moment arms, summed: the hub torque per pascal on each side.
                let (a_cap, a_rod) = cylinders.moment_areas_m3(angle_rad);
                let push = relief_pressure_pa * a_cap - tank_pressure_pa * a_rod;
                let pull = relief_pressure_pa * a_rod - tank_pressure_pa * a_cap;
                (push.max(-pull), pull.max(-push))
            }
        }
    }
}

/// Every lift drive of a scene: the effort, the robot's servo, and its cylinder where the
/// scene's hydraulic circuit gives the relief pressure.
pub fn lift_limits(model: &Model) -> Vec<LiftLimit> {
    let lift = &model.robot.lift;
    let mut limits = vec![LiftLimit::Effort { torque_n_m: lift.effort_n_m }];
    if let Some(servo) = lift.servo {
        limits.push(LiftLimit::Servo { torque_n_m: servo.hub_torque_limit_n_m() });
    }
    if let Actuator::Hydraulic(drive) = &model.drive.actuator {
        limits.push(cylinder_limit(&drive.cylinders, &drive.circuit));
    }
    limits
}

fn cylinder_limit(cylinders: &Cylinders, circuit: &HydraulicCircuit) -> LiftLimit {
    LiftLimit::Cylinder {
        cylinders: cylinders.clone(),
        relief_pressure_pa: circuit.relief_pressure_pa,
        tank_pressure_pa: circuit.tank_pressure_pa,
    }
}

/// The drive that lifts in this scene: its actuator's.
pub fn scene_limit(model: &Model) -> LiftLimit {
    match &model.drive.actuator {
        Actuator::Ideal => LiftLimit::Effort { torque_n_m: model.robot.lift.effort_n_m },
        Actuator::Servo(servo) => LiftLimit::Servo { torque_n_m: servo.machine.hub_torque_limit_n_m() },
        Actuator::Hydraulic(drive) => cylinder_limit(&drive.cylinders, &drive.circuit),
    }
}

/// First moment about the pivot of the arm and its carried links, kg·m.
pub fn machine_first_moment_kg_m(robot: &Robot) -> Result<f64, BeamError> {
    Ok(first_moment_kg_m(&robot.beam_spec(&[])?))
}

fn first_moment_kg_m(spec: &BeamSpec) -> f64 {
    let mut x = 0.0;
    let mut moment = 0.0;
    for s in &spec.segments {
        moment += s.mass_per_length_kg_m * ((x + s.length_m).powi(2) - x * x) / 2.0;
        x += s.length_m;
    }
    moment + spec.masses.iter().map(|m| m.mass_kg * m.position_m).sum::<f64>()
}

/// The payload's mass (kg) and the arm station of its centre of mass (m); none for a string on
/// the tilting head, whose mass the machine's head carries already.
pub fn payload_mass_and_station(payload: &Payload) -> (f64, f64) {
    match payload {
        Payload::None | Payload::StringOnHead(_) => (0.0, 0.0),
        Payload::Lumped(m) => (m.mass_kg, m.position_m),
        Payload::String(held) => (held.pipe.mass_kg(), held.mass_centre_m()),
    }
}

/// The heaviest payload with its centre of mass at `station_m` that `limit` holds at
/// `angle_rad`, kg (infinite where gravity has no lever, negative where it cannot hold the arm
/// alone).
pub fn heaviest_kg(limit: &LiftLimit, angle_rad: f64, machine_kg_m: f64, station_m: f64, gravity_m_s2: f64) -> f64 {
    let lever = gravity_m_s2 * angle_rad.cos();
    if lever.abs() < 1e-12 || station_m <= 0.0 {
        return f64::INFINITY;
    }
    let (lifting, holding_back) = limit.torque_n_m(angle_rad);
    let torque = if lever > 0.0 { lifting } else { holding_back };
    (torque / lever.abs() - machine_kg_m) / station_m
}

/// Why a machine cannot take a payload.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CapacityError {
    /// The pipe is outside the jaws' range.
    #[error(
        "a pipe of {:.1} mm outer diameter: the jaws of {robot} ({}) close on outer diameters {:.1} ..= {:.1} mm (their prismatic joints' limits)",
        1e3 * diameter_m, range.jaws.join(", "), 1e3 * range.min_diameter_m, 1e3 * range.max_diameter_m
    )]
    Jaws { robot: String, diameter_m: f64, range: JawRange },
    /// The drive cannot hold the payload somewhere on the path.
    #[error(
        "{mass_kg:.1} kg with its centre of mass {station_m:.3} m out needs {:.1} kN·m at {:.1} deg to hold against gravity, \
         above the {limit} of {robot}'s lift joint: the heaviest it lifts through the drive's path ({:.1} ..= {:.1} deg) is \
         {heaviest_kg:.1} kg (at {:.1} deg)",
        needed_n_m / 1e3, angle_rad.to_degrees(), path_rad.0.to_degrees(), path_rad.1.to_degrees(), worst_rad.to_degrees()
    )]
    Lift {
        robot: String,
        mass_kg: f64,
        station_m: f64,
        needed_n_m: f64,
        angle_rad: f64,
        limit: String,
        path_rad: (f64, f64),
        heaviest_kg: f64,
        worst_rad: f64,
    },
    /// The drive cannot hold the arm itself somewhere on the path, without any payload.
    #[error(
        "the arm of {robot} alone needs {:.1} kN·m at {:.1} deg to hold against gravity, above the {limit} of its lift joint",
        needed_n_m / 1e3, angle_rad.to_degrees()
    )]
    ArmAlone { robot: String, needed_n_m: f64, angle_rad: f64, limit: String },
    /// The machine's own description.
    #[error("{0}")]
    Beam(#[from] BeamError),
}

/// The scene's payload against its machine: its pipe within the jaws, and its weight within the
/// scene's drive at every angle of the drive's path.
pub fn check(model: &Model) -> Result<(), CapacityError> {
    let robot = &model.robot;
    if let (Some(held), Some(range)) = (model.payload.string(), jaw_range(robot)) {
        let diameter_m = held.pipe.pipe.outer_diameter_m;
        if !range.holds(diameter_m) {
            return Err(CapacityError::Jaws { robot: robot.name.clone(), diameter_m, range });
        }
    }
    let g = model.physics.gravity_m_s2;
    let (mass_kg, station_m) = payload_mass_and_station(&model.payload);
    let machine = machine_first_moment_kg_m(robot)?;
    let limit = scene_limit(model);
    let path = model.drive.motion.angle_range_rad(model.duration_s());
    let angles = (0..=PATH_SAMPLES).map(|i| path.0 + (path.1 - path.0) * i as f64 / PATH_SAMPLES as f64);
    let heaviest = |a: f64| heaviest_kg(&limit, a, machine, station_m, g);
    let worst = angles.min_by(|a, b| heaviest(*a).total_cmp(&heaviest(*b))).expect("one angle at least");
    if heaviest(worst) >= mass_kg {
        return Ok(());
    }
    let torque = |a: f64| limit.torque_n_m(a);
    let needed = |a: f64| g * a.cos() * (machine + mass_kg * station_m);
    let short = |a: f64| {
        let (up, down) = torque(a);
        let n = needed(a);
        if n >= 0.0 { n - up } else { -n - down }
    };
    let angles = (0..=PATH_SAMPLES).map(|i| path.0 + (path.1 - path.0) * i as f64 / PATH_SAMPLES as f64);
    let angle_rad = angles.max_by(|a, b| short(*a).total_cmp(&short(*b))).expect("one angle at least");
    if heaviest(worst) < 0.0 {
        let needed_n_m = (g * angle_rad.cos() * machine).abs();
        return Err(CapacityError::ArmAlone { robot: robot.name.clone(), needed_n_m, angle_rad, limit: limit.name() });
    }
    Err(CapacityError::Lift {
        robot: robot.name.clone(),
        mass_kg,
        station_m,
        needed_n_m: needed(angle_rad).abs(),
        angle_rad,
        limit: limit.name(),
        path_rad: path,
        heaviest_kg: heaviest(worst).max(0.0),
        worst_rad: worst,
    })
}
