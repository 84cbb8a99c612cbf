//! What each sensor reads at one instant, from the arm's state.
//!
//! Kinematics in the hub (floating) frame, notation of `docs/model.md`: a point of the arm at
//! station x sits at r = (x + u, v) (the second-order foreshortening left out, as in the run's
//! tip outputs), and its acceleration, in hub-frame components, is
//!
//! ```text
//! a = r̈ + 2θ̇ k×ṙ + θ̈ k×r − θ̇² r
//!   = (ü − 2θ̇ v̇ − θ̈ v − θ̇² (x + u),  v̈ + 2θ̇ u̇ + θ̈ (x + u) − θ̇² v)
//! ```
//!
//! Gravity in the hub frame is g_b = (−g sin θ, −g cos θ).
//!
//! - Accelerometer: the specific force a − g_b, turned into the section's axes by the local
//!   slope φ = v′: (f_x cos φ + f_y sin φ, −f_x sin φ + f_y cos φ).
//! - Strain gauge: the moment about the section point r_s of every load on the arm outboard of
//!   the station — the d'Alembert and gravity loads dm (g_b − a) of the arm's mass (Gauss
//!   quadrature over the elements) and of the concentrated masses, their rotary inertia
//!   −J (θ̈ + φ̈), and the pads' contact forces — is M_o (a flexible string held by hands all
//!   outboard of the gauge counts as Gauss points of its own elements, which move with it); the section carries −M_o, and the
//!   bending moment reported is M = −M_o (positive when the upper face is in tension). The
//!   beam's sections carry no rotary inertia of their own (Euler–Bernoulli), as in the model.
//! - Encoder: θ and θ̇.

use crate::point_load::{PointLoad, World};
use nalgebra::DVector;

use super::{Sensor, SensorKind};
use crate::arm::{ArmModel, StationRows};
use crate::beam::GAUSS_4;
use crate::drive::DriveState;

/// The arm's state at one instant: hub, elastic coordinates and their first two rates.
#[derive(Debug, Clone, Copy)]
pub struct ArmState<'a> {
    /// Hub angle, rate and acceleration.
    pub hub: DriveState,
    /// q.
    pub q: &'a DVector<f64>,
    /// q̇.
    pub qd: &'a DVector<f64>,
    /// q̈.
    pub qdd: &'a DVector<f64>,
}

/// A mass point of the arm outboard of a strain gauge: station, mass, rotary inertia, rows.
#[derive(Debug, Clone)]
struct MassPoint {
    x_m: f64,
    mass_kg: f64,
    rotary_inertia_kg_m2: f64,
    rows: StationRows,
}

/// A sensor made ready to read: its shape rows computed once.
#[derive(Debug, Clone)]
pub struct SensorProbe {
    /// The sensor.
    pub sensor: Sensor,
    /// Rows of its station (none for the encoder).
    rows: Option<StationRows>,
    /// Mass points outboard of a strain gauge's station.
    outboard: Vec<MassPoint>,
    gravity_m_s2: f64,
}

impl SensorProbe {
    /// Prepares `sensor` on `arm`.
    pub fn new(sensor: &Sensor, arm: &ArmModel) -> Self {
        let station = sensor.kind.station_m();
        let outboard = match sensor.kind {
            SensorKind::StrainGauge { station_m, .. } => outboard_mass_points(arm, station_m),
            _ => Vec::new(),
        };
        SensorProbe {
            sensor: sensor.clone(),
            rows: station.map(|x| arm.station_rows(x)),
            outboard,
            gravity_m_s2: arm.options.gravity_m_s2,
        }
    }

    /// The two channels' readings (units of [`SensorKind::channels`]) at `state`, with the
    /// pads' forces `loads`.
    pub fn read(&self, state: &ArmState, loads: &[PointLoad<World>]) -> [f64; 2] {
        let rows = self.rows.as_ref();
        match self.sensor.kind {
            SensorKind::Encoder => [state.hub.angle_rad, state.hub.rate_rad_s],
            SensorKind::Accelerometer { station_m } => {
                let point = Kinematics::of(station_m, rows.expect("a station"), state);
                let [fx, fy] = point.specific_force(state, self.gravity_m_s2);
                let (s, c) = point.slope_rad.sin_cos();
                [c * fx + s * fy, -s * fx + c * fy]
            }
            SensorKind::StrainGauge { station_m, half_depth_m, second_moment_m4 } => {
                let moment = self.bending_moment(station_m, rows.expect("a station"), state, loads);
                [moment, moment * half_depth_m / second_moment_m4]
            }
        }
    }

