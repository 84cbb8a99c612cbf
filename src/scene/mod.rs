//! The scene around the arm and the coupling loop.
//!
//! The arm's dynamics live in [`ArmSimulation`] (floating frame, modal or FE). The scene holds the
//! shapes riding on it ([`ArmPiece`]: each finite element as a box, the hub, the bodies it
//! carries, a rigidly clamped string), posed from the deformed centreline where they are queried
//! or drawn, and the [`ContactSource`]s that put loads on the arm: the pads of the scene's contact
//! method and a friction clamp.
//!
//! One step, top to bottom ([`Scene::step`]); each source takes part in each stage:
//! 1. pose its shapes from the arm's state;
//! 2. hand the arm the loads of its own bodies (the `rapier` pads, a friction clamp);
//! 3. find the point contacts the implicit arm step evaluates (the `compliant` pads);
//! 4. advance the arm;
//! 5. advance its own bodies to the arm's new pose (rapier's worlds);
//! 6. measure its forces.

mod clamp;
mod geometry;
mod pad_faces;
mod pads;
mod pair;
mod pipeline;
mod rapier_pads;
mod source;

use std::ops::Range;

use rapier3d_f64::prelude::*;

use crate::arm::{ArmError, ArmModel, ArmSimulation, GeneralizedLoad};
use crate::drive::DriveState;
use crate::integrate::StepControl;
use crate::model::{ContactMethod, Detection, Model, StructureShape};
use clamp::ClampPlacement;
pub use clamp::FrictionGrip;
pub use geometry::{ArmPiece, ArmView, Side};
use geometry::{pose_piece, shapes_of_robot, string_segments};
use pad_faces::PadFaces;
pub use pair::{
    ContactPair, Obstacle, PointReading, force_entity, pair_channels, pair_name, pair_names, structure_in_rest_pose,
};
use pipeline::PipelineContacts;
pub use pipeline::{ManifoldPoint, manifold_between};
use rapier_pads::RapierPads;
pub use rapier_pads::{UnsupportedPad, rapier_pad_spring};
pub use source::{ContactSource, GripReading};

/// The arm, the shapes riding on it and the sources of its contact loads.
pub struct Scene {
    /// The arm.
    pub arm: ArmSimulation,
    pieces: Vec<ArmPiece>,
    pivot_m: [f64; 3],
    /// The pads' contact method first, then a friction clamp if the string is held by one.
    sources: Vec<Box<dyn ContactSource>>,
    /// Per source, the range of the arm's contacts it found for the last step.
    spans: Vec<Range<usize>>,
    /// Where the `compliant` method finds its contacts (`auto` resolved).
    detection: Detection,
    /// Stations at which a frame samples the centreline, with their rows.
    centreline: Vec<(f64, crate::arm::StationRows)>,
    /// The held string's probe, if the arm holds one.
    pub string: Option<crate::sensor::string::StringProbe>,
    /// The string's axis off the lift plane, m.
    string_normal_offset_m: f64,
}

/// Stations along the arm at which a frame samples the centreline.
const CENTRELINE_STATIONS: usize = 20;

