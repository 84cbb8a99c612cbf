//! What a held string does during a run, read at every step: its deformed centreline, the
//! deflection of its far end, the bending stress at its hands, and the largest normal stress
//! along it, axial and bending, |N|/A + |M| c/I, at its stations.
//!
//! - A flexibly modelled string (`modal`, `fe`) is a beam of its own ([`crate::beam::MemberModel`]):
//!   the stress at a hand is σ = M c / I = E c |v″| on either side of the clamp, its root
//!   sections, where the bending moment of an overhang or of the span between the hands peaks.
//! - A `rigid` string rides on the arm's section at its centre. Its overhangs carry the
//!   d'Alembert and gravity loads of a rigid body: with f_n(d) = f_n(c) + ψ̈ d the specific
//!   force normal to the string at distance d from the centre (ψ the string's angle), an overhang
//!   of length a beyond a hand at d_h carries M = μ [f_n(d_h) a²/2 ± ψ̈ a³/3] at its root — the
//!   quasi-static moment a rigid string's user would compute by hand, with no ringing of its own.
//!
//! Stations along the string: a flexible string's every element end, both sides of each node
//! (σ = E |u′| + E c |v″| there); a rigid string's overhangs at tenths of their length, each
//! section carrying the overhang beyond it as a cantilever (M as above, N the d'Alembert and
//! gravity load along the string of the part beyond). A rigid string's span between two hands
//! is statically indeterminate on the hands and not represented: its hands carry its largest
//! moment under its own weight whenever the overhangs are longer than a fifth of the span.

use nalgebra::DVector;
use serde::Serialize;

use super::probe::ArmState;
use crate::arm::{ArmModel, StationRows};
use crate::channel::{Channel, Reading};
use crate::model::HeldString;

/// A held string's channels ([`crate::channel`]), plotted only: its far end's deflection
/// normal to the arm (m) and the largest bending stress at its hands (Pa); held by friction,
/// in the tables too, its slip along the arm (plotted) and how deep the jaws have sunk (m).
pub fn channels(held: &HeldString) -> Vec<Channel> {
    let mut out = vec![
        Channel::new("string.tip_deflection", "m", Reading::StringTipDeflection)
            .plotted("plots/string/tip_deflection", 1.0)
            .untabled(),
        Channel::new("string.bending_stress", "Pa", Reading::StringBendingStress)
            .plotted("plots/string/bending_stress", 1.0)
            .untabled(),
    ];
    if held.friction_clamp().is_some() {
        out.push(Channel::new("string_slip", "m", Reading::StringSlip).plotted("plots/string_slip", 1.0));
        out.push(Channel::new("jaw_sinking", "m", Reading::JawSinking));
    }
    out
}

/// A held string made ready to read: its rows computed once.
#[derive(Debug, Clone)]
pub struct StringProbe {
    /// Hub-frame x of the string's ends, m.
    ends_m: [f64; 2],
    /// E c: stress per unit curvature, Pa·m.
    stress_per_curvature_pa_m: f64,
    /// c / I: stress per unit moment, Pa/(N·m).
    stress_per_moment_pa_per_n_m: f64,
    /// E: stress per unit axial strain, Pa.
    youngs_modulus_pa: f64,
    /// 1 / A: stress per unit axial force, 1/m².
    per_axial_force_per_m2: f64,
    form: Form,
}

/// Tenths of each overhang of a rigid string at which its stress is read.
const OVERHANG_STATIONS: usize = 10;

#[derive(Debug, Clone)]
enum Form {
    /// A beam of its own: the deflection rows of centreline points and of its far end, and the
    /// curvature rows at its hands, over q.
    /// And its elements' ends (hub-frame x) with, per element, the rows of its axial strain and
    /// of its curvature at either end, row after row over q in `element_rows` (three rows an
    /// element: read with no allocation, every step).
    Flexible {
        centreline: Vec<(f64, DVector<f64>, DVector<f64>)>,
        tip_v: DVector<f64>,
        curvature: Vec<DVector<f64>>,
        ends_m: Vec<[f64; 2]>,
        element_rows: Vec<f64>,
    },
    /// Riding on the arm's section at its centre, with the overhang beyond each outermost hand.
    Rigid { centre_m: f64, rows: StationRows, mass_per_length_kg_m: f64, overhangs: Vec<Overhang> },
}

