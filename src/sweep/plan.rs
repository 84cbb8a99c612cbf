//! The plan of a sweep: every case's values, its scenario (built from the base file with the
//! values set, then validated) and its hash, in index order (the last key varies fastest).

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::vary::{Vary, show};
use super::{SweepError, io_error};
use crate::robot::Robot;
use crate::scenario::{DriveSpec, Scenario, ScenarioError, ScenarioSpec};

/// What a sweep runs; written to `DIR/plan.json` by every shard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// The base scenario file, as given.
    pub scenario: PathBuf,
    /// The varied keys and their values, in the order given.
    pub vary: Vec<Vary>,
    /// Every case, by index.
    pub cases: Vec<Case>,
}

/// One case of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Case {
    /// Position in the Cartesian product, from 0.
    pub index: usize,
    /// FNV-1a 64 of the case's canonical spec and its robot file, 16 hex digits.
    pub hash: String,
    /// The value of each varied key.
    pub values: BTreeMap<String, toml::Value>,
}

impl Case {
    /// `key=value, ...` in the plan's key order, for messages and labels.
    pub fn describe(&self, keys: &[&str]) -> String {
        keys.iter()
            .map(|k| format!("{k}={}", self.values.get(*k).map(show).unwrap_or_default()))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl Plan {
    /// Builds and validates every case of `vary` over the scenario file at `path`; returns the
    /// plan and the cases' scenarios (by index). Fails on the first key, spec or robot file in
    /// index order that is bad, else on the case of lowest index that does not validate.
    ///
    /// Each robot file is read once, and the cases are checked in parallel on the current rayon
    /// pool (each builds its FE beam): for a sweep of short runs, planning one case after
    /// another, each reading its robot, was a fifth of the whole command and held its parallel
    /// efficiency under 80 % (docs/sweeps.md).
    pub fn build(path: &Path, vary: Vec<Vary>) -> Result<(Plan, Vec<Scenario>), SweepError> {
        if let Some(key) = duplicate_key(&vary) {
            return Err(SweepError::Key { key, message: "varied twice; give its values in one --vary".into() });
        }
        let rows = product(&vary);
        Self::build_cases(path, vary, rows)
    }

    /// Builds and validates the cases `rows` (each the value of every key of `vary`, in its
    /// order) over the scenario file at `path`, as [`Plan::build`] does for a product. An
    /// envelope's cases are samples, not a product: its `vary` names the keys and lists the
    /// values of the grouping key only.
    pub fn build_cases(
        path: &Path,
        vary: Vec<Vary>,
        rows: Vec<Vec<(String, toml::Value)>>,
    ) -> Result<(Plan, Vec<Scenario>), SweepError> {
        let keys: Vec<&str> = vary.iter().map(|v| v.key.as_str()).collect();
        let base = base_document(path, keys.iter().copied())?;
        // Each robot file once: the robot, and the file's bytes for the cases' hashes.
        let mut robots: HashMap<PathBuf, (Robot, Vec<u8>)> = HashMap::new();
        let mut specs = Vec::new();
        for (index, values) in rows.into_iter().enumerate() {
            let case = Case { index, hash: String::new(), values: values.iter().cloned().collect() };
            let spec = case_spec(path, &base, &values, &case, &keys)?;
            let robot_path = Scenario::robot_path(path, &spec);
            if !robots.contains_key(&robot_path) {
                let robot = Scenario::load_robot(path, &spec).map_err(|e| case_error(&case, &keys, e))?;
                let bytes = std::fs::read(&robot_path).map_err(|source| {
                    case_error(&case, &keys, ScenarioError::Io { path: robot_path.clone(), source })
                })?;
                robots.insert(robot_path.clone(), (robot, bytes));
            }
            specs.push((case, spec, robot_path));
        }
        // One compiler for every case: what a case's compile derives, the other cases take
        // where their keys leave it as it was.
        let compiler = std::sync::Arc::new(crate::compile::Compiler::new());
        let checked: Vec<Result<(Case, Scenario), SweepError>> = specs
            .into_par_iter()
            .map(|(mut case, spec, robot_path)| {
                let (robot, robot_bytes) = &robots[&robot_path];
                let checked = Scenario::from_spec_and_robot_sharing(path, spec, robot.clone(), &compiler)
                    .and_then(|scenario| Ok((case_hash(&scenario, robot_bytes)?, scenario)));
                let (hash, scenario) = checked.map_err(|e| case_error(&case, &keys, e))?;
                case.hash = hash;
                Ok((case, scenario))
            })
            .collect();
        let (cases, scenarios) = checked.into_iter().collect::<Result<Vec<_>, _>>()?.into_iter().unzip();
        Ok((Plan { scenario: path.into(), vary, cases }, scenarios))
    }

    /// The varied keys, in the order given.
    pub fn keys(&self) -> Vec<&str> {
        self.vary.iter().map(|v| v.key.as_str()).collect()
    }
}

/// The scenario file at `path` as a document in which `keys` can be set: the arm's damping
/// ratios made explicit where a key sets one of them ([`explicit_damping_ratios`]).
pub fn base_document<'k>(path: &Path, keys: impl IntoIterator<Item = &'k str>) -> Result<toml::Value, ScenarioError> {
    let mut document = read_document(path)?;
    if keys.into_iter().any(|k| dotted_key(k).starts_with("arm.damping_ratios.")) {
        let robot = Scenario::load_robot(path, &spec_of(path, document.clone())?)?;
        explicit_damping_ratios(&mut document, &robot);
    }
    Ok(document)
}

/// `document` as the spec of a scenario read from `path`.
pub fn spec_of(path: &Path, document: toml::Value) -> Result<ScenarioSpec, ScenarioError> {
    document.try_into().map_err(|e: toml::de::Error| ScenarioError::Parse { path: path.into(), message: e.to_string() })
}

/// The scenario file at `path` as a TOML document.
pub fn read_document(path: &Path) -> Result<toml::Value, ScenarioError> {
    crate::scenario::read_document(path).map(toml::Value::Table)
}

fn duplicate_key(vary: &[Vary]) -> Option<String> {
    vary.iter().enumerate().find(|(i, v)| vary[..*i].iter().any(|w| w.key == v.key)).map(|(_, v)| v.key.clone())
}

/// The Cartesian product of the values, the last key varying fastest.
fn product(vary: &[Vary]) -> Vec<Vec<(String, toml::Value)>> {
    vary.iter().fold(vec![Vec::new()], |acc, v| {
        acc.iter()
            .flat_map(|prefix| {
                v.values.iter().map(move |value| {
                    let mut row = prefix.clone();
                    row.push((v.key.clone(), value.clone()));
                    row
                })
            })
            .collect()
    })
}

fn case_error(case: &Case, keys: &[&str], error: ScenarioError) -> SweepError {
    SweepError::Case { index: case.index, values: case.describe(keys), error: Box::new(error) }
}

/// The base document with `values` set in the order varied (a key may lie inside an earlier
/// one's table), as `case`'s scenario spec: fails on a varied key that leads nowhere, or on a
/// spec that does not parse (naming the case).
pub(crate) fn case_spec(
    path: &Path,
    base: &toml::Value,
    values: &[(String, toml::Value)],
    case: &Case,
    keys: &[&str],
) -> Result<ScenarioSpec, SweepError> {
    let mut document = base.clone();
    for (key, value) in values.iter().flat_map(|(k, v)| assignments(k, v)) {
        set_key(&mut document, &key, value).map_err(|message| SweepError::Key { key: key.clone(), message })?;
    }
    document.try_into().map_err(|e: toml::de::Error| {
        case_error(case, keys, ScenarioError::Parse { path: path.into(), message: e.to_string() })
    })
}

/// The key whose values may name catalogue rows (`crate::sweep::pipes`).
pub const SIZE_KEY: &str = "payload.size";

/// The keys and values a varied `key` = `value` sets: an entry its size, product and weight;
/// anything else itself.
pub fn assignments(key: &str, value: &toml::Value) -> Vec<(String, toml::Value)> {
    let row = (dotted_key(key) == SIZE_KEY).then(|| value.as_str().and_then(crate::robot::pipes::entry_row)).flatten();
    match row {
        Some(Ok(row)) => vec![
            (SIZE_KEY.into(), toml::Value::String(row.size.into())),
            ("payload.product".into(), toml::Value::String(row.product.name().into())),
            ("payload.weight_lb_ft".into(), toml::Value::Float(row.nominal_weight_lb_ft)),
        ],
        _ => vec![(key.into(), value.clone())],
    }
}

/// The segments of a key path as errors write it, `dampeners[0].gap_m` (the dotted index,
/// `dampeners.0.gap_m`, is read too): names, and indices into arrays.
pub fn key_segments(key: &str) -> Vec<&str> {
    key.split('.')
        .flat_map(|part| match part.split_once('[') {
            Some((name, rest)) => {
                let indices = rest.trim_end_matches(']').split("][");
                std::iter::once(name).chain(indices).collect::<Vec<_>>()
            }
            None => vec![part],
        })
        .collect()
}

/// `key` with its indices dotted (`dampeners.0.gap_m`), for comparing keys however written.
pub fn dotted_key(key: &str) -> String {
    key_segments(key).join(".")
}

/// Sets `key` (`a.b[0].c`) in `document`; every segment but the last must exist (an index
/// picks from an array). The error message says what does exist there.
pub fn set_key(document: &mut toml::Value, key: &str, value: toml::Value) -> Result<(), String> {
    let key = crate::scenario::spelling::modern_key(key);
    let segments: Vec<&str> = key_segments(&key);
    let (last, parents) = segments.split_last().expect("split gives at least one segment");
    let mut node = document;
    for (depth, segment) in parents.iter().enumerate() {
        node = child(node, segment, &segments[..depth].join("."))?;
    }
    let at = parents.join(".");
    match node {
        toml::Value::Table(table) => {
            table.insert(last.to_string(), value);
            Ok(())
        }
        toml::Value::Array(items) => {
            let i = array_index(items.len(), last, &at)?;
            items[i] = value;
            Ok(())
        }
        other => Err(format!("`{at}` is of type {}, not a table or an array", other.type_str())),
    }
}

fn child<'a>(node: &'a mut toml::Value, segment: &str, at: &str) -> Result<&'a mut toml::Value, String> {
    check_child(node, segment, at)?;
    Ok(match node {
        toml::Value::Table(table) => &mut table[segment],
        toml::Value::Array(items) => &mut items[segment.parse::<usize>().expect("checked")],
        _ => unreachable!("checked"),
    })
}

