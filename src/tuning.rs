//! Input-shaper tuning: the modes a shaper on the model's drive must cancel, picked by their share
//! of the residual vibration the unshaped move leaves.
//!
//! The arm with its payload and drive is linearised at rest at the end of the drive's path
//! (gravity, stiffening and the actuator there included; up to 12 clamped modes, as
//! [`crate::select`] judges the coupled frequencies): `ẏ = A y + B r`, `r` the reference's
//! departure from rest at the end (angle, rate, acceleration; [`crate::arm::LinearSystem`]).
//! Started at rest where the move starts, each oscillating pole λ (Im λ > 0) of `A` is left ringing
//! when the move ends at `T` with, in an output `c`,
//!
//! `Y = R_θ I/λ + R_ω I + R_α λ I`,  `I(λ) = ∫₀ᵀ e^{λ(T−τ)} θ̇(τ) dτ`,
//!
//! `R_k` the residue of `c (sI − A)⁻¹ b_k` at λ (the mode's participation in the output times its
//! excitation by the reference's angle, rate and acceleration), so that the output rings as
//! `2 Re(Y e^{λ(t−T)})`, amplitude `2|Y|`. (In the mode's coordinate `ż = λz + β·r`; integrating
//! by parts with the reference at rest at 0 and at T, the start's offset cancels the angle's
//! integral but for `I/λ`, and the acceleration's is `λ I`.) `I` is the move's rate spectrum at
//! the pole; a shaper multiplies it by its residual vibration there
//! ([`crate::drive::residual_vibration`]).
//!
//! The outputs are the tip deflection (the summary's residual), each pad's station across the arm
//! (the pad force) and, under an actuator, the hub rate. A mode's share in an output is its
//! amplitude over the sum of every oscillating mode's (the largest the output's residual can
//! reach); the shaper is tuned to the modes of largest share until those left carry at most
//! [`LEFT_SHARE`] of every output's.

use std::borrow::Cow;

use nalgebra::{Complex, DMatrix, DVector};

use crate::arm::{ArmError, ArmModel, ArmSimulation, Fidelity, LinearSystem};
use crate::compile::Compiler;
use crate::drive::{DriveError, MotionProfile, ShaperMode};
use crate::model::{Model, TunedMode};

/// The share of every output's residual the modes left unshaped may carry together.
pub const LEFT_SHARE: f64 = 0.05;

/// Clamped modes of the linearised arm (as [`crate::select`]'s coupled-frequency reference).
const TUNING_MODES: usize = 12;

/// One oscillating pole and what the unshaped move leaves of it in each output.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalResidual {
    /// The pole, rad/s (Im > 0).
    pub pole: Complex<f64>,
    /// Per output, `Y`: the output rings as `2 Re(Y e^{λ(t−T)})` after the move (module doc).
    pub amplitudes: Vec<Complex<f64>>,
}

/// The modes an input shaper on `model`'s drive is tuned to by default (module doc), lowest
/// first; empty if the linearised arm has no oscillating mode. `model`'s drive is the unshaped
/// move.
///
/// The beam and the linearised arm are compiled through `compiler`, which keeps them for the
/// runs that share them.
///
/// # Errors
/// The arm or its drive cannot be built or linearised at the end of the path.
pub fn shaper_modes(model: &Model, compiler: &Compiler) -> Result<Vec<TunedMode>, ArmError> {
    let beam = compiler.beam(&model.beam_spec()?)?;
    let k = beam.modes().len().min(TUNING_MODES);
    let arm = compiler.arm(&beam, Fidelity::Modal { modes: k }, &model.arm_options(), model.robot.head.as_ref())?;
    let end_rad = model.drive.motion.end_rad();
    let sim = ArmSimulation::new(arm, model.hub_drive_held_at(end_rad), model.integrator)?;
    let system = sim.linearised()?;
    let outputs = output_rows(model, &sim.arm, &system);
    let residuals = modal_residuals(&system, &outputs, &model.drive.motion);
    Ok(pick(&residuals))
}

