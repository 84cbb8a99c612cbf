//! A recording read back with rerun's own decoder: the entities are there, and the stored
//! contact-force series peaks exactly at the summary's peak force.

use std::collections::BTreeSet;
use std::path::Path;

use pipearm::record::{
    ActuatorViews, BlueprintInAdvance, CENTRELINE_ENTITY, Ending, LEGEND_ENTITY, MODAL_ENTITY, PEAK_ENTITY,
    PIECES_ENTITY, PINS_ENTITY, Recorded, RunViews, TIP_DEFLECTION_ENTITY, WORST_STATION_ENTITY, YIELD_DRAWN_FROM,
    YIELD_ENTITY, force_entity, save_recording, write_recording,
};
use pipearm::run::{CompiledModel, RunOptions, run_compiled, run_with};
use pipearm::scenario::Scenario;

/// The recording store's chunks in `path`, in the order of the file, each with its entity path
/// (without the leading `/`).
fn recording_chunks(path: &Path) -> Vec<(String, re_chunk::Chunk)> {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut chunks = Vec::new();
    for msg in re_log_encoding::DecoderApp::decode_eager(file).unwrap() {
        let re_log_types::LogMsg::ArrowMsg(store, arrow) = msg.unwrap() else { continue };
        if store.kind() == re_log_types::StoreKind::Recording {
            let chunk = re_chunk::Chunk::from_arrow_msg(&arrow).unwrap();
            chunks.push((chunk.entity_path().to_string().trim_start_matches('/').to_string(), chunk));
        }
    }
    chunks
}

/// Every entity path of the recording store, and the scalars of `wanted` with their `sim_time`
/// (s), one scalar per row.
fn read_back(path: &Path, wanted: &str) -> (BTreeSet<String>, Vec<f64>, Vec<f64>) {
    let mut paths = BTreeSet::new();
    let mut values = Vec::new();
    let mut times = Vec::new();
    for (entity, chunk) in recording_chunks(path) {
        let timeline = chunk.timelines().values().find(|t| t.timeline().name().as_str() == "sim_time");
        // A static chunk (a series' style) has no times and no scalars.
        if let (true, Some(timeline)) = (entity == wanted, timeline) {
            let components: Vec<_> = chunk.component_descriptors().map(|d| d.component).collect();
            times.extend(timeline.times_raw().iter().map(|ns| *ns as f64 * 1e-9));
            for component in components.into_iter().filter(|c| c.as_str().contains("scalars")) {
                for slice in chunk.iter_slices::<f64>(component) {
                    values.extend_from_slice(slice);
                }
            }
        }
        paths.insert(entity);
    }
    (paths, values, times)
}

/// The trace names of `wanted`'s series, in the chunk of its values: those of its first row, and
/// how many rows after it are null (no data: the viewer keeps the first row's names).
fn trace_names(path: &Path, wanted: &str) -> (Vec<String>, usize) {
    use arrow::array::Array;
    for (entity, chunk) in recording_chunks(path) {
        let names = chunk.component_descriptors().map(|d| d.component).find(|c| c.as_str() == "SeriesLines:names");
        let (true, Some(names)) = (entity == wanted, names) else { continue };
        let first: Vec<String> =
            chunk.iter_slices::<String>(names).next().unwrap().iter().map(|s| s.to_string()).collect();
        let column = chunk.components().get_array(names).unwrap();
        return (first, (1..column.len()).filter(|&row| column.is_null(row)).count());
    }
    panic!("no names for {wanted}")
}