    /// Bending moment at the station by force summation over the outboard part, N·m
    /// (positive: upper face in tension).
    fn bending_moment(&self, station_m: f64, rows: &StationRows, state: &ArmState, loads: &[PointLoad<World>]) -> f64 {
        let section = Kinematics::of(station_m, rows, state);
        let g = self.gravity_m_s2;
        let hub = &state.hub;
        let mut outboard_moment = 0.0;
        for p in &self.outboard {
            let k = Kinematics::of(p.x_m, &p.rows, state);
            let load = k.specific_force(state, g).map(|f| -p.mass_kg * f);
            outboard_moment += cross(sub(k.position_m, section.position_m), load);
            outboard_moment -= p.rotary_inertia_kg_m2 * (hub.accel_rad_s2 + k.slope_accel_rad_s2);
        }
        let (s, c) = hub.angle_rad.sin_cos();
        let to_hub = |[x, y]: [f64; 2]| [c * x + s * y, -s * x + c * y];
        for load in loads.iter().filter(|l| l.station_m > station_m) {
            let arm = sub(to_hub(load.point_m), section.position_m);
            outboard_moment += cross(arm, to_hub(load.force_n));
        }
        -outboard_moment
    }
}

/// Position, slope and acceleration of one arm point, hub-frame components.
struct Kinematics {
    position_m: [f64; 2],
    slope_rad: f64,
    slope_accel_rad_s2: f64,
    accel_m_s2: [f64; 2],
}

impl Kinematics {
    fn of(x_m: f64, rows: &StationRows, state: &ArmState) -> Self {
        let [u, v, phi] = rows.displacement(state.q);
        let [ud, vd, _] = rows.displacement(state.qd);
        let [udd, vdd, phidd] = rows.displacement(state.qdd);
        let (w, alpha) = (state.hub.rate_rad_s, state.hub.accel_rad_s2);
        let (rx, ry) = (x_m + u, v);
        Kinematics {
            position_m: [rx, ry],
            slope_rad: phi,
            slope_accel_rad_s2: phidd,
            accel_m_s2: [udd - 2.0 * w * vd - alpha * ry - w * w * rx, vdd + 2.0 * w * ud + alpha * rx - w * w * ry],
        }
    }

    /// Acceleration minus gravity, hub-frame components, m/s².
    fn specific_force(&self, state: &ArmState, g: f64) -> [f64; 2] {
        let (s, c) = state.hub.angle_rad.sin_cos();
        [self.accel_m_s2[0] + g * s, self.accel_m_s2[1] + g * c]
    }
}

/// The arm's mass outboard of `station_m` as points: four Gauss points per element (or part of
/// one) and the concentrated masses past the station (a mass at the station itself is inboard).
fn outboard_mass_points(arm: &ArmModel, station_m: f64) -> Vec<MassPoint> {
    let point = |x_m: f64, mass_kg: f64, rotary_inertia_kg_m2: f64| MassPoint {
        x_m,
        mass_kg,
        rotary_inertia_kg_m2,
        rows: arm.station_rows(x_m),
    };
    let mut points = Vec::new();
    for element in &arm.beam.elements {
        let (x0, x1) = (element.x0_m.max(station_m), element.x0_m + element.length_m);
        if x1 <= x0 {
            continue;
        }
        for (xi, weight) in GAUSS_4 {
            points.push(point(x0 + xi * (x1 - x0), weight * (x1 - x0) * element.mass_per_length_kg_m, 0.0));
        }
    }
    let tolerance = 1e-9 * arm.length_m();
    for mass in arm.beam.spec.masses.iter().filter(|m| m.position_m > station_m + tolerance) {
        points.push(point(mass.position_m, mass.mass_kg, mass.rotary_inertia_kg_m2));
    }
    // A string held by hands all outboard of the station hangs on the outboard part whole (one
    // straddling the station is refused by the scenario's checks: its clamps' reactions would be
    // needed).
    if let Some(member) =
        arm.beam.member.as_ref().filter(|m| m.spec.clamps_m.iter().all(|&c| c > station_m + tolerance))
    {
        let n = arm.beam.dofs();
        for element in &member.elements {
            for (xi, weight) in GAUSS_4 {
                let x_m = element.x0_m + xi * element.length_m;
                let [u, v, phi, _] = member.point_rows(x_m, n);
                let rows = StationRows([u, v, phi].map(|r| arm.basis.tr_mul(&r)));
                let mass_kg = weight * element.length_m * element.mass_per_length_kg_m;
                points.push(MassPoint { x_m, mass_kg, rotary_inertia_kg_m2: 0.0, rows });
            }
        }
    }
    points
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// z of a × b.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
