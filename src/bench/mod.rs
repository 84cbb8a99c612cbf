//! Speed against accuracy: a grid of model fidelities, time steps, integrators, contact methods
//! and clamp modes, each run timed and compared with a converged reference (`pipearm bench`).
//!
//! Every point of the grid is a full run of the scene. Its cost is the wall time of the step
//! loop per simulated second (median of repeats, one thread); its errors are taken against the
//! reference of the same physics (same contact law and clamp): the peak contact force, the tip
//! deflection history (RMS difference over the reference's peak) and the residual vibration's
//! frequency. The reference is the full FE arm at an eighth of the scene's step or a 200th of
//! its strongest impact, whichever is shorter; how converged it is is shown by Richardson
//! extrapolation over the step and by doubling the elements ([`Convergence`]).

pub mod chart;
mod report;
pub mod stability;

use std::time::Instant;

pub use chart::{chart_png, chart_svg, pareto_front, register_font};
pub use report::{points_csv, report_markdown, stability_csv};

use crate::arm::Fidelity;
use crate::contact::ForceLaw;
use crate::integrate::IntegratorKind;
use crate::model::{Clamp, ContactMethod, DEFAULT_TOLERANCE_M, Detection, Model};
use crate::run::{RunOptions, RunSummary, Series, run_with};
use crate::scene::{Scene, SceneError};

/// A run of the bench that failed for a reason other than divergence.
#[derive(Debug, thiserror::Error)]
#[error("{what}: {source}")]
pub struct BenchError {
    /// Which run.
    pub what: String,
    /// Why.
    pub source: SceneError,
}

fn labelled(what: impl Into<String>) -> impl FnOnce(SceneError) -> BenchError {
    let what = what.into();
    move |source| BenchError { what, source }
}

/// One point of the grid: how to run the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// What this point varies (`fidelity`, `step: <integrator>`, `contact`, `clamp`).
    pub axis: String,
    /// Model fidelity.
    pub fidelity: Fidelity,
    /// FE elements along the arm (`None`: the robot's).
    pub elements: Option<usize>,
    /// Time integrator.
    pub integrator: IntegratorKind,
    /// Time step (around contact, with `free_step_s`), s.
    pub step_s: f64,
    /// Longest error-controlled step in free motion, s (`None`: fixed steps).
    pub free_step_s: Option<f64>,
    /// Local error tolerance of the controlled steps, m of tip displacement.
    pub tolerance_m: Option<f64>,
    /// Contact method.
    pub contact: ContactMethod,
    /// Where the `compliant` method finds its contacts.
    pub detection: Detection,
    /// The `rapier` method's pad body mass, kg (`None`: the scene's).
    pub pad_mass_kg: Option<f64>,
    /// Pad law made linear (the `rapier` method needs one; its compliant twin shares it).
    pub linear_pads: bool,
    /// How the string is held.
    pub clamp: Clamp,
    /// The held string's fidelity (`None`: the scene's own).
    pub string: Option<Fidelity>,
}

impl Variant {
    /// A short label for charts and tables, e.g. `modal(3) generalized-alpha 2ms`.
    pub fn label(&self) -> String {
        let model = match (self.fidelity, self.elements) {
            (Fidelity::Fe, Some(n)) => format!("fe{n}"),
            (f, _) => f.to_string(),
        };
        // Steps to 4 significant digits: 0.15 ms, not the 0.15000000000005 a division leaves.
        let step_ms = format!("{:.4e}", 1e3 * self.step_s).parse::<f64>().unwrap_or(f64::NAN);
        let mut label = format!("{model} {} {step_ms}ms", self.integrator.name());
        if let Some(free) = self.free_step_s {
            let tolerance = self.tolerance_m.unwrap_or(DEFAULT_TOLERANCE_M);
            label += &format!(" free<={}ms tol {tolerance:.0e}m", 1e3 * free);
        }
        if self.linear_pads {
            label += &format!(" {}", format!("{:?}", self.contact).to_lowercase());
        }
        if self.detection != Detection::Auto {
            label += &format!(" {}", self.detection.name());
        }
        if let Some(mass) = self.pad_mass_kg {
            label += &format!(" pad {mass}kg");
        }
        if self.clamp == Clamp::Friction {
            label += " friction";
        }
        if let Some(string) = self.string {
            label += &format!(" string {string}");
        }
        label
    }

