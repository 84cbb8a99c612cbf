use pipearm::run::{RunOptions, run_with};
use pipearm::scenario::Scenario;
use std::path::Path;

fn main() {
    let path = std::env::args().nth(1).unwrap_or("scenarios/default.toml".into());
    let model = Scenario::load(Path::new(&path)).unwrap().model;
    if std::env::var("MICRO").is_ok() {
        for _ in 0..40 {
            micro(&model);
        }
        return;
    }
    if std::env::var("VARIANTS").is_ok() {
        use pipearm::arm::Fidelity;
        use pipearm::integrate::IntegratorKind;
        let show = |name: &str, m: &pipearm::model::Model, f: Option<Fidelity>| {
            let (s, _) = run_with(m, &RunOptions { fidelity: f, ..RunOptions::default() }).unwrap();
            let st = s.stress.as_ref().unwrap();
            let pins = s.pins.as_ref().unwrap();
            let fat = s.fatigue.as_ref().unwrap();
            println!(
                "{name:<28} {:<9} peak {:.6e} Pa at {:.3} m {:.3} s, util {:?}, pivot {:.6e} N, cyl {:?}, damage {:?} at {:?}, pads {:?}",
                s.model,
                st.peak_stress_pa,
                st.peak_station_m,
                st.peak_time_s,
                st.utilisation,
                pins.pivot.peak_force_n,
                pins.cylinder.as_ref().map(|c| c.peak_force_n),
                fat.damage_per_lift,
                fat.places.first().map(|p| p.station_m),
                s.pairs.iter().map(|p| p.peak_force_n).collect::<Vec<_>>()
            );
        };
        show("baseline", &model, None);
        let mut ga = model.clone();
        ga.integrator = IntegratorKind::default();
        show("generalized-alpha", &ga, Some(Fidelity::Modal { modes: 3 }));
        show("generalized-alpha modal(6)", &ga, Some(Fidelity::Modal { modes: 6 }));
        show("generalized-alpha fe", &ga, Some(Fidelity::Fe));
        let mut step = model.clone();
        step.time.step_s = 0.0015;
        show("rk4 1.5 ms", &step, None);
        let mut pad = model.clone();
        if let pipearm::contact::ForceLaw::HuntCrossley { stiffness, .. } = &mut pad.dampeners[0].law {
            *stiffness *= 1.1;
        }
        show("pad 10 % stiffer", &pad, None);
        return;
    }
    if let Ok(on) = std::env::var("LOOP") {
        for _ in 0..40 {
            run_with(&model, &RunOptions { sign_off: on == "1", ..RunOptions::default() }).unwrap();
        }
        return;
    }
    if let Ok(on) = std::env::var("SIGN_OFF") {
        let (s, _) = run_with(&model, &RunOptions { sign_off: on == "1", ..RunOptions::default() }).unwrap();
        println!("{}", s.steps);
        return;
    }
    micro(&model);
    let mut on = Vec::new();
    let mut off = Vec::new();
    let cpu = || {
        let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
    };
    for i in 0..40 {
        for sign_off in [i % 2 == 0, i % 2 != 0] {
            let t = cpu();
            let (s, _) = run_with(&model, &RunOptions { sign_off, ..RunOptions::default() }).unwrap();
            let wall = cpu() - t;
            if i == 0 && sign_off {
                println!("{}", serde_json::to_string_pretty(&(&s.stress, &s.fatigue, &s.pins)).unwrap());
            }
            if sign_off { on.push(wall) } else { off.push(wall) }
        }
    }
    on.sort_by(f64::total_cmp);
    off.sort_by(f64::total_cmp);
    let (a, b) = (on[on.len() / 2], off[off.len() / 2]);
    println!(
        "median with {:.2} ms, without {:.2} ms, ratio {:.3}; min with {:.2} without {:.2} ratio {:.3}",
        a * 1e3,
        b * 1e3,
        a / b,
        on[0] * 1e3,
        off[0] * 1e3,
        on[0] / off[0]
    );
}

#[allow(dead_code)]
pub fn micro(model: &pipearm::model::Model) {
    use pipearm::scene::Scene;
    use pipearm::stress::StressProbe;
    let mut scene = Scene::with_fidelity(model, pipearm::arm::Fidelity::Modal { modes: 3 }).unwrap();
    for _ in 0..100 {
        scene.step(model.time.step_s).unwrap();
    }
    let sample = scene.arm.sample();
    let t = std::time::Instant::now();
    let mut probe = StressProbe::new(model, &scene.arm.arm, &scene);
    println!("probe new {:.3} ms, width {}", t.elapsed().as_secs_f64() * 1e3, probe.width());
    let mut out = probe.series(7000, &[]);
    let t = std::time::Instant::now();
    for _ in 0..6667 {
        probe.read(&scene, &sample, 9.81, &mut out);
    }
    probe.finish(&mut out);
    println!("6667 reads {:.3} ms", t.elapsed().as_secs_f64() * 1e3);
}
