//! Stress along the arm, pin loads and the sign-off checks against independent truths: the
//! static arm held at an angle against its free-body balance by hand (ideal drive and
//! cylinder), the root moment against the drive torque from Lagrange's equations at every step of
//! a lift, the pivot's reaction through an impact against the machine's momentum balance, the
//! exact nonlinear summation of a strain gauge, and `modal(3)` against `fe`; and the checks of
//! the URDF's and the scenario's sign-off keys.

use std::path::{Path, PathBuf};

use pipearm::arm::{ArmModel, Fidelity};
use pipearm::beam::BeamModel;
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;
use pipearm::model::Model;
use pipearm::run::{RunSummary, Series, run};
use pipearm::scenario::Scenario;
use pipearm::scene::Scene;
use pipearm::sensor::SensorSpec;
use pipearm::stress::{Fibre, StressProbe};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn load(name: &str) -> Model {
    Scenario::load(&root().join("scenarios").join(name)).unwrap().model
}

/// The station index of the first section at `x_m` (its inboard side at a node).
fn station(series: &Series, x_m: f64) -> usize {
    series.stress.stations.iter().position(|s| (s.station_m - x_m).abs() < 1e-9).expect("a station there")
}

/// (axial force N, bending moment N·m) at station `i`, step `k`.
fn forces(series: &Series, i: usize, k: usize) -> [f64; 2] {
    series.stress.section_forces(i, k)
}

/// The default arm's box section by hand: 250 × 500 × 12.5 mm (A, I, c).
fn box_section() -> (f64, f64, f64) {
    let (b, h, t) = (0.25, 0.5, 0.0125);
    let (bi, hi) = (b - 2.0 * t, h - 2.0 * t);
    (b * h - bi * hi, (b * h.powi(3) - bi * hi.powi(3)) / 12.0, h / 2.0)
}

/// Weight (N) and first moment of weight about the pivot (N·m) of the machine by hand: the
/// steel box (ρ A L), each carried body at its station, and the string at its centre.
fn weight_by_hand(model: &Model) -> (f64, f64) {
    let g = model.physics.gravity_m_s2;
    let (area, ..) = box_section();
    let length = model.robot.arm.length_m();
    let mu = 7850.0 * area;
    let mut w = mu * length * g;
    let mut moment = mu * length * length / 2.0 * g;
    for body in &model.robot.carried {
        w += body.mass_kg * g;
        moment += body.mass_kg * g * body.station_m;
    }
    let held = model.payload.string().unwrap();
    w += held.pipe.mass_kg() * g;
    moment += held.pipe.mass_kg() * g * held.centre_m();
    (w, moment)
}

/// The default machine held still at 30° under an ideal drive, the string `string`.
fn held_at(angle_deg: f64, string: Option<Fidelity>) -> (Model, RunSummary, Series) {
    let mut model = load("default.toml");
    model.drive.motion = MotionProfile::hold(angle_deg.to_radians());
    model.dampeners.clear();
    model.time.settle_s = 0.3;
    model.payload.string_mut().unwrap().model = string;
    let (summary, series) = run(&model, Some(Fidelity::Modal { modes: 3 })).unwrap();
    (model, summary, series)
}

