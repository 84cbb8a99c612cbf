//! A run's series as tables, in CSV and Parquet: the formats pandas, spreadsheets and most data
//! tools read.
//!
//! Two tables per run, each in both formats, in the output folder:
//!
//! | file | rows |
//! |---|---|
//! | `<name>.steps.{csv,parquet}` | every step of the run, the initial state included |
//! | `<name>.decimated.{csv,parquet}` | the steps a recording keeps ([`Series::keep`]): every step in contact and the one after it, the last step, the others at the record rate |
//!
//! Every row is a step: all columns hold values at the same instant. (The recording's force plots
//! also insert each impact's peak interpolated between two steps; the tables do not, the summary
//! reports those peaks.)
//!
//! Columns, in this order, SI units in brackets after the name: the time, then each channel its
//! producer declares for the tables, in their order ([`crate::channel`]; the sign-off's last):
//!
//! | column | what |
//! |---|---|
//! | `t[s]` | time |
//! | `hub.angle[rad]`, `hub.rate[rad/s]`, `hub.accel[rad/s^2]` | hub motion |
//! | `tip_deflection.axial[m]`, `tip_deflection.transverse[m]` | tip displacement in the hub frame |
//! | `tip_velocity.axial[m/s]`, `tip_velocity.transverse[m/s]` | tip velocity relative to the hub frame |
//! | `drive_torque[N*m]` | torque of the drive on the hub |
//! | `actuator.tracking_error[rad]`, `actuator.command[N*m or 1]`, `actuator.rod_force[N]`, `actuator.pressure.cap[Pa]`, `actuator.pressure.rod[Pa]` | a servo's or hydraulic drive's channels ([`crate::actuator::channels`]; several cylinders numbered) |
//! | `contact_force.<pair>[N]` | contact force, one column per pair, named as the summary names it (`arm-<pad>`, `arm-<structure>`, `string-<structure>`) |
//! | `head.angle[rad]`, `head.drive_torque[N*m]` | a tilting head's angle on its hinge; a driven head's drive torque |
//! | `string_slip[m]`, `jaw_sinking[m]` | friction clamp only |
//! | `<sensor>.<channel>[unit]` | each sensor's channels ([`crate::sensor`]) |
//! | `energy.kinetic[J]`, `energy.strain[J]`, `energy.gravity[J]` | energies |
//! | `modal.q<i>[m*kg^0.5]` | mass-normalised elastic coordinates, i from 1 (modal models only) |
//! | `stress.worst[Pa]` | σ at the section and fibre of the run's peak stress ([`crate::stress`]) |
//! | `pivot.force.x[N]`, `pivot.force.y[N]` | the pivot's force on the arm, world |
//! | `cylinder_pin.force.x[N]`, `cylinder_pin.force.y[N]` | the rod's force on the arm's pin, world (with a cylinder; of several, `cylinder_pin.<k>.force.x[N]`, k from 1 in the URDF's order) |
//! | `grip.<hand>.force.axial[N]`, `.force.transverse[N]`, `.moment[N*m]` | each hand's grip on the string, arm frame (a rigid string's hands read as pins) |
//!
//! Units are written in ASCII (`^`, `*`) so a column can be typed as a pandas key. A signal has the
//! same name here as in a measured file for `pipearm compare` (energies and modal coordinates are
//! not measured signals).
//!
//! CSV: RFC 4180 (comma separated, `.` decimal point, a header row, a name quoted if it holds a
//! comma or a quote); floats in the shortest text that reads back to the same `f64` (zmij's, as
//! serde_json writes them: positional for everyday magnitudes, an exponent for the very small
//! and large, so a 1e-30 is not thirty zeros; `NaN`, `inf`).
//! Parquet: every column a required DOUBLE, byte-stream-split encoded and zstd compressed.
//!
//! Files are written under temporary names and renamed when all four are complete: an error
//! leaves none of them.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use arrow::array::{ArrayRef, Float64Array, RecordBatch};
use arrow::datatypes::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::{Compression, Encoding, ZstdLevel};
use parquet::file::properties::WriterProperties;

use crate::run::Series;

/// Errors writing the tables.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The output folder's path runs through a file.
    #[error("output folder {folder}: {file} is a file, not a folder")]
    NotAFolder { folder: PathBuf, file: PathBuf },
    /// Filesystem.
    #[error("tables: {path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// From the Parquet writer.
    #[error("tables: {path}: {source}")]
    Parquet { path: PathBuf, source: parquet::errors::ParquetError },
}

