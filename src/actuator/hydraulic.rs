//! A hydraulic drive: a double-acting cylinder between a base pin and an arm pin, a four-way
//! proportional valve, a relief valve per chamber, and a position controller on the joint angle.
//!
//! Cylinder length s(θ) = |R(θ) a − b| (a the arm pin in the hub frame, b the base pin, both
//! from the pivot); its moment arm ds/dθ turns the rod force F into the hub torque F ds/dθ.
//! With A₁ the cap-side and A₂ the rod-side area, V₁ = V₁₀ + A₁ (s − s_closed) and
//! V₂ = V₂₀ + A₂ (s_closed + stroke − s) the chamber volumes (V₁₀, V₂₀ dead volumes of cylinder
//! and hoses), β the oil's bulk modulus, Merritt's chamber equations:
//!
//! ```text
//! ṗ₁ = β / V₁ (Q₁ − A₁ ṡ − Q_r1)        ṗ₂ = β / V₂ (Q₂ + A₂ ṡ − Q_r2)
//! F = p₁ A₁ − p₂ A₂ + F_end(s, ṡ)
//! ```
//!
//! The valve (critically lapped, matched, symmetric) with spool opening x ∈ [−1, 1] and flow
//! gain K = Q_rated / √Δp_rated per land (Q = C_d A √(2 Δp / ρ) with C_d A √(2/ρ) = K at full
//! opening):
//!
//! ```text
//! x ≥ 0:  Q₁ = K x √(p_s − p₁),   Q₂ = −K x √(p₂ − p_t)
//! x < 0:  Q₁ = K x √(p₁ − p_t),   Q₂ = −K x √(p_s − p₂)
//! τ_s ẋ = x_cmd − x
//! ```
//!
//! √ is taken signed and rounded off below a hundredth of the rated drop (Δp/(Δp² + δ²)^¼), so
//! that the flow and its derivative stay finite where a chamber's pressure crosses supply or
//! tank. A relief valve per chamber passes the valve's rated flow at 5 % over its setting; a
//! check valve lets oil in from tank below tank pressure (no cavitation). Beyond the stroke the
//! rod meets the end cap: a stiff spring and damper ([`END_STOP_STIFFNESS_N_M`]).
//!
//! The controller's output is the spool command; its velocity feed-forward is the opening whose
//! flow through the metering-in land, at the chamber pressures it reads, moves the rod at the
//! reference's speed, times `velocity_feedforward` (1: the full estimate).

use serde::{Deserialize, Serialize};

use super::ControllerGains;

/// Stiffness of the cylinder's end stops, N/m (steel on steel through a cushion).
pub const END_STOP_STIFFNESS_N_M: f64 = 1e9;
/// Damping of the cylinder's end stops, N·s/m.
pub const END_STOP_DAMPING_N_S_M: f64 = 1e6;

/// The cylinder and its hoses, from the URDF's `<pipearm:cylinder>` on the lift joint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cylinder {
    /// Base pin (x, y) from the pivot in the base frame, m.
    pub base_pin_m: [f64; 2],
    /// Arm pin (x along the arm, y across) from the pivot in the hub frame, m.
    pub arm_pin_m: [f64; 2],
    /// Bore (piston diameter), m.
    pub bore_m: f64,
    /// Rod diameter, m (< bore).
    pub rod_m: f64,
    /// Pin-to-pin length fully retracted, m.
    pub closed_length_m: f64,
    /// Stroke, m.
    pub stroke_m: f64,
    /// Oil volume on the cap side when retracted (cylinder dead volume and hose), m³.
    pub cap_dead_volume_m3: f64,
    /// Oil volume on the rod side when extended, m³.
    pub rod_dead_volume_m3: f64,
}

impl Cylinder {
    /// Cap-side area A₁, m².
    pub fn cap_area_m2(&self) -> f64 {
        std::f64::consts::FRAC_PI_4 * self.bore_m.powi(2)
    }