/// Whether `node` has `segment`; if not, what it has.
fn check_child(node: &toml::Value, segment: &str, at: &str) -> Result<(), String> {
    let place = if at.is_empty() { "at the top of the scenario".to_string() } else { format!("under `{at}`") };
    match node {
        toml::Value::Table(table) if table.contains_key(segment) => Ok(()),
        toml::Value::Table(table) => {
            let keys: Vec<&str> = table.keys().map(String::as_str).collect();
            Err(format!(
                "`{segment}` does not exist {place}; there: {} (only a key's last segment may be new; \
                 set a whole table inline, e.g. physics={{gravity_m_s2=9.81}})",
                keys.join(", ")
            ))
        }
        toml::Value::Array(items) => array_index(items.len(), segment, at).map(|_| ()),
        other => Err(format!("`{at}` is of type {}, it has no `{segment}`", other.type_str())),
    }
}

fn array_index(len: usize, segment: &str, at: &str) -> Result<usize, String> {
    match segment.parse::<usize>() {
        Ok(i) if i < len => Ok(i),
        Ok(i) => Err(format!("index {i} is outside the array `{at}` (allowed 0..={})", len as i64 - 1)),
        Err(_) => Err(format!("`{at}` is an array: allowed an index 0..={}, not `{segment}`", len as i64 - 1)),
    }
}

