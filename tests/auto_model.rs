//! `model = "auto"`: on every shipped scenario the chosen fidelity is within 2 % of fe on peak
//! contact force and peak tip deflection, and no cheaper fidelity is.

mod common;

use std::path::{Path, PathBuf};

use pipearm::arm::Fidelity;
use pipearm::run::{RunSummary, run};
use pipearm::scenario::Scenario;
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
fn auto_is_within_two_percent_of_fe_and_nothing_cheaper_within_one() {
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
        common::validated_row(
            &common::MODEL_CHOICE,
            &format!("{name}: the arm at `auto`'s {chosen}, peak contact force and peak tip deflection"),
            "the fe arm, same scene",
            &format!("{} N, {} m", common::sig(peak_force(&auto), 5), common::sig(auto.max_tip_deflection_m, 4)),
            &common::relative(off(&auto, &fe)),
            "≤ 2 %",
        );
        assert!(off(&auto, &fe) <= 0.02, "{name}: {chosen} is {} from fe", off(&auto, &fe));
        let cheaper: Vec<Fidelity> = match chosen {
            Fidelity::Rigid => vec![],
            Fidelity::Modal { modes } => {
                std::iter::once(Fidelity::Rigid).chain((1..modes).map(|m| Fidelity::Modal { modes: m })).collect()
            }
            Fidelity::Fe => panic!("auto never picks fe"),
        };
        let mut cheaper_off = Vec::new();
        for fidelity in cheaper {
            // A cheaper model whose run diverges (the friction clamp on one mode) is not within
            // 2 % either.
            match run(&s, Some(fidelity)) {
                Ok((summary, _)) => {
                    println!("  {fidelity}: {:.3} % from fe", 100.0 * off(&summary, &fe));
                    cheaper_off.push(format!("{fidelity} {}", common::relative(off(&summary, &fe))));
                    // auto reads the modes a scene needs off its band, a sufficient rule: a cheaper
                    // model may come within 2 % (the lab's one mode: 1.6 %), not within 1 %.
                    assert!(off(&summary, &fe) > 0.01, "{name}: the cheaper {fidelity} is within 1 %");
                }
                Err(SceneError::Diverged { t_s, what, .. }) => {
                    println!("  {fidelity}: diverged at {t_s} s: {what}");
                    cheaper_off.push(format!("{fidelity} diverges"));
                }
                Err(e) => panic!("{name}: {fidelity}: {e}"),
            }
        }
        if !cheaper_off.is_empty() {
            common::validated(
                &common::MODEL_CHOICE,
                &format!("{name}: each cheaper arm than `auto`'s {chosen}, peak contact force and peak tip deflection"),
                "the fe arm, same scene: `auto` picks nothing cheaper than needed",
                &cheaper_off.join(", "),
                "each > 1 % off",
            );
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
    s.drive.motion = common::lift_to_vertical(5.0).motion().unwrap();
    let (fast, _) = run(&s, None).unwrap();
    assert!(
        !fast.motion_advice.within && (fast.motion_advice.peak_accel_deg_s2 - 22.5).abs() < 1e-9,
        "{:?}",
        fast.motion_advice
    );
}

/// The string's `auto` agrees with the converged answer: where it keeps the string rigid, the
/// rigid string is within 1 % of the fe string on peak force and peak tip deflection (without a
/// pad: on peak tip deflection and the residual vibration's amplitude); where it keeps modes, the
/// rigid string is off by more than 1 % and auto's modes are within 2 %.
#[test]
fn the_strings_auto_is_rigid_exactly_where_a_rigid_string_is_within_one_percent() {
    let default = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap().model;
    // Without its pad, carrying a 6 m pup joint of casing between its hands: overhangs of 1.5 m
    // whose first mode (48 Hz) is ten times the arm's.
    let mut pup = default.clone();
    pup.dampeners.clear();
    let held = pup.payload.string_mut().unwrap();
    held.pipe = pipearm::robot::PipeString::from_spec(&pipearm::robot::StringSpec {
        length_m: Some(6.0),
        ..pipearm::robot::StringSpec::of_size("4-1/2")
    })
    .unwrap();
    for grip in &mut held.grips {
        grip.at_m = grip.station_m - 4.5;
    }
    // The default without its pad: the trapezoid's acceleration jumps ring the arm, and the
    // string's 3 Hz mode beside the arm's 4.7 Hz rings with it.
    let mut no_pad = default.clone();
    no_pad.dampeners.clear();
    let mut scenes = vec![("pup joint, no pad", pup), ("default, no pad", no_pad)];
    for path in shipped() {
        let model = Scenario::load(&path).unwrap().model;
        if model.payload.string().is_some_and(|h| h.model.is_none()) {
            scenes.push((Box::leak(model.name.clone().into_boxed_str()), model));
        }
    }
    for (name, mut s) in scenes {
        if s.integrator.stability_limit_omega_dt().is_some() {
            s.integrator = pipearm::integrate::IntegratorKind::default();
        }
        let arm = pipearm::select::fidelity(&s).unwrap().fidelity;
        let auto = s.string_fidelity().unwrap();
        let with_string = |fidelity: Fidelity| {
            let mut m = s.clone();
            m.payload.string_mut().unwrap().model = Some(fidelity);
            run(&m, Some(arm)).unwrap().0
        };
        let (fe, rigid, chosen) = (with_string(Fidelity::Fe), with_string(Fidelity::Rigid), with_string(auto.fidelity));
        // A scene with a pad is judged on its peak force (and peak deflection); one without, on
        // what a string mode changes there: the residual vibration's amplitude.
        let off = |a: &RunSummary, r: &RunSummary| {
            let residual = (a.residual.amplitude_m - r.residual.amplitude_m).abs() / r.residual.amplitude_m.abs();
            if peak_force(r) > 0.0 { off(a, r) } else { off(a, r).max(residual) }
        };
        let rigid_off = off(&rigid, &fe);
        println!(
            "{name}: string auto = {} ({}); rigid {:.3} % from fe, auto {:.3} %",
            auto.fidelity,
            auto.reason,
            100.0 * rigid_off,
            100.0 * off(&chosen, &fe)
        );
        common::validated_row(
            &common::MODEL_CHOICE,
            &format!("{name}: the string rigid (`auto` keeps {})", auto.fidelity),
            "the fe string, same scene (peak force and deflection; without a pad, also the residual amplitude)",
            &format!("{} from fe", common::relative(rigid_off)),
            &common::relative(rigid_off),
            if auto.fidelity == Fidelity::Rigid { "≤ 1 % (auto keeps it rigid)" } else { "> 1 % (auto keeps modes)" },
        );
        if auto.fidelity != Fidelity::Rigid {
            common::validated_row(
                &common::MODEL_CHOICE,
                &format!("{name}: the string at `auto`'s {}", auto.fidelity),
                "the fe string, same scene",
                &format!("{} from fe", common::relative(off(&chosen, &fe))),
                &common::relative(off(&chosen, &fe)),
                "≤ 2 %",
            );
        }
        if auto.fidelity == Fidelity::Rigid {
            assert!(rigid_off <= 0.01, "{name}: auto keeps the string rigid, {rigid_off} from fe");
        } else {
            assert!(
                rigid_off > 0.01,
                "{name}: a rigid string is within 1 % ({rigid_off}) yet auto keeps {}",
                auto.fidelity
            );
            assert!(off(&chosen, &fe) <= 0.02, "{name}: {} is {} from the fe string", auto.fidelity, off(&chosen, &fe));
        }
    }
}
