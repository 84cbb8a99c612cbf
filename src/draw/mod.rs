//! `pipearm draw`: a dimensioned drawing of the machine as pipearm reads it, as SVG and PNG, for
//! the reader to check what a scenario or URDF says by looking.
//!
//! Panel 1 is the arm in its own frame at true scale (station along the arm, y toward the upper
//! face): the segments and their sections, the bodies it carries, the string in its hands with
//! its overhangs, the pads on their faces, the cylinder's arm pin, and a dimension line from the
//! pivot to every station. Panel 2 is the lift plane in the world at true scale: the base, the
//! arm at the drive's start and end angles with the lift angle's arc between them, the pads at
//! their stops, the structures and the cylinder between its pins. Beside it, the legend and the
//! scenario's values. Everything is read from the resolved [`Model`](crate::model::Model) or
//! [`Robot`](crate::robot::Robot), never from the files again.
//!
//! The SVG carries both panels' scales in `<metadata id="pipearm-draw">`, as JSON
//! ([`Scales`]): a point (x, y) m of a panel is at pixel `origin_px + (x, −y) · px_per_m`.

mod arm_view;
mod notes;
mod outline;
mod paint;
mod subject;
mod world_view;

use std::path::{Component, Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use arm_view::ArmPlan;
pub use paint::View;
use paint::{Drawn, FRAME, INK, Painter, font};
pub use subject::Subject;
use world_view::WorldPlan;

/// The `id` of the SVG's `<metadata>` element that holds the [`Scales`].
pub const METADATA_ID: &str = "pipearm-draw";

/// Width of the drawing, px.
const WIDTH_PX: i32 = 1800;
/// Height of the title, px.
const TITLE_PX: i32 = 66;
/// Narrowest the notes column beside panel 2 is, px (it takes what panel 2 leaves).
const NOTES_MIN_PX: i32 = 560;
/// Tallest panel 2 is drawn, px.
const WORLD_MAX_PX: i32 = 1000;

/// Errors drawing a machine; each names the file.
#[derive(Debug, Error)]
pub enum DrawError {
    /// The output is not an SVG file name.
    #[error("{path}: allowed a file name ending in .svg (the PNG is written beside it, .png)")]
    NotSvg { path: PathBuf },
    /// A file or folder could not be written.
    #[error("{path}: cannot write: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// plotters failed to draw.
    #[error("{path}: drawing failed: {message}")]
    Render { path: PathBuf, message: String },
}

/// Where each panel's plane lies in the drawing's pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Scales {
    /// Panel 1: x the station along the arm from the pivot, y across it toward the upper face.
    pub arm_frame: View,
    /// Panel 2: world X and Y in the lift plane.
    pub lift_plane: View,
    /// The drawing's width and height, px.
    pub size_px: [u32; 2],
}

/// Where the parts of a drawing go.
struct Layout {
    arm: ArmPlan,
    world: WorldPlan,
    notes: [i32; 4],
    size_px: (u32, u32),
}

impl Layout {
    fn new(subject: &Subject) -> Self {
        let arm = ArmPlan::new(subject, [16, WIDTH_PX - 16], TITLE_PX);
        let top = arm.rect[3] + 14;
        let world = WorldPlan::new(subject, [16, WIDTH_PX - 28 - NOTES_MIN_PX], top, WORLD_MAX_PX);
        let left = world.rect[2] + 12;
        let notes_bottom = world.rect[3].max(top + notes::height_px(subject, WIDTH_PX - 16 - left));
        let notes = [left, top, WIDTH_PX - 16, notes_bottom];
        Layout { arm, world, notes, size_px: (WIDTH_PX as u32, (notes_bottom + 16) as u32) }
    }

    fn scales(&self) -> Scales {
        Scales { arm_frame: self.arm.view, lift_plane: self.world.view, size_px: [self.size_px.0, self.size_px.1] }
    }
}

/// The default drawing of a machine named `name`: `<folder>/<name>.machine.svg`.
pub fn default_path(folder: &Path, name: &str) -> PathBuf {
    folder.join(format!("{name}.machine.svg"))
}

/// The PNG written beside an SVG.
pub fn png_path(svg: &Path) -> PathBuf {
    svg.with_extension("png")
}

