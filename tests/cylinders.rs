//! Several cylinders on the lift joint (docs/model-actuators.md, "Several cylinders"): two
//! identical cylinders equal one with twice their areas, fed by one valve or by one each, and
//! two cylinders on different pins hold the arm where the moments about the pivot balance.

mod common;

use common::{ACTUATORS, model, uniform, validated};
use pipearm::actuator::{
    Actuator, ActuatorPlant, ControllerGains, Cylinder, Cylinders, HydraulicCircuit, HydraulicDrive, Valve, ValveFeed,
};
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, HubDrive};
use pipearm::drive::{MotionProfile, TrapezoidLimit};
use pipearm::integrate::IntegratorKind;

const GEN_ALPHA: IntegratorKind = IntegratorKind::GeneralizedAlpha { rho_inf: 0.8 };
const STEP_S: f64 = 1e-3;

/// A 4 m, 200 kg arm on a 100 kg·m² hub under gravity: modal(3), or rigid.
fn arm(fidelity: Fidelity) -> ArmModel {
    let options = ArmOptions { gravity_m_s2: 9.81, hub_inertia_kg_m2: 100.0, ..ArmOptions::default() };
    ArmModel::new(model(uniform(4.0, 2e6, 50.0, 8)), fidelity, options).unwrap()
}

/// A cylinder under the arm, its pins `scale` times as far from the pivot as the first's.
fn cylinder(scale: f64, bore_m: f64, rod_m: f64) -> Cylinder {
    Cylinder {
        base_pin_m: [0.8 * scale, -0.6 * scale],
        arm_pin_m: [0.8 * scale, -0.2 * scale],
        bore_m,
        rod_m,
        closed_length_m: 0.3 * scale,
        stroke_m: 0.5 * scale,
        cap_dead_volume_m3: 5e-4,
        rod_dead_volume_m3: 4e-4,
    }
}

fn circuit(flow_factor: f64) -> HydraulicCircuit {
    HydraulicCircuit {
        supply_pressure_pa: 20e6,
        tank_pressure_pa: 0.5e6,
        bulk_modulus_pa: 1.2e9,
        relief_pressure_pa: 25e6,
        valve: Valve {
            rated_flow_m3_s: 1e-3 * flow_factor,
            rated_pressure_drop_pa: 3.5e6,
            spool_time_constant_s: 0.01,
            leakage_m3_s_per_pa: 2e-12 * flow_factor,
        },
    }
}

fn gains() -> ControllerGains {
    ControllerGains {
        kp: 4.0,
        ki: 2.0,
        kd: 0.0,
        velocity_feedforward: 1.0,
        acceleration_feedforward: 0.0,
        rate_hz: None,
    }
}

/// The arm lifted 0 → 0.4 rad in 1.5 s and held, on `cylinders` fed by `circuit`.
fn lift(arm: ArmModel, cylinders: Cylinders, circuit: HydraulicCircuit) -> ArmSimulation {
    let actuator = Actuator::Hydraulic(HydraulicDrive { cylinders, circuit, controller: gains() });
    let reference = MotionProfile::trapezoidal(0.0, 0.4, 1.5, TrapezoidLimit::RampFraction(0.25)).unwrap();
    let plant = ActuatorPlant::new(actuator, reference, STEP_S).unwrap();
    ArmSimulation::new(arm, HubDrive::Actuated(Box::new(plant)), GEN_ALPHA).unwrap()
}

/// The hub angle, the hub torque and the cap-side pressure per step over `seconds`.
fn histories(mut sim: ArmSimulation, seconds: f64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    while sim.time_s() < seconds - 0.5 * STEP_S {
        sim.step(STEP_S).unwrap();
        let sample = sim.sample();
        let actuator = sample.actuator.unwrap();
        out.push([sim.state().x[0], actuator.hub_torque_n_m, actuator.cylinders[0].pressures_pa[0]]);
    }
    out
}

/// The largest difference between two histories, per column, relative to the column's range
/// in `a`.
fn largest_difference(a: &[[f64; 3]], b: &[[f64; 3]]) -> [f64; 3] {
    std::array::from_fn(|k| {
        let (lo, hi) = a.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| (lo.min(r[k]), hi.max(r[k])));
        let worst = a.iter().zip(b).map(|(x, y)| (x[k] - y[k]).abs()).fold(0.0, f64::max);
        worst / (hi - lo).max(f64::MIN_POSITIVE)
    })
}

