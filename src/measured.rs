//! Measured time series from a rig, read from CSV and checked: what `pipearm compare` (and a fit)
//! sets a run against.
//!
//! The format: a header row of column names, each with its unit in brackets, the first the time
//! `t[s]`; then one row per sample, comma-separated numbers, time strictly increasing; lines
//! starting with `#` and blank lines are skipped.
//!
//! ```text
//! t[s],hand_accel.transverse[m/s^2],root.moment[kN*m]
//! 0.000,9.81,210.4
//! 0.002,9.80,210.5
//! ```
//!
//! [`read`] checks the file's form (header, units written, cells, time); [`Measured::to_si`]
//! checks its columns against the signals a caller knows (their names and SI units) and converts
//! each to SI by the few units a rig's logger writes ([`accepted_units`]). Every error names the
//! file, the column and, for a cell, its line.

use std::path::{Path, PathBuf};

use thiserror::Error;

/// Fewest samples a measured file must hold: fewer cannot show a peak, a frequency or a decay.
pub const MIN_ROWS: usize = 5;

/// The time column's header.
pub const TIME_COLUMN: &str = "t[s]";

/// Errors reading or checking a measured file; each names the file and what is wrong where.
#[derive(Debug, Error)]
pub enum MeasuredError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// A header cell: its column (1-based) and what is wrong.
    #[error("{path}: column {column} `{header}`: {message}")]
    Column { path: PathBuf, column: usize, header: String, message: String },
    /// A data cell: its line (1-based, as an editor shows it), its column and what is wrong.
    #[error("{path}: line {line}, column `{header}`: {message}")]
    Cell { path: PathBuf, line: usize, header: String, message: String },
    /// Too few samples.
    #[error("{path}: {rows} samples: allowed at least {MIN_ROWS}")]
    TooFewRows { path: PathBuf, rows: usize },
}

/// One measured column: its name and unit as the header writes them, and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The name, before the bracket.
    pub name: String,
    /// The unit, inside the bracket.
    pub unit: String,
    /// One value per sample, in `unit`.
    pub values: Vec<f64>,
}

impl Column {
    /// The header as written: `name[unit]`.
    pub fn header(&self) -> String {
        format!("{}[{}]", self.name, self.unit)
    }
}

/// A measured file: the sample times and the columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// The file it came from.
    pub path: PathBuf,
    /// Sample times, s, strictly increasing.
    pub t_s: Vec<f64>,
    /// The columns after the time, in file order.
    pub columns: Vec<Column>,
}

/// Reads and checks a measured CSV file.
pub fn read(path: &Path) -> Result<Measured, MeasuredError> {
    let text = std::fs::read_to_string(path).map_err(|source| MeasuredError::Io { path: path.into(), source })?;
    parse(path, &text)
}

/// Parses and checks measured CSV `text`, as if read from `path` (for the messages).
pub fn parse(path: &Path, text: &str) -> Result<Measured, MeasuredError> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let column_error = |column: usize, header: &str, message: String| MeasuredError::Column {
        path: path.into(),
        column,
        header: header.into(),
        message,
    };
    let Some((_, header_line)) = lines.next() else {
        return Err(MeasuredError::TooFewRows { path: path.into(), rows: 0 });
    };
    let headers: Vec<&str> = header_line.split(',').map(str::trim).collect();
    if headers[0] != TIME_COLUMN {
        return Err(column_error(1, headers[0], format!("the first column must be the time, `{TIME_COLUMN}`")));
    }
    let mut columns = Vec::with_capacity(headers.len() - 1);
    for (i, header) in headers.iter().enumerate().skip(1) {
        let (name, unit) = split_header(header).map_err(|message| column_error(i + 1, header, message))?;
        if columns.iter().any(|c: &Column| c.name == name) {
            return Err(column_error(i + 1, header, format!("`{name}` is already a column")));
        }
        columns.push(Column { name: name.into(), unit: unit.into(), values: Vec::new() });
    }
    if columns.is_empty() {
        return Err(column_error(1, headers[0], "no measured column after the time".into()));
    }
    let mut t_s: Vec<f64> = Vec::new();
    for (index, line) in lines {
        let number = index + 1;
        let cell_error = |header: &str, message: String| MeasuredError::Cell {
            path: path.into(),
            line: number,
            header: header.into(),
            message,
        };
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != headers.len() {
            let header = headers.get(cells.len()).unwrap_or(&headers[headers.len() - 1]);
            return Err(cell_error(header, format!("{} cells: the header has {}", cells.len(), headers.len())));
        }
        let value = |k: usize| -> Result<f64, MeasuredError> {
            let cell = cells[k];
            match cell.parse::<f64>() {
                _ if cell.is_empty() => Err(cell_error(headers[k], "empty: every cell needs a number".into())),
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(cell_error(headers[k], format!("`{cell}` is not a finite number"))),
            }
        };
        let t = value(0)?;
        if let Some(&previous) = t_s.last()
            && t <= previous
        {
            return Err(cell_error(headers[0], format!("{t} s after {previous} s: time must increase row by row")));
        }
        t_s.push(t);
        for (k, column) in columns.iter_mut().enumerate() {
            column.values.push(value(k + 1)?);
        }
    }
    if t_s.len() < MIN_ROWS {
        return Err(MeasuredError::TooFewRows { path: path.into(), rows: t_s.len() });
    }
    Ok(Measured { path: path.into(), t_s, columns })
}