    /// The physics this point computes, which its reference must share: the pad law. (A
    /// friction clamp is compared with the rigid clamp's reference: the friction clamp's staggered
    /// coupling diverges on the FE arm and on some steps of eight modes, docs/accuracy.md, so it
    /// has no converged reference of its own; its error includes the slip it models.)
    fn physics(&self) -> bool {
        self.linear_pads
    }

    /// The model with this point's settings.
    pub fn model(&self, base: &Model, linear_laws: &[ForceLaw]) -> Model {
        let mut s = base.clone();
        s.integrator = self.integrator;
        s.time.step_s = self.step_s;
        s.time.free_step_s = self.free_step_s;
        s.time.tolerance_m = self.tolerance_m;
        s.contact.method = self.contact;
        s.contact.detection = self.detection;
        if let Some(mass) = self.pad_mass_kg {
            s.contact.pad_mass_kg = mass;
        }
        if let Some(held) = s.payload.string_mut() {
            held.clamp = self.clamp;
            if self.string.is_some() {
                held.model = self.string;
            }
        }
        if self.linear_pads {
            for (pad, law) in s.dampeners.iter_mut().zip(linear_laws) {
                pad.law = *law;
            }
        }
        if let Some(n) = self.elements {
            s.robot.arm.elements = n;
        }
        s
    }
}

/// What one point measured.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// It ran: cost and errors.
    Ran(Measured),
    /// The divergence guard stopped it.
    Diverged { t_s: f64, message: String },
}

/// Cost and errors of a point that ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Wall time per simulated second (median of repeats), s/s.
    pub cost_s_per_s: f64,
    /// Largest peak contact force over the pads, N.
    pub peak_force_n: f64,
    /// |peak − reference| / reference.
    pub peak_force_error: f64,
    /// RMS of the tip deflection's difference from the reference, over the reference's peak.
    pub tip_rms_error: f64,
    /// Residual vibration frequency, Hz (NaN: none).
    pub frequency_hz: f64,
    /// |f − f_ref| / f_ref (1 when the point has no vibration to measure).
    pub frequency_error: f64,
}

/// A point and its outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// How it ran.
    pub variant: Variant,
    /// What it measured.
    pub outcome: Outcome,
}

impl Point {
    /// The measurements, if it ran.
    pub fn measured(&self) -> Option<&Measured> {
        match &self.outcome {
            Outcome::Ran(m) => Some(m),
            Outcome::Diverged { .. } => None,
        }
    }
}

/// A converged solution of one physics (contact law, clamp).
#[derive(Debug, Clone)]
pub struct Reference {
    /// How it was computed.
    pub variant: Variant,
    /// Its largest peak contact force, N.
    pub peak_force_n: f64,
    /// Its residual frequency, Hz.
    pub frequency_hz: f64,
    /// Its tip deflection history (t s, v m).
    pub tip: Vec<(f64, f64)>,
    /// Evidence that it is converged.
    pub convergence: Convergence,
}

/// Richardson extrapolation of the reference's peak force over the step, and the change when the
/// elements are doubled.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// (step s, peak force N, frequency Hz) at h, 2h, 4h.
    pub steps: Vec<(f64, f64, f64)>,
    /// Observed order p = log2((F₄ₕ − F₂ₕ) / (F₂ₕ − Fₕ)).
    pub observed_order: f64,
    /// Richardson estimate of the reference's own error, |Fₕ − F₂ₕ| / (2^p − 1) / Fₕ.
    pub peak_force_error: f64,
    /// (elements, peak force N) of the doubled mesh at 2h, and the relative change from the
    /// robot's mesh at 2h.
    pub doubled_mesh: Option<(usize, f64, f64)>,
}

/// How the grid runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchOptions {
    /// Timed repeats per point (the median is kept).
    pub repeats: usize,
    /// A smaller grid (fewer steps and fidelities) for a quick look.
    pub quick: bool,
    /// Also check the reference by doubling the FE mesh (the slowest run of the bench).
    pub mesh_check: bool,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions { repeats: 3, quick: false, mesh_check: true }
    }
}