#[test]
fn the_recording_holds_the_scene_and_the_exact_peak_force() {
    let scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    let options = RunOptions { capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_with(&scenario.model, &options).unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-recording-{}.rrd", std::process::id()));
    write_recording(&path, &summary, &series).unwrap();
    let force = force_entity("vertical_stop");
    let (paths, forces, times) = read_back(&path, &force);
    assert_eq!(forces.len(), times.len(), "one scalar per row");
    // The elastic coordinates share one entity, a row per kept step holding every q in order.
    let (_, q, q_times) = read_back(&path, MODAL_ENTITY);
    let n = series.modal_dofs;
    let kept: Vec<usize> = (0..series.t_s.len()).filter(|&k| series.keep[k]).collect();
    assert!(n > 1 && q_times.len() == kept.len(), "{n} coordinates, {} rows", q_times.len());
    let want: Vec<f64> = kept.iter().flat_map(|&k| series.modal_q[k * n..(k + 1) * n].iter().copied()).collect();
    assert_eq!(q, want, "the kept steps' coordinates, q1 first");
    let names: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
    assert_eq!(trace_names(&path, MODAL_ENTITY), (names, kept.len() - 1), "the names at the first row only");
    std::fs::remove_file(&path).ok();
    for entity in [
        force.as_str(),
        TIP_DEFLECTION_ENTITY,
        "plots/drive_torque",
        PIECES_ENTITY,
        "world/string",
        "world/pads",
        "events",
        "summary",
    ] {
        assert!(paths.contains(entity), "{entity} missing from {paths:?}");
    }
    // Fixed paths (the display scales are in the events), so layouts hold between runs.
    for entity in ["world/centreline", "world/contact_force"] {
        assert!(paths.contains(entity), "{entity} missing from {paths:?}");
    }
    let peak = forces.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(peak, summary.pairs[0].peak_force_n, "stored peak vs summary peak");
    // Decimation kept fewer rows than steps, but a plot of the kept rows, joined by straight
    // lines, passes within 2 % of the peak of every step's force, impacts included.
    assert!(forces.len() < series.t_s.len());
    let interpolated = summary.pairs[0].impacts.iter().filter(|i| i.peak_force_n != i.peak_sample_n).count();
    assert!(interpolated > 0, "the default scene's peaks fall between steps");
    let stored: Vec<(f64, f64)> = times.iter().copied().zip(forces.iter().copied()).collect();
    for (t, f) in series.t_s.iter().zip(&series.pad_force_n[0]) {
        let after = stored.partition_point(|(ts, _)| ts < t).min(stored.len() - 1);
        let before = after.saturating_sub(1);
        let ((t0, f0), (t1, f1)) = (stored[before], stored[after]);
        let line = if t1 > t0 { f0 + (f1 - f0) * (t - t0) / (t1 - t0) } else { f1 };
        assert!((line - f).abs() <= 0.02 * peak, "at {t} s: step {f} N, plot {line} N");
    }
}

/// The file `pipearm run` writes for the default scene (its blueprint encoded while the run
/// steps), with the run's summary.
fn as_pipearm_run_writes_it(tag: &str) -> (pipearm::run::RunSummary, Vec<u8>) {
    let scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    let options = RunOptions { capture_frames: true, ..RunOptions::default() };
    let compiled = CompiledModel::new(&scenario.model, options.fidelity, &scenario.compiler).unwrap();
    let blueprint = BlueprintInAdvance::start(&compiled, &options);
    let (summary, series) = run_compiled(&compiled, &options);
    let summary = summary.unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-{tag}-{}.rrd", std::process::id()));
    let run = Recorded { series: &series, ending: Ending::Finished(&summary), overlay: &[] };
    save_recording(&path, &run, Some(blueprint)).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).ok();
    (summary, bytes)
}

/// The file `pipearm run` writes, decoded: every message.
fn recorded_messages() -> (pipearm::run::RunSummary, Vec<re_log_types::LogMsg>) {
    let (summary, bytes) = as_pipearm_run_writes_it("blueprint");
    let messages = re_log_encoding::DecoderApp::decode_eager(&bytes[..]).unwrap().map(Result::unwrap).collect();
    (summary, messages)
}