    /// Rod-side (annulus) area A₂, m².
    pub fn rod_area_m2(&self) -> f64 {
        std::f64::consts::FRAC_PI_4 * (self.bore_m.powi(2) - self.rod_m.powi(2))
    }

    /// The arm pin from the pivot in the base frame at hub angle `angle_rad` (the arm
    /// undeformed), m.
    pub fn arm_pin_at_m(&self, angle_rad: f64) -> [f64; 2] {
        let (s, c) = angle_rad.sin_cos();
        let [ax, ay] = self.arm_pin_m;
        [c * ax - s * ay, s * ax + c * ay]
    }

    /// Pin-to-pin length s (m) and moment arm ds/dθ (m/rad) at hub angle `angle_rad`.
    pub fn length_and_arm(&self, angle_rad: f64) -> (f64, f64) {
        let pin = self.arm_pin_at_m(angle_rad);
        let d = [pin[0] - self.base_pin_m[0], pin[1] - self.base_pin_m[1]];
        let length = d[0].hypot(d[1]);
        // d/dθ of the pin is (−pin_y, pin_x).
        (length, (pin[0] * d[1] - pin[1] * d[0]) / length)
    }

    /// Chamber volumes (cap, rod) at length `length_m`, m³.
    pub fn volumes_m3(&self, length_m: f64) -> (f64, f64) {
        let extension = length_m - self.closed_length_m;
        (
            self.cap_dead_volume_m3 + self.cap_area_m2() * extension,
            self.rod_dead_volume_m3 + self.rod_area_m2() * (self.stroke_m - extension),
        )
    }

    /// Force of the end caps on the rod (positive: extending), N.
    pub fn end_stop_force_n(&self, length_m: f64, rate_m_s: f64) -> f64 {
        let extension = length_m - self.closed_length_m;
        let (k, c) = (END_STOP_STIFFNESS_N_M, END_STOP_DAMPING_N_S_M);
        if extension < 0.0 {
            (-k * extension - c * rate_m_s).max(0.0)
        } else if extension > self.stroke_m {
            (-k * (extension - self.stroke_m) - c * rate_m_s).min(0.0)
        } else {
            0.0
        }
    }

    /// Oil spring of the locked cylinder, β (A₁²/V₁ + A₂²/V₂), N/m, at length `length_m`.
    pub fn oil_stiffness_n_m(&self, bulk_modulus_pa: f64, length_m: f64) -> f64 {
        let (v1, v2) = self.volumes_m3(length_m);
        bulk_modulus_pa * (self.cap_area_m2().powi(2) / v1 + self.rod_area_m2().powi(2) / v2)
    }
}

/// The proportional valve, from the scenario's `actuator.valve`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Valve {
    /// Flow per land at full opening and the rated pressure drop, m³/s (datasheet).
    pub rated_flow_m3_s: f64,
    /// Pressure drop per land at which the rated flow is given, Pa (datasheet: often 35 bar).
    pub rated_pressure_drop_pa: f64,
    /// Time constant of the spool's first-order response, s.
    pub spool_time_constant_s: f64,
    /// Laminar leakage per land at null, m³/s per Pa (datasheet: internal leakage over its test
    /// pressure): each control port leaks to supply and tank through it. It is the valve's
    /// pressure-flow coefficient, the main damping of the oil column under a position loop.
    #[serde(default)]
    pub leakage_m3_s_per_pa: f64,
}

impl Valve {
    /// Flow gain K = Q_rated / √Δp_rated, m³/s/√Pa.
    pub fn flow_gain(&self) -> f64 {
        self.rated_flow_m3_s / self.rated_pressure_drop_pa.sqrt()
    }

    /// Flow through a land opened `opening` (fraction) under a drop `drop_pa`, m³/s (signed
    /// √ rounded off near zero, module doc).
    pub fn land_flow_m3_s(&self, opening: f64, drop_pa: f64) -> f64 {
        let delta = 0.01 * self.rated_pressure_drop_pa;
        self.flow_gain() * opening * drop_pa / (drop_pa * drop_pa + delta * delta).sqrt().sqrt()
    }
}

