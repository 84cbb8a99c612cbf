//! Shared builders for the integration tests.
#![allow(dead_code)]

use pipearm::beam::{BeamModel, BeamSpec, Segment};
use pipearm::scenario::DriveSpec;

/// A uniform arm with EI, ρA, length; EA stiff enough that the first axial mode sits far above
/// the bending modes tested.
pub fn uniform(length_m: f64, ei: f64, rho_a: f64, elements: usize) -> BeamSpec {
    BeamSpec::uniform(
        Segment {
            length_m,
            axial_rigidity_n: 1e6 * ei / (length_m * length_m),
            bending_rigidity_n_m2: ei,
            mass_per_length_kg_m: rho_a,
        },
        elements,
    )
}

/// λ_i = L (ω_i² ρA / EI)^(1/4) of the first `n` modes of a model.
pub fn lambdas(omegas: &[f64], length_m: f64, ei: f64, rho_a: f64, n: usize) -> Vec<f64> {
    omegas[..n].iter().map(|w| length_m * (w * w * rho_a / ei).powf(0.25)).collect()
}

/// Builds the model, panicking with the error (tests only).
pub fn model(spec: BeamSpec) -> BeamModel {
    BeamModel::new(spec).expect("valid beam")
}

/// Relative error.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// First root λ of the hub-inertia characteristic equation (reference table):
/// (sin λ cosh λ − cos λ sinh λ) + γ λ³ (1 + cos λ cosh λ) = 0, γ = J_h/(ρAL³),
/// bracketed between the clamped-free (γ→∞) and pinned-free (γ→0) first roots.
pub fn hub_inertia_lambda(gamma: f64) -> f64 {
    let f = |l: f64| (l.sin() * l.cosh() - l.cos() * l.sinh()) + gamma * l.powi(3) * (1.0 + l.cos() * l.cosh());
    let (mut lo, mut hi) = (1.8751, 3.9266);
    assert!(f(lo) * f(hi) < 0.0, "root not bracketed for gamma {gamma}");
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(lo) * f(mid) <= 0.0 { hi = mid } else { lo = mid }
    }
    0.5 * (lo + hi)
}

/// The shipped lifts' drive, 0 → 90° trapezoidal with a 20 % ramp, over `duration_s`.
pub fn lift_to_vertical(duration_s: f64) -> DriveSpec {
    DriveSpec::Trapezoidal {
        start_deg: 0.0,
        end_deg: 90.0,
        duration_s,
        accel_deg_s2: None,
        ramp_fraction: Some(0.2),
        shaper: None,
        shaper_hz: None,
        shaper_damping_ratio: None,
    }
}

/// A section of docs/validation.md: the checks of one part of the model.
pub struct Area {
    /// Where the section stands on the page (ascending).
    pub order: u32,
    pub title: &'static str,
    /// One sentence on what the section's checks hold the model to.
    pub about: &'static str,
}