#[test]
fn the_static_arm_held_at_an_angle_balances_as_its_free_body_by_hand() {
    let angle_deg: f64 = 30.0;
    let (s, c) = angle_deg.to_radians().sin_cos();
    for string in [Some(Fidelity::Rigid), Some(Fidelity::Modal { modes: 4 })] {
        let (model, summary, series) = held_at(angle_deg, string);
        let (weight, moment) = weight_by_hand(&model);
        // The pivot holds the weight: (0, W) in the world, (W sin θ, W cos θ) along and across
        // the arm. A static run stays at its start.
        let pivot = &summary.sign_off.as_ref().unwrap().pins.pivot;
        // (The histories are kept to seven digits.)
        assert!(pivot.world_n[0].abs() < 1e-6 * weight, "{string:?}: {:?}", pivot.world_n);
        assert!((pivot.world_n[1] / weight - 1.0).abs() < 1e-6, "{string:?}: {} vs {weight}", pivot.world_n[1]);
        assert!((pivot.arm_n[0] / (weight * s) - 1.0).abs() < 1e-6);
        assert!((pivot.arm_n[1] / (weight * c) - 1.0).abs() < 1e-6);
        // The root section: N = −W sin θ, M = g cos θ Σ m x (the sag's lever on the load along
        // the arm, deflection over length, is below 3e-3), σ = N/A ± M c / I.
        let [n, m] = forces(&series, station(&series, 0.0), series.t_s.len() - 1);
        assert!((n / (-weight * s) - 1.0).abs() < 1e-6, "{string:?}: N {n} vs {}", -weight * s);
        assert!((m / (moment * c) - 1.0).abs() < 3e-3, "{string:?}: M {m} vs {}", moment * c);
        let (area, inertia, half_depth) = box_section();
        let stress = &summary.sign_off.as_ref().unwrap().stress;
        let upper = -weight * s / area + moment * c * half_depth / inertia;
        let lower = -weight * s / area - moment * c * half_depth / inertia;
        assert!((stress.peak_stress_pa / upper.abs().max(lower.abs()) - 1.0).abs() < 3e-3);
        assert_eq!(stress.peak_station_m, 0.0);
        assert_eq!(stress.peak_fibre, if upper.abs() > lower.abs() { Fibre::Upper } else { Fibre::Lower });
        // At the arm's tip only the gripper's hand hangs on: no moment for a string lumped at its
        // centre; a flexible string's overhang beyond the gripper, w a² / 2 with w its weight
        // per length across the arm, give or take the span's end moment (w L² / 12 between two
        // hands held still; the arm's bending turns them a little).
        let tip = series.stress.stations.len() - 1;
        let [_, m_tip] = forces(&series, tip, 0);
        let held = model.payload.string().unwrap();
        let w = held.pipe.pipe.mass_per_length_kg_m * model.physics.gravity_m_s2 * c;
        let overhang = held.start_m() + held.pipe.length_m - model.robot.arm.length_m();
        let span = held.grips[1].station_m - held.grips[0].station_m;
        let expected = if string == Some(Fidelity::Rigid) { 0.0 } else { w * overhang * overhang / 2.0 };
        assert!((m_tip - expected).abs() < 1e-6 * moment + w * span * span / 12.0, "{string:?}: {m_tip} vs {expected}");
        the_hands_hold_the_strings_weight(&model, &series, angle_deg, string == Some(Fidelity::Rigid));
    }
}

/// The string's load on its hands at the end of a static hold: together its weight, whatever
/// its model (hub frame: −m g sin θ along the arm, −m g cos θ across). A rigid string's hands
/// are pins: the lever rule about its centre of mass across, the axial load as the string's
/// length lies either side of the hands' midpoint, no moment.
fn the_hands_hold_the_strings_weight(model: &Model, series: &Series, angle_deg: f64, rigid: bool) {
    let held = model.payload.string().unwrap();
    let weight = held.pipe.mass_kg() * model.physics.gravity_m_s2;
    let (s, c) = angle_deg.to_radians().sin_cos();
    let last = series.t_s.len() - 1;
    let value = |at: usize| f64::from(series.stress.values[last * series.stress.width + at]);
    let loads: Vec<[f64; 3]> =
        series.stress.hands.iter().map(|(_, at)| [value(*at), value(at + 1), value(at + 2)]).collect();
    assert_eq!(loads.len(), held.grips.len(), "a load per hand");
    let total = loads.iter().fold([0.0, 0.0], |t, l| [t[0] + l[0], t[1] + l[1]]);
    // (The arm's sag tilts the hands by ~1e-3 rad.)
    assert!((total[0] + weight * s).abs() < 3e-3 * weight, "rigid {rigid}: along {} vs {}", total[0], -weight * s);
    assert!((total[1] + weight * c).abs() < 3e-3 * weight, "rigid {rigid}: across {} vs {}", total[1], -weight * c);
    if rigid {
        let (x1, x2) = (held.grips[0].station_m, held.grips[1].station_m);
        let outer_across = -weight * c * (held.mass_centre_m() - x1) / (x2 - x1);
        let end = held.start_m() + held.pipe.length_m;
        let outer_along = -weight * s * (end - 0.5 * (x1 + x2)) / held.pipe.length_m;
        let expected = [[-weight * s - outer_along, -weight * c - outer_across, 0.0], [outer_along, outer_across, 0.0]];
        for (load, expected) in loads.iter().zip(expected) {
            for (l, e) in load.iter().zip(expected) {
                assert!((l - e).abs() < 3e-3 * weight, "rigid hands {loads:?} vs {expected:?}");
            }
        }
    }
}

