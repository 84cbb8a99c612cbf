//! `pipearm seed`: the seed paper's experiment families of a project, run and charted.

use std::path::Path;

use anyhow::{Context, Result, bail};
use pipearm::record::write_recording;

use super::project::Project;

/// Runs the seed's families under the project's `scenarios/seed/` (or section `only`): a
/// recording per variant, a chart and a table per section under `out/seed/`.
pub fn seed(only: Option<&str>, project: &Project, out: &Path) -> Result<()> {
    let folder = project.seed();
    let sections = pipearm::seed::sections(&folder).with_context(|| format!("reading {}", folder.display()))?;
    let chosen: Vec<_> = sections.into_iter().filter(|(name, _)| only.is_none_or(|o| name == o)).collect();
    if chosen.is_empty() {
        bail!("no section `{}` under {}", only.unwrap_or_default(), folder.display());
    }
    for (section, files) in chosen {
        let variants = pipearm::seed::run_family(&files, true)?;
        let dir = out.join("seed").join(&section);
        for v in &variants {
            write_recording(&dir.join(format!("{}.rrd", v.name)), &v.summary, &v.series)?;
        }
        let chart = out.join("seed").join(format!("{section}.svg"));
        pipearm::seed::chart(&chart, &section, &variants)?;
        println!(
            "## {section}\n\n{}\nchart {}, recordings {}\n",
            pipearm::seed::table(&variants),
            chart.display(),
            dir.display()
        );
    }
    Ok(())
}
