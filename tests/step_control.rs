//! Error-controlled free-motion steps (`[time] free_step_s`, `tolerance_m`): the steps stay
//! within their bounds and end on the drive's breakpoints, and the error follows the tolerance
//! against a fine fixed-step run of the same model (an independent solution of the same
//! equations). Where the control does not pay — the default scene's impact peak — is measured in
//! docs/performance.md, not asserted here.

mod common;

use std::path::Path;

use pipearm::arm::Fidelity;
use pipearm::bench::{rms_error_over_peak, tip_history};
use pipearm::integrate::IntegratorKind;
use pipearm::run::{RunSummary, Series, run};
use pipearm::scenario::Scenario;

/// The default lift with generalized-α, without its pad (free motion only) and a short settle.
fn free_lift(step_s: f64, free: Option<(f64, f64)>) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let mut spec = Scenario::load(&path).unwrap().spec;
    spec.dampeners.clear();
    spec.integrator = IntegratorKind::GeneralizedAlpha { rho_inf: 0.8 };
    spec.time.settle_s = 1.0;
    spec.time.step_s = step_s;
    spec.time.free_step_s = free.map(|f| f.0);
    spec.time.tolerance_m = free.map(|f| f.1);
    Scenario::from_spec(&path, spec).unwrap()
}

fn run_modal3(s: &Scenario) -> (RunSummary, Series) {
    run(&s.model, Some(Fidelity::Modal { modes: 3 })).unwrap()
}

#[test]
fn controlled_steps_stay_within_their_bounds_and_end_on_the_drives_breakpoints() {
    let (h, free) = (2e-3, 16e-3);
    let (summary, series) = run_modal3(&free_lift(h, Some((free, 1e-6))));
    let fixed_steps = (16.0 / h).round() as usize;
    println!("{} controlled steps against {fixed_steps} fixed", summary.steps);
    assert!(summary.steps < fixed_steps / 2, "{} steps", summary.steps);
    // The trapezoid's pieces change at 3, 12 and 15 s: a step ends on each.
    for breakpoint in [3.0, 12.0, 15.0] {
        assert!(series.t_s.iter().any(|t| (t - breakpoint).abs() < 1e-9), "no step ends at {breakpoint} s");
    }
    for pair in series.t_s.windows(2) {
        let dt = pair[1] - pair[0];
        assert!(dt <= free * (1.0 + 1e-9), "a step of {dt} s beyond {free}");
        // Shorter than step_s only where cut to land on a breakpoint or the end.
        let lands = [3.0, 12.0, 15.0, 16.0].iter().any(|b| (pair[1] - b).abs() < 1e-9);
        assert!(dt >= h * (1.0 - 1e-9) || lands, "a step of {dt} s at {} s", pair[1]);
    }
}

#[test]
fn a_tighter_tolerance_takes_more_steps_and_comes_closer_to_a_fine_fixed_step_run() {
    let (_, fine) = run_modal3(&free_lift(2.5e-4, None));
    let reference = tip_history(&fine);
    let mut previous: Option<(usize, f64)> = None;
    for tolerance in [1e-5, 1e-7, 1e-9] {
        let (summary, series) = run_modal3(&free_lift(1e-3, Some((16e-3, tolerance))));
        let error = rms_error_over_peak(&tip_history(&series), &reference);
        println!("tolerance {tolerance:.0e} m: {} steps, tip history error {error:.2e}", summary.steps);
        if let Some((steps, previous_error)) = previous {
            assert!(summary.steps > steps, "{tolerance}: {} steps", summary.steps);
            assert!(error < previous_error, "{tolerance}: {error} vs {previous_error}");
        }
        previous = Some((summary.steps, error));
    }
    let (steps, error) = previous.unwrap();
    common::validated_row(
        &common::TIME_STEP,
        "default lift without its pad, modal(3), error-controlled steps at tolerance 1e-9 m: tip-deflection history",
        "a fixed-step run at 0.25 ms",
        &format!("{steps} steps, RMS error {} of the peak", common::relative(error)),
        &common::relative(error),
        "< 0.1 % of the peak; each tighter tolerance closer",
    );
    // At the tightest, within 0.1 % of the tip deflection's peak.
    assert!(previous.unwrap().1 < 1e-3);
}
