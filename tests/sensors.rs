//! Sensors against independent truths: the accelerometer of a rigid arm in uniform rotation, the
//! root moment and stress of a static cantilever in closed form, the moment balance of the whole
//! arm about its pivot during a lift, the encoder against the prescribed profile; and the
//! scenario's checks of `[[sensors]]`.

mod common;

use std::path::Path;

use pipearm::arm::Fidelity;
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;
use pipearm::model::Model;
use pipearm::run::{Series, run};
use pipearm::scenario::Scenario;
use pipearm::sensor::{Sensor, SensorSpec};

fn default_model() -> Model {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model
}

fn sensor(model: &Model, name: &str, kind: &str, station_m: Option<f64>) -> Sensor {
    SensorSpec { name: name.into(), kind: kind.into(), station_m }.resolve(&model.robot).unwrap()
}

fn channel<'a>(series: &'a Series, name: &str) -> &'a [[f64; 2]] {
    &series.sensors.iter().find(|s| s.sensor.name == name).unwrap().values
}

/// A rigid arm turning at a constant rate ω: the tip accelerometer reads the centripetal
/// acceleration ω²L toward the hub and gravity turned into its frame, (−ω²L + g sin θ, g cos θ).
#[test]
fn accelerometer_on_a_rigid_arm_in_uniform_rotation() {
    let mut model = default_model();
    let quarter = std::f64::consts::FRAC_PI_2;
    let duration_s = 2.0;
    model.drive.motion = MotionProfile::uniform(0.0, quarter, duration_s).unwrap();
    model.dampeners.clear();
    model.time.settle_s = 0.0;
    let length = model.robot.arm.length_m();
    model.sensors = vec![sensor(&model, "tip", "accelerometer", Some(length))];
    let (_, series) = run(&model, Some(Fidelity::Rigid)).unwrap();
    let (w, g) = (quarter / duration_s, model.physics.gravity_m_s2);
    let mut checked = 0;
    let mut worst = 0.0_f64;
    for (t, [axial, transverse]) in series.t_s.iter().zip(channel(&series, "tip")) {
        if *t < 1e-3 || *t > duration_s - 1e-3 {
            continue; // the rate jumps at start and stop
        }
        let theta = w * t;
        let expected = [-w * w * length + g * theta.sin(), g * theta.cos()];
        worst = worst.max((axial - expected[0]).abs().max((transverse - expected[1]).abs()) / g);
        assert!((axial - expected[0]).abs() < 1e-9 * g, "t {t}: axial {axial} vs {}", expected[0]);
        assert!((transverse - expected[1]).abs() < 1e-9 * g, "t {t}: transverse {transverse} vs {}", expected[1]);
        checked += 1;
    }
    common::validated_row(
        &common::SENSORS,
        "tip accelerometer, rigid default arm turning uniformly 0 → 90° in 2 s, at every step",
        "(−ω²L + g sin θ, g cos θ): centripetal and gravity in the arm's frame",
        &format!("largest difference {} g over {checked} steps", common::sig(worst, 2)),
        &format!("{} g", common::sig(worst, 2)),
        "< 1e-9 g",
    );
    assert!(checked > 500, "{checked} steps checked");
}

