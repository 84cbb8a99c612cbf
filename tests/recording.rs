//! A recording read back with rerun's own decoder: the entities are there, and the stored
//! contact-force series peaks exactly at the summary's peak force.

use std::collections::BTreeSet;
use std::path::Path;

use pipearm::record::{TIP_DEFLECTION_ENTITY, force_entity, write_recording};
use pipearm::run::{RunOptions, run_with};
use pipearm::scenario::Scenario;

/// Every entity path of the recording store, and the scalars of `wanted`.
fn read_back(path: &Path, wanted: &str) -> (BTreeSet<String>, Vec<f64>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut paths = BTreeSet::new();
    let mut values = Vec::new();
    for msg in re_log_encoding::DecoderApp::decode_eager(file).unwrap() {
        let re_log_types::LogMsg::ArrowMsg(store, arrow) = msg.unwrap() else { continue };
        if store.kind() != re_log_types::StoreKind::Recording {
            continue;
        }
        let chunk = re_chunk::Chunk::from_arrow_msg(&arrow).unwrap();
        let entity = chunk.entity_path().to_string();
        let entity = entity.trim_start_matches('/').to_string();
        if entity == wanted {
            let components: Vec<_> = chunk.component_descriptors().map(|d| d.component).collect();
            for component in components.into_iter().filter(|c| c.as_str().contains("scalars")) {
                for slice in chunk.iter_slices::<f64>(component) {
                    values.extend_from_slice(slice);
                }
            }
        }
        paths.insert(entity);
    }
    (paths, values)
}

#[test]
fn the_recording_holds_the_scene_and_the_exact_peak_force() {
    let scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    let options = RunOptions { capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_with(&scenario, &options).unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-recording-{}.rrd", std::process::id()));
    write_recording(&path, &summary, &series, &["vertical_stop".to_string()]).unwrap();
    let force = force_entity("vertical_stop");
    let (paths, forces) = read_back(&path, &force);
    std::fs::remove_file(&path).ok();
    for entity in [
        force.as_str(),
        TIP_DEFLECTION_ENTITY,
        "plots/drive_torque",
        "world/arm",
        "world/hub",
        "world/hand",
        "world/string",
        "world/pads",
        "events",
        "summary",
    ] {
        assert!(paths.contains(entity), "{entity} missing from {paths:?}");
    }
    assert!(paths.iter().any(|p| p.starts_with("world/centreline_x")), "{paths:?}");
    let peak = forces.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(peak, summary.pairs[0].peak_force_n, "stored peak vs summary peak");
    // Decimation kept fewer rows than steps, but every step in contact, plus each impact's
    // interpolated peak between its steps.
    let in_contact = series.pad_force_n[0].iter().filter(|f| **f > 0.0).count();
    let interpolated = summary.pairs[0].impacts.iter().filter(|i| i.peak_force_n != i.peak_sample_n).count();
    assert!(interpolated > 0, "the default scene's peaks fall between steps");
    let stored_in_contact = forces.iter().filter(|f| **f > 0.0).count();
    assert!(forces.len() < series.t_s.len() && stored_in_contact == in_contact + interpolated, "{stored_in_contact}");
}
