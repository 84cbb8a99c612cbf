//! The `pipearm` command line: a thin layer over the library.

/// mimalloc instead of glibc's malloc for the binary: it reuses freed pages instead of returning
/// them to the kernel (docs/performance.md: page faults and malloc were a quarter of a run).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};

use pipearm::arm::Fidelity;
use pipearm::record::{BlueprintInAdvance, Ending, Recorded, Viewer, save_recording, stream_recording, write_summary};
use pipearm::regression::{baseline_path, blessed, compare, read_baseline, setting_changes, write_baseline};
use pipearm::run::{RunOptions, RunSummary, run_compiled};
use pipearm::scenario::Scenario;
use pipearm::scene::SceneError;

use cli::overrides::{Overrides, parse_fidelity};
use cli::project::Project;

mod cli;

/// Flexible pipe-handling arms and the impacts on their dampeners.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scenario; write recordings/<name>.rrd and recordings/<name>.summary.json (and
    /// with --csv the series as tables) and print the summary. A run the divergence guard stops
    /// writes recordings/<name>.diverged.rrd, up to the divergence, and no summary.
    #[command(after_help = cli::help::RUN)]
    Run {
        /// Scenario file.
        #[arg(default_value = "scenarios/default.toml")]
        scenario: PathBuf,
        #[command(flatten)]
        overrides: Overrides,
        /// Folder for the recording and the summary.
        #[arg(long, default_value = "recordings")]
        out: PathBuf,
        /// Print the summary only; write nothing (with --csv, only the tables).
        #[arg(long)]
        no_record: bool,
        /// Rate at which steps without contact are recorded, Hz (steps in contact always are).
        #[arg(long, default_value_t = 25.0)]
        record_rate: f64,
        /// Also stream the run to the rerun viewer listening at URL (default: rerun's, the viewer
        /// `rerun` starts); put it after the scenario, or as --connect=URL.
        #[arg(long, value_name = "URL", num_args = 0..=1, default_missing_value = rerun::DEFAULT_CONNECT_URL,
              value_parser = parse_viewer_url, conflicts_with = "spawn")]
        connect: Option<String>,
        /// Also stream the run to a rerun viewer started from `rerun` on the PATH (or to the one
        /// already listening on rerun's default port).
        #[arg(long)]
        spawn: bool,
        /// Also write the series as tables, CSV and Parquet: <out>/<name>.steps.* (every step)
        /// and <out>/<name>.decimated.* (the recorded steps); docs/export.md.
        #[arg(long)]
        csv: bool,
    },
    /// Run scenarios and compare them with their regression baselines.
    #[command(after_help = cli::help::CHECK)]
    Check {
        /// Scenario files (default: every scenarios/*.toml).
        scenarios: Vec<PathBuf>,
        /// Folder of the baselines (default: the project's tests/baselines/, the project of the
        /// first scenario given, else --project's).
        #[arg(long)]
        baselines: Option<PathBuf>,
        /// The project whose scenarios/*.toml are checked when none is given.
        #[arg(long, default_value = ".")]
        project: PathBuf,
        /// Rewrite the baselines from these runs (keeping their tolerances) and print what changed.
        #[arg(long)]
        bless: bool,
        /// Print the comparison as JSON.
        #[arg(long)]
        json: bool,
        /// Run at this model instead of each scenario's (rigid, modal(N) or fe): the baselines'
        /// recorded model then differs, which fails unless --bless.
        #[arg(long, value_parser = parse_fidelity)]
        model: Option<Fidelity>,
    },
    /// Run the seed paper's experiment families (scenarios/seed/), in parallel: a chart, a table
    /// and one recording per variant.
    #[command(after_help = cli::help::SEED)]
    Seed {
        /// Section to run (e.g. 3.1.1-drive); all if omitted.
        section: Option<String>,
        /// The project whose scenarios/seed/ families are run.
        #[arg(long, default_value = ".")]
        project: PathBuf,
        /// Output folder (charts and recordings under <out>/seed/).
        #[arg(long, default_value = "recordings")]
        out: PathBuf,
    },
    /// Speed against accuracy: run a grid of models, steps, integrators, contact methods and
    /// clamp modes against a converged reference; write a CSV, a chart (SVG, PNG), the stability
    /// map and a Markdown report per scenario under <out>/<name>/.
    #[command(after_help = cli::help::BENCH)]
    Bench {
        /// Scenario files (default: the project's scenarios/default.toml).
        scenarios: Vec<PathBuf>,
        /// The project whose default scenario is benched when none is given.
        #[arg(long, default_value = ".")]
        project: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "recordings/bench")]
        out: PathBuf,
        /// Timed repeats per point (the median is kept).
        #[arg(long, default_value_t = 3)]
        repeats: usize,
        /// A smaller grid for a quick look.
        #[arg(long)]
        quick: bool,
    },
    /// Run a scenario over the Cartesian product of varied keys, in parallel (or one shard of
    /// it): per-case results, a table and a chart of peak contact force against string weight
    /// (docs/sweeps.md). `pipearm sweep merge DIR` joins the shards.
    Sweep(cli::sweep::SweepArgs),
    /// Run a scenario over spread keys (pad gap, stiffness, damping, lift time, ...) drawn from
    /// their distributions, per string size: the percentiles of the peak force and residual
    /// amplitude, a chart with the p5-p95 band, and the sensitivity ranking (docs/envelope.md).
    /// `pipearm envelope merge DIR` joins the shards.
    Envelope(cli::envelope::EnvelopeArgs),
    /// Find the values of scenario keys (lift time, acceleration, ...) that minimise an
    /// objective while every limit holds, nominally or at the envelope's p95; or, with --table,
    /// the largest start/stop acceleration per drive profile (docs/envelope.md).
    Design(cli::design::DesignArgs),
    /// Run a scenario and set it against measured signals (docs/measurements.md): print a table
    /// per signal and write <out>/<name>.compare.json.
    #[command(after_help = cli::help::COMPARE)]
    Compare {
        /// Scenario file.
        scenario: PathBuf,
        /// Measured CSV: `t[s]` then columns named after the run's signals, units in brackets.
        #[arg(long)]
        measured: PathBuf,
        /// Shift the measured file in time to the cross-correlation's peak (reported).
        #[arg(long)]
        shift: bool,
        /// Override the model: rigid, modal(N) or fe.
        #[arg(long, value_parser = parse_fidelity)]
        model: Option<Fidelity>,
        /// Folder for the report.
        #[arg(long, default_value = "recordings")]
        out: PathBuf,
    },
    /// Fit scenario parameters to measured signals (least squares); print them with 95 %
    /// intervals; write <out>/<name>.fit.json and <out>/<name>.fitted.toml.
    #[command(after_help = cli::help::FIT)]
    Fit {
        /// Scenario file.
        scenario: PathBuf,
        /// Measured CSV: `t[s]` then columns named after the run's signals, units in brackets.
        #[arg(long)]
        measured: PathBuf,
        /// Scenario keys to fit, comma separated (docs/measurements.md lists them).
        #[arg(long, value_delimiter = ',', required = true)]
        params: Vec<String>,
        /// Override the model: rigid, modal(N) or fe.
        #[arg(long, value_parser = parse_fidelity)]
        model: Option<Fidelity>,
        /// Override the time step, s (keep it under a twentieth of the shortest impact).
        #[arg(long)]
        step: Option<f64>,
        /// Shift the measured file in time to the run first (its clock's offset, reported).
        #[arg(long)]
        shift: bool,
        /// Folder for the report and the fitted scenario.
        #[arg(long, default_value = "recordings")]
        out: PathBuf,
    },
    /// Write a starter project into DIR (a scenario and the robot it names, an empty baselines
    /// folder): `cd DIR && pipearm run` then runs.
    #[command(after_help = cli::help::INIT)]
    Init {
        /// The folder (created if need be; refused if it already holds scenarios/ or robots/).
        dir: PathBuf,
    },
    /// List the pipe catalogue: size, weight, diameters, kg/m, connection, joint mass per range.
    Pipes(cli::pipes::PipesArgs),
    /// Print the diameters the jaws close on and the heaviest payload per lift angle and drive.
    Capacity(cli::capacity::CapacityArgs),
    /// Draw the machine as pipearm reads it, dimensioned: the arm and its sections, the hands,
    /// the string, the pads, structures and cylinder pins, the lift angle; write
    /// recordings/<name>.machine.svg and .png.
    Draw(cli::draw::DrawArgs),
    /// Print the arm's clamped natural frequencies, λL, modal masses and static w/l.
    #[command(after_help = cli::help::MODES)]
    Modes {
        /// Scenario file whose arm (robot + payload) to analyse.
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

/// `pipearm run | head` ends as any Unix tool would when the reader goes away: by SIGPIPE,
/// silently. Rust ignores SIGPIPE, so `println!` would panic on the closed pipe instead (with a
/// backtrace under `RUST_BACKTRACE`). Files are written before their line is printed, under a
/// temporary name, so a run ended here leaves no partial file.
fn exit_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: restores the default action of one signal before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// A viewer's URL as rerun writes them (`rerun+http://HOST:PORT/proxy`); rerun checks the rest.
fn parse_viewer_url(s: &str) -> Result<String, String> {
    if s.contains("://") {
        Ok(s.to_string())
    } else {
        Err(format!(
            "`{s}`: expected a URL such as {} (the scenario goes before --connect)",
            rerun::DEFAULT_CONNECT_URL
        ))
    }
}

fn main() -> Result<()> {
    exit_quietly_on_closed_pipe();
    match Cli::parse().command {
        Command::Run { scenario, overrides, out, no_record, record_rate, connect, spawn, csv } => {
            let viewer = match (connect, spawn) {
                (Some(url), _) => Some(Viewer::Connect(url)),
                (None, true) => Some(Viewer::Spawn),
                (None, false) => None,
            };
            let options = RunOptions {
                fidelity: overrides.model,
                record_rate_hz: record_rate,
                capture_frames: !no_record || viewer.is_some(),
                ..RunOptions::default()
            };
            let outputs =
                Outputs { files: (!no_record).then_some(out.as_path()), tables: csv.then_some(out.as_path()), viewer };
            run_command(&scenario, &overrides, options, outputs)
        }
        Command::Modes { scenario, count, spin, no_stiffening } => {
            cli::modes::modes(&scenario, count, spin, !no_stiffening)
        }
        Command::Pipes(args) => cli::pipes::pipes(&args.filters),
        Command::Capacity(args) => cli::capacity::capacity(&args.scenario, args.step_deg),
        Command::Check { scenarios, baselines, project, bless, json, model } => {
            check(scenarios, baselines, &Project::at(&project), (bless, json), model)
        }
        Command::Seed { section, project, out } => cli::seed::seed(section.as_deref(), &Project::at(&project), &out),
        Command::Bench { mut scenarios, project, out, repeats, quick } => {
            if scenarios.is_empty() {
                scenarios.push(Project::at(&project).default_scenario());
            }
            bench(&scenarios, &out, repeats, quick)
        }
        Command::Init { dir } => cli::project::init(&dir),
        Command::Sweep(args) => cli::sweep::sweep(args),
        Command::Envelope(args) => cli::envelope::envelope(args),
        Command::Design(args) => cli::design::design_command(args),
        Command::Draw(args) => cli::draw::draw(args),
        Command::Fit { scenario, measured, params, model, step, shift, out } => {
            let settings = pipearm::fit::RunSettings { fidelity: model, step_s: step };
            cli::measured::fit_command(&scenario, &measured, &params, (settings, shift), &out)
        }
        Command::Compare { scenario, measured, shift, model, out } => cli::measured::compare_command(
            &scenario,
            &measured,
            pipearm::compare::CompareOptions { fidelity: model, shift },
            &out,
        ),
    }
}

/// Where `pipearm run` puts a run besides its printed summary.
struct Outputs<'a> {
    /// The folder for `<name>.rrd` and `<name>.summary.json` (none with --no-record).
    files: Option<&'a Path>,
    /// The folder for the series as tables (with --csv).
    tables: Option<&'a Path>,
    /// A viewer to stream the run to.
    viewer: Option<Viewer>,
}

