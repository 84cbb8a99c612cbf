//! `pipearm envelope`: a scenario over spread keys, per string size; percentiles, chart and
//! sensitivity ranking.

use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;

use pipearm::envelope::cases::MethodChoice;
use pipearm::envelope::dist::Spread;
use pipearm::envelope::{Envelope, Merged, Progress, Request};
use pipearm::sweep::{Shard, Vary};

/// `pipearm envelope`: its arguments, or `merge DIR`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true, after_help = super::help::ENVELOPE)]
pub struct EnvelopeArgs {
    #[command(subcommand)]
    command: Option<EnvelopeCommand>,
    /// Base scenario file.
    #[arg(required = true)]
    scenario: Option<PathBuf>,
    /// A spread key: KEY=uniform:A..B, KEY=normal:MEAN,SD,A..B (truncated; unbounded
    /// normal:MEAN,SD only on a key that takes any number) or KEY=triangular:A,MODE,B. Repeat.
    #[arg(long, value_name = "KEY=DIST", required = true)]
    spread: Vec<Spread>,
    /// Runs per group (per value of --per); at least 2.
    #[arg(long, value_name = "N", required = true)]
    samples: Option<usize>,
    /// A grouping key and its values, e.g. payload.size=2-3/8,2-7/8,3-1/2,4-1/2: an envelope
    /// per value, all with the same draws of the spread keys. payload.size also takes catalogue
    /// entries (9-5/8@47.00) and classes (casing, drill-collar, ..., liftable).
    #[arg(long, value_name = "KEY=VALUES")]
    per: Option<Vary>,
    /// Seed of the draw: the same seed gives the same runs on any thread count or shards.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Sensitivity method: sobol (first-order and total indices; N/(k+2) base rows), regression
    /// (standardized coefficients) or auto (sobol from 64 base rows on).
    #[arg(long, default_value = "auto", value_parser = |s: &str| s.parse::<MethodChoice>())]
    sensitivity: MethodChoice,
    /// Output folder: plan.json, sampling.json, cases/, results.*, envelope.json, envelope.csv,
    /// force_vs_weight.svg.
    #[arg(long, default_value = "recordings/envelope")]
    out: PathBuf,
    /// Worker threads (default: one per CPU).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    threads: Option<u32>,
    /// Run only shard I of N (runs with index % N == I); merge afterwards.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
}

#[derive(Subcommand)]
enum EnvelopeCommand {
    /// Join a sharded envelope's runs into its figures, table and chart.
    Merge {
        /// The envelope's output folder.
        dir: PathBuf,
    },
}

pub fn envelope(args: EnvelopeArgs) -> Result<()> {
    if let Some(EnvelopeCommand::Merge { dir }) = args.command {
        return print(&pipearm::envelope::merge(&dir)?);
    }
    let shard = args.shard.unwrap_or(Shard::ALL);
    let request = Request {
        scenario: args.scenario.expect("required by clap"),
        spreads: args.spread,
        samples: args.samples.expect("required by clap"),
        per: args.per,
        seed: args.seed,
        method: args.sensitivity,
        out: args.out,
        threads: args.threads.map(|n| n as usize),
        shard,
    };
    let bar = indicatif::ProgressBar::new(0)
        .with_style(indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed}, eta {eta}")?);
    let report = pipearm::envelope::envelope(&request, &|p| match p {
        Progress::Start { todo } => bar.set_length(todo as u64),
        Progress::Done { .. } => bar.inc(1),
    })?;
    bar.finish_and_clear();
    println!(
        "shard {}/{}: ran {}, skipped {} current, of {} runs ({} per group); run files in {}",
        shard.index,
        shard.count,
        report.ran,
        report.current,
        report.cases,
        report.sampling.runs_per_group,
        request.out.join("cases").display()
    );
    match &report.merged {
        Some(merged) => print(merged),
        None => {
            println!("when every shard is done: pipearm envelope merge {}", request.out.display());
            Ok(())
        }
    }
}

fn print(merged: &Merged) -> Result<()> {
    print_envelope(&merged.envelope);
    let files: Vec<String> = merged.files.iter().map(|f| f.display().to_string()).collect();
    println!("wrote {}", files.join(", "));
    Ok(())
}

fn print_envelope(envelope: &Envelope) {
    println!("{}: {} runs per group, seed {}", envelope.scenario, envelope.runs_per_group, envelope.seed);
    println!(
        "{:>10} {:>9} {:>5}  {:>9} {:>9} {:>9} {:>9}  {:>12} {:>12}",
        "group", "weight N", "div", "F p50 N", "F p95 N", "F p99 N", "F max N", "resid p95 mm", "resid max mm"
    );
    for g in &envelope.groups {
        let (f, r) = (g.peak_force_n, g.residual_amplitude_m);
        println!(
            "{:>10} {:>9.0} {:>5}  {:>9.1} {:>9.1} {:>9.1} {:>9.1}  {:>12.3} {:>12.3}",
            g.per.as_deref().unwrap_or("all"),
            g.weight_n,
            g.diverged,
            f.p50,
            f.p95,
            f.p99,
            f.max,
            r.p95 * 1e3,
            r.max * 1e3
        );
    }
    for g in &envelope.groups {
        for s in &g.sensitivity {
            let show =
                |i: &pipearm::envelope::sensitivity::Index| format!("{:.2} [{:.2}, {:.2}]", i.estimate, i.low, i.high);
            let ranking: Vec<String> = s
                .ranking
                .iter()
                .map(|k| match (&k.first, &k.total, &k.coefficient) {
                    (Some(first), Some(total), _) => format!("{} total {}, first {}", k.key, show(total), show(first)),
                    (_, _, Some(c)) => format!("{} {}", k.key, show(c)),
                    _ => k.key.clone(),
                })
                .collect();
            let method = match s.r_squared {
                Some(r2) => format!("{}, R² {r2:.2}", s.method),
                None => s.method.to_string(),
            };
            let what = s.not_estimated.clone().unwrap_or_else(|| ranking.join("; "));
            println!("sensitivity of {} ({}, {method}): {what}", s.figure, g.per.as_deref().unwrap_or("all"));
        }
    }
}
