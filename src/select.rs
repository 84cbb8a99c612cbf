//! The model a scene needs (`model = { kind = "auto" }`, the default) and the seed's motion advice
//! (§4) for the arm's class. (A shaped drive's modes: [`crate::tuning`].)
//!
//! The cheapest fidelity that resolves what the scene excites within the model's error budget
//! (`[model] tolerance`):
//! - never **rigid**: a rigid arm has no tip deflection, a headline quantity;
//! - **modal(n)** from a floor, the number of clamped modes below the highest frequency the scene
//!   excites, at least 1:
//!   - a pad the arm strikes: an impact of duration t_c ≈ π √(m_eff / k) (m_eff the arm's
//!     first-mode mass at the pad's station) loads modes up to 2.5 / t_c, where the half-sine
//!     pulse's spectrum has fallen below a tenth of its peak;
//!   - a pad the arm rests on under its own weight (its static deflection at the stop closes the
//!     gap) is a support, not an impact, and adds nothing;
//!   - an S-curve drive with jerk time t_j excites up to 1 / t_j; uniform and trapezoidal drives
//!     jump in acceleration and their quasi-static load is carried by the modes already kept;
//!   - under a servo or hydraulic drive the arm's frequencies are not its clamped ones: the
//!     count is the fewest clamped modes with which the arm and its drive, linearised at rest at
//!     the end of the path, reproduce within 2 % every coupled frequency in that band of a
//!     12-mode model (a cylinder props the arm at its pin; with the flexibility the truncated
//!     modes leave there added back as a spring in series with the oil column, three modes do
//!     on the shipped arm, as under a servo: docs/drives.md).
//!
//!   then as many more modes as the budget needs: measured on the arm's linear equations run
//!   through the drive ([`linear_run`]) where the hub follows its drive and nothing strikes the
//!   arm, else the modal truncation bound ([`TruncationBound`]);
//! - **fe** never by default: it is the reference.
//!
//! `tests/auto_model.rs` holds the choice within its budget of fe on every shipped scenario.

use std::sync::Arc;

use nalgebra::Complex;
use serde::Serialize;

use crate::analysis::StiffnessClass;
use crate::arm::{ArmError, ArmModel, ArmSimulation, Fidelity};
use crate::beam::{BeamError, BeamModel, ModalBasis};
use crate::compile::{CompiledBeam, Compiler};
use crate::drive::MotionLaw;
use crate::model::{Dampener, Model};

mod budget;
pub mod linear_run;
pub use crate::choice::{Choice, ExpectedError};
pub use budget::TruncationBound;

impl Model {
    /// The beam description of the arm: the robot's links plus the payload, a held string at
    /// the fidelity [`Self::string_fidelity`] gives.
    pub fn beam_spec(&self) -> Result<crate::beam::BeamSpec, BeamError> {
        let string = match self.payload.string() {
            Some(_) => Some(self.string_fidelity()?.fidelity),
            None => None,
        };
        self.beam_spec_with_string(string)
    }

    /// The held string's fidelity: the scenario's, or the one `auto` chooses, with the reason
    /// ([`string_fidelity`]). Rigid without a string.
    pub fn string_fidelity(&self) -> Result<Choice, BeamError> {
        string_fidelity(self)
    }
}

/// The fidelity to run a model at: its own, or the one `auto` chooses, with the reason.
pub fn fidelity(model: &Model) -> Result<Choice, BeamError> {
    match model.fidelity {
        Some(fidelity) => Ok(Choice::set(fidelity, "set in the scenario")),
        None => {
            let beam = BeamModel::new(model.beam_spec()?)?;
            let modes = beam.modes()?;
            choose(model, &beam, &modes)
        }
    }
}

