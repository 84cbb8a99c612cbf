//! The view a recording opens with ([`super::layout`]) as the messages that log it into a
//! blueprint store of rerun's: its views and containers at time 0 of the `blueprint` timeline, as
//! rerun's `Blueprint` logs them, the viewport, and the command that activates it. A file starts
//! with them ([`super::rrd`]) and a stream to a viewer sends them ([`super::stream`]), alike.
//!
//! Unlike rerun's `Blueprint`, nothing here depends on the clock or on randomness: the store is
//! named by the scenario and a digest of the layout, and the views' identifiers derive from that
//! name, so recordings of one scenario with the same views share one blueprint in the viewer, and
//! ones with other views do not.

use rerun::external::re_log_types::{
    BlueprintActivationCommand, SetStoreInfo, StoreId, StoreInfo, StoreKind, StoreSource,
};
use rerun::log::{Chunk, LogMsg, RowId};
use rerun::{AsComponents, TimePoint};

use super::layout::{BlueprintLayout, RunViews, run_layout};
use super::{RrdResult, text};

/// A blueprint as the messages that log it, and the command that activates it once they have.
pub struct BlueprintMessages {
    /// The store's info, then a chunk per row.
    pub messages: Vec<LogMsg>,
    /// Activates it, as the application's default too.
    pub activation: BlueprintActivationCommand,
}

impl BlueprintMessages {
    /// The blueprint of application `application_id` for a run of scenario `scenario` with
    /// `views`.
    pub fn new(application_id: &'static str, scenario: &str, views: RunViews) -> RrdResult<Self> {
        let layout = run_layout(views);
        let digest = crate::sweep::plan::fnv1a64(&[format!("{layout:?}").as_bytes()]);
        let name = format!("{scenario}-blueprint-{digest:016x}");
        let store = StoreId::new(StoreKind::Blueprint, application_id, name.as_str());
        let mut builder = Builder { messages: vec![store_info(store.clone())], store, name, parts: 0 };
        let root = builder.part(&layout)?;
        let viewport = types::ViewportBlueprint::new().with_root_container(types::RootContainer(root.0.into()));
        builder.row("viewport", &viewport)?;
        let activation =
            BlueprintActivationCommand { blueprint_id: builder.store, make_active: true, make_default: true };
        Ok(BlueprintMessages { messages: builder.messages, activation })
    }
}

/// The message that opens `store`, from this program.
pub(super) fn store_info(store: StoreId) -> LogMsg {
    let source = StoreSource::Other(format!("pipearm {}", env!("CARGO_PKG_VERSION")));
    LogMsg::SetStoreInfo(SetStoreInfo { row_id: *RowId::new(), info: StoreInfo::new(store, source) })
}

/// A blueprint's messages being made.
struct Builder {
    messages: Vec<LogMsg>,
    store: StoreId,
    /// The store's name, from which the parts' identifiers derive.
    name: String,
    /// The parts made so far.
    parts: u8,
}

impl Builder {
    /// Logs a view or a container (its children first) and returns its id and blueprint path.
    fn part(&mut self, part: &BlueprintLayout) -> RrdResult<([u8; 16], String)> {
        self.parts += 1;
        let id = blueprint_uuid(&self.name, self.parts);
        match part {
            BlueprintLayout::View { class, name, origin, eye } => {
                let path = format!("view/{}", uuid_text(&id));
                let contents = types::ViewContents::new([types::QueryExpression("$origin/**".into())]);
                self.row(&format!("{path}/ViewContents"), &contents)?;
                if let Some(eye) = eye {
                    // A view property, at the path rerun's own blueprint API logs them.
                    let controls = types::EyeControls3D::new()
                        .with_kind(types::Eye3DKind::Orbital)
                        .with_position(eye.position_m)
                        .with_look_target(eye.look_target_m);
                    self.row(&format!("{path}/EyeControls3D"), &controls)?;
                }
                let view = types::ViewBlueprint::new(types::ViewClass((*class).into()))
                    .with_display_name(rerun::components::Name((*name).into()))
                    .with_space_origin(*origin);
                self.row(&path, &view)?;
                Ok((id, path))
            }
            BlueprintLayout::Horizontal(children) | BlueprintLayout::Vertical(children) => {
                let mut paths = Vec::with_capacity(children.len());
                for child in children {
                    let (_, path) = self.part(child)?;
                    paths.push(types::IncludedContent(format!("/{path}").into()));
                }
                let kind = match part {
                    BlueprintLayout::Horizontal(_) => types::ContainerKind::Horizontal,
                    _ => types::ContainerKind::Vertical,
                };
                let path = format!("container/{}", uuid_text(&id));
                self.row(&path, &types::ContainerBlueprint::new(kind).with_contents(paths))?;
                Ok((id, path))
            }
        }
    }

    /// A blueprint row: at sequence 0 of the `blueprint` timeline, as rerun's `Blueprint` logs it.
    fn row(&mut self, entity: &str, archetype: &dyn AsComponents) -> RrdResult<()> {
        let time = TimePoint::from([(rerun::Timeline::new_sequence("blueprint"), 0)]);
        let chunk = Chunk::builder(entity).with_archetype(RowId::new(), time, archetype).build().map_err(text)?;
        self.messages.push(LogMsg::ArrowMsg(self.store.clone(), chunk.to_arrow_msg().map_err(text)?));
        Ok(())
    }
}

/// Blueprint types (`rerun::blueprint` re-exports their components, not their archetypes).
mod types {
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
        let a = blueprint_uuid("default-blueprint-0", 1);
        assert_eq!(a, blueprint_uuid("default-blueprint-0", 1));
        assert_ne!(a, blueprint_uuid("default-blueprint-0", 2));
        assert_ne!(a, blueprint_uuid("lowering-blueprint-0", 1));
        let text = uuid_text(&a);
        assert_eq!(text.len(), 36);
        assert_eq!(text.as_bytes()[14], b'4', "version nibble in {text}");
    }
}
