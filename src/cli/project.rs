//! A project: the folder holding `scenarios/` (its robots in `robots/`, its regression baselines
//! in `tests/baselines/`, the seed's families in `scenarios/seed/`), and `pipearm init`, which
//! writes a starter one.
//!
//! Commands given a scenario find its project from the scenario's path; `check`, `seed` and
//! `bench` without one take the project `--project` names (default: the current folder).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// The starter project's scenario and robot: the shipped default lift and arm.
const STARTER_SCENARIO: &str = include_str!("../../scenarios/default.toml");
const STARTER_ROBOT: &str = include_str!("../../robots/pipe_arm.urdf");

/// A project folder.
#[derive(Debug, Clone)]
pub struct Project {
    root: PathBuf,
}

impl Project {
    /// The project at `root`.
    pub fn at(root: &Path) -> Self {
        Project { root: root.to_path_buf() }
    }

    /// The project a scenario file belongs to: the folder above the `scenarios/` it is in (above
    /// `scenarios/seed/` for the seed's), else the scenario's own folder.
    pub fn of_scenario(path: &Path) -> Self {
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let root = folder
            .ancestors()
            .take(3)
            .find(|a| a.file_name().is_some_and(|n| n == "scenarios"))
            .and_then(Path::parent)
            .map(|p| if p.as_os_str().is_empty() { Path::new(".") } else { p });
        Project::at(root.unwrap_or(folder))
    }

    /// Its scenarios folder.
    pub fn scenarios(&self) -> PathBuf {
        self.root.join("scenarios")
    }

    /// Its default scenario.
    pub fn default_scenario(&self) -> PathBuf {
        self.scenarios().join("default.toml")
    }

    /// The seed's scenario families.
    pub fn seed(&self) -> PathBuf {
        self.scenarios().join("seed")
    }

    /// Its regression baselines.
    pub fn baselines(&self) -> PathBuf {
        self.root.join("tests").join("baselines")
    }
}

/// Writes a starter project into `dir` (created if need be; refused if it already holds
/// `scenarios/` or `robots/`): the default lift of a 2⅞ in tubing joint on the shipped 9 m arm,
/// and an empty baselines folder. `pipearm run` inside it then runs.
pub fn init(dir: &Path) -> Result<()> {
    for taken in ["scenarios", "robots"] {
        if dir.join(taken).exists() {
            bail!("{}: already holds {taken}/; allowed an empty or new folder", dir.display());
        }
    }
    let project = Project::at(dir);
    let write = |path: PathBuf, text: &str| -> Result<()> {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
        }
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))
    };
    // Its comments cite pipearm's own pages, which the new project does not hold.
    let scenario = STARTER_SCENARIO
        .replace("(robots/README.md, docs/", "(pipearm's robots/README.md and docs/")
        .replace("(docs/", "(pipearm's docs/");
    write(project.default_scenario(), &scenario)?;
    write(dir.join("robots").join("pipe_arm.urdf"), STARTER_ROBOT)?;
    std::fs::create_dir_all(project.baselines())
        .with_context(|| format!("creating {}", project.baselines().display()))?;
    println!("wrote a starter project in {}:", dir.display());
    println!("  scenarios/default.toml   the default lift (edit it, or add scenarios beside it)");
    println!("  robots/pipe_arm.urdf     the arm it names (replace it with your machine's URDF)");
    println!("  tests/baselines/         regression baselines (`pipearm check --bless` writes them)");
    println!("next: cd {} && pipearm run && pipearm check --bless", dir.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scenario_finds_its_project_above_its_scenarios_folder() {
        let root = |p: &str| Project::of_scenario(Path::new(p)).root;
        assert_eq!(root("/a/proj/scenarios/default.toml"), Path::new("/a/proj"));
        assert_eq!(root("/a/proj/scenarios/seed/3.4/x.toml"), Path::new("/a/proj"));
        assert_eq!(root("scenarios/default.toml"), Path::new("."));
        assert_eq!(root("/elsewhere/mine.toml"), Path::new("/elsewhere"));
        assert_eq!(root("mine.toml"), Path::new("."));
    }
}
