//! A run's sign-off figures from its per-step readings: the peak stress and utilisation of each
//! segment, the fatigue damage of the lift at each segment's most loaded station and at each
//! strain gauge, and the peak loads on the pivot, the cylinder's pin and the hands.

use serde::Serialize;

use super::{Fibre, StressSeries};
use crate::fatigue::LiftDamage;
use crate::model::Model;
use crate::run::SensorSeries;
use crate::sensor::SensorKind;

/// How the stresses were recovered, as the summary states it.
pub const METHOD: &str = "force summation";

/// The arm's stresses: `stress` in the summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressSummary {
    /// How the section forces were recovered.
    pub method: &'static str,
    /// The design factor on stress (`[checks] stress_factor`), applied to utilisation and to the
    /// fatigue ranges.
    pub stress_factor: f64,
    /// Largest |σ| at an outer fibre anywhere along the arm, Pa (unfactored).
    pub peak_stress_pa: f64,
    /// Where: station, m.
    pub peak_station_m: f64,
    /// Which fibre.
    pub peak_fibre: Fibre,
    /// When, s.
    pub peak_time_s: f64,
    /// Largest utilisation, stress_factor × |σ| / yield, over the segments with a yield strength
    /// (`None` without one: `utilisation_note` says why).
    pub utilisation: Option<f64>,
    /// Where, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilisation_station_m: Option<f64>,
    /// Which fibre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilisation_fibre: Option<Fibre>,
    /// When, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilisation_time_s: Option<f64>,
    /// Why some or all segments have no utilisation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilisation_note: Option<String>,
    /// Per segment, hub outwards.
    pub segments: Vec<SegmentStress>,
}

/// One segment's stresses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentStress {
    /// Where it starts and ends along the arm, m.
    pub from_m: f64,
    /// Its outer end, m.
    pub to_m: f64,
    /// Largest |σ| at its outer fibres, Pa.
    pub peak_stress_pa: f64,
    /// Where, m.
    pub peak_station_m: f64,
    /// Which fibre.
    pub peak_fibre: Fibre,
    /// When, s.
    pub peak_time_s: f64,
    /// Largest σ (tension), Pa.
    pub max_stress_pa: f64,
    /// Smallest σ (compression), Pa.
    pub min_stress_pa: f64,
    /// Its yield strength, Pa.
    pub yield_strength_pa: Option<f64>,
    /// Where the yield strength comes from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_source: Option<String>,
    /// stress_factor × peak |σ| / yield.
    pub utilisation: Option<f64>,
}

/// Fatigue of one lift: `fatigue` in the summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FatigueSummary {
    /// The largest damage of the lift over the places checked (`None`: no place has an S–N
    /// curve, `note` says why).
    pub damage_per_lift: Option<f64>,
    /// Lifts to failure there, 1 / damage (`None` if the lift does no damage).
    pub lifts_to_failure: Option<f64>,
    /// The worst place, as in `places`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst: Option<String>,
    /// Why a place is not checked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Each place checked.
    pub places: Vec<FatiguePlace>,
}

/// The damage of one lift at one place.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FatiguePlace {
    /// `segment <i>` (its most loaded station) or `gauge <name>`.
    pub place: String,
    /// The S–N curve.
    pub curve: String,
    /// Station, m.
    pub station_m: f64,
    /// Fibre (the gauge's face for a gauge: upper).
    pub fibre: Fibre,
    /// The damage.
    #[serde(flatten)]
    pub damage: LiftDamage,
}

/// Peak loads on the pins and hands: `pins` in the summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PinSummary {
    /// The pivot's force on the arm.
    pub pivot: PinPeak,
    /// The cylinder's rod force on the arm's pin (absent without a cylinder); of several, the
    /// most loaded pin's (each is in `cylinders`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cylinder: Option<PinPeak>,
    /// The cylinder's force on its base pin's bracket: the arm pin's reversed (the cylinder is a
    /// massless two-force member), its arm-frame components in the arm's frame at the time.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cylinder_base: Option<PinPeak>,
    /// Of several cylinders, each one's rod force on its arm pin, in the URDF's order (its base
    /// pin's is the same reversed); absent for one.
    #[serde(skip_serializing_if = "few")]
    pub cylinders: Vec<PinPeak>,
    /// The string's load on each hand (a flexible string's through its own bending; a rigid
    /// string's on hands read as pins, docs/sign-off.md), none without a string.
    pub hands: Vec<HandPeak>,
}

