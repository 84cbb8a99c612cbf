//! The seed paper's trends (§3.1–3.4, §5), asserted from the measured quantities of the
//! scenario families under scenarios/seed/ — each where physics supports it (docs/seed-experiments.md).

mod common;

use std::path::Path;

use pipearm::seed::{Variant, run_family, sections};

fn family(section: &str) -> Vec<Variant> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/seed");
    let (_, files) = sections(&root).unwrap().into_iter().find(|(s, _)| s == section).unwrap();
    run_family(&files, false).unwrap()
}

fn get<'a>(variants: &'a [Variant], name: &str) -> &'a Variant {
    variants.iter().find(|v| v.name == name).unwrap()
}

fn residual(v: &Variant) -> f64 {
    v.summary.residual.amplitude_m
}

fn frequency(v: &Variant) -> f64 {
    v.summary.residual.frequency_hz
}

/// A row of the seed's trends: each variant's residual amplitude and frequency.
fn trend(check: &str, truth: &str, variants: &[&Variant], tolerance: &str) {
    let measured: Vec<String> = variants
        .iter()
        .map(|v| format!("{} {} mm at {} Hz", v.name, common::sig(1e3 * residual(v), 3), common::sig(frequency(v), 4)))
        .collect();
    common::validated(&common::SEED, check, truth, &measured.join("; "), tolerance);
}

fn same(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs()
}

#[test]
fn drive_type_orders_the_residual_vibration_and_leaves_its_frequency() {
    let f = family("3.1.1-drive");
    let (u, t, s) = (get(&f, "uniform"), get(&f, "trapezoidal"), get(&f, "s-curve"));
    trend(
        "§3.1.1 drive type: residual vibration",
        "uniform > trapezoidal > s-curve, at one frequency",
        &[u, t, s],
        "the order; frequencies within 1 %",
    );
    assert!(residual(u) > residual(t) && residual(t) > residual(s));
    assert!(same(frequency(u), frequency(s), 0.01) && same(frequency(t), frequency(s), 0.01));
}

#[test]
fn a_faster_lift_leaves_more_vibration_at_the_same_frequency() {
    let f = family("3.1.2-speed");
    let (fast, mid, slow) = (get(&f, "5s"), get(&f, "10s"), get(&f, "15s"));
    trend(
        "§3.1.2 lift time: residual vibration",
        "5 s > 10 s > 15 s, at one frequency and one log decrement",
        &[fast, mid, slow],
        "the order; frequencies within 1 %, decrements within 5 %",
    );
    assert!(residual(fast) > residual(mid) && residual(mid) > residual(slow));
    assert!(same(frequency(fast), frequency(slow), 0.01));
    // "Longer decay": with linear damping the decrement is the same, so a larger amplitude
    // takes longer to fall below a fixed level — by ln(A_fast/A_slow)/(ζω).
    assert!(same(fast.summary.residual.log_decrement, slow.summary.residual.log_decrement, 0.05));
}

#[test]
fn a_larger_second_moment_means_less_vibration_at_a_higher_frequency() {
    let f = family("3.2.1-section");
    let arms = [get(&f, "arm1-circle"), get(&f, "arm2-rectangle"), get(&f, "arm3-hollow-rectangle")];
    trend(
        "§3.2.1 section: residual vibration",
        "a larger second moment: less vibration (and deflection) at a higher frequency",
        &arms,
        "the order",
    );
    for pair in arms.windows(2) {
        assert!(residual(pair[0]) > residual(pair[1]) && frequency(pair[0]) < frequency(pair[1]));
        assert!(pair[0].summary.max_tip_deflection_m > pair[1].summary.max_tip_deflection_m);
    }
}

#[test]
fn a_heavier_end_mass_means_more_vibration_lower_frequency_longer_decay() {
    let f = family("3.2.2-load");
    let blocks = [get(&f, "block1-100g"), get(&f, "block2-206g"), get(&f, "block3-412g")];
    trend(
        "§3.2.2 end mass: residual vibration",
        "a heavier end mass: more vibration, lower frequency, longer settling",
        &blocks,
        "the order",
    );
    for pair in blocks.windows(2) {
        assert!(residual(pair[1]) > residual(pair[0]) && frequency(pair[1]) < frequency(pair[0]));
        assert!(pair[1].summary.residual.settling_time_s > pair[0].summary.residual.settling_time_s);
    }
}