/// The number at `key` of a TOML document, written as errors write it (`dampeners[0].gap_m`) or
/// dotted (`dampeners.0.gap_m`), in the current spelling or an old one.
pub fn get_number(document: &toml::Value, key: &str) -> Option<f64> {
    as_number(node_at(document, &key_segments(&crate::scenario::spelling::modern_key(key)))?)
}

/// Why `key` cannot be varied in the scenario at `path`, with the numeric keys near it: those
/// under the deepest part of `key` that exists (or beside `key` where it is not a number).
pub fn not_a_number(document: &toml::Value, key: &str, path: &Path) -> String {
    let modern = crate::scenario::spelling::modern_key(key);
    let segments = key_segments(&modern);
    let depth = (0..=segments.len()).rev().find(|&d| node_at(document, &segments[..d]).is_some()).unwrap_or(0);
    let stem = if depth == segments.len() { depth.saturating_sub(1) } else { depth };
    let node = node_at(document, &segments[..stem]).unwrap_or(document);
    let mut near = Vec::new();
    numeric_leaves(node, &bracketed(&segments[..stem]), &mut near);
    let listed = if near.is_empty() {
        "none there (numeric keys are numbers written in the scenario file, e.g. dampeners[0].gap_m)".to_string()
    } else if near.len() > NEAR_KEYS {
        format!("{}, ... ({} in all)", near[..NEAR_KEYS].join(", "), near.len())
    } else {
        near.join(", ")
    };
    format!("`{key}` is not a number in {}: numeric keys near it: {listed}", path.display())
}

