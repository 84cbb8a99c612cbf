//! An `.rrd` file written with no `RecordingStream`, by rerun's internal encoder
//! (`re_log_encoding`, through `rerun::external`; the blueprint's messages come from
//! [`super::blueprint`]), because rerun's public path to a file costs a third of the default run
//! (docs/recording.md, "How it is written").
//!
//! A `RecordingStream` is made for live logging: a batcher, a forwarding and a file-writer thread
//! per stream, LZ4 on every chunk, a second stream for the blueprint. The file here holds what
//! that stream would write, in the same messages and in the order `with_blueprint` sends them:
//! the blueprint's store ([`Start`]: [`super::blueprint`]'s messages and the command that
//! activates it), then the recording's ([`RrdFile`]: its store info, one Arrow message per
//! chunk), then rerun's footer, which indexes both stores' chunks and which `rerun rrd verify`
//! and rerun's readers that seek find at the file's end. The start is encoded in memory before
//! the file is open (on another thread while the run steps, where the caller wishes); the encoder
//! counts its bytes, so the footer's offsets are the file's.
//!
//! Unlike rerun's streams, nothing here depends on the clock or on randomness: the chunks carry
//! no `log_time`, so a run writes the same entities, times and values every time.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::sync::{Arc, Mutex, PoisonError};

use rerun::external::re_log_encoding::{Encoder, EncodingOptions};
use rerun::external::re_log_types::StoreId;
use rerun::log::{Chunk, LogMsg};

use super::blueprint::{BlueprintMessages, store_info};
use super::{RrdResult, text};

/// The file a recording goes to, once it is open.
type FileSlot = Arc<Mutex<Option<BufWriter<File>>>>;

/// Where the encoder writes: memory until the file is open, then the file (the memory first).
struct Sink {
    memory: Vec<u8>,
    file: FileSlot,
}

impl Sink {
    /// Runs `write` on the file once it is open, the memory written to it first; else `None`.
    fn on_file<T>(
        &mut self,
        write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<T>,
    ) -> Option<std::io::Result<T>> {
        let mut file = self.file.lock().unwrap_or_else(PoisonError::into_inner);
        let file = file.as_mut()?;
        let memory = std::mem::take(&mut self.memory);
        Some(file.write_all(&memory).and_then(|()| write(file)))
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.on_file(|file| file.write(buf)).unwrap_or_else(|| {
            self.memory.extend_from_slice(buf);
            Ok(buf.len())
        })
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.on_file(|file| file.flush()).unwrap_or(Ok(()))
    }
}

/// One rrd stream being encoded: the blueprint's store, then the recording's.
struct Stream {
    encoder: Encoder<Sink>,
}

impl Stream {
    fn begin_store(&mut self, store: StoreId) -> RrdResult<()> {
        self.append(&store_info(store))
    }

    fn append(&mut self, msg: &LogMsg) -> RrdResult<()> {
        self.encoder.append(msg).map(|_| ()).map_err(text)
    }

    fn send_to(&mut self, store: StoreId, chunk: &Chunk) -> RrdResult<()> {
        self.append(&LogMsg::ArrowMsg(store, chunk.to_arrow_msg().map_err(text)?))
    }
}

/// The start of a recording file, encoded before the file is open: the stream's header and the
/// blueprint's store, activated (module doc).
pub struct Start {
    stream: Stream,
    file: FileSlot,
    application_id: &'static str,
}

impl Start {
    /// A file of application `application_id` that starts with `blueprint`.
    pub fn with(application_id: &'static str, blueprint: &BlueprintMessages) -> RrdResult<Self> {
        let version = rerun::external::re_build_info::CrateVersion::LOCAL;
        let file = FileSlot::default();
        let sink = Sink { memory: Vec::new(), file: file.clone() };
        // Uncompressed: LZ4 doubled the encoding time for a file of 1 MB (`rerun rrd optimize`
        // compresses one afterwards).
        let encoder = Encoder::new_eager(version, EncodingOptions::PROTOBUF_UNCOMPRESSED, sink).map_err(text)?;
        let mut stream = Stream { encoder };
        for message in &blueprint.messages {
            stream.append(message)?;
        }
        stream.append(&LogMsg::BlueprintActivationCommand(blueprint.activation.clone()))?;
        Ok(Start { stream, file, application_id })
    }
}

/// A recording file being written after its [`Start`] (module doc).
pub struct RrdFile {
    stream: Stream,
    recording: StoreId,
}

impl RrdFile {
    /// Continues `start` into `file` with a recording of id `recording_id`.
    pub fn create(start: Start, file: File, recording_id: &str) -> RrdResult<Self> {
        // 64 kB: the file is written once, front to back; a larger buffer only touches memory.
        *start.file.lock().unwrap_or_else(PoisonError::into_inner) = Some(BufWriter::with_capacity(1 << 16, file));
        let mut out =
            RrdFile { stream: start.stream, recording: StoreId::recording(start.application_id, recording_id) };
        out.stream.begin_store(out.recording.clone())?;
        Ok(out)
    }

    /// A chunk of the recording.
    pub fn send_chunk(&mut self, chunk: &Chunk) -> RrdResult<()> {
        self.stream.send_to(self.recording.clone(), chunk)
    }

    /// Writes the footer and flushes the file.
    pub fn finish(mut self) -> RrdResult<()> {
        self.stream.encoder.finish().map_err(text)?;
        let mut sink = self.stream.encoder.into_inner().map_err(text)?;
        sink.flush().map_err(text)
    }
}
