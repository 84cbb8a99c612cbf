//! What to change when the actuated arm's closed loop has a growing mode: how each of the
//! controller's gains (and a hydraulic valve's leakage) moves the growth rate of the loop's
//! fastest-growing pole, by central differences of the linearised loop's poles, and the advice
//! that follows from them.
//!
//! A pole λ grows when Re λ > [`GROWTH_TOLERANCE`] · max(|λ|, 1 rad/s). The tolerance lets a
//! neutral pole pass — a sealed cylinder (no leakage) with the valve nearly closed rings
//! undamped, its real part rounding — and no more: over a 20 s run the fastest growth it passes
//! amplifies a mode at |λ| rad/s by e^{20 · 1e-6 |λ|}, a factor 1.0006 at the oil column's
//! 28 rad/s.

use nalgebra::Complex;

use crate::actuator::Actuator;
use crate::arm::{ArmModel, ArmSimulation, HubDrive};
use crate::model::Model;

/// The fraction of max(|λ|, 1 rad/s) by which Re λ must exceed 0 for a pole to grow.
pub(super) const GROWTH_TOLERANCE: f64 = 1e-6;

/// Whether a pole grows (module doc).
pub(super) fn grows(pole: Complex<f64>) -> bool {
    pole.re > GROWTH_TOLERANCE * pole.norm().max(1.0)
}

/// A setting of the actuator the advice may turn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Knob {
    Kp,
    Kd,
    Ki,
    VelocityFeedforward,
    Leakage,
}

impl Knob {
    const ALL: [Knob; 5] = [Knob::Kp, Knob::Kd, Knob::Ki, Knob::VelocityFeedforward, Knob::Leakage];

    /// Its key in the scenario.
    fn key(self) -> &'static str {
        match self {
            Knob::Kp => "actuator.controller.kp",
            Knob::Kd => "actuator.controller.kd",
            Knob::Ki => "actuator.controller.ki",
            Knob::VelocityFeedforward => "actuator.controller.velocity_feedforward",
            Knob::Leakage => "actuator.valve.leakage_m3_s_per_pa",
        }
    }

    /// Its name in the advice.
    fn name(self) -> &'static str {
        self.key().rsplit('.').next().unwrap_or_default()
    }

    /// Its value on `actuator`; `None` where the actuator has no such setting.
    fn value(self, actuator: &Actuator) -> Option<f64> {
        let gains = actuator.controller()?;
        match (self, actuator) {
            (Knob::Kp, _) => Some(gains.kp),
            (Knob::Kd, _) => Some(gains.kd),
            (Knob::Ki, _) => Some(gains.ki),
            (Knob::VelocityFeedforward, _) => Some(gains.velocity_feedforward),
            (Knob::Leakage, Actuator::Hydraulic(h)) => Some(h.circuit.valve.leakage_m3_s_per_pa),
            (Knob::Leakage, _) => None,
        }
    }

    /// `actuator` with this setting at `value`.
    fn set(self, actuator: &mut Actuator, value: f64) {
        let gains = match actuator {
            Actuator::Ideal => return,
            Actuator::Servo(s) => &mut s.controller,
            Actuator::Hydraulic(h) => {
                if self == Knob::Leakage {
                    h.circuit.valve.leakage_m3_s_per_pa = value;
                    return;
                }
                &mut h.controller
            }
        };
        match self {
            Knob::Kp => gains.kp = value,
            Knob::Kd => gains.kd = value,
            Knob::Ki => gains.ki = value,
            Knob::VelocityFeedforward => gains.velocity_feedforward = value,
            Knob::Leakage => {}
        }
    }

    /// The change the growth is differentiated over: a tenth of the setting, or for one at zero a
    /// tenth of what matches kp at the pole's |λ| (kd = kp/|λ|, ki = kp |λ|), a tenth of full
    /// feed-forward, a tenth of the shipped valve's 1e-11 m³/s/Pa.
    fn step(self, value: f64, kp: f64, pole_rad_s: f64) -> f64 {
        if value > 0.0 {
            return 0.1 * value;
        }
        match self {
            Knob::Kp => 1e-3,
            Knob::Kd => 0.1 * kp.max(1e-3) / pole_rad_s,
            Knob::Ki => 0.1 * kp.max(1e-3) * pole_rad_s,
            Knob::VelocityFeedforward => 0.1,
            Knob::Leakage => 1e-12,
        }
    }
}