/// Errors building or stepping a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// In the arm.
    #[error(transparent)]
    Arm(#[from] ArmError),
    /// The drive's shaper cannot be tuned to the arm's modes.
    #[error("key `{key}`: {0}", key = .0.key())]
    Tuning(#[from] crate::tuning::TuningError),
    /// A pad the contact method cannot model.
    #[error(transparent)]
    UnsupportedPad(#[from] UnsupportedPad),
    /// A friction clamp on a string held by several hands (it holds in one hand's jaws).
    #[error("key `payload.grips`: a friction clamp holds the string in one hand's jaws; it has {0} grips")]
    FrictionClampGrips(usize),
    /// A friction clamp on a body without a collision shape to carry its jaws.
    #[error("key `payload.at`: `{0}` has no collision shape to carry the jaws")]
    ClampWithoutPalm(String),
    /// A piece of the tilting head that can reach a pad or a structure.
    #[error(
        "`{0}` turns on the tilting head and can reach a pad or a structure: contact on a tilting head is not \
         modelled yet (lock its hinge, kind=\"locked\", or keep it clear)"
    )]
    ContactOnTiltingHead(String),
    /// A model whose drive's shaper is still to be tuned to the arm's modes: its scene is built
    /// from its compiled model, which tunes it.
    #[error(
        "the drive's shaper is tuned to the arm's modes when the model is compiled: build the scene from \
         run::CompiledModel's model"
    )]
    UntunedShaper,
    /// The run's energy grew without a source, or its values stopped being finite.
    #[error("the run diverged at t = {t_s:.4} s: {what}. Advice: {advice}")]
    Diverged { t_s: f64, what: String, advice: String },
}

impl From<crate::beam::BeamError> for SceneError {
    fn from(e: crate::beam::BeamError) -> Self {
        SceneError::Arm(e.into())
    }
}

impl Scene {
    /// Builds the scene of a model at its own fidelity.
    pub fn new(model: &Model) -> Result<Self, SceneError> {
        Self::with_fidelity(model, crate::select::fidelity(model)?.fidelity)
    }

    /// Builds the scene of a model at `fidelity`.
    pub fn with_fidelity(model: &Model, fidelity: crate::arm::Fidelity) -> Result<Self, SceneError> {
        Self::with_arm(model, model.arm_model(fidelity)?)
    }

