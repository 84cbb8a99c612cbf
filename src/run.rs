//! One run of a scenario: scene → step loop → series → summary.

use std::time::Instant;

use serde::Serialize;

use crate::actuator::{ActuatorOutputs, ActuatorSummary};
use crate::analysis::Residual;
use crate::arm::{ArmError, ArmSample, Fidelity};
use crate::compile::Compiler;
use crate::contact::{Impact, ImpactTracker};
use crate::guard::{Divergence, DivergenceGuard, stability_advice};
use crate::integrate::StepControl;
use crate::model::{DEFAULT_TOLERANCE_M, Model};
use crate::scene::{Frame, Scene, SceneError, SceneLayout};
pub use crate::sensor::summary::{ChannelPeak, SensorSummary};
use crate::sensor::{Sensor, SensorProbe};
use crate::stress::StressProbe;

mod channels;
mod compiled;
mod readings;
mod summarize;

pub use channels::{channels, measurable_channels};
pub use compiled::CompiledModel;
pub use readings::HeadSummary;
use readings::{read_head, read_sensors, read_string};
use summarize::{AsBuilt, summarize};

/// Time histories of a run, one entry per step (the initial state included).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Series {
    /// Time, s.
    pub t_s: Vec<f64>,
    /// Hub angle, rad.
    pub hub_angle_rad: Vec<f64>,
    /// Hub rate, rad/s.
    pub hub_rate_rad_s: Vec<f64>,
    /// Hub acceleration, rad/s².
    pub hub_accel_rad_s2: Vec<f64>,
    /// Tip displacement in the hub frame [axial, transverse], m.
    pub tip_deflection_m: Vec<[f64; 2]>,
    /// Tip velocity relative to the hub frame [axial, transverse], m/s.
    pub tip_velocity_m_s: Vec<[f64; 2]>,
    /// Drive torque, N·m.
    pub drive_torque_n_m: Vec<f64>,
    /// The actuator's outputs per step (empty under an ideal drive).
    pub actuator: Vec<ActuatorOutputs>,
    /// The run's channels as their producers declare them ([`crate::channel`]): what the
    /// recording plots and the tables hold.
    pub channels: Vec<crate::channel::Channel>,
    /// Each contact pair's name (`arm-<pad>`, `string-<structure>`), in the order of
    /// `pad_force_n`.
    pub pair_names: Vec<String>,
    /// Contact force per pad (outer index: pad), N.
    pub pad_force_n: Vec<Vec<f64>>,
    /// Slip of a friction-clamped string along the arm, m (empty with a rigid clamp).
    pub string_slip_m: Vec<f64>,
    /// How deep the friction clamp's jaws have sunk into the string, m (empty with a rigid clamp).
    pub jaw_sinking_m: Vec<f64>,
    /// Deflection of the held string's far end normal to the arm, hub frame, m (empty without
    /// a string).
    pub string_tip_deflection_m: Vec<f64>,
    /// Largest bending stress at the held string's hands, Pa (empty without a string).
    pub string_stress_pa: Vec<f64>,
    /// Largest normal stress along the held string, axial and bending, Pa, and its station from
    /// the string's hub-side end, m (empty without a string).
    pub string_peak_stress: Vec<[f64; 2]>,
    /// The tilting head's angle on its hinge, rad (empty without one).
    pub head_angle_rad: Vec<f64>,
    /// A driven head's drive torque on the head, N·m (empty unless driven).
    pub head_drive_torque_n_m: Vec<f64>,
    /// Kinetic, strain and gravity energy, J.
    pub energies_j: Vec<[f64; 3]>,
    /// Elastic coordinates q (modal and rigid models only; empty for fe), `modal_dofs` per step
    /// one step after another (one buffer, not a vector per step).
    pub modal_q: Vec<f64>,
    /// Elastic coordinates per step in `modal_q`.
    pub modal_dofs: usize,
    /// Steps a recording keeps: every step in contact, the others at the record rate.
    pub keep: Vec<bool>,
    /// The scene for drawing at each kept step (when asked for).
    pub frames: Vec<Frame>,
    /// The unchanging part of the drawing.
    pub layout: Option<SceneLayout>,
    /// Each sensor's two channels per step, in the model's sensor order.
    pub sensors: Vec<SensorSeries>,
    /// Section forces along the arm and pin loads per step (empty without the sign-off).
    pub stress: crate::stress::StressSeries,
}