/// The hydraulic scene `name` held still at `angle` by its cylinders, its pad removed, modal(3).
fn held_by_its_cylinders(name: &str, angle: f64) -> (Model, RunSummary) {
    let mut model = load(name);
    model.drive.motion = MotionProfile::hold(angle);
    model.dampeners.clear();
    model.time.settle_s = 0.3;
    let (summary, _) = run(&model, Some(Fidelity::Modal { modes: 3 })).unwrap();
    (model, summary)
}

/// A rod's line at hub angle `angle` from its base pin `base` (world, from the pivot) to its arm
/// pin `arm` (hub frame: along the arm, across it): its unit vector (world) and its moment arm
/// about the pivot, m.
fn rod_line(angle: f64, base: [f64; 2], arm: [f64; 2]) -> ([f64; 2], f64) {
    let (s, c) = angle.sin_cos();
    let pin = [arm[0] * c - arm[1] * s, arm[0] * s + arm[1] * c];
    let d = [pin[0] - base[0], pin[1] - base[1]];
    let unit = [d[0] / d[0].hypot(d[1]), d[1] / d[0].hypot(d[1])];
    (unit, pin[0] * unit[1] - pin[1] * unit[0])
}

#[test]
fn the_cylinder_and_pivot_hold_the_static_arm_as_its_moment_balance_by_hand() {
    let angle: f64 = 45f64.to_radians();
    let (model, summary) = held_by_its_cylinders("hydraulic.toml", angle);
    let (weight, moment) = weight_by_hand(&model);
    // The rod's line from the base pin to the arm pin (URDF: base (0.40, −0.50), arm pin 2.00 m
    // out and 0.70 m below the arm's axis), its moment arm about the pivot, and the rod force
    // that balances the weight's moment g cos θ Σ m x.
    let c = angle.cos();
    let (unit, lever) = rod_line(angle, [0.40, -0.50], [2.00, -0.70]);
    let rod = moment * c / lever;
    let pins = &summary.sign_off.as_ref().unwrap().pins;
    let cylinder = pins.cylinder.as_ref().unwrap();
    // The arm sags and the pin moves with it (deflection over the pin's lever, ~1e-3).
    assert!((cylinder.peak_force_n / rod - 1.0).abs() < 3e-3, "rod {} vs {rod}", cylinder.peak_force_n);
    for (world, u) in cylinder.world_n.iter().zip(unit) {
        assert!((world - rod * u).abs() < 3e-3 * rod, "{:?}", cylinder.world_n);
    }
    // The cylinder, a two-force member, pushes its base pin's bracket back along the same line.
    let base = pins.cylinder_base.as_ref().unwrap();
    for (world, u) in base.world_n.iter().zip(unit) {
        assert!((world + rod * u).abs() < 3e-3 * rod, "{:?}", base.world_n);
    }
    // The pivot takes the rest: weight minus the rod's push.
    let pivot = [-rod * unit[0], weight - rod * unit[1]];
    let pivot_magnitude = pivot[0].hypot(pivot[1]);
    assert!((pins.pivot.peak_force_n / pivot_magnitude - 1.0).abs() < 3e-3, "{:?} vs {pivot:?}", pins.pivot);
    for (world, expected) in pins.pivot.world_n.iter().zip(pivot) {
        assert!((world - expected).abs() < 3e-3 * rod, "{:?} vs {pivot:?}", pins.pivot.world_n);
    }
}

