//! The held string as a beam of its own, against closed forms and a full finite-element model:
//! a tube clamped at two points (each overhang a cantilever, the span between the hands
//! clamped–clamped), the static sag of an overhang, the coupled arm + string frequencies of the
//! Craig–Bampton reduction against the unreduced FE model of both beams, and the energy balance
//! of the coupled system, free and driven.
//!
//! Roots of the characteristic equations (Blevins, *Formulas for Natural Frequency and Mode
//! Shape*, 1979, Table 8-1): clamped–free λ = 1.87510, 4.69409, 7.85476; clamped–clamped
//! λ = 4.73004, 7.85320; ω = λ² √(EI / (μ L⁴)).

mod common;

use common::{STRING_BEAM, rel, validated_rel, validated_rel_all};
use nalgebra::{DMatrix, DVector};
use pipearm::arm::{ArmModel, ArmOptions, ArmSimulation, Fidelity, HubDrive};
use pipearm::beam::{BeamModel, BeamSpec, MemberSpec, Segment};
use pipearm::drive::{MotionProfile, TrapezoidLimit};
use pipearm::integrate::IntegratorKind;

const CANTILEVER: [f64; 3] = [1.875_10, 4.694_09, 7.854_76];
const CLAMPED_CLAMPED: [f64; 2] = [4.730_04, 7.853_20];

/// A 2-7/8 in tubing joint: EI of the 73.0 x 5.51 mm tube in steel, the API nominal 9.67 kg/m.
fn tubing(length_m: f64) -> Segment {
    let (d, t) = (0.0730_f64, 0.217 * 0.0254);
    let i = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
    let a = std::f64::consts::PI / 4.0 * (d * d - (d - 2.0 * t).powi(2));
    Segment { length_m, axial_rigidity_n: 2.06e11 * a, bending_rigidity_n_m2: 2.06e11 * i, mass_per_length_kg_m: 9.67 }
}

/// A 9 m arm of `ei` carrying a 12.5 m string from `start_m`, clamped at `clamps_m`.
fn arm_with_string(ei: f64, start_m: f64, clamps_m: Vec<f64>, kept_modes: Option<usize>, elements: usize) -> BeamSpec {
    let arm =
        Segment { length_m: 9.0, axial_rigidity_n: 3.7e9, bending_rigidity_n_m2: ei, mass_per_length_kg_m: 142.3 };
    BeamSpec::uniform(arm, 24).with_member(MemberSpec {
        name: "string".into(),
        start_m,
        segment: tubing(12.5),
        clamps_m,
        elements,
        kept_modes,
        damping_ratio: 0.0,
        pieces: Vec::new(),
    })
}

fn omega(lambda: f64, length_m: f64, s: &Segment) -> f64 {
    lambda * lambda * (s.bending_rigidity_n_m2 / (s.mass_per_length_kg_m * length_m.powi(4))).sqrt()
}

#[test]
fn a_tube_clamped_at_two_hands_rings_as_two_cantilevers_and_a_clamped_span() {
    // Overhangs of 4.0 and 5.5 m, a 3.0 m span between the hands (unequal, so no two
    // frequencies coincide): held in its hands the string's modes are those of the three pieces.
    let beam = BeamModel::new(arm_with_string(5.95e-4 * 2.06e11, 2.0, vec![6.0, 9.0], None, 50)).unwrap();
    let s = tubing(12.5);
    let mut exact: Vec<f64> = CANTILEVER
        .iter()
        .flat_map(|l| [omega(*l, 4.0, &s), omega(*l, 5.5, &s)])
        .chain(CLAMPED_CLAMPED.iter().map(|l| omega(*l, 3.0, &s)))
        .collect();
    exact.sort_by(f64::total_cmp);
    let got = &beam.member_modes().unwrap().omegas_rad_s;
    validated_rel_all(
        &STRING_BEAM,
        "2⅞ in tubing held at two hands (overhangs 4.0 and 5.5 m, span 3.0 m): first 6 frequencies, 50 elements",
        &exact[..6],
        "two clamped–free overhangs and a clamped–clamped span, λ of Blevins 1979, Table 8-1",
        &got[..6],
        "rad/s",
        2e-3,
    );
    for (k, (g, e)) in got.iter().zip(&exact).take(6).enumerate() {
        assert!(rel(*g, *e) < 2e-3, "mode {k}: {g} rad/s vs exact {e}");
    }
}

