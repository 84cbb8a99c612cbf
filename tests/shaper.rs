//! Shaped drives against independent truths: an undamped single-mode oscillator driven by the
//! shaped profile, solved exactly segment by segment, against the textbook residual-vibration
//! curves of ZV and ZVD (Singer & Seering 1990); two coupled oscillators, solved exactly through
//! their closed-form modes, left still by a shaper tuned to both; and the shipped scenes without
//! their pads, where the automatically tuned ZVD shaper must cut the residual tip vibration of
//! every lift at least tenfold.

mod common;

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use pipearm::drive::{MotionProfile, Shaper, ShaperMode, TrapezoidLimit};
use pipearm::run::{RunSummary, run};
use pipearm::scenario::{DriveSpec, Scenario, ScenarioSpec};

/// Residual amplitude (rad) of `x'' + ω² x = ω² θ(t)`, started at rest at `θ(0)`, after `θ`
/// comes to rest at `T`. Exact: on each constant-jerk piece of θ the particular solution is
/// `θ − θ''/ω²` (θ'''' = 0) and the rest is a free oscillation, carried in closed form.
fn residual_amplitude(p: &MotionProfile, omega: f64) -> f64 {
    let mut bounds = vec![0.0];
    bounds.extend(p.breakpoints_s());
    let w2 = omega * omega;
    let (mut x, mut v) = (p.sample(0.0).angle_rad, 0.0);
    for pair in bounds.windows(2) {
        let (t0, tau) = (pair[0], pair[1] - pair[0]);
        let s = p.sample(t0); // right limit at the piece's start
        let (th, r, a, j) = (s.angle_rad, s.rate_rad_s, s.accel_rad_s2, s.jerk_rad_s3);
        let (e, de) = (x - (th - a / w2), v - (r - j / w2));
        let (sin, cos) = (omega * tau).sin_cos();
        let (e1, de1) = (e * cos + de / omega * sin, -e * omega * sin + de * cos);
        // θ and its derivatives at the piece's end, from its start (left limit there).
        let th1 = th + tau * (r + tau * (a / 2.0 + tau * j / 6.0));
        let r1 = r + tau * (a + tau * j / 2.0);
        let a1 = a + tau * j;
        x = th1 - a1 / w2 + e1;
        v = r1 - j / w2 + de1;
    }
    let end = p.sample(p.duration_s() + 1.0).angle_rad;
    (x - end).hypot(v / omega)
}

fn shaped(base: &MotionProfile, shaper: Shaper, f_hz: f64) -> MotionProfile {
    MotionProfile::shaped(base.clone(), shaper, f_hz, 0.0).unwrap()
}

/// A near-step (a 0.3 s ramp, whose own residual does not vanish for 0.5–1.5 Hz) and a
/// triangular trapezoid of 1.2 s, shaped for 1 Hz.
fn bases() -> [MotionProfile; 2] {
    [
        MotionProfile::uniform(0.0, 1.0, 0.3).unwrap(),
        MotionProfile::trapezoidal(0.0, 1.0, 1.2, TrapezoidLimit::RampFraction(0.5)).unwrap(),
    ]
}

#[test]
fn zv_and_zvd_cancel_the_design_mode() {
    let omega = 2.0 * PI;
    for base in bases() {
        let unshaped = residual_amplitude(&base, omega);
        assert!(unshaped > 1e-3, "the base leaves a residual to cancel: {unshaped}");
        for shaper in [Shaper::Zv, Shaper::Zvd] {
            let left = residual_amplitude(&shaped(&base, shaper, 1.0), omega);
            common::validated_row(
                &common::DRIVES,
                &format!(
                    "{} shaping a {} move for 1 Hz: residual of a 1 Hz undamped mode",
                    if shaper == Shaper::Zv { "ZV" } else { "ZVD" },
                    base.name()
                ),
                &format!(
                    "0: the design mode cancelled (Singer & Seering 1990); unshaped {} rad",
                    common::sig(unshaped, 3)
                ),
                &format!("{} rad", common::sig(left, 2)),
                &format!("{} of the unshaped", common::relative(left / unshaped)),
                "< 1e-6 of the unshaped",
            );
            assert!(left < 1e-6 * unshaped, "{shaper:?} on {}: {left} of {unshaped}", base.name());
        }
    }
}

