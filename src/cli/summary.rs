//! What `pipearm run` prints of a run: its summary, line by line (docs/tutorial.md names each).

use std::path::Path;

use pipearm::run::RunSummary;

/// Prints a run's summary as `pipearm run` shows it.
pub fn print_summary(path: &Path, s: &RunSummary) {
    println!(
        "scenario            {} ({}), robot {}, payload {:.1} kg",
        s.scenario,
        path.display(),
        s.robot,
        s.payload_kg.max(0.0)
    );
    let detection = s.contact_detection.as_ref().map(|d| format!(" ({d})")).unwrap_or_default();
    println!("model               {}, {}, contact {}{detection}", s.model, s.integrator, s.contact_method);
    println!("static w/l          1/{:.0}: {}", 1.0 / s.static_w_over_l, s.stiffness_class);
    println!("model choice        {}", s.model_reason);
    if let Some(e) = &s.model_expected_error {
        println!("expected error      {} on {}", pipearm::select::percent(e.fraction), e.basis);
        if let Some(residual) = e.residual_fraction {
            println!(
                "                    {} on the residual vibration's amplitude, the same way (stated, not held to the budget)",
                pipearm::select::percent(residual)
            );
        }
    }
    let a = &s.motion_advice;
    if a.limit_deg_s2 > 0.0 {
        println!(
            "motion advice       {} (seed §4); this drive: {:.2} °/s² against {:.1}: {}",
            a.advice,
            a.peak_accel_deg_s2,
            a.limit_deg_s2,
            if a.within { "within" } else { "outside the advice" }
        );
    } else {
        println!("motion advice       {} (seed §4); this drive: {:.2} °/s²", a.advice, a.peak_accel_deg_s2);
    }
    println!(
        "simulated           {:.3} s in {} steps of {} s, wall {:.3} s ({:.0}x real time)",
        s.simulated_s,
        s.steps,
        s.step_s,
        s.wall_time_s,
        s.simulated_s / s.wall_time_s
    );
    println!("max tip deflection  {:.3} mm (w/l = 1/{:.0})", 1e3 * s.max_tip_deflection_m, 1.0 / s.max_w_over_l);
    println!("peak drive torque   {:.1} kN·m at {:.3} s", 1e-3 * s.peak_drive_torque_n_m, s.peak_drive_torque_time_s);
    print_drive_limits(&s.drive, s.peak_drive_torque_n_m);
    print_actuator(&s.actuator);
    let r = &s.residual;
    let frequency =
        if r.frequency_hz.is_finite() { format!("{:.3} Hz", r.frequency_hz) } else { "no oscillation".into() };
    let settling = if r.settled {
        format!("settles in {:.2} s", r.settling_time_s)
    } else {
        format!("not settled within the run's {:.2} s", r.settling_time_s)
    };
    let decrement = if r.log_decrement.is_finite() {
        format!("log decrement {:.3} (ζ = {:.4})", r.log_decrement, r.damping_ratio)
    } else {
        "no decay measured".into()
    };
    let read = match r.hub_rate_amplitude_rad_s {
        Some(rate) => format!(" (frequency and decay of the hub rate, ±{:.4} °/s)", rate.to_degrees()),
        None => String::new(),
    };
    println!("residual vibration  {:.3} mm, {frequency}, {decrement}, {settling}{read}", 1e3 * r.amplitude_m);
    if let Some(h) = &s.head {
        println!(
            "head                {}: rest {:.3}°, range {:.3}° ..= {:.3}°, residual ±{:.3}° after the drive{}",
            h.joint,
            h.rest_angle_deg,
            h.min_angle_deg,
            h.max_angle_deg,
            h.residual_swing_deg,
            h.peak_drive_torque_n_m.map_or(String::new(), |t| format!(", its drive's peak torque {t:.1} N·m"))
        );
    }
    if let Some(slip) = &s.string_slip {
        println!(
            "string slip         max {:.3} mm, final {:.3} mm (friction clamp, {:.0} N per jaw)",
            1e3 * slip.max_slip_m,
            1e3 * slip.final_slip_m,
            slip.squeeze_n
        );
    }
    for p in &s.pairs {
        if p.impact_count == 0 {
            println!("contact {:<14} no contact", p.pair);
            continue;
        }
        let per_weight = if p.peak_force_per_payload_weight.is_finite() {
            format!(" ({:.3} per payload weight)", p.peak_force_per_payload_weight)
        } else {
            String::new()
        };
        println!(
            "contact {:<14} peak {:.1} N at {:.3} s{per_weight}, impulse {:.3} N·s, {} impacts",
            p.pair, p.peak_force_n, p.peak_time_s, p.impulse_n_s, p.impact_count
        );
        for (k, i) in p.impacts.iter().enumerate().take(12) {
            println!(
                "  impact {:>2}: {:.3} s, peak {:.1} N, {:.1} ms",
                k + 1,
                i.start_s,
                i.peak_force_n,
                1e3 * i.duration_s()
            );
        }
    }
    super::sign_off::print(s);
}

/// The drive's peaks against the lift joint's URDF limits; a warning if the torque exceeded its
/// effort (the run is not stopped: the drive is ideal, the URDF's effort is the real one's).
fn print_drive_limits(d: &pipearm::run::DriveLimits, peak_torque_n_m: f64) {
    let shaped = match (&d.shaper, &d.shaper_hz) {
        (Some(shaper), Some(hz)) => {
            let shares = d.shaper_residual_share.as_deref();
            let modes: Vec<String> = hz
                .iter()
                .enumerate()
                .map(|(i, f)| match shares.and_then(|s| s.get(i)) {
                    Some(share) => format!("{f:.3} Hz ({:.0} % of the residual)", 100.0 * share),
                    None => format!("{f:.3} Hz"),
                })
                .collect();
            format!(" with a {shaper} shaper at {}", modes.join(", "))
        }
        _ => String::new(),
    };
    println!(
        "drive               {}{shaped}: peak rate {:.3} °/s (lift velocity limit {:.3}), peak accel {:.3} °/s²",
        d.kind, d.peak_rate_deg_s, d.velocity_limit_deg_s, d.peak_accel_deg_s2
    );
    if !d.torque_within_effort {
        println!(
            "warning             the peak drive torque {:.1} kN·m exceeds the lift joint's effort {:.1} kN·m (URDF)",
            1e-3 * peak_torque_n_m,
            1e-3 * d.effort_n_m
        );
    }
}

/// A servo's or hydraulic drive's peaks and tracking (nothing for an ideal drive).
fn print_actuator(a: &pipearm::actuator::ActuatorSummary) {
    if a.kind == "ideal" {
        return;
    }
    let cylinder = match (a.peak_force_n, a.peak_pressure_pa) {
        (Some(force), Some(pressure)) => {
            format!(", rod force {:.1} kN, pressure {:.1} bar", 1e-3 * force, 1e-5 * pressure)
        }
        _ => String::new(),
    };
    println!(
        "actuator            {}: peak hub torque {:.1} kN·m{cylinder}; tracking error up to {:.3}°, overtravel {:.3}°",
        a.kind,
        1e-3 * a.peak_torque_n_m,
        a.max_tracking_error_deg,
        a.overtravel_deg
    );
}