/// The circuit's operation, from the scenario's `[actuator]` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HydraulicCircuit {
    /// Supply pressure p_s, Pa.
    pub supply_pressure_pa: f64,
    /// Tank (return) pressure p_t, Pa.
    pub tank_pressure_pa: f64,
    /// Effective bulk modulus of oil and hoses, Pa.
    pub bulk_modulus_pa: f64,
    /// Setting of the chambers' relief valves, Pa.
    pub relief_pressure_pa: f64,
    /// The proportional valve.
    pub valve: Valve,
}

impl HydraulicCircuit {
    /// Flows into the chambers (cap, rod) through the valve at spool `opening` and chamber
    /// pressures `p` (Pa), relief and anti-cavitation included, m³/s.
    pub fn flows_m3_s(&self, opening: f64, p: [f64; 2]) -> [f64; 2] {
        let (ps, pt, valve) = (self.supply_pressure_pa, self.tank_pressure_pa, &self.valve);
        let [q1, q2] = if opening >= 0.0 {
            [valve.land_flow_m3_s(opening, ps - p[0]), -valve.land_flow_m3_s(opening, p[1] - pt)]
        } else {
            [valve.land_flow_m3_s(opening, p[0] - pt), -valve.land_flow_m3_s(opening, ps - p[1])]
        };
        let leakage = |p: f64| valve.leakage_m3_s_per_pa * ((ps - p) - (p - pt));
        [q1 + leakage(p[0]) - self.relief_flow_m3_s(p[0]), q2 + leakage(p[1]) - self.relief_flow_m3_s(p[1])]
    }

    /// Flow out of a chamber at pressure `p` through its relief valve (negative: in through
    /// its check valve from tank), m³/s.
    fn relief_flow_m3_s(&self, p: f64) -> f64 {
        let gain = self.valve.rated_flow_m3_s / (0.05 * self.relief_pressure_pa);
        gain * ((p - self.relief_pressure_pa).max(0.0) - (self.tank_pressure_pa - p).max(0.0))
    }
}

/// How the cylinders on the lift joint are fed: the `valve` attribute of each
/// `<pipearm:cylinder>` (all of a joint's must agree).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ValveFeed {
    /// One valve feeds them all in parallel: their cap sides joined, their rod sides joined, one
    /// pair of chamber pressures.
    #[default]
    Shared,
    /// Each cylinder has a valve of its own (the scenario's `actuator.valve`, one per cylinder)
    /// and its own chamber pressures; every spool follows the one controller's command.
    Own,
}

impl ValveFeed {
    /// The spelling of the URDF's `valve` attribute.
    pub fn name(self) -> &'static str {
        match self {
            ValveFeed::Shared => "shared",
            ValveFeed::Own => "own",
        }
    }
}

/// The cylinders on the lift joint (at least one) and how their valves feed them.
#[derive(Debug, Clone, PartialEq)]
pub struct Cylinders {
    /// Each cylinder, in the URDF's order.
    pub each: Vec<Cylinder>,
    /// One valve for all, or one each.
    pub feed: ValveFeed,
}

impl Cylinders {
    /// A single cylinder.
    pub fn one(cylinder: Cylinder) -> Self {
        Cylinders { each: vec![cylinder], feed: ValveFeed::Shared }
    }

    /// How many pairs of chamber pressures they have: one shared, or one per cylinder.
    pub fn chambers(&self) -> usize {
        match self.feed {
            ValveFeed::Shared => 1,
            ValveFeed::Own => self.each.len(),
        }
    }

    /// The pair of chamber pressures cylinder `i` reads.
    pub fn chamber_of(&self, i: usize) -> usize {
        match self.feed {
            ValveFeed::Shared => 0,
            ValveFeed::Own => i,
        }
    }