/// Draws `subject`, read from `source`, to `svg` and to the PNG beside it; each file is written
/// under a temporary name and renamed when complete, so a failure leaves neither.
pub fn write(subject: &Subject, source: &Path, svg: &Path) -> Result<Scales, DrawError> {
    if svg.extension().is_none_or(|e| e != "svg") {
        return Err(DrawError::NotSvg { path: svg.into() });
    }
    let (text, scales) =
        svg_text(subject, source).map_err(|message| DrawError::Render { path: svg.into(), message })?;
    let folder = svg.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(folder).map_err(|source| DrawError::Io { path: folder.into(), source })?;
    let png = png_path(svg);
    let (svg_tmp, png_tmp) = (temporary(svg), temporary(&png));
    let written = write_png(subject, source, &png_tmp)
        .and_then(|()| std::fs::write(&svg_tmp, text).map_err(|source| DrawError::Io { path: svg.into(), source }))
        .and_then(|()| std::fs::rename(&png_tmp, &png).map_err(|source| DrawError::Io { path: png.clone(), source }))
        .and_then(|()| std::fs::rename(&svg_tmp, svg).map_err(|source| DrawError::Io { path: svg.into(), source }));
    if written.is_err() {
        std::fs::remove_file(&svg_tmp).ok();
        std::fs::remove_file(&png_tmp).ok();
    }
    written.map(|()| scales)
}

/// A temporary name beside `path`, keeping its extension (plotters picks the image format by it).
fn temporary(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    let extension = path.extension().map(|e| e.to_string_lossy().to_string()).unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp.{extension}", std::process::id()))
}

/// The drawing as SVG text, with its scales in its `<metadata>`.
pub fn svg_text(subject: &Subject, source: &Path) -> Result<(String, Scales), String> {
    crate::bench::register_font();
    let layout = Layout::new(subject);
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, layout.size_px).into_drawing_area();
        render(root, subject, source, &layout)?;
    }
    let scales = layout.scales();
    let json = serde_json::to_string(&scales).map_err(|e| e.to_string())?;
    let metadata = format!("<metadata id=\"{METADATA_ID}\">{json}</metadata>\n");
    let at = text.find(">\n").map_or(text.len(), |i| i + 2);
    text.insert_str(at, &metadata);
    Ok((text, scales))
}

fn write_png(subject: &Subject, source: &Path, path: &Path) -> Result<(), DrawError> {
    crate::bench::register_font();
    let layout = Layout::new(subject);
    let root = BitMapBackend::new(path, layout.size_px).into_drawing_area();
    render(root, subject, source, &layout).map_err(|message| DrawError::Render { path: path.into(), message })
}

fn render<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    subject: &Subject,
    source: &Path,
    layout: &Layout,
) -> Drawn {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut p = Painter::new(&root);
    let title = format!("{}: the machine as pipearm reads it", subject.name());
    p.text(&title, (20, 14), &font(24, INK, (HPos::Left, VPos::Top)))?;
    let what = if subject.model().is_some() { "scenario" } else { "robot" };
    let subtitle = format!(
        "{what} {} · lengths in m, sections and pads in mm, angles in degrees · `pipearm draw` {}",
        clean_path(source),
        env!("CARGO_PKG_VERSION")
    );
    p.text(&subtitle, (20, 44), &font(14, INK, (HPos::Left, VPos::Top)))?;
    for rect in [layout.arm.rect, layout.world.rect, layout.notes] {
        let [x0, y0, x1, y1] = rect;
        p.line(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)], FRAME, 1)?;
    }
    arm_view::draw(&mut p, &layout.arm, subject)?;
    world_view::draw(&mut p, &layout.world, subject)?;
    notes::draw(&mut p, layout.notes, subject)?;
    root.present().map_err(|e| e.to_string())
}

/// A path with its `folder/..` pairs taken out, as a reader would write it.
pub(crate) fn clean_path(path: &Path) -> String {
    let mut parts: Vec<Component> = Vec::new();
    for part in path.components() {
        match (part, parts.last()) {
            (Component::ParentDir, Some(Component::Normal(_))) => {
                parts.pop();
            }
            (Component::CurDir, _) => {}
            _ => parts.push(part),
        }
    }
    parts.iter().collect::<PathBuf>().display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_is_shown_without_its_detours() {
        assert_eq!(clean_path(Path::new("scenarios/../robots/pipe_arm.urdf")), "robots/pipe_arm.urdf");
        assert_eq!(clean_path(Path::new("../robots/a.urdf")), "../robots/a.urdf");
        assert_eq!(clean_path(Path::new("./scenarios/default.toml")), "scenarios/default.toml");
    }
}
