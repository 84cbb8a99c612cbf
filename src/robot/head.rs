//! A tilting gripper head: links carried by the arm through a revolute joint whose axis is
//! normal to the lift plane (a wrist), declared with `<pipearm:hinge>` inside that joint.
//!
//! A `locked` hinge is read as a fixed joint: its links are carried bodies like any other. A
//! `spring` hinge makes the links below it one rigid body turning on the arm's section at the
//! hinge station, its angle ψ one more coordinate of the arm ([`crate::arm::HeadModel`]); a
//! `driven` hinge turns that body through a profile of its own (the scenario's `head.drive`).

use crate::drive::MotionProfile;

/// How the hinge of a tilting head behaves.
#[derive(Debug, Clone, PartialEq)]
pub enum HingeLaw {
    /// A torsion spring-damper between the head and the arm's section, relaxed at the URDF pose.
    Spring {
        /// Torsional stiffness, N·m/rad (> 0).
        stiffness_n_m_per_rad: f64,
        /// Torsional damping, N·m·s/rad (>= 0).
        damping_n_m_s_per_rad: f64,
    },
    /// Turned by a drive of its own: the angle on the hinge follows `profile` exactly (rad, 0 at
    /// the URDF pose), the scenario's `head.drive` (`None` until a scenario gives it).
    Driven { profile: Option<MotionProfile> },
}

/// The rigid head on its hinge, in the arm frame (x along the arm, y across it in the lift
/// plane) at the URDF pose (ψ = 0).
#[derive(Debug, Clone, PartialEq)]
pub struct TiltingHead {
    /// The revolute joint's name.
    pub joint: String,
    /// Arm station of the hinge axis, m (on the arm: 0 ..= its length).
    pub hinge_station_m: f64,
    /// Offset of the hinge axis across the arm, in the lift plane, m.
    pub hinge_lateral_m: f64,
    /// The hinge's law.
    pub law: HingeLaw,
    /// Mass of every link below the hinge, kg.
    pub mass_kg: f64,
    /// Their centre of mass from the hinge axis, [along the arm, across it], m.
    pub centre_of_mass_m: [f64; 2],
    /// Their inertia about that centre of mass, normal to the lift plane, kg·m².
    pub inertia_kg_m2: f64,
    /// The links below the hinge (they turn with it).
    pub links: Vec<String>,
}

impl TiltingHead {
    /// The hinge's torsional stiffness, N·m/rad (0 for a driven hinge).
    pub fn stiffness_n_m_per_rad(&self) -> f64 {
        match self.law {
            HingeLaw::Spring { stiffness_n_m_per_rad, .. } => stiffness_n_m_per_rad,
            HingeLaw::Driven { .. } => 0.0,
        }
    }

    /// The hinge's torsional damping, N·m·s/rad (0 for a driven hinge).
    pub fn damping_n_m_s_per_rad(&self) -> f64 {
        match self.law {
            HingeLaw::Spring { damping_n_m_s_per_rad, .. } => damping_n_m_s_per_rad,
            HingeLaw::Driven { .. } => 0.0,
        }
    }

    /// A driven hinge's profile (`Some` once a scenario gave it).
    pub fn profile(&self) -> Option<&MotionProfile> {
        match &self.law {
            HingeLaw::Driven { profile } => profile.as_ref(),
            HingeLaw::Spring { .. } => None,
        }
    }

    /// Whether the hinge is driven (its angle prescribed, not a coordinate).
    pub fn is_driven(&self) -> bool {
        matches!(self.law, HingeLaw::Driven { .. })
    }

    /// Inertia about the hinge axis, kg·m².
    pub fn inertia_about_hinge_kg_m2(&self) -> f64 {
        let [x, y] = self.centre_of_mass_m;
        self.inertia_kg_m2 + self.mass_kg * (x * x + y * y)
    }
}

impl TiltingHead {
    /// This head carrying `body` rigidly (a string in its hands): `body`'s centre at its arm
    /// station on the arm's axis in the URDF pose, its mass and own inertia added by the
    /// parallel-axis sum.
    pub fn carrying(mut self, body: &crate::beam::ConcentratedMass) -> Self {
        let offset = [body.position_m - self.hinge_station_m, -self.hinge_lateral_m];
        let own = (self.mass_kg, self.centre_of_mass_m, self.inertia_kg_m2);
        (self.mass_kg, self.centre_of_mass_m, self.inertia_kg_m2) =
            combined(&[own, (body.mass_kg, offset, body.rotary_inertia_kg_m2)]);
        self
    }
}

/// Mass, centre of mass [x, y] and inertia about it (normal to the plane) of point bodies given
/// as (mass kg, [x, y] m, own inertia kg·m²): the parallel-axis sum.
pub(crate) fn combined(bodies: &[(f64, [f64; 2], f64)]) -> (f64, [f64; 2], f64) {
    let mass: f64 = bodies.iter().map(|b| b.0).sum();
    if mass <= 0.0 {
        return (0.0, [0.0; 2], bodies.iter().map(|b| b.2).sum());
    }
    let moment = |k: usize| bodies.iter().map(|b| b.0 * b.1[k]).sum::<f64>() / mass;
    let centre = [moment(0), moment(1)];
    let inertia = bodies.iter().map(|(m, [x, y], j)| j + m * ((x - centre[0]).powi(2) + (y - centre[1]).powi(2))).sum();
    (mass, centre, inertia)
}

impl TiltingHead {
    /// This hinge with the mass properties of the carried `bodies` that tilt.
    pub(crate) fn with_links(mut self, bodies: &[super::CarriedBody]) -> Self {
        let tilting: Vec<_> = bodies.iter().filter(|b| b.tilts).collect();
        let points: Vec<_> = tilting
            .iter()
            .map(|b| {
                let offset = [b.station_m - self.hinge_station_m, b.lateral_m - self.hinge_lateral_m];
                (b.mass_kg, offset, b.rotary_inertia_kg_m2)
            })
            .collect();
        (self.mass_kg, self.centre_of_mass_m, self.inertia_kg_m2) = combined(&points);
        self.links = tilting.iter().map(|b| b.name.clone()).collect();
        self
    }
}