    /// Builds the scene of a model around an arm model already reduced for it.
    pub fn with_arm(model: &Model, arm_model: impl Into<std::sync::Arc<ArmModel>>) -> Result<Self, SceneError> {
        if model.drive.untuned_shaper.is_some() {
            return Err(SceneError::UntunedShaper);
        }
        let arm = ArmSimulation::new(arm_model, model.hub_drive(), model.integrator)?;
        let friction = model.payload.string().and_then(|held| held.friction_clamp().map(|_| held));
        if let Some(held) = friction.filter(|h| h.grips.len() > 1) {
            return Err(SceneError::FrictionClampGrips(held.grips.len()));
        }
        let jaw_names: Vec<&str> =
            model.robot.carried.iter().filter(|b| b.mount.is_prismatic()).map(|b| b.name.as_str()).collect();
        // With a friction clamp the jaws are rapier bodies of the clamp's own, beside a proxy of
        // the whole string; the string also rides on the arm, moved by its slip.
        let mut pieces: Vec<ArmPiece> = shapes_of_robot(model, &arm.arm.beam)
            .into_iter()
            .filter(|p| friction.is_none() || !jaw_names.contains(&p.name.as_str()))
            .collect();
        let clamped_string = friction.and_then(|_| pieces.iter().find(|p| p.side == Side::String).cloned());
        let string = model.payload.string().map(|held| crate::sensor::string::StringProbe::new(held, &arm.arm));
        let string_normal_offset_m = pieces.iter().find(|p| p.side == Side::String).map_or(0.0, |p| p.normal_offset_m);
        for piece in &mut pieces {
            piece.rows = arm.arm.station_rows(piece.hinge_m.map_or(piece.station_m, |[station, _]| station));
        }
        // A flexible string rides on its own sections: cut into segments that do.
        if string.as_ref().is_some_and(|s| s.is_flexible())
            && let Some(i) = pieces.iter().position(|p| p.side == Side::String)
        {
            let whole = pieces.remove(i);
            pieces.extend(string_segments(&whole, &arm.arm));
        }
        let pivot = model.robot.lift.pivot_m;
        let mut pairs: Vec<ContactPair> =
            model.dampeners.iter().map(|d| ContactPair::pad(d, &pieces, &arm.arm, pivot)).collect();
        let sides = if model.payload.string().is_some() { &[Side::Arm, Side::String][..] } else { &[Side::Arm] };
        for structure in &model.structures {
            pairs.extend(sides.iter().map(|side| ContactPair::structure(structure, *side)));
        }
        mark_pieces_near(&mut pieces, &pairs, pivot);
        if let Some(piece) = pieces.iter().find(|p| p.hinge_m.is_some() && p.near_pad) {
            return Err(SceneError::ContactOnTiltingHead(piece.name.clone()));
        }
        let length = arm.arm.length_m();
        let centreline = (0..=CENTRELINE_STATIONS)
            .map(|i| length * i as f64 / CENTRELINE_STATIONS as f64)
            .map(|x| (x, arm.arm.station_rows(x)))
            .collect();
        let mut scene = Scene {
            arm,
            pieces,
            pivot_m: model.robot.lift.pivot_m,
            sources: Vec::new(),
            spans: Vec::new(),
            detection: Detection::Auto,
            centreline,
            string,
            string_normal_offset_m,
        };
        scene.detection = detection(model.contact.detection, &pairs);
        let pads: Box<dyn ContactSource> = match (model.contact.method, scene.detection) {
            (ContactMethod::Compliant, Detection::PadFace) => Box::new(PadFaces::new(pairs)),
            (ContactMethod::Compliant, _) => Box::new(scene.with_view(|view| PipelineContacts::new(view, pairs))),
            (ContactMethod::Rapier, _) => Box::new(scene.with_view(|view| {
                RapierPads::new(view, pairs, model.physics.gravity_m_s2, model.time.step_s, model.contact.pad_mass_kg)
            })?),
        };
        scene.sources.push(pads);
        if let (Some(held), Some(string)) = (friction, clamped_string.as_ref()) {
            let palm_index = scene
                .pieces
                .iter()
                .position(|p| p.name == held.palm().hand)
                .ok_or_else(|| SceneError::ClampWithoutPalm(held.palm().hand.clone()))?;
            let palm = &scene.pieces[palm_index];
            let palm_pose = scene.with_view(|view| view.pose(palm));
            let at = ClampPlacement { palm_index, palm, palm_pose, string };
            let grip = FrictionGrip::new(held, &model.robot, at, model.physics.gravity_m_s2, model.time.step_s);
            scene.sources.push(Box::new(grip));
        }
        scene.spans = vec![0..0; scene.sources.len()];
        Ok(scene)
    }

    /// Calls `f` with a view of the arm's current state.
    fn with_view<T>(&self, f: impl FnOnce(&ArmView) -> T) -> T {
        let (hub, q, qd) = self.arm.kinematics();
        f(&view_of(&self.arm, (hub, &q, &qd), &self.pieces, self.pivot_m))
    }

    /// Advances the scene by `h_s` seconds (the stages of the module doc).
    pub fn step(&mut self, h_s: f64) -> Result<(), SceneError> {
        let mut load = std::mem::replace(&mut self.arm.load, GeneralizedLoad::zero(0));
        let mut contacts = std::mem::take(&mut self.arm.contacts);
        load.clear();
        contacts.clear();
        {
            let (hub, q, qd) = self.arm.kinematics();
            let arm = view_of(&self.arm, (hub, &q, &qd), &self.pieces, self.pivot_m);
            for source in &mut self.sources {
                source.pose(&arm);
            }
            for source in &self.sources {
                source.add_loads(&arm, &mut load);
            }
            for (source, span) in self.sources.iter_mut().zip(&mut self.spans) {
                let start = contacts.len();
                source.find_contacts(&arm, h_s, &mut contacts);
                *span = start..contacts.len();
            }
        }
        self.arm.load = load;
        self.arm.contacts = contacts;
        self.arm.step(h_s)?;
        self.advance_and_measure(Some(h_s));
        self.exchange_with_grip();
        Ok(())
    }