/// The results of a bench of one scene.
#[derive(Debug, Clone)]
pub struct BenchResult {
    /// Scenario name.
    pub scenario: String,
    /// The scene's own step, s.
    pub base_step_s: f64,
    /// The fidelity `auto` chose.
    pub auto_fidelity: Fidelity,
    /// The label of the scene's own setting (its fidelity, integrator and step).
    pub own_label: String,
    /// The string fidelity `auto` chose (`None` without a string).
    pub auto_string: Option<Fidelity>,
    /// The references, one per physics.
    pub references: Vec<Reference>,
    /// Every grid point.
    pub points: Vec<Point>,
    /// The stability map.
    pub stability: stability::StabilityMap,
}

/// The scene's own setting: `auto`'s fidelity, the scene's integrator, step and contact.
pub fn own_setting(model: &Model, auto: Fidelity) -> Variant {
    Variant {
        axis: "fidelity".into(),
        fidelity: auto,
        elements: None,
        integrator: model.integrator,
        step_s: model.time.step_s,
        free_step_s: None,
        tolerance_m: None,
        contact: ContactMethod::Compliant,
        detection: model.contact.detection,
        pad_mass_kg: None,
        linear_pads: false,
        clamp: model.payload.string().map(|held| held.clamp).unwrap_or_default(),
        string: None,
    }
}

/// The grid for a scene: each axis varied around the scene's own settings.
pub fn grid(model: &Model, auto: Fidelity, quick: bool) -> Vec<Variant> {
    let h0 = model.time.step_s;
    let steps: Vec<f64> = if quick { vec![0.5, 1.0, 2.0] } else { vec![0.125, 0.25, 0.5, 1.0, 2.0, 4.0] }
        .into_iter()
        .map(|f| f * h0)
        .collect();
    let robot_elements = model.robot.arm.elements;
    let base_clamp = model.payload.string().map(|held| held.clamp);
    let base = own_setting(model, auto);
    let mut out = Vec::new();
    let modal_counts: Vec<usize> = if quick { vec![1, 3, 8] } else { (1..=8).collect() };
    let fidelities =
        std::iter::once(Fidelity::Rigid).chain(modal_counts.into_iter().map(|n| Fidelity::Modal { modes: n }));
    // The fidelity axis under generalized-α at the scene's step: a method stable for every model
    // there (an explicit scene integrator is not, for eight modes or the FE arm), so that the
    // models are compared, not their stability limits.
    let implicit = Variant { integrator: IntegratorKind::default(), ..base.clone() };
    out.extend(fidelities.map(|fidelity| Variant { fidelity, ..implicit.clone() }));
    let meshes =
        if quick { vec![robot_elements / 2] } else { vec![robot_elements / 4, robot_elements / 2, robot_elements] };
    out.extend(meshes.into_iter().map(|n| Variant {
        fidelity: Fidelity::Fe,
        elements: Some(n.max(2)),
        ..implicit.clone()
    }));
    for integrator in integrators() {
        let axis = format!("step: {}", integrator.name());
        out.extend(steps.iter().map(|&step_s| Variant { axis: axis.clone(), integrator, step_s, ..base.clone() }));
    }
    // Error-controlled free steps (up to 2–8× the scene's step) against the tolerance.
    let (free_factors, tolerances) =
        if quick { (vec![4.0], vec![1e-6]) } else { (vec![2.0, 4.0, 8.0], vec![1e-7, 1e-6, 1e-5]) };
    for &factor in &free_factors {
        out.extend(tolerances.iter().map(|&tol| Variant {
            axis: "adaptive".into(),
            // The error estimate is the implicit methods'.
            integrator: IntegratorKind::default(),
            free_step_s: Some(factor * h0),
            tolerance_m: Some(tol),
            ..base.clone()
        }));
    }
    for fidelity in [Fidelity::Modal { modes: 1 }, Fidelity::Modal { modes: 8 }, Fidelity::Fe] {
        let axis = format!("step: {fidelity}");
        let coarse = steps.iter().filter(|&&h| fidelity != Fidelity::Fe || h >= 0.5 * h0);
        out.extend(coarse.map(|&step_s| Variant { axis: axis.clone(), fidelity, step_s, ..implicit.clone() }));
    }
    if !model.dampeners.is_empty() && model.structures.is_empty() {
        for contact in [ContactMethod::Compliant, ContactMethod::Rapier] {
            let axis = format!("contact: {}", contact.name());
            out.extend(steps.iter().map(|&step_s| Variant {
                axis: axis.clone(),
                contact,
                linear_pads: true,
                step_s,
                ..base.clone()
            }));
        }
        // The `rapier` pad body's mass at the scene's step: its difference from `compliant`
        // shrinks with the mass.
        let masses: &[f64] = if quick { &[0.1, 1.0, 10.0] } else { &[0.01, 0.1, 1.0, 10.0, 100.0] };
        out.extend(masses.iter().map(|&mass| Variant {
            axis: "pad mass".into(),
            contact: ContactMethod::Rapier,
            pad_mass_kg: Some(mass),
            linear_pads: true,
            ..base.clone()
        }));
        // Contact through rapier's pipeline against the pad-face path, at the scene's steps.
        for detection in [Detection::Pipeline, Detection::PadFace] {
            let axis = format!("detection: {}", detection.name());
            out.extend(steps.iter().map(|&step_s| Variant { axis: axis.clone(), detection, step_s, ..base.clone() }));
        }
    }
    if base_clamp == Some(Clamp::Rigid) {
        // The string's fidelity with the arm at auto's: where a rigid (lumped) string is as good
        // as a flexible one, against the reference's fe string.
        let counts: &[usize] = if quick { &[1, 4] } else { &[1, 2, 4, 8] };
        let strings = std::iter::once(Fidelity::Rigid)
            .chain(counts.iter().map(|&modes| Fidelity::Modal { modes }))
            .chain(std::iter::once(Fidelity::Fe));
        out.extend(strings.map(|string| Variant { axis: "string".into(), string: Some(string), ..implicit.clone() }));
    }
    // The other clamp, where the string is held by one hand (a friction clamp holds it in one
    // hand's jaws).
    let one_hand = model.payload.string().is_some_and(|held| held.grips.len() == 1);
    if let Some(clamp) = base_clamp.filter(|_| one_hand) {
        let other = if clamp == Clamp::Rigid { Clamp::Friction } else { Clamp::Rigid };
        let axis = format!("clamp: {}", format!("{other:?}").to_lowercase());
        out.extend(steps.iter().filter(|&&h| h >= 0.25 * h0).map(|&step_s| Variant {
            axis: axis.clone(),
            clamp: other,
            step_s,
            ..base.clone()
        }));
    }
    out
}

