//! The error a modal(n) arm expects on the scene's headline quantities: the modal truncation's
//! own bound (the mode-acceleration argument of Craig and Kurdila, *Fundamentals of Structural
//! Dynamics*, 2nd ed., §14.5).
//!
//! The band rule keeps every mode the scene excites, so the modes left out answer the scene's
//! loads quasi-statically: what modal(n) misses of a response is the
//! truncated modes' share of its static value. For a load pattern b and an output row r over
//! the FE DOFs, the static response is r K⁻¹ b = Σᵢ (r φᵢ)(φᵢᵀ b) / ωᵢ² over every clamped mode
//! (mass-normalised, a complete basis of the arm's DOFs), and modal(n) keeps the first n terms.
//! The loads are those the scene has, at their magnitudes: gravity at angles along the drive's
//! path, the hub's peak acceleration (the inertia S θ̈ of the rigid rotation), under a cylinder
//! each with the push at the pin that carries its moment, and a force at each pad's station. The
//! outputs: the tip's deflection under each load (against the largest the scene's loads give),
//! and each pad's force, whose error follows from the point flexibility f the truncation leaves out at the
//! pad: an impact's peak force goes as the square root of the contact's stiffness
//! 1 / (1/k + f), so it is off by about ½ Δf / (1/k + f).
//!
//! The sums reuse the modes the run solves anyway: a few dot products per mode, and for the loads
//! judged at a hub rate one projection of the spinning arm's extra stiffness onto the modes and
//! one Cholesky factor each (`SpinningStatics`; docs/fidelity.md measures it against a run).

use crate::actuator::Actuator;
use crate::beam::{BeamError, BeamModel, ModalBasis};
use crate::model::Model;

/// A load whose static tip deflection is below this share of its modes' terms in magnitude
/// (they cancel: a pull along the arm) does not bend the tip, and its relative truncation means
/// nothing.
const NEGLIGIBLE_SHARE: f64 = 1e-3;

/// One headline quantity's truncation: what modal(n) misses of it for every n, and what that is
/// relative to.
struct Term {
    /// The quantity, in words.
    quantity: String,
    /// What modal(n) misses of its static value, for n = 0, 1, … (every mode: 0).
    missing: Vec<f64>,
    /// What a missing share is measured against.
    scale: f64,
    /// The factor from a missing share to the quantity's error (½ for an impact's force).
    factor: f64,
}

impl Term {
    fn error(&self, n: usize) -> f64 {
        let missing = self.missing.get(n).copied().unwrap_or(0.0);
        self.factor * missing.abs() / self.scale.abs().max(f64::MIN_POSITIVE)
    }
}

/// What the first n of a mode-by-mode sum leave out, for n = 0 ..= its length.
fn tails(terms: &[f64]) -> Vec<f64> {
    let mut tails = vec![0.0; terms.len() + 1];
    for i in (0..terms.len()).rev() {
        tails[i] = tails[i + 1] + terms[i];
    }
    tails
}

/// The modal truncation bound of a scene on its headline quantities.
pub struct TruncationBound {
    terms: Vec<Term>,
}

