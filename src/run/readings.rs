//! What the run reads off the scene at each step besides the arm's sample: the held string,
//! the sensors, the tilting head; and the head's summary.

use serde::Serialize;

use super::Series;
use crate::model::Model;
use crate::point_load::{PointLoad, World};
use crate::scene::Scene;
use crate::sensor::SensorProbe;
use crate::sensor::probe::ArmState;

/// The held string's tip deflection and stress at the scene's current state.
pub(super) fn read_string(scene: &Scene, gravity_m_s2: f64, series: &mut Series) {
    let Some(probe) = &scene.string else { return };
    let (hub, q, qd) = scene.arm.kinematics();
    let qdd = scene.arm.elastic_accelerations();
    let reading = probe.read(&ArmState { hub, q: &q, qd: &qd, qdd: &qdd }, gravity_m_s2);
    series.string_tip_deflection_m.push(reading.tip_deflection_m);
    series.string_stress_pa.push(reading.max_bending_stress_pa);
    // A flexible string's stations are read from the recorded q after the run, where it is kept.
    if !(probe.is_flexible() && series.modal_dofs > 0) {
        series.string_peak_stress.push(probe.peak_stress(&ArmState { hub, q: &q, qd: &qd, qdd: &qdd }, gravity_m_s2));
    }
}

/// Each sensor's reading at the scene's current state.
pub(super) fn read_sensors(scene: &Scene, probes: &[SensorProbe], series: &mut Series) {
    if probes.is_empty() {
        return;
    }
    let (hub, q, qd) = scene.arm.kinematics();
    let qdd = scene.arm.elastic_accelerations();
    let state = ArmState { hub, q: &q, qd: &qd, qdd: &qdd };
    let loads: Vec<PointLoad<World>> = scene
        .pairs()
        .filter(|p| p.force_n > 0.0 && p.side == crate::scene::Side::Arm)
        .map(|p| PointLoad::new(p.station_m, p.point_m, p.normal_world.map(|n| p.force_n * n)))
        .collect();
    for (probe, out) in probes.iter().zip(&mut series.sensors) {
        out.values.push(probe.read(&state, &loads));
    }
}

/// The tilting head's angle at the scene's current state.
pub(super) fn read_head(scene: &Scene, series: &mut Series) {
    if let Some(head) = scene.arm.head_state() {
        series.head_angle_rad.push(head.angle_rad);
    }
    if let Some(torque) = scene.arm.head_drive_torque_n_m() {
        series.head_drive_torque_n_m.push(torque);
    }
}

/// How the tilting head swung on its hinge: angles relative to the arm's section at the hinge,
/// about the lift axis, 0 at the URDF pose. Its rest moves with the lift (the head's weight turns
/// with the arm), so the range holds the quasi-static travel as well as the swing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeadSummary {
    /// The hinge's joint.
    pub joint: String,
    /// Where the head rests on its hinge at the start, deg.
    pub rest_angle_deg: f64,
    /// Its smallest and largest angle over the run, deg.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Half the peak-to-peak swing after the drive ends, deg.
    pub residual_swing_deg: f64,
    /// A driven head's largest |drive torque| on the head, N·m (absent unless driven).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_drive_torque_n_m: Option<f64>,
}

impl HeadSummary {
    /// The swing in `series`, the drive ending at `drive_end_s`; `None` without a head.
    pub fn of(model: &Model, series: &Series, drive_end_s: f64) -> Option<Self> {
        let head = model.robot.head.as_ref()?;
        let angles = &series.head_angle_rad;
        let rest = *angles.first()?;
        let range = |values: &mut dyn Iterator<Item = f64>| {
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| (lo.min(a), hi.max(a)))
        };
        let (low, high) = range(&mut angles.iter().copied());
        let mut after = series.t_s.iter().zip(angles).filter(|(t, _)| **t >= drive_end_s).map(|(_, a)| *a);
        let (settle_low, settle_high) = range(&mut after);
        Some(HeadSummary {
            joint: head.joint.clone(),
            rest_angle_deg: rest.to_degrees(),
            min_angle_deg: low.to_degrees(),
            max_angle_deg: high.to_degrees(),
            residual_swing_deg: if settle_high >= settle_low {
                0.5 * (settle_high - settle_low).to_degrees()
            } else {
                0.0
            },
            peak_drive_torque_n_m: head
                .is_driven()
                .then(|| series.head_drive_torque_n_m.iter().fold(0.0_f64, |p, t| p.max(t.abs()))),
        })
    }
}