/// An overhang of a rigid string: its root at `root_d_m` from the centre, `length_m` long,
/// running outward (`+1`) or toward the pivot (`−1`), and the masses its connections add on it,
/// (distance from the root, kg).
#[derive(Debug, Clone)]
struct Overhang {
    root_d_m: f64,
    length_m: f64,
    direction: f64,
    added_masses: Vec<(f64, f64)>,
}

/// One step's reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StringReading {
    /// Deflection of the string's far end normal to the arm, hub frame, m.
    pub tip_deflection_m: f64,
    /// Largest bending stress at its hands, Pa.
    pub max_bending_stress_pa: f64,
}

/// Points of the centreline the recording draws.
const CENTRELINE_POINTS: usize = 26;

impl StringProbe {
    /// Prepares the probe for `held` on `arm` (a flexible string when the arm's beam carries it
    /// as a member, else the rigid one).
    pub fn new(held: &HeldString, arm: &ArmModel) -> Self {
        let p = &held.pipe.pipe;
        let (r_out, r_in) = (0.5 * p.outer_diameter_m, 0.5 * p.outer_diameter_m - p.wall_m);
        let second_moment_m4 = std::f64::consts::FRAC_PI_4 * (r_out.powi(4) - r_in.powi(4));
        let e = p.youngs_modulus_pa;
        let start = held.start_m();
        let ends_m = [start, start + held.pipe.length_m];
        let form = match &arm.beam.member {
            Some(member) => {
                let n = arm.beam.dofs();
                let project = |row: &DVector<f64>| arm.basis.tr_mul(row);
                let centreline = (0..CENTRELINE_POINTS)
                    .map(|i| {
                        let x = ends_m[0] + (ends_m[1] - ends_m[0]) * i as f64 / (CENTRELINE_POINTS - 1) as f64;
                        let [u, v, ..] = member.point_rows(x, n);
                        (x, project(&u), project(&v))
                    })
                    .collect();
                let tip_v = project(&member.point_rows(ends_m[1], n)[1]);
                let curvature = member.clamp_curvature_rows(n).iter().map(|(_, row)| project(row)).collect();
                let (mut ends, mut element_rows) = (Vec::new(), Vec::new());
                for (e, element) in member.elements.iter().enumerate() {
                    let [u0, .., kappa0] = member.element_rows(e, 0.0, n);
                    let [u1, .., kappa1] = member.element_rows(e, 1.0, n);
                    for row in [(u1 - u0) / element.length_m, kappa0, kappa1] {
                        element_rows.extend_from_slice(project(&row).as_slice());
                    }
                    ends.push([element.x0_m, element.x0_m + element.length_m]);
                }
                Form::Flexible { centreline, tip_v, curvature, ends_m: ends, element_rows }
            }
            None => {
                let centre_m = held.centre_m();
                let (first, last) = (&held.grips[0], held.palm());
                // The connections beyond each outermost hand, by their distance from it.
                let beyond = |at_m: f64, direction: f64| -> Vec<(f64, f64)> {
                    held.pipe
                        .connections
                        .iter()
                        .map(|c| (direction * (c.centre_m() - at_m), c.added_mass_kg))
                        .filter(|(s, _)| *s > 0.0)
                        .collect()
                };
                let overhangs = vec![
                    Overhang {
                        root_d_m: first.station_m - centre_m,
                        length_m: first.at_m,
                        direction: -1.0,
                        added_masses: beyond(first.at_m, -1.0),
                    },
                    Overhang {
                        root_d_m: last.station_m - centre_m,
                        length_m: held.pipe.length_m - last.at_m,
                        direction: 1.0,
                        added_masses: beyond(last.at_m, 1.0),
                    },
                ];
                Form::Rigid {
                    centre_m,
                    rows: arm.station_rows(centre_m),
                    mass_per_length_kg_m: p.mass_per_length_kg_m,
                    overhangs,
                }
            }
        };
        let area_m2 = std::f64::consts::PI * (r_out * r_out - r_in * r_in);
        StringProbe {
            ends_m,
            stress_per_curvature_pa_m: e * r_out,
            stress_per_moment_pa_per_n_m: r_out / second_moment_m4,
            youngs_modulus_pa: e,
            per_axial_force_per_m2: 1.0 / area_m2,
            form,
        }
    }

    /// Whether the string is a beam of its own in this run.
    pub fn is_flexible(&self) -> bool {
        matches!(self.form, Form::Flexible { .. })
    }