pub const BEAM: Area = Area {
    order: 10,
    title: "Beam: modes and statics",
    about: "The finite-element beam (cubic Hermite elements) against exact Euler–Bernoulli solutions: the roots of \
            the frequency equations and the classical static formulas.",
};
pub const ROTATING_BEAM: Area = Area {
    order: 20,
    title: "Rotating beam: centrifugal stiffening",
    about: "A beam on a spinning hub against the exact rotating-cantilever frequencies, and the spin-up that \
            fails without geometric stiffening.",
};
pub const STRING_BEAM: Area = Area {
    order: 30,
    title: "The held string as a beam",
    about: "The string clamped in its hands against closed forms, and the Craig–Bampton reduction of arm and \
            string against the unreduced finite-element model of both beams.",
};
pub const ARM_DYNAMICS: Area = Area {
    order: 40,
    title: "Arm dynamics",
    about: "The floating-frame arm against conservation laws, closed forms of the rigid arm, the hub-inertia \
            frequency equation, and the full finite-element arm as the finer model.",
};
pub const TILTING_HEAD: Area = Area {
    order: 45,
    title: "The tilting head",
    about: "A rigid head on a hinge on the arm, its angle one more coordinate: against the compound pendulum, a \
            finite-element model of the arm and head built in the test from the beam's own matrices, and the \
            energy its equations must keep.",
};
pub const PIN: Area = Area {
    order: 50,
    title: "The cylinder's pin: residual flexibility",
    about: "The static flexibility a modal arm leaves out at a cylinder's pin, against beam theory and against \
            the full finite-element arm.",
};
pub const INTEGRATORS: Area = Area {
    order: 60,
    title: "Integrators",
    about: "Stability limits, spectral radii and orders of accuracy against Hairer & Wanner (Solving Ordinary \
            Differential Equations I–II) and Chung & Hulbert (1993), on one oscillator and on the arm's highest \
            mode.",
};
pub const CONTACT_LAWS: Area = Area {
    order: 70,
    title: "Contact laws",
    about: "A rigid mass dropped on a pad with each force law (RK4 at 1 µs), against the closed forms of Hertz \
            and the linear spring, the energy balance, and the restitution each law's derivation promises.",
};
pub const CONTACT_SCENE: Area = Area {
    order: 80,
    title: "Contact in the scene",
    about: "Contact through the scene (pads, rapier's collision pipeline, structures, the `rapier` method) \
            against closed forms of impacts and statics, and against the converged compliant contact.",
};
pub const FRICTION_CLAMP: Area = Area {
    order: 90,
    title: "The friction clamp",
    about: "A string held by friction in the jaws against Coulomb's law, the kinematics of its slide and the \
            statics of its landing, and against the rigid clamp where it holds.",
};
pub const ACTUATORS: Area = Area {
    order: 100,
    title: "Servo and hydraulic drives",
    about: "The actuators against closed forms: the oil spring, the drive train's spring, a PD loop's step \
            response, the valve's orifice law, the relief valve's cap, the work done, the seated arm's balance.",
};
pub const DRIVES: Area = Area {
    order: 110,
    title: "Drive profiles: shapers and tables",
    about: "Input shapers against the textbook residual-vibration curves (Singer & Seering 1990) and the arm's \
            own residual; drives from a table against the laws they sample.",
};
pub const SENSORS: Area = Area {
    order: 120,
    title: "Sensors",
    about: "Accelerometers, strain gauges and the encoder against closed forms and against the moment balance \
            of the whole arm about its pivot.",
};
pub const MODEL_CHOICE: Area = Area {
    order: 130,
    title: "The model chosen by `auto`",
    about: "The fidelity and contact path `auto` picks on each shipped scene, against the finer model it stands \
            in for.",
};
pub const TIME_STEP: Area = Area {
    order: 140,
    title: "Time step and step control",
    about: "Runs at the scenes' steps against the same runs at finer steps (the finer model of the same \
            equations).",
};
pub const FIT: Area = Area {
    order: 150,
    title: "Fitting and comparing with measurements",
    about: "Parameters, shifts and statistics recovered from data whose truth is known: measurements made by a \
            finer model, a run's own channels shifted in time, the runs' own peaks.",
};
pub const SEED: Area = Area {
    order: 160,
    title: "The seed paper's trends",
    about: "The trends the seed paper reports for its lab and full-scale arms (§3.1–3.4, §5), on the shipped \
            families under `scenarios/seed/`.",
};

