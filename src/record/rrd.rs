//! An `.rrd` file written with no `RecordingStream`: the one place that uses rerun's internal
//! types (`re_log_encoding`, `re_log_types`, the blueprint archetypes of `re_sdk_types`, all
//! through `rerun::external`), because rerun's public path to a file costs a third of the default
//! run (docs/recording.md, "How it is written").
//!
//! A `RecordingStream` is made for live logging: a batcher, a forwarding and a file-writer thread
//! per stream, LZ4 on every chunk, a second stream for the blueprint. The file here holds what
//! that stream would write, in the same messages and in the order `with_blueprint` sends them:
//! the blueprint's store ([`Start`]: its views and containers at time 0 of the `blueprint`
//! timeline, as rerun's `Blueprint` logs them, and the command that activates it), then the
//! recording's ([`RrdFile`]: its store info, one Arrow message per chunk), then rerun's footer,
//! which indexes both stores' chunks and which `rerun rrd verify` and rerun's readers that seek
//! find at the file's end. The start is encoded in memory before the file is open (on another
//! thread while the run steps, where the caller wishes); the encoder counts its bytes, so the
//! footer's offsets are the file's.
//!
//! Unlike rerun's streams, nothing here depends on the clock or on randomness: the blueprint's
//! identifiers derive from its name and the chunks carry no `log_time`, so a run writes the same
//! entities, times and values every time.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::sync::{Arc, Mutex, PoisonError};

use rerun::external::re_log_encoding::{Encoder, EncodingOptions};
use rerun::external::re_log_types::{
    BlueprintActivationCommand, SetStoreInfo, StoreId, StoreInfo, StoreKind, StoreSource,
};
use rerun::log::{Chunk, LogMsg, RowId};
use rerun::{AsComponents, TimePoint};

use super::layout::BlueprintLayout;

/// An error from rerun's chunk builder or encoder, as text (their error types are many).
pub type RrdResult<T> = Result<T, String>;

