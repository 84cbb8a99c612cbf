//! The measured series for a recording, overlaid on the simulated ones: each column as a
//! scalar series under its signal's plot entity with a `/measured` suffix
//! (`plots/tip_deflection/transverse/measured`), on the run's `sim_time` timeline after the
//! comparison's shift, in the plot's unit. A time-series view whose origin holds the simulated
//! entity draws its child in the same plot.
//!
//! The chunks are built here, on rerun's public chunk API, and handed to whatever writes the
//! recording: append them to the run's chunks before they are sent.

use rerun::log::{Chunk, ChunkComponents, ChunkId};

use super::Comparison;
use crate::channel::{Channel, Plot};
use crate::measured::{Column, Measured};

/// An error from rerun's chunk builder.
#[derive(Debug, thiserror::Error)]
#[error("measured overlay `{entity}`: {message}")]
pub struct OverlayError {
    /// The entity being built.
    pub entity: String,
    /// rerun's message.
    pub message: String,
}

/// Entity path of a signal's measured overlay: a child of its plot's entity (of its trace's
/// where it is one of several).
pub fn measured_entity(plot: &Plot) -> String {
    match &plot.trace {
        Some(trace) => format!("{}/{trace}/measured", plot.entity),
        None => format!("{}/measured", plot.entity),
    }
}

/// One chunk per measured column (SI `columns` of `measured`, as [`Measured::to_si`] gives them),
/// at the measured times less the comparison's shift, from the run's start on.
pub fn measured_chunks(
    measured: &Measured,
    columns: &[Column],
    comparison: &Comparison,
    defs: &[Channel],
) -> Result<Vec<Chunk>, OverlayError> {
    let shift = comparison.shift_s.unwrap_or(0.0);
    let mut chunks = Vec::with_capacity(columns.len());
    for column in columns {
        let Some(plot) = defs.iter().find(|d| d.name == column.name).and_then(|d| d.plot.as_ref()) else { continue };
        let entity = measured_entity(plot);
        let error = |e: &dyn std::fmt::Display| OverlayError { entity: entity.clone(), message: e.to_string() };
        let rows: Vec<(f64, f64)> = measured
            .t_s
            .iter()
            .zip(&column.values)
            .map(|(t, v)| (t - shift, v * plot.scale))
            .filter(|(t, _)| *t >= 0.0)
            .collect();
        let index = rerun::TimeColumn::new_duration_secs("sim_time", rows.iter().map(|r| r.0));
        let scalars = rerun::Scalars::new(rows.iter().map(|r| r.1)).columns_of_unit_batches().map_err(|e| error(&e))?;
        let indexes = std::iter::once((*index.timeline().name(), index)).collect();
        let components: ChunkComponents = scalars.map(|c| (c.descriptor, c.list_array)).collect();
        let chunk = Chunk::from_auto_row_ids(ChunkId::new(), entity.as_str().into(), indexes, components)
            .map_err(|e| error(&e))?;
        chunks.push(chunk);
    }
    Ok(chunks)
}