/// Prints one row of docs/validation.md for `scripts/validation.sh` to gather: a check of
/// `area`, the truth it is held to (value and source), what the test measured, the error and
/// the tolerance the test asserts. The test is named from its thread (libtest names each test's
/// thread after it). Call it with the values the test computed, before its assertions.
pub fn validated_row(area: &Area, check: &str, truth: &str, measured: &str, error: &str, tolerance: &str) {
    let krate = module_path!().split("::").next().unwrap_or("?");
    let thread = std::thread::current();
    let test = thread.name().filter(|n| *n != "main").unwrap_or("?");
    // A `|` inside a field would split it: written as its HTML entity, which Markdown shows as `|`.
    let cells: Vec<String> = [area.title, area.about, check, truth, measured, error, tolerance]
        .iter()
        .map(|f| f.replace('|', "&#124;").replace('\n', " "))
        .collect();
    println!("validation|{:04}|{}|{krate}::{test}", area.order, cells.join("|"));
}

/// A check whose measured result is not a single number against a single truth (a bound held,
/// a run that diverges).
pub fn validated(area: &Area, check: &str, truth: &str, measured: &str, tolerance: &str) {
    validated_row(area, check, truth, measured, "—", tolerance);
}

/// `measured` against `truth` (from `source`), within a relative `tolerance`.
pub fn validated_rel(area: &Area, check: &str, truth: f64, source: &str, measured: f64, unit: &str, tolerance: f64) {
    validated_rel_all(area, check, &[truth], source, &[measured], unit, tolerance);
}

/// Several values against their truths, each within a relative `tolerance`: the largest error shown.
pub fn validated_rel_all(
    area: &Area,
    check: &str,
    truths: &[f64],
    source: &str,
    measured: &[f64],
    unit: &str,
    tolerance: f64,
) {
    let worst = truths.iter().zip(measured).map(|(t, m)| rel(*m, *t)).fold(0.0, f64::max);
    validated_row(
        area,
        check,
        &format!("{} ({source})", with_unit(&trimmed_list(truths), unit)),
        &with_unit(&list(measured), unit),
        &relative(worst),
        &format!("< {}", relative(tolerance)),
    );
}

/// `measured` against `truth` (from `source`), within an absolute `tolerance` (in `unit`).
pub fn validated_abs(area: &Area, check: &str, truth: f64, source: &str, measured: f64, unit: &str, tolerance: f64) {
    validated_row(
        area,
        check,
        &format!("{} ({source})", with_unit(&trimmed(&sig(truth, 6)), unit)),
        &with_unit(&sig(measured, 6), unit),
        &with_unit(&trimmed(&sig((measured - truth).abs(), 2)), unit),
        &format!("< {}", with_unit(&trimmed(&sig(tolerance, 2)), unit)),
    );
}

fn list(values: &[f64]) -> String {
    values.iter().map(|v| sig(*v, 6)).collect::<Vec<_>>().join(", ")
}

/// A truth's values: exact numbers without the zeros `sig` pads them with (`0.5`, not `0.500000`).
fn trimmed_list(values: &[f64]) -> String {
    values.iter().map(|v| trimmed(&sig(*v, 6))).collect::<Vec<_>>().join(", ")
}

fn with_unit(value: &str, unit: &str) -> String {
    if unit.is_empty() { value.to_string() } else { format!("{value} {unit}") }
}

/// A relative error or tolerance: in per cent from 1e-3 up, as a fraction below.
pub fn relative(x: f64) -> String {
    if x.abs() >= 1e-3 { format!("{} %", trimmed(&sig(100.0 * x, 2))) } else { trimmed(&sig(x, 2)) }
}

/// A number's text without the trailing zeros of its fraction (`0.10` → `0.1`, `1.0e-9` → `1e-9`).
pub fn trimmed(text: &str) -> String {
    let (mantissa, exponent) = text.split_once('e').map_or((text, None), |(m, e)| (m, Some(e)));
    let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
    exponent.map_or(mantissa.to_string(), |e| format!("{mantissa}e{e}"))
}

/// `x` to `digits` significant digits: fixed notation from 1e-3 to 1e6, scientific outside.
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let exponent = x.abs().log10().floor() as i32;
    if (-3..6).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.*e}", digits.saturating_sub(1))
    }
}