fn run_command(path: &Path, overrides: &Overrides, options: RunOptions, outputs: Outputs) -> Result<()> {
    if !(options.record_rate_hz.is_finite() && options.record_rate_hz > 0.0) {
        bail!("--record-rate = {}: allowed a rate > 0 Hz", options.record_rate_hz);
    }
    if let Some(out) = outputs.files.or(outputs.tables) {
        pipearm::export::check_folder(out).context("--out")?;
    }
    let started = std::time::Instant::now();
    let scenario = overrides.load(path)?;
    let running = || format!("{}: running", path.display());
    let compiled = scenario.compile(options.fidelity)?;
    let model: &pipearm::model::Model = &compiled.model;
    // The recording's blueprint is encoded on a second thread while the run steps.
    let blueprint = outputs.files.map(|_| BlueprintInAdvance::start(&compiled, &options));
    let (result, series) = run_compiled(&compiled, &options);
    let name = &model.name;
    let summary = match result {
        Ok(summary) => summary,
        Err(error @ SceneError::Diverged { t_s, .. }) if options.capture_frames => {
            let message = error.to_string();
            let ending = Ending::Diverged { scenario: name, t_s, message: &message };
            let run = Recorded { series: &series, ending, overlay: &[] };
            record_divergence(&outputs, name, &run, blueprint);
            return Err(anyhow::Error::new(error).context(running()));
        }
        Err(error) => return Err(error).with_context(running),
    };
    cli::summary::print_summary(path, &summary);
    let run = Recorded { series: &series, ending: Ending::Finished(&summary), overlay: &[] };
    if let Some(out) = outputs.files {
        let started = std::time::Instant::now();
        let rrd = out.join(format!("{name}.rrd"));
        let json = out.join(format!("{name}.summary.json"));
        save_recording(&rrd, &run, blueprint)?;
        write_summary(&json, &summary)?;
        let bytes = std::fs::metadata(&rrd).map(|m| m.len()).unwrap_or(0);
        println!(
            "wrote               {} ({:.2} MB, {:.3} s) and {}",
            rrd.display(),
            bytes as f64 / 1e6,
            started.elapsed().as_secs_f64(),
            json.display()
        );
        // This run finished: a recording of an earlier one that diverged no longer describes it.
        let stale = diverged_path(out, name);
        std::fs::remove_file(&stale)
            .or_else(|e| if e.kind() == std::io::ErrorKind::NotFound { Ok(()) } else { Err(e) })
            .with_context(|| format!("removing {}", stale.display()))?;
    }
    if let Some(out) = outputs.tables {
        write_tables(out, &model.name, (&series, &summary), model)?;
    }
    // In-process: scenario read, model built, stepped, recorded (the sign-off's recovery and the
    // recording's blueprint on a second thread where one is spare).
    let total_s = started.elapsed().as_secs_f64();
    println!(
        "total               {total_s:.3} s from reading the scenario to the last file written ({:.0}x real time)",
        summary.simulated_s / total_s
    );
    if let Some(viewer) = &outputs.viewer {
        stream_recording(viewer, &run)?;
        println!("streamed            to the {viewer}");
    }
    Ok(())
}

