//! The flexibility a modal arm leaves out at a cylinder's pin, added back as a massless spring
//! (docs/model.md, "The cylinder's pin: residual flexibility"): the kept modes and the residual
//! together give the clamped arm's static flexibility at the pin, and with it three modes give
//! the coupled arm and cylinder's frequencies of the full FE arm.

mod common;

use std::path::Path;

use common::{PIN, model, rel, uniform};
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity};
use pipearm::scenario::Scenario;

#[test]
fn kept_modes_and_residual_give_the_cantilevers_static_flexibility_at_the_pin() {
    // A uniform cantilever, EI = 2e6 N·m², EA = 1e6 EI / L², L = 4 m; the pin at a = 1.5 m (a
    // node) on a rigid bracket y = −0.3 m across the arm. A force (F_u, F_v) at the pin loads the
    // section at a with (F_u, F_v) and a moment −y F_u, so (beam theory):
    //   G_uu = a/EA + y² a/EI,   G_uv = G_vu = −y a²/(2 EI),   G_vv = a³/(3 EI).
    let (length, ei, a, y): (f64, f64, f64, f64) = (4.0, 2e6, 1.5, -0.3);
    let ea = 1e6 * ei / (length * length);
    let expected =
        [[a / ea + y * y * a / ei, -y * a * a / (2.0 * ei)], [-y * a * a / (2.0 * ei), a.powi(3) / (3.0 * ei)]];
    let options = ArmOptions { gravity_m_s2: 0.0, ..ArmOptions::default() };
    let mut worst = 0.0_f64;
    for modes in [1, 2, 4, 8, 20] {
        let arm =
            ArmModel::new(model(uniform(length, ei, 30.0, 8)), Fidelity::Modal { modes }, options.clone()).unwrap();
        let pin = arm.pin_couplings(&[[a, y]]).unwrap();
        for j in 0..2 {
            // The kept modes' static response to a unit force along j: K_n q = R_nᵀ e_j.
            let q = arm.static_deflection_under(0.0, &pin.rows[0][j]).unwrap();
            for i in 0..2 {
                let total = pin.rows[0][i].dot(&q) + pin.residual_flexibility_m_per_n[(i, j)];
                worst = worst.max((total - expected[i][j]).abs() / expected[1][1]);
                assert!(
                    (total - expected[i][j]).abs() < 1e-9 * expected[1][1],
                    "modal({modes}): G[{i}][{j}] = {total:e} against {:e} m/N",
                    expected[i][j]
                );
            }
        }
    }
    common::validated_row(
        &PIN,
        "4 m cantilever, pin at 1.5 m on a 0.3 m bracket, modal(1, 2, 4, 8, 20): kept modes + residual, 2 × 2 flexibility",
        &format!(
            "beam theory: G_uu = a/EA + y²a/EI, G_uv = −y a²/2EI, G_vv = a³/3EI = {} m/N",
            common::sig(expected[1][1], 4)
        ),
        &format!("largest difference {} of G_vv", common::relative(worst)),
        &common::relative(worst),
        "< 1e-9 of G_vv",
    );
}

#[test]
fn kept_modes_and_residual_give_the_cross_flexibility_between_two_pins() {
    // Two cylinders' pins on the axis of the same cantilever, at a = 1.5 m and b = 3 m: a force
    // on one moves the other (beam theory, a < b): G_uu(a, b) = a/EA, G_vv(a, b) = a²(3b − a)/(6 EI).
    let (length, ei, a, b): (f64, f64, f64, f64) = (4.0, 2e6, 1.5, 3.0);
    let ea = 1e6 * ei / (length * length);
    let expected = [[a / ea, 0.0], [0.0, a * a * (3.0 * b - a) / (6.0 * ei)]];
    let options = ArmOptions { gravity_m_s2: 0.0, ..ArmOptions::default() };
    for modes in [1, 3, 8] {
        let arm =
            ArmModel::new(model(uniform(length, ei, 30.0, 8)), Fidelity::Modal { modes }, options.clone()).unwrap();
        let pins = arm.pin_couplings(&[[a, 0.0], [b, 0.0]]).unwrap();
        for j in 0..2 {
            let q = arm.static_deflection_under(0.0, &pins.rows[1][j]).unwrap();
            for i in 0..2 {
                let total = pins.rows[0][i].dot(&q) + pins.residual_flexibility_m_per_n[(i, 2 + j)];
                assert!(
                    (total - expected[i][j]).abs() < 1e-9 * expected[1][1],
                    "modal({modes}): G[{i}][{j}] between the pins = {total:e} against {:e} m/N",
                    expected[i][j]
                );
            }
        }
    }
}