#[test]
fn a_tube_on_a_limp_arm_rings_free_free() {
    // Hands on an arm with next to no stiffness or mass: the string is as good as free, and its
    // bending modes are the free–free tube's (λ = 4.73004, 7.85320), above the near-zero
    // frequencies of its rigid motions on the limp arm.
    let limp =
        Segment { length_m: 9.0, axial_rigidity_n: 1e-6, bending_rigidity_n_m2: 1e-6, mass_per_length_kg_m: 1e-3 };
    let spec = BeamSpec::uniform(limp, 24).with_member(MemberSpec {
        name: "string".into(),
        start_m: 1.25,
        segment: tubing(12.5),
        clamps_m: vec![6.0, 9.0],
        elements: 50,
        kept_modes: None,
        damping_ratio: 0.0,
        pieces: Vec::new(),
    });
    let beam = BeamModel::new(spec).unwrap();
    let s = tubing(12.5);
    let all = beam.modes_spinning(0.0, false).unwrap();
    // The string's modes: those whose kinetic energy (Φᵀ M Φ = 1) is mostly in the string's own
    // DOFs, not in the limp arm's.
    let own = beam.member.as_ref().unwrap().own_dofs.clone();
    let m_own = beam.mass.view((own.start, own.start), (own.len(), own.len()));
    let in_string = |i: usize| {
        let phi = all.shapes.column(i).rows(own.start, own.len()).into_owned();
        phi.dot(&(m_own * &phi))
    };
    let flexible: Vec<f64> = (0..all.len())
        .filter(|&i| all.omegas_rad_s[i] > 1.0 && in_string(i) > 0.9)
        .map(|i| all.omegas_rad_s[i])
        .collect();
    let free_free: Vec<f64> = [4.730_04, 7.853_20].iter().map(|l| omega(*l, 12.5, &s)).collect();
    validated_rel_all(
        &STRING_BEAM,
        "the 12.5 m tubing held by a limp arm: first two bending frequencies",
        &free_free,
        "free–free beam, λ = 4.73004, 7.85320: Blevins 1979",
        &flexible[..2],
        "rad/s",
        1e-3,
    );
    for (k, lambda) in [4.730_04, 7.853_20].iter().enumerate() {
        let exact = omega(*lambda, 12.5, &s);
        assert!(rel(flexible[k], exact) < 1e-3, "free-free mode {k}: {} vs {exact} rad/s", flexible[k]);
    }
}

#[test]
fn the_static_sag_of_an_overhang_is_w_l4_over_8_ei() {
    // On an arm a million times stiffer than the real one, the hands stay put: the 5.5 m
    // overhang's tip sags w a⁴ / 8EI under its own weight (w = μ g), the span between the hands
    // only its own w s⁴ / 384 EI.
    let beam = BeamModel::new(arm_with_string(1e6 * 1.2e8, 2.0, vec![6.0, 9.0], None, 50)).unwrap();
    let member = beam.member.as_ref().unwrap();
    let g = 9.80665;
    let mut load = DVector::zeros(beam.dofs());
    let own = member.own_dofs.clone();
    load.rows_mut(own.start, own.len()).copy_from(&(-g * beam.transverse_mass.rows(own.start, own.len())));
    let d = beam.static_displacement(&load).unwrap();
    let s = tubing(12.5);
    let w = s.mass_per_length_kg_m * g;
    let tip = -member.point_rows(14.5, beam.dofs())[1].dot(&d);
    let exact = w * 5.5_f64.powi(4) / (8.0 * s.bending_rigidity_n_m2);
    validated_rel(&STRING_BEAM, "static sag of the 5.5 m overhang's tip", exact, "w a⁴ / 8EI", tip, "m", 1e-3);
    assert!(rel(tip, exact) < 1e-3, "overhang tip sag {tip} m vs w a⁴/8EI = {exact} m");
    let mid = -member.point_rows(7.5, beam.dofs())[1].dot(&d);
    let exact_mid = w * 3.0_f64.powi(4) / (384.0 * s.bending_rigidity_n_m2);
    validated_rel(&STRING_BEAM, "static sag at the middle of the 3 m span", exact_mid, "w s⁴ / 384EI", mid, "m", 1e-2);
    assert!(rel(mid, exact_mid) < 1e-2, "mid-span sag {mid} m vs w s⁴/384EI = {exact_mid} m");
}

