//! Strings of any pipe against independent truths: a custom pipe's overhang rings at the
//! cantilever's closed-form frequency, a stand's couplings put the mass and centre of mass
//! summed by hand into the string's models, and the machine's capacity is the moment balance
//! about the pivot worked by hand from the URDF's numbers.

mod common;

use std::path::{Path, PathBuf};

use common::rel;
use pipearm::arm::Fidelity;
use pipearm::beam::BeamModel;
use pipearm::capacity::{CapacityError, heaviest_kg, jaw_range, scene_limit};
use pipearm::model::Model;
use pipearm::robot::pipes::{CustomPipeSpec, PIPE_CATALOGUE, PipeSize, Product, Range};
use pipearm::robot::{PipeString, StringSpec};
use pipearm::scenario::{PayloadSpec, Scenario, ScenarioError};
use pipearm::sweep::Vary;
use pipearm::sweep::pipes::{LIFTABLE, expand};

fn scenario_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios").join(name)
}

/// `name` with its string's spec edited by `edit`, the string centred between its hands.
fn with_string(name: &str, edit: impl FnOnce(&mut StringSpec)) -> Result<Model, ScenarioError> {
    let path = scenario_path(name);
    let mut spec = Scenario::read_spec(&path).unwrap();
    let PayloadSpec::String { string, grips, .. } = &mut spec.payload else { panic!("{name} holds a string") };
    edit(string);
    for grip in grips.iter_mut().flatten() {
        grip.at_m = None;
    }
    Scenario::from_spec(&path, spec).map(|s| s.model)
}

fn own_pipe(d: f64, wall: f64, kg_m: f64, e: f64) -> CustomPipeSpec {
    CustomPipeSpec {
        outer_diameter_m: d,
        wall_m: Some(wall),
        bore_m: None,
        mass_per_length_kg_m: Some(kg_m),
        youngs_modulus_pa: Some(e),
        yield_strength_pa: Some(550e6),
    }
}

#[test]
fn a_custom_pipe_overhang_rings_at_the_cantilever_frequency() {
    // A 200 x 10 mm tube of 60 kg/m (above its 46.9 kg/m of plain steel: a lined pipe) and
    // E = 200 GPa, 7 m long, held at its middle by the gripper alone: each 3.5 m overhang is a
    // cantilever clamped in the jaws, f = 1.875² / (2π) √(EI / (μ L⁴)) (Blevins, Table 8-1).
    let (d, t, mu, e) = (0.2, 0.01, 60.0, 2.0e11);
    let model = with_string("default.toml", |s| {
        *s = StringSpec { pipe: Some(Box::new(own_pipe(d, t, mu, e))), length_m: Some(7.0), ..StringSpec::default() };
    });
    let mut model = model.unwrap();
    let held = model.payload.string_mut().unwrap();
    let palm = held.palm().clone();
    held.in_one_hand(&palm.hand, palm.station_m);
    let beam = BeamModel::new(model.beam_spec_with_string(Some(Fidelity::Fe)).unwrap()).unwrap();
    let i = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
    let lambda: f64 = 1.875_10;
    let exact_hz = lambda * lambda / std::f64::consts::TAU * (e * i / (mu * 3.5_f64.powi(4))).sqrt();
    let got = beam.member_modes().unwrap().frequencies_hz()[0];
    assert!(rel(got, exact_hz) < 1e-3, "overhang {got} Hz vs cantilever {exact_hz} Hz");
}

#[test]
fn a_custom_pipe_lighter_than_its_steel_or_solid_is_refused_naming_the_key() {
    let refused = |pipe: CustomPipeSpec| {
        with_string("default.toml", |s| {
            *s = StringSpec { pipe: Some(Box::new(pipe)), length_m: Some(7.0), ..StringSpec::default() };
        })
        .unwrap_err()
        .to_string()
    };
    // 200 x 10 mm of steel is 46.9 kg/m: 44 kg/m is 6 % short.
    let e = refused(own_pipe(0.2, 0.01, 44.0, 2.0e11));
    assert!(e.contains("payload.pipe.mass_per_length_kg_m") && e.contains(">= 45.45"), "{e}");
    let e = refused(own_pipe(0.2, 0.1, 300.0, 2.0e11));
    assert!(e.contains("payload.pipe.wall_m") && e.contains("< 0.1"), "{e}");
    let e = refused(CustomPipeSpec { wall_m: None, bore_m: Some(0.0), ..own_pipe(0.2, 0.01, 60.0, 2e11) });
    assert!(e.contains("payload.pipe.bore_m"), "{e}");
    let e = refused(CustomPipeSpec { bore_m: Some(0.1), ..own_pipe(0.2, 0.01, 60.0, 2e11) });
    assert!(e.contains("wall_m and bore_m"), "{e}");
    // A catalogue key beside it.
    let e = with_string("default.toml", |s| s.pipe = Some(Box::new(own_pipe(0.2, 0.01, 60.0, 2e11))))
        .unwrap_err()
        .to_string();
    assert!(e.contains("payload.size"), "{e}");
}

