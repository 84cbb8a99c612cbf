//! `pipearm draw` as a user meets it: every shipped scenario and robot draws to a valid SVG and
//! PNG of the same size; the drawing names what the scenario declares and puts it where the
//! scenario and the URDF say (read through the library, turned into pixels by the scales the SVG
//! states); bad input fails with the library's error and writes nothing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use pipearm::draw::{METADATA_ID, Scales};
use pipearm::model::Model;
use pipearm::robot::{Robot, load_robot};
use pipearm::scenario::Scenario;

fn pipearm_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pipearm")).args(args).current_dir(dir).output().expect("pipearm runs")
}

fn pipearm(args: &[&str]) -> Output {
    pipearm_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pipearm-draw-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The shipped files with `extension` in `folder`, sorted.
fn shipped(folder: &str, extension: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == extension))
        .collect();
    files.sort();
    files
}

/// A drawing as written: its SVG text and scales, checked against its PNG.
struct Drawing {
    svg: String,
    scales: Scales,
}

impl Drawing {
    /// Draws `input` into `out` (an .svg path) and reads both files back.
    fn of(input: &Path, out: &Path) -> Self {
        let output = pipearm(&["draw", input.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{}: {stderr}", input.display());
        let svg = std::fs::read_to_string(out).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{}: not XML: {e}", out.display()));
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        let size: [u32; 2] = ["width", "height"].map(|a| root.attribute(a).unwrap().parse().unwrap());
        let metadata = doc.descendants().find(|n| n.attribute("id") == Some(METADATA_ID)).expect("the scales");
        let scales: Scales = serde_json::from_str(metadata.text().unwrap()).expect("JSON scales");
        assert_eq!(scales.size_px, size);
        let png = std::fs::read(out.with_extension("png")).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{}: not a PNG", out.display());
        assert_eq!(&png[12..16], b"IHDR");
        let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
        assert_eq!([be(16), be(20)], size, "the PNG and the SVG are the same size");
        assert!(png.len() > 20_000, "{} bytes: the PNG holds a drawing", png.len());
        Drawing { svg, scales }
    }

    fn texts(&self) -> Vec<String> {
        let doc = roxmltree::Document::parse(&self.svg).unwrap();
        doc.descendants().filter(|n| n.has_tag_name("text")).filter_map(|n| n.text().map(str::to_string)).collect()
    }

    fn has_text(&self, needle: &str) -> bool {
        self.texts().iter().any(|t| t.contains(needle))
    }

    /// Every `<rect>` as [x0, y0, x1, y1], px.
    fn rects(&self) -> Vec<[f64; 4]> {
        let doc = roxmltree::Document::parse(&self.svg).unwrap();
        doc.descendants()
            .filter(|n| n.has_tag_name("rect"))
            .map(|n| {
                let [x, y, w, h] =
                    ["x", "y", "width", "height"].map(|a| n.attribute(a).unwrap().parse::<f64>().unwrap());
                [x, y, x + w, y + h]
            })
            .collect()
    }

    /// Every `<polygon>`'s bounds [x0, y0, x1, y1], px.
    fn polygons(&self) -> Vec<[f64; 4]> {
        let doc = roxmltree::Document::parse(&self.svg).unwrap();
        doc.descendants()
            .filter(|n| n.has_tag_name("polygon"))
            .map(|n| {
                let points = n.attribute("points").unwrap().split_whitespace().map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    [x.parse::<f64>().unwrap(), y.parse::<f64>().unwrap()]
                });
                points.fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |b, [x, y]| {
                    [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]
                })
            })
            .collect()
    }
}

/// A pixel of a panel, unrounded.
fn px(view: &pipearm::draw::View, [x, y]: [f64; 2]) -> [f64; 2] {
    [view.origin_px[0] + x * view.px_per_m, view.origin_px[1] - y * view.px_per_m]
}

/// Pixels are whole: a drawn edge is within a pixel of where its metres put it.
fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1.01
}

fn assert_robot(drawing: &Drawing, robot: &Robot, what: &str) {
    let length = robot.arm.length_m();
    assert!(
        drawing.has_text(&format!("arm length {length:.3} m")),
        "{what}: the arm's length {length} m as a dimension"
    );
    for body in &robot.carried {
        assert!(drawing.has_text(&body.name), "{what}: body {} labelled", body.name);
    }
    // The arm itself: a rect from the pivot to its length, at its tip section's depth.
    let v = &drawing.scales.arm_frame;
    let half = 0.5 * robot.arm.depth_m();
    let [x0, y0] = px(v, [0.0, half]);
    let [x1, y1] = px(v, [length, -half]);
    let arm = drawing.rects().into_iter().any(|r| near(r[0], x0) && near(r[2], x1) && near(r[1], y0) && near(r[3], y1));
    assert!(arm, "{what}: the arm from 0 to {length} m, {} m deep, in panel 1", 2.0 * half);
}