#[test]
fn two_cylinders_and_the_pivot_hold_the_static_arm_as_its_moment_balance_by_hand() {
    // hydraulic_twin's two 130/70 mm cylinders on one valve: the same pressures, the same areas,
    // so the same rod force F in each, and F (l₁ + l₂) = g cos θ Σ m x; the pivot takes the
    // weight less both pushes.
    let angle: f64 = 45f64.to_radians();
    let (model, summary) = held_by_its_cylinders("hydraulic_twin.toml", angle);
    let (weight, moment) = weight_by_hand(&model);
    let c = angle.cos();
    // URDF: base pins (0.40, −0.50) and (0.48, −0.60); arm pins 2.00 m out, 0.70 m below the
    // arm's axis and 2.40 m out, 0.84 m below.
    let lines = [rod_line(angle, [0.40, -0.50], [2.00, -0.70]), rod_line(angle, [0.48, -0.60], [2.40, -0.84])];
    let rod = moment * c / (lines[0].1 + lines[1].1);
    let pins = &summary.sign_off.as_ref().unwrap().pins;
    assert_eq!(pins.cylinders.len(), 2, "each cylinder's pin: {pins:?}");
    for (pin, (unit, _)) in pins.cylinders.iter().zip(lines) {
        assert!((pin.peak_force_n / rod - 1.0).abs() < 3e-3, "rod {} vs {rod}", pin.peak_force_n);
        for (world, u) in pin.world_n.iter().zip(unit) {
            assert!((world - rod * u).abs() < 3e-3 * rod, "{:?}", pin.world_n);
        }
    }
    let pushes = [0, 1].map(|a| rod * (lines[0].0[a] + lines[1].0[a]));
    let pivot = [-pushes[0], weight - pushes[1]];
    assert!((pins.pivot.peak_force_n / pivot[0].hypot(pivot[1]) - 1.0).abs() < 3e-3, "{:?} vs {pivot:?}", pins.pivot);
    for (world, expected) in pins.pivot.world_n.iter().zip(pivot) {
        assert!((world - expected).abs() < 3e-3 * rod, "{:?} vs {pivot:?}", pins.pivot.world_n);
    }
}

#[test]
fn the_root_moment_is_the_drive_torque_less_the_hubs_inertia_at_every_step() {
    // Lagrange's θ equation gives the drive torque; the summation is Newton–Euler on the parts
    // outboard of the root: they differ by the hub's own inertia, J_hub θ̈, and by second-order
    // terms. The pad strikes the arm in this run and its moment is in both.
    let model = load("default.toml");
    let (summary, series) = run(&model, None).unwrap();
    let j_hub = model.robot.arm.hub_inertia_kg_m2;
    let root = station(&series, 0.0);
    let peak = summary.peak_drive_torque_n_m;
    let mut worst: f64 = 0.0;
    for k in 0..series.t_s.len() {
        let [_, m] = forces(&series, root, k);
        let expected = series.drive_torque_n_m[k] - j_hub * series.hub_accel_rad_s2[k];
        worst = worst.max((m - expected).abs());
    }
    println!("root moment against the drive torque: worst {worst:.1} N·m, {:.2e} of the peak", worst / peak);
    assert!(worst < 1e-4 * peak, "worst {worst} N·m against a peak of {peak}");
}