/// One sensor's readings per step.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorSeries {
    /// The sensor.
    pub sensor: Sensor,
    /// Its two channels per step, in the units of [`crate::sensor::SensorKind::channels`].
    pub values: Vec<[f64; 2]>,
}

impl Series {
    /// Empty histories with room for `steps` steps of `pads` pads, `modal_dofs` elastic
    /// coordinates and `frames` frames: grown by doubling instead, the histories of a run cost
    /// more in reallocation (copies, and fresh pages the kernel zeroes) than its contact detection.
    fn with_capacity(steps: usize, pads: usize, modal_dofs: usize, frames: usize, sensors: &[Sensor]) -> Self {
        Series {
            t_s: Vec::with_capacity(steps),
            hub_angle_rad: Vec::with_capacity(steps),
            hub_rate_rad_s: Vec::with_capacity(steps),
            hub_accel_rad_s2: Vec::with_capacity(steps),
            tip_deflection_m: Vec::with_capacity(steps),
            tip_velocity_m_s: Vec::with_capacity(steps),
            drive_torque_n_m: Vec::with_capacity(steps),
            pad_force_n: vec![Vec::with_capacity(steps); pads],
            energies_j: Vec::with_capacity(steps),
            modal_q: Vec::with_capacity(steps * modal_dofs),
            keep: Vec::with_capacity(steps),
            frames: Vec::with_capacity(frames),
            sensors: sensors
                .iter()
                .map(|sensor| SensorSeries { sensor: sensor.clone(), values: Vec::with_capacity(steps) })
                .collect(),
            ..Series::default()
        }
    }
}

/// How to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// Model fidelity (the scenario's if `None`).
    pub fidelity: Option<Fidelity>,
    /// Rate at which steps without contact are kept for a recording, Hz.
    pub record_rate_hz: f64,
    /// Capture the 3D scene (for a recording): every step in contact, at `frame_rate_hz`
    /// otherwise.
    pub capture_frames: bool,
    /// Rate of 3D frames without contact, Hz.
    pub frame_rate_hz: f64,
    /// Sign the run off: stresses along the arm, pin loads and fatigue (`docs/sign-off.md`).
    pub sign_off: bool,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions { fidelity: None, record_rate_hz: 25.0, capture_frames: false, frame_rate_hz: 10.0, sign_off: true }
    }
}

/// How a friction-clamped string fared.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlipSummary {
    /// Squeeze per jaw, N.
    pub squeeze_n: f64,
    /// Largest |slip| along the arm, m.
    pub max_slip_m: f64,
    /// Slip at the end, m.
    pub final_slip_m: f64,
    /// Deepest the jaws sank into the string, m (they should only touch it).
    pub max_jaw_sinking_m: f64,
}

/// Per contact pair: its peak force, impulse and impacts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairSummary {
    /// `arm-<pad>`.
    pub pair: String,
    /// Largest force, N.
    pub peak_force_n: f64,
    /// When, s.
    pub peak_time_s: f64,
    /// Peak force over the weight of the string (or payload) held, N/N (NaN without one).
    pub peak_force_per_payload_weight: f64,
    /// ∫ F dt over the run, N·s.
    pub impulse_n_s: f64,
    /// Number of impacts.
    pub impact_count: usize,
    /// Each impact.
    pub impacts: Vec<Impact>,
}

