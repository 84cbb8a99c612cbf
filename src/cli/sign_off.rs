//! `pipearm run`'s lines on what the run does to the machine: peak stress, utilisation, pin
//! loads and fatigue (docs/sign-off.md).

use pipearm::run::RunSummary;
use pipearm::stress::summary::PinPeak;

/// Prints the sign-off lines of a run's summary (none for a run without them).
pub fn print(s: &RunSummary) {
    let Some(signed) = &s.sign_off else { return };
    let (stress, pins, fatigue) = (&signed.stress, &signed.pins, &signed.fatigue);
    {
        println!(
            "peak stress         {:.1} MPa at {:.3} m, {} fibre, {:.3} s ({})",
            1e-6 * stress.peak_stress_pa,
            stress.peak_station_m,
            stress.peak_fibre.name(),
            stress.peak_time_s,
            stress.method
        );
        match (stress.utilisation, &stress.utilisation_note) {
            (Some(u), _) => println!(
                "utilisation         {:.3} at {:.3} m, {} fibre, {:.3} s (stress factor {})",
                u,
                stress.utilisation_station_m.unwrap_or(0.0),
                stress.utilisation_fibre.map_or("", |f| f.name()),
                stress.utilisation_time_s.unwrap_or(0.0),
                stress.stress_factor
            ),
            (None, Some(note)) => println!("utilisation         none: {}", note.trim_start_matches("no utilisation: ")),
            (None, None) => {}
        }
    }
    {
        print_pin("pivot pin", &pins.pivot);
        // Of several cylinders, `cylinder` is the most loaded pin; each follows by number.
        let most = if pins.cylinders.is_empty() { "" } else { " (most loaded)" };
        if let Some(cylinder) = &pins.cylinder {
            print_pin(&format!("cylinder pin{most}"), cylinder);
        }
        if let Some(base) = &pins.cylinder_base {
            print_pin(&format!("cylinder base pin{most}"), base);
        }
        for (k, pin) in pins.cylinders.iter().enumerate() {
            print_pin(&format!("cylinder {} pin", k + 1), pin);
        }
        for hand in &pins.hands {
            println!(
                "grip {:<14} peak {:.2} kN at {:.3} s, {:.2} kN·m at {:.3} s",
                hand.hand,
                1e-3 * hand.peak_force_n,
                hand.peak_force_time_s,
                1e-3 * hand.peak_moment_n_m,
                hand.peak_moment_time_s
            );
        }
    }
    {
        match (fatigue.damage_per_lift, &fatigue.worst) {
            (Some(damage), Some(worst)) => {
                let lifts = fatigue
                    .lifts_to_failure
                    .map_or("no damage: every range below the cut-off".into(), |n| format!("{n:.3e} lifts to failure"));
                let place = fatigue.places.iter().find(|p| &p.place == worst);
                let at = place.map(|p| format!(" at {:.3} m ({})", p.station_m, p.curve)).unwrap_or_default();
                println!("fatigue             damage {damage:.3e} per lift, {lifts}, {worst}{at}");
            }
            _ => println!(
                "fatigue             none: {}",
                fatigue.note.as_deref().unwrap_or("").trim_start_matches("no fatigue check: ")
            ),
        }
    }
}

fn print_pin(name: &str, pin: &PinPeak) {
    println!(
        "{:<20}peak {:.2} kN at {:.3} s: world ({:.2}, {:.2}) kN, arm ({:.2}, {:.2}) kN",
        name,
        1e-3 * pin.peak_force_n,
        pin.peak_time_s,
        1e-3 * pin.world_n[0],
        1e-3 * pin.world_n[1],
        1e-3 * pin.arm_n[0],
        1e-3 * pin.arm_n[1]
    );
}