    /// The reading at `state` under gravity `g` (m/s²).
    pub fn read(&self, state: &ArmState, g: f64) -> StringReading {
        let (tip_deflection_m, max_bending_stress_pa) = match &self.form {
            Form::Flexible { tip_v, curvature, .. } => (
                tip_v.dot(state.q),
                curvature.iter().map(|row| self.stress_per_curvature_pa_m * row.dot(state.q).abs()).fold(0.0, f64::max),
            ),
            Form::Rigid { centre_m, rows, overhangs, .. } => {
                let [_, v, phi] = rows.displacement(state.q);
                let loads = self.rigid_loads(state, g);
                let root = overhangs.iter().map(|o| self.stress_per_moment_pa_per_n_m * loads.moment(o, 0.0).abs());
                (v + (self.ends_m[1] - centre_m) * phi, root.fold(0.0, f64::max))
            }
        };
        StringReading { tip_deflection_m, max_bending_stress_pa }
    }

    /// The largest |N|/A + |M| c/I over the stations at `state` under gravity `g`, Pa, and its
    /// station along the string from its hub-side end, m.
    pub fn peak_stress(&self, state: &ArmState, g: f64) -> [f64; 2] {
        let mut peak = [0.0, 0.0];
        self.each_stress(state, g, |(x, sigma)| {
            if sigma > peak[0] {
                peak = [sigma, x];
            }
        });
        peak
    }

    /// [`Self::peak_stress`] of a flexible string at every step of a run from its elastic
    /// coordinates `q_history` (`dofs` a step, one step after another), a few hundred steps at
    /// a time as one matrix product: a modal string's rows over q cost a tenth of the run read
    /// one step at a time. `None` for a rigid string, whose stations need the step's rates.
    pub fn peaks_over(&self, q_history: &[f64], dofs: usize) -> Option<Vec<[f64; 2]>> {
        const CHUNK: usize = 256;
        let Form::Flexible { ends_m, element_rows, .. } = &self.form else { return None };
        let rows = nalgebra::DMatrix::from_row_slice(3 * ends_m.len(), dofs, element_rows);
        let mut values = nalgebra::DMatrix::zeros(rows.nrows(), CHUNK);
        let mut peaks = Vec::with_capacity(q_history.len() / dofs.max(1));
        for chunk in q_history.chunks(CHUNK * dofs) {
            let steps = chunk.len() / dofs;
            let q = nalgebra::DMatrixView::from_slice(chunk, dofs, steps);
            values.columns_mut(0, steps).gemm(1.0, &rows, &q, 0.0);
            for k in 0..steps {
                let mut peak = [0.0, 0.0];
                for (ends, v) in ends_m.iter().zip(values.column(k).as_slice().chunks_exact(3)) {
                    let axial = self.youngs_modulus_pa * v[0].abs();
                    for (x, kappa) in ends.iter().zip(&v[1..]) {
                        let sigma = axial + self.stress_per_curvature_pa_m * kappa.abs();
                        if sigma > peak[0] {
                            peak = [sigma, x - self.ends_m[0]];
                        }
                    }
                }
                peaks.push(peak);
            }
        }
        Some(peaks)
    }

    /// |N|/A + |M| c/I at each of the string's stations at `state` under gravity `g`: (station
    /// along the string from its hub-side end, m; σ, Pa).
    pub fn stresses_pa(&self, state: &ArmState, g: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        self.each_stress(state, g, |station| out.push(station));
        out
    }

    /// Calls `f` with each station's (station, σ) as [`Self::stresses_pa`] gives them.
    fn each_stress(&self, state: &ArmState, g: f64, mut f: impl FnMut((f64, f64))) {
        match &self.form {
            Form::Flexible { ends_m, element_rows, .. } => {
                let q = state.q.as_slice();
                let dot = |row: &[f64]| row.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
                for (ends, rows) in ends_m.iter().zip(element_rows.chunks_exact(3 * q.len())) {
                    let (strain, kappa) = rows.split_at(q.len());
                    let axial = self.youngs_modulus_pa * dot(strain).abs();
                    for (x, row) in ends.iter().zip(kappa.chunks_exact(q.len())) {
                        f((x - self.ends_m[0], axial + self.stress_per_curvature_pa_m * dot(row).abs()));
                    }
                }
            }
            Form::Rigid { centre_m, overhangs, .. } => {
                let loads = self.rigid_loads(state, g);
                for o in overhangs {
                    for j in 0..=OVERHANG_STATIONS {
                        let s = o.length_m * j as f64 / OVERHANG_STATIONS as f64;
                        let sigma = self.stress_per_moment_pa_per_n_m * loads.moment(o, s).abs()
                            + self.per_axial_force_per_m2 * loads.axial(o, s).abs();
                        f((centre_m + o.root_d_m + o.direction * s - self.ends_m[0], sigma));
                    }
                }
            }
        }
    }