/// Whether a list has no more than one entry (one cylinder's pin is `cylinder` alone).
fn few(list: &[PinPeak]) -> bool {
    list.len() <= 1
}

/// The peak of a pin force.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PinPeak {
    /// Largest magnitude, N.
    pub peak_force_n: f64,
    /// When, s.
    pub peak_time_s: f64,
    /// Its world components then (X horizontal, Y up), N.
    pub world_n: [f64; 2],
    /// Its components in the arm's frame then (along the arm, across it), N.
    pub arm_n: [f64; 2],
}

/// The peak grip of a hand on the string.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HandPeak {
    /// The hand (URDF link).
    pub hand: String,
    /// Largest force of the hand on the string, N.
    pub peak_force_n: f64,
    /// When, s.
    pub peak_force_time_s: f64,
    /// Largest moment of the hand on the string, N·m.
    pub peak_moment_n_m: f64,
    /// When, s.
    pub peak_moment_time_s: f64,
}

/// Everything at once: the summary's `stress`, `fatigue` and `pins`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignOff {
    /// Stresses and utilisation.
    pub stress: StressSummary,
    /// Fatigue of the lift.
    pub fatigue: FatigueSummary,
    /// Pin and hand loads.
    pub pins: PinSummary,
}

/// One run's readings at its times and hub angles.
pub struct Readings<'a> {
    /// The readings and their layout.
    pub series: &'a StressSeries,
    /// Times, s.
    pub t_s: &'a [f64],
    /// Hub angle per step, rad.
    pub hub_angle_rad: &'a [f64],
}

impl Readings<'_> {
    fn width(&self) -> usize {
        self.series.width
    }

    fn steps(&self) -> usize {
        self.series.steps()
    }

    fn value(&self, k: usize, at: usize) -> f64 {
        self.series.values[k * self.width() + at].into()
    }

    /// σ at station `i`, `fibre`, step `k`, Pa.
    pub fn stress_pa(&self, i: usize, fibre: Fibre, k: usize) -> f64 {
        self.series.stress_pa(i, fibre, k)
    }

    /// σ at station `i`, `fibre` over the run, Pa.
    pub fn history_pa(&self, i: usize, fibre: Fibre) -> Vec<f64> {
        (0..self.steps()).map(|k| self.stress_pa(i, fibre, k)).collect()
    }

    /// The first step at which |σ| at station `i`, `fibre` reaches `peak_abs`.
    fn step_of_peak(&self, i: usize, fibre: Fibre, peak_abs: f64) -> usize {
        (0..self.steps()).find(|&k| self.stress_pa(i, fibre, k).abs() >= peak_abs).unwrap_or(0)
    }

    /// Per station, the largest and smallest σ over both fibres and the run, Pa: the stress
    /// envelope along the arm.
    pub fn envelope(&self) -> Vec<(f64, f64, f64)> {
        self.series
            .stations
            .iter()
            .zip(self.series.extremes())
            .map(|(station, [u, l])| (station.station_m, u.max.max(l.max), u.min.min(l.min)))
            .collect()
    }

    fn time(&self, k: usize) -> f64 {
        self.t_s.get(k).copied().unwrap_or(0.0)
    }

    /// A force pair at offset `at` of each step, its peak magnitude, and its components then in
    /// the hub frame (`hub_frame`) or the world's.
    fn force_peak(&self, at: usize, hub_frame: bool) -> PinPeak {
        let (mut best, mut best_k) = (0.0, 0);
        for k in 0..self.steps() {
            let (x, y) = (self.value(k, at), self.value(k, at + 1));
            let squared = x * x + y * y;
            if squared > best {
                (best, best_k) = (squared, k);
            }
        }
        let best = best.sqrt();
        let (s, c) = self.hub_angle_rad.get(best_k).copied().unwrap_or(0.0).sin_cos();
        let (fx, fy) =
            if self.steps() == 0 { (0.0, 0.0) } else { (self.value(best_k, at), self.value(best_k, at + 1)) };
        let (world_n, arm_n) = if hub_frame {
            ([c * fx - s * fy, s * fx + c * fy], [fx, fy])
        } else {
            ([fx, fy], [c * fx + s * fy, -s * fx + c * fy])
        };
        PinPeak { peak_force_n: best, peak_time_s: self.time(best_k), world_n, arm_n }
    }
}