/// The default arm held horizontal at rest under gravity: the bending moment at a station s is
/// g (μ (L − s)² / 2 + Σ m_i (x_i − s)) over the masses past s (w L²/2 + P L at the root), the
/// upper face's stress M c / I, from the section's dimensions; the accelerometer reads +g across.
/// A truncated modal model gets the moment exactly: it is summed from the loads, not from the
/// curvature of two modes.
#[test]
fn static_cantilever_moment_and_stress() {
    let mut model = default_model();
    model.drive.motion = MotionProfile::hold(0.0);
    model.dampeners.clear();
    model.time.settle_s = 1.0;
    // A strain gauge takes moments of point masses: the string lumped at its centre.
    model.payload.string_mut().unwrap().model = Some(Fidelity::Rigid);
    // Implicit: the fe arm's axial modes are far beyond RK4's limit at the scenario's step.
    model.integrator = IntegratorKind::default();
    let stations = [0.0, 4.5, 8.5];
    model.sensors = stations
        .iter()
        .enumerate()
        .map(|(i, &x)| sensor(&model, &format!("gauge{i}"), "strain-gauge", Some(x)))
        .collect();
    model.sensors.push(sensor(&model, "hand", "accelerometer", Some(6.0)));
    // The URDF's section: hollow rectangle 250 (width) x 500 (depth) x 12.5 mm, steel 7850 kg/m³.
    let (b, h, t, rho): (f64, f64, f64, f64) = (0.25, 0.5, 0.0125, 7850.0);
    let (bi, hi) = (b - 2.0 * t, h - 2.0 * t);
    let mu = rho * (b * h - bi * hi);
    let second_moment = (b * h.powi(3) - bi * hi.powi(3)) / 12.0;
    let length = model.robot.arm.length_m();
    // Carried bodies and the string, each at its own station (robot and catalogue data).
    let mut masses: Vec<(f64, f64)> = model.robot.carried.iter().map(|c| (c.station_m, c.mass_kg)).collect();
    let held = model.payload.string().unwrap();
    masses.push((held.centre_m(), model.payload.mass_kg()));
    let g = model.physics.gravity_m_s2;
    for fidelity in [Fidelity::Modal { modes: 2 }, Fidelity::Fe] {
        let (_, series) = run(&model, Some(fidelity)).unwrap();
        let expected: Vec<f64> = stations
            .iter()
            .map(|&s| {
                let outboard: f64 = masses.iter().filter(|m| m.0 > s).map(|(x, m)| m * (x - s)).sum();
                g * (0.5 * mu * (length - s).powi(2) + outboard)
            })
            .collect();
        let readings: Vec<[f64; 2]> =
            (0..stations.len()).map(|i| *channel(&series, &format!("gauge{i}")).last().unwrap()).collect();
        let case = format!("default arm held horizontal, {fidelity}: strain gauges at 0, 4.5, 8.5 m");
        common::validated_rel_all(
            &common::SENSORS,
            &format!("{case}, moment"),
            &expected,
            "g (μ(L − s)²/2 + Σ m_i (x_i − s)), the URDF's section and masses",
            &readings.iter().map(|r| r[0]).collect::<Vec<_>>(),
            "N·m",
            1e-6,
        );
        common::validated_rel_all(
            &common::SENSORS,
            &format!("{case}, stress"),
            &expected.iter().map(|m| m * (h / 2.0) / second_moment).collect::<Vec<_>>(),
            "M c / I",
            &readings.iter().map(|r| r[1]).collect::<Vec<_>>(),
            "Pa",
            1e-6,
        );
        for (i, &s) in stations.iter().enumerate() {
            let outboard: f64 = masses.iter().filter(|m| m.0 > s).map(|(x, m)| m * (x - s)).sum();
            let expected = g * (0.5 * mu * (length - s).powi(2) + outboard);
            let [moment, stress] = *channel(&series, &format!("gauge{i}")).last().unwrap();
            assert!((moment / expected - 1.0).abs() < 1e-6, "{fidelity} at {s} m: M {moment} vs {expected}");
            let expected_stress = expected * (h / 2.0) / second_moment;
            assert!((stress / expected_stress - 1.0).abs() < 1e-6, "{fidelity}: σ {stress} vs {expected_stress}");
        }
        // The accelerometer reads g, tilted with the section by the sag's slope at the hand, 6.0 m:
        // φ = −(w/6EI)(3L²x − 3Lx² + x³) − Σ P min(x, a)(2a − min(x, a))/2EI.
        let ei = 2.06e11 * second_moment;
        let x: f64 = 6.0;
        let point_loads: f64 = masses.iter().map(|&(a, m)| m * g * x.min(a) * (2.0 * a - x.min(a)) / (2.0 * ei)).sum();
        let slope =
            -(mu * g / (6.0 * ei) * (3.0 * length * length * x - 3.0 * length * x * x + x.powi(3)) + point_loads);
        let [axial, across] = *channel(&series, "hand").last().unwrap();
        assert!((axial.hypot(across) / g - 1.0).abs() < 1e-9, "{fidelity}: hand reads ({axial}, {across})");
        let tolerance = if fidelity == Fidelity::Fe { 1e-6 } else { 1e-2 };
        common::validated_rel(
            &common::SENSORS,
            &format!("the same, {fidelity}: accelerometer at the lower hand (6.0 m), axial reading"),
            g * slope.sin(),
            "g sin φ, φ the closed-form cantilever slope there",
            axial,
            "m/s²",
            tolerance,
        );
        assert!(
            (axial / (g * slope.sin()) - 1.0).abs() < tolerance,
            "{fidelity}: axial {axial} vs {}",
            g * slope.sin()
        );
    }
}