/// What a run reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// Scenario name.
    pub scenario: String,
    /// Robot name.
    pub robot: String,
    /// Payload mass, kg.
    pub payload_kg: f64,
    /// Model fidelity used.
    pub model: String,
    /// Why that fidelity.
    pub model_reason: String,
    /// The error `auto` expects of it on the headline quantities (absent when set by hand).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_expected_error: Option<crate::select::ExpectedError>,
    /// Integrator.
    pub integrator: String,
    /// Contact method.
    pub contact_method: String,
    /// Where the `compliant` method found its contacts: `pad-face` or `pipeline` (absent for
    /// the `rapier` method).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_detection: Option<String>,
    /// Time step around contact, s.
    pub step_s: f64,
    /// Time step in free motion, s (the same as `step_s` unless the scenario sets `free_step_s`).
    pub free_step_s: f64,
    /// Steps taken.
    pub steps: usize,
    /// Simulated time, s.
    pub simulated_s: f64,
    /// Wall time of the step loop, s (printed, not written: it varies run to run, and the
    /// summary file is bit-identical across runs).
    #[serde(skip)]
    pub wall_time_s: f64,
    /// Static tip deflection ratio of the horizontal arm under gravity with its payload.
    pub static_w_over_l: f64,
    /// The seed's class for that ratio.
    pub stiffness_class: String,
    /// The seed's motion advice for the class, against the drive.
    pub motion_advice: crate::select::MotionAdvice,
    /// Largest |transverse tip deflection| in the hub frame, m.
    pub max_tip_deflection_m: f64,
    /// That over the arm length.
    pub max_w_over_l: f64,
    /// Largest |drive torque|, N·m, and when.
    pub peak_drive_torque_n_m: f64,
    /// Time of the peak drive torque, s.
    pub peak_drive_torque_time_s: f64,
    /// The drive's peaks against the lift joint's URDF limits.
    pub drive: DriveLimits,
    /// The actuator's peaks and how well it tracked.
    pub actuator: ActuatorSummary,
    /// Residual vibration after the drive stops: the tip deflection's amplitude, and the frequency
    /// and decay of the signal that moves (the hub rate under an actuator).
    pub residual: Residual,
    /// Contact pairs.
    pub pairs: Vec<PairSummary>,
    /// The friction clamp's slip, if the string is held by one.
    pub string_slip: Option<SlipSummary>,
    /// The tilting head's swing (left out of the file without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub head: Option<HeadSummary>,
    /// The held string: its fidelity, frequencies in its hands and peak stress (left out of
    /// the file without a string).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub string: Option<crate::sensor::string::StringSummary>,
    /// ω_max·dt of the highest mode the model keeps (with an actuator: of the fastest pole of
    /// the arm and its drive held at rest at the end of the drive's path): an explicit integrator
    /// is stable only below its limit (2 for symplectic Euler, 2√2 for RK4; explicit Euler never).
    pub highest_omega_dt: f64,
    /// The integrator's stability limit on ω·dt (`None`: unconditionally stable; 0: none).
    pub stability_limit_omega_dt: Option<f64>,
    /// Each sensor's peaks (left out of the file when the scenario has none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorSummary>,
    /// `stress`, `fatigue` and `pins` (`docs/sign-off.md`; left out of a run without them).
    #[serde(flatten)]
    pub sign_off: Option<crate::stress::SignOff>,
}