/// One column of a table: its header (name and unit) and a value per row.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// `name[unit]`.
    pub header: String,
    /// Values, one per row.
    pub values: Vec<f64>,
}

/// Which rows a table holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rate {
    /// Every step.
    Steps,
    /// The steps a recording keeps ([`Series::keep`]).
    Decimated,
}

impl Rate {
    /// Both tables.
    pub const ALL: [Rate; 2] = [Rate::Steps, Rate::Decimated];

    /// The file name's tag: `<name>.<tag>.csv`.
    pub fn tag(self) -> &'static str {
        match self {
            Rate::Steps => "steps",
            Rate::Decimated => "decimated",
        }
    }
}

/// What [`write_tables`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The files, steps then decimated, CSV then Parquet each.
    pub paths: Vec<PathBuf>,
    /// Rows of the steps and the decimated table.
    pub rows: [usize; 2],
    /// Bytes of the CSV files and of the Parquet files.
    pub bytes: [u64; 2],
}

/// The path of the `rate` table of the run `name` in `folder`, in format `extension`.
pub fn table_path(folder: &Path, name: &str, rate: Rate, extension: &str) -> PathBuf {
    folder.join(format!("{name}.{}.{extension}", rate.tag()))
}

/// The columns of a table of `series` at `rate`: the time, then every channel its producers
/// declare for the tables ([`crate::channel`]), in their order (the sign-off's last).
pub fn columns(series: &Series, rate: Rate) -> Vec<Column> {
    let rows = |values: &mut dyn Iterator<Item = f64>| -> Vec<f64> {
        match rate {
            Rate::Steps => values.collect(),
            Rate::Decimated => values.zip(&series.keep).filter(|(_, k)| **k).map(|(v, _)| v).collect(),
        }
    };
    let mut out = Vec::new();
    let mut push = |header: String, values: &mut dyn Iterator<Item = f64>| {
        out.push(Column { header, values: rows(values) });
    };
    let s = series;
    push("t[s]".into(), &mut s.t_s.iter().copied());
    for channel in s.channels.iter().filter(|c| c.tabled) {
        push(channel.header(), &mut (0..s.t_s.len()).map(|k| s.value(channel.reading(), k)));
    }
    out
}

/// Writes the steps and decimated tables of `series` (run `name`) as CSV and Parquet into
/// `folder`, creating it if needed: all four files, or none (an older set is left as it was
/// unless the error came while renaming, which leaves no set).
pub fn write_tables(folder: &Path, name: &str, series: &Series) -> Result<Written, ExportError> {
    make_folder(folder)?;
    let mut staged: Vec<Staged> = Vec::new();
    let written = stage(folder, name, series, &mut staged);
    if written.is_err() {
        staged.iter().for_each(|s| drop(std::fs::remove_file(&s.tmp)));
        return written;
    }
    for (k, s) in staged.iter().enumerate() {
        if let Err(source) = std::fs::rename(&s.tmp, &s.path) {
            staged[..k].iter().for_each(|s| drop(std::fs::remove_file(&s.path)));
            staged[k..].iter().for_each(|s| drop(std::fs::remove_file(&s.tmp)));
            return Err(ExportError::Io { path: s.path.clone(), source });
        }
    }
    written
}

/// A file written under a temporary name, to be renamed to its own.
struct Staged {
    tmp: PathBuf,
    path: PathBuf,
}

impl Staged {
    /// The `rate` table in format `extension`, created under its temporary name (returned with
    /// the file, then its own name, which errors show); listed in `staged` before it is created,
    /// so the caller removes it on any error.
    fn create(
        folder: &Path,
        name: &str,
        rate: Rate,
        extension: &str,
        staged: &mut Vec<Staged>,
    ) -> Result<(File, PathBuf, PathBuf), ExportError> {
        let path = table_path(folder, name, rate, extension);
        let file_name = path.file_name().unwrap_or_default().to_string_lossy();
        let tmp = path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
        staged.push(Staged { tmp: tmp.clone(), path: path.clone() });
        let file = File::create(&tmp).map_err(|source| ExportError::Io { path: path.clone(), source })?;
        Ok((file, tmp, path))
    }
}