impl TruncationBound {
    /// The bound's terms for `model` on its clamped `modes`.
    pub fn new(model: &Model, beam: &BeamModel, modes: &ModalBasis) -> Result<Self, BeamError> {
        let per_mode = |r: &nalgebra::DVector<f64>, b: &nalgebra::DVector<f64>| -> Vec<f64> {
            let (rp, bp) = (modes.shapes.tr_mul(r), modes.shapes.tr_mul(b));
            modes.omegas_rad_s.iter().enumerate().map(|(i, w)| rp[i] * bp[i] / (w * w)).collect()
        };
        let [_, tip, _] = beam.point_rows(beam.length_m());
        // The scene's own loads, scaled to what the scene applies (gravity in m/s², the hub's
        // peak acceleration in rad/s²): their static tip deflections are in metres.
        let loads = match &model.drive.actuator {
            Actuator::Hydraulic(h) => held_at_the_pins(model, beam, &h.cylinders),
            _ => held_at_the_hub(model, beam),
        };
        let tip_modal = modes.shapes.tr_mul(&tip);
        let spin_stiffness = loads.iter().any(|l| l.rate_rad_s != 0.0).then(|| spin_stiffness(model, beam, modes));
        // One factor per distinct rate: a lift's cruise shares one among its samples.
        let mut factors: Vec<(f64, SpinningStatics)> = Vec::new();
        let tips: Vec<(String, Vec<f64>)> = loads
            .iter()
            .map(|load| {
                let rate = load.rate_rad_s;
                let index = factors.iter().position(|(r, _)| *r == rate).unwrap_or_else(|| {
                    factors.push((rate, SpinningStatics::new(modes, spin_stiffness.as_ref(), rate)));
                    factors.len() - 1
                });
                let terms = factors[index].1.terms(&tip_modal, &modes.shapes.tr_mul(&load.vector));
                (load.name.clone(), tails(&terms))
            })
            .collect();
        // Each load's missing share is measured against the largest static tip deflection the
        // scene's loads give, a stand-in for its peak: a load that hardly bends the tip (gravity
        // along the raised arm) is not judged against its own near-zero deflection.
        let largest = tips.iter().map(|(_, t)| t[0].abs()).fold(0.0, f64::max);
        // Loads that bend the tip by less than a thousandth of the arm's own sag laid level (an
        // arm held upright, gravity along it) leave nothing to judge: their shares are round-off,
        // and judged against each other they would ask for every mode.
        let sag = per_mode(&tip, &gravity_at(model, beam, 0.0)).iter().sum::<f64>().abs();
        let mut terms = Vec::new();
        if largest > 1e-3 * sag && largest > 0.0 {
            for (name, missing) in tips {
                let quantity = format!("tip deflection under {name}");
                terms.push(Term { quantity, missing, scale: largest, factor: 1.0 });
            }
        }
        for pad in &model.dampeners {
            let [_, v, _] = beam.point_rows(pad.station_m);
            let point = per_mode(&v, &v);
            let stiffness = pad.law.force_n(1e-3, 0.0, 1.0) / 1e-3;
            let flexibility: f64 = point.iter().sum();
            terms.push(Term {
                quantity: format!("peak force on {}", pad.name),
                missing: tails(&point),
                scale: 1.0 / stiffness.max(f64::MIN_POSITIVE) + flexibility,
                factor: 0.5,
            });
            // A pad's force has no magnitude before the run: its tip deflection is judged against
            // its own (unless the modes' terms cancel there and it does not bend the tip).
            let t = per_mode(&tip, &v);
            let full: f64 = t.iter().sum();
            if full.abs() > NEGLIGIBLE_SHARE * t.iter().map(|x| x.abs()).sum::<f64>() {
                let quantity = format!("tip deflection under a force on {}", pad.name);
                terms.push(Term { quantity, missing: tails(&t), scale: full, factor: 1.0 });
            }
        }
        Ok(TruncationBound { terms })
    }

    /// The largest expected error of modal(n) and the quantity it is on.
    pub fn error(&self, n: usize) -> (f64, &str) {
        self.terms
            .iter()
            .map(|t| (t.error(n), t.quantity.as_str()))
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .unwrap_or((0.0, "nothing"))
    }

    /// The fewest modes from `floor` (at most `cap`) whose expected error is within `tolerance`;
    /// `cap` if none is.
    pub fn modes_within(&self, floor: usize, cap: usize, tolerance: f64) -> usize {
        (floor..=cap).find(|&n| self.error(n).0 <= tolerance).unwrap_or(cap)
    }
}

/// A load the scene applies, N over the FE DOFs, and the hub's rate when it does, rad/s.
struct Load {
    name: String,
    vector: nalgebra::DVector<f64>,
    rate_rad_s: f64,
}

/// How many equal intervals of the drive's time gravity is judged at: an arm held at a
/// cylinder's pin deflects most mid-lift, where the push's line has swung (on `hydraulic`,
/// 3.3 mm at 25° against 1.2 mm at the start), not at either end.
const PATH_INTERVALS: usize = 12;

/// The drive's states where the loads are judged: along its path (its start and end among
/// them) for gravity, and where its acceleration peaks (sampled), that one at the drive's peak
/// rate: the arm's answer to the acceleration rings on past it (a spin-up's peaks mid-way, at
/// half its final rate, and judged there the bound let a 1 s spin-up run modal(1) 1.4 % from
/// fe).
struct JudgedStates {
    path: Vec<crate::drive::DriveState>,
    peak: crate::drive::DriveState,
}

impl JudgedStates {
    fn of(model: &Model) -> Self {
        let motion = &model.drive.motion;
        let at = |i: usize, count: usize| motion.sample(motion.duration_s() * i as f64 / count as f64);
        let samples = 400;
        let peak = (0..=samples)
            .map(|i| at(i, samples))
            .max_by(|a, b| a.accel_rad_s2.abs().total_cmp(&b.accel_rad_s2.abs()))
            .unwrap_or_else(|| motion.sample(0.0));
        let peak = crate::drive::DriveState { rate_rad_s: motion.peak_rate_rad_s(), ..peak };
        JudgedStates { path: (0..=PATH_INTERVALS).map(|i| at(i, PATH_INTERVALS)).collect(), peak }
    }
}