#[test]
fn a_clamped_string_acts_as_a_heavier_end_load() {
    let f = family("3.3.1-clamp");
    let (clamped, free) = (get(&f, "clamped-2-7-8"), get(&f, "unclamped"));
    trend(
        "§3.3.1 string clamped or not: residual vibration",
        "a clamped string acts as a heavier end load: more vibration, lower frequency",
        &[clamped, free],
        "the order",
    );
    assert!(residual(clamped) > residual(free) && frequency(clamped) < frequency(free));
}

#[test]
fn string_size_changes_deflection_and_torque_slightly_growing_with_size() {
    let f = family("3.3.2-size");
    let sizes = [get(&f, "2-3-8"), get(&f, "2-7-8"), get(&f, "4-1-2")];
    common::validated(
        &common::SEED,
        "§3.3.2 string size: peak tip deflection and drive torque",
        "growing slightly with the string's size",
        &sizes
            .iter()
            .map(|v| {
                format!(
                    "{} {} mm, {} kN·m",
                    v.name,
                    common::sig(1e3 * v.summary.max_tip_deflection_m, 3),
                    common::sig(1e-3 * v.summary.peak_drive_torque_n_m, 4)
                )
            })
            .collect::<Vec<_>>()
            .join("; "),
        "growing, within 15 % step to step",
    );
    for pair in sizes.windows(2) {
        let (a, b) = (&pair[0].summary, &pair[1].summary);
        assert!(b.max_tip_deflection_m > a.max_tip_deflection_m && b.peak_drive_torque_n_m > a.peak_drive_torque_n_m);
        // "Slightly": within 15 % step to step.
        assert!(
            same(b.max_tip_deflection_m, a.max_tip_deflection_m, 0.15)
                && same(b.peak_drive_torque_n_m, a.peak_drive_torque_n_m, 0.15)
        );
    }
}

#[test]
fn a_heavier_string_does_not_raise_the_contact_force() {
    let f = family("3.4-contact");
    let (light, heavy) = (get(&f, "2-7-8"), get(&f, "4-1-2"));
    // "Did not significantly increase": less than in proportion to the string's weight (200 kg
    // against 121 kg); the force per string weight falls (docs/seed-experiments.md).
    let per_weight = |v: &Variant| v.summary.pairs[0].peak_force_per_payload_weight;
    let (a, b) = (light.summary.pairs[0].peak_force_n, heavy.summary.pairs[0].peak_force_n);
    println!("peak force {a:.1} N -> {b:.1} N, per weight {:.3} -> {:.3}", per_weight(light), per_weight(heavy));
    common::validated(
        &common::SEED,
        "§3.4 contact: peak pad force, 2⅞ in against 4½ in string",
        "a heavier string does not raise the contact force significantly (less than in proportion to its weight)",
        &format!(
            "{} N → {} N; per string weight {} → {}",
            common::sig(a, 5),
            common::sig(b, 5),
            common::sig(per_weight(light), 3),
            common::sig(per_weight(heavy), 3)
        ),
        "the force per weight falls",
    );
    assert!(per_weight(heavy) < per_weight(light), "{} vs {}", per_weight(heavy), per_weight(light));
}

#[test]
fn tip_vibration_stays_below_two_percent_of_the_arm_length() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/seed");
    let mut largest = (0.0_f64, String::new());
    let families = sections(&root).unwrap();
    let runs: Vec<(String, Vec<Variant>)> =
        families.into_iter().map(|(section, files)| (section, run_family(&files, false).unwrap())).collect();
    for (section, variants) in &runs {
        for v in variants {
            if v.summary.max_w_over_l > largest.0 {
                largest = (v.summary.max_w_over_l, format!("{section}/{}", v.name));
            }
        }
    }
    common::validated(
        &common::SEED,
        "§5 every variant of every family: largest tip vibration w/L",
        "below 2 % of the arm length",
        &format!("{} at most ({})", common::relative(largest.0), largest.1),
        "< 2 %",
    );
    for (section, variants) in runs {
        for v in variants {
            assert!(v.summary.max_w_over_l < 0.02, "{section}/{}: {}", v.name, v.summary.max_w_over_l);
        }
    }
}
