//! The reference pages cannot go stale: every scenario key the shipped scenarios and the page's
//! own example use (defaults filled in) is in docs/reference/scenario.md, every key the page lists
//! is a field the code reads, the page's example scenario loads, every summary field a run writes
//! is in docs/reference/summary.md, and every relative link in the README and the docs resolves.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use pipearm::scenario::{Scenario, ScenarioSpec};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The dotted paths in backticks that open a Markdown table row: | `a.b[].c` | ... (not the
/// rows that open with a value, `kind = "linear"`).
fn listed_keys(page: &str) -> BTreeSet<String> {
    let key_like = |k: &&str| k.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || "_.[]".contains(c));
    page.lines()
        .filter_map(|l| l.trim_start().strip_prefix("| `"))
        .filter_map(|rest| rest.split_once('`').map(|(key, _)| key))
        .filter(key_like)
        .map(str::to_string)
        .collect()
}

/// Every key path of a TOML or JSON value, arrays as `[]` (tables in arrays included).
fn key_paths(value: &serde_json::Value, prefix: &str, out: &mut BTreeSet<String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                out.insert(path.clone());
                key_paths(v, &path, out);
            }
        }
        serde_json::Value::Array(items) => {
            for item in items.iter().filter(|i| i.is_object()) {
                key_paths(item, &format!("{prefix}[]"), out);
            }
        }
        _ => {}
    }
}

fn paths_of(value: impl serde::Serialize) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    key_paths(&serde_json::to_value(value).unwrap(), "", &mut out);
    out
}

/// Every scenario file shipped: scenarios/*.toml and the seed's families.
fn shipped_scenarios() -> Vec<PathBuf> {
    let mut files = pipearm::scenario::scenario_files(&root().join("scenarios")).unwrap();
    for family in std::fs::read_dir(root().join("scenarios/seed")).unwrap() {
        files.extend(pipearm::scenario::scenario_files(&family.unwrap().path()).unwrap());
    }
    files
}

/// The last ```toml block of a page.
fn example(page: &str) -> String {
    let start = page.rfind("```toml").expect("the page ends with an example scenario") + "```toml".len();
    page[start..].split("```").next().unwrap().to_string()
}

#[test]
fn the_scenario_reference_lists_every_key_and_only_keys_the_code_reads() {
    let page = read("docs/reference/scenario.md");
    let listed = listed_keys(&page);
    // The example loads, as written beside the shipped robots.
    let text = example(&page).replace("../robots/", &format!("{}/robots/", root().display()));
    let spec: ScenarioSpec = toml::from_str(&text).unwrap_or_else(|e| panic!("the page's example: {e}"));
    let example_path = root().join("scenarios/reference-example.toml");
    Scenario::from_spec(&example_path, spec.clone()).unwrap_or_else(|e| panic!("the page's example: {e}"));
    let mut used = paths_of(&spec);
    for path in shipped_scenarios() {
        used.extend(paths_of(Scenario::read_spec(&path).unwrap()));
    }
    // Array-of-table parents (`dampeners`) are listed by their keys.
    let missing: Vec<&String> = used
        .iter()
        .filter(|k| {
            !listed.contains(*k)
                && !listed.iter().any(|l| l.starts_with(&format!("{k}.")) || l.starts_with(&format!("{k}[]")))
        })
        .collect();
    assert!(missing.is_empty(), "keys the scenarios use that docs/reference/scenario.md does not list: {missing:?}");
    // A listed key's last name is a field or a serde name the code has.
    let source = rust_sources();
    let stale: Vec<&String> = listed
        .iter()
        .filter(|k| {
            let leaf = k.rsplit('.').next().unwrap().trim_end_matches("[]");
            !source.contains(&format!("{leaf}:")) && !source.contains(&format!("\"{leaf}\""))
        })
        .collect();
    assert!(stale.is_empty(), "keys docs/reference/scenario.md lists that no code reads: {stale:?}");
}

#[test]
fn the_summary_reference_lists_every_field_a_run_writes() {
    let listed = listed_keys(&read("docs/reference/summary.md"));
    let mut written = BTreeSet::new();
    for name in ["default", "string_strike", "friction_clamp", "hydraulic"] {
        let model = Scenario::load(&root().join(format!("scenarios/{name}.toml"))).unwrap().model;
        let (summary, _) = pipearm::run::run(&model, None).unwrap();
        written.extend(paths_of(&summary));
    }
    let missing: Vec<&String> = written.iter().filter(|k| !listed.contains(*k)).collect();
    assert!(missing.is_empty(), "summary fields docs/reference/summary.md does not list: {missing:?}");
    let stale: Vec<&String> = listed.iter().filter(|k| !written.contains(*k)).collect();
    println!("listed but not written by these four runs (optional fields): {stale:?}");
}

/// Every file under `dir` whose name ends with `.{ext}`.
fn files_under(dir: PathBuf, ext: &str) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == ext) {
                files.push(path);
            }
        }
    }
    files
}

fn rust_sources() -> String {
    files_under(root().join("src"), "rs").into_iter().map(|p| std::fs::read_to_string(p).unwrap()).collect()
}

/// Every Markdown file of the README and docs/.
fn markdown_files() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md"), root().join("robots/README.md")];
    files.extend(files_under(root().join("docs"), "md"));
    files
}

#[test]
fn every_relative_link_in_the_readme_and_the_docs_resolves() {
    let mut broken = Vec::new();
    for file in markdown_files() {
        let text = std::fs::read_to_string(&file).unwrap();
        let mut rest = text.as_str();
        while let Some(at) = rest.find("](") {
            rest = &rest[at + 2..];
            let Some(end) = rest.find(')') else { break };
            let target = &rest[..end];
            let path = target.split('#').next().unwrap().trim();
            let external = path.contains("://") || path.starts_with("mailto:");
            if !external && !path.is_empty() && !file.parent().unwrap().join(path).exists() {
                broken.push(format!("{}: {target}", file.strip_prefix(root()).unwrap().display()));
            }
        }
    }
    assert!(broken.is_empty(), "links that do not resolve: {broken:#?}");
}