#[test]
fn the_blueprint_is_complete_and_activated_and_the_events_are_timed() {
    use re_log_types::{LogMsg, StoreKind};
    let (summary, messages) = recorded_messages();
    // The stores in the order they are announced (rerun's stream may announce one twice).
    let mut stores: Vec<_> = Vec::new();
    for msg in &messages {
        if let LogMsg::SetStoreInfo(s) = msg
            && !stores.contains(&s.info.store_id)
        {
            stores.push(s.info.store_id.clone());
        }
    }
    // The blueprint first and activated, then the recording, as rerun's
    // `RecordingStreamBuilder::with_blueprint` sends them.
    assert_eq!(stores.iter().map(|s| s.kind()).collect::<Vec<_>>(), [StoreKind::Blueprint, StoreKind::Recording]);
    let activated = messages.iter().position(|m| matches!(m, LogMsg::BlueprintActivationCommand(_)));
    let activated = activated.expect("the blueprint is activated");
    let LogMsg::BlueprintActivationCommand(activation) = &messages[activated] else { unreachable!() };
    assert!(activation.blueprint_id == stores[0] && activation.make_active && activation.make_default);
    let recording_begins =
        messages.iter().position(|m| matches!(m, LogMsg::SetStoreInfo(s) if s.info.store_id == stores[1]));
    assert!(recording_begins.is_some_and(|r| r > activated), "the activation comes before the recording's store");

    // Blueprint entities: the viewport's root is a logged container; views by class.
    let mut blueprint_paths = Vec::new();
    let mut classes = Vec::new();
    let mut root = None;
    let mut events = None;
    for msg in &messages {
        let LogMsg::ArrowMsg(store, arrow) = msg else { continue };
        let chunk = re_chunk::Chunk::from_arrow_msg(arrow).unwrap();
        let entity = chunk.entity_path().to_string();
        if store.kind() == StoreKind::Blueprint {
            for descriptor in chunk.component_descriptors() {
                let column = chunk.components().get_array(descriptor.component).unwrap();
                match descriptor.component.as_str() {
                    "ViewBlueprint:class_identifier" => classes.push(format!("{column:?}")),
                    "ViewportBlueprint:root_container" => root = Some(uuid_path(column)),
                    _ => {}
                }
            }
            blueprint_paths.push(entity);
        } else if entity == "/events" {
            events = Some(chunk);
        }
    }
    let classes = classes.join(" ");
    // Contact force, tip deflection, drive torque, the held string's tip deflection, the stress at
    // the worst station and the pin loads.
    for (class, count) in [("\"3D\"", 1), ("\"TimeSeries\"", 6), ("\"TextLog\"", 1)] {
        assert_eq!(classes.matches(class).count(), count, "{class} in {classes}");
    }
    let root = root.expect("the viewport has a root container");
    assert!(blueprint_paths.contains(&format!("/container/{root}")), "root {root} not in {blueprint_paths:?}");
    assert_eq!(blueprint_paths.iter().filter(|p| p.starts_with("/container/")).count(), 2, "{blueprint_paths:?}");
    // The 3D view opens framed on the lift: its camera is set, on the one 3D view.
    let eyes = blueprint_paths.iter().filter(|p| p.starts_with("/view/") && p.ends_with("/EyeControls3D")).count();
    assert_eq!(eyes, 1, "{blueprint_paths:?}");

    // Events: on sim_time (not static, which would shadow every timed row), three per impact.
    let events = events.expect("an events chunk");
    assert!(!events.is_static(), "static events hide the timed ones in the viewer");
    let impacts: usize = summary.pairs.iter().map(|p| p.impacts.len()).sum();
    assert!(events.num_rows() >= 3 * impacts, "{} rows for {impacts} impacts", events.num_rows());
}

/// The file ends in rerun's footer, found from the file's end as rerun's readers that seek find
/// it, and it indexes every chunk of both stores where it lies in the file, as `rerun rrd verify`
/// checks (the blueprint's were encoded before the file was open).
#[test]
fn the_footer_at_the_files_end_finds_every_chunk_where_it_lies() {
    use re_log_encoding::{Decodable as _, StreamFooter, ToApplication as _};
    let (_, bytes) = as_pipearm_run_writes_it("footer");

    let stream_footer = StreamFooter::from_rrd_bytes(&bytes[bytes.len() - StreamFooter::ENCODED_SIZE_BYTES..]);
    let span = stream_footer.expect("a stream footer at the file's end").entries[0]
        .rrd_footer_byte_span_from_start_excluding_header;
    let (start, end) = (span.start as usize, (span.start + span.len) as usize);
    let footer = re_protos::log_msg::v1alpha1::RrdFooter::from_rrd_bytes(&bytes[start..end]).unwrap();
    let footer = footer.to_application(()).unwrap();
    let mut kinds: Vec<_> = footer.manifests.keys().map(|store| store.kind()).collect();
    kinds.sort_by_key(|kind| format!("{kind:?}"));
    assert_eq!(kinds, [re_log_types::StoreKind::Blueprint, re_log_types::StoreKind::Recording]);

    let mut decoded = std::collections::HashMap::new();
    for msg in re_log_encoding::DecoderApp::decode_eager(&bytes[..]).unwrap() {
        if let re_log_types::LogMsg::ArrowMsg(store, arrow) = msg.unwrap() {
            let chunk = re_chunk::Chunk::from_arrow_msg(&arrow).unwrap();
            decoded.entry(store).or_insert_with(Vec::new).push(chunk.id());
        }
    }
    for (store, manifest) in &footer.manifests {
        let ids: Vec<_> = manifest.col_chunk_id().unwrap().collect();
        assert_eq!(ids, decoded[store], "{store:?}: the footer lists the store's chunks in order");
        let spans = manifest.col_chunk_byte_offset().unwrap().zip(manifest.col_chunk_byte_size().unwrap());
        for (id, (offset, size)) in ids.iter().zip(spans) {
            let (start, end) = (offset as usize, (offset + size) as usize);
            let arrow = re_protos::log_msg::v1alpha1::ArrowMsg::from_rrd_bytes(&bytes[start..end]).unwrap();
            let chunk = re_chunk::Chunk::from_arrow_msg(&arrow.to_application(()).unwrap()).unwrap();
            assert_eq!(chunk.id(), *id, "{store:?}: the chunk at {offset}");
        }
    }
}