/// Where a run the divergence guard stopped is recorded: beside `<name>.rrd`.
fn diverged_path(out: &Path, name: &str) -> PathBuf {
    out.join(format!("{name}.diverged.rrd"))
}

/// Records a diverged run for inspection: its file and its stream. The divergence is the
/// command's error; failing to record it is reported beside it.
fn record_divergence(outputs: &Outputs, name: &str, run: &Recorded, blueprint: Option<BlueprintInAdvance>) {
    if let Some(out) = outputs.files {
        let rrd = diverged_path(out, name);
        match save_recording(&rrd, run, blueprint) {
            Ok(()) => println!("wrote               {} (the run up to its divergence)", rrd.display()),
            Err(e) => eprintln!("{e}"),
        }
    }
    if let Some(viewer) = &outputs.viewer {
        match stream_recording(viewer, run) {
            Ok(()) => println!("streamed            to the {viewer} (the run up to its divergence)"),
            Err(e) => eprintln!("{e}"),
        }
    }
}

/// `run --csv`: the run's series as CSV and Parquet tables in `out`.
fn write_tables(
    out: &Path,
    name: &str,
    (series, summary): (&pipearm::run::Series, &RunSummary),
    model: &pipearm::model::Model,
) -> Result<()> {
    let started = std::time::Instant::now();
    let written = pipearm::export::write_tables(out, name, series)?;
    let [steps, decimated] = written.rows;
    let [csv, parquet] = written.bytes.map(|b| b as f64 / 1e6);
    println!(
        "wrote tables        {} ({steps} rows) and {} ({decimated} rows): CSV {csv:.2} MB, Parquet {parquet:.2} MB, {:.3} s",
        out.join(format!("{name}.steps.{{csv,parquet}}")).display(),
        out.join(format!("{name}.decimated.{{csv,parquet}}")).display(),
        started.elapsed().as_secs_f64()
    );
    if let Some(signed) = &summary.sign_off {
        let svg = out.join(format!("{name}.stress.svg"));
        let caption = format!("{name}: stress envelope along the arm");
        pipearm::stress::chart::envelope(
            &svg,
            &caption,
            &series.stress,
            &model.robot.arm.segments,
            signed.stress.stress_factor,
        )
        .map_err(|e| anyhow::anyhow!("{}: {e}", svg.display()))?;
        println!("wrote chart         {}", svg.display());
    }
    Ok(())
}