/// `name[unit]` into its name and unit.
fn split_header(header: &str) -> Result<(&str, &str), String> {
    let Some((name, rest)) = header.split_once('[') else {
        return Err(format!("no unit: write it as `{header}[unit]`"));
    };
    let unit = rest.strip_suffix(']').filter(|u| !u.is_empty() && !u.contains(['[', ']']));
    let Some(unit) = unit else {
        return Err("allowed `name[unit]`, with the unit in one pair of brackets at the end".into());
    };
    if name.trim().is_empty() {
        return Err("no name before the unit".into());
    }
    Ok((name.trim(), unit.trim()))
}

/// The units a column may be written in for a signal in SI unit `si`, with the factor to SI.
pub fn accepted_units(si: &str) -> &'static [(&'static str, f64)] {
    const G: f64 = crate::arm::STANDARD_GRAVITY_M_S2;
    const DEG: f64 = std::f64::consts::PI / 180.0;
    match si {
        "m/s^2" => &[("m/s^2", 1.0), ("m/s²", 1.0), ("g", G)],
        "N*m" => &[("N*m", 1.0), ("N·m", 1.0), ("Nm", 1.0), ("kN*m", 1e3), ("kN·m", 1e3), ("kNm", 1e3)],
        "Pa" => &[("Pa", 1.0), ("kPa", 1e3), ("MPa", 1e6)],
        "rad" => &[("rad", 1.0), ("deg", DEG)],
        "rad/s" => &[("rad/s", 1.0), ("deg/s", DEG)],
        "rad/s^2" => &[("rad/s^2", 1.0), ("deg/s^2", DEG)],
        "m" => &[("m", 1.0), ("mm", 1e-3)],
        "m/s" => &[("m/s", 1.0), ("mm/s", 1e-3)],
        "N" => &[("N", 1.0), ("kN", 1e3)],
        _ => &[],
    }
}

/// A signal a measured column may name: its name and SI unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Known<'a> {
    /// The name a column must carry.
    pub name: &'a str,
    /// Its SI unit (one of [`accepted_units`]' keys).
    pub unit: &'a str,
}

impl<'a> From<&'a crate::channel::Channel> for Known<'a> {
    fn from(channel: &'a crate::channel::Channel) -> Self {
        Known { name: &channel.name, unit: channel.unit }
    }
}

impl Measured {
    /// The columns in SI units, each checked against the `known` signals: an unknown name or a
    /// unit the signal cannot be written in is an error naming the column.
    pub fn to_si(&self, known: &[Known]) -> Result<Vec<Column>, MeasuredError> {
        self.columns
            .iter()
            .enumerate()
            .map(|(i, column)| {
                let error = |message: String| MeasuredError::Column {
                    path: self.path.clone(),
                    column: i + 2,
                    header: column.header(),
                    message,
                };
                let Some(signal) = known_as(known, &column.name) else {
                    let names: Vec<&str> = known.iter().map(|k| k.name).collect();
                    return Err(error(format!("no signal `{}`: allowed {}", column.name, names.join(", "))));
                };
                let units = accepted_units(signal.unit);
                let Some((_, factor)) = units.iter().find(|(u, _)| *u == column.unit) else {
                    let allowed: Vec<&str> = units.iter().map(|u| u.0).collect();
                    return Err(error(format!("unit `{}`: allowed {}", column.unit, allowed.join(", "))));
                };
                let values = column.values.iter().map(|v| v * factor).collect();
                Ok(Column { name: signal.name.into(), unit: signal.unit.into(), values })
            })
            .collect()
    }

