//! The error a modal(n) arm expects on a scene whose hub follows its drive and which nothing
//! strikes: measured, not bounded, on the arm's linear equations run through the drive.
//!
//! Where the hub's motion is prescribed and no contact loads the arm, the arm's elastic
//! equations in its clamped modes η are, to first order in the deflection,
//!
//! η̈ + 2 Z ω η̇ + (ω² + θ̇(t)² P) η = −θ̈(t) Φᵀ s − g Φᵀ (sin θ(t) m_axial + cos θ(t) m_transverse)
//!
//! with P = Φᵀ (K_c − M_tr) Φ the spinning arm's extra stiffness (K_c where the scene keeps the
//! centrifugal stiffening), s the rigid rotation's inertia and the gravity loads of
//! [`crate::beam::BeamModel`]. modal(n) keeps the first n rows and columns; its peak tip
//! deflection over the run against that of [`JUDGED_BEYOND`] modes more is what it misses. Unlike
//! the quasi-static [`super::TruncationBound`] this follows the drive in time: a spin-up's
//! acceleration and the rate that stiffens the arm peak at different instants, and the answer
//! to the one rings on into the other.
//!
//! Each run is Newmark's average acceleration at the scene's step: unconditionally stable, and
//! its matrix I + (h/2) C + (h²/4)(ω² + θ̇² P) is diagonal plus θ̇² times one symmetric matrix,
//! so one eigen-decomposition per n solves every step in O(n²).

use nalgebra::{DMatrix, DVector};

use crate::actuator::Actuator;
use crate::beam::{BeamModel, ModalBasis};
use crate::model::{Clamp, Model, Payload};

/// The modes the runs keep at most (the actuator's coupled check uses as many).
pub const REFERENCE_MODES: usize = 12;

/// A run whose peak tip deflection is below this share of the arm's sag laid level bends the
/// tip by round-off only: the floor stands (as for [`super::TruncationBound`]).
const NEGLIGIBLE_SHARE: f64 = 1e-3;

/// A residual vibration below this share of the run's peak tip deflection is within the linear
/// run's own first-order error (it matches fe's peak to about 1e-4 of it): its error is not
/// estimated (a lowering that settles by a hundredth of a millimetre on a 18 mm peak).
const RESIDUAL_SHARE: f64 = 5e-3;

/// How many modes beyond modal(n) the run that judges it keeps: four more change the shipped
/// spin-ups' and lowering's peak tip deflection by under 0.01 % (docs/fidelity.md), a hundredth
/// of the default budget.
pub const JUDGED_BEYOND: usize = 4;

/// Whether the linear run stands for `model`: an ideal drive (the hub follows its motion), no
/// pads or structures (nothing strikes the arm), no tilting head (its hinge is a coordinate the
/// clamped modes lack) and no friction clamp (a slipping string is not linear).
pub fn applies(model: &Model) -> bool {
    let friction = matches!(&model.payload, Payload::String(held) if held.clamp == Clamp::Friction);
    model.drive.actuator == Actuator::Ideal
        && model.dampeners.is_empty()
        && model.structures.is_empty()
        && model.robot.head.is_none()
        && !friction
}

/// The arm's linear equations in its clamped modes, through the scene's drive.
pub struct LinearRun<'a> {
    model: &'a Model,
    /// ωᵢ, rad/s, and the damping rates 2 ζᵢ ωᵢ, 1/s.
    omegas: Vec<f64>,
    rates: Vec<f64>,
    /// P, per (rad/s)².
    spin: DMatrix<f64>,
    /// Φᵀ s, Φᵀ m_axial, Φᵀ m_transverse, and the tip's transverse row Φᵀ r.
    inertia: DVector<f64>,
    axial: DVector<f64>,
    transverse: DVector<f64>,
    tip: DVector<f64>,
    /// The tip's static deflection under gravity with the arm laid level, m: the scale below
    /// which a run's tip deflection is round-off (an arm held upright).
    level_sag_m: f64,
    /// The drive at each step of the run (the start's first): θ̈ and gravity's two components
    /// g sin θ, g cos θ, and θ̇², sampled once for every count of modes.
    drive: Vec<[f64; 4]>,
}