/// How one setting moves the growth rate.
#[derive(Debug, Clone, Copy)]
struct Effect {
    knob: Knob,
    value: f64,
    step: f64,
    /// The growth rate's change (1/s) when the setting rises by `step`.
    per_step: f64,
}

/// The error's key and the advice for a loop whose fastest-growing pole is `pole` when `drive_of`
/// the model is held by its actuator on `arm`: each setting's effect on the growth, and the
/// settings that lower it, the strongest first (its key is the error's).
pub(super) fn advice(
    model: &Model,
    arm: &ArmModel,
    drive_of: &dyn Fn(&Model) -> HubDrive,
    pole: Complex<f64>,
) -> (&'static str, String) {
    let growth = |edited: &Model| -> Option<f64> {
        let sim = ArmSimulation::new(arm.clone(), drive_of(edited), edited.integrator).ok()?;
        sim.linear_poles().ok()?.into_iter().map(|p| p.re).reduce(f64::max)
    };
    let kp = model.drive.actuator.controller().map_or(0.0, |g| g.kp);
    let effects: Vec<Effect> = Knob::ALL
        .into_iter()
        .filter_map(|knob| {
            let value = knob.value(&model.drive.actuator)?;
            let step = knob.step(value, kp, pole.norm());
            let at = |v: f64| {
                let mut edited = model.clone();
                knob.set(&mut edited.drive.actuator, v);
                growth(&edited)
            };
            let per_step =
                if value >= step { 0.5 * (at(value + step)? - at(value - step)?) } else { at(value + step)? - pole.re };
            Some(Effect { knob, value, step, per_step })
        })
        .collect();
    let listed: Vec<String> = effects
        .iter()
        .map(|e| format!("{} {} → {}: {:+.3} 1/s", e.knob.name(), short(e.value), short(e.value + e.step), e.per_step))
        .collect();
    // A setting helps if turning it the way it may go lowers the growth: up for any, down for one
    // above zero. Those that move it by under a thousandth of the growth leave it.
    let still = 1e-3 * pole.re.abs();
    let mut helps: Vec<(f64, String, Knob)> = effects
        .iter()
        .filter_map(|e| {
            if e.per_step < -still {
                Some((
                    -e.per_step,
                    format!("raise {} (by {} lowers it {:.3} 1/s)", e.knob.name(), short(e.step), -e.per_step),
                    e.knob,
                ))
            } else if e.per_step > still && e.value > 0.0 {
                Some((
                    e.per_step,
                    format!("lower {} (by {} lowers it {:.3} 1/s)", e.knob.name(), short(e.step), e.per_step),
                    e.knob,
                ))
            } else {
                None
            }
        })
        .collect();
    helps.sort_by(|a, b| b.0.total_cmp(&a.0));
    let how = format!("its growth rate {:.3} 1/s moves with each setting as {}", pole.re, listed.join("; "));
    match helps.first() {
        Some(&(_, _, knob)) => {
            let remedies: Vec<&str> = helps.iter().map(|h| h.1.as_str()).collect();
            (
                knob.key(),
                format!("{how}. Allowed settings whose poles all decay: {} (docs/drives.md)", remedies.join(", or ")),
            )
        }
        None => (
            Knob::Kp.key(),
            format!(
                "{how}. No setting moves it toward decay: allowed a drive whose poles all decay (a reference that \
                 starts at rest, a different machine: docs/drives.md)"
            ),
        ),
    }
}

/// A setting's value, short.
fn short(x: f64) -> String {
    if x == 0.0 || (1e-3..1e4).contains(&x.abs()) { format!("{}", (x * 1e4).round() / 1e4) } else { format!("{x:.2e}") }
}