    /// The columns named in a former spelling that [`Measured::to_si`] reads under the signal's
    /// name: (as written, as read).
    pub fn renamed<'a>(&self, known: &[Known<'a>]) -> Vec<(String, &'a str)> {
        self.columns
            .iter()
            .filter_map(|c| known_as(known, &c.name).filter(|k| k.name != c.name).map(|k| (c.name.clone(), k.name)))
            .collect()
    }
}

/// The signal of `known` a column named `name` is: by its name, or by the former spelling of an
/// arm's contact pair, `contact_force.<pad>` for `contact_force.arm-<pad>` (the pair's name in
/// the summary and the recording), still read.
fn known_as<'k, 'a>(known: &'k [Known<'a>], name: &str) -> Option<&'k Known<'a>> {
    let by = |wanted: &str| known.iter().find(|k| k.name == wanted);
    by(name).or_else(|| {
        let obstacle = name.strip_prefix("contact_force.")?;
        by(&format!("contact_force.{}", crate::scene::pair_name(obstacle)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse(Path::new("rig.csv"), text).unwrap_err().to_string()
    }

    const ROWS: &str = "0,1\n0.1,2\n0.2,3\n0.3,4\n0.4,5\n";

    #[test]
    fn a_well_formed_file_reads_and_converts() {
        let m = parse(Path::new("rig.csv"), &format!("# logger 7\nt[s], root.moment[kN*m]\n\n{ROWS}")).unwrap();
        assert_eq!(m.t_s, [0.0, 0.1, 0.2, 0.3, 0.4]);
        let si = m.to_si(&[Known { name: "root.moment", unit: "N*m" }]).unwrap();
        assert_eq!(si[0].values, [1e3, 2e3, 3e3, 4e3, 5e3]);
        assert_eq!(si[0].unit, "N*m");
    }

    #[test]
    fn bad_files_name_the_column_and_line() {
        let cases = [
            (format!("time,a[m]\n{ROWS}"), "column 1 `time`"),
            (format!("t[s],a\n{ROWS}"), "column 2 `a`: no unit"),
            (format!("t[s],a[]\n{ROWS}"), "column 2 `a[]`"),
            ("t[s],a[m]\n0,1\n0.2,2\n0.1,3\n0.3,4\n0.4,5\n".into(), "line 4, column `t[s]`: 0.1 s after 0.2 s"),
            ("t[s],a[m]\n0,1\n0.1,NaN\n0.2,3\n0.3,4\n0.4,5\n".into(), "line 3, column `a[m]`: `NaN`"),
            ("t[s],a[m]\n0,1\n0.1,\n0.2,3\n0.3,4\n0.4,5\n".into(), "line 3, column `a[m]`: empty"),
            ("t[s],a[m]\n0,1\n0.1,2\n".into(), "2 samples: allowed at least 5"),
            (format!("t[s],a[m],a[mm]\n{ROWS}"), "column 3 `a[mm]`: `a` is already a column"),
        ];
        for (text, expected) in cases {
            let e = error(&text);
            assert!(e.starts_with("rig.csv: ") && e.contains(expected), "{text}\n{e}");
        }
    }

    #[test]
    fn unknown_names_and_wrong_units_name_the_column() {
        let m = parse(Path::new("rig.csv"), &format!("t[s],tip.axial[m/s]\n{ROWS}")).unwrap();
        let e = m.to_si(&[Known { name: "tip.transverse", unit: "m/s^2" }]).unwrap_err().to_string();
        assert!(e.contains("column 2 `tip.axial[m/s]`: no signal `tip.axial`: allowed tip.transverse"), "{e}");
        let e = m.to_si(&[Known { name: "tip.axial", unit: "m/s^2" }]).unwrap_err().to_string();
        assert!(e.contains("unit `m/s`: allowed m/s^2, m/s², g"), "{e}");
    }
}