/// Off design, the residual over the unshaped one's is |cos(πr/2)| for ZV and cos²(πr/2) for
/// ZVD, r = ω/ω_design; ZVD's curve is the flatter (smaller at ±20 %).
#[test]
fn off_design_residual_follows_the_textbook_curves() {
    for base in bases() {
        let rs = [0.5, 0.7, 0.8, 0.9, 1.1, 1.2, 1.3, 1.5];
        let ratios = |shaper: Shaper| -> Vec<f64> {
            rs.iter()
                .map(|r| {
                    let omega = 2.0 * PI * r;
                    residual_amplitude(&shaped(&base, shaper, 1.0), omega) / residual_amplitude(&base, omega)
                })
                .collect()
        };
        let cosine: Vec<f64> = rs.iter().map(|r| (0.5 * PI * r).cos().abs()).collect();
        let squared: Vec<f64> = cosine.iter().map(|c| c * c).collect();
        let case = |s: &str| format!("{s} for 1 Hz on a {} move: residual over unshaped at r = 0.5 … 1.5", base.name());
        common::validated_rel_all(
            &common::DRIVES,
            &case("ZV"),
            &cosine,
            "|cos(πr/2)|, Singer & Seering 1990",
            &ratios(Shaper::Zv),
            "",
            0.01,
        );
        common::validated_rel_all(
            &common::DRIVES,
            &case("ZVD"),
            &squared,
            "cos²(πr/2), Singer & Seering 1990",
            &ratios(Shaper::Zvd),
            "",
            0.01,
        );
        for r in rs {
            let omega = 2.0 * PI * r;
            let unshaped = residual_amplitude(&base, omega);
            let zv = residual_amplitude(&shaped(&base, Shaper::Zv, 1.0), omega) / unshaped;
            let zvd = residual_amplitude(&shaped(&base, Shaper::Zvd, 1.0), omega) / unshaped;
            let c = (0.5 * PI * r).cos().abs();
            assert!((zv - c).abs() <= 0.01 * c, "ZV at r = {r}: {zv} vs {c}");
            assert!((zvd - c * c).abs() <= 0.01 * c * c, "ZVD at r = {r}: {zvd} vs {}", c * c);
            if (r - 0.8_f64).abs() < 1e-9 || (r - 1.2_f64).abs() < 1e-9 {
                assert!(zvd < zv, "ZVD flatter than ZV at r = {r}: {zvd} vs {zv}");
            }
        }
    }
}

/// Two masses in a chain, `m₁` on a spring `k₁` from a base that follows θ(t), `m₂` on `k₂` from
/// `m₁`, undamped: the closed-form modes of the 2 × 2 problem `K φ = ω² M φ`, as (ω, the
/// participation of the mode in x₂ per unit base motion). With x = θ + r the relative motion
/// obeys `M r̈ + K r = −M 1 θ̈`; mode i's coordinate is a unit oscillator `η̈ + ω² η = ω² θ`
/// scaled by `Γᵢ = φᵢᵀ M 1 / φᵢᵀ M φᵢ`, shifted by −θ: x₂'s ringing in mode i is `Γᵢ φᵢ₂` times
/// that oscillator's about its rest.
fn chain_modes() -> [(f64, f64); 2] {
    let (m1, m2, k1, k2): (f64, f64, f64, f64) = (2.0, 1.0, 400.0, 150.0);
    // det(K − ω² M) = 0: m1 m2 ω⁴ − (m1 k2 + m2 (k1 + k2)) ω² + k1 k2 = 0.
    let (a, b, c) = (m1 * m2, -(m1 * k2 + m2 * (k1 + k2)), k1 * k2);
    let root = (b * b - 4.0 * a * c).sqrt();
    [(-b - root) / (2.0 * a), (-b + root) / (2.0 * a)].map(|w2: f64| {
        // (k1 + k2 − ω² m1) φ1 = k2 φ2, with φ2 = 1.
        let phi1 = k2 / (k1 + k2 - w2 * m1);
        let gamma = (m1 * phi1 + m2) / (m1 * phi1 * phi1 + m2);
        (w2.sqrt(), gamma)
    })
}

/// Residual amplitude bound of m₂ after `p`: the sum of its two modes' exact ones.
fn chain_residual(p: &MotionProfile) -> [f64; 2] {
    chain_modes().map(|(omega, participation)| participation.abs() * residual_amplitude(p, omega))
}