/// How many numeric keys an error lists before it says how many there are.
const NEAR_KEYS: usize = 12;

/// The node at `segments` of a document (array entries by index).
fn node_at<'a>(document: &'a toml::Value, segments: &[&str]) -> Option<&'a toml::Value> {
    segments.iter().try_fold(document, |node, segment| match node {
        toml::Value::Table(table) => table.get(*segment),
        toml::Value::Array(items) => items.get(segment.parse::<usize>().ok()?),
        _ => None,
    })
}

fn as_number(node: &toml::Value) -> Option<f64> {
    match node {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// `segments` as a key in the form errors write it: `dampeners[0].gap_m`.
fn bracketed(segments: &[&str]) -> String {
    segments.iter().fold(String::new(), |mut key, segment| {
        if segment.parse::<usize>().is_ok() {
            key.push_str(&format!("[{segment}]"));
        } else {
            if !key.is_empty() {
                key.push('.');
            }
            key.push_str(segment);
        }
        key
    })
}

/// Every numeric leaf under `node`, as keys starting with `prefix`.
fn numeric_leaves(node: &toml::Value, prefix: &str, out: &mut Vec<String>) {
    match node {
        toml::Value::Table(table) => {
            for (name, child) in table {
                let key = if prefix.is_empty() { name.clone() } else { format!("{prefix}.{name}") };
                numeric_leaves(child, &key, out);
            }
        }
        toml::Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                numeric_leaves(child, &format!("{prefix}[{i}]"), out);
            }
        }
        leaf if as_number(leaf).is_some() => out.push(prefix.to_string()),
        _ => {}
    }
}

/// Writes the robot's modal damping ratios into `document` as `arm.damping_ratios` unless the
/// scenario overrides them already: they live in the URDF, and a key such as
/// `arm.damping_ratios.0` can only be set once the override is explicit.
pub fn explicit_damping_ratios(document: &mut toml::Value, robot: &Robot) {
    let toml::Value::Table(top) = document else { return };
    let arm = top.entry("arm").or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let toml::Value::Table(arm) = arm {
        arm.entry("damping_ratios")
            .or_insert_with(|| toml::Value::try_from(&robot.arm.damping_ratios).expect("floats serialise"));
    }
}

