//! The code's seams, kept: data flows one way (scenario file → model → step loop), so the
//! physics modules never import the scenario file's module; no two source files import each
//! other, directly or round a cycle; no source file grows past 700 lines; the run takes its arm
//! compiled.
//!
//! The import graph is read from the source text: an edge for every `crate::m` path (to the
//! top-level module `m`) and every `super::f` path from a file in a module's folder (to its
//! sibling file `f`), comments and string literals left out.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()) {
        if entry.is_dir() {
            out.extend(rust_files(&entry));
        } else if entry.extension().is_some_and(|x| x == "rs") {
            out.push(entry);
        }
    }
    out.sort();
    out
}

/// The text without comments and string or char literals (their quotes kept empty).
fn code_of(text: &str) -> String {
    let bytes = text.as_bytes();
    let (mut out, mut i) = (String::with_capacity(text.len()), 0);
    while i < bytes.len() {
        let rest = &text[i..];
        if rest.starts_with("//") {
            i += rest.find('\n').unwrap_or(rest.len());
        } else if rest.starts_with("/*") {
            i += rest.find("*/").map_or(rest.len(), |j| j + 2);
        } else if bytes[i] == b'"' {
            let mut j = i + 1;
            while j < bytes.len() && bytes[j] != b'"' {
                j += if bytes[j] == b'\\' { 2 } else { 1 };
            }
            out.push_str("\"\"");
            i = j + 1;
        } else if rest.starts_with("'\\") || (rest.len() > 2 && bytes[i] == b'\'' && bytes[i + 2] == b'\'') {
            // A char literal ('x', '\n', '\''); a lifetime ('a) has no closing quote there.
            let end = rest[1..].find('\'').map_or(1, |j| j + 2);
            out.push_str("' '");
            i += end.max(3).min(rest.len());
        } else {
            let c = rest.chars().next().unwrap();
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// The identifiers that follow `prefix` in `code` (`crate::` → the top modules named).
fn names_after<'a>(code: &'a str, prefix: &str) -> Vec<&'a str> {
    let mut out = Vec::new();
    for (at, _) in code.match_indices(prefix) {
        if code[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[at + prefix.len()..];
        let rest = rest.trim_start_matches('{').trim_start();
        let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
        out.push(&rest[..end]);
        // `use crate::{a, b::c}`: each name of the group.
        if code[at + prefix.len()..].starts_with('{') {
            let group = &code[at + prefix.len() + 1..];
            let group = &group[..group.find('}').unwrap_or(group.len())];
            out.extend(group.split(',').filter_map(|item| item.trim().split("::").next()));
        }
    }
    out
}

/// The file of module path `module` (`["scene", "pads"]`), if there is one.
fn file_of(root: &Path, module: &[&str]) -> Option<PathBuf> {
    let joined: PathBuf = module.iter().collect();
    [root.join(&joined).with_extension("rs"), root.join(&joined).join("mod.rs")].into_iter().find(|p| p.exists())
}

/// File → files it imports (relative to `src/`), main.rs left out (a crate of its own).
fn import_graph() -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let root = src();
    let mut graph = BTreeMap::new();
    for file in rust_files(&root).into_iter().filter(|f| !f.ends_with("main.rs")) {
        let code = code_of(&std::fs::read_to_string(&file).unwrap());
        let rel = file.strip_prefix(&root).unwrap().to_path_buf();
        let mut targets = BTreeSet::new();
        for name in names_after(&code, "crate::") {
            targets.extend(file_of(&root, &[name]));
        }
        // `super::x` from a file in a module's folder names a sibling; from a mod.rs, the parent.
        let folder = rel.parent().unwrap_or(Path::new("")).to_path_buf();
        if !rel.ends_with("mod.rs") && folder != Path::new("") {
            let parts: Vec<&str> = folder.iter().map(|p| p.to_str().unwrap()).collect();
            for name in names_after(&code, "super::") {
                targets.extend(file_of(&root, &[&parts[..], &[name]].concat()));
            }
        }
        let targets = targets.into_iter().map(|t| t.strip_prefix(&root).unwrap().to_path_buf());
        graph.insert(rel.clone(), targets.filter(|t| *t != rel).collect());
    }
    graph
}

/// A cycle of the graph, if it has one (depth-first search).
fn find_cycle(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Option<Vec<PathBuf>> {
    fn visit(
        node: &PathBuf,
        graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        path: &mut Vec<PathBuf>,
        done: &mut BTreeSet<PathBuf>,
    ) -> Option<Vec<PathBuf>> {
        if let Some(at) = path.iter().position(|p| p == node) {
            return Some(path[at..].to_vec());
        }
        if !done.insert(node.clone()) {
            return None;
        }
        path.push(node.clone());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(next, graph, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(node, graph, &mut Vec::new(), &mut done))
}

#[test]
fn the_reader_finds_imports_in_code_and_not_in_comments() {
    let code =
        code_of("use crate::{arm::Fidelity, model};\n// crate::scenario\nlet s = \"crate::run\"; crate::select::f();");
    assert_eq!(names_after(&code, "crate::"), vec!["arm", "arm", "model", "select"]);
    let mut graph = BTreeMap::new();
    let (a, b) = (PathBuf::from("a.rs"), PathBuf::from("b.rs"));
    graph.insert(a.clone(), BTreeSet::from([b.clone()]));
    graph.insert(b.clone(), BTreeSet::new());
    assert_eq!(find_cycle(&graph), None);
    graph.get_mut(&b).unwrap().insert(a.clone());
    assert_eq!(find_cycle(&graph), Some(vec![a, b]));
}

#[test]
fn no_physics_module_imports_the_scenario_file() {
    let graph = import_graph();
    let scenario = PathBuf::from("scenario.rs");
    let lower = ["scene", "select.rs", "arm", "beam", "drive", "contact", "integrate", "model.rs", "run.rs"];
    for (file, targets) in &graph {
        if lower.iter().any(|m| file.starts_with(m)) {
            assert!(!targets.contains(&scenario), "{} imports scenario.rs", file.display());
        }
    }
    assert!(graph.contains_key(&PathBuf::from("scene/mod.rs")), "the graph reads src/");
}

#[test]
fn no_two_source_files_import_each_other() {
    let graph = import_graph();
    let edges: usize = graph.values().map(BTreeSet::len).sum();
    assert!(edges > 50, "{edges} edges: the reader lost the imports");
    assert_eq!(find_cycle(&graph), None, "an import cycle between files");
}

#[test]
fn no_source_file_is_over_700_lines() {
    for file in rust_files(&src()) {
        let lines = std::fs::read_to_string(&file).unwrap().lines().count();
        assert!(lines <= 700, "{}: {lines} lines", file.display());
    }
}

/// Identity is typed: no source picks what to do by comparing a thing's name to a string (a
/// piece named "string", a profile named "s-curve") or by downcasting through `Any`: an enum or
/// a hook trait, which the compiler checks when a kind is added, says it instead.
#[test]
fn nothing_dispatches_on_a_name_string_or_downcasts() {
    let forbidden = [".name() == \"\"", ".name == \"\"", "as_any", "downcast", "dyn Any"];
    for file in rust_files(&src()) {
        let code = code_of(&std::fs::read_to_string(&file).unwrap());
        for pattern in forbidden {
            assert!(!code.contains(pattern), "{}: `{pattern}`", file.display());
        }
    }
}

/// The run takes its arm compiled (`run::CompiledModel`, through a `compile::Compiler`, which
/// keeps what a sweep's runs share): the step loop and everything that reads its results — the
/// scene, the sensors, the sign-off, the summary's analysis, the recording and the tables — build
/// no beam or arm and solve no eigenproblem of their own, before the loop or after it; only
/// `run/compiled.rs` compiles.
#[test]
fn the_run_takes_its_arm_compiled() {
    let derived = [
        "BeamModel::new",
        ".modes()",
        "with_modes(",
        "symmetric_eigen",
        "ArmModel::new",
        "linear_poles",
        "compile_arm",
        "compiler.beam",
        "compiler.arm",
    ];
    let after_compile = ["run.rs", "run", "scene", "sensor", "stress", "record", "export.rs", "analysis.rs"];
    let mut read = 0;
    for file in rust_files(&src()) {
        let rel = file.strip_prefix(src()).unwrap().to_path_buf();
        if !after_compile.iter().any(|m| rel.starts_with(m)) || rel.ends_with("run/compiled.rs") {
            continue;
        }
        read += 1;
        let code = code_of(&std::fs::read_to_string(&file).unwrap());
        for pattern in derived {
            assert!(!code.contains(pattern), "{}: `{pattern}`", rel.display());
        }
    }
    assert!(read > 20, "{read} files read: the list lost its modules");
}

/// Reading a scenario checks its file and resolves its model; what needs the arm's modes — the
/// shaper's default tuning, the arm at its fidelity, the closed loop's poles — is its compile's
/// (`scenario/compile.rs`, through `run::CompiledModel`, and the loop's advice it asks for):
/// the reader solves no eigenproblem, reduces no arm and simulates nothing.
#[test]
fn reading_a_scenario_solves_no_eigenproblem() {
    let derived = [
        "symmetric_eigen",
        "eigenvalues",
        ".modes()",
        "with_modes(",
        "ArmModel::new",
        "ArmSimulation",
        "linear_poles",
        "linearised",
        "compile_arm",
        "compiler.beam",
        "compiler.arm",
        "compiler.choice",
        "CompiledModel",
        "tuning::",
        "run::",
        ".compile(",
        "select::",
        "string_fidelity",
        "arm_model(",
        "Scene::",
        "modes_spinning",
    ];
    let compiling = ["scenario/compile.rs", "scenario/loop_advice.rs"];
    let mut read = 0;
    for file in rust_files(&src()) {
        let rel = file.strip_prefix(src()).unwrap().to_path_buf();
        let reader = rel.starts_with("scenario.rs") || rel.starts_with("scenario");
        if !reader || compiling.iter().any(|c| rel.ends_with(c)) {
            continue;
        }
        read += 1;
        let code = code_of(&std::fs::read_to_string(&file).unwrap());
        for pattern in derived {
            assert!(!code.contains(pattern), "{}: `{pattern}`", rel.display());
        }
    }
    assert!(read >= 10, "{read} files read: the list lost the reader's modules");
}

#[test]
fn the_dispatch_check_sees_through_formatting_but_not_into_comments() {
    let code = code_of("if piece.name == \"string\" { } // x.as_any()\n");
    assert!(code.contains(".name == \"\"") && !code.contains("as_any"));
}

/// A run's channels are declared once, by their producers (`pipearm::channel`): a plot's entity
/// path is spelled in their declarations, and otherwise only where the recording arranges its
/// views (`record/layout.rs`) and draws the sign-off's own figures (`record/stress.rs`) — not
/// by the recording's writer, the tables, `compare` or `fit`, which read the declarations.
#[test]
fn plot_entities_are_spelled_only_where_channels_are_declared() {
    let declaring = [
        "actuator/channels.rs",
        "arm/channels.rs",
        "scene/pair.rs",
        "sensor/mod.rs",
        "sensor/string.rs",
        "stress/channels.rs",
        "record/layout.rs",
        "record/stress.rs",
    ];
    let root = src();
    let mut spelling = Vec::new();
    for file in rust_files(&root) {
        if std::fs::read_to_string(&file).unwrap().contains("\"plots/") {
            spelling.push(file.strip_prefix(&root).unwrap().to_string_lossy().into_owned());
        }
    }
    assert!(spelling.len() >= 6, "{spelling:?}: the reader lost the declarations");
    let stray: Vec<&String> = spelling.iter().filter(|f| !declaring.contains(&f.as_str())).collect();
    assert!(stray.is_empty(), "plot entities spelled outside the channels' declarations: {stray:?}");
}
