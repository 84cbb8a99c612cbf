//! Bad input fails with a typed error that names the parameter (and, for files, the file and
//! the key), never a panic.

mod common;

use std::path::{Path, PathBuf};

use common::uniform;
use pipearm::arm::{ArmError, ArmModel, ArmOptions, Fidelity};
use pipearm::beam::{BeamError, BeamModel, Material, SectionShape, Segment};
use pipearm::scenario::Scenario;

fn named(err: &BeamError) -> &str {
    match err {
        BeamError::InvalidParameter { name, .. } => name,
        other => panic!("expected InvalidParameter, got {other}"),
    }
}

#[test]
fn beam_parameters_out_of_range_are_named() {
    let mut spec = uniform(0.0, 1.0, 1.0, 10);
    assert_eq!(named(&BeamModel::new(spec.clone()).unwrap_err()), "length_m");
    spec.segments[0].length_m = -2.0;
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "length_m");
    let mut spec = uniform(1.0, 1.0, 1.0, 10);
    spec.segments[0].mass_per_length_kg_m = 0.0;
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "mass_per_length_kg_m");
    let spec = uniform(1.0, 1.0, 1.0, 0);
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "elements");
    let shape = SectionShape::SolidCircle { diameter_m: 0.1 };
    let e =
        Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: -2e11, density_kg_m3: 7850.0 }).unwrap_err();
    assert_eq!(named(&e), "youngs_modulus_pa");
    let e = Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: 2e11, density_kg_m3: 0.0 }).unwrap_err();
    assert_eq!(named(&e), "density_kg_m3");
    let e =
        Segment::from_shape(1.0, &shape, &Material { youngs_modulus_pa: f64::NAN, density_kg_m3: 1.0 }).unwrap_err();
    assert_eq!(named(&e), "youngs_modulus_pa");
}

#[test]
fn masses_outside_the_arm_are_named() {
    let spec = uniform(2.0, 1.0, 1.0, 10).with_mass("gripper", 2.5, 10.0, 0.0);
    let e = BeamModel::new(spec).unwrap_err();
    assert_eq!(named(&e), "masses.gripper.position_m");
    assert!(e.to_string().contains("0 ..= 2"), "{e}");
    let spec = uniform(2.0, 1.0, 1.0, 10).with_mass("hand", 1.0, -3.0, 0.0);
    assert_eq!(named(&BeamModel::new(spec).unwrap_err()), "masses.hand.mass_kg");
}

#[test]
fn more_modes_than_dofs_is_refused() {
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    let dofs = beam.dofs();
    let e = ArmModel::new(beam, Fidelity::Modal { modes: dofs + 1 }, ArmOptions::default()).unwrap_err();
    match &e {
        ArmError::InvalidParameter { name, .. } => assert_eq!(name, "model.modes"),
        other => panic!("unexpected {other}"),
    }
    assert!(e.to_string().contains(&format!("1 ..= {dofs}")), "{e}");
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    assert!(ArmModel::new(beam, Fidelity::Modal { modes: 0 }, ArmOptions::default()).is_err());
    let beam = BeamModel::new(uniform(2.0, 1.0, 1.0, 4)).unwrap();
    let options = ArmOptions { damping_ratios: vec![-0.1], ..ArmOptions::default() };
    assert!(matches!(ArmModel::new(beam, Fidelity::Fe, options), Err(ArmError::InvalidParameter { .. })));
}

/// Writes the default scenario with `edit` applied to a temporary file beside it (so that its
/// relative robot path still resolves).
fn edited_default(tag: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let text = std::fs::read_to_string(dir.join("default.toml")).unwrap();
    let path = dir.join(format!(".bad-{tag}-{}.toml", std::process::id()));
    std::fs::write(&path, edit(text)).unwrap();
    path
}

fn load_error(tag: &str, edit: impl Fn(String) -> String) -> String {
    let path = edited_default(tag, edit);
    let result = Scenario::load(&path);
    std::fs::remove_file(&path).ok();
    let message = match result {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{tag}: the edited scenario loaded"),
    };
    assert!(message.contains(&path.display().to_string()), "error does not name the file: {message}");
    message
}