#[test]
fn a_stand_puts_its_joints_and_tool_joints_in_the_string_s_models() {
    // Two R2 joints of 5 in 19.50 lb/ft drill pipe (8.69 m each) centred between the hands: the
    // flexible string's beam and the lumped one carry the mass and first moment about the pivot
    // summed by hand from the catalogue's plain-end weight and tool joint.
    let model = with_string("default.toml", |s| {
        *s = StringSpec {
            product: Some(Product::DrillPipe),
            range: Some(Range::R2),
            joints: Some(2),
            ..StringSpec::of_size("5")
        };
    })
    .unwrap();
    let held = model.payload.string().unwrap();
    let row = held.pipe.pipe.row.unwrap();
    let (l, body_kg_m, tj) = (8.69, row.plain_end_kg_m(), row.connection);
    let start = 7.5 - l; // centred between the hands at 6.0 and 9.0 m
    let per_m = tj.added_mass_kg / tj.length_m;
    let (pin, bx) = (tj.pin_length_m, tj.length_m - tj.pin_length_m);
    // (mass, station) of the plain pipe and of each tool joint part, by hand.
    let mut parts = vec![(body_kg_m * 2.0 * l, start + l)];
    for k in 0..2 {
        let joint_start = start + k as f64 * l;
        parts.push((per_m * pin, joint_start + 0.5 * pin));
        parts.push((per_m * bx, joint_start + l - 0.5 * bx));
    }
    let mass: f64 = parts.iter().map(|p| p.0).sum();
    let moment: f64 = parts.iter().map(|p| p.0 * p.1).sum();
    assert!(rel(held.pipe.mass_kg(), mass) < 1e-12);
    assert!(rel(held.mass_centre_m(), moment / mass) < 1e-12, "{} vs {}", held.mass_centre_m(), moment / mass);
    let arm_alone = BeamModel::new(model.robot.beam_spec(&[]).unwrap()).unwrap();
    for fidelity in [None, Some(Fidelity::Fe)] {
        let beam = BeamModel::new(model.beam_spec_with_string(fidelity).unwrap()).unwrap();
        let (m, s) =
            (beam.total_mass_kg - arm_alone.total_mass_kg, beam.first_moment_kg_m - arm_alone.first_moment_kg_m);
        assert!(rel(m, mass) < 1e-9, "{fidelity:?}: {m} kg vs {mass} kg by hand");
        assert!(rel(s, moment) < 1e-9, "{fidelity:?}: {s} kg·m vs {moment} kg·m by hand");
    }
    // auto builds the string's beam with them and runs.
    assert!(pipearm::select::string_fidelity(&model).is_ok());
}

/// The first moment of pipe_arm's arm and carried links about the pivot, by hand from
/// robots/pipe_arm.urdf: 9 m of 500 x 250 x 12.5 mm steel box, hand 180 kg at 6 m, gripper 96 kg
/// and two 12 kg jaws at 9 m.
fn pipe_arm_first_moment_kg_m() -> f64 {
    let area = 0.5 * 0.25 - 0.475 * 0.225;
    7850.0 * area * 9.0 * 9.0 / 2.0 + 180.0 * 6.0 + (96.0 + 2.0 * 12.0) * 9.0
}

