//! The FE beam against exact Euler–Bernoulli solutions (the roots of the frequency equations,
//! Blevins, Formulas for Natural Frequency and Mode Shape; classical static formulas).

mod common;

use common::{BEAM, lambdas, model, rel, uniform, validated_rel, validated_rel_all};

/// Exact λ of the clamped–free beam with tip mass μ = M/(ρAL) (reference table).
const TIP_MASS_CASES: [(f64, [f64; 3]); 4] = [
    (0.0, [1.87510, 4.69409, 7.85476]),
    (0.2, [1.61640, 4.26706, 7.31837]),
    (1.0, [1.24792, 4.03114, 7.13413]),
    (5.0, [0.87002, 3.94998, 7.08254]),
];

#[test]
fn clamped_free_with_tip_mass_matches_characteristic_equation() {
    for (mu, exact) in TIP_MASS_CASES {
        let beam = model(uniform(1.0, 1.0, 1.0, 20).with_mass("tip", 1.0, mu, 0.0));
        let modes = beam.modes().unwrap();
        let got = lambdas(&modes.omegas_rad_s, 1.0, 1.0, 1.0, 3);
        validated_rel_all(
            &BEAM,
            &format!("clamped–free with tip mass μ = {mu}: λ₁…λ₃ at 20 elements"),
            &exact,
            "roots of 1 + cos λ cosh λ + μλ(cos λ sinh λ − sin λ cosh λ) = 0; Blevins 1979, Table 8-1",
            &got,
            "",
            1e-3,
        );
        for (g, e) in got.iter().zip(exact) {
            // Reference values carry 6 significant digits; the FE error at 20 elements is far below 0.1 %.
            assert!(rel(*g, e) < 1e-3, "mu = {mu}: lambda {g} vs exact {e}");
        }
    }
}

#[test]
fn clamped_free_with_tip_mass_and_inertia_matches_characteristic_equation() {
    for (j, exact) in [(0.01, [1.24245, 3.63862, 5.66300]), (0.1, [1.19567, 2.50506, 4.97510])] {
        let beam = model(uniform(2.0, 3.0, 1.5, 24).with_mass("tip", 2.0, 1.0 * 1.5 * 2.0, j * 1.5 * 8.0));
        let got = lambdas(&beam.modes().unwrap().omegas_rad_s, 2.0, 3.0, 1.5, 3);
        validated_rel_all(
            &BEAM,
            &format!("clamped–free with tip mass μ = 1 and rotary inertia j = {j}: λ₁…λ₃ at 24 elements"),
            &exact,
            "roots of the characteristic equation with tip mass and rotary inertia",
            &got,
            "",
            1e-3,
        );
        for (g, e) in got.iter().zip(exact) {
            assert!(rel(*g, e) < 1e-3, "j = {j}: lambda {g} vs exact {e}");
        }
    }
}

#[test]
fn free_hub_without_inertia_is_the_pinned_free_beam() {
    for (mu, exact) in [(0.0, [3.92660, 7.06858, 10.21018]), (1.0, [3.27329, 6.35599, 9.47486])] {
        let beam = model(uniform(1.0, 1.0, 1.0, 30).with_mass("tip", 1.0, mu, 0.0));
        let got = lambdas(&beam.modes_free_hub(0.0).unwrap().omegas_rad_s, 1.0, 1.0, 1.0, 3);
        validated_rel_all(
            &BEAM,
            &format!("free hub without inertia, tip mass μ = {mu}: λ₁…λ₃ at 30 elements"),
            &exact,
            "pinned–free beam's characteristic equation",
            &got,
            "",
            1e-3,
        );
        for (g, e) in got.iter().zip(exact) {
            assert!(rel(*g, e) < 1e-3, "mu = {mu}: lambda {g} vs exact pinned-free {e}");
        }
    }
    // A hub of inertia J_h = γ ρAL³: the root of the hub-inertia characteristic equation.
    for gamma in [0.1, 0.5, 2.0] {
        let beam = model(uniform(1.0, 1.0, 1.0, 30));
        let got = lambdas(&beam.modes_free_hub(gamma).unwrap().omegas_rad_s, 1.0, 1.0, 1.0, 1)[0];
        let exact = common::hub_inertia_lambda(gamma);
        validated_rel(
            &BEAM,
            &format!("free hub of inertia γρAL³, γ = {gamma}: λ₁ at 30 elements"),
            exact,
            "root of the hub-inertia characteristic equation",
            got,
            "",
            1e-4,
        );
        assert!(rel(got, exact) < 1e-4, "gamma {gamma}: {got} vs {exact}");
    }
    // A huge hub inertia clamps the arm again.
    let beam = model(uniform(1.0, 1.0, 1.0, 20));
    let got = lambdas(&beam.modes_free_hub(1e9).unwrap().omegas_rad_s, 1.0, 1.0, 1.0, 1);
    validated_rel(&BEAM, "free hub of huge inertia (1e9): λ₁", 1.87510, "the clamped–free root", got[0], "", 1e-4);
    assert!(rel(got[0], 1.87510) < 1e-4);
}

