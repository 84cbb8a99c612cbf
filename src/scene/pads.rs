//! Rubber pads placed against the arm at their stops, and what every contact method knows of
//! them: where their face is, how far the arm is from it, and the force measured on it.

use nalgebra::DVector;
use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView};
use crate::arm::{ArmModel, StationRows};
use crate::model::Dampener;

/// A rubber pad in the scene and its state at the end of the last step.
#[derive(Debug, Clone)]
pub struct Pad {
    /// Its description.
    pub dampener: Dampener,
    /// Unit normal of its face in the world (X, Y), pointing at the arm.
    pub normal_world: [f64; 2],
    /// World position of its face centre, m.
    pub face_centre_m: [f64; 3],
    /// World pose of its centre (where the `rapier` method's pad body is now).
    pub pose: Pose,
    /// Its shape, a box, in its own frame.
    pub shape: SharedShape,
    /// Force at the end of the last step, N.
    pub force_n: f64,
    /// How far the pad is compressed at the end of the last step, m (the arm's penetration for
    /// `compliant`, the pad body's travel for `rapier`); beyond the pad's thickness the run is
    /// meaningless.
    pub compression_m: f64,
    /// Point of application of that force relative to the pivot (world X, Y), m.
    pub point_m: [f64; 2],
    /// Name of the arm part touching it.
    pub touching: Option<String>,
    /// The arm's face point at the pad's station, to measure the clearance cheaply.
    watch: PadWatch,
}

/// The arm's face point at a pad's station.
#[derive(Debug, Clone)]
struct PadWatch {
    rows: StationRows,
    /// Body-frame y of the face that meets the pad, m.
    face_lateral_m: f64,
    /// Extra clearance for shapes standing out beyond the face, plus 0.1 mm, m.
    margin_m: f64,
}

impl Pad {
    /// Places a pad against the undeformed arm at its stop, `gap_m` from the named face.
    pub fn place(dampener: &Dampener, pieces: &[ArmPiece], arm: &ArmModel, pivot_m: [f64; 3]) -> Self {
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
        Pad {
            dampener: spec.clone(),
            normal_world: [sign * s, -sign * c],
            face_centre_m: to_world(spec.station_m, face_y),
            pose,
            shape: SharedShape::cuboid(0.5 * spec.length_m, 0.5 * spec.thickness_m, 0.5 * spec.width_m),
            force_n: 0.0,
            compression_m: 0.0,
            point_m: [0.0; 2],
            touching: None,
            watch: PadWatch {
                rows: arm.station_rows(spec.station_m),
                face_lateral_m: sign * half_depth,
                margin_m: protrusion + 1e-4,
            },
        }
    }

    /// Distance from the pad's face to the arm's face, m: the nearer of the face's two ends from
    /// the line of the arm's face at the pad's station (its tangent there, with the elastic
    /// slope), measured along the face's outward normal. Exact for the straight face across the
    /// pad's length, whatever the arm's angle to the pad; negative in contact.
    pub fn clearance_m(&self, arm: &ArmView) -> f64 {
        let [u, v, phi] = self.watch.rows.displacement(arm.q);
        let lateral = self.watch.face_lateral_m;
        let (x, y) = (self.dampener.station_m + u - lateral * phi, lateral + v);
        let (s, c) = arm.hub.angle_rad.sin_cos();
        let point = [arm.pivot_m[0] + c * x - s * y, arm.pivot_m[1] + s * x + c * y];
        // The face's outward normal: the body's ±y turned by the hub angle and the slope.
        let (sf, cf) = (arm.hub.angle_rad + phi).sin_cos();
        let outward = [-sf * lateral.signum(), cf * lateral.signum()];
        let n = self.normal_world;
        let half = 0.5 * self.dampener.length_m;
        [-1.0, 1.0]
            .map(|side| {
                let end = [self.face_centre_m[0] - side * half * n[1], self.face_centre_m[1] + side * half * n[0]];
                outward[0] * (end[0] - point[0]) + outward[1] * (end[1] - point[1])
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min)
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

    /// What makes the pad's state meaningless: a force that is not finite, or the pad crushed
    /// beyond its thickness.
    pub fn fault(&self) -> Option<String> {
        let name = &self.dampener.name;
        if !self.force_n.is_finite() {
            Some(format!("pad {name}'s contact force is no longer finite"))
        } else if self.compression_m > self.dampener.thickness_m {
            Some(format!(
                "pad {name} is compressed {:.1} mm, beyond its {:.1} mm thickness",
                1e3 * self.compression_m,
                1e3 * self.dampener.thickness_m
            ))
        } else {
            None
        }
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
