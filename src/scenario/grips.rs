//! The string's grips: which hands hold it and where along it, and whether they hold it on the
//! tilting head.

use super::{Check, DEFAULT_HAND, GripSpec, ScenarioError};
use crate::arm::Fidelity;
use crate::model::{Clamp, Grip, HeldString};
use crate::robot::{PipeString, Robot};

impl Check<'_> {
    /// The grips on a string: `at` (one hand at the string's middle) or `grips`, each hand a link
    /// on the arm (or on its tilting head: [`Check::string_on_head`]), no hand twice or on another's station, each grip on the string, and the grips
    /// as far apart along the string as their hands are along the arm.
    pub(super) fn grips(
        &self,
        at: Option<&str>,
        grips: Option<&[GripSpec]>,
        pipe: &PipeString,
        robot: &Robot,
    ) -> Result<Vec<Grip>, ScenarioError> {
        let length = pipe.length_m;
        let specs: Vec<(String, GripSpec)> = match (at, grips) {
            (Some(_), Some(_)) => {
                return Err(self.invalid("payload.at", "give either `at` (one hand at the string's middle) or `grips`"));
            }
            (_, Some([])) => return Err(self.invalid("payload.grips", "empty: allowed one or more { hand, at_m }")),
            (_, Some(list)) => {
                list.iter().enumerate().map(|(i, g)| (format!("payload.grips[{i}]"), g.clone())).collect()
            }
            (at, None) => {
                let hand = at.unwrap_or(DEFAULT_HAND).to_string();
                vec![("payload".into(), GripSpec { hand, at_m: Some(0.5 * length) })]
            }
        };
        let key_of = |prefix: &str, k: &str| {
            if prefix == "payload" { "payload.at".to_string() } else { format!("{prefix}.{k}") }
        };
        let arm_length = robot.arm.length_m();
        let mut resolved: Vec<(String, Grip)> = Vec::with_capacity(specs.len());
        for (prefix, spec) in &specs {
            let body = robot.body(&spec.hand).ok_or_else(|| {
                let names: Vec<_> = robot.carried.iter().map(|b| b.name.as_str()).collect();
                self.invalid(
                    &key_of(prefix, "hand"),
                    format!("`{}` is not a link on the arm: allowed {}", spec.hand, names.join(", ")),
                )
            })?;
            // A hand on the tilting head may reach past the arm's end, as the head may.
            if !(body.station_m > 0.0 && (body.station_m <= arm_length || body.tilts)) {
                return Err(self.invalid(
                    &key_of(prefix, "hand"),
                    format!(
                        "`{}` sits at arm station {} m, beyond the arm: allowed 0 < station <= {arm_length}",
                        spec.hand, body.station_m
                    ),
                ));
            }
            if let Some((other, _)) =
                resolved.iter().find(|(_, g)| g.hand == spec.hand || (g.station_m - body.station_m).abs() < 0.05)
            {
                return Err(self.invalid(
                    &key_of(prefix, "hand"),
                    format!(
                        "`{}` overlaps the hand of {other}: hands must be different links at least 0.05 m apart",
                        spec.hand
                    ),
                ));
            }
            if let Some(at_m) = spec.at_m
                && !(at_m.is_finite() && (0.0..=length).contains(&at_m))
            {
                return Err(self.invalid(
                    &key_of(prefix, "at_m"),
                    format!("{at_m} is outside 0 ..= {length} (the string's length, m)"),
                ));
            }
            resolved.push((
                prefix.clone(),
                Grip { hand: spec.hand.clone(), station_m: body.station_m, at_m: spec.at_m.unwrap_or(f64::NAN) },
            ));
        }
        let given = specs.iter().filter(|(_, g)| g.at_m.is_some()).count();
        if given != 0 && given != specs.len() {
            return Err(self.invalid(
                "payload.grips",
                "give at_m for every grip or for none (none: the string centred between its hands)",
            ));
        }
        resolved.sort_by(|a, b| a.1.station_m.total_cmp(&b.1.station_m));
        if given == 0 {
            let mid = 0.5 * (resolved[0].1.station_m + resolved[resolved.len() - 1].1.station_m);
            for (_, grip) in &mut resolved {
                grip.at_m = 0.5 * length + grip.station_m - mid;
            }
            if let Some((prefix, grip)) = resolved.iter().find(|(_, g)| !(0.0..=length).contains(&g.at_m)) {
                return Err(self.invalid(
                    &key_of(prefix, "hand"),
                    format!(
                        "`{}` is {:.3} m from the string's centre, beyond the string ({length} m long)",
                        grip.hand,
                        grip.at_m - 0.5 * length
                    ),
                ));
            }
        }
        let (_, first) = &resolved[0];
        for (prefix, grip) in &resolved[1..] {
            let (along_arm, along_string) = (grip.station_m - first.station_m, grip.at_m - first.at_m);
            if (along_arm - along_string).abs() > 1e-3 {
                return Err(self.invalid(
                    &key_of(prefix, "at_m"),
                    format!(
                        "{} grips {along_string:.3} m along the string from {}, but the hands are {along_arm:.3} m apart on the arm: allowed at_m = {:.3}",
                        grip.hand, first.hand, first.at_m + along_arm
                    ),
                ));
            }
        }
        Ok(resolved.into_iter().map(|(_, g)| g).collect())
    }

    /// Whether `held` is gripped by hands on the tilting head. It is then rigid with the head,
    /// its mass and inertia the head's: every hand on the head, clamped fast, the string rigid
    /// (`auto` takes it so).
    pub(super) fn string_on_head(&self, held: &HeldString, robot: &Robot) -> Result<bool, ScenarioError> {
        let Some(head) = &robot.head else { return Ok(false) };
        let tilts = |g: &Grip| robot.body(&g.hand).is_some_and(|b| b.tilts);
        let on_head = held.grips.iter().filter(|g| tilts(g)).count();
        if on_head == 0 {
            return Ok(false);
        }
        let joint = &head.joint;
        if on_head < held.grips.len() {
            let message = format!(
                "hands on the tilting head (joint `{joint}`) and on the arm: allowed every hand on the head or none"
            );
            return Err(self.invalid("payload.grips", message));
        }
        if held.clamp != Clamp::Rigid {
            let message = "a string on the tilting head is held fast by its hands: allowed \"rigid\"";
            return Err(self.invalid("payload.clamp", message));
        }
        if held.model.is_some_and(|f| f != Fidelity::Rigid) {
            let message = "a string on the tilting head is rigid with it: allowed { kind = \"rigid\" } or auto";
            return Err(self.invalid("payload.model", message));
        }
        Ok(true)
    }

    /// A string on the tilting head strikes nothing: its contact with rig structures is modelled
    /// for a string riding on the arm only.
    pub(super) fn head_without_structures(&self, structures: &[super::StructureSpec]) -> Result<(), ScenarioError> {
        if structures.is_empty() {
            return Ok(());
        }
        let message = "a string held on the tilting head takes no part in contact: allowed no [[structures]] \
                       (hold it with hands on the arm, or lock the head's hinge)";
        Err(self.invalid("structures", message))
    }
}