    /// The cap-side and rod-side areas times each cylinder's moment arm at hub angle `angle_rad`,
    /// summed: the hub torque per pascal in the cap and in the rod side, m³ (all chambers at the
    /// same pressures).
    pub fn moment_areas_m3(&self, angle_rad: f64) -> (f64, f64) {
        let levers: Vec<f64> = self.each.iter().map(|c| c.length_and_arm(angle_rad).1).collect();
        self.moment_areas_with(&levers)
    }

    /// [`Self::moment_areas_m3`] with the moment arms `levers_m` given (the deformed arm's).
    fn moment_areas_with(&self, levers_m: &[f64]) -> (f64, f64) {
        self.each
            .iter()
            .zip(levers_m)
            .fold((0.0, 0.0), |(a1, a2), (c, l)| (a1 + c.cap_area_m2() * l, a2 + c.rod_area_m2() * l))
    }
}

/// How outputs number cylinder `k` (from 0) among `count`: a lone cylinder has no number
/// (`actuator.rod_force`, the pin loads' trace `cylinder`), several are numbered from 1 in the
/// URDF's order (`actuator.rod_force.2`, the trace `cylinder_2`).
pub fn cylinder_number(k: usize, count: usize) -> Option<usize> {
    (count > 1).then_some(k + 1)
}

/// A hydraulic drive: cylinders, circuit and controller.
#[derive(Debug, Clone, PartialEq)]
pub struct HydraulicDrive {
    /// The cylinders and hoses.
    pub cylinders: Cylinders,
    /// The circuit's operation.
    pub circuit: HydraulicCircuit,
    /// The position controller on the joint angle; its output is the spool command.
    pub controller: ControllerGains,
}

impl HydraulicDrive {
    /// Chamber pressures (cap, rod) and spool opening that hold a hub torque `torque_n_m` at
    /// rest, the cylinders' moment arms `levers_m`: Σ (p₁ A₁ − p₂ A₂) lever = torque with no
    /// net flow into any chamber. Every valve sits at the same null, so every chamber pair holds
    /// the same pressures. Without leakage the spool is centred and p₁ + p₂ = p_s + p_t (a
    /// matched valve's null); with it, the spool opens just enough to feed the leaks (Newton's
    /// method from there). `Err` when no such state lies between tank and supply.
    pub fn holding_state(&self, torque_n_m: f64, levers_m: &[f64]) -> Result<([f64; 2], f64), String> {
        let (a1, a2) = self.cylinders.moment_areas_with(levers_m);
        let (ps, pt) = (self.circuit.supply_pressure_pa, self.circuit.tank_pressure_pa);
        let pressures = |p1: f64| [p1, (p1 * a1 - torque_n_m) / a2];
        let (mut p1, mut spool) = ((torque_n_m + a2 * (ps + pt)) / (a1 + a2), 0.0);
        let residual = |p1: f64, spool: f64| self.circuit.flows_m3_s(spool, pressures(p1));
        for _ in 0..50 {
            let r = residual(p1, spool);
            if r[0].abs().max(r[1].abs()) < 1e-12 * self.circuit.valve.rated_flow_m3_s {
                break;
            }
            let (dp, dx) = (1e-6 * ps, 1e-7);
            let (rp, rx) = (residual(p1 + dp, spool), residual(p1, spool + dx));
            let j = [[(rp[0] - r[0]) / dp, (rx[0] - r[0]) / dx], [(rp[1] - r[1]) / dp, (rx[1] - r[1]) / dx]];
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            p1 -= (j[1][1] * r[0] - j[0][1] * r[1]) / det;
            spool -= (-j[1][0] * r[0] + j[0][0] * r[1]) / det;
        }
        let p = pressures(p1);
        if p.iter().chain([&spool]).any(|v| !v.is_finite()) || p.iter().any(|p| !(pt..=ps).contains(p)) {
            return Err(format!(
                "holding the arm takes {torque_n_m:.0} N·m at the hub, which needs chamber pressures \
                 {:.3e} and {:.3e} Pa outside tank to supply ({pt:.3e} to {ps:.3e} Pa)",
                p[0], p[1]
            ));
        }
        Ok((p, spool))
    }

