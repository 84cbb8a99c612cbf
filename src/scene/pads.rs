//! Rubber pads placed against the arm at their stops: where their face is and how far the arm is
//! from it.

use nalgebra::DVector;
use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView};
use crate::arm::{ArmContact, ArmModel, PointContact, StationRows};
use crate::model::Dampener;

/// Where a rubber pad sits against the arm: its face, and the arm's face point at its station.
#[derive(Debug, Clone)]
pub struct PadPlacement {
    /// Its length along the arm, m.
    length_m: f64,
    /// Unit normal of its face in the world (X, Y), pointing at the arm.
    pub normal_world: [f64; 2],
    /// World position of its face centre, m.
    pub face_centre_m: [f64; 3],
    /// The arm's face point at the pad's station, to measure the clearance cheaply.
    watch: PadWatch,
}

/// Margin on a pad's clearance beyond what stands out of the arm's face, m.
const FACE_MARGIN_M: f64 = 1e-4;

/// The arm's face point at a pad's station.
#[derive(Debug, Clone)]
struct PadWatch {
    rows: StationRows,
    /// The pad's station, m.
    station_m: f64,
    /// Body-frame y of the face that meets the pad, m.
    face_lateral_m: f64,
    /// Extra clearance for shapes standing out beyond the face, plus 0.1 mm, m.
    margin_m: f64,
}

impl PadPlacement {
    /// Places a pad against the undeformed arm at its stop, `gap_m` from the named face; with
    /// the world pose of the pad's centre.
    pub fn place(dampener: &Dampener, pieces: &[ArmPiece], arm: &ArmModel, pivot_m: [f64; 3]) -> (Self, Pose) {
        let spec = dampener;
        let theta = spec.angle_rad;
        let (s, c) = theta.sin_cos();
        let half_depth = 0.5 * arm_depth_at(pieces, spec.station_m);
        let sign = spec.face.sign();
        // Body-frame y of the pad's face and centre; the normal points back at the arm.
        let face_y = sign * (half_depth + spec.gap_m);
        let centre_y = face_y + sign * 0.5 * spec.thickness_m;
        let to_world = |x: f64, y: f64| [pivot_m[0] + c * x - s * y, pivot_m[1] + s * x + c * y, pivot_m[2]];
        let centre = to_world(spec.station_m, centre_y);
        let pose = Pose::from_parts(Vector::new(centre[0], centre[1], centre[2]), Rotation::from_rotation_z(theta));
        // How far any shape riding on the arm across the pad's length stands out beyond the arm's
        // face on the pad's side (its box turned into the section's axes).
        let protrusion = pieces
            .iter()
            .filter(|p| !p.is_arm_element)
            .filter_map(|p| {
                let [ext_x, ext_y] = p.section_extents_m();
                let overlaps = (p.station_m - spec.station_m).abs() <= 0.5 * spec.length_m + ext_x;
                overlaps.then_some(sign * p.lateral_m + ext_y - half_depth)
            })
            .fold(0.0, f64::max);
        let placement = PadPlacement {
            length_m: spec.length_m,
            normal_world: [sign * s, -sign * c],
            face_centre_m: to_world(spec.station_m, face_y),
            watch: PadWatch {
                rows: arm.station_rows(spec.station_m),
                station_m: spec.station_m,
                face_lateral_m: sign * half_depth,
                margin_m: protrusion + FACE_MARGIN_M,
            },
        };
        (placement, pose)
    }