#[test]
fn scenario_errors_name_file_key_and_range() {
    let m = load_error("unknown", |t| t.replace("step_s = 0.003", "step_s = 0.003\nstep_count = 3"));
    assert!(m.contains("step_count"), "{m}");
    let m = load_error("missing", |t| t.replace("step_s = 0.003\n", ""));
    assert!(m.contains("step_s"), "{m}");
    let m = load_error("negative-step", |t| t.replace("step_s = 0.003", "step_s = -0.003"));
    assert!(m.contains("time.step_s") && m.contains("0 < step_s"), "{m}");
    let m = load_error("accel", |t| t.replace("ramp_fraction = 0.2", "ramp_fraction = 0.9"));
    assert!(m.contains("drive.ramp_fraction"), "{m}");
    let m = load_error("both-limits", |t| t.replace("ramp_fraction = 0.2", "ramp_fraction = 0.2\naccel_deg_s2 = 3.0"));
    assert!(m.contains("drive.limit") && m.contains("exactly one"), "{m}");
    let generalized_alpha = |rho: &str| format!("method = \"generalized-alpha\"\nrho_inf = {rho}");
    let m = load_error("integrator", |t| t.replace("method = \"rk4\"", &generalized_alpha("1.5")));
    assert!(m.contains("integrator") && m.contains("rho_inf"), "{m}");
    // Controlled free steps: a tolerance needs a free step, a free step an implicit method.
    let m = load_error("tolerance", |t| t.replace("step_s = 0.003", "step_s = 0.003\ntolerance_m = 1e-6"));
    assert!(m.contains("time.tolerance_m") && m.contains("free_step_s"), "{m}");
    let m = load_error("free-explicit", |t| t.replace("step_s = 0.003", "step_s = 0.003\nfree_step_s = 0.01"));
    assert!(m.contains("time.free_step_s") && m.contains("implicit"), "{m}");
    let m = load_error("bad-tolerance", |t| {
        t.replace("method = \"rk4\"", &generalized_alpha("0.8"))
            .replace("step_s = 0.003", "step_s = 0.003\nfree_step_s = 0.01\ntolerance_m = -1.0")
    });
    assert!(m.contains("time.tolerance_m") && m.contains("0 < tolerance_m"), "{m}");
    let m = load_error("modes", |t| t.replace("kind = \"auto\"", "kind = \"modal\"\nmodes = 500"));
    assert!(m.contains("model.modes") && m.contains("1 ..= 72"), "{m}");
    let m = load_error("beyond-limit", |t| t.replace("end_deg = 90.0", "end_deg = 120.0"));
    assert!(m.contains("drive.end_deg") && m.contains("limits"), "{m}");
    let m = load_error("pipe", |t| t.replace("size = \"2-7/8\"", "size = \"2-1/2\""));
    assert!(m.contains("payload.string.size") && m.contains("2-3/8"), "{m}");
    let m = load_error("pad-station", |t| t.replace("station_m = 8.2", "station_m = 12.0"));
    assert!(m.contains("dampeners[0].station_m") && m.contains("0 ..= 9"), "{m}");
    let m = load_error("pad-law", |t| t.replace("restitution = 0.6", "restitution = 1.6"));
    assert!(m.contains("dampeners[0].law.restitution") && m.contains("0 < e <= 1"), "{m}");
    let m = load_error("pad-gap", |t| t.replace("gap_m = 0.0002", "gap_m = -0.001"));
    assert!(m.contains("dampeners[0].gap_m"), "{m}");
    let m = load_error("damping", |t| format!("{t}\n[arm]\ndamping_ratios = [0.01, -0.1]\n"));
    assert!(m.contains("arm.damping_ratios[1]") && m.contains("0 <= ratio < 2"), "{m}");
    let m = load_error("law-kind", |t| t.replace("kind = \"hunt-crossley\"", "kind = \"hertz\""));
    assert!(m.contains("hertz") && m.contains("hunt-crossley"), "{m}");
    let m = load_error("robot-missing", |t| t.replace("pipe_arm.urdf", "no_such_arm.urdf"));
    assert!(m.contains("no_such_arm.urdf") && m.contains("cannot read"), "{m}");
    let m = load_error("block", |t| t.replace("kind = \"string\"\nsize = \"2-7/8\"", "kind = \"block\"\nblock = 4"));
    assert!(m.contains("payload.block") && m.contains("1, 2, 3"), "{m}");
}
