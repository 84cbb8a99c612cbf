//! What a run does to the machine: the normal stress at the outer fibres of every section along
//! the arm, its utilisation against the steel's yield, the loads on the pivot, the cylinder's pin
//! and the hands, and the fatigue damage of one lift (`docs/sign-off.md`).
//!
//! - [`recovery`]: section forces, pivot and hand loads by force summation, every step.
//! - [`fibres`]: σ = N/A ± M c/I at a section's upper and lower fibres.
//! - [`summary`]: the run's peaks, utilisation, pin loads and fatigue, from the series.
//! - [`chart`]: the stress envelope along the arm, as an SVG.

mod beside;
mod channels;
pub mod chart;
pub mod fibres;
pub mod forms;
pub mod recovery;
pub mod summary;

use std::sync::Arc;

use nalgebra::DVector;

use crate::actuator::{Actuator, Cylinder};
use crate::arm::{ArmModel, ArmSample};
use crate::model::Model;
use crate::point_load::{Hub, PointLoad, World};
use crate::scene::{Scene, Side as PairSide};
use crate::sensor::probe::ArmState;

pub use crate::robot::{SegmentChecks, YieldSource, YieldStrength};
pub use channels::PINS_ENTITY;
pub use fibres::{Fibre, Fibres};
pub use recovery::{SectionRecovery, Station};
pub use summary::{FatigueSummary, PinSummary, Readings, SignOff, StressSummary, sign_off, sign_off_run};

/// The per-step reading of the run's stresses and pin loads. The step's thread records what the
/// recovery reads of each step; a chunk of steps at a time is completed beside it ([`beside`]).
#[derive(Debug)]
pub struct StressProbe {
    /// The recovery of section forces.
    pub recovery: Arc<SectionRecovery>,
    /// The outer fibres of each station's section.
    pub fibres: Vec<Fibres>,
    /// Each cylinder and its pin's rows over q.
    cylinders: Vec<(Cylinder, [DVector<f64>; 2])>,
    /// The step's force on each cylinder's pin, world X, Y, N (kept for its room).
    pins_world_n: Vec<[f64; 2]>,
    recorded: beside::Recorded,
    on_arm: Vec<PointLoad<Hub>>,
    on_string: Vec<PointLoad<Hub>>,
    gravity_m_s2: f64,
    /// Where the recorded chunks are completed: a worker once one is started; here, by
    /// `completer`, where none is.
    worker: Option<beside::Worker>,
    completer: Option<beside::Completer>,
    worker_tried: bool,
}

/// Values per step and cylinder after the recovery's: its pin's force on the arm, world X, Y, N.
pub const CYLINDER_VALUES: usize = 2;

/// A station of a run's stress series: where, on which segment, and its fibres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesStation {
    /// Station along the arm, m.
    pub station_m: f64,
    /// Its segment.
    pub segment: usize,
    /// Its section's fibres.
    pub fibres: Fibres,
}

/// A run's stress and pin readings per step, and what each value is.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StressSeries {
    /// `width` values per step, one step after another: the axial force of each station (N),
    /// then the bending moment of each (N·m), the pivot's force on the arm (hub frame, N), per
    /// hand of the held string its load on the hand (hub frame x, y, N; moment, N·m), the
    /// cylinder pins' forces (world, N). Read a station's through [`Self::section_forces`].
    /// Single precision (seven digits): a run's histories at every section are its largest
    /// series, and the extremes are taken in double precision as they are read.
    pub values: Vec<f32>,
    /// Values per step.
    pub width: usize,
    /// The stations, hub outwards.
    pub stations: Vec<SeriesStation>,
    /// Where the pivot's force starts in a step's values.
    pub pivot_index: usize,
    /// Each hand of the held string and where its load starts.
    pub hands: Vec<(String, usize)>,
    /// Where each cylinder pin's force starts (none without cylinders).
    pub cylinder_indices: Vec<usize>,
    running: RunningExtremes,
}

