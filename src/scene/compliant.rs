//! `contact.method = "compliant"`: each pad's force law, evaluated inside the implicit arm step.
//!
//! Per pad, parry's contact query between the pad's box and each arm shape that can reach it
//! (posed from the arm's state) finds the deepest point within reach; it becomes a
//! [`PointContact`] whose law the arm step evaluates on the arm's configuration within the step
//! (no staggering, no added-mass trap). rapier's `detect_collisions` gave the same points through
//! its broad phase and manifolds at about twice the instructions a detection.

use std::any::Any;

use rapier3d_f64::prelude::*;

use super::geometry::{ArmPiece, ArmView};
use super::pads::Pad;
use super::source::ContactSource;
use crate::arm::{ArmContact, PointContact};

/// Pads whose force law the arm step evaluates.
pub struct CompliantPads {
    pads: Vec<Pad>,
    /// Closing speed at first touch of each pad's current impact, m/s.
    impact_speed_m_s: Vec<f64>,
}

impl CompliantPads {
    /// The pads, placed.
    pub fn new(pads: Vec<Pad>) -> Self {
        let impact_speed_m_s = vec![0.0; pads.len()];
        CompliantPads { pads, impact_speed_m_s }
    }

    /// How far ahead a contact must be seen: the arm's fastest closing during a step, with margin.
    fn reach_m(arm: &ArmView, h_s: f64) -> f64 {
        (3.0 * arm.speed_bound_m_s() * h_s).max(2e-3)
    }

    /// The deepest point of the arm against pad `i`, within `reach` of touching.
    fn deepest_point(&mut self, i: usize, arm: &ArmView, reach: f64) -> Option<ArmContact> {
        let pad = &self.pads[i];
        // Shapes whose bounding box is beyond reach of the pad's are not queried.
        let pad_box = pad.shape.compute_aabb(&pad.pose).loosened(reach);
        let mut best: Option<(f64, Vector, &ArmPiece, Pose)> = None;
        for piece in arm.pieces.iter().filter(|p| p.near_pad) {
            let pose = arm.pose(piece);
            if !piece.shape.compute_aabb(&pose).intersects(&pad_box) {
                continue;
            }
            let found = parry3d_f64::query::contact(&pose, &*piece.shape, &pad.pose, &*pad.shape, reach);
            if let Ok(Some(contact)) = found
                && contact.dist <= reach
                && best.as_ref().is_none_or(|b| contact.dist < b.0)
            {
                best = Some((contact.dist, contact.point1, piece, pose));
            }
        }
        let (dist, world, piece, pose) = best?;
        let world = [world.x, world.y, world.z];
        let (station_m, lateral_m) = piece.station_of(&pose, world);
        let point = PointContact {
            pair: i,
            station_m,
            lateral_m,
            normal_world: pad.normal_world,
            depth_m: -dist,
            reference_point_m: [world[0] - arm.pivot_m[0], world[1] - arm.pivot_m[1]],
            law: pad.dampener.law,
            impact_speed_m_s: self.impact_speed_m_s[i],
        };
        // Projected once: the same rows give the closing speed now and the force in the step.
        let mut contact = arm.arm.arm_contact(point);
        let closing = contact.state(&arm.hub, arm.q, arm.qd).rate_m_s;
        if pad.force_n <= 0.0 {
            self.impact_speed_m_s[i] = closing.max(1e-6);
        }
        self.pads[i].touching = Some(piece.name.clone());
        contact.contact.impact_speed_m_s = self.impact_speed_m_s[i];
        Some(contact)
    }
}

impl ContactSource for CompliantPads {
    fn find_contacts(&mut self, arm: &ArmView, h_s: f64, contacts: &mut Vec<ArmContact>) {
        // Contact queries are most of a step's cost: skip them while every pad is out of reach.
        if self.allows_free_step(arm, h_s) {
            return;
        }
        let reach = Self::reach_m(arm, h_s);
        contacts.extend((0..self.pads.len()).filter_map(|i| self.deepest_point(i, arm, reach)));
    }

    fn measure(&mut self, arm: &ArmView, contacts: &[ArmContact]) {
        for pad in &mut self.pads {
            pad.force_n = 0.0;
            pad.compression_m = 0.0;
        }
        for c in contacts {
            let state = c.state(&arm.hub, arm.q, arm.qd);
            let pad = &mut self.pads[c.contact.pair];
            pad.force_n = state.force_n;
            pad.compression_m = state.depth_m.max(0.0);
            pad.point_m = state.point_m;
            if state.force_n <= 0.0 {
                pad.touching = None;
            }
        }
    }

    fn pads(&self) -> &[Pad] {
        &self.pads
    }

    fn allows_free_step(&self, arm: &ArmView, h_s: f64) -> bool {
        // Three times the travel of the arm's fastest point over the step.
        let travel_m = 3.0 * arm.speed_bound_m_s() * h_s;
        !self.pads.iter().any(|p| p.within_reach(arm, travel_m))
    }

    fn fault(&self) -> Option<String> {
        self.pads.iter().find_map(Pad::fault)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