#[test]
fn the_capacity_is_the_moment_balance_about_the_pivot() {
    let g = 9.80665;
    let s0 = pipe_arm_first_moment_kg_m();
    // servo.toml: the string in the gripper (9.0 m); the servo's 160 N·m through 1000:1. At the
    // horizontal, the worst angle: m = (T / g − S₀) / x.
    let servo = Scenario::load(&scenario_path("servo.toml")).unwrap().model;
    let servo_kg = (1000.0 * 160.0 / g - s0) / 9.0;
    let limit = scene_limit(&servo);
    let machine = pipearm::capacity::machine_first_moment_kg_m(&servo.robot).unwrap();
    assert!(rel(machine, s0) < 1e-12, "{machine} vs {s0}");
    assert!(rel(heaviest_kg(&limit, 0.0, machine, 9.0, g), servo_kg) < 1e-9);
    // At 60 deg the lever halves.
    assert!(rel(heaviest_kg(&limit, 60f64.to_radians(), machine, 9.0, g), (2.0 * 160e3 / g - s0) / 9.0) < 1e-9);
    // hydraulic.toml: the cylinder at 23 MPa relief on its cap side, 0.5 MPa tank on its rod
    // side, on the moment arm of its pins at 0 deg (base (0.4, -0.5), arm (2.0, -0.7) m): the
    // arm pin moves along (0.7, 2.0) m/rad, the cylinder along (1.6, -0.2) / |.|.
    let hydraulic = Scenario::load(&scenario_path("hydraulic.toml")).unwrap().model;
    let force = 23e6 * std::f64::consts::FRAC_PI_4 * 0.18_f64.powi(2)
        - 0.5e6 * std::f64::consts::FRAC_PI_4 * (0.18_f64.powi(2) - 0.1_f64.powi(2));
    let arm_m = (1.6 * 0.7 - 0.2 * 2.0) / 1.6_f64.hypot(0.2);
    let hydraulic_kg = (force * arm_m / g - s0) / 9.0;
    assert!(rel(heaviest_kg(&scene_limit(&hydraulic), 0.0, machine, 9.0, g), hydraulic_kg) < 1e-9);
    // The check before a run: a string 0.5 % over the servo's limit is refused naming the limit
    // and the heaviest string; 0.5 % under passes.
    let string_of = |kg: f64| {
        let pipe = pipearm::robot::pipes::CustomPipeSpec {
            mass_per_length_kg_m: Some(kg / 12.5),
            ..own_pipe(0.2445, 0.0119, 0.0, 2.06e11)
        };
        let spec = StringSpec { pipe: Some(Box::new(pipe)), length_m: Some(12.5), ..StringSpec::default() };
        PipeString::from_spec(&spec).unwrap()
    };
    let mut heavy = servo.clone();
    heavy.payload.string_mut().unwrap().pipe = string_of(1.005 * servo_kg);
    match pipearm::capacity::check(&heavy) {
        Err(e @ CapacityError::Lift { .. }) => {
            let text = e.to_string();
            assert!(text.contains("servo 160 kN·m") && text.contains(&format!("{servo_kg:.1} kg")), "{text}");
        }
        other => panic!("{other:?}"),
    }
    heavy.payload.string_mut().unwrap().pipe = string_of(0.995 * servo_kg);
    assert!(pipearm::capacity::check(&heavy).is_ok());
}

#[test]
fn the_jaws_close_on_the_diameters_their_travel_allows() {
    // pipe_arm's jaws: origins 0.12 m either side of the string's axis, 80 mm thick, travel
    // ±0.05 m: faces 0.03 ..= 0.13 m from the axis, outer diameters 60 ..= 260 mm.
    let robot = Scenario::load(&scenario_path("default.toml")).unwrap().model.robot;
    let range = jaw_range(&robot).unwrap();
    assert!((range.min_diameter_m - 0.06).abs() < 1e-12 && (range.max_diameter_m - 0.26).abs() < 1e-12, "{range:?}");
    // 9-5/8 in casing (244.5 mm) fits, 10-3/4 in (273.1 mm) does not: refused before a run.
    assert!(with_string("default.toml", |s| *s = StringSpec::of_size("9-5/8")).is_ok());
    let e = with_string("default.toml", |s| *s = StringSpec::of_size("10-3/4")).unwrap_err().to_string();
    assert!(e.contains("payload.size") && e.contains("273.1 mm") && e.contains("60.0 ..= 260.0 mm"), "{e}");
}

/// A catalogue row as `--vary` and `pipearm pipes` spell it, written here from its columns.
fn entry_of(p: &PipeSize) -> String {
    format!("{}@{:.2}", p.size, p.nominal_weight_lb_ft)
}

fn expanded(scenario: &str, values: &str) -> Result<Vec<String>, String> {
    let vary: Vary = format!("payload.size={values}").parse().unwrap();
    let vary = expand(&scenario_path(scenario), vary).map_err(|e| e.to_string())?;
    Ok(vary.values.iter().map(|v| v.as_str().unwrap().to_string()).collect())
}