pub(super) fn text(e: impl std::fmt::Display) -> String {
    e.to_string()
}

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
        let source = StoreSource::Other(format!("pipearm {}", env!("CARGO_PKG_VERSION")));
        let info = SetStoreInfo { row_id: *RowId::new(), info: StoreInfo::new(store, source) };
        self.append(&LogMsg::SetStoreInfo(info))
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
    /// The blueprint `layout` of application `application_id`, in a store named `blueprint_name`
    /// (the identifiers of its views derive from it).
    pub fn blueprint(application_id: &'static str, blueprint_name: &str, layout: &BlueprintLayout) -> RrdResult<Self> {
        let version = rerun::external::re_build_info::CrateVersion::LOCAL;
        let file = FileSlot::default();
        let sink = Sink { memory: Vec::new(), file: file.clone() };
        // Uncompressed: LZ4 doubled the encoding time for a file of 1 MB (`rerun rrd optimize`
        // compresses one afterwards).
        let encoder = Encoder::new_eager(version, EncodingOptions::PROTOBUF_UNCOMPRESSED, sink).map_err(text)?;
        let mut stream = Stream { encoder };
        let store = StoreId::new(StoreKind::Blueprint, application_id, blueprint_name);
        stream.begin_store(store.clone())?;
        let mut ids = 0u8;
        let root = stream.blueprint_part(&store, blueprint_name, layout, &mut ids)?;
        let viewport = blueprint::ViewportBlueprint::new().with_root_container(blueprint::RootContainer(root.0.into()));
        stream.blueprint_row(&store, "viewport", &viewport)?;
        let activate = BlueprintActivationCommand { blueprint_id: store, make_active: true, make_default: true };
        stream.append(&LogMsg::BlueprintActivationCommand(activate))?;
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

impl Stream {
    /// Logs a view or a container (its children first) and returns its id and blueprint path.
    fn blueprint_part(
        &mut self,
        store: &StoreId,
        blueprint_name: &str,
        part: &BlueprintLayout,
        ids: &mut u8,
    ) -> RrdResult<([u8; 16], String)> {
        *ids += 1;
        let id = blueprint_uuid(blueprint_name, *ids);
        match part {
            BlueprintLayout::View { class, name, origin, eye } => {
                let path = format!("view/{}", uuid_text(&id));
                let contents = blueprint::ViewContents::new([blueprint::QueryExpression("$origin/**".into())]);
                self.blueprint_row(store, &format!("{path}/ViewContents"), &contents)?;
                if let Some(eye) = eye {
                    // A view property, at the path rerun's own blueprint API logs them.
                    let controls = blueprint::EyeControls3D::new()
                        .with_kind(blueprint::Eye3DKind::Orbital)
                        .with_position(eye.position_m)
                        .with_look_target(eye.look_target_m);
                    self.blueprint_row(store, &format!("{path}/EyeControls3D"), &controls)?;
                }
                let view = blueprint::ViewBlueprint::new(blueprint::ViewClass((*class).into()))
                    .with_display_name(rerun::components::Name((*name).into()))
                    .with_space_origin(*origin);
                self.blueprint_row(store, &path, &view)?;
                Ok((id, path))
            }
            BlueprintLayout::Horizontal(children) | BlueprintLayout::Vertical(children) => {
                let mut paths = Vec::with_capacity(children.len());
                for child in children {
                    let (_, path) = self.blueprint_part(store, blueprint_name, child, ids)?;
                    paths.push(blueprint::IncludedContent(format!("/{path}").into()));
                }
                let kind = match part {
                    BlueprintLayout::Horizontal(_) => blueprint::ContainerKind::Horizontal,
                    _ => blueprint::ContainerKind::Vertical,
                };
                let path = format!("container/{}", uuid_text(&id));
                self.blueprint_row(store, &path, &blueprint::ContainerBlueprint::new(kind).with_contents(paths))?;
                Ok((id, path))
            }
        }
    }

    /// A blueprint row: at sequence 0 of the `blueprint` timeline, as rerun's `Blueprint` logs it.
    fn blueprint_row(&mut self, store: &StoreId, entity: &str, archetype: &dyn AsComponents) -> RrdResult<()> {
        let time = TimePoint::from([(rerun::Timeline::new_sequence("blueprint"), 0)]);
        let chunk = Chunk::builder(entity).with_archetype(RowId::new(), time, archetype).build().map_err(text)?;
        self.send_to(store.clone(), &chunk)
    }
}

/// Blueprint types (`rerun::blueprint` re-exports their components, not their archetypes).
mod blueprint {
    pub use rerun::blueprint::components::{
        ContainerKind, Eye3DKind, IncludedContent, QueryExpression, RootContainer, ViewClass,
    };
    pub use rerun::external::re_sdk_types::blueprint::archetypes::{
        ContainerBlueprint, EyeControls3D, ViewBlueprint, ViewContents, ViewportBlueprint,
    };
}

/// A version-4-shaped UUID for the `k`-th part of the blueprint named `name` (FNV-1a): the same
/// blueprint gets the same identifiers every time.
fn blueprint_uuid(name: &str, k: u8) -> [u8; 16] {
    let hash = |seed: u64| name.bytes().chain([k]).fold(seed, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3));
    let mut bytes = [0u8; 16];
    bytes[..8].copy_from_slice(&hash(0xcbf2_9ce4_8422_2325).to_be_bytes());
    bytes[8..].copy_from_slice(&hash(0x8422_2325_cbf2_9ce4).to_be_bytes());
    bytes[6] = (bytes[6] & 0x0f) | 0x40;
    bytes[8] = (bytes[8] & 0x3f) | 0x80;
    bytes
}

/// `8-4-4-4-12` lowercase hex, as rerun writes the ids in blueprint paths.
fn uuid_text(bytes: &[u8; 16]) -> String {
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    format!("{}-{}-{}-{}-{}", &hex[..8], &hex[8..12], &hex[12..16], &hex[16..20], &hex[20..])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blueprint_ids_are_distinct_stable_uuids() {
        let a = blueprint_uuid("default-blueprint", 1);
        assert_eq!(a, blueprint_uuid("default-blueprint", 1));
        assert_ne!(a, blueprint_uuid("default-blueprint", 2));
        assert_ne!(a, blueprint_uuid("lowering-blueprint", 1));
        let text = uuid_text(&a);
        assert_eq!(text.len(), 36);
        assert_eq!(text.as_bytes()[14], b'4', "version nibble in {text}");
    }
}