#[test]
fn the_summation_is_the_strain_gauges_exact_moment_to_second_order() {
    // A strain gauge sums the outboard loads with the full nonlinear kinematics at every step;
    // the recovery's rows drop products of two elastic quantities.
    let mut model = load("default.toml");
    let gauge = SensorSpec { name: "g".into(), kind: "strain-gauge".into(), station_m: Some(3.0) };
    model.sensors = vec![gauge.resolve(&model.robot).unwrap()];
    // A curve without a cut-off, so that the lift's every cycle counts.
    let curve = pipearm::fatigue::SnCurve::dnv("dnv-d").unwrap();
    model.robot.arm.segments.iter_mut().for_each(|s| s.checks.sn_curve = Some(curve));
    let (summary, series) = run(&model, None).unwrap();
    let i = station(&series, 3.0);
    let readings = &series.sensors[0].values;
    let peak = readings.iter().map(|v| v[0].abs()).fold(0.0, f64::max);
    let worst = (0..series.t_s.len()).map(|k| (forces(&series, i, k)[1] - readings[k][0]).abs()).fold(0.0, f64::max);
    println!("summation against the gauge: worst {worst:.2} N·m, {:.2e} of the peak", worst / peak);
    assert!(worst < 5e-4 * peak, "worst {worst} N·m against a peak of {peak}");
    the_gauges_fatigue_is_its_own_historys(&summary, &series, i, &curve);
}

/// A strain gauge's fatigue is counted on its own stress channel: its largest rainflow range is
/// the channel's max − min (the largest cycle a rainflow count closes always spans the history),
/// and its damage per lift is the section's there (the recovery's bending stress at the upper
/// fibre, M c / I as the gauge reads it: another sum of the same loads) to within their
/// difference in stress, three to five times over in damage.
fn the_gauges_fatigue_is_its_own_historys(
    summary: &RunSummary,
    series: &Series,
    i: usize,
    curve: &pipearm::fatigue::SnCurve,
) {
    let fatigue = &summary.sign_off.as_ref().unwrap().fatigue;
    let gauge =
        fatigue.places.iter().find(|p| p.place == "gauge g").expect("the gauge's place: its segment has a curve");
    let sigma: Vec<f64> = series.sensors[0].values.iter().map(|v| v[1]).collect();
    let span = sigma.iter().copied().fold(f64::MIN, f64::max) - sigma.iter().copied().fold(f64::MAX, f64::min);
    assert!((gauge.damage.max_range_pa - span).abs() <= 1e-9 * span, "{} vs {span}", gauge.damage.max_range_pa);
    let per_moment = series.stress.stations[i].fibres.per_moment_per_m3;
    let section: Vec<f64> = (0..series.t_s.len()).map(|k| forces(series, i, k)[1] * per_moment).collect();
    let expected =
        pipearm::fatigue::LiftDamage::of(&section, curve, summary.sign_off.as_ref().unwrap().stress.stress_factor);
    let damage = gauge.damage.damage_per_lift;
    println!("gauge damage {damage:.4e} per lift, the section's {:.4e}", expected.damage_per_lift);
    assert!((damage / expected.damage_per_lift - 1.0).abs() < 5e-3, "{damage} vs {}", expected.damage_per_lift);
}

/// The machine's linear momentum, world frame, from the state: the arm's Gauss points, its
/// carried bodies and a flexible string's Gauss points.
fn momentum(scene: &Scene) -> [f64; 2] {
    let arm = &scene.arm.arm;
    let (hub, q, qd) = scene.arm.kinematics();
    let (s, c) = hub.angle_rad.sin_cos();
    let w = hub.rate_rad_s;
    let velocity = |x: f64, rows: &pipearm::arm::StationRows| {
        let [u, v, _] = rows.displacement(&q);
        let [ud, vd, _] = rows.displacement(&qd);
        let body = [ud - w * v, vd + w * (x + u)];
        [c * body[0] - s * body[1], s * body[0] + c * body[1]]
    };
    let mut p = [0.0; 2];
    let mut add = |mass: f64, v: [f64; 2]| {
        p[0] += mass * v[0];
        p[1] += mass * v[1];
    };
    for e in &arm.beam.elements {
        for (xi, weight) in pipearm::beam::GAUSS_4 {
            let x = e.x0_m + xi * e.length_m;
            add(weight * e.length_m * e.mass_per_length_kg_m, velocity(x, &arm.station_rows(x)));
        }
    }
    for m in &arm.beam.spec.masses {
        add(m.mass_kg, velocity(m.position_m, &arm.station_rows(m.position_m)));
    }
    if let Some(member) = &arm.beam.member {
        for e in &member.elements {
            for (xi, weight) in pipearm::beam::GAUSS_4 {
                let x = e.x0_m + xi * e.length_m;
                add(weight * e.length_m * e.mass_per_length_kg_m, velocity(x, &arm.string_station_rows(x).unwrap()));
            }
        }
    }
    p
}

