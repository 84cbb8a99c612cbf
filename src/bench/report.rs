//! The bench's tables: CSV for tools, Markdown for docs/accuracy.md.

use std::fmt::Write;

use super::stability::{Limit, StabilityMap};
use super::{BenchResult, Outcome, pareto_front};

/// Every grid point, one CSV row each.
pub fn points_csv(result: &BenchResult) -> String {
    let mut out = String::from(
        "axis,label,model,integrator,step_s,contact,clamp,status,cost_s_per_s,real_time_factor,peak_force_n,\
         peak_force_error,tip_rms_error,frequency_hz,frequency_error,pareto_peak,pareto_tip\n",
    );
    let front = |pick: fn(&super::Measured) -> f64| {
        let xy: Vec<(f64, f64)> = result
            .points
            .iter()
            .map(|p| p.measured().map_or((f64::NAN, f64::NAN), |m| (m.cost_s_per_s, pick(m))))
            .collect();
        pareto_front(&xy)
    };
    let (peak_front, tip_front) = (front(|m| m.peak_force_error), front(|m| m.tip_rms_error));
    for (i, p) in result.points.iter().enumerate() {
        let v = &p.variant;
        let _ = write!(
            out,
            "{},{},{},{},{},{:?},{:?},",
            v.axis,
            v.label(),
            v.fidelity,
            v.integrator.name(),
            v.step_s,
            v.contact,
            v.clamp
        );
        match &p.outcome {
            Outcome::Ran(m) => {
                let _ = writeln!(
                    out,
                    "ran,{:.6e},{:.1},{},{:.6e},{:.6e},{},{:.6e},{},{}",
                    m.cost_s_per_s,
                    1.0 / m.cost_s_per_s,
                    m.peak_force_n,
                    m.peak_force_error,
                    m.tip_rms_error,
                    m.frequency_hz,
                    m.frequency_error,
                    peak_front.contains(&i),
                    tip_front.contains(&i)
                );
            }
            Outcome::Diverged { t_s, .. } => {
                let _ = writeln!(out, "diverged at {t_s:.4} s,,,,,,,,false,false");
            }
        }
    }
    out
}

/// The stability map as CSV.
pub fn stability_csv(map: &StabilityMap) -> String {
    let mut out = String::from(
        "kind,what,model,omega_max_rad_s,theory_omega_dt,theory_step_s,measured,measured_step_s,measured_omega_dt\n",
    );
    for r in &map.arm {
        let theory = r.theory_omega_dt.map_or("unconditional".into(), |l| format!("{l}"));
        let theory_step = r.theory_omega_dt.map_or(String::new(), |l| format!("{:.6e}", l / r.omega_max_rad_s));
        let (kind, step) = limit_parts(&r.measured);
        let _ = writeln!(
            out,
            "integrator,{},{},{},{theory},{theory_step},{kind},{step:.6e},{:.5}",
            r.integrator.name(),
            r.model,
            r.omega_max_rad_s,
            step * r.omega_max_rad_s
        );
    }
    for c in &map.contact {
        let _ = writeln!(out, "penalty,{},,,,{:.6e},,,", c.pad, c.penalty_limit_s);
    }
    for s in &map.scene {
        let (kind, step) = limit_parts(&s.measured);
        let predicted = s.predicted_s.map_or(String::new(), |p| format!("{p:.6e}"));
        let _ = writeln!(out, "scene,\"{}\",,,,{predicted},{kind},{step:.6e},", s.what);
    }
    out
}

fn limit_parts(limit: &Limit) -> (&'static str, f64) {
    match *limit {
        Limit::Step(h) => ("stable up to", h),
        Limit::Unconditional(h) => ("stable at the largest step tried", h),
        Limit::Never(h) => ("unstable at the smallest step tried", h),
    }
}

fn describe(limit: &Limit) -> String {
    match *limit {
        Limit::Step(h) => ms(h),
        Limit::Unconditional(h) => format!("≥ {} (largest tried)", ms(h)),
        Limit::Never(h) => format!("none (unstable at {})", ms(h)),
    }
}

fn ms(h: f64) -> String {
    if h >= 1e-3 { format!("{:.4} ms", 1e3 * h) } else { format!("{:.3} µs", 1e6 * h) }
}