/// Why a model's shaper could not be tuned; each names the scenario key that settles it.
#[derive(Debug, thiserror::Error)]
pub enum TuningError {
    /// The arm cannot be built or linearised at the end of the drive's path.
    #[error("the arm's modes at the end of the path cannot be computed ({0}): set drive.shaper_hz")]
    Modes(ArmError),
    /// The linearised arm does not oscillate.
    #[error("the arm with its drive has no oscillating mode at the end of the path: set drive.shaper_hz")]
    NoOscillatingMode,
    /// The shaped move cannot be built in the drive's duration.
    #[error("{0}{note}", note = .0.in_degrees_note())]
    Drive(DriveError),
}

impl TuningError {
    /// The scenario key that settles it.
    pub fn key(&self) -> String {
        match self {
            TuningError::Modes(_) | TuningError::NoOscillatingMode => "drive.shaper".into(),
            TuningError::Drive(error) => error.scenario_key(),
        }
    }
}

/// `model` with the shaper its drive asks to tune ([`crate::model::Drive::untuned_shaper`])
/// tuned to the modes [`shaper_modes`] finds and its motion shaped within the same duration;
/// `model` itself if it asks for none.
///
/// # Errors
/// [`TuningError`].
pub fn tuned<'a>(model: &'a Model, compiler: &Compiler) -> Result<Cow<'a, Model>, TuningError> {
    let Some(shaper) = model.drive.untuned_shaper else { return Ok(Cow::Borrowed(model)) };
    let found = shaper_modes(model, compiler).map_err(TuningError::Modes)?;
    if found.is_empty() {
        return Err(TuningError::NoOscillatingMode);
    }
    let modes: Vec<ShaperMode> =
        found.iter().map(|m| ShaperMode { frequency_hz: m.frequency_hz, damping_ratio: m.damping_ratio }).collect();
    let mut tuned = model.clone();
    tuned.drive.motion = model.drive.motion.shaped_within(shaper, &modes).map_err(TuningError::Drive)?;
    tuned.drive.shaper_tuning = found;
    tuned.drive.untuned_shaper = None;
    Ok(Cow::Owned(tuned))
}

/// Rows over the linear state: the tip deflection, each pad's station across the arm (with the
/// hub's turn under a free hub), and the hub rate under one.
fn output_rows(model: &Model, arm: &ArmModel, system: &LinearSystem) -> Vec<DVector<f64>> {
    let n = system.a.nrows();
    let elastic = |row: &DVector<f64>, hub_lever_m: f64| {
        let mut out = DVector::zeros(n);
        out.rows_mut(system.elastic_offset, row.len()).copy_from(row);
        if let Some((angle, _)) = system.hub {
            out[angle] = hub_lever_m;
        }
        out
    };
    let mut rows = vec![elastic(&arm.tip_rows()[1], 0.0)];
    for pad in &model.dampeners {
        rows.push(elastic(&arm.station_rows(pad.station_m).0[1], pad.station_m));
    }
    if let Some((_, rate)) = system.hub {
        let mut hub_rate = DVector::zeros(n);
        hub_rate[rate] = 1.0;
        rows.push(hub_rate);
    }
    rows
}

/// The shaped modes: the largest shares, until those left carry at most [`LEFT_SHARE`] of every
/// output's residual; lowest frequency first.
fn pick(residuals: &[ModalResidual]) -> Vec<TunedMode> {
    let outputs = residuals.first().map_or(0, |r| r.amplitudes.len());
    let totals: Vec<f64> = (0..outputs).map(|o| residuals.iter().map(|r| r.amplitudes[o].norm()).sum()).collect();
    // Outputs the move leaves (to rounding) still carry no share (a rigid arm's tip).
    let largest_total = totals.iter().copied().fold(0.0, f64::max);
    let shares: Vec<Vec<f64>> = residuals
        .iter()
        .map(|r| {
            (0..outputs)
                .map(|o| if totals[o] > 1e-9 * largest_total { r.amplitudes[o].norm() / totals[o] } else { 0.0 })
                .collect()
        })
        .collect();
    let share_of = |i: usize| shares[i].iter().copied().fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..residuals.len()).collect();
    order.sort_by(|&i, &j| share_of(j).total_cmp(&share_of(i)));
    let left = |picked: usize| {
        (0..outputs).map(|o| order[picked..].iter().map(|&i| shares[i][o]).sum::<f64>()).fold(0.0, f64::max)
    };
    let count = (0..=order.len()).find(|&picked| left(picked) <= LEFT_SHARE).unwrap_or(order.len());
    let mut modes: Vec<TunedMode> = order[..count]
        .iter()
        .map(|&i| {
            let pole = residuals[i].pole;
            TunedMode {
                frequency_hz: pole.norm() / std::f64::consts::TAU,
                damping_ratio: -pole.re / pole.norm(),
                residual_share: share_of(i),
            }
        })
        .collect();
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    modes
}