/// The arm's static answer at a hub rate Ω, in the clamped modes' coordinates: a
/// spinning arm's stiffness K_Ω = K + Ω² (K_c − M_tr) (its centrifugal stiffening, when the
/// scene keeps it) is not diagonal in them, so modal(n) answers a load b with the Galerkin
/// solution Φₙ (Φₙᵀ K_Ω Φₙ)⁻¹ Φₙᵀ b, and misses what the first n modes cannot hold of the shape
/// the spinning arm takes. With L the Cholesky factor of Φᵀ K_Ω Φ, the leading n × n block of L
/// is that of Φₙᵀ K_Ω Φₙ, so r (…)⁻¹ b over the first n modes is Σ_{i<n} (L⁻¹r)ᵢ (L⁻¹b)ᵢ: one
/// factorisation for every n. At rest, L = diag(ωᵢ) and this is the module doc's sum.
struct SpinningStatics {
    /// L, lower triangular.
    factor: nalgebra::DMatrix<f64>,
}

impl SpinningStatics {
    /// At hub rate `spin`, with `spin_stiffness` the modes' Φᵀ (K_c − M_tr) Φ (needed unless
    /// `spin` is 0): Φᵀ K_Ω Φ = diag(ωᵢ²) + Ω² Φᵀ (K_c − M_tr) Φ, the modes being mass-normalised.
    fn new(modes: &ModalBasis, spin_stiffness: Option<&nalgebra::DMatrix<f64>>, spin: f64) -> Self {
        let omegas = nalgebra::DVector::from_iterator(modes.len(), modes.omegas_rad_s.iter().copied());
        let at_rest = || nalgebra::DMatrix::from_diagonal(&omegas);
        let Some(spun) = spin_stiffness.filter(|_| spin != 0.0) else { return SpinningStatics { factor: at_rest() } };
        let mut stiffness = spin * spin * spun;
        for (i, w) in omegas.iter().enumerate() {
            stiffness[(i, i)] += w * w;
        }
        // An arm that buckles at that rate (no stiffening) is judged at rest.
        let factor = stiffness.cholesky().map_or_else(at_rest, |c| c.l());
        SpinningStatics { factor }
    }

    /// Each mode's term of r K_Ω⁻¹ b (`r`, `b` in modal coordinates), lowest first.
    fn terms(&self, r: &nalgebra::DVector<f64>, b: &nalgebra::DVector<f64>) -> Vec<f64> {
        let solve = |v: &nalgebra::DVector<f64>| self.factor.solve_lower_triangular(v).unwrap_or_else(|| v * 0.0);
        solve(r).component_mul(&solve(b)).iter().copied().collect()
    }
}

/// The modes' share of a spinning arm's stiffness per (rad/s)², Φᵀ (K_c − M_tr) Φ (K_c where
/// the scene keeps the centrifugal stiffening): one projection for every load and rate.
fn spin_stiffness(model: &Model, beam: &BeamModel, modes: &ModalBasis) -> nalgebra::DMatrix<f64> {
    let stiffening = if model.physics.geometric_stiffening { 1.0 } else { 0.0 };
    let phi = &modes.shapes;
    phi.transpose() * (stiffening * &beam.centrifugal_stiffness - &beam.translational_mass) * phi
}

/// The scene's loads on an arm its hub holds (an ideal drive or a servo): gravity along the
/// drive's path, and the hub's peak acceleration.
fn held_at_the_hub(model: &Model, beam: &BeamModel) -> Vec<Load> {
    let states = JudgedStates::of(model);
    let peak = states.peak;
    let mut loads: Vec<Load> = states
        .path
        .iter()
        .map(|at| Load {
            name: format!("gravity at {:.0}°", at.angle_rad.to_degrees()),
            vector: gravity_at(model, beam, at.angle_rad),
            rate_rad_s: at.rate_rad_s,
        })
        .collect();
    loads.push(Load {
        name: "the hub's peak acceleration".into(),
        vector: peak.accel_rad_s2.abs() * &beam.coupling,
        rate_rad_s: peak.rate_rad_s,
    });
    loads
}

/// Gravity's load on the arm at hub angle `angle`, N.
fn gravity_at(model: &Model, beam: &BeamModel, angle: f64) -> nalgebra::DVector<f64> {
    let (s, c) = angle.sin_cos();
    -model.physics.gravity_m_s2 * (s * &beam.axial_mass + c * &beam.transverse_mass)
}

