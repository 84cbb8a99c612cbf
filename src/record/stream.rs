//! A run streamed to a viewer on rerun's public `RecordingStream`, the viewer reached as rerun's
//! own tools reach one (`--connect [URL]`, `--spawn`).

use rerun::log::ChunkBatcherConfig;
use rerun::{RecordingStream, RecordingStreamBuilder};

use super::blueprint::BlueprintMessages;
use super::layout::RunViews;
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

/// A stream to `viewer`, as a new recording. Its name is the run's chunk of recording
/// properties, as in a file ([`super::content`]): the stream sends none of its own, which, made
/// after the run's chunks, would name the recording anew.
///
/// The run arrives all at once as whole chunks, which the batcher passes straight through, so it
/// never flushes on its own (no timer, no size threshold) whatever the `RERUN_FLUSH_*` variables
/// say; [`finish`] flushes. Enabled whatever `RERUN` says: the stream was asked for.
pub(super) fn to_viewer(viewer: &Viewer) -> Result<RecordingStream, RecordError> {
    let builder = RecordingStreamBuilder::new(APPLICATION_ID)
        .enabled(true)
        .batcher_config(ChunkBatcherConfig::NEVER)
        .send_properties(false);
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

/// Ends a stream: its data through the sink, then the blueprint of a run of `scenario` with
/// `views` and the command that activates it ([`super::blueprint`], as a file has them), and
/// closes it. A viewer that stops answering fails the flush after rerun's connection timeout
/// (5 s).
pub(super) fn finish(
    stream: RecordingStream,
    target: &str,
    scenario: &str,
    views: RunViews,
) -> Result<(), RecordError> {
    let flush = |stream: &RecordingStream| {
        stream.flush_blocking().map_err(|source| RecordError::Flush { target: target.to_string(), source })
    };
    flush(&stream)?;
    let blueprint = BlueprintMessages::new(APPLICATION_ID, scenario, views)
        .map_err(|message| RecordError::Rrd { path: target.to_string(), message })?;
    stream.send_blueprint(blueprint.messages, blueprint.activation);
    flush(&stream)?;
    drop(stream);
    Ok(())
}