impl<'a> LinearRun<'a> {
    /// The equations of `model`'s arm (`beam`) in its first [`REFERENCE_MODES`] clamped `modes`.
    pub fn new(model: &'a Model, beam: &BeamModel, modes: &ModalBasis) -> Self {
        let count = modes.len().min(REFERENCE_MODES);
        let phi = modes.shapes.columns(0, count);
        let ratios = &model.robot.arm.damping_ratios;
        let zeta = |i: usize| ratios.get(i).or(ratios.last()).copied().unwrap_or(0.0);
        let omegas: Vec<f64> = modes.omegas_rad_s.iter().take(count).copied().collect();
        let rates = omegas.iter().enumerate().map(|(i, w)| 2.0 * zeta(i) * w).collect();
        let stiffening = if model.physics.geometric_stiffening { 1.0 } else { 0.0 };
        let spin = phi.transpose() * (stiffening * &beam.centrifugal_stiffness - &beam.translational_mass) * phi;
        let [_, tip, _] = beam.point_rows(beam.length_m());
        let (h, motion, g) = (model.time.step_s, &model.drive.motion, model.physics.gravity_m_s2);
        let steps = (model.duration_s() / h).ceil() as usize;
        let drive = (0..=steps)
            .map(|k| {
                let at = motion.sample((k as f64 * h).min(motion.duration_s()));
                let (s, c) = at.angle_rad.sin_cos();
                [at.accel_rad_s2, g * s, g * c, at.rate_rad_s * at.rate_rad_s]
            })
            .collect();
        let tip = phi.tr_mul(&tip);
        let transverse = phi.tr_mul(&beam.transverse_mass);
        let level_sag_m = (0..count).map(|i| g * tip[i] * transverse[i] / (omegas[i] * omegas[i])).sum::<f64>().abs();
        LinearRun {
            model,
            level_sag_m,
            omegas,
            rates,
            spin,
            inertia: phi.tr_mul(&beam.coupling),
            axial: phi.tr_mul(&beam.axial_mass),
            transverse,
            tip,
            drive,
        }
    }

    /// The most modes a run keeps.
    pub fn most_modes(&self) -> usize {
        self.omegas.len()
    }

    /// What modal(n) misses of the peak tip deflection and the residual vibration: its run's
    /// against that with [`JUDGED_BEYOND`] modes more ([`Judged`]); `None` where that peak is below
    /// [`NEGLIGIBLE_SHARE`] of the arm's sag laid level (an arm held upright, gravity along it:
    /// nothing bends the tip, and its share would be round-off).
    pub fn error(&self, n: usize) -> Option<Judged> {
        let (reference, run) = (self.tip_m(n + JUDGED_BEYOND), self.tip_m(n));
        let relative = |a: f64, r: f64| (a - r).abs() / r;
        (reference.peak_m > NEGLIGIBLE_SHARE * self.level_sag_m).then(|| Judged {
            peak: relative(run.peak_m, reference.peak_m),
            residual: (reference.residual_m > RESIDUAL_SHARE * reference.peak_m)
                .then(|| relative(run.residual_m, reference.residual_m)),
        })
    }

