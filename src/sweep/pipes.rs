//! `payload.size` values naming catalogue rows: a size (`9-5/8`, its default weight, as the
//! scenario reads it), an entry (`9-5/8@47.00`: the row of that size and nominal weight, as
//! `pipearm pipes` prints it), a class (a product, `casing`: every row of it) or `liftable`
//! (every row the scenario's machine holds and lifts through its drive's path, [`liftable`]). Classes expand when the plan is made, so `plan.json` lists the
//! entries run; an entry sets `payload.size`, `payload.product` and `payload.weight_lb_ft`.

use std::path::Path;

use rayon::prelude::*;

pub use super::plan::{SIZE_KEY, assignments};
use super::plan::{dotted_key, read_document, set_key, spec_of};
use super::{SweepError, Vary};
use crate::robot::pipes::{PIPE_CATALOGUE, PipeSize, class_rows, entry_row, product_named};
use crate::scenario::Scenario;

/// The class of every row the machine lifts.
pub const LIFTABLE: &str = "liftable";

/// What a `payload.size` value may be, for messages.
fn allowed() -> String {
    let products: Vec<&str> = crate::robot::Product::ALL.iter().map(|p| p.name()).collect();
    format!(
        "allowed a size (2-3/8, 9-5/8, ...), an entry SIZE@LB_FT as `pipearm pipes` prints it (9-5/8@47.00), \
         or a class: {}, {LIFTABLE}",
        products.join(", ")
    )
}

/// `vary` with its entries written as `pipearm pipes` prints them and its classes expanded to
/// their entries (each row once, in the order given); other keys as they are. Fails naming the
/// value and what is allowed, before anything runs.
pub fn expand(path: &Path, vary: Vary) -> Result<Vary, SweepError> {
    if dotted_key(&vary.key) != SIZE_KEY {
        return Ok(vary);
    }
    let bad = |message: String| SweepError::Key { key: vary.key.clone(), message };
    let mut values: Vec<toml::Value> = Vec::new();
    let mut push = |value: toml::Value| {
        if !values.contains(&value) {
            values.push(value);
        }
    };
    for value in &vary.values {
        let Some(text) = value.as_str() else {
            push(value.clone()); // the scenario names the type it wants
            continue;
        };
        let rows: Vec<&'static PipeSize> = if let Some(row) = entry_row(text) {
            vec![row.map_err(bad)?]
        } else if let Some(product) = product_named(text) {
            class_rows(product)
        } else if text == LIFTABLE {
            liftable(path).map_err(|m| bad(format!("{LIFTABLE}: {m}")))?
        } else if PIPE_CATALOGUE.iter().any(|p| p.size == text) {
            push(value.clone());
            continue;
        } else {
            return Err(bad(format!("`{text}` is not in the catalogue: {}", allowed())));
        };
        for row in rows {
            push(toml::Value::String(row.entry()));
        }
    }
    Ok(Vary { key: vary.key, values })
}

/// Every catalogue row the scenario at `path` takes as its string: its machine's jaws close on
/// it and its drive holds it at every angle of the drive's path ([`crate::capacity::check`]),
/// and the scenario's other checks pass (an actuator's holding at the drive's start among them).
/// Fails if none does, with the first row's reason.
pub fn liftable(path: &Path) -> Result<Vec<&'static PipeSize>, String> {
    let base = read_document(path).map_err(|e| e.to_string())?;
    let robot = Scenario::load_robot(path, &spec_of(path, base.clone()).map_err(|e| e.to_string())?)
        .map_err(|e| e.to_string())?;
    let takes = |row: &'static PipeSize| -> Result<(), String> {
        let mut document = base.clone();
        for (key, value) in assignments(SIZE_KEY, &toml::Value::String(row.entry())) {
            set_key(&mut document, &key, value).map_err(|m| format!("{key}: {m}"))?;
        }
        let spec = spec_of(path, document).map_err(|e| e.to_string())?;
        Scenario::from_spec_and_robot(path, spec, robot.clone())
            .map(|_| ())
            .map_err(|e| format!("{}: {e}", row.entry()))
    };
    let checked: Vec<Result<(), String>> = PIPE_CATALOGUE.par_iter().map(takes).collect();
    let rows: Vec<&'static PipeSize> =
        PIPE_CATALOGUE.iter().zip(&checked).filter(|(_, c)| c.is_ok()).map(|(row, _)| row).collect();
    match checked.into_iter().find_map(Result::err) {
        Some(first) if rows.is_empty() => Err(format!("the scenario takes no row of the catalogue: {first}")),
        _ => Ok(rows),
    }
}
