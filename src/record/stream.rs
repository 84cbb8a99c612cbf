//! Where a recording goes, on rerun's public `RecordingStream`: a file written once at the end of
//! a run, or a viewer reached as rerun's own tools reach one (`--connect [URL]`, `--spawn`).

use std::path::Path;

use rerun::blueprint::{
    Blueprint, BlueprintActivation, Horizontal, Spatial3DView, TextLogView, TimeSeriesView, Vertical,
};
use rerun::log::ChunkBatcherConfig;
use rerun::{RecordingStream, RecordingStreamBuilder};

use super::RecordError;

/// Application id of every recording.
const APPLICATION_ID: &str = "pipearm";

/// A viewer to stream a run to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Viewer {
    /// The viewer's gRPC proxy at this URL (rerun's default: [`rerun::DEFAULT_CONNECT_URL`]).
    Connect(String),
    /// A viewer started from the `rerun` executable on the `PATH`, or the one already listening on
    /// rerun's default port.
    Spawn,
}

impl std::fmt::Display for Viewer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Viewer::Connect(url) => write!(f, "viewer at {url}"),
            Viewer::Spawn => write!(f, "spawned viewer"),
        }
    }
}

/// A stream of recording `recording_id` (rerun's random id if `None`, then named `name`).
///
/// The run arrives all at once, its series as whole columns (a chunk each, which the batcher
/// passes straight through), so the batcher only gathers the few static rows until the stream is
/// flushed: it never flushes on its own (no timer, no size threshold), whatever the
/// `RERUN_FLUSH_*` variables say. Enabled whatever `RERUN` says: the recording was asked for.
fn builder(recording_id: Option<&str>, name: &str) -> RecordingStreamBuilder {
    let builder = RecordingStreamBuilder::new(APPLICATION_ID).enabled(true).batcher_config(ChunkBatcherConfig::NEVER);
    match recording_id {
        Some(id) => builder.recording_id(id),
        None => builder.recording_name(name),
    }
}

/// A stream to the file `path` (errors name `target`), its recording's id `recording_id`: the
/// scenario's name, as the file's. rerun's file sink compresses the chunks (LZ4) and writes the
/// footer (which `rerun rrd verify` requires) when the stream closes.
pub(super) fn to_file(path: &Path, recording_id: &str, target: &str) -> Result<RecordingStream, RecordError> {
    builder(Some(recording_id), recording_id)
        .save(path)
        .map_err(|source| RecordError::Stream { target: target.to_string(), source })
}

/// A stream to `viewer`, as a new recording named `name`.
pub(super) fn to_viewer(viewer: &Viewer, name: &str) -> Result<RecordingStream, RecordError> {
    let builder = builder(None, name);
    let stream = match viewer {
        Viewer::Connect(url) => {
            check_listening(url)?;
            builder.connect_grpc_opts(url.clone())
        }
        Viewer::Spawn => builder.spawn(),
    };
    stream.map_err(|source| RecordError::Stream { target: viewer.to_string(), source })
}

/// Fails at once if nothing listens at `url`'s host and port. rerun's sink would retry until its
/// flush gives up (5 s), and would block for good with more messages waiting than its queue holds
/// (100). A URL without an explicit port is left to rerun.
fn check_listening(url: &str) -> Result<(), RecordError> {
    use std::net::{TcpStream, ToSocketAddrs};
    let authority = url.split_once("://").and_then(|(_, rest)| rest.split('/').next());
    let Some(addresses) = authority.filter(|a| a.contains(':')).and_then(|a| a.to_socket_addrs().ok()) else {
        return Ok(());
    };
    let mut refused = None;
    for address in addresses {
        match TcpStream::connect_timeout(&address, CONNECT_TIMEOUT) {
            Ok(_) => return Ok(()),
            Err(e) => refused = Some(e),
        }
    }
    refused.map_or(Ok(()), |source| Err(RecordError::NoViewer { url: url.to_string(), source }))
}

/// How long a viewer's port may take to accept a connection.
const CONNECT_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(1);

/// Ends a stream: its data through the sink, then the blueprint and the command that activates
/// it (last: the viewer activates a blueprint once it is complete), and closes it; a file sink
/// writes its footer as the stream closes, before this returns. A viewer that cannot be reached
/// fails the flush after rerun's connection timeout (5 s).
pub(super) fn finish(stream: RecordingStream, target: &str) -> Result<(), RecordError> {
    let flush = |stream: &RecordingStream| {
        stream.flush_blocking().map_err(|source| RecordError::Flush { target: target.to_string(), source })
    };
    flush(&stream)?;
    blueprint()
        .send(&stream, BlueprintActivation { make_active: true, make_default: true })
        .map_err(|source| RecordError::Stream { target: target.to_string(), source })?;
    flush(&stream)?;
    drop(stream);
    Ok(())
}

/// The view a recording opens with: the 3D scene left; contact force, tip deflection, drive
/// torque and the event log one above the other on the right.
fn blueprint() -> Blueprint {
    let plots = Vertical::new([
        TimeSeriesView::new("contact force (N)").with_origin("plots/contact_force").into(),
        TimeSeriesView::new("tip deflection (m)").with_origin("plots/tip_deflection").into(),
        TimeSeriesView::new("drive torque (N·m)").with_origin("plots/drive_torque").into(),
        TextLogView::new("events").with_origin("events").into(),
    ]);
    Blueprint::new(Horizontal::new([Spatial3DView::new("scene").with_origin("world").into(), plots.into()]))
}