/// The integrators the bench compares, with the scene defaults' parameters.
pub fn integrators() -> [IntegratorKind; 6] {
    [
        IntegratorKind::default(),
        IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 },
        IntegratorKind::Hht { alpha: -0.1 },
        IntegratorKind::SymplecticEuler,
        IntegratorKind::Rk4,
        IntegratorKind::ExplicitEuler,
    ]
}

/// Linear pad laws equivalent to the scene's: the tangent stiffness at `force_n` and the damping
/// that gives the law's restitution on the arm's effective mass (ζ = −ln e / √(π² + ln² e)).
pub fn linear_laws(model: &Model, force_n: f64) -> Result<Vec<ForceLaw>, SceneError> {
    let scene = Scene::with_fidelity(model, Fidelity::Modal { modes: 3 })?;
    let masses = scene.pad_effective_masses_kg();
    Ok(model
        .dampeners
        .iter()
        .zip(masses)
        .map(|(pad, m_eff)| {
            let law = pad.law;
            if let ForceLaw::Linear { .. } = law {
                return law;
            }
            let k = law.tangent_stiffness_at_force(force_n);
            let e = law.restitution().unwrap_or(0.6).clamp(1e-3, 1.0);
            let zeta = -e.ln() / (std::f64::consts::PI.powi(2) + e.ln().powi(2)).sqrt();
            let m = m_eff.unwrap_or(1.0);
            ForceLaw::Linear { stiffness_n_m: k, damping_n_s_m: 2.0 * zeta * (k * m).sqrt() }
        })
        .collect())
}

/// Runs a variant `repeats` times; the first run's results, the median wall time.
pub fn run_timed(model: &Model, fidelity: Fidelity, repeats: usize) -> Result<(RunSummary, Series, f64), SceneError> {
    let options = RunOptions { fidelity: Some(fidelity), ..RunOptions::default() };
    let mut walls = Vec::with_capacity(repeats.max(1));
    let mut first = None;
    for _ in 0..repeats.max(1) {
        let started = Instant::now();
        let (summary, series) = run_with(model, &options)?;
        // The whole run, model building included: what a user waits for.
        walls.push(started.elapsed().as_secs_f64());
        first.get_or_insert((summary, series));
    }
    walls.sort_by(f64::total_cmp);
    let (summary, series) = first.expect("at least one run");
    let cost = walls[walls.len() / 2] / summary.simulated_s.max(1e-12);
    Ok((summary, series, cost))
}

