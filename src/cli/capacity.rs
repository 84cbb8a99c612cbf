//! `pipearm capacity [SCENARIO]`: what the scenario's machine holds and lifts.

use std::path::{Path, PathBuf};

use anyhow::{Result, bail};
use clap::Args;

use pipearm::capacity::{
    heaviest_kg, jaw_range, lift_limits, machine_first_moment_kg_m, payload_mass_and_station, scene_limit,
};
use pipearm::scenario::Scenario;

/// `pipearm capacity`' arguments.
#[derive(Args)]
#[command(after_help = super::help::CAPACITY)]
pub struct CapacityArgs {
    /// Scenario file (its robot, actuator and payload placement).
    #[arg(default_value = "scenarios/default.toml")]
    pub scenario: PathBuf,
    /// Lift angle step of the table, degrees.
    #[arg(long, default_value_t = 10.0)]
    pub step_deg: f64,
}

/// Prints the jaws' range and, per lift angle, the heaviest payload each drive holds with its
/// centre of mass where the scenario's payload has it.
pub fn capacity(path: &Path, step_deg: f64) -> Result<()> {
    if !(step_deg.is_finite() && step_deg >= 0.1) {
        bail!("--step-deg = {step_deg}: allowed >= 0.1");
    }
    let scenario = Scenario::load_beyond_capacity(path)?;
    let model = &scenario.model;
    let robot = &model.robot;
    let g = model.physics.gravity_m_s2;
    println!("capacity of {} ({}), scenario {}", robot.name, robot.source.display(), model.name);
    let string = model.payload.string();
    match jaw_range(robot) {
        Some(range) => println!(
            "jaws {} close on outer diameters {:.1} ..= {:.1} mm{}",
            range.jaws.join(", "),
            1e3 * range.min_diameter_m,
            1e3 * range.max_diameter_m,
            string.map_or(String::new(), |h| format!("; this string's {:.1} mm", 1e3 * h.pipe.pipe.outer_diameter_m))
        ),
        None => println!("no jaws (fewer than two links on prismatic joints)"),
    }
    let machine = machine_first_moment_kg_m(robot)?;
    let (mass_kg, mut station_m) = payload_mass_and_station(&model.payload);
    if station_m <= 0.0 {
        station_m = robot.arm.length_m();
    }
    println!(
        "arm and carried links: {machine:.1} kg·m about the pivot; payload centre of mass {station_m:.3} m out{}",
        match &model.payload {
            pipearm::model::Payload::StringOnHead(_) =>
                " (the string is rigid with the tilting head: in the machine's moment)",
            _ if string.is_none() && mass_kg == 0.0 => " (no payload: at the arm's tip)",
            _ => "",
        }
    );
    let limits = lift_limits(model);
    let (lo, hi) = robot.lift.limits_rad;
    let mut angles = vec![lo];
    let step = step_deg.to_radians();
    let mut a = (lo / step).floor() * step + step;
    while a < hi - 1e-9 {
        if a > lo + 1e-9 {
            angles.push(a);
        }
        a += step;
    }
    angles.push(hi);
    println!("heaviest payload held against gravity, kg:");
    let heads: Vec<String> = limits.iter().map(|l| format!("{:>28}", l.name())).collect();
    println!("{:>9} {}", "angle_deg", heads.join(" "));
    for &angle in &angles {
        let cells: Vec<String> =
            limits.iter().map(|l| format!("{:>28}", cell(heaviest_kg(l, angle, machine, station_m, g)))).collect();
        println!("{:>9.1} {}", angle.to_degrees(), cells.join(" "));
    }
    let limit = scene_limit(model);
    let (p0, p1) = model.drive.motion.angle_range_rad(model.duration_s());
    let path: Vec<f64> = (0..=720).map(|i| p0 + (p1 - p0) * i as f64 / 720.0).collect();
    let heaviest = |a: f64| heaviest_kg(&limit, a, machine, station_m, g);
    let worst = path.iter().copied().min_by(|a, b| heaviest(*a).total_cmp(&heaviest(*b))).unwrap_or(p0);
    let label = string.map_or("payload".to_string(), |h| format!("string {}", h.pipe.pipe.label));
    println!(
        "on the drive's path ({:.1} ..= {:.1} deg) the scene's drive ({}) lifts at most {} kg (at {:.1} deg); the {label}: {mass_kg:.1} kg",
        p0.to_degrees(),
        p1.to_degrees(),
        limit.name(),
        cell(heaviest(worst)),
        worst.to_degrees()
    );
    Ok(())
}

/// A heaviest payload as the table prints it.
fn cell(kg: f64) -> String {
    if kg.is_infinite() {
        "no limit".into()
    } else if kg < 0.0 {
        "none (arm alone)".into()
    } else {
        format!("{kg:.1}")
    }
}