/// The largest and smallest σ at each station's fibres over the steps read, Pa: one array per
/// fibre and bound, so that a step's stations are compared a vector's width at a time.
#[derive(Debug, Clone, PartialEq, Default)]
struct RunningExtremes {
    per_axial_force_per_m2: Vec<f64>,
    per_moment_per_m3: Vec<f64>,
    /// Upper fibre, then lower.
    max: [Vec<f64>; 2],
    min: [Vec<f64>; 2],
}

impl RunningExtremes {
    fn new(stations: &[SeriesStation]) -> Self {
        let none = |v: f64| vec![v; stations.len()];
        RunningExtremes {
            per_axial_force_per_m2: stations.iter().map(|s| s.fibres.per_axial_force_per_m2).collect(),
            per_moment_per_m3: stations.iter().map(|s| s.fibres.per_moment_per_m3).collect(),
            max: [none(Extremes::NONE.max), none(Extremes::NONE.max)],
            min: [none(Extremes::NONE.min), none(Extremes::NONE.min)],
        }
    }

    /// Takes the σ of one step whose stations carry `axial` and `moment`.
    fn take(&mut self, axial: &[f64], moment: &[f64]) {
        let n = axial.len();
        let (moment, per_axial, per_moment) =
            (&moment[..n], &self.per_axial_force_per_m2[..n], &self.per_moment_per_m3[..n]);
        let [max_upper, max_lower] = self.max.each_mut().map(|v| &mut v[..n]);
        let [min_upper, min_lower] = self.min.each_mut().map(|v| &mut v[..n]);
        for i in 0..n {
            let axial = axial[i] * per_axial[i];
            let bending = moment[i] * per_moment[i];
            let (upper, lower) = (axial + bending, axial - bending);
            // Written as selects, not `f64::max`, so that they compile to vector max/min.
            max_upper[i] = if upper > max_upper[i] { upper } else { max_upper[i] };
            min_upper[i] = if upper < min_upper[i] { upper } else { min_upper[i] };
            max_lower[i] = if lower > max_lower[i] { lower } else { max_lower[i] };
            min_lower[i] = if lower < min_lower[i] { lower } else { min_lower[i] };
        }
    }

    fn at(&self, i: usize) -> [Extremes; 2] {
        [0, 1].map(|f| Extremes { max: self.max[f][i], min: self.min[f][i] })
    }
}

/// The largest and smallest σ at a station's fibre, Pa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Largest σ.
    pub max: f64,
    /// Smallest σ.
    pub min: f64,
}

impl Extremes {
    /// None yet.
    pub const NONE: Extremes = Extremes { max: f64::MIN, min: f64::MAX };

    /// The larger of |max| and |min|.
    pub fn peak_abs(&self) -> f64 {
        self.max.abs().max(self.min.abs())
    }
}

impl StressSeries {
    /// Steps read.
    pub fn steps(&self) -> usize {
        self.values.len() / self.width.max(1)
    }

    /// Its values and extremes so far, handed to whoever completes the next chunks.
    fn take_evaluated(&mut self) -> beside::Evaluated {
        beside::Evaluated { values: std::mem::take(&mut self.values), extremes: std::mem::take(&mut self.running) }
    }

    /// Takes back its values and extremes.
    fn put_evaluated(&mut self, evaluated: beside::Evaluated) {
        (self.values, self.running) = (evaluated.values, evaluated.extremes);
    }

    /// Per station, hub outwards, and fibre (upper, lower): the largest and smallest σ over the
    /// steps read, Pa.
    pub fn extremes(&self) -> Vec<[Extremes; 2]> {
        (0..self.stations.len()).map(|i| self.running.at(i)).collect()
    }

    /// (axial force N, bending moment N·m) at station `i`, step `k`.
    pub fn section_forces(&self, i: usize, k: usize) -> [f64; 2] {
        let at = k * self.width + i;
        [self.values[at].into(), self.values[at + self.stations.len()].into()]
    }

