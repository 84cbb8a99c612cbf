//! `pipearm sweep`: parallel runs over varied scenario keys, sharded or not, and their merge.

use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;

/// `pipearm sweep`: its arguments, or `merge DIR`, or `chart DIR... --out FILE`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true, after_help = super::help::SWEEP)]
pub struct SweepArgs {
    #[command(subcommand)]
    command: Option<SweepCommand>,
    /// Base scenario file.
    #[arg(required = true)]
    scenario: Option<PathBuf>,
    /// A varied key: KEY=V1,V2,... or KEY=A..B:STEP (B included); repeat for a Cartesian product.
    /// payload.size also takes catalogue entries (9-5/8@47.00) and classes (casing, tubing,
    /// drill-pipe, heavy-weight-drill-pipe, drill-collar, liftable).
    #[arg(long, value_name = "KEY=VALUES")]
    vary: Vec<pipearm::sweep::Vary>,
    /// Output folder: plan.json, cases/, results.csv, results.json, force_vs_weight.svg.
    #[arg(long, default_value = "recordings/sweep")]
    out: PathBuf,
    /// Worker threads (default: rayon's, one per CPU).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    threads: Option<u32>,
    /// Run only shard I of N (cases with index % N == I, I from 0); merge afterwards.
    #[arg(long, value_name = "I/N", conflicts_with = "shard_count")]
    shard: Option<pipearm::sweep::Shard>,
    /// Run one of N shards, I from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX; merge afterwards
    /// (`--shards N` is the old spelling, still read).
    #[arg(long, value_name = "N", alias = "shards")]
    shard_count: Option<usize>,
}

#[derive(Subcommand)]
enum SweepCommand {
    /// Join a sharded sweep's case files into results.csv, results.json and force_vs_weight.svg.
    Merge {
        /// The sweep's output folder.
        dir: PathBuf,
    },
    /// Draw finished sweeps on one chart of peak contact force against string weight.
    Chart {
        /// The sweeps' output folders (each with plan.json and cases/).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// A label per folder, in the same order (default: the folder's name).
        #[arg(long)]
        label: Vec<String>,
        /// The chart's title.
        #[arg(long, default_value = "peak contact force against string weight")]
        title: String,
        /// The SVG file to write.
        #[arg(long)]
        out: PathBuf,
    },
}

pub fn sweep(args: SweepArgs) -> Result<()> {
    use pipearm::sweep::{Progress, Request, Shard, merge};
    match args.command {
        Some(SweepCommand::Merge { dir }) => return print_merged(&merge(&dir)?),
        Some(SweepCommand::Chart { dirs, label, title, out }) => return chart(dirs, label, &title, &out),
        None => {}
    }
    let shard = match (args.shard, args.shard_count) {
        (Some(shard), _) => shard,
        (None, Some(count)) => Shard::from_env(count, |name| std::env::var(name).ok())?,
        (None, None) => Shard::ALL,
    };
    let request = Request {
        scenario: args.scenario.expect("required by clap"),
        vary: args.vary,
        out: args.out,
        threads: args.threads.map(|n| n as usize),
        shard,
    };
    let bar = indicatif::ProgressBar::new(0)
        .with_style(indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} cases, {elapsed}, eta {eta}")?);
    let report = pipearm::sweep::sweep(&request, &|p| match p {
        Progress::Start { todo } => bar.set_length(todo as u64),
        Progress::Done { .. } => bar.inc(1),
    })?;
    bar.finish_and_clear();
    println!(
        "shard {}/{}: ran {}, skipped {} current, of {} cases; case files in {}",
        shard.index,
        shard.count,
        report.ran,
        report.current,
        report.cases,
        request.out.join("cases").display()
    );
    match &report.merged {
        Some(merged) => print_merged(merged),
        None => {
            println!("when every shard is done: pipearm sweep merge {}", request.out.display());
            Ok(())
        }
    }
}

fn chart(dirs: Vec<PathBuf>, labels: Vec<String>, title: &str, out: &std::path::Path) -> Result<()> {
    if !labels.is_empty() && labels.len() != dirs.len() {
        anyhow::bail!(
            "--label given {} times for {} folders: allowed one per folder, or none",
            labels.len(),
            dirs.len()
        );
    }
    let labelled: Vec<(String, PathBuf)> = dirs
        .into_iter()
        .enumerate()
        .map(|(i, dir)| {
            let label =
                labels.get(i).cloned().unwrap_or_else(|| dir.file_name().unwrap_or_default().to_string_lossy().into());
            (label, dir)
        })
        .collect();
    pipearm::sweep::compare(out, title, &labelled)?;
    println!("chart of {} sweeps: {}", labelled.len(), out.display());
    Ok(())
}

fn print_merged(merged: &pipearm::sweep::Merged) -> Result<()> {
    println!(
        "merged {} cases: {}, {}, {}",
        merged.cases,
        merged.csv.display(),
        merged.json.display(),
        merged.chart.display()
    );
    Ok(())
}