/// The Markdown report of a scene: reference and its convergence, the grid, the stability map.
pub fn report_markdown(result: &BenchResult, command: &str) -> String {
    let mut out = format!(
        "# Bench of `{}`\n\nWritten by `{command}`; the scene's own step is {}, `auto` chooses {}{}. \
         Costs are wall time per simulated second on one thread (median of repeats), errors are against the \
         reference of the same physics.\n\n## References\n\n",
        result.scenario,
        ms(result.base_step_s),
        result.auto_fidelity,
        result.auto_string.map_or(String::new(), |s| format!(" and the string {s}"))
    );
    out += "| physics | reference | peak force (N) | frequency (Hz) | Richardson: F(h), F(2h), F(4h) (N) | observed order | est. error of F(h) | doubled mesh |\n|---|---|---|---|---|---|---|---|\n";
    for r in &result.references {
        let c = &r.convergence;
        let steps: Vec<String> = c.steps.iter().map(|s| format!("{:.3}", s.1)).collect();
        let mesh = c.doubled_mesh.map_or("—".into(), |(n, f, d)| format!("fe{n} at 2h: {f:.3} N ({:.2e})", d));
        let _ = writeln!(
            out,
            "| {} | {} | {:.3} | {:.4} | {} | {:.2} | {:.1e} | {mesh} |",
            physics_name(&r.variant),
            r.variant.label(),
            r.peak_force_n,
            r.frequency_hz,
            steps.join(", "),
            c.observed_order,
            c.peak_force_error
        );
    }
    out += "\n## Grid\n\n| axis | point | cost (s/s) | real time × | peak force (N) | peak error | tip RMS error | frequency error |\n|---|---|---|---|---|---|---|---|\n";
    for p in &result.points {
        match &p.outcome {
            Outcome::Ran(m) => {
                let _ = writeln!(
                    out,
                    "| {} | {} | {:.2e} | {:.0} | {:.1} | {:.1e} | {:.1e} | {:.1e} |",
                    p.variant.axis,
                    p.variant.label(),
                    m.cost_s_per_s,
                    1.0 / m.cost_s_per_s,
                    m.peak_force_n,
                    m.peak_force_error,
                    m.tip_rms_error,
                    m.frequency_error
                );
            }
            Outcome::Diverged { t_s, message } => {
                let _ = writeln!(
                    out,
                    "| {} | {} | diverged at {t_s:.4} s: {message} | | | | | |",
                    p.variant.axis,
                    p.variant.label()
                );
            }
        }
    }
    out += &stability_markdown(&result.stability);
    out += &rapier_markdown(result);
    out += &clamp_markdown(&result.stability.clamp);
    out
}

/// The `rapier` contact method as the step and the pad body's mass grow, and the pipeline
/// against the pad-face path (from the grid's contact, pad mass and detection axes).
fn rapier_markdown(result: &BenchResult) -> String {
    let on = |axis: &str| result.points.iter().filter(|p| p.variant.axis == axis).collect::<Vec<_>>();
    let row = |p: &super::Point| match &p.outcome {
        Outcome::Ran(m) => {
            format!("ran | {:.1} | {:.1e} | {:.3}", m.peak_force_n, m.peak_force_error, m.cost_s_per_s)
        }
        Outcome::Diverged { t_s, .. } => format!("diverged at {t_s:.4} s | — | — | —"),
    };
    let mut out = String::new();
    let header = "| outcome | peak force (N) | peak error vs reference | cost (s/s) |\n|---|---|---|---|---|\n";
    let rapier = on("contact: rapier");
    if !rapier.is_empty() {
        out += "\n### The `rapier` contact method as the step grows\n\nThe pad body (the scene's mass) on its spring as \
                a joint motor in rapier's solver, the spring's law in the arm step, the body's inertia handed over \
                one step late. Against the compliant reference on the same linear law.\n\n| step ";
        out += header;
        for p in rapier {
            let _ = writeln!(out, "| {} | {} |", ms(p.variant.step_s), row(p));
        }
    }
    let masses = on("pad mass");
    if !masses.is_empty() {
        out += "\n### The `rapier` contact method against the pad body's mass, at the scene's step\n\n| pad mass (kg) ";
        out += header;
        for p in masses {
            let _ = writeln!(out, "| {} | {} |", p.variant.pad_mass_kg.unwrap_or(f64::NAN), row(p));
        }
    }
    for axis in ["detection: pipeline", "detection: pad-face"] {
        let points = on(axis);
        if !points.is_empty() {
            let _ = write!(out, "\n### Contact found by `{}`\n\n| step ", &axis["detection: ".len()..]);
            out += header;
            for p in points {
                let _ = writeln!(out, "| {} | {} |", ms(p.variant.step_s), row(p));
            }
        }
    }
    out
}