/// During a lift the moment at the root is the moment balance of the whole arm about the pivot:
/// the drive torque less the hub's own inertia, τ − J_hub θ̈. The torque comes from the Lagrange
/// equations' hub row, the moment from the loads summed along the arm: two routes to one number.
#[test]
fn root_moment_balances_the_drive_torque_during_a_lift() {
    let mut model = default_model();
    model.dampeners.clear();
    model.time.settle_s = 1.0;
    // Implicit: the fe arm's axial modes are far beyond RK4's limit at the scenario's step.
    model.integrator = IntegratorKind::default();
    model.sensors = vec![sensor(&model, "root", "strain-gauge", Some(0.0))];
    let hub_inertia = model.robot.arm.hub_inertia_kg_m2;
    for fidelity in [Fidelity::Rigid, Fidelity::Modal { modes: 3 }, Fidelity::Fe] {
        let (summary, series) = run(&model, Some(fidelity)).unwrap();
        let scale = summary.peak_drive_torque_n_m;
        let worst = series
            .drive_torque_n_m
            .iter()
            .zip(&series.hub_accel_rad_s2)
            .zip(channel(&series, "root"))
            .map(|((tau, acc), [moment, _])| (tau - hub_inertia * acc - moment).abs())
            .fold(0.0, f64::max);
        // Foreshortening (second order in q) is in the torque, not in the summed moment.
        eprintln!("{fidelity}: worst |τ − J θ̈ − M| = {:.2e} of the peak torque", worst / scale);
        common::validated_row(
            &common::SENSORS,
            &format!("root strain gauge, default lift without its pad, {fidelity}: at every step"),
            "τ − J_hub θ̈, the moment balance of the arm about the pivot (τ from the equations' hub row)",
            &format!("largest difference {} N·m", common::sig(worst, 2)),
            &format!("{} of the peak torque", common::relative(worst / scale)),
            "< 1e-4 of the peak torque",
        );
        assert!(worst < 1e-4 * scale, "{fidelity}: worst |τ − J θ̈ − M| = {worst} N·m of {scale}");
    }
}

/// The same balance on the default lift with its pad: the impacts' forces enter the torque as
/// the contact's moment about the pivot and the root moment as a load outboard of the root.
#[test]
fn root_moment_balances_the_drive_torque_through_the_impacts() {
    let mut model = default_model();
    model.sensors = vec![sensor(&model, "root", "strain-gauge", Some(0.0))];
    let hub_inertia = model.robot.arm.hub_inertia_kg_m2;
    let (summary, series) = run(&model, None).unwrap();
    assert!(summary.pairs[0].impact_count > 0, "the default lift strikes its pad");
    let scale = summary.peak_drive_torque_n_m;
    let worst = series
        .drive_torque_n_m
        .iter()
        .zip(&series.hub_accel_rad_s2)
        .zip(channel(&series, "root"))
        .zip(&series.pad_force_n[0])
        .filter(|(_, force)| **force > 0.0)
        .map(|(((tau, acc), [moment, _]), _)| (tau - hub_inertia * acc - moment).abs())
        .fold(0.0, f64::max);
    eprintln!("in contact: worst |τ − J θ̈ − M| = {:.2e} of the peak torque", worst / scale);
    common::validated_row(
        &common::SENSORS,
        "root strain gauge, default lift with its pad: at every step in contact",
        "τ − J_hub θ̈, the impacts' force an outboard load",
        &format!("largest difference {} N·m", common::sig(worst, 2)),
        &format!("{} of the peak torque", common::relative(worst / scale)),
        "< 1e-4 of the peak torque",
    );
    assert!(worst < 1e-4 * scale, "worst |τ − J θ̈ − M| in contact = {worst} N·m of {scale}");
}

