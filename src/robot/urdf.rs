//! URDF reading: urdf-rs for the standard elements, a second XML pass (roxmltree) for
//! pipearm's elements, which urdf-rs silently drops: the flexible link's parameters, and the
//! machines that can turn the lift joint (a hydraulic cylinder, a servo motor and gearbox;
//! [`crate::actuator`]). Every attribute of a pipearm element is required; unknown ones are
//! refused.
//!
//! ```xml
//! <robot name="..." xmlns:pipearm="https://pipearm.dev/urdf/1">
//!   <joint name="lift" type="revolute">
//!     ...
//!     <pipearm:cylinder base_pin_m="0.4 -0.5" arm_pin_m="2.0 -0.7" bore_m="0.18" rod_m="0.10"
//!                       closed_length_m="1.56" stroke_m="1.0"
//!                       cap_dead_volume_m3="1.65e-3" rod_dead_volume_m3="1.45e-3"/>
//!     <!-- more cylinders on the joint: each with `valve="shared"` (the default: one valve,
//!          chambers joined) or all with `valve="own"` (one valve each) -->
//!     <pipearm:servo gear_ratio="1000" rotor_inertia_kg_m2="0.025" stiffness_n_m_per_rad="3e7"
//!                    damping_n_m_s_per_rad="5e4" torque_limit_n_m="160" speed_limit_rad_s="314.16"/>
//!   </joint>
//!   <link name="arm" pipearm:flexible="true">
//!     <pipearm:flexible elements="24" damping_ratios="0.01" hub_inertia_kg_m2="50">
//!       <pipearm:segment length_m="9" youngs_modulus_pa="2.06e11" density_kg_m3="7850"
//!                        section="hollow-rectangle" width_m="0.25" depth_m="0.5" wall_m="0.0125"/>
//!     </pipearm:flexible>
//!   </link>
//! ```

use std::collections::{HashSet, VecDeque};
use std::path::Path;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};

use super::SegmentChecks;
use super::{
    ArmSegment, CarriedBody, FlexibleLink, LiftJoint, Mount, PlacedShape, Robot, RobotError, Shape, TiltingHead,
};

mod head;
use crate::actuator::{Cylinder, Cylinders, ServoMachine, ValveFeed};
use crate::beam::{BeamModel, Material, SectionShape};

/// A segment's optional sign-off attributes: yield strength or steel grade, detail or curve.
const SEGMENT_CHECKS: [&str; 4] = ["yield_strength_pa", "steel", "detail", "curve"];

/// The arm's section shapes, as a URDF names them.
const SECTIONS: &str = "solid-circle, solid-rectangle, hollow-rectangle, tube";

/// Namespace of pipearm's URDF extensions.
pub const PIPEARM_NS: &str = "https://pipearm.dev/urdf/1";

/// Reads a robot from a URDF file, with its flexible-link parameters.
pub fn load_robot(path: &Path) -> Result<Robot, RobotError> {
    let parse = |message: String| RobotError::Parse { path: path.into(), message };
    let text = std::fs::read_to_string(path).map_err(|e| parse(format!("cannot read: {e}")))?;
    let urdf = urdf_rs::read_from_string(&text).map_err(|e| parse(format!("not valid URDF: {e}")))?;
    let doc = roxmltree::Document::parse(&text).map_err(|e| parse(format!("not well-formed XML: {e}")))?;
    let ctx = Context { path };
    let arm = ctx.flexible_link(&doc)?;
    let mut lift = ctx.lift_joint(&urdf, &arm.name)?;
    (lift.0.cylinders, lift.0.servo) = ctx.lift_machines(&doc, &lift.0.name)?;
    let (carried, head) = ctx.carried_bodies(&urdf, &doc, &arm)?;
    let base_shapes = urdf
        .links
        .iter()
        .find(|l| l.name == lift.1)
        .map(|l| ctx.collision_shapes(l, &Isometry3::identity()))
        .transpose()?
        .unwrap_or_default();
    let robot = Robot { name: urdf.name.clone(), source: path.into(), lift: lift.0, arm, carried, head, base_shapes };
    ctx.check_beam(&robot)?;
    Ok(robot)
}