/// Runs each scenario and compares it with its baseline; fails if any quantity is off.
fn check(
    mut scenarios: Vec<PathBuf>,
    baselines: Option<PathBuf>,
    project: &Project,
    (bless, json): (bool, bool),
    model: Option<Fidelity>,
) -> Result<()> {
    let baselines = baselines.unwrap_or_else(|| match scenarios.first() {
        Some(first) => Project::of_scenario(first).baselines(),
        None => project.baselines(),
    });
    let baselines = baselines.as_path();
    if scenarios.is_empty() {
        let folder = project.scenarios();
        scenarios =
            pipearm::scenario::scenario_files(&folder).with_context(|| format!("reading {}", folder.display()))?;
    }
    let mut failed = 0;
    let mut report = Vec::new();
    for path in &scenarios {
        let scenario = Overrides { model, ..Overrides::default() }.load(path)?;
        let name = scenario.model.name.clone();
        let compiled = scenario.compile(model)?;
        let options = RunOptions { fidelity: model, ..RunOptions::default() };
        let summary = run_compiled(&compiled, &options).0.with_context(|| format!("{}: running", path.display()))?;
        let file = baseline_path(baselines, &name);
        if bless {
            let previous = read_baseline(&file, &name, path).ok();
            let new = blessed(&summary, previous.as_ref());
            if let Some(previous) = &previous {
                for c in setting_changes(previous, &summary) {
                    println!("{name}: {} {} -> {}", c.setting, c.baseline, c.now);
                }
                for row in compare(previous, &summary).iter().filter(|r| r.now != r.baseline) {
                    println!("{name}: {} {} -> {}", row.name, row.baseline, row.now);
                }
            }
            write_baseline(&file, &new)?;
            println!("blessed {}", file.display());
            continue;
        }
        let baseline = read_baseline(&file, &name, path)?;
        let rows = compare(&baseline, &summary);
        let changed = setting_changes(&baseline, &summary);
        failed += rows.iter().filter(|r| !r.pass).count() + changed.len();
        if !json {
            for c in &changed {
                println!("{name}: SETTING CHANGED {}: blessed under {}, run under {}", c.setting, c.baseline, c.now);
            }
            print_rows(&name, &rows);
        }
        report
            .push(serde_json::json!({ "scenario": name, "baseline": file, "settings_changed": changed, "rows": rows }));
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    }
    if failed > 0 {
        bail!(
            "{failed} quantities outside their tolerance or settings changed (docs/regression.md); `pipearm check --bless` accepts a change on purpose"
        );
    }
    Ok(())
}