    /// A friction-clamped string is a shape riding on the arm (struck by structures) and a body
    /// in the clamp's world (its slip): the structures' force on it goes to the clamp for the
    /// next step, and its shapes move along the arm by the slip.
    fn exchange_with_grip(&mut self) {
        let on_string = self.pairs().filter(|p| p.side == Side::String).flat_map(|p| &p.points);
        let load = on_string.fold([0.0; 2], |sum, r| [sum[0] + r.force_n[0], sum[1] + r.force_n[1]]);
        let Some(slip_m) = self.sources.iter_mut().find_map(|s| s.take_string_load(load)) else { return };
        self.pieces.iter_mut().filter(|p| p.side == Side::String).for_each(|p| p.axial_shift_m = slip_m);
    }

    /// Whether the next step may be `free_step_s` long: no source has anything that could begin
    /// or change within it (no pad within reach, nothing staggered that needs the contact step).
    pub fn free_step_allowed(&self, free_step_s: f64) -> bool {
        self.with_view(|arm| self.sources.iter().all(|s| s.allows_free_step(arm, free_step_s)))
    }

    /// A step of free motion of at most `h_s` under error `control` (call where
    /// [`Self::free_step_allowed`] holds: no contact, no load to hand over). Returns the step
    /// taken and the next to try, s.
    pub fn step_free(&mut self, h_s: f64, control: &StepControl) -> Result<(f64, f64), SceneError> {
        self.arm.load.clear();
        self.arm.contacts.clear();
        self.spans.iter_mut().for_each(|span| *span = 0..0);
        let steps = self.arm.step_controlled(h_s, control)?;
        self.advance_and_measure(None);
        Ok(steps)
    }

    /// Stages 5 and 6: each source advances its own bodies over `h_s` (none on a free step) and
    /// measures its forces on the arm's new state.
    fn advance_and_measure(&mut self, h_s: Option<f64>) {
        let (hub, q, qd) = self.arm.kinematics();
        let arm = view_of(&self.arm, (hub, &q, &qd), &self.pieces, self.pivot_m);
        for (source, span) in self.sources.iter_mut().zip(&self.spans) {
            if let Some(h_s) = h_s {
                source.advance(&arm, h_s);
            }
            source.measure(&arm, &self.arm.contacts[span.clone()]);
        }
    }

    /// Where the `compliant` method finds its contacts: `pad-face` or `pipeline`.
    pub fn detection(&self) -> Detection {
        self.detection
    }

    /// The tilting head's angle on its hinge, rad (0 without one).
    fn head_rad(&self) -> f64 {
        self.arm.head_state().map_or(0.0, |h| h.angle_rad)
    }

    /// The hub state at the arm's current time.
    pub fn hub(&self) -> DriveState {
        self.arm.kinematics().0
    }

    /// Every contact pair of the scene, with its force at the end of the last step.
    pub fn pairs(&self) -> impl Iterator<Item = &ContactPair> {
        self.sources.iter().flat_map(|s| s.pairs())
    }

    /// The friction clamp, if the string is held by one.
    pub fn grip(&self) -> Option<GripReading> {
        self.sources.iter().find_map(|s| s.grip())
    }

    /// What makes the scene's state meaningless though the arm's is not, if anything.
    pub fn fault(&self) -> Option<String> {
        self.sources.iter().find_map(|s| s.fault())
    }

    /// Advice from the source most likely to blame for a divergence at `step_s`, if one is
    /// (the friction clamp first, then a staggered pad method).
    pub fn divergence_advice(&self, step_s: f64) -> Option<String> {
        self.sources.iter().rev().find_map(|s| s.divergence_advice(step_s))
    }

    /// Per pad, the arm's effective mass at the pad's station along the arm's normal with the hub
    /// held, 1 / (rᵀ M⁻¹ r), kg. `None` for a rigid arm on a prescribed hub (infinite).
    pub fn pad_effective_masses_kg(&self) -> Vec<Option<f64>> {
        let inverse = self.arm.arm.mass.clone().try_inverse().filter(|m| m.nrows() > 0);
        self.pairs().map(|pair| pair.effective_mass_kg(inverse.as_ref())).collect()
    }