fn assert_scene(drawing: &Drawing, model: &Model, what: &str) {
    let v = &drawing.scales.arm_frame;
    let depth = model.robot.arm.depth_m();
    for d in &model.dampeners {
        assert!(drawing.has_text(&d.name), "{what}: pad {} labelled", d.name);
        // Its face `gap_m` off the arm's face on its side, centred on its station.
        let face_y = d.face.sign() * (0.5 * depth + d.gap_m);
        let [cx, face] = px(v, [d.station_m, face_y]);
        let found = drawing.rects().into_iter().any(|r| {
            let on_face = if d.face.sign() > 0.0 { near(r[3], face) } else { near(r[1], face) };
            near(0.5 * (r[0] + r[2]), cx) && on_face && r[2] - r[0] >= 4.0
        });
        assert!(found, "{what}: pad {} at station {} m on its face in panel 1", d.name, d.station_m);
    }
    for s in &model.structures {
        assert!(drawing.has_text(&s.name), "{what}: structure {} labelled", s.name);
        if let pipearm::model::StructureShape::Box { half_extents_m: [hx, hy, _] } = s.shape {
            let [x, y, _] = s.position_m;
            let w = &drawing.scales.lift_plane;
            let [a0, a1] = [px(w, [x - hx, y + hy]), px(w, [x + hx, y - hy])];
            let found = drawing
                .polygons()
                .into_iter()
                .any(|b| near(b[0], a0[0]) && near(b[1], a0[1]) && near(b[2], a1[0]) && near(b[3], a1[1]));
            assert!(found || s.angle_rad != 0.0, "{what}: structure {} where the scenario puts it", s.name);
        }
    }
    if let Some(held) = model.payload.string() {
        let robot = &model.robot;
        let first = &held.grips[0];
        // Its inner end: the first hand's station (URDF) less where that hand grips it (scenario).
        let start = robot.body(&first.hand).unwrap().station_m - first.at_m;
        let end = start + held.pipe.length_m;
        let [x0, _] = px(v, [start, 0.0]);
        let [x1, _] = px(v, [end, 0.0]);
        assert!(
            drawing.rects().into_iter().any(|r| near(r[0], x0) && near(r[2], x1)),
            "{what}: the string from {start} to {end} m in panel 1"
        );
        assert!(drawing.has_text(&format!("string {:.3} m", held.pipe.length_m)), "{what}: the string's length");
        assert!(drawing.has_text(&format!("overhang {:.3} m", first.at_m)), "{what}: its inner overhang");
        for g in &held.grips {
            assert!(drawing.has_text(&format!("{} (grip", g.hand)), "{what}: hand {} labelled", g.hand);
        }
    }
    let lift = format!("θ: {}° → {}°", trim(model.drive.motion.start_rad()), trim(model.drive.motion.end_rad()));
    assert!(drawing.has_text(&lift), "{what}: the lift angle's sense, {lift}");
}

/// Degrees as the drawing writes them: to 0.1°, no trailing zeros.
fn trim(angle_rad: f64) -> String {
    let text = format!("{:.1}", angle_rad.to_degrees());
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[test]
fn every_shipped_scenario_is_drawn_where_it_says() {
    let out = scratch("scenarios");
    let scenarios = shipped("scenarios", "toml");
    assert!(scenarios.len() >= 10, "{} scenarios", scenarios.len());
    for path in &scenarios {
        let what = path.file_name().unwrap().to_string_lossy().to_string();
        let drawing = Drawing::of(path, &out.join(format!("{what}.svg")));
        let scenario = Scenario::load(path).unwrap();
        assert_robot(&drawing, &scenario.model.robot, &what);
        assert_scene(&drawing, &scenario.model, &what);
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn every_shipped_robot_is_drawn_alone() {
    let out = scratch("robots");
    let robots = shipped("robots", "urdf");
    assert!(robots.len() >= 5);
    for path in &robots {
        let what = path.file_name().unwrap().to_string_lossy().to_string();
        let drawing = Drawing::of(path, &out.join(format!("{what}.svg")));
        let robot = load_robot(path).unwrap();
        assert_robot(&drawing, &robot, &what);
        assert!(drawing.has_text(&format!("joint `{}` limits", robot.lift.name)), "{what}: the joint's limits");
        assert!(!drawing.has_text("pad "), "{what}: a robot alone has no scene");
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn the_default_drawing_goes_beside_the_recordings_under_the_scenarios_name() {
    let dir = scratch("default");
    for (from, to) in
        [("scenarios/default.toml", "scenarios/default.toml"), ("robots/pipe_arm.urdf", "robots/pipe_arm.urdf")]
    {
        std::fs::create_dir_all(dir.join(to).parent().unwrap()).unwrap();
        std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join(from), dir.join(to)).unwrap();
    }
    let output = pipearm_in(&dir, &["draw"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("recordings/default.machine.svg"), "{stdout}");
    assert!(dir.join("recordings/default.machine.svg").is_file());
    assert!(dir.join("recordings/default.machine.png").is_file());
    let output = pipearm_in(&dir, &["draw", "robots/pipe_arm.urdf"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(dir.join("recordings/pipe_arm.machine.svg").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

/// The files in `dir`, by name.
fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect();
    names.sort();
    names
}

#[test]
fn bad_input_fails_with_the_librarys_error_and_writes_nothing() {
    let dir = scratch("bad");
    let out = dir.join("out/x.svg");
    let out = out.to_str().unwrap();
    let missing = pipearm(&["draw", "scenarios/no_such.toml", "--out", out]);
    let stderr = String::from_utf8_lossy(&missing.stderr);
    assert!(!missing.status.success());
    assert!(stderr.contains("scenarios/no_such.toml: cannot read"), "{stderr}");
    let urdf = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/pipe_arm.urdf")).unwrap();
    let broken = dir.join("broken.urdf");
    std::fs::write(&broken, urdf.replace("wall_m=", "wal_m=")).unwrap();
    let bad = pipearm(&["draw", broken.to_str().unwrap(), "--out", out]);
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(!bad.status.success());
    assert!(stderr.contains("broken.urdf") && stderr.contains("wal_m") && stderr.contains("allowed"), "{stderr}");
    let not_svg = pipearm(&["draw", "--out", dir.join("x.png").to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&not_svg.stderr);
    assert!(!not_svg.status.success() && stderr.contains("ending in .svg"), "{stderr}");
    assert_eq!(files_in(&dir), vec!["broken.urdf"], "nothing written");
    std::fs::remove_dir_all(&dir).ok();
}