struct Context<'p> {
    path: &'p Path,
}

impl Context<'_> {
    fn invalid(&self, key: impl Into<String>, message: impl Into<String>) -> RobotError {
        RobotError::InvalidInFile { path: self.path.into(), key: key.into(), message: message.into() }
    }

    /// The one link marked `pipearm:flexible="true"` and its parameters.
    fn flexible_link(&self, doc: &roxmltree::Document<'_>) -> Result<FlexibleLink, RobotError> {
        let links: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("link")).collect();
        let marked: Vec<_> = links.iter().filter(|l| l.attribute((PIPEARM_NS, "flexible")) == Some("true")).collect();
        for l in &links {
            let has_params = l.children().any(|c| c.has_tag_name((PIPEARM_NS, "flexible")));
            if has_params && !marked.iter().any(|m| m.id() == l.id()) {
                let name = l.attribute("name").unwrap_or("?");
                return Err(self.invalid(
                    format!("link[{name}]"),
                    "has <pipearm:flexible> parameters but is not marked pipearm:flexible=\"true\"",
                ));
            }
        }
        let [link] = marked.as_slice() else {
            return Err(self.invalid(
                "link@pipearm:flexible",
                format!("exactly one link must be marked pipearm:flexible=\"true\" (xmlns:pipearm=\"{PIPEARM_NS}\"); found {}", marked.len()),
            ));
        };
        let name = link.attribute("name").unwrap_or_default().to_string();
        let key = format!("link[{name}].pipearm:flexible");
        let params = link
            .children()
            .find(|c| c.has_tag_name((PIPEARM_NS, "flexible")))
            .ok_or_else(|| self.invalid(&key, "the link is marked flexible but has no <pipearm:flexible> element"))?;
        self.only_attributes(&params, &key, &["elements", "damping_ratios", "hub_inertia_kg_m2"])?;
        let elements = self.number(&params, &key, "elements")?;
        if elements.fract() != 0.0 || !(1.0..=2000.0).contains(&elements) {
            return Err(self.invalid(format!("{key}@elements"), format!("{elements}: allowed an integer 1 ..= 2000")));
        }
        let damping_ratios = self.numbers(&params, &key, "damping_ratios")?;
        if damping_ratios.is_empty() || damping_ratios.iter().any(|z| !(0.0..2.0).contains(z)) {
            return Err(self.invalid(format!("{key}@damping_ratios"), "allowed one or more ratios 0 <= ratio < 2"));
        }
        let hub_inertia_kg_m2 = self.number(&params, &key, "hub_inertia_kg_m2")?;
        if hub_inertia_kg_m2 < 0.0 {
            return Err(self.invalid(format!("{key}@hub_inertia_kg_m2"), format!("{hub_inertia_kg_m2}: allowed >= 0")));
        }
        let segments = params
            .children()
            .filter(|c| c.is_element())
            .enumerate()
            .map(|(i, c)| self.segment(&c, &format!("{key}.segment[{i}]")))
            .collect::<Result<Vec<_>, _>>()?;
        if segments.is_empty() {
            return Err(self.invalid(&key, "needs at least one <pipearm:segment>"));
        }
        Ok(FlexibleLink { name, segments, elements: elements as usize, damping_ratios, hub_inertia_kg_m2 })
    }

    fn segment(&self, node: &roxmltree::Node<'_, '_>, key: &str) -> Result<ArmSegment, RobotError> {
        if !node.has_tag_name((PIPEARM_NS, "segment")) {
            return Err(self
                .invalid(key, format!("unexpected element <{}>: allowed <pipearm:segment>", node.tag_name().name())));
        }
        let written = node
            .attribute("section")
            .ok_or_else(|| self.invalid(format!("{key}@section"), format!("missing: allowed {SECTIONS}")))?;
        // Kebab-case, as every value in a scenario; the snake_case of older files is read too.
        let kind = written.replace('_', "-");
        let kind = kind.as_str();
        let dims: &[&str] = match kind {
            "solid-circle" => &["diameter_m"],
            "solid-rectangle" => &["width_m", "depth_m"],
            "hollow-rectangle" => &["width_m", "depth_m", "wall_m"],
            "tube" => &["outer_diameter_m", "wall_m"],
            _ => {
                return Err(self.invalid(format!("{key}@section"), format!("`{written}`: allowed {SECTIONS}")));
            }
        };
        let mut allowed = vec!["section", "length_m", "youngs_modulus_pa", "density_kg_m3"];
        allowed.extend_from_slice(dims);
        allowed.extend_from_slice(&SEGMENT_CHECKS);
        self.only_attributes(node, key, &allowed)?;
        let n = |name| self.number(node, key, name);
        let section = match kind {
            "solid-circle" => SectionShape::SolidCircle { diameter_m: n("diameter_m")? },
            "solid-rectangle" => SectionShape::SolidRectangle { width_m: n("width_m")?, depth_m: n("depth_m")? },
            "hollow-rectangle" => {
                SectionShape::HollowRectangle { width_m: n("width_m")?, depth_m: n("depth_m")?, wall_m: n("wall_m")? }
            }
            _ => SectionShape::Tube { outer_diameter_m: n("outer_diameter_m")?, wall_m: n("wall_m")? },
        };
        let material = Material { youngs_modulus_pa: n("youngs_modulus_pa")?, density_kg_m3: n("density_kg_m3")? };
        let length_m = n("length_m")?;
        // The section is checked before its steel: a grade's yield depends on a wall that must
        // first be a wall.
        crate::beam::Segment::from_shape(length_m, &section, &material)
            .and_then(|s| crate::beam::BeamSpec::uniform(s, 1).validate())
            .map_err(|e| self.invalid(key, e.to_string()))?;
        let checks = self.segment_checks(node, key, &section)?;
        Ok(ArmSegment { length_m, section, material, checks })
    }

    /// A segment's yield strength (`yield_strength_pa`, or `steel` naming a grade) and S–N
    /// curve (`detail`, an EN 1993-1-9 category, or `curve`, a DNVGL-RP-C203 curve in air).
    fn segment_checks(
        &self,
        node: &roxmltree::Node<'_, '_>,
        key: &str,
        section: &SectionShape,
    ) -> Result<SegmentChecks, RobotError> {
        use super::{YieldSource, YieldStrength};
        use crate::steel;
        let one_of = |a: &str, b: &str| -> Result<(), RobotError> {
            if node.attribute(a).is_some() && node.attribute(b).is_some() {
                return Err(self.invalid(format!("{key}@{b}"), format!("give {a} or {b}, not both")));
            }
            Ok(())
        };
        one_of("yield_strength_pa", "steel")?;
        one_of("detail", "curve")?;
        let yield_strength = if node.attribute("yield_strength_pa").is_some() {
            let fy = self.number(node, key, "yield_strength_pa")?;
            if fy <= 0.0 {
                return Err(self.invalid(format!("{key}@yield_strength_pa"), format!("{fy}: allowed > 0")));
            }
            Some(YieldStrength { strength_pa: fy, source: YieldSource::Given })
        } else if let Some(name) = node.attribute("steel") {
            let grade = steel::grade(name).ok_or_else(|| {
                self.invalid(format!("{key}@steel"), format!("`{name}`: allowed {}", steel::grade_names()))
            })?;
            let t = steel::nominal_thickness_m(section);
            let fy = grade.yield_strength_pa(t).ok_or_else(|| {
                let max_mm = grade.max_thickness_m() * 1e3;
                let message = format!(
                    "{} is tabled up to {max_mm} mm thick; this section is {} mm: give yield_strength_pa",
                    grade.name,
                    t * 1e3
                );
                self.invalid(format!("{key}@steel"), message)
            })?;
            Some(YieldStrength { strength_pa: fy, source: YieldSource::Grade(grade) })
        } else {
            None
        };
        let sn_curve = match (node.attribute("detail"), node.attribute("curve")) {
            (Some(detail), _) => Some(
                crate::fatigue::SnCurve::en1993(detail)
                    .map_err(|e| self.invalid(format!("{key}@detail"), e.to_string()))?,
            ),
            (None, Some(curve)) => Some(
                crate::fatigue::SnCurve::dnv(curve).map_err(|e| self.invalid(format!("{key}@curve"), e.to_string()))?,
            ),
            (None, None) => None,
        };
        Ok(SegmentChecks { yield_strength, sn_curve })
    }

    /// Rejects attributes outside `allowed` (a typo must not silently become a default).
    fn only_attributes(&self, node: &roxmltree::Node<'_, '_>, key: &str, allowed: &[&str]) -> Result<(), RobotError> {
        match node.attributes().find(|a| a.namespace().is_none() && !allowed.contains(&a.name())) {
            Some(a) => Err(self
                .invalid(format!("{key}@{}", a.name()), format!("unknown attribute: allowed {}", allowed.join(", ")))),
            None => Ok(()),
        }
    }

    fn number(&self, node: &roxmltree::Node<'_, '_>, key: &str, name: &str) -> Result<f64, RobotError> {
        let text = node.attribute(name).ok_or_else(|| self.invalid(format!("{key}@{name}"), "missing"))?;
        text.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| self.invalid(format!("{key}@{name}"), format!("`{text}` is not a finite number")))
    }

    fn numbers(&self, node: &roxmltree::Node<'_, '_>, key: &str, name: &str) -> Result<Vec<f64>, RobotError> {
        let text = node.attribute(name).ok_or_else(|| self.invalid(format!("{key}@{name}"), "missing"))?;
        text.split_whitespace()
            .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| self.invalid(format!("{key}@{name}"), format!("`{text}` is not a list of numbers")))
    }

    /// The revolute joint about z whose child is the arm; returns it and its parent link.
    fn lift_joint(&self, urdf: &urdf_rs::Robot, arm: &str) -> Result<(LiftJoint, String), RobotError> {
        let joint = urdf.joints.iter().find(|j| j.child.link == arm).ok_or_else(|| {
            self.invalid(format!("link[{arm}]"), "the flexible link must be the child of the lift joint (revolute)")
        })?;
        let key = format!("joint[{}]", joint.name);
        if joint.joint_type != urdf_rs::JointType::Revolute {
            return Err(self.invalid(&key, format!("type {:?}: the lift joint must be revolute", joint.joint_type)));
        }
        if joint.axis.xyz.0 != [0.0, 0.0, 1.0] {
            return Err(self.invalid(
                format!("{key}.axis"),
                format!("{:?}: the lift joint turns about z (0 0 1)", joint.axis.xyz.0),
            ));
        }
        if joint.origin.rpy.0 != [0.0, 0.0, 0.0] {
            return Err(self.invalid(format!("{key}.origin@rpy"), "must be 0 0 0: the arm lies along x at zero angle"));
        }
        let (lower, upper) = (joint.limit.lower, joint.limit.upper);
        let (effort, velocity) = (joint.limit.effort, joint.limit.velocity);
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if lower >= upper || lower.is_nan() || upper.is_nan() || !positive(effort) || !positive(velocity) {
            return Err(self.invalid(
                format!("{key}.limit"),
                format!(
                    "lower = {lower}, upper = {upper}, effort = {effort}, velocity = {velocity}: needs lower < upper \
                     (rad), effort > 0 (N·m) and velocity > 0 (rad/s)"
                ),
            ));
        }
        let lift = LiftJoint {
            name: joint.name.clone(),
            pivot_m: joint.origin.xyz.0,
            limits_rad: (lower, upper),
            effort_n_m: effort,
            velocity_rad_s: velocity,
            cylinders: None,
            servo: None,
        };
        Ok((lift, joint.parent.link.clone()))
    }

    /// The machines that can turn the lift joint: any number of `<pipearm:cylinder>` (their
    /// `valve` attributes agreeing) and at most one `<pipearm:servo>` among the joint's children,
    /// no other pipearm element there.
    fn lift_machines(
        &self,
        doc: &roxmltree::Document<'_>,
        joint: &str,
    ) -> Result<(Option<Cylinders>, Option<ServoMachine>), RobotError> {
        let key = format!("joint[{joint}]");
        let node =
            doc.root_element().children().find(|n| n.has_tag_name("joint") && n.attribute("name") == Some(joint));
        let ours: Vec<_> =
            node.iter().flat_map(|n| n.children()).filter(|c| c.tag_name().namespace() == Some(PIPEARM_NS)).collect();
        let count = ours.iter().filter(|c| c.has_tag_name((PIPEARM_NS, "cylinder"))).count();
        let (mut cylinders, mut servo): (Option<Cylinders>, _) = (None, None);
        for child in ours {
            let name = child.tag_name().name();
            match name {
                "cylinder" => {
                    let index = cylinders.as_ref().map_or(0, |c| c.each.len());
                    let child_key = super::cylinder_element(joint, index, count);
                    let (cylinder, feed) = self.cylinder(&child, &child_key)?;
                    match &mut cylinders {
                        None => cylinders = Some(Cylinders { each: vec![cylinder], feed }),
                        Some(c) if c.feed == feed => c.each.push(cylinder),
                        Some(c) => {
                            return Err(self.invalid(
                                format!("{child_key}@valve"),
                                format!(
                                    "\"{}\" where the first cylinder's is \"{}\": allowed one feed for all of a \
                                     joint's cylinders, \"shared\" (one valve) or \"own\" (one valve each)",
                                    feed.name(),
                                    c.feed.name()
                                ),
                            ));
                        }
                    }
                }
                "servo" if servo.is_none() => servo = Some(self.servo(&child, &format!("{key}.pipearm:servo"))?),
                "servo" => {
                    return Err(self.invalid(format!("{key}.pipearm:servo"), "given twice: allowed one per joint"));
                }
                _ => {
                    return Err(self.invalid(
                        &key,
                        format!("unexpected element <pipearm:{name}>: allowed <pipearm:cylinder>, <pipearm:servo>"),
                    ));
                }
            }
        }
        Ok((cylinders, servo))
    }

    /// `<pipearm:cylinder>`: pins, bore and rod, lengths and dead volumes ([`Cylinder`]), and
    /// how its valve feeds it (`valve`, optional: `shared`, the default, or `own`).
    fn cylinder(&self, node: &roxmltree::Node<'_, '_>, key: &str) -> Result<(Cylinder, ValveFeed), RobotError> {
        self.only_attributes(
            node,
            key,
            &[
                "base_pin_m",
                "arm_pin_m",
                "bore_m",
                "rod_m",
                "closed_length_m",
                "stroke_m",
                "cap_dead_volume_m3",
                "rod_dead_volume_m3",
                "valve",
            ],
        )?;
        let feed = match node.attribute("valve") {
            None | Some("shared") => ValveFeed::Shared,
            Some("own") => ValveFeed::Own,
            Some(other) => {
                return Err(self.invalid(
                    format!("{key}@valve"),
                    format!(
                        "\"{other}\": allowed \"shared\" (one valve for the joint's cylinders) or \"own\" (one each)"
                    ),
                ));
            }
        };
        let positive = |name| self.positive(node, key, name);
        let cylinder = Cylinder {
            base_pin_m: self.pin(node, key, "base_pin_m")?,
            arm_pin_m: self.pin(node, key, "arm_pin_m")?,
            bore_m: positive("bore_m")?,
            rod_m: positive("rod_m")?,
            closed_length_m: positive("closed_length_m")?,
            stroke_m: positive("stroke_m")?,
            cap_dead_volume_m3: positive("cap_dead_volume_m3")?,
            rod_dead_volume_m3: positive("rod_dead_volume_m3")?,
        };
        let c = &cylinder;
        if c.rod_m >= c.bore_m {
            return Err(self.invalid(
                format!("{key}@rod_m"),
                format!("{} is not below the bore {}: allowed 0 < rod_m < bore_m", c.rod_m, c.bore_m),
            ));
        }
        if c.closed_length_m <= c.stroke_m {
            return Err(self.invalid(
                format!("{key}@closed_length_m"),
                format!(
                    "{} does not exceed the stroke {}: a single-stage rod retracts into its barrel, allowed \
                     closed_length_m > stroke_m",
                    c.closed_length_m, c.stroke_m
                ),
            ));
        }
        if c.arm_pin_m == [0.0, 0.0] {
            return Err(self.invalid(format!("{key}@arm_pin_m"), "at the pivot: the cylinder would have no lever"));
        }
        Ok((cylinder, feed))
    }

    /// `<pipearm:servo>`: gearbox, rotor, drive train and the motor's limits ([`ServoMachine`]).
    fn servo(&self, node: &roxmltree::Node<'_, '_>, key: &str) -> Result<ServoMachine, RobotError> {
        self.only_attributes(
            node,
            key,
            &[
                "gear_ratio",
                "rotor_inertia_kg_m2",
                "stiffness_n_m_per_rad",
                "damping_n_m_s_per_rad",
                "torque_limit_n_m",
                "speed_limit_rad_s",
            ],
        )?;
        let positive = |name| self.positive(node, key, name);
        let damping = self.number(node, key, "damping_n_m_s_per_rad")?;
        if damping < 0.0 {
            return Err(self.invalid(format!("{key}@damping_n_m_s_per_rad"), format!("{damping}: allowed >= 0")));
        }
        Ok(ServoMachine {
            gear_ratio: positive("gear_ratio")?,
            rotor_inertia_kg_m2: positive("rotor_inertia_kg_m2")?,
            stiffness_n_m_per_rad: positive("stiffness_n_m_per_rad")?,
            damping_n_m_s_per_rad: damping,
            torque_limit_n_m: positive("torque_limit_n_m")?,
            speed_limit_rad_s: positive("speed_limit_rad_s")?,
        })
    }

    /// A required attribute that must be a finite number > 0.
    fn positive(&self, node: &roxmltree::Node<'_, '_>, key: &str, name: &str) -> Result<f64, RobotError> {
        let value = self.number(node, key, name)?;
        if value > 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(format!("{key}@{name}"), format!("{value}: allowed > 0")))
        }
    }

    /// A required attribute of two numbers "x y", m.
    fn pin(&self, node: &roxmltree::Node<'_, '_>, key: &str, name: &str) -> Result<[f64; 2], RobotError> {
        match *self.numbers(node, key, name)?.as_slice() {
            [x, y] => Ok([x, y]),
            _ => Err(self.invalid(format!("{key}@{name}"), "allowed two numbers \"x y\" (m, from the pivot)")),
        }
    }

    /// Links hanging from the arm through fixed, prismatic or revolute joints, in the arm frame,
    /// and the tilting head where a revolute joint's hinge is a spring.
    fn carried_bodies(
        &self,
        urdf: &urdf_rs::Robot,
        doc: &roxmltree::Document<'_>,
        arm: &FlexibleLink,
    ) -> Result<(Vec<CarriedBody>, Option<TiltingHead>), RobotError> {
        let mut frames = VecDeque::from([(arm.name.clone(), Isometry3::identity(), Mount::Fixed, false)]);
        let mut seen = HashSet::from([arm.name.clone()]);
        let (mut bodies, mut hinge) = (Vec::new(), None);
        while let Some((parent, parent_pose, parent_mount, parent_tilts)) = frames.pop_front() {
            for joint in urdf.joints.iter().filter(|j| j.parent.link == parent) {
                let key = format!("joint[{}]", joint.name);
                let pose = parent_pose * pose_of(&joint.origin);
                let mut tilts = parent_tilts;
                let mount = match joint.joint_type {
                    urdf_rs::JointType::Fixed => parent_mount,
                    urdf_rs::JointType::Prismatic => self.prismatic(joint, &pose, &key)?,
                    urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous => {
                        if let head::Hinge::Free(law) = self.hinge(doc, &joint.name)? {
                            if parent_tilts || hinge.is_some() {
                                return Err(self.invalid(&key, "a second spring hinge: allowed one tilting head"));
                            }
                            hinge = Some(self.hinge_on_arm(joint, &pose, law, arm.length_m())?);
                            tilts = true;
                        }
                        parent_mount
                    }
                    ref other => {
                        return Err(self.invalid(
                            &key,
                            format!("type {other:?}: links on the arm hang on fixed, prismatic or revolute joints"),
                        ));
                    }
                };
                if !seen.insert(joint.child.link.clone()) {
                    return Err(self.invalid(&key, "the link tree has a loop"));
                }
                let link =
                    urdf.links.iter().find(|l| l.name == joint.child.link).ok_or_else(|| {
                        self.invalid(&key, format!("child link `{}` is not defined", joint.child.link))
                    })?;
                bodies.push(self.carried_body(link, &pose, mount, tilts, arm.length_m())?);
                frames.push_back((link.name.clone(), pose, mount, tilts));
            }
        }
        let head = hinge.map(|h| h.with_links(&bodies));
        Ok((bodies, head))
    }

    /// A prismatic joint's mount: its axis in the arm frame, effort and travel.
    fn prismatic(&self, joint: &urdf_rs::Joint, pose: &Isometry3<f64>, key: &str) -> Result<Mount, RobotError> {
        let axis = pose.rotation * nalgebra::Vector3::from(joint.axis.xyz.0);
        if joint.limit.effort.is_nan() || joint.limit.effort <= 0.0 || axis.norm() < 1e-9 {
            return Err(self.invalid(key, "a prismatic joint needs a non-zero axis and limit effort > 0 (N)"));
        }
        let (lower, upper) = (joint.limit.lower, joint.limit.upper);
        if !(lower.is_finite() && upper.is_finite() && lower < upper) {
            return Err(self.invalid(
                format!("{key}.limit"),
                format!("lower = {lower}, upper = {upper}: a prismatic joint needs lower < upper (m)"),
            ));
        }
        let axis = axis.normalize();
        Ok(Mount::Prismatic { axis: [axis.x, axis.y, axis.z], effort_n: joint.limit.effort, travel_m: [lower, upper] })
    }

    /// A spring hinge's place on the arm: its axis normal to the lift plane, on the arm.
    fn hinge_on_arm(
        &self,
        joint: &urdf_rs::Joint,
        pose: &Isometry3<f64>,
        law: super::HingeLaw,
        length_m: f64,
    ) -> Result<TiltingHead, RobotError> {
        let key = format!("joint[{}]", joint.name);
        let axis = pose.rotation * nalgebra::Vector3::from(joint.axis.xyz.0);
        if axis.norm() < 1e-9 || axis.z.abs() < (1.0 - 1e-9) * axis.norm() {
            return Err(self.invalid(
                format!("{key}.axis"),
                format!(
                    "({:.3}, {:.3}, {:.3}) in the arm frame: a tilting head turns about an axis normal to the lift \
                     plane (the arm's z)",
                    axis.x, axis.y, axis.z
                ),
            ));
        }
        let at = pose.translation.vector;
        if !(0.0..=length_m).contains(&at.x) {
            return Err(self.invalid(
                format!("{key}.origin"),
                format!("the hinge is at arm station {:.3} m, off the arm: allowed 0 ..= {length_m} m", at.x),
            ));
        }
        Ok(TiltingHead {
            joint: joint.name.clone(),
            hinge_station_m: at.x,
            hinge_lateral_m: at.y,
            law,
            mass_kg: 0.0,
            centre_of_mass_m: [0.0; 2],
            inertia_kg_m2: 0.0,
            links: Vec::new(),
        })
    }

    fn carried_body(
        &self,
        link: &urdf_rs::Link,
        pose: &Isometry3<f64>,
        mount: Mount,
        tilts: bool,
        length_m: f64,
    ) -> Result<CarriedBody, RobotError> {
        let key = format!("link[{}].inertial", link.name);
        let cg = pose * pose_of(&link.inertial.origin) * Point3::origin();
        let (mass_kg, izz) = (link.inertial.mass.value, link.inertial.inertia.izz);
        if !(mass_kg.is_finite() && mass_kg >= 0.0) {
            return Err(self.invalid(format!("{key}.mass@value"), format!("{mass_kg}: allowed >= 0 kg")));
        }
        if !(izz.is_finite() && izz >= 0.0) {
            return Err(self.invalid(format!("{key}.inertia@izz"), format!("{izz}: allowed >= 0 kg·m²")));
        }
        // A tilting head may reach past the arm's end: its hinge is what must be on the arm.
        if mass_kg > 0.0 && !tilts && !(0.0..=length_m).contains(&cg.x) {
            return Err(self.invalid(
                format!("link[{}]", link.name),
                format!("centre of mass at arm station {:.3} m is off the arm: allowed 0 ..= {length_m} m", cg.x),
            ));
        }
        Ok(CarriedBody {
            name: link.name.clone(),
            mount,
            station_m: cg.x,
            lateral_m: cg.y,
            normal_offset_m: cg.z,
            mass_kg,
            rotary_inertia_kg_m2: izz,
            shapes: self.collision_shapes(link, pose)?,
            tilts,
        })
    }

    fn collision_shapes(&self, link: &urdf_rs::Link, pose: &Isometry3<f64>) -> Result<Vec<PlacedShape>, RobotError> {
        link.collision
            .iter()
            .map(|c| {
                let placed = pose * pose_of(&c.origin);
                let shape = match &c.geometry {
                    urdf_rs::Geometry::Box { size } => Shape::Box { half_extents_m: size.0.map(|s| s / 2.0) },
                    urdf_rs::Geometry::Cylinder { radius, length } => {
                        Shape::Cylinder { radius_m: *radius, half_length_m: length / 2.0 }
                    }
                    urdf_rs::Geometry::Sphere { radius } => Shape::Sphere { radius_m: *radius },
                    _ => {
                        return Err(self.invalid(
                            format!("link[{}].collision.geometry", link.name),
                            "unsupported: allowed box, cylinder, sphere",
                        ));
                    }
                };
                let (roll, pitch, yaw) = placed.rotation.euler_angles();
                let t = placed.translation.vector;
                Ok(PlacedShape { position_m: [t.x, t.y, t.z], rpy_rad: [roll, pitch, yaw], shape })
            })
            .collect()
    }

    /// Builds the beam once so that a bad combination (e.g. a mass off the arm) fails here.
    fn check_beam(&self, robot: &Robot) -> Result<(), RobotError> {
        robot
            .beam_spec(&[])
            .and_then(BeamModel::new)
            .map(|_| ())
            .map_err(|e| self.invalid(format!("link[{}]", robot.arm.name), e.to_string()))
    }
}

fn pose_of(p: &urdf_rs::Pose) -> Isometry3<f64> {
    let [x, y, z] = p.xyz.0;
    let [r, pi, ya] = p.rpy.0;
    Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::from_euler_angles(r, pi, ya))
}