/// [`fidelity`] on the beam and clamped modes a run compiled, `auto`'s choice taken from
/// `compiler` where a run with the same keys made it ([`Compiler::choice`]).
fn fidelity_on(model: &Model, compiled: &CompiledBeam, compiler: &Compiler) -> Result<Choice, BeamError> {
    match model.fidelity {
        Some(fidelity) => Ok(Choice::set(fidelity, "set in the scenario")),
        None => compiler.choice(model, compiled, || choose(model, compiled.beam(), compiled.modes())),
    }
}

/// Picks the cheapest fidelity the model needs, given its beam and clamped modes: the modes the
/// scene's band (and an actuator's coupled frequencies) need as a floor, then as many more as
/// the model's tolerance needs: on a linear run through the drive ([`linear_run`]) where it
/// applies, else by the modal truncation's bound ([`TruncationBound`]).
/// Never rigid: a rigid arm has no tip deflection, a headline quantity.
pub fn choose(model: &Model, beam: &BeamModel, modes: &ModalBasis) -> Result<Choice, BeamError> {
    // The class of the arm as built (its sag under standard gravity), as the summary states it,
    // whatever gravity the scene sets: a spin-up without gravity is not a rigid arm.
    let w_over_l = beam.gravity_tip_deflection_m(crate::arm::STANDARD_GRAVITY_M_S2)? / beam.length_m();
    let Band { band_hz, modes: mut n, mut reasons } = excited_band(model, beam, modes)?;
    if let Some((k, coupled_hz)) = coupled_modes(model, beam, modes, band_hz).filter(|_| band_hz > 0.0) {
        let listed: Vec<String> = coupled_hz.iter().map(|f| format!("{f:.1}")).collect();
        reasons.push(format!(
            "with its {} drive the arm's coupled frequencies up to {band_hz:.0} Hz are [{}] Hz: {k} clamped \
             mode(s) reproduce them within 2 %",
            model.drive.actuator.kind(),
            listed.join(", ")
        ));
        n = k;
    }
    if n == 0 {
        reasons.push(format!(
            "the arm's own deflection needs its first mode (static w/l 1/{:.0}: {})",
            1.0 / w_over_l,
            StiffnessClass::of_ratio(w_over_l).describe()
        ));
    }
    let floor = n.max(1);
    let (chosen, expected) = if linear_run::applies(model) {
        by_linear_run(model, beam, modes, floor, &mut reasons)
    } else {
        by_bound(model, beam, modes, floor, &mut reasons)?
    };
    Ok(Choice { fidelity: Fidelity::Modal { modes: chosen }, reason: reasons.join("; "), expected: Some(expected) })
}

/// The modes from `floor` the budget needs, measured on a linear run through the drive
/// ([`linear_run`]): the count, its expected error and what that is on; the reason in `reasons`.
fn by_linear_run(
    model: &Model,
    beam: &BeamModel,
    modes: &ModalBasis,
    floor: usize,
    reasons: &mut Vec<String>,
) -> (usize, ExpectedError) {
    let run = linear_run::LinearRun::new(model, beam, modes);
    let (chosen, judged) = linear_run::modes_within(&run, floor, model.tolerance);
    let errors: Vec<f64> = judged.iter().map(|j| j.peak).collect();
    let fraction = errors.last().copied().unwrap_or(0.0);
    let more = linear_run::JUDGED_BEYOND;
    let verdict = against_budget(fraction, model.tolerance, "the most modes a linear run can judge");
    reasons.push(if chosen == floor {
        format!(
            "at that floor its peak tip deflection, run linearly through the drive, is {} from that with \
             {more} modes more, {verdict}",
            percent(fraction)
        )
    } else {
        format!(
            "{chosen} mode(s) bring its peak tip deflection, run linearly through the drive, from {} to {} \
             from that with {more} modes more, {verdict}",
            percent(errors[0]),
            percent(fraction)
        )
    });
    let basis = format!("peak tip deflection: against {more} modes more, run linearly through the drive");
    let residual_fraction = judged.last().and_then(|j| j.residual);
    (chosen, ExpectedError { fraction, basis, floor_modes: floor, residual_fraction })
}

