//! The sign-off's channels ([`crate::channel`]), declared by the series that holds them once the
//! run has read every step (the worst station is where the run's peak fell): σ there, the
//! pivot's force (world), each cylinder pin's (world), each hand's grip on the string (arm frame),
//! all in the tables; and each pin's and grip's force magnitude, plotted as the traces of one
//! entity, [`PINS_ENTITY`].

use super::{Fibre, StressSeries};
use crate::channel::{Channel, Reading};

/// Entity path of the pins' and grips' force magnitudes, N: a trace each, `pivot`, `cylinder` (of
/// several `cylinder_<k>`) and each hand's name.
pub const PINS_ENTITY: &str = "plots/pins";

impl StressSeries {
    /// The station and fibre of the run's largest |σ| (the last of equals), if it read any.
    pub fn peak_station(&self) -> Option<(usize, Fibre)> {
        let extremes = self.extremes();
        let each =
            extremes.iter().enumerate().flat_map(|(i, e)| Fibre::BOTH.into_iter().zip(e).map(move |(f, e)| (i, f, e)));
        each.max_by(|a, b| a.2.peak_abs().total_cmp(&b.2.peak_abs())).map(|(i, fibre, _)| (i, fibre))
    }

    /// Its channels (module doc); none without the sign-off.
    pub fn channels(&self) -> Vec<Channel> {
        let Some((station, fibre)) = self.peak_station() else { return Vec::new() };
        let upper = fibre == Fibre::Upper;
        let mut out = vec![Channel::new("stress.worst", "Pa", Reading::Stress { station, upper })];
        let magnitude = |name: String, trace: String, at| {
            Channel::new(name, "N", Reading::PinForce { at }).traced(PINS_ENTITY, trace).untabled()
        };
        out.extend(
            ["x", "y"]
                .into_iter()
                .enumerate()
                .map(|(k, axis)| Channel::new(format!("pivot.force.{axis}"), "N", Reading::PivotForce(k))),
        );
        out.push(magnitude("pivot.force".into(), "pivot".into(), self.pivot_index));
        let count = self.cylinder_indices.len();
        for (i, &at) in self.cylinder_indices.iter().enumerate() {
            let (name, trace) = match crate::actuator::cylinder_number(i, count) {
                None => ("cylinder_pin".to_string(), "cylinder".to_string()),
                Some(k) => (format!("cylinder_pin.{k}"), format!("cylinder_{k}")),
            };
            out.extend(["x", "y"].into_iter().enumerate().map(|(k, axis)| {
                Channel::new(format!("{name}.force.{axis}"), "N", Reading::SignOffValue { at: at + k, sign: 1.0 })
            }));
            out.push(magnitude(format!("{name}.force"), trace, at));
        }
        for (hand, at) in &self.hands {
            // The hand's grip on the string: minus the string's load on the hand.
            let parts = [("force.axial", "N"), ("force.transverse", "N"), ("moment", "N*m")].into_iter().enumerate();
            out.extend(parts.map(|(k, (part, unit))| {
                Channel::new(format!("grip.{hand}.{part}"), unit, Reading::SignOffValue { at: at + k, sign: -1.0 })
            }));
            out.push(magnitude(format!("grip.{hand}.force"), hand.clone(), *at));
        }
        out
    }
}