/// The scene's loads on an arm cylinders hold: gravity along the drive's path and the hub's
/// acceleration at its start and end angles, each with the cylinders' push that carries its
/// moment about the hub. A cylinder holds the arm at its pin, not at the hub, and pushes mostly along the arm
/// at the pin's offset: the push bends the arm against the load, the two cancel in part at the
/// tip, and the truncation's share of what is left is the larger. Several cylinders share the
/// moment as their pressures do: each pushes in proportion to its cap area.
fn held_at_the_pins(model: &Model, beam: &BeamModel, cylinders: &crate::actuator::Cylinders) -> Vec<Load> {
    let rotation = beam.arm_ride() * rigid_rotation(beam);
    let states = JudgedStates::of(model);
    let peak = states.peak;
    let mut loads = Vec::new();
    for (k, at) in states.path.iter().enumerate() {
        let angle = at.angle_rad;
        let (s, c) = angle.sin_cos();
        let mut push = nalgebra::DVector::zeros(rotation.len());
        for cylinder in &cylinders.each {
            let [x, y] = cylinder.arm_pin_m;
            let [u, v, slope] = beam.point_rows(x);
            let pin = cylinder.arm_pin_at_m(angle);
            let (dx, dy) = (pin[0] - cylinder.base_pin_m[0], pin[1] - cylinder.base_pin_m[1]);
            // The push's direction in the hub frame, per unit length of the cylinder.
            let length = dx.hypot(dy);
            let (along, across) = ((c * dx + s * dy) / length, (-s * dx + c * dy) / length);
            push += cylinder.cap_area_m2() * (along * (&u - y * &slope) + across * &v);
        }
        let lever = rotation.dot(&push);
        let deg = angle.to_degrees();
        let accel = peak.accel_rad_s2.abs() * &beam.coupling;
        let mut judged = vec![(format!("gravity at {deg:.0}°"), gravity_at(model, beam, angle), at.rate_rad_s)];
        // The acceleration peaks as the drive starts and stops: judged at its ends' angles.
        if k == 0 || k == PATH_INTERVALS {
            judged.push((format!("the hub's peak acceleration at {deg:.0}°"), accel, peak.rate_rad_s));
        }
        for (name, load, rate) in judged {
            let held = &load - (rotation.dot(&load) / lever) * &push;
            let pins = if cylinders.each.len() == 1 { "the cylinder's pin" } else { "the cylinders' pins" };
            loads.push(Load { name: format!("{name} held at {pins}"), vector: held, rate_rad_s: rate });
        }
    }
    loads
}

/// The arm's rigid rotation about the hub over its own DOFs: v = x and a unit slope at every
/// node (its elements' cubic shapes hold it exactly).
fn rigid_rotation(beam: &BeamModel) -> nalgebra::DVector<f64> {
    let mut shape = nalgebra::DVector::zeros(beam.arm_dofs());
    for (k, x) in beam.nodes_x_m.iter().skip(1).enumerate() {
        shape[3 * k + 1] = *x;
        shape[3 * k + 2] = 1.0;
    }
    shape
}

/// The error a held string at `kept` of its bending modes (0: rigid) expects on the arm's
/// headline quantities: the share of the moving mass in its modes left out, each amplified over
/// its static ride by r² / (1 − r²), r the arm's first frequency over the mode's (the hands move
/// at the arm's frequency; the modes left out lie above [`super::STRING_MODE_MARGIN`] times it,
/// so r ≤ 1/5 and the share each adds is at most 4 %). 0 without a flexible string.
pub fn string_truncation(beam: &BeamModel, arm_first_hz: f64, kept: usize) -> f64 {
    let (Some(member), Some(modes)) = (&beam.member, beam.member_modes()) else { return 0.0 };
    let own = member.own_dofs.clone();
    let ride = beam.transverse_mass.rows(own.start, own.len());
    let participation: Vec<f64> = (0..modes.len()).map(|j| modes.shapes.column(j).dot(&ride).powi(2)).collect();
    // (φⱼᵀ M ι)² is the mass mode j moves with when the hands translate (Σ over every mode: the
    // string's own DOFs' mass).
    let amplified: f64 = participation
        .iter()
        .zip(modes.frequencies_hz())
        .skip(kept)
        .map(|(p, f)| {
            let r2 = (arm_first_hz / f).powi(2);
            p * r2 / (1.0 - r2).max(f64::MIN_POSITIVE)
        })
        .sum();
    amplified / beam.total_mass_kg.max(f64::MIN_POSITIVE)
}