/// A shaper tuned to both closed-form frequencies leaves neither mode ringing; tuned to one, the
/// other rings as unshaped would (to within the base's shortening).
#[test]
fn a_shaper_tuned_to_both_modes_stills_two_coupled_oscillators() {
    let modes = chain_modes();
    let [f1, f2] = modes.map(|(omega, _)| omega / (2.0 * PI));
    assert!(f2 > 1.8 * f1, "two distinct modes: {f1} and {f2} Hz");
    let base = MotionProfile::trapezoidal(0.0, 1.0, 1.2, TrapezoidLimit::RampFraction(0.3)).unwrap();
    let unshaped = chain_residual(&base);
    assert!(unshaped.iter().all(|a| *a > 1e-4), "both modes ring unshaped: {unshaped:?}");
    for shaper in [Shaper::Zv, Shaper::Zvd] {
        let both = [f1, f2].map(|frequency_hz| ShaperMode { frequency_hz, damping_ratio: 0.0 });
        let shaped = MotionProfile::shaped_for(base.clone(), shaper, &both).unwrap();
        let left = chain_residual(&shaped);
        for (l, u) in left.iter().zip(unshaped) {
            assert!(*l < 1e-6 * u, "{shaper:?} on both: {left:?} of {unshaped:?}");
        }
        let first_only = MotionProfile::shaped(base.clone(), shaper, f1, 0.0).unwrap();
        let [first, second] = chain_residual(&first_only);
        assert!(first < 1e-6 * unshaped[0] && second > 0.1 * unshaped[1], "{shaper:?} on the first: {first}, {second}");
    }
}

/// The shipped scenes with a point-to-point drive, their pads removed (contact would clip the
/// vibration), their string as shipped; `shaper` set on the drive, tuned automatically.
fn without_pad(path: &Path, shaper: Option<Shaper>) -> Option<RunSummary> {
    let mut spec: ScenarioSpec = Scenario::load(path).unwrap().spec;
    spec.dampeners.clear();
    let (DriveSpec::Uniform { shaper: s, .. }
    | DriveSpec::Trapezoidal { shaper: s, .. }
    | DriveSpec::SCurve { shaper: s, .. }) = &mut spec.drive
    else {
        return None;
    };
    *s = shaper;
    let model = Scenario::from_spec(path, spec).unwrap().model;
    Some(run(&model, None).unwrap().0)
}

fn shipped() -> Vec<PathBuf> {
    pipearm::scenario::scenario_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios")).unwrap()
}

/// On every shipped scene with a point-to-point lift, without its pad, the automatically tuned
/// ZVD shaper leaves at most a tenth of the unshaped lift's residual tip amplitude at the same
/// lift time; EI (5 % left at each design frequency by design) at most a fifth.
#[test]
fn automatic_shaping_cuts_every_shipped_lifts_residual_tenfold() {
    for path in shipped() {
        let Some(plain) = without_pad(&path, None) else { continue };
        let a0 = plain.residual.amplitude_m;
        for (shaper, bound) in [(Shaper::Zvd, 0.1), (Shaper::Ei, 0.2)] {
            let shaped = without_pad(&path, Some(shaper)).unwrap();
            let a1 = shaped.residual.amplitude_m;
            println!(
                "{}: {} {a1:.3e} m of {a0:.3e} m unshaped ({:.3}), tuned to {:?} Hz, shares {:?}",
                plain.scenario,
                shaper.name(),
                a1 / a0,
                shaped.drive.shaper_hz.as_deref().unwrap_or_default(),
                shaped.drive.shaper_residual_share.as_deref().unwrap_or_default()
            );
            assert!(a1 <= bound * a0, "{}: {} leaves {a1} m of {a0} m", plain.scenario, shaper.name());
        }
    }
}

/// The default scene's spec with its string lumped and `shaper` on its drive (and its pad removed
/// if `pad` is false), run.
fn default_run(pad: bool, shaper: Option<Shaper>) -> RunSummary {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let mut spec: ScenarioSpec = Scenario::load(&path).unwrap().spec;
    if let pipearm::scenario::PayloadSpec::String { model, .. } = &mut spec.payload {
        *model = pipearm::scenario::ModelSpec::Rigid;
    }
    if !pad {
        spec.dampeners.clear();
    }
    let DriveSpec::Trapezoidal { shaper: s, .. } = &mut spec.drive else { panic!("default drive changed") };
    *s = shaper;
    let model = Scenario::from_spec(&path, spec).unwrap().model;
    assert_eq!(model.drive.motion.duration_s(), 15.0, "the lift keeps its time");
    run(&model, None).unwrap().0
}