#[test]
fn the_pivot_reaction_through_an_impact_keeps_the_momentum_balance() {
    // ∫ (R + F_pad + W) dt = Δp over the first impact: the pivot's reaction from the recovered
    // accelerations against the change of the momentum of every mass, from the velocities. The
    // window holds the drive's stop too (its deceleration ends at 15 s); the trapezoidal sum across
    // that jump and the integrator's own velocity rule leave an error that falls with the step
    // (0.19 N·s at 1 ms, 0.048 N·s at 0.25 ms).
    let mut model = load("default.toml");
    model.integrator = IntegratorKind::default();
    let h = model.time.step_s / 12.0;
    let beam = BeamModel::new(model.beam_spec_with_string(Some(Fidelity::Modal { modes: 4 })).unwrap()).unwrap();
    let arm = ArmModel::new(beam, Fidelity::Modal { modes: 3 }, model.arm_options()).unwrap();
    let mut scene = Scene::with_arm(&model, arm.clone()).unwrap();
    while scene.arm.time_s() < 14.9 {
        scene.step(model.time.step_s).unwrap();
    }
    let mut probe = StressProbe::new(&model, &arm, &scene);
    let g = model.physics.gravity_m_s2;
    let weight = (arm.beam.total_mass_kg) * g;
    let mut readings = probe.series(0, &[]);
    let (mut pad, mut momenta, mut times) = (Vec::new(), Vec::new(), Vec::new());
    let mut peak_pad: f64 = 0.0;
    while scene.arm.time_s() < 15.1 {
        let sample = scene.arm.sample();
        probe.read(&scene, &sample, g, &mut readings);
        let force = scene
            .pairs()
            .map(|p| p.normal_world.map(|n| p.force_n * n))
            .fold([0.0; 2], |a, f| [a[0] + f[0], a[1] + f[1]]);
        peak_pad = peak_pad.max(force[0].hypot(force[1]));
        pad.push(force);
        momenta.push(momentum(&scene));
        times.push(scene.arm.time_s());
        scene.step(h).unwrap();
    }
    probe.finish(&mut readings);
    let values: Vec<f64> = readings.values.iter().map(|v| f64::from(*v)).collect();
    assert!(peak_pad > 500.0, "the window holds the impact: peak {peak_pad} N");
    let width = probe.width();
    let pivot_at = probe.recovery.pivot_index();
    let mut impulse = [0.0; 2];
    let net = |k: usize| {
        let (s, c) = scene_angle(&times, k, &model);
        let r = [values[k * width + pivot_at], values[k * width + pivot_at + 1]];
        let world = [c * r[0] - s * r[1], s * r[0] + c * r[1]];
        [world[0] + pad[k][0], world[1] + pad[k][1] - weight]
    };
    for k in 1..times.len() {
        let (a, b) = (net(k - 1), net(k));
        let dt = times[k] - times[k - 1];
        impulse[0] += 0.5 * dt * (a[0] + b[0]);
        impulse[1] += 0.5 * dt * (a[1] + b[1]);
    }
    let last = times.len() - 1;
    let change = [momenta[last][0] - momenta[0][0], momenta[last][1] - momenta[0][1]];
    let pad_impulse: f64 = (1..times.len())
        .map(|k| 0.5 * (times[k] - times[k - 1]) * (pad[k][0].hypot(pad[k][1]) + pad[k - 1][0].hypot(pad[k - 1][1])))
        .sum();
    println!("impulse {impulse:?} N·s against the momentum change {change:?} N·s; pad impulse {pad_impulse:.3} N·s");
    for k in 0..2 {
        assert!(
            (impulse[k] - change[k]).abs() < 0.005 * pad_impulse,
            "{impulse:?} vs {change:?} (pad impulse {pad_impulse})"
        );
    }
}