/// The modes from `floor` the budget needs by the modal truncation bound ([`TruncationBound`]):
/// the count, its expected error and what that is on; the reason in `reasons`.
fn by_bound(
    model: &Model,
    beam: &BeamModel,
    modes: &ModalBasis,
    floor: usize,
    reasons: &mut Vec<String>,
) -> Result<(usize, ExpectedError), BeamError> {
    let bound = TruncationBound::new(model, beam, modes)?;
    let chosen = bound.modes_within(floor, modes.len(), model.tolerance);
    let (fraction, quantity) = bound.error(chosen);
    let verdict = against_budget(fraction, model.tolerance, "every clamped mode the beam has");
    reasons.push(if chosen == floor {
        format!("at that floor the truncation bound is {} ({quantity}), {verdict}", percent(fraction))
    } else {
        format!(
            "{chosen} mode(s) bring the truncation bound from {} to {} ({quantity}), {verdict}",
            percent(bound.error(floor).0),
            percent(fraction)
        )
    });
    let basis = format!("{quantity}: the modes left out, answering quasi-statically (modal truncation bound)");
    Ok((chosen, ExpectedError { fraction, basis, floor_modes: floor, residual_fraction: None }))
}

/// How an expected error `fraction` stands against the budget `tolerance`: "within" it, or, where
/// the search stopped at its last count (`last`) above it, "beyond" it, so that no reason claims
/// a budget the choice does not meet.
fn against_budget(fraction: f64, tolerance: f64, last: &str) -> String {
    let budget = percent(tolerance);
    if fraction <= tolerance { format!("within {budget}") } else { format!("beyond {budget}: not met with {last}") }
}

/// A relative error as a percentage: two decimals, or two significant digits below 0.01 % (a
/// budget of 1e-5 is not "0.00 %").
pub fn percent(fraction: f64) -> String {
    let p = 100.0 * fraction;
    if p == 0.0 || p.abs() >= 0.01 { format!("{p:.2} %") } else { format!("{p:.1e} %") }
}

/// What a scene excites: the highest frequency (Hz), the clamped modes below it, and why.
struct Band {
    band_hz: f64,
    modes: usize,
    reasons: Vec<String>,
}

/// The band the scene's impacts and drive excite, and the arm's clamped modes in it.
fn excited_band(model: &Model, beam: &BeamModel, modes: &ModalBasis) -> Result<Band, BeamError> {
    let frequencies = modes.frequencies_hz();
    let below = |f_max: f64| frequencies.iter().take_while(|f| **f <= f_max).filter(|f| **f > 0.0).count();
    let mut reasons = Vec::new();
    let mut n = 0;
    // The highest frequency the scene excites, Hz.
    let mut band_hz: f64 = 0.0;
    for pad in &model.dampeners {
        let station_shape = beam.point_rows(pad.station_m)[1].dot(&modes.shapes.column(0));
        let m_eff = 1.0 / station_shape.powi(2).max(1e-30);
        let (resting, stiffness) = pad_kind(model, beam, pad)?;
        if resting {
            reasons.push(format!("{} supports the arm under its weight (quasi-static)", pad.name));
            continue;
        }
        let t_c = std::f64::consts::PI * (m_eff / stiffness).sqrt();
        band_hz = band_hz.max(2.5 / t_c);
        let k = below(2.5 / t_c).max(1);
        reasons.push(format!(
            "impacts on {} last ≈ {:.0} ms and load modes up to {:.0} Hz: {k} mode(s)",
            pad.name,
            1e3 * t_c,
            2.5 / t_c
        ));
        n = n.max(k);
    }
    let motion = &model.drive.motion;
    if motion.law() == MotionLaw::SCurve {
        let t_j = motion.peak_accel_rad_s2() / motion.peak_jerk_rad_s3();
        let k = below(1.0 / t_j);
        band_hz = band_hz.max(1.0 / t_j);
        reasons.push(format!("the S-curve's jerk time {t_j:.2} s excites up to {:.2} Hz: {k} mode(s)", 1.0 / t_j));
        n = n.max(k);
    }
    Ok(Band { band_hz, modes: n, reasons })
}

