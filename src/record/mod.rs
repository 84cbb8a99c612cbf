//! Recordings for the rerun viewer (`.rrd`), on a `sim_time` timeline, with a blueprint that
//! opens the 3D scene beside the time series.
//!
//! Layout of a recording:
//!
//! | entity | what |
//! |---|---|
//! | `world/machine` | 3D: the machine's pieces — hub, arm elements, hands, jaws, a tilting head's — a box each, coloured by kind (m, Y up) |
//! | `world/string`, `world/pads`, `world/ground` | the held string's centreline, the pads, the rig floor |
//! | `world/centreline` | the deformed centreline, its deflection magnified (the factor in `events`); with the sign-off, shaded per piece by utilisation (by \|σ\| against the run's peak without a yield strength) |
//! | `world/stress_legend` | the shading's colour bar, labelled, beyond the arm's reach |
//! | `world/stress_peak` | a marker at the worst station (the largest utilisation's, else the largest \|σ\|'s), labelled |
//! | `world/contact_force` | every contact point with its force arrow (newtons per metre in `events`) |
//! | `world/structures/<name>` | a rig structure |
//! | `plots/contact_force/<side>-<obstacle>` | contact force per pair (`arm-<pad>`, `string-<structure>`), N |
//! | `plots/tip_deflection/{axial,transverse}` | tip displacement in the hub frame, m |
//! | `plots/tip_velocity/{axial,transverse}` | tip velocity in the hub frame, m/s |
//! | `plots/hub/{angle_deg,rate_deg_s,accel_deg_s2}` | hub motion |
//! | `plots/drive_torque` | N·m |
//! | `plots/modal` | elastic coordinates (modal models), one instance each, named `q<i>` from 1 |
//! | `plots/energy` | kinetic, strain and gravity energy, J: three instances, named so |
//! | `plots/string_slip` | friction clamp slip, m |
//! | `plots/head/angle_deg` | a tilting head's angle on its hinge, deg |
//! | `plots/head/drive_torque` | a driven head's drive torque on the head, N·m |
//! | `plots/sensors/<sensor>/<channel>` | each sensor's channels, SI (`crate::sensor`) |
//! | `plots/stress/worst_station` | σ at the worst station and fibre, Pa |
//! | `plots/stress/yield/{tension,compression}` | ± yield / stress_factor there, Pa (where a yield strength is given and the peak reaches half of it; else the trace's name gives it) |
//! | `plots/pins` | pin and grip force magnitudes, N: a trace each, `pivot`, `cylinder` (several: `cylinder_<k>`), each hand by name |
//! | `events` | impacts (start, peak, end), warnings, the model, the display scales: each at its time; a diverged run's guard message last |
//! | `summary` | the run summary (JSON; not for a diverged run) |
//!
//! The `plots/…` entities are the run's channels as their producers declare them
//! ([`crate::channel`]): this module reads the declarations and spells no channel itself, except
//! the sign-off's ([`stress`]).
//!
//! Steps are kept at the record rate in free motion and every step in contact, and each impact's
//! interpolated peak is inserted at its time in its pad's force series, so no peak is lost and the
//! plot peaks at the summary's figure ([`crate::run::RunOptions`]).
//!
//! A recording is a file, written by the small encoder of `rrd` to a temporary name and renamed
//! when complete, so a failed write leaves no half recording; or a stream to a viewer
//! ([`Viewer`]) through rerun's public `RecordingStream`. Both carry the same chunks and layout. A run the divergence guard stopped is recorded up to its last good step,
//! with the guard's message as the last event and no `summary` ([`Ending::Diverged`]).

use std::path::Path;

mod blueprint;
mod content;
mod layout;
mod rrd;
mod stream;
mod stress;
mod writer;

pub use crate::arm::{ENERGY_ENTITY, MODAL_ENTITY, TIP_DEFLECTION_ENTITY};
pub use crate::scene::{force_entity, pair_name};
pub use content::{arrow_scale_n_per_m, magnification};
pub use layout::{ActuatorViews, RunViews};
pub use stream::Viewer;
pub use stress::{LEGEND_ENTITY, PEAK_ENTITY, PINS_ENTITY, WORST_STATION_ENTITY, YIELD_DRAWN_FROM, YIELD_ENTITY};

use crate::run::{RunSummary, Series};

