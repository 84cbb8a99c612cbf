//! Merging a sweep: the plan and every case file → `results.json` (the case files in index
//! order, verbatim), `results.csv` (one row per case: index, hash, each varied key, the outcome,
//! every scalar of the summary but the per-impact arrays) and the chart. The bytes depend only on
//! the case files, so any split into shards merges to the same files.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde_json::Value;

use super::cases::case_path;
use super::plan::{Plan, read_plan};
use super::row::{Row, cell};
use super::vary::show;
use super::{SweepError, chart, io_error, write_atomic};

/// Keys whose values the table leaves out (they stay in the JSON).
pub const TABLE_SKIPS: [&str; 1] = ["impacts"];

/// What the string is: columns a table has whenever a case holds a string, in this order, empty
/// where the summary leaves one out (a grade not given, the joint mass of a uniform string), so
/// that a table over pipes always says each one's size, weight, grade and joint mass.
pub const STRING_COLUMNS: [&str; 4] = ["string.size", "string.weight_lb_ft", "string.grade", "string.joint_mass_kg"];

/// The files a merge wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged {
    /// Number of cases.
    pub cases: usize,
    /// `results.csv`.
    pub csv: PathBuf,
    /// `results.json`.
    pub json: PathBuf,
    /// `force_vs_weight.svg`.
    pub chart: PathBuf,
}

/// Reads `DIR/plan.json` and every case file and writes the results; fails naming the cases
/// not run yet.
pub fn merge(dir: &Path) -> Result<Merged, SweepError> {
    let (plan, rows) = read_results(dir)?;
    let merged = Merged {
        cases: rows.len(),
        csv: dir.join("results.csv"),
        json: dir.join("results.json"),
        chart: dir.join("force_vs_weight.svg"),
    };
    write_atomic(&merged.json, json(&rows).as_bytes(), "merge")?;
    write_atomic(&merged.csv, csv(&plan, &rows).as_bytes(), "merge")?;
    chart::force_vs_weight(&merged.chart, &plan, &rows)?;
    Ok(merged)
}

/// A sweep's plan and every case file read back, from its folder `dir`; fails naming the cases
/// not run yet.
pub fn read_results(dir: &Path) -> Result<(Plan, Vec<Row>), SweepError> {
    let plan = read_plan(&dir.join("plan.json"))?;
    let rows = read_rows(&plan, dir)?;
    Ok((plan, rows))
}

fn read_rows(plan: &Plan, dir: &Path) -> Result<Vec<Row>, SweepError> {
    let missing: Vec<String> = plan
        .cases
        .iter()
        .filter(|c| !case_path(dir, c).exists())
        .map(|c| format!("{} ({})", c.index, c.describe(&plan.keys())))
        .collect();
    if !missing.is_empty() {
        let shown = missing.iter().take(20).cloned().collect::<Vec<_>>().join("; ");
        let more = if missing.len() > 20 { format!("; and {} more", missing.len() - 20) } else { String::new() };
        return Err(SweepError::Missing { dir: dir.into(), count: missing.len(), missing: shown + &more });
    }
    // In parallel on the caller's pool: reading and flattening is most of a merge, and a merge
    // is serial time between a sweep's runs and its end (docs/sweeps.md, parallel efficiency).
    plan.cases
        .par_iter()
        .map(|c| {
            let path = case_path(dir, c);
            let text = std::fs::read_to_string(&path).map_err(io_error(&path))?;
            Row::read(text, &TABLE_SKIPS)
                .map_err(|e| SweepError::Format { path: path.clone(), message: format!("not JSON: {e}") })
        })
        .collect()
}

/// The case files as one JSON array, each indented as serde_json's pretty printer would.
pub(crate) fn json(rows: &[Row]) -> String {
    let items: Vec<String> = rows
        .iter()
        .map(|r| r.text.trim_end().lines().map(|l| format!("  {l}")).collect::<Vec<_>>().join("\n"))
        .collect();
    format!("[\n{}\n]\n", items.join(",\n"))
}

/// Columns: index, hash, each varied key, then every summary scalar met in any case, in
/// the order first met.
pub(crate) fn csv(plan: &Plan, rows: &[Row]) -> String {
    let mut summary_columns: Vec<&str> = Vec::new();
    let mut seen = HashSet::new();
    for (path, _) in rows.iter().flat_map(|r| &r.scalars) {
        if let Some(name) = path.strip_prefix("summary.")
            && seen.insert(name)
        {
            summary_columns.push(name);
        }
    }
    if summary_columns.contains(&STRING_COLUMNS[0]) {
        for pair in STRING_COLUMNS.windows(2) {
            if !summary_columns.contains(&pair[1]) {
                let after = summary_columns.iter().position(|c| *c == pair[0]).expect("inserted in order");
                summary_columns.insert(after + 1, pair[1]);
            }
        }
    }
    let keys = plan.keys();
    let header = ["index", "hash"].into_iter().chain(keys.iter().copied()).chain(["outcome"]);
    let mut out = line(header.chain(summary_columns.iter().copied()));
    for (row, case) in rows.iter().zip(&plan.cases) {
        let by_path: HashMap<&str, &Value> = row.scalars.iter().map(|(k, v)| (k.as_str(), v)).collect();
        let get = |path: &str| by_path.get(path).copied();
        let cell_at = |path: String| get(&path).map(cell).unwrap_or_default();
        // An inline table or array value has no single scalar: the plan shows it as TOML.
        let value = |k: &&str| get(&format!("values.{k}")).map_or_else(|| show(&case.values[*k]), cell);
        // `ran`, or where the guard stopped the run (its reason and advice are in the JSON).
        let outcome = get("diverged.t_s").map_or_else(|| "ran".to_string(), |t| format!("diverged at {} s", cell(t)));
        let cells: Vec<String> = [cell_at("index".into()), cell_at("hash".into())]
            .into_iter()
            .chain(keys.iter().map(value))
            .chain([outcome])
            .chain(summary_columns.iter().map(|c| cell_at(format!("summary.{c}"))))
            .collect();
        out += &line(cells.iter().map(String::as_str));
    }
    out
}

fn line<'a>(cells: impl Iterator<Item = &'a str>) -> String {
    cells.map(quote).collect::<Vec<_>>().join(",") + "\n"
}

/// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_string()
    }
}