/// A run's arm as compiled for it: the fidelities chosen and the arm reduced to its own.
pub struct CompiledArm {
    /// The held string's fidelity, with a string.
    pub string: Option<Choice>,
    /// The arm's fidelity.
    pub arm: Choice,
    /// The arm reduced to it.
    pub model: Arc<ArmModel>,
    /// The fastest motion it keeps, rad/s: its highest mode under a prescribed hub; under an
    /// actuator the fastest pole of the arm and its drive held at rest at the end of the drive's
    /// path, if faster (the clamped modes understate it once the hub is free).
    pub fastest_rad_s: f64,
}

/// Chooses the string's fidelity and the arm's (`fidelity` if given) and reduces the arm to it,
/// taking from `compiler` what it kept. The beam `auto` compiled to choose the string's fidelity
/// is the run's.
pub fn compile_arm(model: &Model, fidelity: Option<Fidelity>, compiler: &Compiler) -> Result<CompiledArm, ArmError> {
    let (string, compiled) = match model.payload.string() {
        Some(_) => {
            let (choice, compiled) = string_fidelity_and_beam(model, compiler)?;
            (Some(choice), compiled)
        }
        None => (None, None),
    };
    let compiled = match compiled {
        Some(compiled) => compiled,
        None => compiler.beam(&model.beam_spec_with_string(string.as_ref().map(|c| c.fidelity))?)?,
    };
    let arm = match fidelity {
        Some(fidelity) => Choice::set(fidelity, "set on the command line"),
        None => fidelity_on(model, &compiled, compiler)?,
    };
    let reduced = compiler.arm(&compiled, arm.fidelity, &model.arm_options(), model.robot.head.as_ref())?;
    let fastest_rad_s = fastest_rad_s(model, &reduced);
    Ok(CompiledArm { string, arm, model: reduced, fastest_rad_s })
}

/// [`CompiledArm::fastest_rad_s`] of `arm` in `model`.
fn fastest_rad_s(model: &Model, arm: &Arc<ArmModel>) -> f64 {
    let clamped = arm.highest_omega_rad_s;
    if model.drive.actuator == crate::actuator::Actuator::Ideal {
        return clamped;
    }
    poles_held_at_end(model, arm.clone())
        .map_or(clamped, |poles| poles.iter().map(|p| p.norm()).fold(clamped, f64::max))
}

/// The poles (rad/s) of `arm` with the model's drive, held at rest at the end of the drive's path
/// (where it meets its stops) and linearised there; `None` if it cannot be held or linearised.
fn poles_held_at_end(model: &Model, arm: Arc<ArmModel>) -> Option<Vec<Complex<f64>>> {
    let drive = model.hub_drive_held_at(model.drive.motion.end_rad());
    ArmSimulation::new(arm, drive, model.integrator).ok()?.linear_poles().ok()
}

/// A held string's bending modes count when they lie below this multiple of the arm's first
/// frequency, whatever the scene's band: a string mode that close to the arm's takes part in its
/// motion as a tuned mass does, and at 1 % damping a little of the drive's spectrum rings it
/// (`pipearm bench`'s `string` axis shows where a rigid string stays within 1 % of the converged
/// peak force; docs/fidelity.md).
pub const STRING_MODE_MARGIN: f64 = 5.0;

/// The held string's fidelity: the scenario's, or the cheapest the scene needs — `rigid` (lumped
/// at its centre) when every bending mode of the string held in its hands lies above both the
/// band the scene excites and [`STRING_MODE_MARGIN`] times the arm's first frequency, else
/// `modal(k)` with the k string modes below that (the band's own edge is conservative: an
/// impact on the arm reaches the string only through its hands). A friction-clamped string is
/// rigid. Rigid without a string.
pub fn string_fidelity(model: &Model) -> Result<Choice, BeamError> {
    Ok(string_fidelity_and_beam(model, &Compiler::new())?.0)
}