/// Writes the four files under their temporary names (listed in `staged`).
fn stage(folder: &Path, name: &str, series: &Series, staged: &mut Vec<Staged>) -> Result<Written, ExportError> {
    let mut written = Written { paths: Vec::new(), rows: [0; 2], bytes: [0; 2] };
    let size = |path: &Path| std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    for (r, rate) in Rate::ALL.into_iter().enumerate() {
        let table = columns(series, rate);
        written.rows[r] = table.first().map_or(0, |c| c.values.len());
        let (file, tmp, path) = Staged::create(folder, name, rate, "csv", staged)?;
        write_csv(BufWriter::new(file), &table).map_err(|source| ExportError::Io { path, source })?;
        written.bytes[0] += size(&tmp);
        let (file, tmp, path) = Staged::create(folder, name, rate, "parquet", staged)?;
        write_parquet(file, table).map_err(|source| ExportError::Parquet { path, source })?;
        written.bytes[1] += size(&tmp);
    }
    written.paths = staged.iter().map(|s| s.path.clone()).collect();
    Ok(written)
}

/// Whether `folder` could be made: an error naming the file in the way if its path runs through
/// one. Creates nothing, so a caller can check before a long run and leave nothing on an error.
pub fn check_folder(folder: &Path) -> Result<(), ExportError> {
    match folder.ancestors().find(|a| a.is_file()) {
        Some(file) => Err(ExportError::NotAFolder { folder: folder.into(), file: file.into() }),
        None => Ok(()),
    }
}

/// Creates `folder` (and its parents).
fn make_folder(folder: &Path) -> Result<(), ExportError> {
    check_folder(folder)?;
    std::fs::create_dir_all(folder).map_err(|source| ExportError::Io { path: folder.into(), source })
}

/// A table as CSV (module doc).
fn write_csv(mut out: impl Write, table: &[Column]) -> std::io::Result<()> {
    let header: Vec<String> = table.iter().map(|c| csv_field(&c.header)).collect();
    writeln!(out, "{}", header.join(","))?;
    let rows = table.first().map_or(0, |c| c.values.len());
    let mut text = zmij::Buffer::new();
    for row in 0..rows {
        for (k, column) in table.iter().enumerate() {
            if k > 0 {
                out.write_all(b",")?;
            }
            out.write_all(text.format(column.values[row]).as_bytes())?;
        }
        out.write_all(b"\n")?;
    }
    out.flush()
}

/// A header as one CSV field: quoted, its quotes doubled, if it holds a comma, quote or line end.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.into() }
}

/// A table as Parquet (module doc): byte-stream split puts the bytes of equal weight of
/// neighbouring floats side by side, where zstd finds the runs a smooth series has.
fn write_parquet(file: File, table: Vec<Column>) -> Result<(), parquet::errors::ParquetError> {
    let fields: Vec<Field> = table.iter().map(|c| Field::new(&c.header, DataType::Float64, false)).collect();
    let arrays: Vec<ArrayRef> = table.into_iter().map(|c| Arc::new(Float64Array::from(c.values)) as ArrayRef).collect();
    let batch = RecordBatch::try_new(Arc::new(Schema::new(fields)), arrays)?;
    let properties = WriterProperties::builder()
        .set_dictionary_enabled(false)
        .set_encoding(Encoding::BYTE_STREAM_SPLIT)
        .set_compression(Compression::ZSTD(ZstdLevel::default()))
        .build();
    let mut writer = ArrowWriter::try_new(file, batch.schema(), Some(properties))?;
    writer.write(&batch)?;
    writer.close()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_header_with_a_comma_or_quote_is_quoted() {
        assert_eq!(csv_field("contact_force.stop[N]"), "contact_force.stop[N]");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
    }

    #[test]
    fn the_csv_float_form_reads_back_to_the_same_bits() {
        let values = [
            0.0,
            -0.0,
            1.0,
            0.1,
            1e-30,
            -3.5e-5,
            1e16,
            123456.789,
            f64::MIN_POSITIVE,
            f64::MAX,
            2.0 / 3.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut text = Vec::new();
        write_csv(&mut text, &[Column { header: "x[m]".into(), values: values.to_vec() }]).unwrap();
        let text = String::from_utf8(text).unwrap();
        let back: Vec<f64> = text.lines().skip(1).map(|l| l.parse().unwrap()).collect();
        assert_eq!(back.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), values.map(f64::to_bits));
        assert!(text.contains("\n1e-30\n"), "{text}");
    }
}
