//! Reading a table drive from a CSV file of time and angle.
//!
//! ```text
//! # comment lines (starting with #) and blank lines are skipped
//! t[s],angle[deg]
//! 0.00,0.0
//! 0.01,0.00012
//! ...
//! ```
//!
//! The header names each column with its unit in brackets: `t[s]` and `angle[deg]` (degrees, as
//! every drive key of a scenario), in either order, and no other column. Each row gives both, as
//! numbers. The times start at 0 and strictly increase; there are at least
//! [`MIN_TABLE_SAMPLES`] rows. Every error names the file, the column and the row (counted from
//! the first row after the header, with its line in the file).

use std::path::{Path, PathBuf};

use thiserror::Error;

use super::profile::MotionProfile;
use super::table::MIN_TABLE_SAMPLES;
use super::validate::DriveError;

/// The time column's header.
const TIME: &str = "t[s]";
/// The angle column's header.
const ANGLE: &str = "angle[deg]";

/// Errors reading a table drive; each names the file and, for its content, the column and row.
#[derive(Debug, Error)]
pub enum TableError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// A header or a cell out of the format.
    #[error("{path}: {place}: {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// Where: the header, or a column and row and the row's line in the file.
        place: String,
        /// What is wrong, and what is allowed.
        message: String,
    },
    /// A parameter of the table drive that is not in the file (its end rate).
    #[error("{path}: {source}")]
    Drive { path: PathBuf, source: DriveError },
}

/// One data row as read: its line in the file (from 1) and its cells' text.
struct Row<'a> {
    line: usize,
    cells: Vec<&'a str>,
}

impl MotionProfile {
    /// The table drive of the CSV file at `path` (see [`crate::drive`]'s `table_file` module for
    /// the format), ending at `end_rate_rad_s` (rad/s; 0: at rest): [`MotionProfile::table`]
    /// through its rows, angles converted from degrees.
    ///
    /// # Errors
    /// [`TableError`] naming the file and, for its content, the column and the row.
    pub fn from_csv(path: &Path, end_rate_rad_s: f64) -> Result<Self, TableError> {
        let text = std::fs::read_to_string(path).map_err(|source| TableError::Io { path: path.into(), source })?;
        let reader = Reader { path };
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l)).filter(|(_, l)| {
            let l = l.trim();
            !(l.is_empty() || l.starts_with('#'))
        });
        let (header_line, header) =
            lines.next().ok_or_else(|| reader.invalid("header", format!("none: allowed a header `{TIME},{ANGLE}`")))?;
        let (time_col, angle_col) = reader.header(header_line, header)?;
        let rows: Vec<Row> =
            lines.map(|(line, l)| Row { line, cells: l.split(',').map(str::trim).collect() }).collect();
        if rows.len() < MIN_TABLE_SAMPLES {
            return Err(reader.invalid(
                format!("after the header (line {header_line})"),
                format!("{} row(s): allowed at least {MIN_TABLE_SAMPLES}", rows.len()),
            ));
        }
        let mut times_s = Vec::with_capacity(rows.len());
        let mut angles_rad = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            if row.cells.len() != 2 {
                return Err(reader.invalid(
                    format!("row {} (line {})", i + 1, row.line),
                    format!("{} field(s): allowed 2 ({TIME}, {ANGLE})", row.cells.len()),
                ));
            }
            times_s.push(reader.number(&rows, i, time_col, TIME)?);
            angles_rad.push(reader.number(&rows, i, angle_col, ANGLE)?.to_radians());
        }
        MotionProfile::table(&times_s, &angles_rad, end_rate_rad_s).map_err(|e| match e {
            DriveError::InvalidSample { name, index, allowed, .. } => {
                let (column, col) = if name == "times_s" { (TIME, time_col) } else { (ANGLE, angle_col) };
                let text = rows[index].cells[col];
                reader.invalid(reader.place(&rows, index, column), format!("`{text}`: allowed {allowed}"))
            }
            source => TableError::Drive { path: path.into(), source },
        })
    }
}

/// Reads one file; its errors name it.
struct Reader<'p> {
    path: &'p Path,
}

impl Reader<'_> {
    fn invalid(&self, place: impl Into<String>, message: impl Into<String>) -> TableError {
        TableError::Invalid { path: self.path.into(), place: place.into(), message: message.into() }
    }

    fn place(&self, rows: &[Row], index: usize, column: &str) -> String {
        format!("column `{column}`, row {} (line {})", index + 1, rows[index].line)
    }

    /// The positions of the time and angle columns in the header on line `line`.
    fn header(&self, line: usize, header: &str) -> Result<(usize, usize), TableError> {
        let place = format!("header (line {line})");
        let allowed = format!("allowed the columns `{TIME}` and `{ANGLE}`");
        let (mut time, mut angle) = (None, None);
        for (i, column) in header.split(',').map(str::trim).enumerate() {
            let (name, unit) = match column.split_once('[') {
                Some((name, rest)) => (name.trim(), rest.strip_suffix(']').map(str::trim)),
                None => (column, None),
            };
            let (slot, wanted) = match name {
                "t" => (&mut time, TIME),
                "angle" => (&mut angle, ANGLE),
                _ => return Err(self.invalid(&place, format!("column `{column}` is unknown: {allowed}"))),
            };
            let wanted_unit = &wanted[name.len() + 1..wanted.len() - 1];
            match unit {
                None => {
                    return Err(self.invalid(&place, format!("column `{column}` has no unit: allowed `{wanted}`")));
                }
                Some(u) if u != wanted_unit => {
                    return Err(self.invalid(&place, format!("column `{column}`: unit `{u}`: allowed `{wanted}`")));
                }
                Some(_) if slot.is_some() => {
                    return Err(self.invalid(&place, format!("column `{wanted}` appears twice: {allowed}")));
                }
                Some(_) => *slot = Some(i),
            }
        }
        match (time, angle) {
            (Some(t), Some(a)) => Ok((t, a)),
            (None, _) => Err(self.invalid(&place, format!("no column `{TIME}`: {allowed}"))),
            (_, None) => Err(self.invalid(&place, format!("no column `{ANGLE}`: {allowed}"))),
        }
    }

    /// The number in column `col` (named `column`) of row `index`.
    fn number(&self, rows: &[Row], index: usize, col: usize, column: &str) -> Result<f64, TableError> {
        let text = rows[index].cells[col];
        text.parse::<f64>().map_err(|_| {
            self.invalid(self.place(rows, index, column), format!("`{text}` is not a number: allowed a finite number"))
        })
    }
}