fn bench(scenarios: &[PathBuf], out: &Path, repeats: usize, quick: bool) -> Result<()> {
    use pipearm::bench;
    let options = bench::BenchOptions { repeats, quick, mesh_check: !quick };
    let loaded: Vec<Scenario> = scenarios.iter().map(|p| Scenario::load(p)).collect::<Result<_, _>>()?;
    // Compiled (checked, and a shaper tuned to the nominal arm) once: every variant the bench
    // runs takes the same shaped move.
    let compiled: Vec<_> = loaded.iter().map(|s| s.compile(None)).collect::<Result<_, _>>()?;
    let command = std::iter::once("pipearm".to_string()).chain(std::env::args().skip(1)).collect::<Vec<_>>().join(" ");
    for (path, compiled) in scenarios.iter().zip(&compiled) {
        let bar = indicatif::ProgressBar::new(1).with_style(
            indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {elapsed} {wide_msg}")
                .expect("a valid template")
                .progress_chars("=> "),
        );
        let model: &pipearm::model::Model = &compiled.model;
        bar.set_prefix(model.name.clone());
        let mut progress = |label: &str, done: usize, total: usize| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            bar.set_message(label.to_string());
        };
        let result =
            bench::bench(model, &options, &mut progress).with_context(|| format!("{}: bench", path.display()))?;
        bar.finish_and_clear();
        let dir = out.join(&model.name);
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        std::fs::write(dir.join("points.csv"), bench::points_csv(&result))?;
        std::fs::write(dir.join("stability.csv"), bench::stability_csv(&result.stability))?;
        let report = bench::report_markdown(&result, &command);
        std::fs::write(dir.join("report.md"), &report)?;
        bench::chart_svg(&dir.join("chart.svg"), &result).map_err(anyhow::Error::msg)?;
        bench::chart_png(&dir.join("chart.png"), &result).map_err(anyhow::Error::msg)?;
        println!(
            "{report}
wrote {}/{{points.csv, stability.csv, report.md, chart.svg, chart.png}}",
            dir.display()
        );
    }
    Ok(())
}

fn print_rows(scenario: &str, rows: &[pipearm::regression::Row]) {
    println!("{scenario}");
    println!("  {:<38} {:>14} {:>14} {:>9} {:>16}", "quantity", "baseline", "now", "change", "tolerance");
    for r in rows {
        println!(
            "  {:<38} {:>14.6} {:>14.6} {:>8.3}% {:>7.2}% ±{:<7} {}",
            r.name,
            r.baseline,
            r.now,
            100.0 * r.change,
            100.0 * r.tolerance.0,
            r.tolerance.1,
            if r.pass { "pass" } else { "FAIL" }
        );
    }
}