/// A drive's peaks against the lift joint's URDF limits. The rate is known before the run and a
/// scenario faster than the joint's velocity is refused ([`crate::scenario`]); the torque is
/// known only after it, so a run beyond the joint's effort is flagged here, not stopped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DriveLimits {
    /// The drive's kind (`uniform`, `trapezoidal`, `s-curve`, `hold`, `spin-up`, `table`), as
    /// the scenario's `drive.kind` names it.
    pub kind: String,
    /// Its peak rate, deg/s.
    pub peak_rate_deg_s: f64,
    /// Its peak acceleration, deg/s².
    pub peak_accel_deg_s2: f64,
    /// The lift joint's velocity limit (URDF `limit@velocity`), deg/s.
    pub velocity_limit_deg_s: f64,
    /// The lift joint's effort (URDF `limit@effort`), N·m.
    pub effort_n_m: f64,
    /// Whether the run's peak drive torque is within that effort.
    pub torque_within_effort: bool,
    /// The input shaper convolved with the profile (`zv`, `zvd`, `ei`); absent when unshaped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shaper: Option<String>,
    /// The natural frequencies the shaper is tuned to, Hz, lowest first; absent when unshaped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shaper_hz: Option<Vec<f64>>,
    /// The damping ratio of each, as tuned; absent when unshaped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shaper_damping_ratio: Option<Vec<f64>>,
    /// Each mode's largest share of an output's residual vibration after the unshaped move
    /// (0..1), where the tuning found the modes (no `shaper_hz` given); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shaper_residual_share: Option<Vec<f64>>,
}

impl DriveLimits {
    /// `model`'s drive against its lift joint, with the run's peak drive torque (N·m).
    pub fn of(model: &Model, peak_drive_torque_n_m: f64) -> Self {
        let (motion, lift) = (&model.drive.motion, &model.robot.lift);
        let (modes, tuning) = (motion.shaper_modes(), &model.drive.shaper_tuning);
        let shaped = !modes.is_empty();
        DriveLimits {
            kind: motion.name().into(),
            peak_rate_deg_s: motion.peak_rate_rad_s().to_degrees(),
            peak_accel_deg_s2: motion.peak_accel_rad_s2().to_degrees(),
            velocity_limit_deg_s: lift.velocity_rad_s.to_degrees(),
            effort_n_m: lift.effort_n_m,
            torque_within_effort: peak_drive_torque_n_m <= lift.effort_n_m,
            shaper: motion.shaper().map(|s| s.name().into()),
            shaper_hz: shaped.then(|| modes.iter().map(|m| m.frequency_hz).collect()),
            shaper_damping_ratio: shaped.then(|| modes.iter().map(|m| m.damping_ratio).collect()),
            shaper_residual_share: (!tuning.is_empty()).then(|| tuning.iter().map(|m| m.residual_share).collect()),
        }
    }
}

/// Runs a model at `fidelity` (its own if `None`), capturing no frames.
pub fn run(model: &Model, fidelity: Option<Fidelity>) -> Result<(RunSummary, Series), SceneError> {
    run_with(model, &RunOptions { fidelity, ..RunOptions::default() })
}

/// Runs a model with `options`.
pub fn run_with(model: &Model, options: &RunOptions) -> Result<(RunSummary, Series), SceneError> {
    run_reusing(model, options, &Compiler::new())
}

/// Runs a model with `options`, taking what `compiler` kept from earlier runs that it shares
/// (the beam, its modes, the reduced arm) and keeping what it compiles for the next.
pub fn run_reusing(
    model: &Model,
    options: &RunOptions,
    compiler: &Compiler,
) -> Result<(RunSummary, Series), SceneError> {
    let (summary, series) = run_partial(model, options, compiler);
    Ok((summary?, series))
}

/// Runs a model with `options` and returns its series whether it finished or not: up to the
/// divergence for a run the guard stopped (empty if the scene could not be built). It takes
/// what `compiler` kept from earlier compiles that it shares.
pub fn run_partial(
    model: &Model,
    options: &RunOptions,
    compiler: &Compiler,
) -> (Result<RunSummary, SceneError>, Series) {
    match CompiledModel::new(model, options.fidelity, compiler) {
        Ok(compiled) => run_compiled(&compiled, options),
        Err(error) => (Err(error), Series::default()),
    }
}

/// Runs `compiled` with `options` (its fidelity is the compiled one's), as [`run_partial`] does.
pub fn run_compiled(compiled: &CompiledModel, options: &RunOptions) -> (Result<RunSummary, SceneError>, Series) {
    let mut series = Series::default();
    let summary = simulate(compiled, options, &mut series);
    // The sign-off's channels, declared once every step is read (where the peak fell); a run the
    // guard stopped may leave its last readings unevaluated, and then has none.
    if series.stress.steps() == series.t_s.len() {
        let sign_off = series.stress.channels();
        series.channels.extend(sign_off);
    }
    (summary, series)
}