/// The views a run calls for are known once its model is compiled, before it steps: on shipped
/// scenes with each kind of actuator, a held string and a tilting head, the views the blueprint
/// encoded ahead of the run shows are those of the run's series.
#[test]
fn the_views_known_before_the_run_are_the_runs() {
    let scenes = ["default", "servo", "hydraulic_twin", "tilting_head", "lab"];
    let mut seen = Vec::new();
    for name in scenes {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"));
        let scenario = Scenario::load(&path).unwrap();
        for sign_off in [true, false] {
            let options = RunOptions { capture_frames: true, sign_off, ..RunOptions::default() };
            let compiled = CompiledModel::new(&scenario.model, options.fidelity, &scenario.compiler).unwrap();
            let before = RunViews::before_run(&compiled, &options);
            let (summary, series) = run_compiled(&compiled, &options);
            summary.unwrap();
            assert_eq!(before, RunViews::of(&series), "{name}, sign-off {sign_off}");
            // And they are what the run filled: the declarations hold.
            let actuator = match series.actuator.first() {
                None => ActuatorViews::None,
                Some(outputs) if outputs.cylinders.is_empty() => ActuatorViews::Tracking,
                Some(_) => ActuatorViews::TrackingAndPressures,
            };
            assert_eq!(before.actuator, actuator, "{name}");
            assert_eq!(before.string, !series.string_tip_deflection_m.is_empty(), "{name}");
            assert_eq!(before.head, !series.head_angle_rad.is_empty(), "{name}");
            assert_eq!(before.sign_off, series.stress.steps() == series.t_s.len(), "{name}");
            seen.push(before);
        }
    }
    // The scenes between them call for every kind of view.
    for actuator in [ActuatorViews::None, ActuatorViews::Tracking, ActuatorViews::TrackingAndPressures] {
        assert!(seen.iter().any(|v| v.actuator == actuator), "{actuator:?}");
    }
    assert!(seen.iter().any(|v| v.string) && seen.iter().any(|v| !v.string));
    assert!(seen.iter().any(|v| v.head) && seen.iter().any(|v| !v.head));
}

/// A run that records other views than the ones its blueprint was encoded for ahead of it (here
/// a sign-off asked for and not run, as when the guard stops a run before its sign-off is
/// complete) gets a blueprint of its own views.
#[test]
fn a_blueprint_for_views_the_run_did_not_record_is_encoded_again() {
    let scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    let asked = RunOptions { capture_frames: true, sign_off: true, ..RunOptions::default() };
    let compiled = CompiledModel::new(&scenario.model, asked.fidelity, &scenario.compiler).unwrap();
    let blueprint = BlueprintInAdvance::start(&compiled, &asked);
    let (summary, series) = run_compiled(&compiled, &RunOptions { sign_off: false, ..asked });
    let summary = summary.unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-reencoded-{}.rrd", std::process::id()));
    let run = Recorded { series: &series, ending: Ending::Finished(&summary), overlay: &[] };
    save_recording(&path, &run, Some(blueprint)).unwrap();
    let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
    let mut classes = String::new();
    for msg in re_log_encoding::DecoderApp::decode_eager(file).unwrap() {
        let re_log_types::LogMsg::ArrowMsg(store, arrow) = msg.unwrap() else { continue };
        let chunk = re_chunk::Chunk::from_arrow_msg(&arrow).unwrap();
        if store.kind() == re_log_types::StoreKind::Blueprint {
            for descriptor in
                chunk.component_descriptors().filter(|d| d.component.as_str() == "ViewBlueprint:class_identifier")
            {
                classes += &format!("{:?}", chunk.components().get_array(descriptor.component).unwrap());
            }
        }
    }
    std::fs::remove_file(&path).ok();
    // Contact force, tip deflection, drive torque and the held string's tip deflection: no stress
    // at the worst station, no pin loads.
    assert_eq!(classes.matches("\"TimeSeries\"").count(), 4, "{classes}");
}