    /// A rigid string's loads per unit mass at `state`: what its overhangs carry.
    fn rigid_loads(&self, state: &ArmState, g: f64) -> RigidLoads {
        let Form::Rigid { centre_m, rows, mass_per_length_kg_m, .. } = &self.form else {
            unreachable!("only a rigid string has rigid loads")
        };
        let [u, v, phi] = rows.displacement(state.q);
        let [udd, vdd, phidd] = rows.displacement(state.qdd);
        let [ud, vd, phid] = rows.displacement(state.qd);
        let (w, alpha) = (state.hub.rate_rad_s, state.hub.accel_rad_s2);
        let (rx, ry) = (centre_m + u, v);
        let a = [udd - 2.0 * w * vd - alpha * ry - w * w * rx, vdd + 2.0 * w * ud + alpha * rx - w * w * ry];
        let (s, c) = state.hub.angle_rad.sin_cos();
        let f = [a[0] + g * s, a[1] + g * c];
        RigidLoads {
            f_normal: -phi.sin() * f[0] + phi.cos() * f[1],
            f_along: phi.cos() * f[0] + phi.sin() * f[1],
            psi_dd: alpha + phidd,
            psi_d_squared: (w + phid).powi(2),
            mass_per_length_kg_m: *mass_per_length_kg_m,
        }
    }

    /// The string's deformed centreline in the hub frame at `q`, m (its two ends for a rigid
    /// string, which stays straight).
    pub fn centreline_hub_m(&self, q: &DVector<f64>) -> Vec<[f64; 2]> {
        match &self.form {
            Form::Flexible { centreline, .. } => centreline.iter().map(|(x, u, v)| [x + u.dot(q), v.dot(q)]).collect(),
            Form::Rigid { centre_m, rows, .. } => {
                let [u, v, phi] = rows.displacement(q);
                self.ends_m.iter().map(|x| [x + u, v + (x - centre_m) * phi]).collect()
            }
        }
    }
}

/// A rigid string's specific loads (m/s², the d'Alembert force and gravity per unit mass) at its
/// centre, normal to it and along it, its angular acceleration and rate squared.
struct RigidLoads {
    f_normal: f64,
    f_along: f64,
    psi_dd: f64,
    psi_d_squared: f64,
    mass_per_length_kg_m: f64,
}

impl RigidLoads {
    /// The bending moment at `s` from overhang `o`'s root, carrying what lies beyond, N·m.
    fn moment(&self, o: &Overhang, s: f64) -> f64 {
        let (length, d) = (o.length_m - s, o.root_d_m + o.direction * s);
        let root = self.f_normal + self.psi_dd * d;
        let added: f64 = o
            .added_masses
            .iter()
            .filter(|(at, _)| *at > s)
            .map(|(at, m)| m * (root + o.direction * self.psi_dd * (at - s)) * (at - s))
            .sum();
        self.mass_per_length_kg_m * (root * length.powi(2) / 2.0 + o.direction * self.psi_dd * length.powi(3) / 3.0)
            + added
    }

    /// The axial force at `s` from overhang `o`'s root, carrying what lies beyond: the load along
    /// the string less the centripetal ψ̇² r of each part, N.
    fn axial(&self, o: &Overhang, s: f64) -> f64 {
        let along = |distance_from_root: f64| {
            let d = o.root_d_m + o.direction * distance_from_root;
            self.f_along - self.psi_d_squared * d
        };
        let length = o.length_m - s;
        let added: f64 = o.added_masses.iter().filter(|(at, _)| *at > s).map(|(at, m)| m * along(*at)).sum();
        self.mass_per_length_kg_m * length * along(s + 0.5 * length) + added
    }
}