/// [`string_fidelity`], with the beam (and the arm's modes) `auto` compiled to choose, ready for
/// a run where it chose a flexible string (`None` where it did not compile one or chose rigid).
pub fn string_fidelity_and_beam(
    model: &Model,
    compiler: &Compiler,
) -> Result<(Choice, Option<CompiledBeam>), BeamError> {
    let choice = |fidelity, reason: &str| Ok((Choice::set(fidelity, reason), None));
    let Some(held) = model.payload.string() else { return choice(Fidelity::Rigid, "no string") };
    if let Some(fidelity) = held.model {
        return choice(fidelity, "set in the scenario");
    }
    let compiled = compiler.beam(&model.beam_spec_with_string(Some(Fidelity::Modal { modes: 1 }))?)?;
    let (beam, arm_modes) = (compiled.beam(), compiled.modes());
    let string_hz = beam.member_modes().map(|m| m.frequencies_hz()).unwrap_or_default();
    let arm_first_hz = arm_modes.frequencies_hz().first().copied().unwrap_or(0.0);
    let band_hz = excited_band(model, beam, arm_modes)?.band_hz;
    let limit_hz = band_hz.max(STRING_MODE_MARGIN * arm_first_hz);
    let k = string_hz.iter().take_while(|f| **f <= limit_hz).count();
    let first = string_hz.first().copied().unwrap_or(f64::INFINITY);
    let why = format!(
        "held in its hands the string's first mode is {first:.1} Hz against the arm's {arm_first_hz:.1} Hz and \
         the scene's band {band_hz:.0} Hz"
    );
    let expected = Some(ExpectedError {
        fraction: budget::string_truncation(beam, arm_first_hz, k),
        basis: "the arm's headline quantities: the string's mass in the modes left out, amplified at the arm's \
                first frequency (string truncation estimate)"
            .into(),
        floor_modes: 0,
        residual_fraction: None,
    });
    if k == 0 {
        return Ok((Choice { fidelity: Fidelity::Rigid, reason: format!("{why}: rigid"), expected }, None));
    }
    // The beam compiled for the choice is the run's, keeping k of the string's modes.
    let fidelity = Fidelity::Modal { modes: k };
    let reason = format!("{why}: {k} string mode(s) below {limit_hz:.0} Hz");
    Ok((Choice { fidelity, reason, expected }, Some(compiler.keeping_member_modes(&compiled, k))))
}

/// Clamped modes of the model against which an actuated arm's coupled frequencies are judged.
const COUPLED_REFERENCE_MODES: usize = 12;

/// The fewest clamped modes with which an arm and its actuator, linearised at rest at the end of
/// the drive's path (where it meets its stops), reproduce within 2 % every coupled frequency up
/// to `band_hz` of the same arm with [`COUPLED_REFERENCE_MODES`] modes; with those frequencies,
/// Hz. `None` under an ideal drive (the clamped frequencies are the arm's), or if the actuated
/// arm cannot be built (the scenario's checks say why).
fn coupled_modes(model: &Model, beam: &BeamModel, modes: &ModalBasis, band_hz: f64) -> Option<(usize, Vec<f64>)> {
    if model.drive.actuator == crate::actuator::Actuator::Ideal {
        return None;
    }
    let frequencies = |k: usize| -> Option<Vec<f64>> {
        Some(oscillating_poles_at_end(model, beam, modes, k)?.iter().map(|p| p.im / std::f64::consts::TAU).collect())
    };
    let cap = modes.len().min(COUPLED_REFERENCE_MODES);
    let reference: Vec<f64> = frequencies(cap)?.into_iter().filter(|f| *f <= band_hz).collect();
    // Each reference frequency matched, and as many in the band as the reference has (one model
    // frequency must not stand for two).
    let reproduces = |hz: &[f64]| {
        reference.iter().all(|r| hz.iter().any(|f| (f - r).abs() <= 0.02 * r))
            && hz.iter().filter(|f| **f <= 1.02 * band_hz).count() >= reference.len()
    };
    let k = (1..cap).find(|&k| frequencies(k).is_some_and(|hz| reproduces(&hz))).unwrap_or(cap);
    Some((k, reference))
}