/// sin, cos of the hub angle at step `k` of the window (the prescribed drive's).
fn scene_angle(times: &[f64], k: usize, model: &Model) -> (f64, f64) {
    model.drive.motion.sample(times[k]).angle_rad.sin_cos()
}

/// Curvature row over q at the station `x_m`, on the side `inboard` of it: second-order one-sided
/// differences of the slope rows inside the one element (Hermite slopes are quadratic there).
fn curvature_row(arm: &ArmModel, x_m: f64, inboard: bool, element_m: f64) -> nalgebra::DVector<f64> {
    let h = 0.1 * element_m;
    let sign = if inboard { -1.0 } else { 1.0 };
    let slope = |x: f64| arm.station_rows(x).0[2].clone();
    (-3.0 * slope(x_m) + 4.0 * slope(x_m + sign * h) - slope(x_m + 2.0 * sign * h)) * (sign / (2.0 * h))
}

#[test]
fn modal_summation_follows_fe_where_loads_concentrate_and_modal_curvature_does_not() {
    // The default lift with its pad strike, the string lumped at its centre (a 121 kg point load on
    // the arm besides the hands), under generalized-α (stable for fe at 3 ms): the bending moment at
    // every section from modal(3) against fe, by force summation and by the modes' curvature
    // (M = −EI v″, the modal stress shapes).
    let mut model = load("default.toml");
    model.integrator = IntegratorKind::default();
    model.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    let (_, fe) = run(&model, Some(Fidelity::Fe)).unwrap();
    let modal_fidelity = Fidelity::Modal { modes: 3 };
    let (_, modal) = run(&model, Some(modal_fidelity)).unwrap();
    let arm = model.arm_model(modal_fidelity).unwrap();
    let (_, inertia, _) = box_section();
    let ei = 2.06e11 * inertia;
    let element_m = model.robot.arm.length_m() / model.robot.arm.elements as f64;
    let stations = &fe.stress.stations;
    assert_eq!(stations.len(), modal.stress.stations.len());
    let steps = fe.t_s.len();
    let peak = (0..stations.len())
        .flat_map(|i| (0..steps).map(move |k| (i, k)))
        .map(|(i, k)| forces(&fe, i, k)[1].abs())
        .fold(0.0, f64::max);
    let (mut worst_sum, mut worst_shape) = ((0.0, 0.0), (0.0, 0.0));
    for (i, station) in stations.iter().enumerate() {
        // The tip's outboard side carries nothing but its own bodies' inertia: not a section.
        if i == stations.len() - 1 {
            continue;
        }
        let inboard = i > 0 && (i + 1 == stations.len() || stations[i + 1].station_m != station.station_m);
        let kappa = curvature_row(&arm, station.station_m, inboard, element_m);
        let n = modal.modal_dofs;
        for k in 0..steps {
            let m_fe = forces(&fe, i, k)[1];
            let sum = (forces(&modal, i, k)[1] - m_fe).abs();
            let q = nalgebra::DVector::from_column_slice(&modal.modal_q[k * n..(k + 1) * n]);
            let shape = (-ei * kappa.dot(&q) - m_fe).abs();
            if sum > worst_sum.0 {
                worst_sum = (sum, station.station_m);
            }
            if shape > worst_shape.0 {
                worst_shape = (shape, station.station_m);
            }
        }
    }
    println!(
        "modal(3) against fe, worst over the sections and the run, of the peak moment {peak:.0} N·m: \
         summation {:.2e} at {:.3} m, modal curvature {:.2e} at {:.3} m",
        worst_sum.0 / peak,
        worst_sum.1,
        worst_shape.0 / peak,
        worst_shape.1
    );
    assert!(worst_sum.0 < 5e-3 * peak, "summation {worst_sum:?}");
    assert!(worst_shape.0 > 4.0 * worst_sum.0, "curvature {worst_shape:?} against summation {worst_sum:?}");
}
