//! A run's summary, from its compiled model, the scene as it was built and the series the loop
//! filled: nothing here reads the scene the loop left.

use super::{CompiledModel, DriveLimits, HeadSummary, PairSummary, RunSummary, SensorSummary, Series, SlipSummary};
use crate::actuator::ActuatorSummary;
use crate::analysis::{StiffnessClass, residual_of_run};
use crate::contact::ImpactTracker;
use crate::model::Model;
use crate::scene::{Scene, SceneError};

/// What the summary reads of the scene, constant over the run and taken as it was built: the
/// summary reads the compiled model, this and the series, not the scene the loop left.
pub(super) struct AsBuilt {
    /// The contact detection the pads resolved to.
    detection: crate::model::Detection,
    /// A friction clamp's squeeze on each jaw, N.
    squeeze_n: Option<f64>,
}

impl AsBuilt {
    pub(super) fn of(scene: &Scene) -> Self {
        AsBuilt { detection: scene.detection(), squeeze_n: scene.grip().map(|g| g.squeeze_n) }
    }
}

pub(super) fn summarize(
    compiled: &CompiledModel,
    built: &AsBuilt,
    series: &Series,
    trackers: &[ImpactTracker],
    steps: usize,
    wall_time_s: f64,
) -> Result<RunSummary, SceneError> {
    let (model, fastest_rad_s): (&Model, f64) = (&compiled.model, compiled.arm.fastest_rad_s);
    let arm = &compiled.arm.model;
    let g = model.physics.gravity_m_s2;
    let w_static = arm.beam.gravity_tip_deflection_m(crate::arm::STANDARD_GRAVITY_M_S2)?;
    let length = arm.length_m();
    let payload_kg = model.payload.mass_kg();
    let deflection: Vec<(f64, f64)> =
        series.t_s.iter().zip(&series.tip_deflection_m).map(|(t, d)| (*t, d[1])).collect();
    let max_tip_deflection_m = deflection.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    // Under an actuator the hub rings on its drive: the residual's frequency and decay are its.
    let hub_rate: Option<Vec<(f64, f64)>> = (model.drive.actuator != crate::actuator::Actuator::Ideal)
        .then(|| series.t_s.iter().copied().zip(series.hub_rate_rad_s.iter().copied()).collect());
    let (torque_i, peak_torque) = series
        .drive_torque_n_m
        .iter()
        .enumerate()
        .fold((0, 0.0_f64), |best, (i, t)| if t.abs() > best.1 { (i, t.abs()) } else { best });
    let pairs = compiled
        .pair_names
        .iter()
        .zip(trackers)
        .map(|(pair, tracker)| {
            let impacts = tracker.impacts();
            let peak = impacts.iter().copied().max_by(|a, b| a.peak_force_n.total_cmp(&b.peak_force_n));
            let peak_force_n = peak.map_or(0.0, |p| p.peak_force_n);
            PairSummary {
                pair: pair.clone(),
                peak_force_n,
                peak_time_s: peak.map_or(f64::NAN, |p| p.peak_time_s),
                peak_force_per_payload_weight: if payload_kg > 0.0 {
                    peak_force_n / (payload_kg * g)
                } else {
                    f64::NAN
                },
                impulse_n_s: impacts.iter().map(|i| i.impulse_n_s).sum(),
                impact_count: impacts.len(),
                impacts,
            }
        })
        .collect();
    let w_over_l = w_static / length;
    Ok(RunSummary {
        scenario: model.name.clone(),
        robot: model.robot.name.clone(),
        payload_kg,
        model: arm.fidelity.to_string(),
        model_reason: String::new(),
        model_expected_error: None,
        integrator: model.integrator.to_string(),
        contact_method: model.contact.method.name().into(),
        contact_detection: (model.contact.method == crate::model::ContactMethod::Compliant)
            .then(|| built.detection.name().into()),
        step_s: model.time.step_s,
        free_step_s: model.time.free_step_s.unwrap_or(model.time.step_s),
        steps,
        simulated_s: series.t_s.last().copied().unwrap_or(0.0),
        wall_time_s,
        static_w_over_l: w_over_l,
        stiffness_class: StiffnessClass::of_ratio(w_over_l).describe().to_string(),
        motion_advice: crate::select::motion_advice(model, StiffnessClass::of_ratio(w_over_l)),
        max_tip_deflection_m,
        max_w_over_l: max_tip_deflection_m / length,
        peak_drive_torque_n_m: peak_torque,
        peak_drive_torque_time_s: series.t_s.get(torque_i).copied().unwrap_or(0.0),
        drive: DriveLimits::of(model, peak_torque),
        actuator: ActuatorSummary::of(
            model.drive.actuator.kind(),
            &model.drive.motion,
            &series.hub_angle_rad,
            &series.drive_torque_n_m,
            &series.actuator,
        ),
        residual: residual_of_run(&deflection, hub_rate.as_deref(), model.drive_end_s()),
        pairs,
        highest_omega_dt: fastest_rad_s * model.time.step_s,
        stability_limit_omega_dt: model.integrator.stability_limit_omega_dt(),
        sensors: series.sensors.iter().map(|s| SensorSummary::of(s, &series.t_s)).collect(),
        string_slip: built.squeeze_n.map(|squeeze_n| SlipSummary {
            squeeze_n,
            max_slip_m: series.string_slip_m.iter().map(|s| s.abs()).fold(0.0, f64::max),
            final_slip_m: series.string_slip_m.last().copied().unwrap_or(0.0),
            max_jaw_sinking_m: series.jaw_sinking_m.iter().copied().fold(0.0, f64::max),
        }),
        string: None,
        head: HeadSummary::of(model, series, model.drive_end_s()),
        sign_off: None,
    })
}