/// With the string lumped the arm has one low mode: the tuning's largest share is it, at the
/// unshaped run's measured residual frequency.
#[test]
fn with_the_string_lumped_the_tuning_finds_the_arms_mode() {
    let plain = default_run(false, None);
    let zvd = default_run(false, Some(Shaper::Zvd));
    let (hz, shares) = (zvd.drive.shaper_hz.clone().unwrap(), zvd.drive.shaper_residual_share.clone().unwrap());
    let largest = (0..hz.len()).max_by(|&i, &j| shares[i].total_cmp(&shares[j])).unwrap();
    let measured = plain.residual.frequency_hz;
    let (a0, a1) = (plain.residual.amplitude_m, zvd.residual.amplitude_m);
    common::validated(
        &common::DRIVES,
        "default lift without its pad, string lumped: residual tip amplitude with ZVD on the tuned modes",
        &format!("at most a tenth of the unshaped trapezoid's {} m", common::sig(a0, 3)),
        &format!("{} m ({} of it)", common::sig(a1, 3), common::relative(a1 / a0)),
        "≤ 10 %",
    );
    common::validated_rel(
        &common::DRIVES,
        "the ZVD shaper's largest-share mode on the default arm",
        measured,
        "the unshaped run's measured residual frequency",
        hz[largest],
        "Hz",
        0.03,
    );
    assert!((hz[largest] - measured).abs() <= 0.03 * measured, "{hz:?} Hz (shares {shares:?}) vs {measured} Hz");
    assert!(a1 <= 0.1 * a0, "ZVD {a1} m vs unshaped {a0} m");
    assert_eq!(zvd.drive.shaper.as_deref(), Some("zvd"));
    assert_eq!((plain.drive.shaper.as_ref(), plain.drive.shaper_hz.as_ref()), (None, None));
}

/// With the pad: what the shaper does to the peak force (reported).
#[test]
fn zvd_with_the_pad_reports_the_peak_force() {
    let force = |s: &RunSummary| s.pairs.iter().map(|p| p.peak_force_n).fold(0.0, f64::max);
    let plain = default_run(true, None);
    let zvd = default_run(true, Some(Shaper::Zvd));
    eprintln!(
        "with pad: peak force unshaped {:.1} N, ZVD {:.1} N; residual {:.4e} m vs {:.4e} m",
        force(&plain),
        force(&zvd),
        plain.residual.amplitude_m,
        zvd.residual.amplitude_m
    );
    assert!(force(&plain) > 0.0 && force(&zvd).is_finite());
}

/// An envelope or a design pins the nominal tuning as `drive.shaper_hz` and
/// `drive.shaper_damping_ratio`: given those keys, the scenario is shaped exactly as the modes
/// found (the same impulses), and a spread that moves the arm no longer retunes it.
#[test]
fn the_pinned_tuning_reproduces_the_modes_found() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml");
    let mut document = pipearm::sweep::plan::read_document(&path).unwrap();
    pipearm::sweep::plan::set_key(&mut document, "drive.shaper", toml::Value::String("zvd".into())).unwrap();
    let found = Scenario::from_spec(&path, pipearm::sweep::plan::spec_of(&path, document.clone()).unwrap()).unwrap();
    let pinned_keys = pipearm::envelope::cases::nominal_shaper_tuning(&path, &document).unwrap();
    assert_eq!(pinned_keys.len(), 2, "{pinned_keys:?}");
    for (key, value) in pinned_keys {
        pipearm::sweep::plan::set_key(&mut document, &key, value).unwrap();
    }
    let pinned = Scenario::from_spec(&path, pipearm::sweep::plan::spec_of(&path, document.clone()).unwrap()).unwrap();
    // The modes are found when the scenario is compiled; given, they shape it as it is read.
    assert!(found.model.drive.motion.shaper_modes().is_empty() && found.model.drive.untuned_shaper.is_some());
    let untuned = pipearm::scene::Scene::new(&found.model).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(untuned.contains("tuned to the arm's modes when the model is compiled"), "{untuned}");
    let tuned = found.tuned().unwrap();
    let (a, b) = (&tuned.drive.motion, &pinned.model.drive.motion);
    assert_eq!(a.shaper_modes(), b.shaper_modes());
    assert_eq!(a.impulses(), b.impulses());
    assert!(tuned.drive.shaper_tuning.len() == 2 && pinned.model.drive.shaper_tuning.is_empty());
    // Half the damping: the modes found move, the pinned tuning does not.
    pipearm::sweep::plan::set_key(&mut document, "arm", toml::from_str("damping_ratios = [0.005]").unwrap()).unwrap();
    let damped = Scenario::from_spec(&path, pipearm::sweep::plan::spec_of(&path, document).unwrap()).unwrap();
    assert_eq!(damped.model.drive.motion.shaper_modes(), b.shaper_modes());
}
