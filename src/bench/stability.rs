//! The stability map: the largest stable step of each integrator on each arm model, found by
//! bisection and set beside the theory (Hairer & Wanner's stability intervals: explicit Euler
//! none, symplectic Euler and the central difference ω h < 2, RK4 ω h < 2.83, Newmark's average
//! acceleration and generalized-α unconditional); the pad contacts' penalty limit; the largest
//! step the friction clamp's coupling and the `rapier` method survive, and the heaviest pad body
//! the `rapier` method's coupling carries at the scene's step.
//!
//! An arm run is unstable when its vibration energy grows without a source: the arm, undamped,
//! is held still at the horizontal, started from its static sag with every mode moving, and
//! watched for 400 periods of its highest mode; it is unstable when the largest energy over the
//! second half exceeds twice that over the first half (a bounded oscillation repeats itself, a
//! growing one doubles), or a value stops being finite. A scene run is unstable when the
//! divergence guard stops it ([`crate::guard`]).

use nalgebra::DVector;

use super::Reference;
use crate::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, HubDrive};
use crate::beam::BeamModel;
use crate::contact::ForceLaw;
use crate::drive::MotionProfile;
use crate::integrate::IntegratorKind;
use crate::model::{Clamp, ContactMethod, Model};
use crate::robot::{PipeString, StringSpec};
use crate::run::{RunOptions, run_with};
use crate::scene::{Scene, SceneError};

/// Smallest ω·dt tried: below it a method that is still unstable is called unstable at any step.
pub const FLOOR_OMEGA_DT: f64 = 0.05;
/// Largest ω·dt tried (and a step of at most 1 s): a method stable there is called unconditional.
pub const CAP_OMEGA_DT: f64 = 1000.0;

/// What bisection found for one method on one model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Limit {
    /// Stable up to this step and unstable just above it, s.
    Step(f64),
    /// Stable even at the largest step tried, s.
    Unconditional(f64),
    /// Unstable even at the smallest step tried, s.
    Never(f64),
}

/// One integrator on one arm model.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmRow {
    /// The integrator.
    pub integrator: IntegratorKind,
    /// The model (`fe24` for FE with 24 elements).
    pub model: String,
    /// Its highest natural frequency, rad/s.
    pub omega_max_rad_s: f64,
    /// The theoretical limit on ω·dt (`None`: unconditional; 0: none).
    pub theory_omega_dt: Option<f64>,
    /// What bisection found.
    pub measured: Limit,
}

/// One pad's contact limit.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactRow {
    /// Pad name.
    pub pad: String,
    /// The arm's effective mass at the pad (the bench's auto model), kg.
    pub effective_mass_kg: f64,
    /// The law's tangent stiffness at the reference's peak force, N/m.
    pub stiffness_n_m: f64,
    /// 2√(m_eff/k), s.
    pub penalty_limit_s: f64,
}

/// The heaviest pad body the `rapier` method's coupling carries at the scene's step (it hands
/// the pad's inertia to the arm one step late: an added mass against the arm's effective mass).
#[derive(Debug, Clone, PartialEq)]
pub struct PadMassRow {
    /// The arm's effective mass at the lightest-loaded pad, kg.
    pub effective_mass_kg: f64,
    /// The largest pad mass (kg, in the `Limit`'s value) at which the scene runs to its end.
    pub heaviest_pad: Limit,
}

/// The largest stable step of a whole scene run, for one setting.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRow {
    /// What was run (`symplectic-euler, compliant`, `rapier`, `friction clamp, 121 kg`).
    pub what: String,
    /// What bisection found.
    pub measured: Limit,
    /// The predicted limit, if there is one, s.
    pub predicted_s: Option<f64>,
}

/// The whole map.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityMap {
    /// Integrator × arm model.
    pub arm: Vec<ArmRow>,
    /// Pads.
    pub contact: Vec<ContactRow>,
    /// Scene runs bisected: explicit integration of the pad contact, the `rapier` method.
    pub scene: Vec<SceneRow>,
    /// The `rapier` method's heaviest pad body (scenes with pads).
    pub pad_mass: Option<PadMassRow>,
    /// The friction clamp over steps, strings and models.
    pub clamp: Vec<ClampRun>,
}

