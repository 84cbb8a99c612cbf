//! `pipearm modes`: the arm's clamped natural frequencies, λL, modal masses and static w/l.

use std::path::Path;

use anyhow::{Context, Result, bail};
use pipearm::analysis::StiffnessClass;
use pipearm::arm::STANDARD_GRAVITY_M_S2;
use pipearm::beam::BeamModel;
use pipearm::scenario::Scenario;

/// Prints the first `count` modes of the scenario's arm spinning at `spin_rad_s` (with or without
/// geometric stiffening), the held string's own frequencies and the static w/l.
pub fn modes(path: &Path, count: usize, spin_rad_s: f64, stiffening: bool) -> Result<()> {
    let scenario = Scenario::load(path)?;
    if !(spin_rad_s.is_finite() && spin_rad_s >= 0.0) {
        bail!("--spin = {spin_rad_s}: allowed a finite rate >= 0 rad/s");
    }
    let beam = BeamModel::new(scenario.model.beam_spec()?)?;
    let basis = if spin_rad_s > 0.0 {
        beam.modes_spinning(spin_rad_s, stiffening).with_context(|| format!("at {spin_rad_s} rad/s"))?
    } else {
        beam.modes()?
    };
    let l = beam.length_m();
    // λL from the length-averaged EI and ρA (exact for a uniform arm).
    let (ei, mu) = beam.elements.iter().fold((0.0, 0.0), |(ei, mu), e| {
        (ei + e.bending_rigidity_n_m2 * e.length_m / l, mu + e.mass_per_length_kg_m * e.length_m / l)
    });
    let [_, tip_v, _] = beam.point_rows(l);
    let stiffening_note = if stiffening { "" } else { " without stiffening" };
    let string_dofs =
        beam.member.as_ref().map_or(String::new(), |m| format!(", {} of them the string's", m.own_dofs.len()));
    println!(
        "arm of {} ({} elements, L = {l} m, {} DOFs{string_dofs}), spin {spin_rad_s} rad/s{stiffening_note}",
        scenario.model.robot.name,
        beam.elements.len(),
        beam.dofs()
    );
    println!("{:>4} {:>12} {:>12} {:>10} {:>20}", "mode", "f (Hz)", "ω (rad/s)", "λL", "tip modal mass (kg)");
    for i in 0..count.min(basis.len()) {
        let w = basis.omegas_rad_s[i];
        let tip = tip_v.dot(&basis.shapes.column(i));
        let lambda_l = (w * w * mu / ei).powf(0.25) * l;
        let tip_mass = if tip.abs() > 1e-12 { format!("{:.4e}", 1.0 / (tip * tip)) } else { "axial/no tip".into() };
        println!("{:>4} {:>12.5} {:>12.5} {:>10.5} {:>20}", i + 1, w / std::f64::consts::TAU, w, lambda_l, tip_mass);
    }
    if let (Some(member), Some(string)) = (&beam.member, beam.member_modes()) {
        // The modes above are the arm's with the string riding on its hands; the string's own:
        let listed: Vec<String> = string.frequencies_hz().iter().take(count).map(|f| format!("{f:.3}")).collect();
        println!(
            "{} held in its hands (at {:?} m): [{}] Hz",
            member.spec.name,
            member.spec.clamps_m,
            listed.join(", ")
        );
    }
    let w = beam.gravity_tip_deflection_m(STANDARD_GRAVITY_M_S2)?;
    println!(
        "static tip deflection, horizontal under gravity: {:.3} mm, w/l = 1/{:.0}: {}",
        w * 1e3,
        l / w,
        StiffnessClass::of_ratio(w / l).describe()
    );
    Ok(())
}