/// The sign-off of `model`'s run from its `series`, with the scenario's design factor.
pub fn sign_off_run(model: &Model, series: &crate::run::Series) -> SignOff {
    let readings = Readings { series: &series.stress, t_s: &series.t_s, hub_angle_rad: &series.hub_angle_rad };
    sign_off(model, &readings, &series.sensors, model.checks.stress_factor)
}

/// The sign-off of `model`'s run from its `readings`, its sensors' series, with the design
/// factor `stress_factor`.
pub fn sign_off(model: &Model, readings: &Readings, sensors: &[SensorSeries], stress_factor: f64) -> SignOff {
    let segments = &model.robot.arm.segments;
    let stations = &readings.series.stations;
    let extremes = &readings.series.extremes();
    let mut from = 0.0;
    let mut segment_stress = Vec::new();
    let mut fatigue_places = Vec::new();
    let mut notes = Vec::new();
    for (s, segment) in segments.iter().enumerate() {
        let to = from + segment.length_m;
        let mine: Vec<usize> = (0..stations.len()).filter(|&i| stations[i].segment == s).collect();
        let mut peak = (0.0, 0, Fibre::Upper);
        let (mut max, mut min) = (f64::MIN, f64::MAX);
        let mut widest = (f64::MIN, 0, Fibre::Upper);
        for &i in &mine {
            for (f, fibre) in Fibre::BOTH.iter().enumerate() {
                let e = extremes[i][f];
                if e.peak_abs() > peak.0 {
                    peak = (e.peak_abs(), i, *fibre);
                }
                max = max.max(e.max);
                min = min.min(e.min);
                if e.max - e.min > widest.0 {
                    widest = (e.max - e.min, i, *fibre);
                }
            }
        }
        let peak_step = readings.step_of_peak(peak.1, peak.2, peak.0);
        let checks = segment.checks;
        let thickness = crate::steel::nominal_thickness_m(&segment.section);
        let utilisation = checks.yield_strength.map(|y| stress_factor * peak.0 / y.strength_pa);
        if checks.yield_strength.is_none() {
            notes.push(format!(
                "segment {s} has no yield strength (yield_strength_pa or steel on its <pipearm:segment>)"
            ));
        }
        segment_stress.push(SegmentStress {
            from_m: from,
            to_m: to,
            peak_stress_pa: peak.0,
            peak_station_m: stations.get(peak.1).map_or(from, |st| st.station_m),
            peak_fibre: peak.2,
            peak_time_s: readings.time(peak_step),
            max_stress_pa: max,
            min_stress_pa: min,
            yield_strength_pa: checks.yield_strength.map(|y| y.strength_pa),
            yield_source: checks.yield_strength.map(|y| y.describe(thickness)),
            utilisation,
        });
        // Rainflow at the station and fibre whose stress spans the widest range in the run.
        if let (Some(curve), false) = (checks.sn_curve, mine.is_empty()) {
            let (_, i, fibre) = widest;
            let history = readings.history_pa(i, fibre);
            fatigue_places.push(FatiguePlace {
                place: format!("segment {s}"),
                curve: curve.describe(),
                station_m: stations[i].station_m,
                fibre,
                damage: LiftDamage::of(&history, &curve, stress_factor),
            });
        }
        from = to;
    }
    let mut fatigue_notes: Vec<String> = segments
        .iter()
        .enumerate()
        .filter(|(_, seg)| seg.checks.sn_curve.is_none())
        .map(|(s, _)| format!("segment {s} has no S-N curve (detail or curve on its <pipearm:segment>)"))
        .collect();
    for series in sensors {
        let SensorKind::StrainGauge { station_m, .. } = series.sensor.kind else { continue };
        let s = segment_index(model, station_m);
        match segments[s].checks.sn_curve {
            Some(curve) => {
                let history: Vec<f64> = series.values.iter().map(|v| v[1]).collect();
                fatigue_places.push(FatiguePlace {
                    place: format!("gauge {}", series.sensor.name),
                    curve: curve.describe(),
                    station_m,
                    fibre: Fibre::Upper,
                    damage: LiftDamage::of(&history, &curve, stress_factor),
                });
            }
            None => {
                fatigue_notes.push(format!("gauge {} sits on segment {s}, which has no S-N curve", series.sensor.name))
            }
        }
    }
    let stress = overall_stress(&segment_stress, stress_factor, notes);
    let fatigue = overall_fatigue(fatigue_places, fatigue_notes);
    let pins = pins(readings);
    SignOff { stress, fatigue, pins }
}