/// Every oscillating pole of `system` (Im λ > 0, distinct) with what `motion`, run from rest to
/// rest, leaves of it in each of `outputs` (module doc).
pub fn modal_residuals(system: &LinearSystem, outputs: &[DVector<f64>], motion: &MotionProfile) -> Vec<ModalResidual> {
    let eigenvalues: Vec<Complex<f64>> = system.a.complex_eigenvalues().iter().copied().collect();
    oscillating(&eigenvalues)
        .into_iter()
        .map(|pole| {
            let residues = residues(system, outputs, pole, &eigenvalues);
            let rate_spectrum = rate_spectrum(motion, pole);
            let g = [1.0 / pole, Complex::new(1.0, 0.0), pole];
            let amplitudes = (0..outputs.len())
                .map(|o| (0..3).map(|k| residues[(o, k)] * g[k]).sum::<Complex<f64>>() * rate_spectrum)
                .collect();
            ModalResidual { pole, amplitudes }
        })
        .collect()
}

/// The eigenvalues with Im λ > 0, those within 1e-6 |λ| of another taken once.
fn oscillating(eigenvalues: &[Complex<f64>]) -> Vec<Complex<f64>> {
    let mut poles: Vec<Complex<f64>> = eigenvalues.iter().copied().filter(|p| p.im > 0.0).collect();
    poles.sort_by(|x, y| x.im.total_cmp(&y.im));
    let mut distinct: Vec<Complex<f64>> = Vec::with_capacity(poles.len());
    for p in poles {
        if !distinct.iter().any(|q| (q - p).norm() <= 1e-6 * p.norm()) {
            distinct.push(p);
        }
    }
    distinct
}

/// Points on the contour around a pole.
const CONTOUR_POINTS: usize = 8;

/// The residues at `pole` of `c (sI − A)⁻¹ b_k` for every output row `c` and input column `b_k`
/// (outputs × 3): `(1/2πi) ∮ G(s) ds` on a circle about the pole clear of every other
/// eigenvalue, by the trapezoidal rule (exact to `(ρ/d)^N` for a circle of radius ρ, d the
/// nearest other eigenvalue; a repeated pole's residues summed).
fn residues(
    system: &LinearSystem,
    outputs: &[DVector<f64>],
    pole: Complex<f64>,
    eigenvalues: &[Complex<f64>],
) -> DMatrix<Complex<f64>> {
    let n = system.a.nrows();
    let nearest =
        eigenvalues.iter().map(|q| (q - pole).norm()).filter(|d| *d > 1e-6 * pole.norm()).fold(f64::INFINITY, f64::min);
    let radius = (0.05 * nearest).min(1e-3 * pole.norm());
    let a = system.a.map(|x| Complex::new(x, 0.0));
    let b = system.b.map(|x| Complex::new(x, 0.0));
    let c = DMatrix::from_fn(outputs.len(), n, |o, j| Complex::new(outputs[o][j], 0.0));
    let mut sum = DMatrix::zeros(outputs.len(), system.b.ncols());
    for k in 0..CONTOUR_POINTS {
        let phase = Complex::from_polar(1.0, std::f64::consts::TAU * k as f64 / CONTOUR_POINTS as f64);
        let s = pole + phase * radius;
        let shifted = DMatrix::from_diagonal_element(n, n, s) - &a;
        let Some(x) = shifted.lu().solve(&b) else { continue };
        sum += (&c * x) * (phase * radius);
    }
    sum / Complex::new(CONTOUR_POINTS as f64, 0.0)
}

