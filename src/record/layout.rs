//! The view a recording opens with, as data: written into a file by [`super::rrd`] and sent to a
//! viewer through `rerun::blueprint` by [`super::stream`].

/// Views (rerun's class identifiers: `3D`, `TimeSeries`, `TextLog`) in horizontal and vertical
/// containers.
#[derive(Debug, Clone, PartialEq)]
pub enum BlueprintLayout {
    /// A view of the entities under `origin`.
    View { class: &'static str, name: &'static str, origin: &'static str },
    /// Side by side.
    Horizontal(Vec<BlueprintLayout>),
    /// One above the other.
    Vertical(Vec<BlueprintLayout>),
}

/// The 3D scene left; contact force, tip deflection, drive torque and the event log one above the
/// other on the right.
pub fn run_layout() -> BlueprintLayout {
    let view = |class, name, origin| BlueprintLayout::View { class, name, origin };
    let plots = BlueprintLayout::Vertical(vec![
        view("TimeSeries", "contact force (N)", "plots/contact_force"),
        view("TimeSeries", "tip deflection (m)", "plots/tip_deflection"),
        view("TimeSeries", "drive torque (N·m)", "plots/drive_torque"),
        view("TextLog", "events", "events"),
    ]);
    BlueprintLayout::Horizontal(vec![view("3D", "scene", "world"), plots])
}
