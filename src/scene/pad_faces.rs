//! `contact.detection = "pad-face"`: each pad's face against the arm's face, without a collision
//! query, evaluated inside the implicit arm step.
//!
//! The arm's face is its tangent line at the pad's station (with the elastic slope); the pad's
//! law is spread over the two ends of the pad's face, half each, at the arm's penetration there
//! measured along the pad's normal. These are the points rapier's manifold holds for a pad's box
//! pressed flat on the arm's box (its four corners, in two pairs of equal depth across the lift
//! plane), so the pipeline's Winkler spreading gives the same force. It sees the arm's own face
//! only: shapes standing out beyond it, and structures, need the pipeline (`auto` knows).

use super::geometry::ArmView;
use super::pair::ContactPair;
use super::source::ContactSource;
use crate::arm::ArmContact;

/// Pads whose force law the arm step evaluates at the two ends of each face.
pub struct PadFaces {
    pads: Vec<ContactPair>,
    /// Closing speed at first touch of each pad's current impact, m/s.
    impact_speed_m_s: Vec<f64>,
}

impl PadFaces {
    /// The pads, placed (pairs of the arm and a pad only).
    pub fn new(pads: Vec<ContactPair>) -> Self {
        let impact_speed_m_s = vec![0.0; pads.len()];
        PadFaces { pads, impact_speed_m_s }
    }

    /// Pad `i`'s two contacts, if the arm's face is within `reach` of either end.
    fn contacts(&mut self, i: usize, arm: &ArmView, reach: f64, contacts: &mut Vec<ArmContact>) {
        let pair = &self.pads[i];
        let Some(placement) = pair.pad.as_ref() else { return };
        let mut ends = placement.end_contacts(arm, i, pair.obstacle.law());
        if ends.iter().all(|c| c.contact.depth_m < -reach) {
            return;
        }
        if pair.force_n <= 0.0 {
            let closing = ends.iter().map(|c| c.state(&arm.hub, arm.q, arm.qd).rate_m_s).fold(0.0, f64::max);
            self.impact_speed_m_s[i] = closing.max(1e-6);
        }
        for end in &mut ends {
            end.contact.impact_speed_m_s = self.impact_speed_m_s[i];
        }
        contacts.extend(ends);
    }
}

impl ContactSource for PadFaces {
    fn find_contacts(&mut self, arm: &ArmView, h_s: f64, contacts: &mut Vec<ArmContact>) {
        if self.allows_free_step(arm, h_s) {
            return;
        }
        let reach = arm.contact_reach_m(h_s);
        for i in 0..self.pads.len() {
            self.contacts(i, arm, reach, contacts);
        }
    }

    fn measure(&mut self, arm: &ArmView, contacts: &[ArmContact]) {
        super::pair::measure_points(&mut self.pads, arm, contacts, |_| "arm");
    }

    fn pairs(&self) -> &[ContactPair] {
        &self.pads
    }

    fn allows_free_step(&self, arm: &ArmView, h_s: f64) -> bool {
        ContactPair::none_within_reach(&self.pads, arm, h_s)
    }

    fn fault(&self) -> Option<String> {
        self.pads.iter().find_map(ContactPair::fault)
    }
}