/// The step loop: builds the scene, steps it to the model's end, fills `series` as it goes.
fn simulate(compiled: &CompiledModel, options: &RunOptions, series: &mut Series) -> Result<RunSummary, SceneError> {
    let model: &Model = &compiled.model;
    let crate::select::CompiledArm { string: string_choice, arm: choice, model: arm, .. } = &compiled.arm;
    let mut scene = Scene::with_arm(model, arm.clone())?;
    let built = AsBuilt::of(&scene);
    let h = model.time.step_s;
    let control = free_step_control(model);
    let end = model.duration_s();
    let steps = ((end / h) - 1e-9).ceil().max(0.0) as usize + 1;
    // Frames at the frame rate, and a quarter more for the steps in contact (all drawn).
    let frames = if options.capture_frames { (1.25 * end * options.frame_rate_hz) as usize + 1 } else { 0 };
    let pads = scene.pairs().count();
    *series = Series::with_capacity(steps, pads, compiled.modal_dofs(), frames, &model.sensors);
    series.channels = compiled.channels.clone();
    series.pair_names = compiled.pair_names.clone();
    let probes: Vec<SensorProbe> = model.sensors.iter().map(|s| SensorProbe::new(s, &scene.arm.arm)).collect();
    let mut stress = options.sign_off.then(|| StressProbe::for_run(model, &scene, steps, &mut series.stress));
    let mut trackers = vec![ImpactTracker::default(); pads];
    if options.capture_frames {
        series.layout = Some(scene.layout());
    }
    let mut keeper = Keeper::new(options, pads);
    let started = Instant::now();
    let first = scene.arm.sample();
    let mut guard = DivergenceGuard::new(&first, gravity_span_j(model, &scene));
    record(&scene, &first, series, &mut trackers);
    read_sensors(&scene, &probes, series);
    read_string(&scene, model.physics.gravity_m_s2, series);
    read_head(&scene, series);
    stress.iter_mut().for_each(|p| p.read(&scene, &first, model.physics.gravity_m_s2, &mut series.stress));
    keeper.keep(&scene, series, options.capture_frames, false);
    // The steps, in a closure so that the stress readings are completed whether they end or
    // the run diverges (a diverged run's series keeps its readings up to there).
    let mut step_to_end = || -> Result<usize, SceneError> {
        let mut steps = 0;
        // The last step is stretched or cut to land on `end`: a sliver left over by rounding would
        // be a step too short to take.
        let sliver = 1e-6 * h;
        // The free-motion step the error control proposes next (it restarts from `h` after contact).
        let mut free_h = h;
        while end - scene.arm.time_s() > sliver {
            let remaining = end - scene.arm.time_s();
            let last_within = |wanted: f64| if remaining <= wanted + sliver { remaining } else { wanted };
            steps += 1;
            match &control {
                Some(control) if scene.free_step_allowed(free_h) => {
                    let (_, next) =
                        scene.step_free(last_within(free_h), control).map_err(|e| diverged_step(model, &scene, e))?;
                    free_h = next;
                }
                _ => {
                    scene.step(last_within(h)).map_err(|e| diverged_step(model, &scene, e))?;
                    free_h = h;
                }
            }
            let sample = scene.arm.sample();
            guard.check(&sample).map_err(|d| divergence_error(model, &scene, d))?;
            if let Some(what) = scene.fault() {
                return Err(divergence_error(model, &scene, Divergence { t_s: sample.t_s, what }));
            }
            record(&scene, &sample, series, &mut trackers);
            read_sensors(&scene, &probes, series);
            read_string(&scene, model.physics.gravity_m_s2, series);
            read_head(&scene, series);
            stress.iter_mut().for_each(|p| p.read(&scene, &sample, model.physics.gravity_m_s2, &mut series.stress));
            keeper.keep(&scene, series, options.capture_frames, end - scene.arm.time_s() <= sliver);
        }
        Ok(steps)
    };
    let stepped = step_to_end();
    // The last stress readings go to their worker now and are collected after the run's own
    // summary, which does not read them.
    stress.iter_mut().for_each(|p| p.hand_over_rest(&mut series.stress));
    let summarized = stepped.and_then(|steps| {
        let wall_time_s = started.elapsed().as_secs_f64();
        let mut summary = summarize(compiled, &built, series, &trackers, steps, wall_time_s)?;
        (summary.model_reason, summary.model_expected_error) = (choice.reason.clone(), choice.expected.clone());
        if let Some(choice) = string_choice {
            if let Some(peaks) = scene.string.as_ref().filter(|_| series.string_peak_stress.is_empty()) {
                series.string_peak_stress = peaks.peaks_over(&series.modal_q, series.modal_dofs).unwrap_or_default();
            }
            let readings = crate::sensor::string::StringSeries {
                t_s: &series.t_s,
                tip_deflection_m: &series.string_tip_deflection_m,
                stress_pa: &series.string_stress_pa,
                peak_stress: &series.string_peak_stress,
            };
            summary.string = Some(crate::sensor::string::StringSummary::of(
                model,
                &compiled.string_frequencies_hz,
                choice.clone(),
                &readings,
            ));
        }
        Ok(summary)
    });
    stress.iter_mut().for_each(|p| p.finish(&mut series.stress));
    let mut summary = summarized?;
    summary.sign_off = stress.map(|_| crate::stress::sign_off_run(model, series));
    Ok(summary)
}

