//! What the arm and the string strike: the scenario's `[[dampeners]]`, rubber pads set against the
//! arm at its stops, and its `[[structures]]`, fixed rig structure placed in the world.
//!
//! ```toml
//! [[structures]]
//! name = "well_guide"
//! shape = { kind = "box", size_m = [0.3, 0.4, 0.6] }   # or { kind = "cylinder", radius_m, length_m }
//! position_m = [0.6, 2.5, 0.0]                          # world position of its centre
//! angle_deg = 0.0                                        # about the world z axis
//! law = { kind = "hunt-crossley", stiffness = 2e7, exponent = 1.5, restitution = 0.4 }
//! friction = 0.3
//! ```
//!
//! Positions are in the world frame of the URDF (the lift plane is the x–y plane through the
//! pivot); a cylinder stands along world z, across the lift plane.

use serde::{Deserialize, Serialize};

use super::{Check, ScenarioError};
use crate::contact::ForceLaw;
use crate::model::{ContactMethod, ContactOptions, Dampener, Detection, Face, Model, Structure, StructureShape};
use crate::robot::Robot;

use super::ScenarioSpec;

/// Largest extent of a structure, m.
const MAX_SIZE_M: f64 = 50.0;

/// A rubber pad as a scenario states it (angles in degrees).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampenerSpec {
    /// Name of the pad (the contact pair is reported as `arm-<name>`).
    pub name: String,
    /// Lift angle of the stop the pad is set against, deg.
    pub angle_deg: f64,
    /// Arm station the pad's centre faces, m.
    pub station_m: f64,
    /// Arm face it touches.
    pub face: Face,
    /// Clearance between that face and the pad with the undeformed arm at the stop, m.
    pub gap_m: f64,
    /// Pad thickness (normal to the face), m.
    pub thickness_m: f64,
    /// Pad extent along the arm, m.
    pub length_m: f64,
    /// Pad extent across the lift plane, m.
    pub width_m: f64,
    /// Force law of the rubber.
    pub law: ForceLaw,
}

/// A structure as a scenario states it (angles in degrees, full sizes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StructureSpec {
    /// Its name (pairs are reported as `arm-<name>` and `string-<name>`).
    pub name: String,
    /// Its shape.
    pub shape: ShapeSpec,
    /// World position of its centre, m.
    pub position_m: [f64; 3],
    /// Rotation about the world z axis, deg.
    #[serde(default)]
    pub angle_deg: f64,
    /// Force law of its face.
    pub law: ForceLaw,
    /// Coulomb friction coefficient of its face against steel (default 0.3).
    #[serde(default = "default_friction")]
    pub friction: f64,
}

fn default_friction() -> f64 {
    0.3
}

/// A structure's shape as a scenario states it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ShapeSpec {
    /// A box of these full sizes along its own x, y, z, m.
    Box { size_m: [f64; 3] },
    /// A cylinder along world z: radius and length, m.
    Cylinder { radius_m: f64, length_m: f64 },
}

