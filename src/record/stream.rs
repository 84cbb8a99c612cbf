//! A run streamed to a viewer on rerun's public `RecordingStream`, the viewer reached as rerun's
//! own tools reach one (`--connect [URL]`, `--spawn`).

use rerun::blueprint::{
    Blueprint, BlueprintActivation, ContainerLike, Horizontal, Spatial3DView, TextLogView, TimeSeriesView, Vertical,
};
use rerun::log::ChunkBatcherConfig;
use rerun::{RecordingStream, RecordingStreamBuilder};

use super::layout::{BlueprintLayout, RunViews, run_layout};
use super::{APPLICATION_ID, RecordError};

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

/// A stream to `viewer`, as a new recording named `name`.
///
/// The run arrives all at once as whole chunks, which the batcher passes straight through, so it
/// never flushes on its own (no timer, no size threshold) whatever the `RERUN_FLUSH_*` variables
/// say; [`finish`] flushes. Enabled whatever `RERUN` says: the stream was asked for.
pub(super) fn to_viewer(viewer: &Viewer, name: &str) -> Result<RecordingStream, RecordError> {
    let builder = RecordingStreamBuilder::new(APPLICATION_ID)
        .enabled(true)
        .batcher_config(ChunkBatcherConfig::NEVER)
        .recording_name(name);
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
/// it (last, as in a file), and closes it. A viewer that stops answering fails the flush after
/// rerun's connection timeout (5 s).
pub(super) fn finish(stream: RecordingStream, target: &str, views: RunViews) -> Result<(), RecordError> {
    let flush = |stream: &RecordingStream| {
        stream.flush_blocking().map_err(|source| RecordError::Flush { target: target.to_string(), source })
    };
    flush(&stream)?;
    blueprint(views)
        .send(&stream, BlueprintActivation { make_active: true, make_default: true })
        .map_err(|source| RecordError::Stream { target: target.to_string(), source })?;
    flush(&stream)?;
    drop(stream);
    Ok(())
}

/// The run's layout as rerun's blueprint.
fn blueprint(views: RunViews) -> Blueprint {
    match to_rerun(run_layout(views)) {
        ContainerLike::View(view) => Blueprint::new(view),
        root => Blueprint::new(root),
    }
}

fn to_rerun(part: BlueprintLayout) -> ContainerLike {
    match part {
        // rerun's SDK sets no camera on a 3D view: the viewer frames the scene itself.
        BlueprintLayout::View { class: "3D", name, origin, .. } => Spatial3DView::new(name).with_origin(origin).into(),
        BlueprintLayout::View { class: "TextLog", name, origin, .. } => {
            TextLogView::new(name).with_origin(origin).into()
        }
        BlueprintLayout::View { name, origin, .. } => TimeSeriesView::new(name).with_origin(origin).into(),
        BlueprintLayout::Horizontal(children) => Horizontal::new(children.into_iter().map(to_rerun)).into(),
        BlueprintLayout::Vertical(children) => Vertical::new(children.into_iter().map(to_rerun)).into(),
    }
}