/// The segment holding arm station `station_m` (at a joint, the outboard one; at the tip, the last).
pub fn segment_index(model: &Model, station_m: f64) -> usize {
    let segments = &model.robot.arm.segments;
    let mut end = 0.0;
    for (s, segment) in segments.iter().enumerate() {
        end += segment.length_m;
        if station_m < end {
            return s;
        }
    }
    segments.len() - 1
}

fn overall_stress(segments: &[SegmentStress], stress_factor: f64, notes: Vec<String>) -> StressSummary {
    let peak =
        segments.iter().max_by(|a, b| a.peak_stress_pa.total_cmp(&b.peak_stress_pa)).expect("an arm has segments");
    let worst = segments
        .iter()
        .filter(|s| s.utilisation.is_some())
        .max_by(|a, b| a.utilisation.unwrap_or(0.0).total_cmp(&b.utilisation.unwrap_or(0.0)));
    let note = if notes.is_empty() {
        None
    } else if worst.is_none() {
        Some(format!("no utilisation: {}", notes.join("; ")))
    } else {
        Some(notes.join("; "))
    };
    StressSummary {
        method: METHOD,
        stress_factor,
        peak_stress_pa: peak.peak_stress_pa,
        peak_station_m: peak.peak_station_m,
        peak_fibre: peak.peak_fibre,
        peak_time_s: peak.peak_time_s,
        utilisation: worst.and_then(|s| s.utilisation),
        utilisation_station_m: worst.map(|s| s.peak_station_m),
        utilisation_fibre: worst.map(|s| s.peak_fibre),
        utilisation_time_s: worst.map(|s| s.peak_time_s),
        utilisation_note: note,
        segments: segments.to_vec(),
    }
}

fn overall_fatigue(places: Vec<FatiguePlace>, notes: Vec<String>) -> FatigueSummary {
    let worst = places.iter().max_by(|a, b| a.damage.damage_per_lift.total_cmp(&b.damage.damage_per_lift));
    let note = if notes.is_empty() {
        None
    } else if places.is_empty() {
        Some(format!("no fatigue check: {}", notes.join("; ")))
    } else {
        Some(notes.join("; "))
    };
    FatigueSummary {
        damage_per_lift: worst.map(|p| p.damage.damage_per_lift),
        lifts_to_failure: worst.and_then(|p| p.damage.lifts_to_failure),
        worst: worst.map(|p| p.place.clone()),
        note,
        places,
    }
}

fn pins(readings: &Readings) -> PinSummary {
    let series = readings.series;
    let hands = series
        .hands
        .iter()
        .map(|(hand, at)| {
            let (mut force, mut moment) = ((0.0, 0), (0.0, 0));
            for k in 0..readings.steps() {
                let (x, y) = (readings.value(k, *at), readings.value(k, at + 1));
                let squared = x * x + y * y;
                let m = readings.value(k, at + 2).abs();
                if squared > force.0 {
                    force = (squared, k);
                }
                if m > moment.0 {
                    moment = (m, k);
                }
            }
            let force = (force.0.sqrt(), force.1);
            HandPeak {
                hand: hand.clone(),
                peak_force_n: force.0,
                peak_force_time_s: readings.time(force.1),
                peak_moment_n_m: moment.0,
                peak_moment_time_s: readings.time(moment.1),
            }
        })
        .collect();
    let cylinders: Vec<PinPeak> = series.cylinder_indices.iter().map(|&at| readings.force_peak(at, false)).collect();
    let cylinder = cylinders.iter().max_by(|a, b| a.peak_force_n.total_cmp(&b.peak_force_n)).cloned();
    let cylinder_base = cylinder.as_ref().map(|pin| PinPeak {
        world_n: pin.world_n.map(|f| -f),
        arm_n: pin.arm_n.map(|f| -f),
        ..pin.clone()
    });
    let cylinders = if cylinders.len() > 1 { cylinders } else { Vec::new() };
    PinSummary { pivot: readings.force_peak(series.pivot_index, true), cylinder, cylinder_base, cylinders, hands }
}