impl Check<'_> {
    pub(super) fn dampener(
        &self,
        i: usize,
        d: &DampenerSpec,
        robot: &Robot,
        spec: &ScenarioSpec,
    ) -> Result<Dampener, ScenarioError> {
        let key = |k: &str| format!("dampeners[{i}].{k}");
        let length = robot.arm.length_m();
        if !(d.station_m.is_finite() && (0.0..=length).contains(&d.station_m)) {
            return Err(
                self.invalid(&key("station_m"), format!("{} is outside 0 ..= {length} (the arm length)", d.station_m))
            );
        }
        if !(d.angle_deg.is_finite() && (-180.0..=180.0).contains(&d.angle_deg)) {
            return Err(self.invalid(&key("angle_deg"), format!("{} is outside -180 ..= 180", d.angle_deg)));
        }
        if !(d.gap_m.is_finite() && (0.0..=1.0).contains(&d.gap_m)) {
            return Err(self.invalid(&key("gap_m"), format!("{} is outside 0 ..= 1", d.gap_m)));
        }
        for (name, v) in [("thickness_m", d.thickness_m), ("length_m", d.length_m), ("width_m", d.width_m)] {
            if !(v.is_finite() && v > 0.0 && v <= 5.0) {
                return Err(self.invalid(&key(name), format!("{v} is outside 0 < {name} <= 5")));
            }
        }
        d.law.validate().map_err(|(name, v, allowed)| {
            self.invalid(&key(&format!("law.{name}")), format!("{v} is outside {allowed}"))
        })?;
        let dampener = Dampener {
            name: d.name.clone(),
            angle_rad: d.angle_deg.to_radians(),
            station_m: d.station_m,
            face: d.face,
            gap_m: d.gap_m,
            thickness_m: d.thickness_m,
            length_m: d.length_m,
            width_m: d.width_m,
            law: d.law,
        };
        if spec.contact.method == ContactMethod::Rapier {
            crate::scene::rapier_pad_spring(&dampener).map_err(|(k, message)| self.invalid(&key(k), message))?;
        }
        Ok(dampener)
    }

    /// `[[structures]]`: sizes, placement, law and friction in range, names unique among
    /// structures and dampeners.
    pub(super) fn structures(
        &self,
        specs: &[StructureSpec],
        dampener_names: &[&str],
        contact: &ContactOptions,
    ) -> Result<Vec<Structure>, ScenarioError> {
        if !specs.is_empty() && contact.method == ContactMethod::Rapier {
            let message = "the rapier method models pads only: allowed \"compliant\" with [[structures]]";
            return Err(self.invalid("contact.kind", message));
        }
        if !specs.is_empty() && contact.detection == Detection::PadFace {
            let message = "pad-face sees pads only: allowed \"pipeline\" or \"auto\" with [[structures]]";
            return Err(self.invalid("contact.detection", message));
        }
        let mut structures: Vec<Structure> = Vec::with_capacity(specs.len());
        for (i, spec) in specs.iter().enumerate() {
            let key = |k: &str| format!("structures[{i}].{k}");
            let taken = structures.iter().any(|s| s.name == spec.name) || dampener_names.contains(&spec.name.as_str());
            if spec.name.is_empty() || taken {
                return Err(self
                    .invalid(&key("name"), format!("`{}`: allowed a name no other structure or pad has", spec.name)));
            }
            let in_size = |v: f64| v.is_finite() && v > 0.0 && v <= MAX_SIZE_M;
            let shape = match spec.shape {
                ShapeSpec::Box { size_m } => {
                    if let Some(v) = size_m.iter().find(|v| !in_size(**v)) {
                        return Err(self.invalid(&key("shape.size_m"), format!("{v} is outside 0 < size <= 50")));
                    }
                    StructureShape::Box { half_extents_m: size_m.map(|v| 0.5 * v) }
                }
                ShapeSpec::Cylinder { radius_m, length_m } => {
                    for (name, v) in [("radius_m", radius_m), ("length_m", length_m)] {
                        if !in_size(v) {
                            return Err(self
                                .invalid(&key(&format!("shape.{name}")), format!("{v} is outside 0 < {name} <= 50")));
                        }
                    }
                    StructureShape::Cylinder { radius_m, half_length_m: 0.5 * length_m }
                }
            };
            if let Some(v) = spec.position_m.iter().find(|v| !(v.is_finite() && v.abs() <= 1e3)) {
                return Err(self.invalid(&key("position_m"), format!("{v} is outside -1000 ..= 1000")));
            }
            if !(spec.angle_deg.is_finite() && (-180.0..=180.0).contains(&spec.angle_deg)) {
                return Err(self.invalid(&key("angle_deg"), format!("{} is outside -180 ..= 180", spec.angle_deg)));
            }
            if !(spec.friction.is_finite() && (0.0..=2.0).contains(&spec.friction)) {
                return Err(self.invalid(&key("friction"), format!("{} is outside 0 ..= 2", spec.friction)));
            }
            spec.law.validate().map_err(|(name, v, allowed)| {
                self.invalid(&key(&format!("law.{name}")), format!("{v} is outside {allowed}"))
            })?;
            structures.push(Structure {
                name: spec.name.clone(),
                shape,
                position_m: spec.position_m,
                angle_rad: spec.angle_deg.to_radians(),
                law: spec.law,
                friction: spec.friction,
            });
        }
        Ok(structures)
    }

    /// No structure may overlap the arm, what it carries or the string in the rest pose at the
    /// drive's start: the run would begin inside it.
    pub(super) fn structures_clear(&self, model: &Model) -> Result<(), ScenarioError> {
        match crate::scene::structure_in_rest_pose(model) {
            Some((i, piece)) => Err(self.invalid(
                &format!("structures[{i}].position_m"),
                format!(
                    "`{}` overlaps the {piece} in its rest pose at the drive's start: allowed a place clear of the \
                     arm, what it carries and the string",
                    model.structures[i].name
                ),
            )),
            None => Ok(()),
        }
    }
}
