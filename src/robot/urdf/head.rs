//! `<pipearm:hinge>`: the dynamics of a revolute joint on the arm (a tilting head's wrist).

use super::{Context, PIPEARM_NS};
use crate::robot::{HingeLaw, RobotError};

/// What a revolute joint on the arm declares: locked (read as fixed) or a hinge law.
pub(super) enum Hinge {
    Locked,
    Free(HingeLaw),
}

impl Context<'_> {
    /// The `<pipearm:hinge>` inside joint `joint`: `kind="locked"`, `kind="spring"` with
    /// `stiffness_n_m_per_rad` (> 0) and `damping_n_m_s_per_rad` (>= 0, default 0), or
    /// `kind="driven"` (its profile from the scenario's `head.drive`).
    pub(super) fn hinge(&self, doc: &roxmltree::Document<'_>, joint: &str) -> Result<Hinge, RobotError> {
        let key = format!("joint[{joint}].pipearm:hinge");
        let node = doc
            .root_element()
            .children()
            .find(|n| n.has_tag_name("joint") && n.attribute("name") == Some(joint))
            .and_then(|n| n.children().find(|c| c.has_tag_name((PIPEARM_NS, "hinge"))))
            .ok_or_else(|| {
                self.invalid(
                    &key,
                    "missing: a revolute joint on the arm needs its dynamics, <pipearm:hinge kind=\"locked\"/> or \
                     <pipearm:hinge kind=\"spring\" stiffness_n_m_per_rad=\"...\" damping_n_m_s_per_rad=\"...\"/>",
                )
            })?;
        match node.attribute("kind") {
            Some("locked") => {
                self.only_attributes(&node, &key, &["kind"])?;
                Ok(Hinge::Locked)
            }
            Some("spring") => {
                self.only_attributes(&node, &key, &["kind", "stiffness_n_m_per_rad", "damping_n_m_s_per_rad"])?;
                let stiffness_n_m_per_rad = self.positive(&node, &key, "stiffness_n_m_per_rad")?;
                let damping_n_m_s_per_rad = match node.attribute("damping_n_m_s_per_rad") {
                    None => 0.0,
                    Some(_) => self.number(&node, &key, "damping_n_m_s_per_rad")?,
                };
                if damping_n_m_s_per_rad < 0.0 {
                    return Err(self.invalid(
                        format!("{key}@damping_n_m_s_per_rad"),
                        format!("{damping_n_m_s_per_rad}: allowed >= 0 N·m·s/rad"),
                    ));
                }
                Ok(Hinge::Free(HingeLaw::Spring { stiffness_n_m_per_rad, damping_n_m_s_per_rad }))
            }
            Some("driven") => {
                self.only_attributes(&node, &key, &["kind"])?;
                Ok(Hinge::Free(HingeLaw::Driven { profile: None }))
            }
            other => Err(self.invalid(
                format!("{key}@kind"),
                format!(
                    "{}: allowed \"locked\", \"spring\" or \"driven\"",
                    other.map_or("missing".into(), |k| format!("`{k}`"))
                ),
            )),
        }
    }
}