/// Largest peak contact force of a run, N (0 without pads).
pub fn peak_force_n(summary: &RunSummary) -> f64 {
    summary.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max)
}

/// The transverse tip deflection history of a run.
pub fn tip_history(series: &Series) -> Vec<(f64, f64)> {
    series.t_s.iter().zip(&series.tip_deflection_m).map(|(t, d)| (*t, d[1])).collect()
}

/// RMS of `history − reference` at the history's times (reference interpolated linearly), over
/// the reference's largest |value|.
pub fn rms_error_over_peak(history: &[(f64, f64)], reference: &[(f64, f64)]) -> f64 {
    let peak = reference.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    if history.is_empty() || peak == 0.0 {
        return f64::NAN;
    }
    let mut j = 0;
    let mut sum = 0.0;
    for &(t, v) in history {
        while j + 2 < reference.len() && reference[j + 1].0 < t {
            j += 1;
        }
        let (a, b) = (reference[j], reference[(j + 1).min(reference.len() - 1)]);
        let w = if b.0 > a.0 { ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0) } else { 0.0 };
        let r = a.1 + w * (b.1 - a.1);
        sum += (v - r).powi(2);
    }
    (sum / history.len() as f64).sqrt() / peak
}

fn relative(a: f64, b: f64) -> f64 {
    if b == 0.0 { if a == 0.0 { 0.0 } else { 1.0 } } else { ((a - b) / b).abs() }
}

/// The reference's step: an eighth of the scene's, or a 200th of its strongest impact if that is
/// shorter (measured on a run of the scene's own model and step), s.
pub fn reference_step_s(base: &Model) -> Result<f64, SceneError> {
    let h0 = base.time.step_s;
    let (summary, _) = crate::run::run(base, None)?;
    let strongest = summary
        .pairs
        .iter()
        .filter_map(|p| p.impacts.iter().max_by(|a, b| a.peak_force_n.total_cmp(&b.peak_force_n)))
        .map(|i| i.duration_s())
        .fold(f64::INFINITY, f64::min);
    Ok((h0 / 8.0).min(strongest / 200.0))
}

/// Computes the reference of a variant's physics: the full FE arm at the robot's mesh and
/// [`reference_step_s`], with a rigid clamp, and its convergence evidence.
pub fn reference(
    base: &Model,
    physics_of: &Variant,
    linear: &[ForceLaw],
    h_ref: f64,
    mesh_check: bool,
) -> Result<Reference, SceneError> {
    let fidelity = Fidelity::Fe;
    let at = |step_s: f64, elements: Option<usize>| Variant {
        axis: "reference".into(),
        fidelity,
        elements,
        integrator: IntegratorKind::default(),
        step_s,
        free_step_s: None,
        tolerance_m: None,
        clamp: Clamp::Rigid,
        // The string converged too: every FE DOF of it, held rigidly.
        string: base.payload.string().map(|_| Fidelity::Fe),
        ..physics_of.clone()
    };
    let mut steps = Vec::new();
    let mut finest = None;
    for factor in [1.0, 2.0, 4.0] {
        let variant = at(factor * h_ref, None);
        let (summary, series) =
            run_with(&variant.model(base, linear), &RunOptions { fidelity: Some(fidelity), ..RunOptions::default() })?;
        steps.push((variant.step_s, peak_force_n(&summary), summary.residual.frequency_hz));
        finest.get_or_insert((variant, summary, series));
    }
    let (f1, f2, f4) = (steps[0].1, steps[1].1, steps[2].1);
    let observed_order = ((f4 - f2) / (f2 - f1)).abs().log2();
    // Extrapolate only where the differences shrink at a plausible order; otherwise they are at
    // the level of the peak's sampling by the step, and the last difference is the estimate.
    let peak_force_error = if (0.5..=6.0).contains(&observed_order) {
        relative(f1 + (f1 - f2) / (2f64.powf(observed_order) - 1.0), f1)
    } else {
        relative(f2, f1)
    };
    let doubled_mesh = if mesh_check {
        let n = 2 * base.robot.arm.elements;
        let variant = at(2.0 * h_ref, Some(n));
        let (summary, _) = run_with(
            &variant.model(base, linear),
            &RunOptions { fidelity: Some(Fidelity::Fe), ..RunOptions::default() },
        )?;
        let f = peak_force_n(&summary);
        Some((n, f, relative(f, f2)))
    } else {
        None
    };
    let (variant, summary, series) = finest.expect("three runs");
    Ok(Reference {
        variant,
        peak_force_n: peak_force_n(&summary),
        frequency_hz: summary.residual.frequency_hz,
        tip: tip_history(&series),
        convergence: Convergence { steps, observed_order, peak_force_error, doubled_mesh },
    })
}

