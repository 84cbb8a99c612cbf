//! Outlines in a plane, m: a URDF collision shape seen along z (its side view in the lift plane),
//! a structure's, a rectangle, and the plane motions the drawing puts them through.

use nalgebra::{Rotation3, Vector3};

use crate::model::{Structure, StructureShape};
use crate::robot::{PlacedShape, Shape};

/// A closed outline in a plane, m.
#[derive(Debug, Clone, PartialEq)]
pub enum Outline {
    /// A convex polygon, counter-clockwise.
    Polygon(Vec<[f64; 2]>),
    /// A circle.
    Circle { centre: [f64; 2], radius: f64 },
}

impl Outline {
    /// The rectangle between x0..x1 and y0..y1.
    pub fn rectangle([x0, x1]: [f64; 2], [y0, y1]: [f64; 2]) -> Self {
        Outline::Polygon(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    }

    /// The outline turned by `angle_rad` about the origin, then moved by `offset`.
    pub fn placed(&self, angle_rad: f64, offset: [f64; 2]) -> Self {
        let to = |p: [f64; 2]| add(rotate(p, angle_rad), offset);
        match self {
            Outline::Polygon(points) => Outline::Polygon(points.iter().map(|p| to(*p)).collect()),
            Outline::Circle { centre, radius } => Outline::Circle { centre: to(*centre), radius: *radius },
        }
    }

    /// [x_min, x_max, y_min, y_max], m.
    pub fn bounds(&self) -> [f64; 4] {
        match self {
            Outline::Polygon(points) => points.iter().fold(EMPTY, |b, p| grow(b, *p)),
            Outline::Circle { centre: [x, y], radius: r } => [x - r, x + r, y - r, y + r],
        }
    }

    /// Its centre (of its bounds), m.
    pub fn centre(&self) -> [f64; 2] {
        let [x0, x1, y0, y1] = self.bounds();
        [0.5 * (x0 + x1), 0.5 * (y0 + y1)]
    }
}

/// Bounds that hold nothing yet.
pub const EMPTY: [f64; 4] = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];

/// `bounds` grown to hold `p`.
pub fn grow([x0, x1, y0, y1]: [f64; 4], [x, y]: [f64; 2]) -> [f64; 4] {
    [x0.min(x), x1.max(x), y0.min(y), y1.max(y)]
}

/// The union of two bounds.
pub fn union(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [a[0].min(b[0]), a[1].max(b[1]), a[2].min(b[2]), a[3].max(b[3])]
}

pub fn rotate([x, y]: [f64; 2], angle_rad: f64) -> [f64; 2] {
    let (s, c) = angle_rad.sin_cos();
    [c * x - s * y, s * x + c * y]
}

pub fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// A URDF collision shape seen along z: the convex hull of its corners (a box's eight, a
/// cylinder's rims sampled) turned by its roll-pitch-yaw, or a sphere's circle.
pub fn of_placed(placed: &PlacedShape) -> Outline {
    let [x, y, _] = placed.position_m;
    let [roll, pitch, yaw] = placed.rpy_rad;
    let rotation = Rotation3::from_euler_angles(roll, pitch, yaw);
    let local: Vec<Vector3<f64>> = match placed.shape {
        Shape::Sphere { radius_m } => return Outline::Circle { centre: [x, y], radius: radius_m },
        Shape::Box { half_extents_m: [hx, hy, hz] } => (0..8)
            .map(|k| {
                let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
                Vector3::new(sign(1) * hx, sign(2) * hy, sign(4) * hz)
            })
            .collect(),
        // A URDF cylinder runs along its own z.
        Shape::Cylinder { radius_m, half_length_m } => (0..32)
            .map(|k| {
                let a = std::f64::consts::TAU * (k / 2) as f64 / 16.0;
                let end = if k % 2 == 0 { -half_length_m } else { half_length_m };
                Vector3::new(radius_m * a.cos(), radius_m * a.sin(), end)
            })
            .collect(),
    };
    let points: Vec<[f64; 2]> = local
        .iter()
        .map(|v| {
            let w = rotation * v;
            [x + w.x, y + w.y]
        })
        .collect();
    Outline::Polygon(convex_hull(points))
}

/// A structure seen along z in the world: a box turned by its angle, a cylinder (along z) as
/// its circle.
pub fn of_structure(structure: &Structure) -> Outline {
    let [x, y, _] = structure.position_m;
    match structure.shape {
        StructureShape::Box { half_extents_m: [hx, hy, _] } => {
            Outline::rectangle([-hx, hx], [-hy, hy]).placed(structure.angle_rad, [x, y])
        }
        StructureShape::Cylinder { radius_m, .. } => Outline::Circle { centre: [x, y], radius: radius_m },
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
pub fn convex_hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
    if points.len() < 3 {
        return points;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for pass in [points.clone(), points.into_iter().rev().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_turned_about_x_shows_its_depth_across() {
        // A 0.2 × 0.4 × 0.6 box rolled 90° about x: its z extent (0.6) now lies along y.
        let placed = PlacedShape {
            position_m: [1.0, 0.0, 0.0],
            rpy_rad: [std::f64::consts::FRAC_PI_2, 0.0, 0.0],
            shape: Shape::Box { half_extents_m: [0.1, 0.2, 0.3] },
        };
        let [x0, x1, y0, y1] = of_placed(&placed).bounds();
        assert!((x0 - 0.9).abs() < 1e-12 && (x1 - 1.1).abs() < 1e-12);
        assert!((y0 + 0.3).abs() < 1e-12 && (y1 - 0.3).abs() < 1e-12);
    }

    #[test]
    fn the_hull_of_a_square_and_its_centre_is_the_square() {
        let hull = convex_hull(vec![[0.0, 0.0], [1.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(hull, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    }
}