fn clamp_markdown(runs: &[super::stability::ClampRun]) -> String {
    use super::stability::ClampOutcome;
    if runs.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "\n### The friction clamp's coupling as the step grows\n\n| string | model | step | outcome | max slip (mm) | peak force (N) |\n|---|---|---|---|---|---|\n",
    );
    for r in runs {
        let row = match r.outcome {
            ClampOutcome::Held { max_slip_m, peak_force_n } => {
                format!("held | {:.3} | {peak_force_n:.1}", 1e3 * max_slip_m)
            }
            ClampOutcome::Diverged { t_s } => format!("diverged at {t_s:.3} s | — | —"),
        };
        let (size, kg, string) = (&r.size, r.string_kg, r.string);
        let _ = writeln!(out, "| {size} in ({kg:.0} kg), {string} | {} | {} | {row} |", r.model, ms(r.step_s));
    }
    out
}

fn physics_name(v: &super::Variant) -> String {
    let contact = if v.linear_pads { "linear pad law" } else { "scene's pad law" };
    format!("{contact}, {:?} clamp", v.clamp).to_lowercase()
}

fn stability_markdown(map: &StabilityMap) -> String {
    let mut out = String::from(
        "\n## Stability map\n\nLargest stable step of each integrator on the undamped arm (bisection, module \
         `bench::stability`), beside the theory.\n\n| integrator | model | ω_max (rad/s) | theory ω·dt | theory step | measured step | measured ω·dt |\n|---|---|---|---|---|---|---|\n",
    );
    for r in &map.arm {
        let theory = match r.theory_omega_dt {
            None => "unconditional".to_string(),
            Some(0.0) => "none (grows at any step)".to_string(),
            Some(l) => format!("{l:.4}"),
        };
        let theory_step = r.theory_omega_dt.filter(|&l| l > 0.0).map_or("—".into(), |l| ms(l / r.omega_max_rad_s));
        let omega_dt = match r.measured {
            Limit::Step(h) => format!("{:.4}", h * r.omega_max_rad_s),
            _ => "—".into(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {:.1} | {theory} | {theory_step} | {} | {omega_dt} |",
            r.integrator.name(),
            r.model,
            r.omega_max_rad_s,
            describe(&r.measured)
        );
    }
    if !map.contact.is_empty() {
        out +=
            "\n| pad | m_eff (kg) | k at the reference peak (N/m) | penalty limit 2√(m_eff/k) |\n|---|---|---|---|\n";
        for c in &map.contact {
            let _ = writeln!(
                out,
                "| {} | {:.2} | {:.3e} | {} |",
                c.pad,
                c.effective_mass_kg,
                c.stiffness_n_m,
                ms(c.penalty_limit_s)
            );
        }
    }
    if !map.scene.is_empty() {
        out += "\n| whole-scene run | largest step without divergence (bisection) | predicted |\n|---|---|---|\n";
        for s in &map.scene {
            let _ =
                writeln!(out, "| {} | {} | {} |", s.what, describe(&s.measured), s.predicted_s.map_or("—".into(), ms));
        }
    }
    if let Some(row) = &map.pad_mass {
        let heaviest = match row.heaviest_pad {
            Limit::Step(kg) => format!("{kg:.0} kg"),
            Limit::Unconditional(kg) => format!("every mass up to {kg:.0} kg"),
            Limit::Never(kg) => format!("none from {kg:.0} kg"),
        };
        let _ = write!(
            out,
            "\nThe `rapier` method's heaviest pad body at the scene's step: {heaviest}, against the arm's effective \
             mass of {:.1} kg at the pad (it hands the pad's inertia to the arm one step late).\n",
            row.effective_mass_kg
        );
    }
    out
}
