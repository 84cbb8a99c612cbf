//! The arm's channels ([`crate::channel`]): its hub's motion, its tip, the drive's torque on it, a
//! tilting head's angle and drive torque, and the arm's energies and elastic coordinates.

use crate::channel::{Channel, Reading};
use crate::robot::{HingeLaw, TiltingHead};

/// Entity path of the tip deflection's plot: axial and transverse, a trace each.
pub const TIP_DEFLECTION_ENTITY: &str = "plots/tip_deflection";

/// Entity path of the tip velocity's plot: axial and transverse, a trace each.
pub const TIP_VELOCITY_ENTITY: &str = "plots/tip_velocity";

/// Entity path of the energies' plot: kinetic, strain and gravity, a trace each.
pub const ENERGY_ENTITY: &str = "plots/energy";

/// Entity path of the elastic coordinates' plot, a trace each (`q1`, `q2`, …).
pub const MODAL_ENTITY: &str = "plots/modal";

/// Radians to the degrees the hub and the head are plotted in.
const DEGREES: f64 = 180.0 / std::f64::consts::PI;

/// The hub's angle, rate and acceleration (plotted in degrees), the tip's deflection and
/// velocity in the hub frame, axial and transverse, and the drive's torque: all measurable.
pub fn channels() -> Vec<Channel> {
    let mut out = vec![
        Channel::new("hub.angle", "rad", Reading::HubAngle).plotted("plots/hub/angle_deg", DEGREES),
        Channel::new("hub.rate", "rad/s", Reading::HubRate).plotted("plots/hub/rate_deg_s", DEGREES),
        Channel::new("hub.accel", "rad/s^2", Reading::HubAccel).plotted("plots/hub/accel_deg_s2", DEGREES),
    ];
    let axes = ["axial", "transverse"].into_iter().enumerate();
    out.extend(axes.clone().map(|(k, axis)| {
        Channel::new(format!("tip_deflection.{axis}"), "m", Reading::TipDeflection(k))
            .traced(TIP_DEFLECTION_ENTITY, axis)
    }));
    out.extend(axes.map(|(k, axis)| {
        Channel::new(format!("tip_velocity.{axis}"), "m/s", Reading::TipVelocity(k)).traced(TIP_VELOCITY_ENTITY, axis)
    }));
    out.push(Channel::new("drive_torque", "N*m", Reading::DriveTorque).plotted("plots/drive_torque", 1.0));
    out.into_iter().map(Channel::measurable).collect()
}

/// A tilting head's angle on its hinge (measurable, plotted in degrees) and, driven, its drive's
/// torque.
pub fn head_channels(head: &TiltingHead) -> Vec<Channel> {
    let angle = Channel::new("head.angle", "rad", Reading::HeadAngle).plotted("plots/head/angle_deg", DEGREES);
    let mut out = vec![angle.measurable()];
    if matches!(head.law, HingeLaw::Driven { .. }) {
        let torque = Channel::new("head.drive_torque", "N*m", Reading::HeadDriveTorque);
        out.push(torque.plotted("plots/head/drive_torque", 1.0));
    }
    out
}

/// The kinetic, strain and gravity energies and `modal_dofs` elastic coordinates (the arm's,
/// then a flexible string's), each a trace of one plot.
pub fn state_channels(modal_dofs: usize) -> Vec<Channel> {
    let energies = ["kinetic", "strain", "gravity"].into_iter().enumerate();
    let mut out: Vec<Channel> = energies
        .map(|(k, kind)| Channel::new(format!("energy.{kind}"), "J", Reading::Energy(k)).traced(ENERGY_ENTITY, kind))
        .collect();
    out.extend((0..modal_dofs).map(|i| {
        Channel::new(format!("modal.q{}", i + 1), "m*kg^0.5", Reading::Modal(i))
            .traced(MODAL_ENTITY, format!("q{}", i + 1))
    }));
    out
}
