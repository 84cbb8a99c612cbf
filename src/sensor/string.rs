//! What a held string does during a run, read at every step: its deformed centreline, the
//! deflection of its far end, and the bending stress at its hands.
//!
//! - A flexibly modelled string (`modal`, `fe`) is a beam of its own ([`crate::beam::MemberModel`]):
//!   the stress at a hand is σ = M c / I = E c |v″| on either side of the clamp, its root
//!   sections, where the bending moment of an overhang or of the span between the hands peaks.
//! - A `rigid` string rides on the arm's section at its centre. Its overhangs carry the
//!   d'Alembert and gravity loads of a rigid body: with f_n(d) = f_n(c) + ψ̈ d the specific
//!   force normal to the string at distance d from the centre (ψ the string's angle), an overhang
//!   of length a beyond a hand at d_h carries M = μ [f_n(d_h) a²/2 ± ψ̈ a³/3] at its root — the
//!   quasi-static moment a rigid string's user would compute by hand, with no ringing of its own.

use nalgebra::DVector;
use serde::Serialize;

use super::probe::ArmState;
use crate::arm::{ArmModel, StationRows};
use crate::model::HeldString;

/// A held string made ready to read: its rows computed once.
#[derive(Debug, Clone)]
pub struct StringProbe {
    /// Hub-frame x of the string's ends, m.
    ends_m: [f64; 2],
    /// E c: stress per unit curvature, Pa·m.
    stress_per_curvature_pa_m: f64,
    /// c / I: stress per unit moment, Pa/(N·m).
    stress_per_moment_pa_per_n_m: f64,
    form: Form,
}

#[derive(Debug, Clone)]
enum Form {
    /// A beam of its own: the deflection rows of centreline points and of its far end, and the
    /// curvature rows at its hands, over q.
    Flexible { centreline: Vec<(f64, DVector<f64>, DVector<f64>)>, tip_v: DVector<f64>, curvature: Vec<DVector<f64>> },
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
                Form::Flexible { centreline, tip_v, curvature }
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
        StringProbe {
            ends_m,
            stress_per_curvature_pa_m: e * r_out,
            stress_per_moment_pa_per_n_m: r_out / second_moment_m4,
            form,
        }
    }

    /// Whether the string is a beam of its own in this run.
    pub fn is_flexible(&self) -> bool {
        matches!(self.form, Form::Flexible { .. })
    }

    /// The reading at `state` under gravity `g` (m/s²).
    pub fn read(&self, state: &ArmState, g: f64) -> StringReading {
        match &self.form {
            Form::Flexible { tip_v, curvature, .. } => StringReading {
                tip_deflection_m: tip_v.dot(state.q),
                max_bending_stress_pa: curvature
                    .iter()
                    .map(|row| self.stress_per_curvature_pa_m * row.dot(state.q).abs())
                    .fold(0.0, f64::max),
            },
            Form::Rigid { centre_m, rows, mass_per_length_kg_m, overhangs } => {
                let [_, v, phi] = rows.displacement(state.q);
                let [udd, vdd, phidd] = rows.displacement(state.qdd);
                let [ud, vd, _] = rows.displacement(state.qd);
                let [u, ..] = rows.displacement(state.q);
                let (w, alpha) = (state.hub.rate_rad_s, state.hub.accel_rad_s2);
                let (rx, ry) = (centre_m + u, v);
                let a = [udd - 2.0 * w * vd - alpha * ry - w * w * rx, vdd + 2.0 * w * ud + alpha * rx - w * w * ry];
                let (s, c) = state.hub.angle_rad.sin_cos();
                let f = [a[0] + g * s, a[1] + g * c];
                let f_normal = -phi.sin() * f[0] + phi.cos() * f[1];
                let psi_dd = alpha + phidd;
                let moment = |o: &Overhang| {
                    let root = f_normal + psi_dd * o.root_d_m;
                    let added: f64 =
                        o.added_masses.iter().map(|(s, m)| m * (root + o.direction * psi_dd * s) * s).sum();
                    mass_per_length_kg_m
                        * (root * o.length_m.powi(2) / 2.0 + o.direction * psi_dd * o.length_m.powi(3) / 3.0)
                        + added
                };
                StringReading {
                    tip_deflection_m: v + (self.ends_m[1] - centre_m) * phi,
                    max_bending_stress_pa: overhangs
                        .iter()
                        .map(|o| self.stress_per_moment_pa_per_n_m * moment(o).abs())
                        .fold(0.0, f64::max),
                }
            }
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
}

impl StringSummary {
    /// The summary of a run's string at `fidelity` chosen as `choice` says, from its readings at
    /// times `t_s`. The frequencies are those of the run's beam where it holds the string as a
    /// beam of its own (every fixed-interface mode is solved whatever the kept count), else of
    /// `model`'s fe string.
    pub fn of(
        model: &crate::model::Model,
        beam: &crate::beam::BeamModel,
        choice: crate::select::Choice,
        t_s: &[f64],
        tip_deflection_m: &[f64],
        stress_pa: &[f64],
    ) -> Result<Self, crate::beam::BeamError> {
        let frequencies_hz = match beam.member_modes() {
            Some(modes) => modes.frequencies_hz(),
            None => {
                let spec = model.beam_spec_with_string(Some(crate::arm::Fidelity::Fe))?;
                crate::beam::BeamModel::new(spec)?.member_modes().map(|m| m.frequencies_hz()).unwrap_or_default()
            }
        };
        let yield_strength_pa = model.payload.string().and_then(|held| held.pipe.pipe.yield_strength_pa);

        let (i, stress) =
            stress_pa.iter().enumerate().fold((0, 0.0_f64), |best, (i, s)| if *s > best.1 { (i, *s) } else { best });
        let held = model.payload.string().expect("a string summary is of a held string");
        let (pipe, joints) = (&held.pipe.pipe, held.pipe.joints);
        Ok(StringSummary {
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
        })
    }
}
