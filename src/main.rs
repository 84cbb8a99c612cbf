//! The `pipearm` command line: a thin layer over the library.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};

use pipearm::analysis::{StiffnessClass, summarize};
use pipearm::arm::{ArmSample, ArmSimulation, Fidelity, STANDARD_GRAVITY_M_S2};
use pipearm::beam::BeamModel;
use pipearm::scenario::Scenario;

/// Flexible pipe-handling arms and the impacts on their dampeners.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scenario's lift and print its summary.
    Run {
        /// Scenario file.
        #[arg(default_value = "scenarios/default.toml")]
        scenario: PathBuf,
        /// Override the model: rigid, modal:N or fe.
        #[arg(long, value_parser = parse_fidelity)]
        model: Option<Fidelity>,
        /// Write the time history (t, hub angle, tip deflection, torque, ...) as CSV.
        #[arg(long)]
        csv: Option<PathBuf>,
    },
    /// Print the arm's clamped natural frequencies, λL, modal masses and static w/l.
    Modes {
        /// Scenario file whose arm to analyse.
        #[arg(default_value = "scenarios/default.toml")]
        scenario: PathBuf,
        /// Number of modes to print.
        #[arg(long, default_value_t = 6)]
        count: usize,
        /// Steady spin rate of the hub, rad/s.
        #[arg(long, default_value_t = 0.0)]
        spin: f64,
        /// Leave out centrifugal stiffening at --spin (the model that fails past ω₁).
        #[arg(long)]
        no_stiffening: bool,
    },
}

fn parse_fidelity(s: &str) -> Result<Fidelity, String> {
    match s {
        "rigid" => Ok(Fidelity::Rigid),
        "fe" => Ok(Fidelity::Fe),
        _ => s
            .strip_prefix("modal:")
            .and_then(|n| n.parse().ok())
            .map(|modes| Fidelity::Modal { modes })
            .ok_or_else(|| format!("`{s}`: expected rigid, modal:N or fe")),
    }
}

fn main() -> Result<()> {
    match Cli::parse().command {
        Command::Run { scenario, model, csv } => run(&scenario, model, csv.as_deref()),
        Command::Modes { scenario, count, spin, no_stiffening } => modes(&scenario, count, spin, !no_stiffening),
    }
}

fn run(path: &Path, model: Option<Fidelity>, csv: Option<&Path>) -> Result<()> {
    let scenario = Scenario::load(path)?;
    let fidelity = model.unwrap_or(scenario.model);
    let arm = scenario.arm_model(fidelity).with_context(|| format!("{}: building the arm", path.display()))?;
    let drive_end_s = scenario.motion()?.duration_s();
    let mut sim = ArmSimulation::new(arm, scenario.hub_drive()?, scenario.integrator)?;
    let mut samples: Vec<ArmSample> = Vec::new();
    let started = Instant::now();
    sim.run_until(scenario.duration_s(), scenario.time.step_s, |s| samples.push(s.clone()))?;
    let wall_s = started.elapsed().as_secs_f64();
    let summary = summarize(&samples, drive_end_s);
    let w_over_l = sim.arm.beam.gravity_tip_deflection_m(STANDARD_GRAVITY_M_S2)? / sim.arm.length_m();
    println!("scenario            {} ({})", scenario.name, path.display());
    println!(
        "model               {fidelity}, {} elastic coordinates, {}",
        sim.arm.elastic_dofs(),
        integrator_name(&scenario)
    );
    println!("static w/l          1/{:.0}: {}", 1.0 / w_over_l, StiffnessClass::of_ratio(w_over_l).describe());
    println!(
        "simulated           {:.3} s in {} steps of {} s",
        scenario.duration_s(),
        samples.len() - 1,
        scenario.time.step_s
    );
    println!("peak tip deflection {:.3} mm", 1e3 * summary.peak_tip_deflection_m);
    let frequency = match summary.residual_frequency_hz {
        f if f.is_finite() => format!("at {f:.3} Hz"),
        _ => "(no oscillation)".to_string(),
    };
    println!("residual amplitude  {:.3} mm {frequency}", 1e3 * summary.residual_amplitude_m);
    println!("peak drive torque   {:.1} kN·m", 1e-3 * summary.peak_drive_torque_n_m);
    println!("wall time           {:.3} s ({:.0}x real time)", wall_s, scenario.duration_s() / wall_s);
    if let Some(csv) = csv {
        write_csv(csv, &samples)?;
        println!("time history        {}", csv.display());
    }
    Ok(())
}