/// The undamped arm of a scenario at `fidelity` (`elements` overrides the robot's mesh).
pub fn undamped_arm(model: &Model, fidelity: Fidelity) -> Result<ArmModel, SceneError> {
    let spec = model.beam_spec()?;
    let beam = BeamModel::new(spec)?;
    let options = ArmOptions { damping_ratios: vec![0.0], ..model.arm_options() };
    Ok(ArmModel::new(beam, fidelity, options)?.with_head(model.robot.head.as_ref())?)
}

/// Whether `integrator` at `step_s` keeps the undamped arm's vibration bounded (module doc).
pub fn arm_is_stable(arm: &ArmModel, integrator: IntegratorKind, step_s: f64) -> bool {
    let omega = arm.highest_omega_rad_s.max(1e-9);
    let steps = ((400.0 * std::f64::consts::TAU / (omega * step_s)).ceil() as usize).clamp(200, 60_000);
    let Ok(q0) = arm.static_deflection(0.0) else { return false };
    let qd0 = every_mode_moving(arm);
    let given_j = 0.5 * qd0.dot(&(&arm.mass * &qd0));
    let drive = HubDrive::Prescribed(MotionProfile::hold(0.0));
    let Ok(mut sim) = ArmSimulation::with_initial(arm.clone(), drive, integrator, q0, qd0) else { return false };
    // The energy of the arm at rest in its static sag: what the vibration is measured from.
    let rest = sim.sample().energies.total_j() - given_j;
    let (mut first_half, mut second_half) = (0.0_f64, 0.0_f64);
    for i in 0..steps {
        if sim.step(step_s).is_err() {
            return false;
        }
        let vibration = sim.sample().energies.total_j() - rest;
        if !vibration.is_finite() {
            return false;
        }
        if i < steps / 2 {
            first_half = first_half.max(vibration);
        } else {
            second_half = second_half.max(vibration);
        }
    }
    second_half <= 2.0 * first_half
}

/// A velocity with every mode of the arm moving (modal coordinates of unit amplitude).
fn every_mode_moving(arm: &ArmModel) -> DVector<f64> {
    match arm.fidelity {
        Fidelity::Fe => {
            let n = arm.elastic_dofs();
            // The arm's modes; a flexible string's own DOFs (beyond the arm's) start at rest.
            let moving = arm.beam.modes().map(|m| &m.shapes * DVector::repeat(m.shapes.ncols(), 1.0));
            moving.unwrap_or_default().resize_vertically(n, 0.0)
        }
        _ => DVector::repeat(arm.elastic_dofs(), 1.0),
    }
}

/// Bisects (in log step) for the largest step at which `stable` holds, between `lo` and `hi`, s.
pub fn bisect(lo: f64, hi: f64, iterations: usize, mut stable: impl FnMut(f64) -> bool) -> Limit {
    if stable(hi) {
        return Limit::Unconditional(hi);
    }
    if !stable(lo) {
        return Limit::Never(lo);
    }
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..iterations {
        if hi / lo < 1.0005 {
            break;
        }
        let mid = (lo * hi).sqrt();
        if stable(mid) { lo = mid } else { hi = mid }
    }
    Limit::Step(lo)
}

/// Largest stable step of `integrator` on `arm`.
pub fn arm_limit(arm: &ArmModel, integrator: IntegratorKind) -> Limit {
    let omega = arm.highest_omega_rad_s.max(1e-9);
    let (lo, hi) = (FLOOR_OMEGA_DT / omega, (CAP_OMEGA_DT / omega).min(1.0));
    bisect(lo, hi, 40, |h| arm_is_stable(arm, integrator, h))
}

/// Largest step at which a scene run finishes without the divergence guard stopping it.
pub fn scene_limit(
    model: &Model,
    fidelity: Fidelity,
    lo: f64,
    hi: f64,
    iterations: usize,
) -> Result<Limit, SceneError> {
    runs_within(model, fidelity, (lo, hi, iterations), |s, h| s.time.step_s = h)
}

