//! The chunks of a recording as they are made: a run's columns at its kept steps, static
//! archetypes, and the magnified centreline's points, shared by the plots and the scene
//! ([`super::content`]) and the sign-off's ([`super::stress`]).

use rerun::external::arrow::array::ListArray;
use rerun::external::arrow::buffer::{NullBuffer, OffsetBuffer};
use rerun::log::{Chunk, ChunkComponents, ChunkId, RowId};
use rerun::{AsComponents, RecordingStreamResult, SerializedComponentColumn, TimeColumn, TimePoint};

use super::Recorded;
use crate::scene::{Frame, SceneLayout};

/// A recording's chunks being made from `run`.
pub(super) struct Writer<'a> {
    /// Takes each chunk as it is made.
    pub(super) out: &'a mut dyn FnMut(Chunk),
    /// The run.
    pub(super) run: &'a Recorded<'a>,
    /// Steps the plots keep.
    pub(super) keep: &'a [bool],
}

impl Writer<'_> {
    /// Columns of `entity` at the times of `index` (what `RecordingStream::send_columns` sends).
    pub(super) fn send_columns(
        &mut self,
        entity: &str,
        index: TimeColumn,
        columns: impl IntoIterator<Item = SerializedComponentColumn>,
    ) -> RecordingStreamResult<()> {
        let indexes = std::iter::once((*index.timeline().name(), index)).collect();
        let components: ChunkComponents = columns.into_iter().map(|c| (c.descriptor, c.list_array)).collect();
        (self.out)(Chunk::from_auto_row_ids(ChunkId::new(), entity.into(), indexes, components)?);
        Ok(())
    }

    /// A static archetype of `entity`.
    pub(super) fn log_static(&mut self, entity: &str, archetype: &dyn AsComponents) -> RecordingStreamResult<()> {
        (self.out)(Chunk::builder(entity).with_archetype(RowId::new(), TimePoint::default(), archetype).build()?);
        Ok(())
    }

    /// Whether the plots keep step `k`.
    pub(super) fn keeps(&self, k: usize) -> bool {
        self.keep.get(k).copied().unwrap_or(false)
    }

    /// The kept steps of `values`.
    pub(super) fn kept<T: Copy>(&self, values: impl IntoIterator<Item = T>) -> Vec<T> {
        values.into_iter().zip(self.keep).filter(|(_, k)| **k).map(|(v, _)| v).collect()
    }

    /// The steps the plots keep, and their times on `sim_time`.
    fn kept_steps(&self) -> (Vec<usize>, TimeColumn) {
        let t_s = &self.run.series.t_s;
        let rows: Vec<usize> = (0..t_s.len()).filter(|&k| self.keeps(k)).collect();
        let times = TimeColumn::new_duration_secs("sim_time", rows.iter().map(|&k| t_s[k]));
        (rows, times)
    }

    /// The kept steps of `value` of a step, evaluated at those steps only.
    pub(super) fn send_kept(&mut self, entity: &str, value: impl Fn(usize) -> f64) -> RecordingStreamResult<()> {
        let (rows, times) = self.kept_steps();
        let columns = rerun::Scalars::new(rows.into_iter().map(value)).columns_of_unit_batches()?;
        self.send_columns(entity, times, columns)
    }

    /// The kept steps of several series of one kind as one entity, an instance per series, named
    /// by `names` in the viewer's legend: one chunk where an entity per series would take one
    /// each, and rerun's cost is per chunk. `value(step, i)` is series i at `step`.
    pub(super) fn send_named(
        &mut self,
        entity: &str,
        names: &[String],
        value: impl Fn(usize, usize) -> f64,
    ) -> RecordingStreamResult<()> {
        let width = names.len();
        let (rows, times) = self.kept_steps();
        let values = rows.iter().flat_map(|&k| (0..width).map(move |i| (k, i))).map(|(k, i)| value(k, i));
        let scalars = rerun::Scalars::new(values).columns(std::iter::repeat_n(width, rows.len()))?;
        let names =
            rerun::SeriesLines::update_fields().with_names(names.iter().map(String::as_str)).columns([width])?;
        self.send_columns(entity, times, scalars.chain(from_first_row(names, rows.len())))
    }
}

/// A style's columns (`style`, each one row: `update_fields()…columns([width])`) held from the
/// first of `rows` rows: the later rows null, which the viewer reads as no data (it keeps the
/// first row's), where an empty row would clear them. A series' name or a marker's label, colour
/// and size then go in the chunk of the values they style, not in a static chunk of their own.
pub(super) fn from_first_row(
    style: impl IntoIterator<Item = SerializedComponentColumn>,
    rows: usize,
) -> Vec<SerializedComponentColumn> {
    if rows == 0 {
        return Vec::new();
    }
    style
        .into_iter()
        .map(|mut column| {
            let (field, offsets, values, _) = column.list_array.into_parts();
            let width = offsets.last().copied().unwrap_or(0);
            let offsets = std::iter::once(0).chain(std::iter::repeat_n(width, rows)).collect::<Vec<i32>>();
            let held = NullBuffer::from((0..rows).map(|r| r == 0).collect::<Vec<bool>>());
            column.list_array = ListArray::new(field, OffsetBuffer::new(offsets.into()), values, Some(held));
            column
        })
        .collect()
}

/// The magnified centreline of `frame`, world points.
pub(super) fn centreline_points(layout: &SceneLayout, frame: &Frame, magnify: f64) -> Vec<[f32; 3]> {
    let (s, c) = frame.hub_angle_rad.sin_cos();
    let p = layout.pivot_m;
    frame
        .centreline
        .iter()
        .map(|(x, [u, v])| {
            let (bx, by) = (x + magnify * u, magnify * v);
            [(p[0] + c * bx - s * by) as f32, (p[1] + s * bx + c * by) as f32, p[2] as f32]
        })
        .collect()
}