/// Errors writing a recording.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// Opening a stream to a file or a viewer, or logging into it.
    #[error("recording to {target}: {source}")]
    Stream { target: String, source: rerun::RecordingStreamError },
    /// Getting the data through to the file or the viewer.
    #[error("recording to {target}: {source}")]
    Flush { target: String, source: rerun::sink::SinkFlushError },
    /// Writing the file (rerun's encoder, as text: its error types are many).
    #[error("recording {path}: {message}")]
    Rrd { path: String, message: String },
    /// Nothing listens at a viewer's address.
    #[error("no rerun viewer at {url} ({source}); start one with `rerun`")]
    NoViewer { url: String, source: std::io::Error },
    /// Filesystem.
    #[error("recording {path}: {source}")]
    Io { path: String, source: std::io::Error },
    /// The summary as JSON.
    #[error("summary {path}: {source}")]
    Json { path: String, source: serde_json::Error },
}

/// Entity path of the magnified centreline.
pub const CENTRELINE_ENTITY: &str = "world/centreline";

/// Entity path of the machine's pieces (hub, the arm's segments, hands, jaws, a tilting head's),
/// a box each, coloured by kind.
pub const PIECES_ENTITY: &str = "world/machine";

/// Entity path of the contact points and their force arrows.
pub const CONTACT_FORCE_ENTITY: &str = "world/contact_force";

/// How a recorded run ended.
#[derive(Debug, Clone, Copy)]
pub enum Ending<'a> {
    /// It ran to its end: its impacts' interpolated peaks go into the force series, its findings
    /// into the events, its JSON into `summary`.
    Finished(&'a RunSummary),
    /// The divergence guard stopped `scenario` at `t_s` (s) with `message`, the last event.
    Diverged { scenario: &'a str, t_s: f64, message: &'a str },
}

impl Ending<'_> {
    /// The scenario's name.
    pub fn scenario(&self) -> &str {
        match self {
            Ending::Finished(summary) => &summary.scenario,
            Ending::Diverged { scenario, .. } => scenario,
        }
    }
}

/// A run as a recording shows it.
#[derive(Debug, Clone, Copy)]
pub struct Recorded<'a> {
    /// Its series (with the 3D frames and layout if captured), with its channels.
    pub series: &'a Series,
    /// How it ended.
    pub ending: Ending<'a>,
    /// Chunks drawn over the run's own (a measured file's series, `pipearm compare`); empty for a
    /// plain run.
    pub overlay: &'a [rerun::log::Chunk],
}

/// Writes a finished run to `path` (.rrd).
pub fn write_recording(path: &Path, summary: &RunSummary, series: &Series) -> Result<(), RecordError> {
    save_recording(path, &Recorded { series, ending: Ending::Finished(summary), overlay: &[] }, None)
}

/// A recording file's start, its blueprint, encoded on a thread of its own while the run steps:
/// the layout depends on what the run records, which its compiled model declares, not on its
/// results ([`RunViews::before_run`]).
pub struct BlueprintInAdvance {
    views: RunViews,
    /// The encoding thread; none where no core is spare (it is encoded at the save then).
    encoding: Option<std::thread::JoinHandle<RrdResult<rrd::Start>>>,
}

impl BlueprintInAdvance {
    /// Starts encoding the blueprint of a run of `compiled` with `options`.
    pub fn start(compiled: &crate::run::CompiledModel, options: &crate::run::RunOptions) -> Self {
        let views = RunViews::before_run(compiled, options);
        let name = compiled.model.name.clone();
        let thread = std::thread::Builder::new().name("pipearm-blueprint".into());
        let encoding = crate::cores::spare().then(|| thread.spawn(move || start_of(&name, views)).ok()).flatten();
        BlueprintInAdvance { views, encoding }
    }

    /// The start of `run`'s file: the one encoded in advance if its views are `run`'s and its
    /// thread finished it, else encoded here.
    fn take_for(self, run: &Recorded) -> RrdResult<rrd::Start> {
        let views = RunViews::of(run.series);
        let encoded = self.encoding.filter(|_| views == self.views).and_then(|thread| thread.join().ok());
        encoded.unwrap_or_else(|| start_of(run.ending.scenario(), views))
    }
}

