//! `model = "auto"`: on every shipped scenario the chosen fidelity is within 2 % of fe on peak
//! contact force and peak tip deflection, and no cheaper fidelity is.

use std::path::{Path, PathBuf};

use pipearm::arm::Fidelity;
use pipearm::run::{RunSummary, run};
use pipearm::scenario::{DriveSpec, Scenario};
use pipearm::scene::SceneError;

fn shipped() -> Vec<PathBuf> {
    pipearm::scenario::scenario_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios")).unwrap()
}

fn peak_force(s: &RunSummary) -> f64 {
    s.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max)
}

/// Largest relative difference of peak force and peak tip deflection.
fn off(a: &RunSummary, reference: &RunSummary) -> f64 {
    let rel = |x: f64, r: f64| (x - r).abs() / r.abs().max(1e-12);
    rel(peak_force(a), peak_force(reference)).max(rel(a.max_tip_deflection_m, reference.max_tip_deflection_m))
}

#[test]
fn auto_is_within_two_percent_of_fe_and_nothing_cheaper_is() {
    for path in shipped() {
        let mut s = Scenario::load(&path).unwrap().model;
        // The models are compared under one unconditionally stable integrator: the FE arm's
        // highest mode is far beyond an explicit method's limit at the scene's step (the default
        // scene's RK4 is chosen for its three modes).
        if s.integrator.stability_limit_omega_dt().is_some() {
            s.integrator = pipearm::integrate::IntegratorKind::default();
        }
        let chosen = pipearm::select::fidelity(&s).unwrap().fidelity;
        let (fe, _) = run(&s, Some(Fidelity::Fe)).unwrap();
        let (auto, _) = run(&s, Some(chosen)).unwrap();
        let name = &s.name;
        println!("{name}: auto = {chosen}, {:.3} % from fe", 100.0 * off(&auto, &fe));
        assert!(off(&auto, &fe) <= 0.02, "{name}: {chosen} is {} from fe", off(&auto, &fe));
        let cheaper: Vec<Fidelity> = match chosen {
            Fidelity::Rigid => vec![],
            Fidelity::Modal { modes } => {
                std::iter::once(Fidelity::Rigid).chain((1..modes).map(|m| Fidelity::Modal { modes: m })).collect()
            }
            Fidelity::Fe => panic!("auto never picks fe"),
        };
        for fidelity in cheaper {
            // A cheaper model whose run diverges (the friction clamp on one mode) is not within
            // 2 % either.
            match run(&s, Some(fidelity)) {
                Ok((summary, _)) => {
                    println!("  {fidelity}: {:.3} % from fe", 100.0 * off(&summary, &fe));
                    assert!(off(&summary, &fe) > 0.02, "{name}: the cheaper {fidelity} is within 2 % too");
                }
                Err(SceneError::Diverged { t_s, what, .. }) => println!("  {fidelity}: diverged at {t_s} s: {what}"),
                Err(e) => panic!("{name}: {fidelity}: {e}"),
            }
        }
    }
}

#[test]
fn motion_advice_flags_drives_beyond_the_seed_limits() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let mut s = Scenario::load(&path).unwrap().model;
    let (within, _) = run(&s, None).unwrap();
    assert!(within.motion_advice.within, "{:?}", within.motion_advice);
    // 0 → 90° in 5 s with a 20 % ramp: 22.5 °/s², beyond the seed's 5 °/s² for this class.
    s.drive.motion = DriveSpec::Trapezoidal {
        start_deg: 0.0,
        end_deg: 90.0,
        duration_s: 5.0,
        accel_deg_s2: None,
        ramp_fraction: Some(0.2),
        shaper: None,
        shaper_hz: None,
    }
    .motion()
    .unwrap();
    let (fast, _) = run(&s, None).unwrap();
    assert!(
        !fast.motion_advice.within && (fast.motion_advice.peak_accel_deg_s2 - 22.5).abs() < 1e-9,
        "{:?}",
        fast.motion_advice
    );
}