    /// Distance from the pad's face to the arm's face, m: the nearer of the face's two ends from
    /// the line of the arm's face at the pad's station (its tangent there, with the elastic
    /// slope), measured along the face's outward normal. Exact for the straight face across the
    /// pad's length, whatever the arm's angle to the pad; negative in contact.
    pub fn clearance_m(&self, arm: &ArmView) -> f64 {
        let [u, v, phi] = self.watch.rows.displacement(arm.q);
        let lateral = self.watch.face_lateral_m;
        let (x, y) = (self.watch.station_m + u - lateral * phi, lateral + v);
        let (s, c) = arm.hub.angle_rad.sin_cos();
        let point = [arm.pivot_m[0] + c * x - s * y, arm.pivot_m[1] + s * x + c * y];
        // The face's outward normal: the body's ±y turned by the hub angle and the slope.
        let (sf, cf) = (arm.hub.angle_rad + phi).sin_cos();
        let outward = [-sf * lateral.signum(), cf * lateral.signum()];
        let n = self.normal_world;
        let half = 0.5 * self.length_m;
        [-1.0, 1.0]
            .map(|side| {
                let end = [self.face_centre_m[0] - side * half * n[1], self.face_centre_m[1] + side * half * n[0]];
                outward[0] * (end[0] - point[0]) + outward[1] * (end[1] - point[1])
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min)
    }

    /// The arm's face opposite each end of the pad's face, as contacts that each carry half of
    /// `law` for pair `pair`: the arm's face is its tangent line at the pad's station (with the
    /// elastic slope), the penetration measured along the pad's normal.
    pub fn end_contacts(&self, arm: &ArmView, pair: usize, law: crate::contact::ForceLaw) -> [ArmContact; 2] {
        let [u, v, phi] = self.watch.rows.displacement(arm.q);
        let lateral = self.watch.face_lateral_m;
        let (x, y) = (self.watch.station_m + u - lateral * phi, lateral + v);
        let (s, c) = arm.hub.angle_rad.sin_cos();
        // The arm's face point at the station and the face's direction, relative to the pivot.
        let face = [c * x - s * y, s * x + c * y];
        let (sf, cf) = (arm.hub.angle_rad + phi).sin_cos();
        let n = self.normal_world;
        let half = 0.5 * self.length_m;
        [-1.0, 1.0].map(|side| {
            let end = [
                self.face_centre_m[0] - arm.pivot_m[0] - side * half * n[1],
                self.face_centre_m[1] - arm.pivot_m[1] + side * half * n[0],
            ];
            let along_m = cf * (end[0] - face[0]) + sf * (end[1] - face[1]);
            let opposite = [face[0] + along_m * cf, face[1] + along_m * sf];
            let point = PointContact {
                pair,
                station_m: self.watch.station_m + along_m,
                lateral_m: lateral,
                normal_world: n,
                depth_m: n[0] * (end[0] - opposite[0]) + n[1] * (end[1] - opposite[1]),
                reference_point_m: opposite,
                law,
                impact_speed_m_s: 0.0,
                share: 0.5,
                friction: 0.0,
            };
            ArmContact::on_section(point, &self.watch.rows, along_m)
        })
    }

    /// Whether only the arm's own face can reach the pad (no shape riding on the arm stands out
    /// beyond it across the pad's length).
    pub fn arm_face_only(&self) -> bool {
        self.watch.margin_m <= FACE_MARGIN_M
    }

    /// Whether the arm could reach the pad within `travel_m`, the fastest point's travel in the
    /// coming step with margin: its clearance, less what stands out beyond the arm's face.
    pub fn within_reach(&self, arm: &ArmView, travel_m: f64) -> bool {
        self.clearance_m(arm) <= travel_m + self.watch.margin_m
    }

    /// The arm's effective mass at the pad's station along the arm's normal with the hub held,
    /// 1 / (rᵀ M⁻¹ r), kg, given M⁻¹ (`None`: no elastic coordinates, infinite).
    pub fn effective_mass_kg(&self, mass_inverse: Option<&nalgebra::DMatrix<f64>>) -> Option<f64> {
        let row: &DVector<f64> = &self.watch.rows.0[1];
        let m_eff = 1.0 / row.dot(&(mass_inverse? * row));
        m_eff.is_finite().then_some(m_eff)
    }
}

/// Depth of the arm section at a station, m (the nearest element's).
fn arm_depth_at(pieces: &[ArmPiece], station_m: f64) -> f64 {
    pieces
        .iter()
        .filter(|p| p.is_arm_element)
        .min_by(|a, b| (a.station_m - station_m).abs().total_cmp(&(b.station_m - station_m).abs()))
        .map_or(0.0, |p| p.depth_m)
}
