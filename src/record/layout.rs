//! The view a recording opens with, as data: logged as a blueprint of rerun's by
//! [`super::blueprint`], which a file starts with and a stream to a viewer sends.

/// Views (rerun's class identifiers: `3D`, `TimeSeries`, `TextLog`) in horizontal and vertical
/// containers.
#[derive(Debug, Clone, PartialEq)]
pub enum BlueprintLayout {
    /// A view of the entities under `origin` (a 3D view's camera where `eye` gives it).
    View { class: &'static str, name: &'static str, origin: &'static str, eye: Option<Eye> },
    /// Side by side.
    Horizontal(Vec<BlueprintLayout>),
    /// One above the other.
    Vertical(Vec<BlueprintLayout>),
}

/// Where a 3D view's camera stands and what it looks at, world m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eye {
    /// The camera.
    pub position_m: [f32; 3],
    /// The point it looks at (and orbits about).
    pub look_target_m: [f32; 3],
}

impl Eye {
    /// Framing the lift plane an arm of `length_m` pivoting at `pivot_m` sweeps from the
    /// horizontal to the vertical: looking at the middle of that quarter disc from in front of
    /// the plane, a little to the side and above.
    pub fn framing_the_lift(pivot_m: [f64; 3], length_m: f64) -> Self {
        let l = length_m as f32;
        let [x, y, z] = pivot_m.map(|v| v as f32);
        let target = [x + 0.45 * l, y + 0.4 * l, z];
        // Far enough that the quarter disc fits the scene's panel, a third of the window wide.
        Eye { position_m: [target[0] + 0.3 * l, target[1] + 0.5 * l, z + 2.8 * l], look_target_m: target }
    }
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunViews {
    /// The actuator's.
    pub actuator: ActuatorViews,
    /// A held string's tip deflection.
    pub string: bool,
    /// A tilting head's angle on its hinge.
    pub head: bool,
    /// The sign-off's stress at the worst station and pin loads.
    pub sign_off: bool,
    /// The 3D view's camera (a run with frames).
    pub eye: Option<Eye>,
}

impl RunViews {
    /// The views for a run's series: its channels (a complete sign-off's among them) and its 3D
    /// frames.
    pub fn of(series: &crate::run::Series) -> Self {
        let lift = series.layout.as_ref().map(|l| (l.pivot_m, l.length_m));
        Self::declared(&series.channels, lift)
    }

    /// The views a run of `compiled` with `options` will call for, known before it steps: from
    /// the channels its producers declare, the sign-off it is asked for (whose channels follow
    /// where the run's peak falls) and the 3D frames it captures. A run that ends as it should
    /// calls for these ([`RunViews::of`] its series); one the guard stopped before its sign-off
    /// was complete does not.
    pub fn before_run(compiled: &crate::run::CompiledModel, options: &crate::run::RunOptions) -> Self {
        let lift = (compiled.model.robot.lift.pivot_m, compiled.arm.model.length_m());
        let declared = Self::declared(&compiled.channels, options.capture_frames.then_some(lift));
        RunViews { sign_off: options.sign_off, ..declared }
    }

    /// The views of a run with `channels`, with a 3D view framing the lift about a pivot with an
    /// arm's length (m) where the run draws it.
    fn declared(channels: &[crate::channel::Channel], lift: Option<([f64; 3], f64)>) -> Self {
        use crate::channel::{ActuatorOutput, Reading};
        let reads = |wanted: fn(Reading) -> bool| channels.iter().any(|c| wanted(c.reading()));
        let actuator = if reads(|r| matches!(r, Reading::Actuator(ActuatorOutput::Pressure(..)))) {
            ActuatorViews::TrackingAndPressures
        } else if reads(|r| matches!(r, Reading::Actuator(ActuatorOutput::TrackingError))) {
            ActuatorViews::Tracking
        } else {
            ActuatorViews::None
        };
        RunViews {
            actuator,
            string: reads(|r| r == Reading::StringTipDeflection),
            head: reads(|r| r == Reading::HeadAngle),
            sign_off: reads(|r| matches!(r, Reading::Stress { .. })),
            eye: lift.map(|(pivot_m, length_m)| Eye::framing_the_lift(pivot_m, length_m)),
        }
    }
}

/// The 3D scene left; contact force, tip deflection, drive torque, a held string's tip
/// deflection, a tilting head's angle, the sign-off's stress and pin loads, an actuator's tracking error and chamber pressures, and the event log one above
/// the other on the right.
pub fn run_layout(views: RunViews) -> BlueprintLayout {
    let actuator = views.actuator;
    let view = |class, name, origin| BlueprintLayout::View { class, name, origin, eye: None };
    let mut plots = vec![
        view("TimeSeries", "contact force (N)", "plots/contact_force"),
        view("TimeSeries", "tip deflection (m)", "plots/tip_deflection"),
        view("TimeSeries", "drive torque (N·m)", "plots/drive_torque"),
    ];
    if views.string {
        plots.push(view("TimeSeries", "string tip deflection (m)", "plots/string/tip_deflection"));
    }
    if views.head {
        plots.push(view("TimeSeries", "head angle (°)", "plots/head/angle_deg"));
    }
    if views.sign_off {
        plots.push(view("TimeSeries", "stress at the worst station (Pa)", "plots/stress"));
        plots.push(view("TimeSeries", "pin loads (N)", "plots/pins"));
    }
    if actuator != ActuatorViews::None {
        plots.push(view("TimeSeries", "tracking error (°)", "plots/actuator/tracking_error_deg"));
    }
    if actuator == ActuatorViews::TrackingAndPressures {
        plots.push(view("TimeSeries", "chamber pressures (Pa)", "plots/actuator/pressure"));
    }
    plots.push(view("TextLog", "events", "events"));
    let scene = BlueprintLayout::View { class: "3D", name: "scene", origin: "world", eye: views.eye };
    BlueprintLayout::Horizontal(vec![scene, BlueprintLayout::Vertical(plots)])
}