    /// Per pad, the explicit stability limit of its penalty contact, 2√(m_eff/k), s, with k the
    /// law's tangent stiffness at `force_n` ([`Self::pad_effective_masses_kg`] for m_eff).
    pub fn penalty_limits_s(&self, force_n: f64) -> Vec<Option<f64>> {
        self.pairs()
            .zip(self.pad_effective_masses_kg())
            .map(|(pair, m_eff)| {
                let k = pair.obstacle.law().tangent_stiffness_at_force(force_n);
                m_eff.filter(|_| k > 0.0).map(|m| 2.0 * (m / k).sqrt())
            })
            .collect()
    }

    /// What is drawn and never changes shape: each piece's and pad's name and half extents (m),
    /// each structure with its pose.
    pub fn layout(&self) -> SceneLayout {
        let pads = self
            .pairs()
            .filter_map(|p| p.dampener())
            .map(|d| (d.name.clone(), [0.5 * d.length_m, 0.5 * d.thickness_m, 0.5 * d.width_m]));
        let mut structures: Vec<(String, Pose, StructureShape)> = Vec::new();
        for pair in self.pairs() {
            if let Obstacle::Structure(s) = &pair.obstacle
                && !structures.iter().any(|(name, ..)| *name == s.name)
            {
                structures.push((s.name.clone(), pair.pose, s.shape));
            }
        }
        SceneLayout {
            pieces: self.drawn_pieces().map(|p| (p.name.clone(), p.half_extents_m)).collect(),
            pads: pads.collect(),
            structures,
            pivot_m: self.pivot_m,
            length_m: self.arm.arm.length_m(),
            string_normal_offset_m: self.string_normal_offset_m,
            cylinders: match self.arm.drive.plant().map(|p| &p.actuator) {
                Some(crate::actuator::Actuator::Hydraulic(h)) => h.cylinders.each.clone(),
                _ => Vec::new(),
            },
        }
    }

    /// The pieces drawn as shapes (a flexible string's segments are drawn as its centreline).
    fn drawn_pieces(&self) -> impl Iterator<Item = &ArmPiece> {
        self.pieces.iter().filter(|p| !p.on_string)
    }

    /// The scene's state for drawing, from the arm's current state (poses in `layout` order).
    pub fn frame(&self) -> Frame {
        // The kinematics only: the torque and energies `sample` would compute are not drawn.
        let (hub, q, _) = self.arm.kinematics();
        let head_rad = self.head_rad();
        let pieces = self.drawn_pieces().map(|p| pose_piece(p, &hub, &q, head_rad, self.pivot_m)).collect();
        let pads = self.pairs().filter(|p| p.dampener().is_some()).map(|p| p.pose).collect();
        let contacts = self
            .pairs()
            .filter(|p| p.force_n > 0.0)
            .flat_map(|p| p.points.iter().map(|r| (p.name.clone(), r.point_m, r.force_n)))
            .collect();
        let centreline = self
            .centreline
            .iter()
            .map(|(x, rows)| {
                let [u, v, _] = rows.displacement(&q);
                (*x, [u, v])
            })
            .collect();
        // A friction-clamped string's slip moves it along the arm as a whole, its bending kept.
        let slip_m = self.grip().map_or(0.0, |g| g.slip_m);
        let string_centreline = self
            .string
            .as_ref()
            .map(|s| s.centreline_hub_m(&q).into_iter().map(|[x, y]| [x + slip_m, y]).collect())
            .unwrap_or_default();
        Frame {
            t_s: self.arm.time_s(),
            hub_angle_rad: hub.angle_rad,
            pieces,
            pads,
            contacts,
            centreline,
            string_centreline,
        }
    }
}