/// `I(λ) = ∫₀ᵀ e^{λ(T−τ)} θ̇(τ) dτ` over the move's duration T, in closed form for a move of
/// constant-jerk pieces between its breakpoints (every kind but the spin-up): on a piece where
/// θ̇ is a quadratic p, `∫ e^{λ(T−τ)} p dτ = [−e^{λ(T−τ)} (p + p′/λ + p″/λ²)/λ]` between its ends.
pub fn rate_spectrum(motion: &MotionProfile, pole: Complex<f64>) -> Complex<f64> {
    let duration = motion.duration_s();
    let mut points: Vec<f64> = std::iter::once(0.0).chain(motion.breakpoints_s()).filter(|t| *t <= duration).collect();
    points.push(duration);
    points.sort_by(f64::total_cmp);
    points.dedup_by(|later, earlier| *later - *earlier <= 1e-12 * duration);
    let primitive = |tau: f64, rate: f64, accel: f64, jerk: f64| {
        -(pole * (duration - tau)).exp() * (rate + accel / pole + jerk / (pole * pole)) / pole
    };
    points
        .windows(2)
        .map(|piece| {
            // The piece's cubic, taken at its midpoint (clear of either breakpoint's rounding) and
            // carried to its ends.
            let (t0, t1) = (piece[0], piece[1]);
            let mid = motion.sample(0.5 * (t0 + t1));
            let (accel, jerk) = (mid.accel_rad_s2, mid.jerk_rad_s3);
            let at = |dt: f64| (mid.rate_rad_s + dt * (accel + 0.5 * dt * jerk), accel + dt * jerk);
            let ((rate0, accel0), (rate1, accel1)) = (at(-0.5 * (t1 - t0)), at(0.5 * (t1 - t0)));
            primitive(t1, rate1, accel1, jerk) - primitive(t0, rate0, accel0, jerk)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use nalgebra::{Complex, DMatrix, DVector};

    use super::{LinearSystem, modal_residuals, rate_spectrum};
    use crate::drive::{MotionProfile, TrapezoidLimit};

    /// Two masses in a chain on springs from a base that follows θ (a prescribed reference),
    /// lightly damped: ẏ = A y + B r with r = (θ, θ̇, θ̈), y = (x₁, x₂, ẋ₁, ẋ₂) absolute.
    fn chain() -> LinearSystem {
        let (m1, m2, k1, k2, c1) = (2.0, 1.0, 400.0, 150.0, 0.8);
        let mut a = DMatrix::zeros(4, 4);
        a[(0, 2)] = 1.0;
        a[(1, 3)] = 1.0;
        // m1 ẍ1 = −k1 (x1 − θ) − k2 (x1 − x2) − c1 (ẋ1 − θ̇); m2 ẍ2 = −k2 (x2 − x1).
        a[(2, 0)] = -(k1 + k2) / m1;
        a[(2, 1)] = k2 / m1;
        a[(2, 2)] = -c1 / m1;
        a[(3, 0)] = k2 / m2;
        a[(3, 1)] = -k2 / m2;
        let mut b = DMatrix::zeros(4, 3);
        b[(2, 0)] = k1 / m1;
        b[(2, 1)] = c1 / m1;
        LinearSystem { a, b, hub: None, elastic_offset: 0 }
    }

    /// The state at the move's end, integrated exactly: on each piece the reference is a cubic in
    /// time, so [y, θ, θ̇, θ̈, θ⃛] evolves by one matrix exponential of the augmented system.
    fn exact_state_at_end(system: &LinearSystem, motion: &MotionProfile) -> DVector<f64> {
        let mut bounds = vec![0.0];
        bounds.extend(motion.breakpoints_s());
        let start = motion.sample(0.0).angle_rad;
        // At rest in equilibrium at the start: x = θ(0) for both masses.
        let mut y = DVector::from_vec(vec![start, start, 0.0, 0.0]);
        for piece in bounds.windows(2) {
            // The piece's cubic from its midpoint, carried back to its start (right limit there).
            let (mid, back) = (motion.sample(0.5 * (piece[0] + piece[1])), -0.5 * (piece[1] - piece[0]));
            let j = mid.jerk_rad_s3;
            let s = crate::drive::DriveState {
                angle_rad: mid.angle_rad + back * (mid.rate_rad_s + back * (0.5 * mid.accel_rad_s2 + back * j / 6.0)),
                rate_rad_s: mid.rate_rad_s + back * (mid.accel_rad_s2 + 0.5 * back * j),
                accel_rad_s2: mid.accel_rad_s2 + back * j,
                jerk_rad_s3: j,
            };
            let mut aug = DMatrix::zeros(8, 8);
            aug.view_mut((0, 0), (4, 4)).copy_from(&system.a);
            aug.view_mut((0, 4), (4, 3)).copy_from(&system.b);
            aug[(4, 5)] = 1.0;
            aug[(5, 6)] = 1.0;
            aug[(6, 7)] = 1.0;
            let z = DVector::from_iterator(
                8,
                y.iter().copied().chain([s.angle_rad, s.rate_rad_s, s.accel_rad_s2, s.jerk_rad_s3]),
            );
            y = ((aug * (piece[1] - piece[0])).exp() * z).rows(0, 4).into_owned();
        }
        y
    }

    /// The predicted free vibration after a trapezoidal and an s-curve move matches the exact
    /// response of the chain (relative to its end equilibrium, x = θ(T)) in displacement and
    /// velocity.
    #[test]
    fn predicted_residual_is_the_exact_free_vibration() {
        let system = chain();
        let limit = crate::drive::SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.25 };
        for motion in [
            MotionProfile::trapezoidal(0.0, 1.0, 1.3, TrapezoidLimit::RampFraction(0.3)).unwrap(),
            MotionProfile::s_curve(1.0, -0.5, 1.7, limit).unwrap(),
        ] {
            let end = motion.end_rad();
            let y_end = exact_state_at_end(&system, &motion);
            let rows: Vec<DVector<f64>> =
                (0..4).map(|j| DVector::from_fn(4, |i, _| f64::from(u8::from(i == j)))).collect();
            let residuals = modal_residuals(&system, &rows, &motion);
            assert_eq!(residuals.len(), 2);
            let departure = [y_end[0] - end, y_end[1] - end, y_end[2], y_end[3]];
            let scale = departure.iter().map(|d| d.abs()).fold(0.0, f64::max);
            assert!(scale > 1e-3, "{} leaves the chain ringing: {departure:?}", motion.name());
            for (j, want) in departure.iter().enumerate() {
                let got: f64 = residuals.iter().map(|r| 2.0 * r.amplitudes[j].re).sum();
                assert!((got - want).abs() <= 1e-7 * scale, "{} component {j}: {got} vs {want}", motion.name());
            }
        }
    }

    /// I(λ) of a uniform move (constant rate ω₀ over T): ω₀ (e^{λT} − 1)/λ; of a trapezoid and an
    /// s-curve, against composite Simpson on 200 000 intervals.
    #[test]
    fn rate_spectrum_in_closed_form() {
        let motion = MotionProfile::uniform(0.0, 2.0, 3.0).unwrap();
        let pole = Complex::new(-0.3, 7.0);
        let want = (2.0 / 3.0) * ((pole * 3.0).exp() - 1.0) / pole;
        let got = rate_spectrum(&motion, pole);
        assert!((got - want).norm() <= 1e-12 * want.norm(), "{got} vs {want}");
        let limit = crate::drive::SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.25 };
        for motion in [
            MotionProfile::trapezoidal(0.0, 1.5, 4.0, TrapezoidLimit::RampFraction(0.2)).unwrap(),
            MotionProfile::s_curve(1.5, 0.2, 4.0, limit).unwrap(),
        ] {
            let (n, t) = (200_000, motion.duration_s());
            let h = t / f64::from(n);
            let f = |k: u32| (pole * (t - h * f64::from(k))).exp() * motion.sample(h * f64::from(k)).rate_rad_s;
            let simpson: Complex<f64> = (0..=n)
                .map(|k| {
                    f(k) * if k == 0 || k == n {
                        1.0
                    } else if k % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    }
                })
                .sum();
            let want = simpson * (h / 3.0);
            let got = rate_spectrum(&motion, pole);
            assert!((got - want).norm() <= 1e-9 * want.norm(), "{}: {got} vs {want}", motion.name());
        }
    }
}