/// The UUID of a `RootContainer` column (a list of 16 bytes), as written in blueprint paths.
fn uuid_path(column: &dyn re_chunk::external::arrow::array::Array) -> String {
    use re_chunk::external::arrow::array::AsArray;
    use re_chunk::external::arrow::datatypes::UInt8Type;
    let bytes = column.as_list::<i32>().values().as_fixed_size_list().values().as_primitive::<UInt8Type>().values();
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    format!("{}-{}-{}-{}-{}", &hex[..8], &hex[8..12], &hex[12..16], &hex[16..20], &hex[20..])
}

/// The sign-off in the recording: the worst station's stress peaks at the summary's figure (the
/// peak step is kept whatever the record rate), its yield line is the segment's yield over the
/// design factor, the pivot's force peaks at the summary's, and the centreline is shaded, marked
/// and explained by a legend.
#[test]
fn the_recording_plots_the_worst_stress_against_its_yield_and_the_pin_loads() {
    let mut scenario = Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/default.toml")).unwrap();
    // A design factor that brings the peak (a tenth of the yield as shipped) within the range
    // where the yield line is drawn.
    scenario.model.checks.stress_factor = 6.0;
    let options = RunOptions { capture_frames: true, ..RunOptions::default() };
    let (summary, series) = run_with(&scenario.model, &options).unwrap();
    let path = std::env::temp_dir().join(format!("pipearm-stress-recording-{}.rrd", std::process::id()));
    write_recording(&path, &summary, &series).unwrap();
    let sign_off = summary.sign_off.as_ref().expect("the default run signs off");
    let stress = &sign_off.stress;
    let (paths, sigma, _) = read_back(&path, WORST_STATION_ENTITY);
    let (_, tension, _) = read_back(&path, &format!("{YIELD_ENTITY}/tension"));
    let (_, pins, _) = read_back(&path, PINS_ENTITY);
    std::fs::remove_file(&path).ok();
    for entity in [CENTRELINE_ENTITY, LEGEND_ENTITY, PEAK_ENTITY, PINS_ENTITY] {
        assert!(paths.contains(entity), "{entity} missing from {paths:?}");
    }
    let utilisation = stress.utilisation.expect("the default arm has a yield strength");
    let peak = sigma.iter().map(|s| s.abs()).fold(0.0, f64::max);
    // The series holds single-precision section forces: seven digits.
    let worst = stress.segments.iter().find(|s| s.utilisation == Some(utilisation)).unwrap();
    assert!((peak - worst.peak_stress_pa).abs() <= 1e-5 * worst.peak_stress_pa, "{peak} vs {}", worst.peak_stress_pa);
    let yield_pa = worst.yield_strength_pa.unwrap() / stress.stress_factor;
    assert_eq!(tension, [yield_pa, yield_pa]);
    assert!((utilisation - peak / yield_pa).abs() <= 1e-5 * utilisation);
    assert!(utilisation >= YIELD_DRAWN_FROM, "the line is drawn from {YIELD_DRAWN_FROM} of the yield: {utilisation}");
    // The pins share one entity, a trace each in their channels' order, the pivot's first.
    let traces: Vec<_> =
        series.channels.iter().filter_map(|c| c.plot.as_ref()).filter(|p| p.entity == PINS_ENTITY).collect();
    assert_eq!(traces.first().and_then(|p| p.trace.as_deref()), Some("pivot"));
    assert!(traces.iter().any(|p| p.trace.as_deref() == Some("hand")), "{traces:?}");
    let pivot_peak = pins.iter().step_by(traces.len()).copied().fold(0.0, f64::max);
    assert!(pivot_peak <= sign_off.pins.pivot.peak_force_n * (1.0 + 1e-6));
    assert!(
        pivot_peak >= 0.9 * sign_off.pins.pivot.peak_force_n,
        "{pivot_peak} vs {}",
        sign_off.pins.pivot.peak_force_n
    );
}
