//! An `.rrd` file written on the caller's thread, with no `RecordingStream`: the one place that
//! uses rerun's internal types (`re_log_encoding`, `re_log_types`, the blueprint archetypes of
//! `re_sdk_types`, all through `rerun::external`), because rerun's public path to a file costs a
//! third of the default run (docs/recording.md, "How it is written").
//!
//! A `RecordingStream` is made for live logging: a batcher, a forwarding and a file-writer thread
//! per stream, LZ4 on every chunk, a second stream for the blueprint. The writer here writes what
//! that stream would, in the same messages: the recording's store info, one Arrow message per
//! chunk, the blueprint's store (its views and containers at time 0 of the `blueprint` timeline,
//! as rerun's `Blueprint` logs them) and the command that activates it, last. The encoder writes
//! rerun's footer on [`RrdFile::finish`] (`rerun rrd verify` requires it); errors, the footer's
//! included, are returned, not logged.
//!
//! Unlike rerun's streams, nothing here depends on the clock or on randomness: the blueprint's
//! identifiers derive from the recording id and the chunks carry no `log_time`, so a run writes
//! the same entities, times and values every time.

use std::fs::File;
use std::io::BufWriter;

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

/// A recording file being written: the recording's store, then the blueprint's.
pub struct RrdFile {
    encoder: Encoder<BufWriter<File>>,
    recording: StoreId,
}

impl RrdFile {
    /// Starts a recording of application `application_id` with id `recording_id` in `file`.
    pub fn create(file: File, application_id: &'static str, recording_id: &str) -> RrdResult<Self> {
        let version = rerun::external::re_build_info::CrateVersion::LOCAL;
        // 64 kB: the file is written once, front to back; a larger buffer only touches memory.
        let writer = BufWriter::with_capacity(1 << 16, file);
        // Uncompressed: LZ4 doubled the encoding time for a file of 1 MB (`rerun rrd optimize`
        // compresses one afterwards).
        let encoder = Encoder::new_eager(version, EncodingOptions::PROTOBUF_UNCOMPRESSED, writer).map_err(text)?;
        let mut out = RrdFile { encoder, recording: StoreId::recording(application_id, recording_id) };
        out.begin_store(out.recording.clone())?;
        Ok(out)
    }

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

    /// A chunk of the recording.
    pub fn send_chunk(&mut self, chunk: &Chunk) -> RrdResult<()> {
        self.send_to(self.recording.clone(), chunk)
    }

    /// Writes `layout` as the recording's blueprint and activates it (ends the recording's store:
    /// call it last).
    pub fn blueprint(&mut self, layout: &BlueprintLayout) -> RrdResult<()> {
        let application = self.recording.application_id().clone();
        let store =
            StoreId::new(StoreKind::Blueprint, application, format!("{}-blueprint", self.recording.recording_id()));
        self.begin_store(store.clone())?;
        let mut ids = 0u8;
        let root = self.blueprint_part(&store, layout, &mut ids)?;
        let viewport = blueprint::ViewportBlueprint::new().with_root_container(blueprint::RootContainer(root.0.into()));
        self.blueprint_row(&store, "viewport", &viewport)?;
        let activate = BlueprintActivationCommand { blueprint_id: store, make_active: true, make_default: true };
        self.append(&LogMsg::BlueprintActivationCommand(activate))
    }

    /// Logs a view or a container (its children first) and returns its id and blueprint path.
    fn blueprint_part(
        &mut self,
        store: &StoreId,
        part: &BlueprintLayout,
        ids: &mut u8,
    ) -> RrdResult<([u8; 16], String)> {
        *ids += 1;
        let id = blueprint_uuid(self.recording.recording_id().as_str(), *ids);
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
                    let (_, path) = self.blueprint_part(store, child, ids)?;
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

    /// Writes the footer and flushes the file.
    pub fn finish(mut self) -> RrdResult<()> {
        self.encoder.finish().map_err(text)?;
        let mut writer = self.encoder.into_inner().map_err(text)?;
        std::io::Write::flush(&mut writer).map_err(text)
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

/// A version-4-shaped UUID for the `k`-th blueprint part of a recording, from its id (FNV-1a):
/// the same recording gets the same blueprint every time.
fn blueprint_uuid(recording_id: &str, k: u8) -> [u8; 16] {
    let hash = |seed: u64| {
        recording_id.bytes().chain([k]).fold(seed, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
    };
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
        let a = blueprint_uuid("default", 1);
        assert_eq!(a, blueprint_uuid("default", 1));
        assert_ne!(a, blueprint_uuid("default", 2));
        assert_ne!(a, blueprint_uuid("lowering", 1));
        let text = uuid_text(&a);
        assert_eq!(text.len(), 36);
        assert_eq!(text.as_bytes()[14], b'4', "version nibble in {text}");
    }
}