    /// The spool opening whose flow through the metering-in lands turns the hub at `rate_rad_s`
    /// at `angle_rad` with the chambers at `pressures_pa` (cap, rod; one pair per valve):
    /// Σ A₁ ṡ = K x √(p_s − p₁) extending, Σ A₂ |ṡ| = K |x| √(p_s − p₂) retracting, per valve,
    /// averaged over the valves — the controller reads the chamber pressures, so the
    /// feed-forward follows the load (a drop fixed in advance would be off by the load's share).
    pub fn feedforward_opening(&self, angle_rad: f64, rate_rad_s: f64, pressures_pa: &[[f64; 2]]) -> f64 {
        let c = &self.circuit;
        let cylinders = &self.cylinders;
        // One (cap, rod) flow demand per valve, inline: this runs at every controller sample.
        let mut demand: smallvec::SmallVec<[(f64, f64); 2]> = smallvec::smallvec![(0.0, 0.0); cylinders.chambers()];
        for (i, cylinder) in cylinders.each.iter().enumerate() {
            let rate_m_s = cylinder.length_and_arm(angle_rad).1 * rate_rad_s;
            let d = &mut demand[cylinders.chamber_of(i)];
            (d.0, d.1) = (d.0 + cylinder.cap_area_m2() * rate_m_s, d.1 + cylinder.rod_area_m2() * rate_m_s);
        }
        let opening = demand.iter().zip(pressures_pa).map(|(&(cap_flow, rod_flow), p)| {
            let (flow, chamber) = if cap_flow >= 0.0 { (cap_flow, p[0]) } else { (rod_flow, p[1]) };
            // Floored at a tenth of the supply: a chamber at supply pressure leaves no drop to meter.
            let drop = (c.supply_pressure_pa - chamber).max(0.1 * c.supply_pressure_pa);
            flow / (c.valve.flow_gain() * drop.sqrt())
        });
        opening.sum::<f64>() / demand.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cylinder() -> Cylinder {
        Cylinder {
            base_pin_m: [1.0, -1.0],
            arm_pin_m: [1.0, -0.3],
            bore_m: 0.14,
            rod_m: 0.08,
            closed_length_m: 0.5,
            stroke_m: 1.0,
            cap_dead_volume_m3: 1e-3,
            rod_dead_volume_m3: 1e-3,
        }
    }

    #[test]
    fn moment_arm_is_the_derivative_of_the_length() {
        let c = cylinder();
        for theta in [0.0, 0.4, 1.2] {
            let h = 1e-6;
            let numeric = (c.length_and_arm(theta + h).0 - c.length_and_arm(theta - h).0) / (2.0 * h);
            assert!((numeric - c.length_and_arm(theta).1).abs() < 1e-8, "at {theta}");
        }
    }

    #[test]
    fn land_flow_follows_the_orifice_law_above_the_round_off() {
        let v = Valve {
            rated_flow_m3_s: 1e-3,
            rated_pressure_drop_pa: 3.5e6,
            spool_time_constant_s: 0.01,
            leakage_m3_s_per_pa: 0.0,
        };
        // The round-off δ = 1 % of the rated drop scales the flow by (1 + δ²/Δp²)^(−1/4).
        for drop in [1e6, 3.5e6, 1e7] {
            let exact = 1e-3 * 0.5 * (drop / 3.5e6f64).sqrt();
            let tolerance = 0.3 * (0.01 * 3.5e6 / drop).powi(2);
            assert!((v.land_flow_m3_s(0.5, drop) / exact - 1.0).abs() < tolerance);
            assert!((v.land_flow_m3_s(0.5, -drop) + exact).abs() < tolerance * exact);
        }
    }
}