/// The encoder reads the prescribed hub exactly; the summary holds each channel's peak.
#[test]
fn encoder_reads_the_prescribed_profile() {
    let mut model = default_model();
    model.time.settle_s = 0.5;
    model.sensors = vec![sensor(&model, "hub_encoder", "encoder", None)];
    let (summary, series) = run(&model, None).unwrap();
    let exact = series.t_s.iter().zip(channel(&series, "hub_encoder")).all(|(t, [angle, rate])| {
        let hub = model.drive.motion.sample(*t);
        (*angle, *rate) == (hub.angle_rad, hub.rate_rad_s)
    });
    common::validated(
        &common::SENSORS,
        "hub encoder on the default lift, at every step",
        "the prescribed profile's angle and rate",
        if exact { "equal, bit for bit" } else { "different" },
        "equal",
    );
    for (t, [angle, rate]) in series.t_s.iter().zip(channel(&series, "hub_encoder")) {
        let hub = model.drive.motion.sample(*t);
        assert_eq!((*angle, *rate), (hub.angle_rad, hub.rate_rad_s), "t {t}");
    }
    let peaks = &summary.sensors[0].channels;
    assert_eq!(peaks[0].channel, "angle_rad");
    assert!((peaks[0].peak_abs - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    assert!((peaks[1].peak_abs - model.drive.motion.peak_rate_rad_s()).abs() < 1e-9);
}

/// A summary without sensors has no `sensors` key: the files written before sensors existed
/// stay as they were.
#[test]
fn summary_without_sensors_has_no_sensor_key() {
    let mut model = default_model();
    model.time.settle_s = 0.0;
    model.drive.motion = MotionProfile::hold(0.0);
    let (summary, _) = run(&model, None).unwrap();
    assert!(!serde_json::to_string(&summary).unwrap().contains("sensors"));
}

fn scenario_with(sensors: &str) -> Result<Scenario, String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let base = std::fs::read_to_string(dir.join("default.toml")).unwrap();
    let path = dir.join(".sensors_test.toml");
    let spec: pipearm::scenario::ScenarioSpec =
        toml::from_str(&format!("{base}\n{sensors}")).map_err(|e| e.to_string())?;
    Scenario::from_spec(&path, spec).map_err(|e| e.to_string())
}

#[test]
fn bad_sensors_name_the_file_and_key() {
    let cases = [
        ("[[sensors]]\nname = \"a\"\nkind = \"gyro\"\nstation_m = 1.0", "sensors[0].kind", "strain-gauge"),
        ("[[sensors]]\nname = \"a\"\nkind = \"accelerometer\"\nstation_m = 9.5", "sensors[0].station_m", "0 ..= 9"),
        ("[[sensors]]\nname = \"a\"\nkind = \"strain-gauge\"", "sensors[0].station_m", "missing"),
        ("[[sensors]]\nname = \"a\"\nkind = \"encoder\"\nstation_m = 1.0", "sensors[0].station_m", "hub"),
        (
            "[[sensors]]\nname = \"a\"\nkind = \"encoder\"\n[[sensors]]\nname = \"a\"\nkind = \"accelerometer\"\nstation_m = 1.0",
            "sensors[1].name",
            "sensors[0]",
        ),
        ("[[sensors]]\nname = \"hub\"\nkind = \"encoder\"", "sensors[0].name", "other than"),
        ("[[sensors]]\nname = \"a.b\"\nkind = \"encoder\"", "sensors[0].name", "letters"),
    ];
    for (text, key, allowed) in cases {
        let e = scenario_with(text).unwrap_err();
        assert!(e.contains(".sensors_test.toml") && e.contains(key) && e.contains(allowed), "{text}: {e}");
    }
    let e = scenario_with("[[sensors]]\nname = \"a\"\nkind = \"encoder\"\nstation = 1.0").unwrap_err();
    assert!(e.contains("station"), "{e}");
    let ok = scenario_with("[[sensors]]\nname = \"root\"\nkind = \"strain-gauge\"\nstation_m = 0.0").unwrap();
    assert_eq!(ok.model.sensors.len(), 1);
}