fn integrator_name(scenario: &Scenario) -> String {
    format!("{:?}", scenario.integrator)
}

/// Writes to a temporary file and renames it, so a failure leaves no partial output.
fn write_csv(path: &Path, samples: &[ArmSample]) -> Result<()> {
    let tmp = path.with_extension("csv.tmp");
    let mut out =
        std::io::BufWriter::new(std::fs::File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?);
    writeln!(
        out,
        "t_s,hub_angle_rad,hub_rate_rad_s,hub_accel_rad_s2,tip_u_m,tip_v_m,tip_vu_m_s,tip_vv_m_s,drive_torque_n_m,kinetic_j,strain_j,gravity_j"
    )?;
    for s in samples {
        let e = s.energies;
        writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            s.t_s,
            s.hub.angle_rad,
            s.hub.rate_rad_s,
            s.hub.accel_rad_s2,
            s.tip_deflection_hub_m[0],
            s.tip_deflection_hub_m[1],
            s.tip_velocity_hub_m_s[0],
            s.tip_velocity_hub_m_s[1],
            s.drive_torque_n_m,
            e.kinetic_j,
            e.strain_j,
            e.gravity_j
        )?;
    }
    out.into_inner().map_err(|e| e.into_error())?.sync_all()?;
    std::fs::rename(&tmp, path)?;
    Ok(())
}

fn modes(path: &Path, count: usize, spin_rad_s: f64, stiffening: bool) -> Result<()> {
    let scenario = Scenario::load(path)?;
    if !(spin_rad_s.is_finite() && spin_rad_s >= 0.0) {
        bail!("--spin = {spin_rad_s}: allowed a finite rate >= 0 rad/s");
    }
    let beam = BeamModel::new(scenario.beam_spec()?)?;
    let basis = if spin_rad_s > 0.0 { beam.modes_spinning(spin_rad_s, stiffening)? } else { beam.modes()? };
    let l = beam.length_m();
    // λL from the length-averaged EI and ρA (exact for a uniform arm).
    let (ei, mu) = beam.elements.iter().fold((0.0, 0.0), |(ei, mu), e| {
        (ei + e.bending_rigidity_n_m2 * e.length_m / l, mu + e.mass_per_length_kg_m * e.length_m / l)
    });
    let [_, tip_v, _] = beam.point_rows(l);
    println!(
        "arm of {} ({} elements, L = {l} m, {} DOFs), spin {spin_rad_s} rad/s{}",
        scenario.name,
        beam.elements.len(),
        beam.dofs(),
        if stiffening { "" } else { " without stiffening" }
    );
    println!("{:>4} {:>12} {:>12} {:>10} {:>16}", "mode", "f (Hz)", "ω (rad/s)", "λL", "tip modal mass (kg)");
    for i in 0..count.min(basis.len()) {
        let w = basis.omegas_rad_s[i];
        let tip = tip_v.dot(&basis.shapes.column(i));
        let lambda_l = (w * w * mu / ei).powf(0.25) * l;
        let tip_mass = if tip.abs() > 1e-12 { format!("{:.4e}", 1.0 / (tip * tip)) } else { "axial/no tip".into() };
        println!("{:>4} {:>12.5} {:>12.5} {:>10.5} {:>16}", i + 1, w / std::f64::consts::TAU, w, lambda_l, tip_mass);
    }
    let w = beam.gravity_tip_deflection_m(STANDARD_GRAVITY_M_S2)?;
    println!(
        "static tip deflection, horizontal under gravity: {:.3} mm, w/l = 1/{:.0}: {}",
        w * 1e3,
        l / w,
        StiffnessClass::of_ratio(w / l).describe()
    );
    Ok(())
}