/// FNV-1a 64 of the case's canonical TOML spec followed by `robot_bytes`, its robot file, and a
/// table drive's file, as 16 hex digits: equal for equal inputs, so a rerun can tell a current
/// case file.
pub fn case_hash(scenario: &Scenario, robot_bytes: &[u8]) -> Result<String, ScenarioError> {
    let canonical = toml::to_string(&scenario.spec)
        .map_err(|e| ScenarioError::Parse { path: scenario.path.clone(), message: format!("canonical form: {e}") })?;
    let table_bytes = match &scenario.spec.drive {
        DriveSpec::Table { file, .. } => {
            let path = Scenario::table_path(&scenario.path, file);
            std::fs::read(&path).map_err(|source| ScenarioError::Io { path, source })?
        }
        _ => Vec::new(),
    };
    Ok(format!("{:016x}", fnv1a64(&[canonical.as_bytes(), robot_bytes, &table_bytes])))
}

/// FNV-1a, 64 bits, over the parts in order.
pub fn fnv1a64(parts: &[&[u8]]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    parts.iter().flat_map(|p| p.iter()).fold(OFFSET_BASIS, |h, &b| (h ^ u64::from(b)).wrapping_mul(PRIME))
}

/// Reads a plan written by a sweep.
pub fn read_plan(path: &Path) -> Result<Plan, SweepError> {
    let text = std::fs::read_to_string(path).map_err(io_error(path))?;
    serde_json::from_str(&text).map_err(|e| SweepError::Format { path: path.into(), message: e.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_matches_the_reference_vectors() {
        assert_eq!(fnv1a64(&[b""]), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(&[b"a"]), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(&[b"foo", b"bar"]), fnv1a64(&[b"foobar"]));
        assert_eq!(fnv1a64(&[b"foobar"]), 0x85944171f73967e8);
    }

    #[test]
    fn keys_walk_tables_and_arrays() {
        let mut doc: toml::Value = toml::from_str("[a]\nb = 1\n[[c]]\nd = 2\n").unwrap();
        set_key(&mut doc, "a.b", toml::Value::Integer(5)).unwrap();
        set_key(&mut doc, "a.new", toml::Value::Integer(6)).unwrap();
        set_key(&mut doc, "c.0.d", toml::Value::Integer(7)).unwrap();
        set_key(&mut doc, "c[0].e", toml::Value::Integer(8)).unwrap();
        assert_eq!(doc["a"]["b"].as_integer(), Some(5));
        assert_eq!(doc["c"][0]["d"].as_integer(), Some(7));
        assert_eq!(doc["c"][0]["e"].as_integer(), Some(8));
        assert!(set_key(&mut doc, "x.y", toml::Value::Integer(1)).unwrap_err().contains("there: a, c"));
        assert!(set_key(&mut doc, "c.1.d", toml::Value::Integer(1)).unwrap_err().contains("outside the array `c`"));
        assert!(set_key(&mut doc, "a.b.z", toml::Value::Integer(1)).unwrap_err().contains("`a.b` is of type integer"));
    }

    #[test]
    fn numbers_are_read_by_either_key_form_and_misses_list_the_numbers_near() {
        let doc: toml::Value =
            toml::from_str("[a]\nb = 1\ns = \"x\"\n[[c]]\nd = 2.5\nlaw = { k = 3.0, kind = \"hc\" }\n").unwrap();
        assert_eq!(get_number(&doc, "c[0].d"), Some(2.5));
        assert_eq!(get_number(&doc, "c.0.d"), Some(2.5));
        assert_eq!(get_number(&doc, "c[0].law.k"), Some(3.0));
        assert_eq!(get_number(&doc, "c[0].law.kind"), None);
        let path = Path::new("s.toml");
        let beside = not_a_number(&doc, "c[0].law.kind", path);
        assert!(beside.ends_with("numeric keys near it: c[0].law.k"), "{beside}");
        let under = not_a_number(&doc, "c[0].nope", path);
        assert!(under.ends_with("numeric keys near it: c[0].d, c[0].law.k"), "{under}");
        let text = not_a_number(&doc, "a.s", path);
        assert!(text.ends_with("numeric keys near it: a.b"), "{text}");
    }
}