/// Runs one point against its reference.
pub fn measure(
    base: &Model,
    v: &Variant,
    linear: &[ForceLaw],
    r: &Reference,
    repeats: usize,
) -> Result<Point, SceneError> {
    let outcome = match run_timed(&v.model(base, linear), v.fidelity, repeats) {
        Ok((summary, series, cost_s_per_s)) => {
            let peak = peak_force_n(&summary);
            let f = summary.residual.frequency_hz;
            Outcome::Ran(Measured {
                cost_s_per_s,
                peak_force_n: peak,
                peak_force_error: relative(peak, r.peak_force_n),
                tip_rms_error: rms_error_over_peak(&tip_history(&series), &r.tip),
                frequency_hz: f,
                frequency_error: if f.is_finite() { relative(f, r.frequency_hz) } else { 1.0 },
            })
        }
        Err(SceneError::Diverged { t_s, what, .. }) => Outcome::Diverged { t_s, message: what },
        Err(e) => return Err(e),
    };
    Ok(Point { variant: v.clone(), outcome })
}

/// Runs the whole bench of a scene; `progress` is told each point's label as it starts.
pub fn bench(
    model: &Model,
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<BenchResult, BenchError> {
    let auto = crate::select::fidelity(model).map_err(|e| labelled("model choice")(e.into()))?.fidelity;
    let variants = grid(model, auto, options.quick);
    let main_physics = &variants[0];
    let total = variants.len() + 3;
    progress("reference (fe, fine step)", 0, total);
    let h_ref = reference_step_s(model).map_err(labelled("reference step"))?;
    let mut references = vec![
        reference(model, main_physics, &[], h_ref, options.mesh_check)
            .map_err(labelled("reference (fe, fine step)"))?,
    ];
    let linear = linear_laws(model, references[0].peak_force_n).map_err(labelled("linear pad laws"))?;
    let mut points = Vec::with_capacity(variants.len());
    for (i, v) in variants.iter().enumerate() {
        progress(&v.label(), i + 1, total);
        let r = match references.iter().position(|r| r.variant.physics() == v.physics()) {
            Some(k) => &references[k],
            None => {
                let r = reference(model, v, &linear, h_ref, false)
                    .map_err(labelled(format!("reference of {}", v.label())))?;
                references.push(r);
                references.last().expect("just pushed")
            }
        };
        points.push(measure(model, v, &linear, r, options.repeats).map_err(labelled(v.label()))?);
    }
    progress("stability map", total - 2, total);
    let stability =
        stability::map(model, auto, &references[0], &linear, options.quick).map_err(labelled("stability map"))?;
    progress("done", total, total);
    Ok(BenchResult {
        scenario: model.name.clone(),
        base_step_s: model.time.step_s,
        auto_fidelity: auto,
        own_label: own_setting(model, auto).label(),
        auto_string: match model.payload.string() {
            Some(_) => Some(model.string_fidelity().map_err(|e| labelled("string model choice")(e.into()))?.fidelity),
            None => None,
        },
        references,
        points,
        stability,
    })
}

#[cfg(test)]
mod tests {
    use super::rms_error_over_peak;

    #[test]
    fn rms_error_of_a_shifted_sine_is_the_shift_over_the_peak() {
        let reference: Vec<(f64, f64)> = (0..=1000).map(|i| (i as f64 * 1e-3, (i as f64 * 1e-2).sin())).collect();
        // Sampled more coarsely, offset by 0.01: the interpolation error of a fine reference is
        // negligible against the offset.
        let history: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 * 1e-2, (i as f64 * 0.1).sin() + 0.01)).collect();
        let e = rms_error_over_peak(&history, &reference);
        assert!((e - 0.01).abs() < 1e-4, "{e}");
        assert!(rms_error_over_peak(&reference, &reference) < 1e-15);
    }
}
