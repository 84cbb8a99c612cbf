//! What `pipearm run`, `check` and `compare` may override of a scenario on the command line,
//! applied to the file's own text before it is checked, resolved and compiled: the scenario's
//! checks (an explicit integrator's stable step, an actuator's loop at the step and at the model's
//! poles, when it is compiled) see the values that will run.

use std::path::Path;

use anyhow::{Context, Result, bail};
use pipearm::arm::Fidelity;
use pipearm::scenario::Scenario;

/// Command-line overrides of a scenario.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Overrides {
    /// Override the model: rigid, modal(N) or fe (`[model]`).
    #[arg(long, value_parser = parse_fidelity)]
    pub model: Option<Fidelity>,
    /// Override the time step around contact, s (`[time] step_s`).
    #[arg(long, value_name = "SECONDS")]
    pub step: Option<f64>,
    /// Override the integrator: rk4, generalized-alpha, newmark, hht, symplectic-euler,
    /// explicit-euler (`[integrator] kind`, with its parameters' defaults).
    #[arg(long, value_name = "METHOD")]
    pub integrator: Option<String>,
}

impl Overrides {
    /// The scenario at `path` with these overrides.
    pub fn load(&self, path: &Path) -> Result<Scenario> {
        note_old_spellings(path);
        let mut spec = Scenario::read_spec(path)?;
        if let Some(fidelity) = self.model {
            spec.model = fidelity.into();
        }
        if let Some(step) = self.step {
            if !(step.is_finite() && step > 0.0) {
                bail!("--step = {step}: allowed a step > 0 s");
            }
            spec.time.step_s = step;
        }
        if let Some(method) = &self.integrator {
            spec.integrator =
                toml::from_str(&format!("kind = \"{method}\"")).with_context(|| format!("--integrator = {method}"))?;
        }
        Ok(Scenario::from_spec(path, spec)?)
    }
}

/// Prints, on stderr, each old spelling a scenario file uses and the key it is read as.
pub fn note_old_spellings(path: &Path) {
    for old in Scenario::deprecations(path).unwrap_or_default() {
        eprintln!("note: {}: {old}", path.display());
    }
}

/// A model fidelity as the summary prints it: `rigid`, `modal(N)` or `fe` (`modal:N` is the old
/// spelling, still read).
pub fn parse_fidelity(s: &str) -> Result<Fidelity, String> {
    let modes = |n: &str| n.parse().ok().filter(|m: &usize| *m > 0).map(|modes| Fidelity::Modal { modes });
    match s {
        "rigid" => Ok(Fidelity::Rigid),
        "fe" => Ok(Fidelity::Fe),
        _ => s
            .strip_prefix("modal(")
            .and_then(|rest| rest.strip_suffix(')'))
            .and_then(modes)
            .or_else(|| s.strip_prefix("modal:").and_then(modes))
            .ok_or_else(|| format!("`{s}`: expected rigid, modal(N) or fe")),
    }
}