/// The start of a recording of scenario `name`: its blueprint, the layout of `views`.
fn start_of(name: &str, views: RunViews) -> RrdResult<rrd::Start> {
    rrd::Start::with(APPLICATION_ID, &blueprint::BlueprintMessages::new(APPLICATION_ID, name, views)?)
}

/// An error from rerun's chunk builder or encoder, as text (their error types are many).
type RrdResult<T> = Result<T, String>;

fn text(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// Application id of every recording, a file's and a stream's.
const APPLICATION_ID: &str = "pipearm";

/// Writes `run` to `path` (.rrd), under a temporary name renamed when complete, with `blueprint`
/// where it was started ahead of the run (else the blueprint is encoded here).
pub fn save_recording(path: &Path, run: &Recorded, blueprint: Option<BlueprintInAdvance>) -> Result<(), RecordError> {
    let shown = path.display().to_string();
    let io = |source| RecordError::Io { path: shown.clone(), source };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    let tmp = path.with_extension("rrd.tmp");
    let file = std::fs::File::create(&tmp).map_err(io)?;
    let written = write_rrd(file, run, blueprint);
    if let Err(message) = written {
        std::fs::remove_file(&tmp).ok();
        return Err(RecordError::Rrd { path: shown, message });
    }
    replace(&tmp, path).map_err(io)
}

/// A recording's id: its scenario and a digest of its results, so that two runs of one scenario
/// with different results open as two recordings (not merged), and a re-run with the same
/// results as the same one.
fn recording_id(run: &Recorded) -> String {
    let series = run.series;
    let values = series.pad_force_n.iter().flatten().chain(series.tip_deflection_m.iter().flatten());
    let digest = values.fold(0xcbf2_9ce4_8422_2325_u64, |h, v| (h ^ v.to_bits()).wrapping_mul(0x0100_0000_01b3));
    format!("{}-{digest:016x}", run.ending.scenario())
}

/// `run` into `file` after its start, `blueprint`'s where it was encoded ahead of the run: each
/// chunk encoded as it is made (and its memory reused for the next), then the footer.
fn write_rrd(file: std::fs::File, run: &Recorded, blueprint: Option<BlueprintInAdvance>) -> Result<(), String> {
    let start = match blueprint {
        Some(blueprint) => blueprint.take_for(run)?,
        None => start_of(run.ending.scenario(), RunViews::of(run.series))?,
    };
    let mut out = rrd::RrdFile::create(start, file, &recording_id(run))?;
    let mut encoded = Ok(());
    content::chunks(run, &mut |chunk| {
        if encoded.is_ok() {
            encoded = out.send_chunk(&chunk);
        }
    })
    .map_err(|e| e.to_string())?;
    encoded?;
    out.finish()
}

/// Streams `run` to `viewer`, as a new recording named as its file is (its scenario, model and
/// largest peak force).
pub fn stream_recording(viewer: &Viewer, run: &Recorded) -> Result<(), RecordError> {
    let target = viewer.to_string();
    let mut chunks = Vec::new();
    content::chunks(run, &mut |chunk| chunks.push(chunk))
        .map_err(|source| RecordError::Stream { target: target.clone(), source })?;
    let out = stream::to_viewer(viewer)?;
    out.send_chunks(chunks);
    stream::finish(out, &target, run.ending.scenario(), RunViews::of(run.series))
}

/// Moves the complete file `tmp` to `path`. The old file is removed first: renamed over, ext4
/// (`auto_da_alloc`) starts writing the new file's blocks out inside the rename (3 % of a run's
/// samples in `perf record`), to keep the old file readable until the last instant, which
/// nothing here needs. A crash between the two leaves no file, never a partial one.
fn replace(tmp: &Path, path: &Path) -> std::io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    std::fs::rename(tmp, path)
}

/// Writes the summary as JSON to `path`, atomically.
pub fn write_summary(path: &Path, summary: &RunSummary) -> Result<(), RecordError> {
    let shown = path.display().to_string();
    let io = |source| RecordError::Io { path: shown.clone(), source };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    let tmp = path.with_extension("json.tmp");
    let text =
        serde_json::to_string_pretty(summary).map_err(|source| RecordError::Json { path: shown.clone(), source })?;
    std::fs::write(&tmp, text).map_err(io)?;
    replace(&tmp, path).map_err(io)
}