#[test]
fn a_class_expands_to_exactly_the_catalogue_rows_of_its_product() {
    for product in Product::ALL {
        let want: Vec<String> = PIPE_CATALOGUE.iter().filter(|p| p.product == product).map(entry_of).collect();
        assert!(!want.is_empty());
        assert_eq!(expanded("default.toml", product.name()).unwrap(), want, "{}", product.name());
    }
    // An entry is written as `pipearm pipes` prints it; a row named twice runs once; a size stays.
    let casing = PIPE_CATALOGUE.iter().filter(|p| p.product == Product::Casing).count();
    let mixed = expanded("default.toml", "9-5/8@47,casing,2-7/8").unwrap();
    assert_eq!(mixed[0], "9-5/8@47.00");
    assert_eq!(mixed.len(), casing + 1);
    assert_eq!(mixed.last().unwrap(), "2-7/8");
    // Unknown entries and classes name what is allowed, before anything runs.
    for (bad, allowed) in [("9-5/8@48", "9-5/8@47.00"), ("9-7/8@47", "pipearm pipes"), ("casings", "drill-collar")] {
        let e = expanded("default.toml", bad).unwrap_err();
        assert!(e.contains("payload.size") && e.contains(bad) && e.contains(allowed), "{e}");
    }
}

#[test]
fn liftable_is_every_row_the_jaws_take_and_the_servo_holds_by_hand() {
    // servo.toml: the string in the gripper alone at its middle, 9.0 m out; the servo holds
    // (1000 × 160 N·m / g − S₀) / 9.0 at the horizontal, the worst angle of its lift; the jaws
    // close on 60 ..= 260 mm. A size alone is a uniform string of its default range's length.
    let g = 9.80665;
    let servo_kg = (1000.0 * 160.0 / g - pipe_arm_first_moment_kg_m()) / 9.0;
    let mass = |p: &PipeSize| {
        p.mass_per_length_kg_m * p.product.ranges()[p.product.default_range().index()].unwrap().default_m
    };
    // A row within 0.1 % of the limit is left out of the comparison (the hand sum's rounding).
    let on_the_limit = |p: &PipeSize| (mass(p) / servo_kg - 1.0).abs() < 1e-3;
    let by_hand: Vec<String> = PIPE_CATALOGUE
        .iter()
        .filter(|p| (0.06..=0.26).contains(&p.outer_diameter_m) && mass(p) <= servo_kg && !on_the_limit(p))
        .map(entry_of)
        .collect();
    let limit: Vec<String> = PIPE_CATALOGUE.iter().filter(|p| on_the_limit(p)).map(entry_of).collect();
    assert!(limit.len() <= 1, "{limit:?}");
    let lifted: Vec<String> =
        expanded("servo.toml", LIFTABLE).unwrap().into_iter().filter(|e| !limit.contains(e)).collect();
    assert_eq!(lifted, by_hand);
    // The shipped arm's servo lifts no casing of 10-3/4 in or more, no collar of 6 in or more.
    assert!(!lifted.iter().any(|e| e.starts_with("10-3/4@") || e.starts_with("6@") || e.starts_with("11@")));
}

/// robots/casing_arm.urdf: 9 m of 600 x 300 x 20 mm steel box, hand 350 kg at 6 m, gripper 200 kg
/// and two 40 kg jaws at 9 m.
fn casing_arm_first_moment_kg_m() -> f64 {
    let area = 0.6 * 0.3 - 0.56 * 0.26;
    7850.0 * area * 9.0 * 9.0 / 2.0 + 350.0 * 6.0 + (200.0 + 2.0 * 40.0) * 9.0
}

#[test]
fn the_casing_arm_lifts_every_casing_and_collar_by_the_moment_balance() {
    let g = 9.80665;
    let s0 = casing_arm_first_moment_kg_m();
    let model = Scenario::load(&scenario_path("casing_arm.toml")).unwrap().model;
    let machine = pipearm::capacity::machine_first_moment_kg_m(&model.robot).unwrap();
    assert!(rel(machine, s0) < 1e-12, "{machine} vs {s0}");
    // The joint's 600 kN·m at the horizontal, the worst angle: m = (T / g − S₀) / x.
    let limit = scene_limit(&model);
    for x in [5.0, 7.5, 9.0] {
        assert!(rel(heaviest_kg(&limit, 0.0, machine, x, g), (600e3 / g - s0) / x) < 1e-9);
        assert!(rel(heaviest_kg(&limit, 60f64.to_radians(), machine, x, g), (1200e3 / g - s0) / x) < 1e-9);
    }
    // Its jaws: 0.1975 m either side, 100 mm thick, ±0.11 m: 75 ..= 515 mm.
    let range = jaw_range(&model.robot).unwrap();
    assert!((range.min_diameter_m - 0.075).abs() < 1e-12 && (range.max_diameter_m - 0.515).abs() < 1e-12);
    // Its rated range: every casing and drill collar, held by casing_arm.toml's grips.
    let lifted = expanded("casing_arm.toml", LIFTABLE).unwrap();
    for p in PIPE_CATALOGUE.iter().filter(|p| matches!(p.product, Product::Casing | Product::DrillCollar)) {
        assert!(lifted.contains(&entry_of(p)), "{} not lifted", entry_of(p));
    }
}
