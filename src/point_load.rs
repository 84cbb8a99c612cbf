//! A concentrated force on the machine at one step — a pad's contact, the cylinder's rod — with
//! the frame its point and force are given in carried by its type.

use std::marker::PhantomData;

/// The world frame: X horizontal, Y up, origin at the pivot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct World;

/// The hub frame: x along the undeformed arm, y normal to it in the lift plane, origin at the
/// pivot (the world frame turned by the hub angle).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Hub;

/// A force on the machine, its point and force in frame `F` ([`World`] or [`Hub`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad<F> {
    /// Arm station of the part it acts on, m (a string's: along the arm's axis).
    pub station_m: f64,
    /// Point of application, m.
    pub point_m: [f64; 2],
    /// Force, N.
    pub force_n: [f64; 2],
    /// A couple with it, N·m (counter-clockwise positive; 0 for a contact's force).
    pub couple_n_m: f64,
    frame: PhantomData<F>,
}

impl<F> PointLoad<F> {
    /// The force `force_n` at `point_m`, on the part at station `station_m`.
    pub fn new(station_m: f64, point_m: [f64; 2], force_n: [f64; 2]) -> Self {
        PointLoad { station_m, point_m, force_n, couple_n_m: 0.0, frame: PhantomData }
    }

    /// The same force with a couple `couple_n_m`, N·m, counter-clockwise positive.
    pub fn with_couple(self, couple_n_m: f64) -> Self {
        PointLoad { couple_n_m, ..self }
    }

    /// The same force, read as acting on the part at station `station_m`.
    pub fn at_station(self, station_m: f64) -> Self {
        PointLoad { station_m, ..self }
    }
}

impl PointLoad<World> {
    /// The load in the hub frame of a hub at the angle whose sine and cosine are `(s, c)`.
    pub fn in_hub(&self, (s, c): (f64, f64)) -> PointLoad<Hub> {
        let turn = |[x, y]: [f64; 2]| [c * x + s * y, -s * x + c * y];
        PointLoad::new(self.station_m, turn(self.point_m), turn(self.force_n)).with_couple(self.couple_n_m)
    }
}

impl PointLoad<Hub> {
    /// The load in the world frame, the hub at the angle whose sine and cosine are `(s, c)`.
    pub fn in_world(&self, (s, c): (f64, f64)) -> PointLoad<World> {
        let turn = |[x, y]: [f64; 2]| [c * x - s * y, s * x + c * y];
        PointLoad::new(self.station_m, turn(self.point_m), turn(self.force_n)).with_couple(self.couple_n_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_load_in_the_hub_frame_keeps_its_moment_turns_with_the_hub_and_back() {
        let angle: f64 = 0.7;
        let world = PointLoad::<World>::new(2.0, [1.5, 2.5], [-30.0, 40.0]);
        let hub = world.in_hub(angle.sin_cos());
        let moment = |p: [f64; 2], f: [f64; 2]| p[0] * f[1] - p[1] * f[0];
        assert!((moment(hub.point_m, hub.force_n) - moment(world.point_m, world.force_n)).abs() < 1e-12);
        assert!((hub.force_n[0].hypot(hub.force_n[1]) - 50.0).abs() < 1e-12);
        // A force along the arm at θ reads as along x in the hub frame.
        let along = PointLoad::<World>::new(0.0, [0.0; 2], [angle.cos(), angle.sin()]).in_hub(angle.sin_cos());
        assert!((along.force_n[0] - 1.0).abs() < 1e-12 && along.force_n[1].abs() < 1e-12);
        assert_eq!(hub.at_station(3.0).station_m, 3.0);
        let back = hub.in_world(angle.sin_cos());
        for j in 0..2 {
            assert!((back.point_m[j] - world.point_m[j]).abs() < 1e-12);
            assert!((back.force_n[j] - world.force_n[j]).abs() < 1e-12);
        }
    }
}