/// Frequencies (rad/s) of the arm at `fidelity` with the string at its beam's reduction,
/// clamped at the hub: the eigenvalues of the reduced K and M (Bᵀ K B, Bᵀ M B).
fn reduced_omegas(beam: BeamModel, fidelity: Fidelity) -> Vec<f64> {
    let arm = ArmModel::new(beam, fidelity, ArmOptions { damping_ratios: vec![0.0], ..ArmOptions::default() }).unwrap();
    let b = &arm.basis;
    let k = b.transpose() * &arm.beam.stiffness * b;
    let m = b.transpose() * &arm.beam.mass * b;
    generalized_omegas(&k, &m)
}

fn generalized_omegas(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Vec<f64> {
    let l = m.clone().cholesky().unwrap().l();
    let l_inv = l.clone().try_inverse().unwrap();
    let a = &l_inv * k * l_inv.transpose();
    let mut w: Vec<f64> = a.symmetric_eigen().eigenvalues.iter().map(|x| x.max(0.0).sqrt()).collect();
    w.sort_by(f64::total_cmp);
    w
}

#[test]
fn the_reduced_arm_and_string_ring_at_the_full_fe_models_frequencies() {
    // The shipped geometry: hands at 6.0 and 9.0 m, the string centred between them. The full
    // FE model of both beams (every DOF, no reduction) against arm modal(4) + string modal(6)
    // (Craig–Bampton): the first four coupled frequencies within 0.5 %.
    let spec = |kept| arm_with_string(1.226e8, 1.25, vec![6.0, 9.0], kept, 25);
    let full = BeamModel::new(spec(None)).unwrap();
    let exact = full.modes_spinning(0.0, false).unwrap().omegas_rad_s;
    let reduced = reduced_omegas(BeamModel::new(spec(Some(6))).unwrap(), Fidelity::Modal { modes: 4 });
    validated_rel_all(
        &STRING_BEAM,
        "arm modal(4) + string modal(6) (Craig–Bampton), shipped geometry: first 4 coupled frequencies",
        &exact[..4],
        "the full FE model of both beams, every DOF",
        &reduced[..4],
        "rad/s",
        5e-3,
    );
    for k in 0..4 {
        assert!(rel(reduced[k], exact[k]) < 5e-3, "coupled mode {k}: {} vs full fe {} rad/s", reduced[k], exact[k]);
    }
    // The string's first mode sits below the arm's; coupled, the two repel: the lowest coupled
    // mode falls below the string's own and the arm's first rises above its own (the string in
    // its hands acts on the arm as a tuned mass).
    let alone = BeamModel::new(spec(Some(6))).unwrap();
    let string_first = alone.member_modes().unwrap().omegas_rad_s[0];
    let arm_first = alone.modes().unwrap().omegas_rad_s[0];
    assert!(string_first < arm_first, "string {string_first} vs arm {arm_first} rad/s");
    assert!(
        exact[0] < string_first && exact[2] > arm_first,
        "coupled {:?}, string {string_first}, arm {arm_first}",
        &exact[..3]
    );
    // fe arm + fe string through the arm's basis is the full model itself.
    let both_fe = reduced_omegas(BeamModel::new(spec(None)).unwrap(), Fidelity::Fe);
    validated_rel_all(
        &STRING_BEAM,
        "fe arm + fe string through the arm's basis: first 6 coupled frequencies",
        &exact[..6],
        "the full FE model of both beams",
        &both_fe[..6],
        "rad/s",
        1e-7,
    );
    for k in 0..6 {
        assert!(rel(both_fe[k], exact[k]) < 1e-7, "fe/fe mode {k}: {} vs {}", both_fe[k], exact[k]);
    }
}

const NEWMARK: IntegratorKind = IntegratorKind::Newmark { beta: 0.25, gamma: 0.5 };

#[test]
fn the_free_coupled_system_keeps_its_energy() {
    // Free hub, gravity, no damping: the arm and the string released bent (a tip load on the
    // string's outer end) swing and ring; the trapezoidal rule conserves the total energy of
    // the coupled system (kinetic + strain + gravity) to its second-order error.
    let beam = BeamModel::new(arm_with_string(1.226e8, 1.25, vec![6.0, 9.0], Some(4), 25)).unwrap();
    let member_tip = beam.member.as_ref().unwrap().point_rows(13.75, beam.dofs())[1].clone();
    let options = ArmOptions { damping_ratios: vec![0.0], hub_inertia_kg_m2: 50.0, ..ArmOptions::default() };
    let arm = ArmModel::new(beam, Fidelity::Modal { modes: 3 }, options).unwrap();
    let q0 = static_shape(&arm, &(2e3 * &member_tip));
    let n = arm.elastic_dofs();
    let mut sim =
        ArmSimulation::with_initial(arm, HubDrive::Free { torque_n_m: 0.0 }, NEWMARK, q0, DVector::zeros(n)).unwrap();
    let e0 = sim.sample().energies.total_j();
    let scale = sim.sample().energies.strain_j.abs() + sim.sample().energies.gravity_j.abs();
    let mut worst = 0.0_f64;
    for _ in 0..4000 {
        sim.step(5e-4).unwrap();
        worst = worst.max((sim.sample().energies.total_j() - e0).abs());
    }
    common::validated_row(
        &STRING_BEAM,
        "free hub, gravity, undamped: arm modal(3) + string modal(4) released bent, 2 s at 0.5 ms (Newmark ¼)",
        "total energy conserved (the trapezoidal rule's second-order error)",
        &format!("largest drift {} J of {} J", common::sig(worst, 2), common::sig(scale, 4)),
        &common::relative(worst / scale),
        "< 1e-4 of strain + gravity energy",
    );
    assert!(sim.state().x[0] < -0.05, "the arm must swing down under gravity: θ = {}", sim.state().x[0]);
    assert!(worst < 1e-4 * scale, "energy drift {worst} J of {scale} J");
}

/// The elastic coordinates that a static generalized load `f` (over the beam's DOFs) gives.
fn static_shape(arm: &ArmModel, f: &DVector<f64>) -> DVector<f64> {
    let b = &arm.basis;
    let k = b.transpose() * &arm.beam.stiffness * b;
    k.lu().solve(&(b.transpose() * f)).unwrap()
}

#[test]
fn the_drive_s_work_on_the_coupled_system_is_its_energy_gain() {
    // Prescribed hub, a 5 s trapezoidal lift to 90° under gravity, no damping: ∫ τ θ̇ dt equals
    // the change of kinetic + strain + gravity energy of arm and string.
    let beam = BeamModel::new(arm_with_string(1.226e8, 1.25, vec![6.0, 9.0], Some(4), 25)).unwrap();
    let options = ArmOptions { damping_ratios: vec![0.0], ..ArmOptions::default() };
    let arm = ArmModel::new(beam, Fidelity::Modal { modes: 3 }, options).unwrap();
    let profile =
        MotionProfile::trapezoidal(0.0, std::f64::consts::FRAC_PI_2, 5.0, TrapezoidLimit::RampFraction(0.2)).unwrap();
    let mut sim = ArmSimulation::new(arm, HubDrive::Prescribed(profile), NEWMARK).unwrap();
    let first = sim.sample();
    let (e0, mut power0, mut work) = (first.energies.total_j(), first.drive_torque_n_m * first.hub.rate_rad_s, 0.0);
    let h = 5e-4;
    let mut sample = first;
    for _ in 0..(6.0 / h) as usize {
        sim.step(h).unwrap();
        sample = sim.sample();
        let power = sample.drive_torque_n_m * sample.hub.rate_rad_s;
        work += 0.5 * h * (power0 + power);
        power0 = power;
    }
    let gain = sample.energies.total_j() - e0;
    validated_rel(
        &STRING_BEAM,
        "arm + string lifted to 90° in 5 s, undamped: energy gained",
        work,
        "∫ τ θ̇ dt, the drive's work",
        gain,
        "J",
        1e-3,
    );
    assert!(work > 1e4, "lifting arm and string takes work: {work} J");
    assert!((gain - work).abs() < 1e-3 * work, "energy gain {gain} J vs drive work {work} J");
}