/// One cylinder with twice `c`'s areas and dead volumes, on the same pins.
fn doubled(c: Cylinder) -> Cylinder {
    Cylinder {
        bore_m: c.bore_m * 2f64.sqrt(),
        rod_m: c.rod_m * 2f64.sqrt(),
        cap_dead_volume_m3: 2.0 * c.cap_dead_volume_m3,
        rod_dead_volume_m3: 2.0 * c.rod_dead_volume_m3,
        ..c
    }
}

#[test]
fn two_identical_cylinders_equal_one_with_twice_the_areas_dead_volumes_and_flows() {
    // Side by side on the same pins of a flexible arm (modal(3), the pins' residual flexibility
    // shared): on one valve, their joined chambers are one cylinder of twice the areas and dead
    // volumes on that valve; each on a valve of its own, they are that cylinder on a valve of
    // twice the flow (and leakage).
    let one = cylinder(1.0, 0.07, 0.04);
    let single =
        |flow| histories(lift(arm(Fidelity::Modal { modes: 3 }), Cylinders::one(doubled(one)), circuit(flow)), 3.0);
    let pair = |feed| Cylinders { each: vec![one, one], feed };
    let twin = |feed| histories(lift(arm(Fidelity::Modal { modes: 3 }), pair(feed), circuit(1.0)), 3.0);
    for (feed, flow) in [(ValveFeed::Shared, 1.0), (ValveFeed::Own, 2.0)] {
        let worst = largest_difference(&single(flow), &twin(feed));
        let text = format!(
            "hub angle {:.1e}, hub torque {:.1e}, cap pressure {:.1e} of their ranges",
            worst[0], worst[1], worst[2]
        );
        validated(
            &ACTUATORS,
            &format!(
                "two identical cylinders, valve = \"{}\", lifting a modal(3) arm 0 → 0.4 rad in 1.5 s under PI control, 3 s",
                feed.name()
            ),
            &format!(
                "one cylinder of twice the areas and dead volumes{}",
                if flow > 1.0 { " on a valve of twice the flow" } else { "" }
            ),
            &text,
            "< 1e-9 of each range",
        );
        assert!(worst.iter().all(|w| *w < 1e-9), "valve {}: {text}", feed.name());
    }
}

#[test]
fn two_cylinders_on_different_pins_hold_the_arm_where_the_moments_balance() {
    // A rigid 4 m, 200 kg arm on two unlike cylinders, the second's pins 1.5 times as far out;
    // lifted to 0.4 rad and held under PI control. At rest the rods' moments about the pivot
    // carry gravity's, m g L/2 cos θ, whatever share each takes; on a valve each, the leaking
    // valves reach the same null, so the two chamber pairs settle at the same pressures.
    let cylinders = |feed| Cylinders { each: vec![cylinder(1.0, 0.07, 0.04), cylinder(1.5, 0.05, 0.03)], feed };
    for feed in [ValveFeed::Shared, ValveFeed::Own] {
        let mut sim = lift(arm(Fidelity::Rigid), cylinders(feed), circuit(1.0));
        // The leaking valves bring two cylinders that share the load unequally to one pressure
        // pair with a time constant of about 1.4 s here: 14 s is ten of them.
        while sim.time_s() < 14.0 {
            sim.step(STEP_S).unwrap();
        }
        let theta = sim.state().x[0];
        let readings = sim.sample().actuator.unwrap().cylinders;
        let moment: f64 =
            cylinders(feed).each.iter().zip(&readings).map(|(c, r)| r.rod_force_n * c.length_and_arm(theta).1).sum();
        let gravity = 200.0 * 9.81 * 2.0 * theta.cos();
        let error = (moment - gravity).abs() / gravity;
        let spread = (readings[0].pressures_pa[0] - readings[1].pressures_pa[0]).abs() / readings[0].pressures_pa[0];
        validated(
            &ACTUATORS,
            &format!(
                "rigid arm held at 0.4 rad by two cylinders on different pins, valve = \"{}\": rods' moment about the pivot",
                feed.name()
            ),
            &format!("gravity's, m g L/2 cos θ = {gravity:.1} N·m"),
            &format!("{moment:.1} N·m ({error:.1e}); cap pressures {spread:.1e} apart"),
            "< 1e-4; pressures within 1e-4",
        );
        assert!(error < 1e-4, "valve {}: moment {moment} against {gravity} N·m", feed.name());
        assert!((theta - 0.4).abs() < 1e-4, "valve {}: held at {theta} rad, not the reference", feed.name());
        assert!(
            spread < 1e-4,
            "valve {}: cap pressures {:?}",
            feed.name(),
            readings.iter().map(|r| r.pressures_pa).collect::<Vec<_>>()
        );
    }
}