/// Bisects (in log) for the largest value `set` may put into the model (between `lo` and `hi`)
/// at which the scene runs to its end without the divergence guard stopping it.
fn runs_within(
    model: &Model,
    fidelity: Fidelity,
    (lo, hi, iterations): (f64, f64, usize),
    set: impl Fn(&mut Model, f64),
) -> Result<Limit, SceneError> {
    let mut error = None;
    let limit = bisect(lo, hi, iterations, |value| {
        let mut s = model.clone();
        set(&mut s, value);
        match run_with(&s, &RunOptions { fidelity: Some(fidelity), ..RunOptions::default() }) {
            Ok(_) => true,
            Err(SceneError::Diverged { .. }) => false,
            Err(e) => {
                error.get_or_insert(e);
                false
            }
        }
    });
    error.map_or(Ok(limit), Err)
}

/// The stability map of a scene.
pub fn map(
    model: &Model,
    auto: Fidelity,
    reference: &Reference,
    linear: &[ForceLaw],
    quick: bool,
) -> Result<StabilityMap, SceneError> {
    let mut arm = Vec::new();
    let fidelities = if quick {
        vec![auto]
    } else {
        vec![Fidelity::Modal { modes: 1 }, auto, Fidelity::Modal { modes: 8 }, Fidelity::Fe]
    };
    let mut integrators = super::integrators().to_vec();
    integrators.insert(2, IntegratorKind::Newmark { beta: 1.0 / 6.0, gamma: 0.5 });
    for fidelity in dedup(fidelities) {
        let undamped = undamped_arm(model, fidelity)?;
        let name = match fidelity {
            Fidelity::Fe => format!("fe{}", model.robot.arm.elements),
            f => f.to_string(),
        };
        for &integrator in &integrators {
            arm.push(ArmRow {
                integrator,
                model: name.clone(),
                omega_max_rad_s: undamped.highest_omega_rad_s,
                theory_omega_dt: integrator.stability_limit_omega_dt(),
                measured: arm_limit(&undamped, integrator),
            });
        }
    }
    let scene = Scene::with_fidelity(model, auto)?;
    let masses = scene.pad_effective_masses_kg();
    let penalties = scene.penalty_limits_s(reference.peak_force_n);
    let contact: Vec<ContactRow> = model
        .dampeners
        .iter()
        .zip(masses.into_iter().zip(penalties))
        .filter_map(|(pad, (m, penalty))| {
            Some(ContactRow {
                pad: pad.name.clone(),
                effective_mass_kg: m?,
                stiffness_n_m: pad.law.tangent_stiffness_at_force(reference.peak_force_n),
                penalty_limit_s: penalty?,
            })
        })
        .collect();
    let h0 = model.time.step_s;
    let mut rows = Vec::new();
    if !contact.is_empty() {
        let mut explicit = model.clone();
        explicit.integrator = IntegratorKind::SymplecticEuler;
        let arm_limit_s = 2.0 / scene.arm.arm.highest_omega_rad_s.max(1e-9);
        let penalty = contact.iter().map(|c| c.penalty_limit_s).fold(f64::INFINITY, f64::min);
        let predicted = penalty.min(arm_limit_s);
        let (lo, hi) = (predicted / 4.0, (4.0 * h0).max(2.0 * predicted));
        rows.push(SceneRow {
            what: format!("symplectic-euler, compliant pads, {auto}"),
            measured: scene_limit(&explicit, auto, lo, hi, if quick { 4 } else { 8 })?,
            predicted_s: Some(predicted),
        });
    }
    let mut pad_mass = None;
    if !contact.is_empty() && model.structures.is_empty() {
        let mut rapier = model.clone();
        rapier.contact.method = ContactMethod::Rapier;
        for (pad, law) in rapier.dampeners.iter_mut().zip(linear) {
            pad.law = *law;
        }
        let iterations = if quick { 3 } else { 6 };
        rows.push(SceneRow {
            what: format!("rapier, {} kg pad, {auto}", rapier.contact.pad_mass_kg),
            measured: scene_limit(&rapier, auto, 0.25 * h0, 8.0 * h0, iterations)?,
            predicted_s: None,
        });
        let effective_mass_kg = contact.iter().map(|c| c.effective_mass_kg).fold(f64::INFINITY, f64::min);
        pad_mass = Some(PadMassRow { effective_mass_kg, heaviest_pad: heaviest_pad(&rapier, auto, iterations)? });
    }
    let clamp = clamp_sweep(model, auto, quick)?;
    Ok(StabilityMap { arm, contact, scene: rows, pad_mass, clamp })
}