/// The error control of free-motion steps, if the model asks for longer free steps.
fn free_step_control(model: &Model) -> Option<StepControl> {
    let t = &model.time;
    t.free_step_s.filter(|&free| free > t.step_s).map(|free| StepControl {
        tolerance: t.tolerance_m.unwrap_or(DEFAULT_TOLERANCE_M),
        min_step_s: t.step_s,
        max_step_s: free,
    })
}

/// Decides which steps a recording keeps: every step in contact (and the one after), the
/// others at the record rate, so no peak is lost.
struct Keeper {
    period_s: f64,
    frame_period_s: f64,
    last_kept_s: f64,
    last_frame_s: f64,
    was_in_contact: bool,
    /// Each pad's force at the last kept step, and its largest so far, N.
    kept_force_n: Vec<f64>,
    peak_force_n: Vec<f64>,
}

/// A contact step is kept when a pad's force has moved by more than this fraction of its peak so
/// far since the last kept step: every step of an impact, the record rate while an arm rests on
/// its pad (a seated arm would otherwise be kept at every step for as long as it rests there).
const KEPT_FORCE_CHANGE: f64 = 0.005;

impl Keeper {
    fn new(options: &RunOptions, pads: usize) -> Self {
        Keeper {
            period_s: 1.0 / options.record_rate_hz,
            frame_period_s: 1.0 / options.frame_rate_hz,
            last_kept_s: f64::NEG_INFINITY,
            last_frame_s: f64::NEG_INFINITY,
            was_in_contact: false,
            kept_force_n: vec![0.0; pads],
            peak_force_n: vec![0.0; pads],
        }
    }

