//! A beam on a spinning hub: centrifugal stiffening against the exact rotating-cantilever
//! frequencies, and the classic failure of the model without it.

mod common;

use common::{ROTATING_BEAM, model, rel, uniform, validated, validated_rel};
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, HubDrive};
use pipearm::drive::MotionProfile;
use pipearm::integrate::IntegratorKind;

/// First flapwise frequency ω̄ = ω / sqrt(EI/ρAL⁴) of a uniform cantilever spinning at Ω̄ about a
/// hub of zero radius (Wright, Smith, Thresher & Wang 1982; also Banerjee 2000, Table 1).
const FLAPWISE_EXACT: [(f64, f64); 6] =
    [(0.0, 3.5160), (1.0, 3.6817), (2.0, 4.1373), (3.0, 4.7973), (4.0, 5.5850), (5.0, 6.4495)];

#[test]
fn in_plane_frequency_matches_the_exact_rotating_cantilever() {
    // In the plane of rotation the centrifugal field also softens: ω_in² = ω_flap² − Ω².
    let beam = model(uniform(1.0, 1.0, 1.0, 30));
    for (spin, exact_flap) in FLAPWISE_EXACT {
        let omega_in = beam.modes_spinning(spin, true).unwrap().omegas_rad_s[0];
        let flap = (omega_in * omega_in + spin * spin).sqrt();
        validated_rel(
            &ROTATING_BEAM,
            &format!("first in-plane frequency at Ω̄ = {spin}, as flapwise √(ω_in² + Ω²), 30 elements"),
            exact_flap,
            "ω̄ of Wright, Smith, Thresher & Wang 1982; Banerjee 2000, Table 1",
            flap,
            "",
            1e-3,
        );
        assert!(rel(flap, exact_flap) < 1e-3, "Ω̄ = {spin}: {flap} vs {exact_flap}");
    }
}

#[test]
fn southwell_coefficient_of_the_first_mode() {
    // ω² = ω₁² + (K_S − 1)Ω² with K_S = 1.193 for the uniform cantilever's first mode.
    let beam = model(uniform(1.0, 1.0, 1.0, 30));
    let w1 = beam.modes().unwrap().omegas_rad_s[0];
    for spin in [0.5, 1.0] {
        let w = beam.modes_spinning(spin, true).unwrap().omegas_rad_s[0];
        let southwell = (w * w - w1 * w1) / (spin * spin) + 1.0;
        validated_rel(
            &ROTATING_BEAM,
            &format!("Southwell coefficient of the first mode at Ω̄ = {spin}"),
            1.193,
            "K_S of the uniform cantilever's first mode",
            southwell,
            "",
            5e-3,
        );
        assert!(rel(southwell, 1.193) < 5e-3, "Ω̄ = {spin}: K_S = {southwell}");
    }
}

#[test]
fn without_stiffening_the_arm_softens_as_omega_squared_and_fails_past_omega_1() {
    let beam = model(uniform(1.0, 1.0, 1.0, 30));
    let w1 = beam.modes().unwrap().omegas_rad_s[0];
    let spin = 0.8 * w1;
    let w = beam.modes_spinning(spin, false).unwrap().omegas_rad_s[0];
    validated_rel(
        &ROTATING_BEAM,
        "without stiffening, at Ω = 0.8 ω₁: ω² of the first mode",
        w1 * w1 - spin * spin,
        "ω₁² − Ω² (centrifugal softening alone)",
        w * w,
        "",
        1e-6,
    );
    assert!(rel(w * w, w1 * w1 - spin * spin) < 1e-6);
    assert!(beam.modes_spinning(1.05 * w1, false).is_err(), "an unstiffened arm past ω₁ must be unstable");
    assert!(beam.modes_spinning(1.05 * w1, true).is_ok(), "with stiffening the same spin is stable");
}

/// Kane, Ryan & Banerjee's spin-up beam: max |tip deflection| during the spin-up and after it,
/// or None if the run blew up.
fn spin_up_deflections(stiffening: bool, final_rate_rad_s: f64) -> Option<(f64, f64)> {
    let spec = pipearm::beam::BeamSpec::uniform(
        pipearm::beam::Segment {
            length_m: 10.0,
            axial_rigidity_n: 2.8e7,
            bending_rigidity_n_m2: 1.4e4,
            mass_per_length_kg_m: 1.2,
        },
        20,
    );
    let options = ArmOptions {
        damping_ratios: vec![0.0],
        gravity_m_s2: 0.0,
        geometric_stiffening: stiffening,
        ..Default::default()
    };
    let arm = ArmModel::new(model(spec), Fidelity::Modal { modes: 4 }, options).unwrap();
    let drive = HubDrive::Prescribed(MotionProfile::spin_up(0.0, final_rate_rad_s, 15.0).unwrap());
    let mut sim = ArmSimulation::new(arm, drive, IntegratorKind::default()).unwrap();
    let (mut during, mut after) = (0.0_f64, 0.0_f64);
    let result = sim.run_until(30.0, 0.005, |s| {
        let v = s.tip_deflection_hub_m[1].abs();
        if s.t_s <= 15.0 { during = during.max(v) } else { after = after.max(v) }
    });
    (result.is_ok() && after.is_finite() && after < 1e3).then_some((during, after))
}

#[test]
fn spin_up_past_the_first_frequency_needs_geometric_stiffening() {
    // ω₁ = 1.875² sqrt(EI/ρAL⁴) = 3.80 rad/s; spin up to 6 rad/s.
    let (during, after) = spin_up_deflections(true, 6.0).expect("the stiffened model stays bounded");
    let unstiffened = spin_up_deflections(false, 6.0);
    validated(
        &ROTATING_BEAM,
        "Kane, Ryan & Banerjee's spin-up beam to 6 rad/s, past ω₁ = 3.80 rad/s, modal(4)",
        "bounded with geometric stiffening; divergent without (Kane, Ryan & Banerjee 1987)",
        &format!(
            "stiffened: {} m during, {} m after; unstiffened: {}",
            common::sig(during, 3),
            common::sig(after, 3),
            match unstiffened {
                None => "diverged".to_string(),
                Some((_, a)) => format!("{} m after", common::sig(a, 3)),
            }
        ),
        "after < 2 × during stiffened; unstiffened diverges or > 100 × it",
    );
    assert!(after < 2.0 * during.max(1e-3), "stiffened: {during} m during, {after} m after");
    match unstiffened {
        None => {}
        Some((_, after_unstiffened)) => {
            assert!(after_unstiffened > 100.0 * after, "unstiffened stayed bounded: {after_unstiffened} m")
        }
    }
    // Below ω₁ both models stay bounded.
    assert!(spin_up_deflections(false, 2.0).is_some());
}