/// A view of `arm` at its kinematics (hub, q, q̇), carrying `pieces` about `pivot_m`.
fn view_of<'a>(
    arm: &'a ArmSimulation,
    (hub, q, qd): (DriveState, &'a nalgebra::DVector<f64>, &'a nalgebra::DVector<f64>),
    pieces: &'a [ArmPiece],
    pivot_m: [f64; 3],
) -> ArmView<'a> {
    let head_rad = arm.head_state().map_or(0.0, |h| h.angle_rad);
    ArmView { arm: &arm.arm, hub, q, qd, pieces, pivot_m, head_rad }
}

/// Where the `compliant` method finds the contacts of `pairs`, `auto` resolved: `pad-face` where
/// every pair is a pad only the arm's own face can reach (where it agrees with the pipeline,
/// docs/scene.md), else `pipeline`.
fn detection(chosen: Detection, pairs: &[ContactPair]) -> Detection {
    let pads_on_the_face = pairs.iter().all(|p| p.pad.as_ref().is_some_and(|pad| pad.arm_face_only()));
    match chosen {
        Detection::Auto if pads_on_the_face => Detection::PadFace,
        Detection::Auto => Detection::Pipeline,
        chosen => chosen,
    }
}

/// Marks the shapes that can come within 0.5 m of an obstacle of their side: only those are
/// posed for contact. A pad by its extent along the arm; a structure by distance from the pivot
/// (the arm turns about it: a piece sweeps a ring, the structure must come near the ring).
fn mark_pieces_near(pieces: &mut [ArmPiece], pairs: &[ContactPair], pivot_m: [f64; 3]) {
    for piece in pieces {
        let size = piece.half_extents_m.iter().fold(0.0_f64, |a, b| a.max(*b));
        let reach = size + 0.5;
        let radius = piece.station_m.hypot(piece.lateral_m);
        piece.near_pad = pairs.iter().filter(|p| p.involves(piece)).any(|p| match (p.dampener(), &p.obstacle) {
            (Some(d), _) => (d.station_m - piece.station_m).abs() <= 0.5 * d.length_m + reach,
            (None, Obstacle::Structure(s)) => {
                let size = s.shape.bounding_radius_m();
                let centre = (s.position_m[0] - pivot_m[0]).hypot(s.position_m[1] - pivot_m[1]);
                (centre - radius).abs() <= size + reach
            }
            _ => false,
        });
    }
}

/// The unchanging part of what is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneLayout {
    /// Piece names and half extents, m.
    pub pieces: Vec<(String, [f64; 3])>,
    /// Pad names and half extents, m.
    pub pads: Vec<(String, [f64; 3])>,
    /// Structures: name, world pose, shape.
    pub structures: Vec<(String, Pose, StructureShape)>,
    /// Pivot in the world, m.
    pub pivot_m: [f64; 3],
    /// Arm length, m.
    pub length_m: f64,
    /// A held string's axis off the lift plane, m.
    pub string_normal_offset_m: f64,
    /// The hydraulic cylinders that drive the hub, if any do.
    pub cylinders: Vec<crate::actuator::Cylinder>,
}

/// The scene at one instant, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Time, s.
    pub t_s: f64,
    /// Hub angle, rad.
    pub hub_angle_rad: f64,
    /// World pose of each piece (layout order).
    pub pieces: Vec<Pose>,
    /// World pose of each pad.
    pub pads: Vec<Pose>,
    /// Contact points: pair name, world point (m), force on the machine (world X, Y, N).
    pub contacts: Vec<(String, [f64; 3], [f64; 2])>,
    /// Centreline: station (m) and displacement in the hub frame (axial, transverse, m).
    pub centreline: Vec<(f64, [f64; 2])>,
    /// The held string's deformed centreline, hub-frame points (x, y), m (empty without one).
    pub string_centreline: Vec<[f64; 2]>,
}
