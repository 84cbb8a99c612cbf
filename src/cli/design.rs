//! `pipearm design`: the fastest safe lift (or any objective under limits), nominal or robust,
//! and the seed's table of acceleration limits per drive profile.

use std::path::PathBuf;

use anyhow::{Result, bail};

use pipearm::design::table::acceleration_table;
use pipearm::design::{Design, Limit, Over, Request, Robustness, design, write_json};
use pipearm::envelope::dist::Spread;

/// The table's limit on the residual amplitude where `--limit` sets none, m.
const DEFAULT_RESIDUAL_LIMIT_M: f64 = 1e-3;

/// `pipearm design` arguments.
#[derive(clap::Args)]
#[command(after_help = super::help::DESIGN)]
pub struct DesignArgs {
    /// Scenario file.
    scenario: PathBuf,
    /// A limit on a figure of the run's summary: KEY<=VALUE or KEY>=VALUE (peak_force_n is the
    /// largest pair's peak force; else a dotted summary path such as residual.amplitude_m).
    #[arg(long, value_name = "KEY<=VALUE")]
    limit: Vec<Limit>,
    /// What to minimise: one of the --over keys (e.g. drive.duration_s) or a figure.
    #[arg(long, value_name = "KEY", required_unless_present_any = ["table", "maximize"], conflicts_with = "maximize")]
    minimize: Option<String>,
    /// What to maximise instead: one of the --over keys (e.g. drive.accel_deg_s2) or a figure.
    #[arg(long, value_name = "KEY")]
    maximize: Option<String>,
    /// A searched key and its range: KEY=A..B. Repeat.
    #[arg(long, value_name = "KEY=A..B", required_unless_present = "table")]
    over: Vec<Over>,
    /// Hold the limits at the envelope's p95 over these spreads (as `pipearm envelope`).
    #[arg(long, value_name = "KEY=DIST", requires = "samples", conflicts_with = "nominal")]
    spread: Vec<Spread>,
    /// Draws of the spreads per candidate (the same draws for every candidate).
    #[arg(long, value_name = "N")]
    samples: Option<usize>,
    /// Hold the limits in the scenario's own run (the default without --spread).
    #[arg(long)]
    nominal: bool,
    /// Seed of the draws.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The seed's table instead of a search: per drive profile (trapezoidal, S-curve, each
    /// shaper), the largest start/stop acceleration within the limits (residual.amplitude_m <=
    /// 0.001 unless --limit sets it).
    #[arg(long, conflicts_with_all = ["minimize", "maximize", "over"])]
    table: bool,
    /// Relative tolerance of the search on each key (of its range).
    #[arg(long, default_value_t = 0.01)]
    tolerance: f64,
    /// Most candidates a search evaluates.
    #[arg(long, default_value_t = 40)]
    budget: usize,
    /// Worker threads (default: one per CPU).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    threads: Option<u32>,
    /// Output file (JSON).
    #[arg(long, default_value = "recordings/design.json")]
    out: PathBuf,
}

pub fn design_command(args: DesignArgs) -> Result<()> {
    if args.samples.is_some() && args.spread.is_empty() {
        bail!("--samples without --spread: allowed with one or more --spread KEY=DIST");
    }
    if args.budget < 2 {
        bail!("--budget {}: allowed 2 or more candidates", args.budget);
    }
    let robustness = if args.spread.is_empty() {
        Robustness::Nominal
    } else {
        Robustness::Envelope { spreads: args.spread, samples: args.samples.expect("required by clap"), seed: args.seed }
    };
    if !(args.tolerance > 0.0 && args.tolerance < 1.0) {
        bail!("--tolerance {}: allowed 0 < tolerance < 1", args.tolerance);
    }
    let threads = args.threads.map(|n| n as usize);
    if args.table {
        let mut limits = args.limit;
        if !limits.iter().any(|l| l.figure == "residual.amplitude_m") {
            limits.insert(
                0,
                Limit { figure: "residual.amplitude_m".into(), bound: DEFAULT_RESIDUAL_LIMIT_M, upper: true },
            );
        }
        let table = acceleration_table(&args.scenario, &limits, &robustness, args.tolerance, threads)?;
        println!(
            "largest start/stop acceleration within the limits ({} runs per candidate):",
            table.runs_per_candidate
        );
        let names: Vec<String> = table.limits.iter().map(show_limit).collect();
        println!(
            "{:>12} {:>7} {:>18} {:>9}  {}  {:>10}",
            "profile",
            "shaper",
            "accel deg/s^2",
            "ramp",
            names.join("  "),
            "candidates"
        );
        for row in &table.rows {
            let accel = match row.largest_accel_deg_s2 {
                Some(a) if row.at_least => format!(">= {a:.2}"),
                Some(a) => format!("{a:.2}"),
                None => "none".into(),
            };
            let figures: Vec<String> =
                row.figures.iter().zip(&names).map(|(f, n)| format!("{f:>w$.4e}", w = n.len())).collect();
            println!(
                "{:>12} {:>7} {:>18} {:>9} {}  {:>10}",
                row.profile,
                row.shaper.as_deref().unwrap_or("-"),
                accel,
                row.ramp_fraction.map_or("-".into(), |f| format!("{f:.4}")),
                figures.join("  "),
                row.candidates
            );
        }
        write_json(&args.out, &table)?;
        println!("wrote {}", args.out.display());
        return Ok(());
    }
    let request = Request {
        scenario: args.scenario,
        limits: args.limit,
        maximize: args.maximize.is_some(),
        objective: args.minimize.or(args.maximize).expect("required by clap"),
        over: args.over,
        robustness,
        tolerance: args.tolerance,
        budget: args.budget,
        threads,
    };
    let found = design(&request)?;
    print_design(&found);
    write_json(&args.out, &found)?;
    println!("wrote {}", args.out.display());
    Ok(())
}

fn show_limit(limit: &Limit) -> String {
    format!("{}{}{}", limit.figure, if limit.upper { "<=" } else { ">=" }, limit.bound)
}

fn print_design(found: &Design) {
    println!(
        "{} search: {} candidates, {} runs ({} per candidate)",
        found.outcome.method, found.candidates, found.runs, found.runs_per_candidate
    );
    match &found.outcome.best {
        Some(best) => {
            let keys: Vec<String> = found.keys.iter().zip(&best.x).map(|(k, v)| format!("{k} = {v:.6}")).collect();
            println!("best: {} ({} = {:.6})", keys.join(", "), found.objective, best.objective);
            for (limit, figure) in found.limits.iter().zip(&best.figures) {
                println!("  {:<40} {figure:.6e}", show_limit(limit));
            }
        }
        None => println!("no candidate in the box meets every limit"),
    }
}