#[test]
fn the_residual_is_zero_where_no_mode_is_truncated_and_grows_as_modes_are_dropped() {
    let options = ArmOptions { gravity_m_s2: 0.0, ..ArmOptions::default() };
    let build = |f| ArmModel::new(model(uniform(4.0, 2e6, 30.0, 8)), f, options.clone()).unwrap();
    let residual = |f| build(f).pin_couplings(&[[1.5, -0.3]]).unwrap().residual_flexibility_m_per_n[(1, 1)];
    assert_eq!(residual(Fidelity::Fe), 0.0);
    let all = build(Fidelity::Fe).elastic_dofs();
    let first = residual(Fidelity::Modal { modes: 1 });
    let every = residual(Fidelity::Modal { modes: all });
    assert!(every.abs() < 1e-9 * first, "{every:e} m/N with every mode kept, {first:e} with one");
    let shrinking: Vec<f64> = [1, 2, 3, 6, 12].map(|modes| residual(Fidelity::Modal { modes })).to_vec();
    common::validated(
        &PIN,
        "residual flexibility G_vv at the pin: fe, every mode kept, then modal(1, 2, 3, 6, 12)",
        "0 where no mode is truncated; shrinking as modes are kept",
        &format!(
            "fe {}; every mode {} m/N; {} m/N",
            residual(Fidelity::Fe),
            common::sig(every, 2),
            shrinking.iter().map(|r| common::sig(*r, 3)).collect::<Vec<_>>().join(", ")
        ),
        "fe exactly 0; every mode < 1e-9 of modal(1)'s; decreasing, positive",
    );
    assert!(shrinking.windows(2).all(|w| w[1] < w[0]) && shrinking[4] > 0.0, "{shrinking:?}");
}

/// Coupled frequencies (Hz) up to `band_hz` of the hydraulic scene's arm and drive, linearised
/// at rest at the end of the drive's path, at `fidelity`.
fn coupled_hz(fidelity: Fidelity, band_hz: f64) -> Vec<f64> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hydraulic.toml");
    let m = Scenario::load(&path).unwrap().model;
    let arm = m.arm_model(fidelity).unwrap();
    let drive = m.hub_drive_held_at(m.drive.motion.end_rad());
    let poles = ArmSimulation::new(arm, drive, m.integrator).unwrap().linear_poles().unwrap();
    let mut hz: Vec<f64> =
        poles.iter().filter(|p| p.im > 0.0).map(|p| p.im / std::f64::consts::TAU).filter(|f| *f <= band_hz).collect();
    hz.sort_by(f64::total_cmp);
    hz
}

#[test]
fn three_modes_with_the_pin_residual_give_the_fe_arms_coupled_frequencies() {
    // The cylinder props the arm at its pin, 2 m from the pivot. The full FE arm (no truncation,
    // no residual) is the reference; up to the shipped scene's impact band, 70 Hz.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hydraulic.toml");
    let m = Scenario::load(&path).unwrap().model;
    let pipearm::actuator::Actuator::Hydraulic(h) = &m.drive.actuator else { panic!("not hydraulic") };
    let cylinder = h.cylinders.each[0];
    let pin = m.arm_model(Fidelity::Modal { modes: 3 }).unwrap().pin_couplings(&[cylinder.arm_pin_m]).unwrap();
    let end = m.drive.motion.end_rad();
    let [px, py] = cylinder.arm_pin_at_m(end);
    let d = [px - cylinder.base_pin_m[0], py - cylinder.base_pin_m[1]];
    let (s, c, l) = (end.sin(), end.cos(), d[0].hypot(d[1]));
    let along = pin.flexibility_along_m_per_n(&[[(c * d[0] + s * d[1]) / l, (-s * d[0] + c * d[1]) / l]])[0];
    let column = cylinder.oil_stiffness_n_m(h.circuit.bulk_modulus_pa, l);
    println!(
        "modal(3) residual at the pin {:.3e} m/N, {along:.3e} along the rod at the end; oil column 1/k {:.3e} m/N",
        pin.residual_flexibility_m_per_n[(1, 1)],
        1.0 / column
    );
    let fe = coupled_hz(Fidelity::Fe, 70.0);
    let modal = coupled_hz(Fidelity::Modal { modes: 3 }, 80.0);
    println!("coupled frequencies: fe {fe:.2?} Hz, modal(3) {modal:.2?} Hz");
    let nearest: Vec<f64> = fe
        .iter()
        .map(|f| modal.iter().copied().min_by(|a, b| rel(*a, *f).total_cmp(&rel(*b, *f))).unwrap_or(f64::NAN))
        .collect();
    common::validated_rel_all(
        &PIN,
        "hydraulic.toml, arm and cylinder linearised at rest at 90°: coupled frequencies up to 70 Hz, modal(3) + pin residual",
        &fe,
        "the full FE arm with the cylinder, no truncation, no residual",
        &nearest,
        "Hz",
        0.02,
    );
    assert!(fe.len() >= 3, "{fe:?}");
    for f in &fe {
        let nearest = modal.iter().copied().min_by(|a, b| rel(*a, *f).total_cmp(&rel(*b, *f))).unwrap();
        assert!(rel(nearest, *f) < 0.02, "fe {fe:?} Hz against modal(3) {modal:?} Hz");
    }
}