    /// modal(n)'s tip deflection over the run, m: its largest |value| (drive and settling), and
    /// the residual vibration after the drive (half its peak-to-peak, as the summary reads it).
    fn tip_m(&self, n: usize) -> TipRun {
        let n = n.clamp(1, self.most_modes());
        let h = self.model.time.step_s;
        let (w, c, tip) = (&self.omegas[..n], &self.rates[..n], &self.tip.as_slice()[..n]);
        let spin = self.spin.view((0, 0), (n, n)).into_owned();
        let (inertia, axial, transverse) =
            (&self.inertia.as_slice()[..n], &self.axial.as_slice()[..n], &self.transverse.as_slice()[..n]);
        let load = |i: usize, [accel, gs, gc, _]: [f64; 4]| -accel * inertia[i] - gs * axial[i] - gc * transverse[i];
        // Newmark's matrix A + θ̇² B: A diagonal, A^-1/2 B A^-1/2 = Q Λ Qᵀ.
        let a: Vec<f64> = (0..n).map(|i| (1.0 + 0.5 * h * c[i] + 0.25 * h * h * w[i] * w[i]).sqrt()).collect();
        let eigen = DMatrix::from_fn(n, n, |i, j| 0.25 * h * h * spin[(i, j)] / (a[i] * a[j])).symmetric_eigen();
        // Q column by column (for Qᵀ r) and row by row (for Q z).
        let (columns, lambda) = (eigen.eigenvectors.as_slice(), &eigen.eigenvalues);
        let rows = eigen.eigenvectors.transpose();
        let rows = rows.as_slice();
        // At rest under the start's loads.
        let start = self.drive[0];
        let mut stiffness = start[3] * &spin;
        (0..n).for_each(|i| stiffness[(i, i)] += w[i] * w[i]);
        let rest = stiffness.lu().solve(&DVector::from_fn(n, |i, _| load(i, start)));
        let mut x: Vec<f64> = rest.map_or_else(|| vec![0.0; n], |x| x.as_slice().to_vec());
        let (mut v, mut acc, mut rhs, mut z) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
        let mut peak = dot(tip, &x).abs();
        // The steps from the drive's end on (the summary's residual, `analysis::residual_of_run`).
        let settling = (self.model.drive_end_s() / h - 1e-9).ceil().max(1.0) as usize;
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        let inverse_a: Vec<f64> = a.iter().map(|a| 1.0 / a).collect();
        let (half_h, quarter_h2) = (0.5 * h, 0.25 * h * h);
        for (k, &at) in self.drive.iter().enumerate().skip(1) {
            let spin2 = at[3];
            // The predicted displacement, in x.
            for i in 0..n {
                x[i] += h * v[i] + quarter_h2 * acc[i];
            }
            for (i, row) in spin.as_slice().chunks_exact(n).enumerate() {
                let held = c[i] * (v[i] + half_h * acc[i]) + w[i] * w[i] * x[i] + spin2 * dot(row, &x);
                rhs[i] = (load(i, at) - held) * inverse_a[i];
            }
            // (A + θ̇² B) next = rhs: z = (I + θ̇² Λ)⁻¹ Qᵀ A^-1/2 rhs, next = A^-1/2 Q z.
            for ((z, column), l) in z.iter_mut().zip(columns.chunks_exact(n)).zip(lambda.iter()) {
                *z = dot(column, &rhs) / (1.0 + spin2 * l);
            }
            for (i, row) in rows.chunks_exact(n).enumerate() {
                let next = dot(row, &z) * inverse_a[i];
                x[i] += quarter_h2 * next;
                v[i] += half_h * (acc[i] + next);
                acc[i] = next;
            }
            let deflection = dot(tip, &x);
            peak = peak.max(deflection.abs());
            if k >= settling {
                (low, high) = (low.min(deflection), high.max(deflection));
            }
        }
        TipRun { peak_m: peak, residual_m: if high >= low { 0.5 * (high - low) } else { 0.0 } }
    }
}

/// A linear run's tip deflection (m): [`LinearRun::tip_m`].
struct TipRun {
    peak_m: f64,
    residual_m: f64,
}

/// What modal(n) misses against [`JUDGED_BEYOND`] modes more, relative to the latter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Judged {
    /// Of the peak tip deflection, the budget's quantity.
    pub peak: f64,
    /// Of the residual vibration's amplitude (stated, not held to the budget); `None` where the
    /// tip rings by less than [`RESIDUAL_SHARE`] of its peak.
    pub residual: Option<f64>,
}

/// The fewest modes from `floor` (at most [`REFERENCE_MODES`] less [`JUDGED_BEYOND`]) whose
/// [`LinearRun::error`] is within `tolerance`, and the error of each count run on the way, from
/// `floor`; `floor` itself, with no error, where the arm has too few modes to judge it or nothing
/// bends its tip.
pub fn modes_within(run: &LinearRun, floor: usize, tolerance: f64) -> (usize, Vec<Judged>) {
    let floor = floor.max(1);
    let last = run.most_modes().saturating_sub(JUDGED_BEYOND);
    let mut errors = Vec::new();
    for n in floor..=last {
        let Some(error) = run.error(n) else { return (floor, Vec::new()) };
        errors.push(error);
        if error.peak <= tolerance {
            return (n, errors);
        }
    }
    (floor.max(last), errors)
}
