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

/// What a run's actuator adds to the layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActuatorViews {
    /// An ideal drive: nothing.
    None,
    /// A servo: its tracking error.
    Tracking,
    /// A hydraulic drive: its tracking error and chamber pressures.
    TrackingAndPressures,
}

/// The plots a run's outputs call for besides the ones every run has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunViews {
    /// The actuator's.
    pub actuator: ActuatorViews,
    /// A held string's tip deflection.
    pub string: bool,
}

impl RunViews {
    /// The views for a run's series.
    pub fn of(series: &crate::run::Series) -> Self {
        RunViews { actuator: ActuatorViews::of(&series.actuator), string: !series.string_tip_deflection_m.is_empty() }
    }
}

/// The 3D scene left; contact force, tip deflection, drive torque, a held string's tip
/// deflection, an actuator's tracking error and chamber pressures, and the event log one above
/// the other on the right.
pub fn run_layout(views: RunViews) -> BlueprintLayout {
    let actuator = views.actuator;
    let view = |class, name, origin| BlueprintLayout::View { class, name, origin };
    let mut plots = vec![
        view("TimeSeries", "contact force (N)", "plots/contact_force"),
        view("TimeSeries", "tip deflection (m)", "plots/tip_deflection"),
        view("TimeSeries", "drive torque (N·m)", "plots/drive_torque"),
    ];
    if views.string {
        plots.push(view("TimeSeries", "string tip deflection (m)", "plots/string/tip_deflection"));
    }
    if actuator != ActuatorViews::None {
        plots.push(view("TimeSeries", "tracking error (°)", "plots/actuator/tracking_error_deg"));
    }
    if actuator == ActuatorViews::TrackingAndPressures {
        plots.push(view("TimeSeries", "chamber pressures (Pa)", "plots/actuator/pressure"));
    }
    plots.push(view("TextLog", "events", "events"));
    BlueprintLayout::Horizontal(vec![view("3D", "scene", "world"), BlueprintLayout::Vertical(plots)])
}

impl ActuatorViews {
    /// The views for a run's actuator outputs.
    pub fn of(outputs: &[crate::actuator::ActuatorOutputs]) -> Self {
        match outputs.first() {
            None => ActuatorViews::None,
            Some(o) if o.pressures_pa.is_some() => ActuatorViews::TrackingAndPressures,
            Some(_) => ActuatorViews::Tracking,
        }
    }
}