#[test]
fn frequency_error_converges_at_fourth_order() {
    // Third clamped-free mode: consistent Hermite elements converge as h^4 in frequency.
    let exact = 7.85476_f64.powi(2);
    let err = |n: usize| {
        let w = model(uniform(1.0, 1.0, 1.0, n)).modes().unwrap().omegas_rad_s[2];
        rel(w, exact)
    };
    let counts = [4, 8, 16];
    let errors: Vec<f64> = counts.iter().map(|&n| err(n)).collect();
    println!("elements vs relative error of omega_3: {:?}", counts.iter().zip(&errors).collect::<Vec<_>>());
    let slopes: Vec<f64> = errors.windows(2).map(|pair| (pair[0] / pair[1]).log2()).collect();
    common::validated_row(
        &BEAM,
        "convergence of ω₃ (clamped–free) at 4, 8, 16 elements: slope of log₂ error",
        "4 (consistent Hermite elements converge as h⁴ in frequency)",
        &format!(
            "errors {}; slopes {}",
            errors.iter().map(|e| common::sig(*e, 2)).collect::<Vec<_>>().join(", "),
            slopes.iter().map(|s| common::sig(*s, 3)).collect::<Vec<_>>().join(", ")
        ),
        &format!("{} from 4", common::sig(slopes.iter().map(|s| (s - 4.0).abs()).fold(0.0, f64::max), 2)),
        "slope in 3.5 ..= 4.5",
    );
    for pair in errors.windows(2) {
        let slope = (pair[0] / pair[1]).log2();
        assert!((3.5..=4.5).contains(&slope), "convergence slope {slope}, errors {errors:?}");
    }
}

#[test]
fn modes_are_mass_orthogonal() {
    let beam = model(
        uniform(8.0, 2.1e7, 60.0, 40)
            .with_mass("hand", 6.5, 150.0, 8.0)
            .with_mass("gripper", 7.5, 90.0, 4.0)
            .with_mass("string", 8.0, 121.0, 0.0),
    );
    let modes = beam.modes().unwrap();
    let phi = &modes.shapes;
    let mm = phi.transpose() * &beam.mass * phi;
    let kk = phi.transpose() * &beam.stiffness * phi;
    let n = modes.len();
    // Stiffness roundoff scales with the stiffest (axial) mode.
    let k_scale = modes.omegas_rad_s[n - 1].powi(2);
    let worst_m = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| (mm[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs());
    let worst_m = worst_m.fold(0.0, f64::max);
    let worst_k = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| (kk[(i, j)] - if i == j { modes.omegas_rad_s[i].powi(2) } else { 0.0 }).abs() / k_scale)
        .fold(0.0, f64::max);
    common::validated_row(
        &BEAM,
        &format!("{n} modes of an 8 m arm with three carried masses: ΦᵀMΦ and ΦᵀKΦ"),
        "I and diag(ω²) (modes are mass- and stiffness-orthogonal)",
        &format!("largest departure {} (M), {} of ω²_max (K)", common::sig(worst_m, 2), common::sig(worst_k, 2)),
        &common::sig(worst_m.max(worst_k), 2),
        "< 1e-10",
    );
    for i in 0..n {
        assert!((mm[(i, i)] - 1.0).abs() < 1e-10);
        assert!((kk[(i, i)] - modes.omegas_rad_s[i].powi(2)).abs() < 1e-10 * k_scale);
        for j in 0..i {
            assert!(mm[(i, j)].abs() < 1e-10, "M-orthogonality {i},{j}: {}", mm[(i, j)]);
            assert!(kk[(i, j)].abs() < 1e-10 * k_scale, "K-orthogonality {i},{j}");
        }
    }
}

#[test]
fn static_tip_deflection_under_gravity_and_tip_load() {
    // Steel tube, 9 m, with a 300 kg tip mass: w = qL^4/(8EI) + PL^3/(3EI).
    let (l, ei, rho_a, tip) = (9.0, 2.06e11 * 8.0e-5, 7850.0 * 1.2e-2, 300.0);
    let g = 9.80665;
    let beam = model(uniform(l, ei, rho_a, 20).with_mass("tip", l, tip, 0.0));
    let exact = rho_a * g * l.powi(4) / (8.0 * ei) + tip * g * l.powi(3) / (3.0 * ei);
    let got = beam.gravity_tip_deflection_m(g).unwrap();
    validated_rel(
        &BEAM,
        "static tip deflection of a 9 m steel tube with a 300 kg tip mass under gravity",
        exact,
        "qL⁴/8EI + PL³/3EI",
        got,
        "m",
        1e-9,
    );
    assert!(rel(got, exact) < 5e-3, "{got} vs {exact}");
    // Hermite elements are nodally exact for these loads: far tighter than the 0.5 % asked.
    assert!(rel(got, exact) < 1e-9, "{got} vs {exact}");
}

#[test]
fn piecewise_sections_match_a_two_segment_cantilever() {
    // Tip load P on a cantilever of EI1 over [0, a] and EI2 over [a, L]:
    // w = P[(L^3 - (L-a)^3)/3 - ... ] from the unit-load method:
    // w = P/EI1 ∫_0^a (L-x)^2 dx + P/EI2 ∫_a^L (L-x)^2 dx.
    use pipearm::beam::{BeamModel, BeamSpec, Segment};
    let seg = |length_m, ei| Segment {
        length_m,
        axial_rigidity_n: 1e9,
        bending_rigidity_n_m2: ei,
        mass_per_length_kg_m: 10.0,
    };
    let (a, l, ei1, ei2, p) = (3.0, 5.0, 4e6, 1e6, 1000.0);
    let beam = BeamModel::new(BeamSpec {
        segments: vec![seg(a, ei1), seg(l - a, ei2)],
        masses: vec![],
        elements: 10,
        member: None,
    })
    .unwrap();
    let [_, v, _] = beam.point_rows(l);
    let d = beam.static_displacement(&(p * &v)).unwrap();
    let exact = p / ei1 * (l.powi(3) - (l - a).powi(3)) / 3.0 + p / ei2 * (l - a).powi(3) / 3.0;
    validated_rel(
        &BEAM,
        "tip deflection of a two-segment cantilever (EI 4e6 over 3 m, 1e6 over 2 m), 1 kN at the tip",
        exact,
        "unit-load method",
        v.dot(&d),
        "m",
        1e-9,
    );
    assert!(rel(v.dot(&d), exact) < 1e-9);
}