    fn keep(&mut self, scene: &Scene, series: &mut Series, capture: bool, last: bool) {
        let t = scene.arm.time_s();
        let mut in_contact = false;
        let mut changed = false;
        for ((pad, kept), peak) in scene.pairs().zip(&self.kept_force_n).zip(&mut self.peak_force_n) {
            in_contact |= pad.force_n > 0.0;
            *peak = peak.max(pad.force_n);
            changed |= (pad.force_n - kept).abs() > KEPT_FORCE_CHANGE * *peak;
        }
        let contact = changed || in_contact != self.was_in_contact || last;
        if in_contact && !self.was_in_contact {
            // The step before a contact begins, too: a plot of the kept steps then rises from
            // zero where the force does.
            series.keep.last_mut().into_iter().for_each(|kept| *kept = true);
        }
        let due = |since: f64, period: f64| t - since >= period * (1.0 - 1e-9);
        let keep = contact || due(self.last_kept_s, self.period_s);
        self.was_in_contact = in_contact;
        series.keep.push(keep);
        if keep {
            self.last_kept_s = t;
            self.kept_force_n.iter_mut().zip(scene.pairs()).for_each(|(kept, pad)| *kept = pad.force_n);
        }
        if capture && (contact || due(self.last_frame_s, self.frame_period_s)) {
            self.last_frame_s = t;
            series.frames.push(scene.frame());
        }
    }
}

/// Total mass × g × twice the reach (arm plus string): the most gravity could release, J.
fn gravity_span_j(model: &Model, scene: &Scene) -> f64 {
    let string_m = model.payload.string().map_or(0.0, |s| s.pipe.length_m);
    let arm = &scene.arm.arm;
    let mass_kg = arm.beam.total_mass_kg + model.payload.mass_kg();
    mass_kg * model.physics.gravity_m_s2.abs() * 2.0 * (arm.length_m() + string_m)
}

/// A step that failed because the state blew up or Newton could not follow it is a divergence.
fn diverged_step(model: &Model, scene: &Scene, error: SceneError) -> SceneError {
    use crate::integrate::IntegrateError;
    match error {
        SceneError::Arm(ArmError::Integrate(
            e @ (IntegrateError::NonFinite { .. } | IntegrateError::NoConvergence { .. }),
        )) => {
            let t_s = match e {
                IntegrateError::NonFinite { t } | IntegrateError::NoConvergence { t, .. } => t,
                _ => f64::NAN,
            };
            divergence_error(model, scene, Divergence { t_s, what: e.to_string() })
        }
        other => other,
    }
}

fn divergence_error(model: &Model, scene: &Scene, d: Divergence) -> SceneError {
    let h = model.time.step_s;
    let advice = scene.divergence_advice(h).unwrap_or_else(|| {
        let peak_force_n = scene.pairs().map(|p| p.force_n).fold(0.0, f64::max).max(1.0);
        let penalty = scene.penalty_limits_s(peak_force_n).into_iter().flatten().reduce(f64::min);
        stability_advice(&model.integrator, scene.arm.arm.highest_omega_rad_s, h, penalty)
    });
    SceneError::Diverged { t_s: d.t_s, what: d.what, advice }
}

fn record(scene: &Scene, s: &ArmSample, series: &mut Series, trackers: &mut [ImpactTracker]) {
    series.t_s.push(s.t_s);
    series.hub_angle_rad.push(s.hub.angle_rad);
    series.hub_rate_rad_s.push(s.hub.rate_rad_s);
    series.hub_accel_rad_s2.push(s.hub.accel_rad_s2);
    series.tip_deflection_m.push(s.tip_deflection_hub_m);
    series.tip_velocity_m_s.push(s.tip_velocity_hub_m_s);
    series.drive_torque_n_m.push(s.drive_torque_n_m);
    series.actuator.extend(s.actuator.clone());
    series.energies_j.push([s.energies.kinetic_j, s.energies.strain_j, s.energies.gravity_j]);
    if scene.arm.arm.fidelity != Fidelity::Fe {
        series.modal_dofs = s.q.len();
        series.modal_q.extend_from_slice(s.q.as_slice());
    }
    if let Some(grip) = scene.grip() {
        series.string_slip_m.push(grip.slip_m);
        series.jaw_sinking_m.push(grip.jaw_sinking_m);
    }
    for ((pad, forces), tracker) in scene.pairs().zip(&mut series.pad_force_n).zip(trackers) {
        forces.push(pad.force_n);
        tracker.push(s.t_s, pad.force_n);
    }
}