/// The largest pad body mass (kg) at which the `rapier` scene runs to its end at its step.
fn heaviest_pad(model: &Model, fidelity: Fidelity, iterations: usize) -> Result<Limit, SceneError> {
    runs_within(model, fidelity, (1.0, 1e5, iterations), |s, mass| s.contact.pad_mass_kg = mass)
}

/// The friction clamp (the palm's jaws alone) with the 121 kg and 200 kg strings at the
/// fidelity `auto` gives each in that hand, over a range of steps, at the bench's auto model and
/// at eight modes, under generalized-α (so that a divergence is the clamp's coupling, not an
/// explicit scene integrator's limit on the arm): whether each run holds, and its slip.
fn clamp_sweep(model: &Model, auto: Fidelity, quick: bool) -> Result<Vec<ClampRun>, SceneError> {
    if model.payload.string().is_none() {
        return Ok(Vec::new());
    }
    let h0 = model.time.step_s;
    let factors: &[f64] = if quick { &[0.5, 1.0, 2.0] } else { &[0.125, 0.25, 0.5, 1.0, 2.0, 4.0] };
    let models = if quick { vec![auto] } else { dedup(vec![auto, Fidelity::Modal { modes: 8 }]) };
    let mut out = Vec::new();
    // Both sizes are in the compiled-in catalogue (robot::pipes' tests).
    let one_joint = |size: &str| PipeString::from_spec(&StringSpec::of_size(size)).ok();
    for pipe in ["2-7/8", "4-1/2"].into_iter().filter_map(one_joint) {
        let size = pipe.pipe.size.clone();
        let mut s = model.clone();
        s.integrator = IntegratorKind::default();
        if let Some(held) = s.payload.string_mut() {
            held.pipe = pipe;
            held.clamp = Clamp::Friction;
            // In the palm's jaws alone, at its middle: a friction clamp is one hand's.
            let palm = held.palm().clone();
            held.in_one_hand(&palm.hand, palm.station_m);
            held.model = None;
        }
        let string_kg = s.payload.mass_kg();
        let string = crate::select::string_fidelity(&s)?.fidelity;
        for &model in &models {
            for &f in factors {
                s.time.step_s = f * h0;
                let outcome = match run_with(&s, &RunOptions { fidelity: Some(model), ..RunOptions::default() }) {
                    Ok((summary, _)) => ClampOutcome::Held {
                        max_slip_m: summary.string_slip.map_or(0.0, |g| g.max_slip_m),
                        peak_force_n: super::peak_force_n(&summary),
                    },
                    Err(SceneError::Diverged { t_s, .. }) => ClampOutcome::Diverged { t_s },
                    Err(e) => return Err(e),
                };
                out.push(ClampRun { size: size.clone(), string_kg, string, model, step_s: f * h0, outcome });
            }
        }
    }
    Ok(out)
}

/// One run of the friction clamp sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct ClampRun {
    /// String size.
    pub size: String,
    /// Its mass, kg.
    pub string_kg: f64,
    /// Its fidelity (`auto`'s in the one hand).
    pub string: Fidelity,
    /// Arm model.
    pub model: Fidelity,
    /// Step, s.
    pub step_s: f64,
    /// What happened.
    pub outcome: ClampOutcome,
}

/// How a friction clamp run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClampOutcome {
    /// It ran to the end.
    Held {
        /// Largest slip, m.
        max_slip_m: f64,
        /// Peak contact force, N.
        peak_force_n: f64,
    },
    /// The guard stopped it.
    Diverged {
        /// When, s.
        t_s: f64,
    },
}

fn dedup(mut v: Vec<Fidelity>) -> Vec<Fidelity> {
    let mut seen = Vec::new();
    v.retain(|f| {
        let new = !seen.contains(f);
        seen.push(*f);
        new
    });
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_a_known_threshold() {
        let Limit::Step(h) = bisect(1e-3, 1.0, 60, |h| h <= 0.0123) else { panic!("no threshold") };
        assert!((h / 0.0123 - 1.0).abs() < 1e-3 && h <= 0.0123);
        assert_eq!(bisect(1e-3, 1.0, 60, |_| true), Limit::Unconditional(1.0));
        assert_eq!(bisect(1e-3, 1.0, 60, |_| false), Limit::Never(1e-3));
    }
}