/// How the held string fared: the summary's `string` object.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StringSummary {
    /// What it is: the catalogue row ("9-5/8 casing 47.00 lb/ft") or its own pipe's section.
    pub pipe: String,
    /// Its trade size, or `custom`.
    pub size: String,
    /// Its nominal weight, lb/ft (a catalogue row's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weight_lb_ft: Option<f64>,
    /// Its steel grade, if one was chosen.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grade: Option<String>,
    /// Its joints, when it is made of joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joints: Option<usize>,
    /// The mass of one of its joints with its connection, kg (when it is made of joints).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_mass_kg: Option<f64>,
    /// Its fidelity (`rigid`, `modal(n)`, `fe`).
    pub model: String,
    /// Why that fidelity.
    pub model_reason: String,
    /// The error `auto` expects of it on the arm's headline quantities (absent when set by hand).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_expected_error: Option<crate::select::ExpectedError>,
    /// Its first three bending frequencies held in its hands (the hands fixed), Hz, whatever
    /// fidelity ran.
    pub frequencies_hz: Vec<f64>,
    /// Largest bending stress at its hands, σ = M c / I, Pa.
    pub max_bending_stress_pa: f64,
    /// When, s.
    pub max_bending_stress_time_s: f64,
    /// Largest |deflection| of its far end normal to the arm, hub frame, m.
    pub max_tip_deflection_m: f64,
    /// The minimum yield strength of its steel, Pa, where its grade (or its own pipe) gives one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_strength_pa: Option<f64>,
    /// Its largest bending stress over that yield strength.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_to_yield: Option<f64>,
    /// Largest normal stress along it, |N|/A + |M| c/I over its stations (module doc), Pa.
    pub peak_stress_pa: f64,
    /// Where, along the string from its hub-side end, m.
    pub peak_stress_station_m: f64,
    /// When, s.
    pub peak_stress_time_s: f64,
    /// `peak_stress_pa` over the yield strength.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_stress_to_yield: Option<f64>,
}

/// A held string's readings over a run, one per step.
pub struct StringSeries<'a> {
    /// Times, s.
    pub t_s: &'a [f64],
    /// Deflection of its far end, m.
    pub tip_deflection_m: &'a [f64],
    /// Largest bending stress at its hands, Pa.
    pub stress_pa: &'a [f64],
    /// Largest stress along it, Pa, and where, m.
    pub peak_stress: &'a [[f64; 2]],
}

impl StringSummary {
    /// The summary of a run's string at the fidelity chosen as `choice` says, from its
    /// `readings`, with its frequencies in its hands as compiled
    /// ([`crate::run::CompiledModel::string_frequencies_hz`]).
    pub fn of(
        model: &crate::model::Model,
        frequencies_hz: &[f64],
        choice: crate::select::Choice,
        readings: &StringSeries,
    ) -> Self {
        let (t_s, tip_deflection_m, stress_pa) = (readings.t_s, readings.tip_deflection_m, readings.stress_pa);
        let frequencies_hz = frequencies_hz.to_vec();
        let yield_strength_pa = model.payload.string().and_then(|held| held.pipe.pipe.yield_strength_pa);

        let (i, stress) =
            stress_pa.iter().enumerate().fold((0, 0.0_f64), |best, (i, s)| if *s > best.1 { (i, *s) } else { best });
        let (k, peak) = readings
            .peak_stress
            .iter()
            .enumerate()
            .fold((0, [0.0, 0.0]), |best, (k, p)| if p[0] > best.1[0] { (k, *p) } else { best });
        let held = model.payload.string().expect("a string summary is of a held string");
        let (pipe, joints) = (&held.pipe.pipe, held.pipe.joints);
        StringSummary {
            pipe: pipe.label.clone(),
            size: pipe.size.clone(),
            weight_lb_ft: pipe.row.map(|r| r.nominal_weight_lb_ft),
            grade: pipe.grade.map(str::to_string),
            joints: joints.map(|j| j.count),
            joint_mass_kg: joints.map(|j| held.pipe.mass_kg() / j.count as f64),
            model: choice.fidelity.to_string(),
            model_reason: choice.reason,
            model_expected_error: choice.expected,
            frequencies_hz: frequencies_hz.into_iter().take(3).collect(),
            max_bending_stress_pa: stress,
            max_bending_stress_time_s: t_s.get(i).copied().unwrap_or(0.0),
            max_tip_deflection_m: tip_deflection_m.iter().map(|d| d.abs()).fold(0.0, f64::max),
            yield_strength_pa,
            stress_to_yield: yield_strength_pa.map(|y| stress / y),
            peak_stress_pa: peak[0],
            peak_stress_station_m: peak[1],
            peak_stress_time_s: t_s.get(k).copied().unwrap_or(0.0),
            peak_stress_to_yield: yield_strength_pa.map(|y| peak[0] / y),
        }
    }
}