    /// σ at station `i`, `fibre`, step `k`, Pa.
    pub fn stress_pa(&self, i: usize, fibre: Fibre, k: usize) -> f64 {
        let [axial_n, moment_n_m] = self.section_forces(i, k);
        self.stations[i].fibres.stress_pa(fibre, axial_n, moment_n_m)
    }
}

impl StressProbe {
    /// The probe on `arm`, the run's model of `model`'s arm; `scene` gives the cylinder's pin.
    pub fn new(model: &Model, arm: &ArmModel, scene: &Scene) -> Self {
        let segments = &model.robot.arm.segments;
        let mut end = 0.0;
        let segment_ends: Vec<f64> = segments
            .iter()
            .map(|s| {
                end += s.length_m;
                end
            })
            .collect();
        let cylinders: Vec<(Cylinder, [DVector<f64>; 2])> =
            scene.arm.drive.plant().map_or(Vec::new(), |plant| match (&plant.actuator, &plant.arm_pins) {
                (Actuator::Hydraulic(h), Some(couplings)) => {
                    h.cylinders.each.iter().copied().zip(couplings.rows.iter().cloned()).collect()
                }
                _ => Vec::new(),
            });
        let pin_station: Vec<f64> = cylinders.iter().map(|(c, _)| c.arm_pin_m[0]).collect();
        let stations = recovery::stations_of(arm, &segment_ends, &pin_station);
        let fibres = stations.iter().map(|s| Fibres::of(&segments[s.segment].section)).collect();
        StressProbe {
            recovery: Arc::new(SectionRecovery::new(arm, stations, model.payload.string())),
            fibres,
            cylinders,
            pins_world_n: Vec::new(),
            recorded: beside::Recorded::default(),
            on_arm: Vec::new(),
            on_string: Vec::new(),
            gravity_m_s2: 0.0,
            worker: None,
            completer: None,
            worker_tried: false,
        }
    }

    /// Values per step: the recovery's, then the cylinder pins'.
    pub fn width(&self) -> usize {
        self.recovery.width() + CYLINDER_VALUES * self.cylinders.len()
    }

    /// The probe of a run of `model` in `scene` of `steps` steps, its readings to go in `series`.
    pub fn for_run(model: &Model, scene: &Scene, steps: usize, series: &mut StressSeries) -> Self {
        let probe = StressProbe::new(model, &scene.arm.arm, scene);
        let hands: Vec<String> =
            model.payload.string().map(|s| s.grips.iter().map(|g| g.hand.clone()).collect()).unwrap_or_default();
        *series = probe.series(steps, &hands);
        probe
    }

    /// An empty series of this probe's readings, with room for `steps` steps; `hands` names the
    /// string's hands in order.
    pub fn series(&self, steps: usize, hands: &[String]) -> StressSeries {
        let stations: Vec<SeriesStation> = self
            .recovery
            .stations
            .iter()
            .zip(&self.fibres)
            .map(|(s, f)| SeriesStation { station_m: s.x_m(), segment: s.segment, fibres: *f })
            .collect();
        StressSeries {
            values: Vec::with_capacity(steps * self.width()),
            width: self.width(),
            pivot_index: self.recovery.pivot_index(),
            hands: (0..self.recovery.hand_count())
                .map(|h| (hands.get(h).cloned().unwrap_or_else(|| format!("hand {h}")), self.recovery.hand_index(h)))
                .collect(),
            cylinder_indices: (0..self.cylinders.len()).map(|i| self.recovery.width() + CYLINDER_VALUES * i).collect(),
            running: RunningExtremes::new(&stations),
            stations,
        }
    }

