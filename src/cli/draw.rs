//! `pipearm draw`: the machine of a scenario, or a robot alone, as a dimensioned SVG and PNG.

use std::path::PathBuf;

use anyhow::Result;
use pipearm::draw::{Subject, default_path, png_path, write};
use pipearm::robot::load_robot;
use pipearm::scenario::Scenario;

/// `pipearm draw`'s arguments.
#[derive(clap::Args)]
#[command(after_help = super::help::DRAW)]
pub struct DrawArgs {
    /// A scenario (.toml: the machine in its scene) or a robot (.urdf: the robot alone).
    #[arg(default_value = "scenarios/default.toml")]
    input: PathBuf,
    /// The SVG to write; the PNG is written beside it (default: recordings/<name>.machine.svg,
    /// <name> the scenario's, or the robot's).
    #[arg(long, value_name = "FILE.svg")]
    out: Option<PathBuf>,
}

pub fn draw(args: DrawArgs) -> Result<()> {
    let path = &args.input;
    let is_robot = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
    let (scenario, robot);
    let subject = if is_robot {
        robot = load_robot(path)?;
        Subject::Robot(&robot)
    } else {
        super::overrides::note_old_spellings(path);
        scenario = Scenario::load(path)?;
        Subject::Scene(&scenario.model)
    };
    let svg = args.out.unwrap_or_else(|| default_path(&PathBuf::from("recordings"), subject.name()));
    write(&subject, path, &svg)?;
    println!("wrote {} and {}", svg.display(), png_path(&svg).display());
    Ok(())
}