/// The oscillating poles (Im λ > 0, lowest first, rad/s) of the arm at `Modal { modes: k }` with
/// its drive, linearised at rest at the end of the drive's path; `None` if that arm cannot be
/// built or linearised.
fn oscillating_poles_at_end(
    model: &Model,
    beam: &BeamModel,
    modes: &ModalBasis,
    k: usize,
) -> Option<Vec<Complex<f64>>> {
    let fidelity = Fidelity::Modal { modes: k };
    let arm = ArmModel::with_modes(beam.clone(), modes.clone(), fidelity, model.arm_options())
        .and_then(|arm| arm.with_head(model.robot.head.as_ref()))
        .ok()?;
    let poles = poles_held_at_end(model, Arc::new(arm))?;
    let mut oscillating: Vec<Complex<f64>> = poles.into_iter().filter(|p| p.im > 0.0).collect();
    oscillating.sort_by(|a, b| a.im.total_cmp(&b.im));
    Some(oscillating)
}

/// Whether the arm rests on a pad under gravity at the stop (its static deflection there closes
/// the gap), and the pad's stiffness for an impact estimate, N/m (a nonlinear law's secant at
/// 1 mm).
fn pad_kind(model: &Model, beam: &BeamModel, pad: &Dampener) -> Result<(bool, f64), BeamError> {
    let theta = pad.angle_rad;
    let g = model.physics.gravity_m_s2;
    let load = -g * (theta.sin() * &beam.axial_mass + theta.cos() * &beam.transverse_mass);
    let d = beam.static_displacement(&load)?;
    let v = beam.point_rows(pad.station_m)[1].dot(&d);
    let toward = pad.face.sign() * v;
    Ok((toward > pad.gap_m, pad.law.force_n(1e-3, 0.0, 1.0) / 1e-3))
}

/// The seed's §4 advice for an arm's class, and how the scenario's drive compares.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionAdvice {
    /// The advice, in the seed's words.
    pub advice: String,
    /// The drive's peak acceleration, deg/s².
    pub peak_accel_deg_s2: f64,
    /// The limit that applies to this drive's profile, deg/s².
    pub limit_deg_s2: f64,
    /// Whether the drive keeps to it (and to the recommended profile).
    pub within: bool,
}

/// The seed's recommended acceleration limits (§4) for `class`, against the model's drive.
pub fn motion_advice(model: &Model, class: StiffnessClass) -> MotionAdvice {
    let motion = &model.drive.motion;
    let s_curve = motion.law() == MotionLaw::SCurve;
    let peak = motion.peak_accel_rad_s2().to_degrees();
    let (advice, limit, profile_ok) = match class {
        StiffnessClass::Rigid => ("trapezoidal drive, acceleration at start and stop ≤ 7–8 °/s²", 7.0, true),
        StiffnessClass::RigidFlexible if s_curve => ("trapezoidal ≤ 5 °/s², or S-curve ≤ about 9 °/s²", 9.0, true),
        StiffnessClass::RigidFlexible => ("trapezoidal ≤ 5 °/s², or S-curve ≤ about 9 °/s²", 5.0, true),
        StiffnessClass::Flexible => ("S-curve, acceleration ≤ 7–8 °/s²", 7.0, s_curve),
        StiffnessClass::BeyondYield => ("beyond the seed's bands: stiffen the arm", 0.0, false),
    };
    let uniform = motion.law() == MotionLaw::Uniform;
    MotionAdvice {
        advice: advice.into(),
        peak_accel_deg_s2: peak,
        limit_deg_s2: limit,
        within: profile_ok && !uniform && peak <= limit,
    }
}