    /// Appends the reading at the scene's current state, whose sample is `sample`, under gravity
    /// `g` to `series` (made by [`Self::series`]).
    pub fn read(&mut self, scene: &Scene, sample: &ArmSample, g: f64, series: &mut StressSeries) {
        let (hub, q, qd) = scene.arm.kinematics();
        let qdd = scene.arm.elastic_accelerations();
        let state = &ArmState { hub, q: &q, qd: &qd, qdd: &qdd };
        let (s, c) = hub.angle_rad.sin_cos();
        self.on_arm.clear();
        self.on_string.clear();
        for pair in scene.pairs().filter(|p| p.force_n > 0.0) {
            let load = PointLoad::<World>::new(pair.station_m, pair.point_m, pair_force(pair)).in_hub((s, c));
            match pair.side {
                PairSide::Arm => self.on_arm.push(load),
                PairSide::String => self.on_string.push(load),
            }
        }
        self.on_arm.extend(scene.arm.head_loads_on_arm());
        self.pins_world_n.clear();
        let readings = sample.actuator.as_ref().map_or(&[][..], |a| &a.cylinders[..]);
        for (i, (cylinder, rows)) in self.cylinders.iter().enumerate() {
            let rod_force_n = readings.get(i).map_or(0.0, |r| r.rod_force_n);
            let pin =
                crate::arm::ArmPin::at(cylinder, rows, (hub.angle_rad, hub.rate_rad_s), q.as_slice(), qd.as_slice());
            let [ax, ay] = cylinder.arm_pin_m;
            let point_m = [ax + rows[0].dot(&q), ay + rows[1].dot(&q)];
            let force_n = pin.body_unit.map(|u| rod_force_n * u);
            let pin_load = PointLoad::<Hub>::new(ax, point_m, force_n);
            self.on_arm.push(pin_load);
            self.pins_world_n.push(pin_load.in_world((s, c)).force_n);
        }
        self.gravity_m_s2 = g;
        self.recorded.push(state, (s, c), (&self.on_arm, &self.on_string), &self.pins_world_n);
        if self.recorded.steps() == recovery::CHUNK_STEPS {
            self.hand_over(series);
        }
    }

    /// Completes the recorded chunk into `series`: on the worker, started with the first chunk,
    /// or here.
    fn hand_over(&mut self, series: &mut StressSeries) {
        let (recovery, g, stride) = (&self.recovery, self.gravity_m_s2, self.width());
        let completer = || beside::Completer::new(recovery.clone(), g, stride);
        if !self.worker_tried {
            self.worker_tried = true;
            match beside::Worker::start(completer(), series.take_evaluated()) {
                Ok(worker) => self.worker = Some(worker),
                Err(evaluated) => series.put_evaluated(*evaluated),
            }
        }
        match &self.worker {
            Some(worker) => self.recorded = worker.hand_over(std::mem::take(&mut self.recorded)),
            None => {
                let completer = self.completer.get_or_insert_with(completer);
                let mut evaluated = series.take_evaluated();
                completer.complete(&self.recorded, &mut evaluated);
                series.put_evaluated(evaluated);
                self.recorded.clear();
            }
        }
    }

    /// Hands the readings not yet handed over to whoever completes them (without waiting for
    /// a worker to finish them: [`Self::finish`] does).
    pub fn hand_over_rest(&mut self, series: &mut StressSeries) {
        if self.recorded.steps() > 0 || !self.worker_tried {
            self.hand_over(series);
        }
    }

    /// Completes the readings in `series`: call once after the last read, and before using it.
    pub fn finish(&mut self, series: &mut StressSeries) {
        self.hand_over_rest(series);
        if let Some(worker) = self.worker.take() {
            series.put_evaluated(worker.finish());
        }
        self.worker_tried = false;
    }
}

/// A pair's force on the machine, world X, Y: the sum over its points (friction included), or
/// its normal force along its normal where it reports no points.
fn pair_force(pair: &crate::scene::ContactPair) -> [f64; 2] {
    if pair.points.is_empty() {
        return pair.normal_world.map(|n| pair.force_n * n);
    }
    pair.points.iter().fold([0.0; 2], |acc, p| [acc[0] + p.force_n[0], acc[1] + p.force_n[1]])
}
