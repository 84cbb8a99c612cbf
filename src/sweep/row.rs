//! A case file read back: its text, verbatim, and its scalars by dotted path, as the table and
//! the chart take them.
//!
//! serde_json reads the file with `preserve_order` (keys in the file's order, so the table's
//! columns come in the order the summary writes them) and `float_roundtrip` (every float is the
//! one written, so a cell shows exactly the value of the case file).

use serde_json::Value;

/// One case read back.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The case file, verbatim.
    pub text: String,
    /// Its scalars by dotted path (`values.<key>`, `summary.<...>`, array elements by index), in
    /// document order: numbers, strings, booleans and nulls (serde_json writes NaN as `null`).
    pub scalars: Vec<(String, Value)>,
}

impl Row {
    /// Reads the JSON `text`, leaving out the values of the object keys in `skip`, at any depth.
    pub fn read(text: String, skip: &[&str]) -> Result<Row, serde_json::Error> {
        let mut scalars = Vec::new();
        flatten(serde_json::from_str(&text)?, String::new(), skip, &mut scalars);
        Ok(Row { text, scalars })
    }

    /// The scalar at `path`.
    pub fn get(&self, path: &str) -> Option<&Value> {
        self.scalars.iter().find(|(k, _)| k == path).map(|(_, v)| v)
    }

    /// The largest peak force over the run's contact pairs, N (`None` without a pair), its
    /// summary at `prefix` (`summary.` in a case file, empty in a summary read alone).
    pub fn largest_peak_force_n(&self, prefix: &str) -> Option<f64> {
        let pairs = format!("{prefix}pairs.");
        self.scalars
            .iter()
            .filter(|(k, _)| k.starts_with(&pairs) && k.ends_with(".peak_force_n"))
            .filter_map(|(_, v)| v.as_f64())
            .reduce(f64::max)
    }
}

/// Pushes every scalar of `value`, which is at `path`, onto `out`.
fn flatten(value: Value, path: String, skip: &[&str], out: &mut Vec<(String, Value)>) {
    match value {
        Value::Object(map) => {
            for (key, inner) in map.into_iter().filter(|(key, _)| !skip.contains(&key.as_str())) {
                flatten(inner, join(&path, &key), skip, out);
            }
        }
        Value::Array(items) => {
            for (i, inner) in items.into_iter().enumerate() {
                flatten(inner, join(&path, &i.to_string()), skip, out);
            }
        }
        scalar => out.push((path, scalar)),
    }
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() { key.to_string() } else { format!("{path}.{key}") }
}

/// A value as a table cell: integers as written, floats with Rust's `{}` (the shortest text
/// that reads back to the same number), strings unescaped, booleans as `true`/`false`, `null`
/// empty, an array or object as its JSON text.
pub fn cell(value: &Value) -> String {
    match value {
        Value::Number(n) => match n.as_f64() {
            Some(f) if n.is_f64() => f.to_string(),
            _ => n.to_string(),
        },
        Value::String(s) => s.clone(),
        Value::Bool(b) => b.to_string(),
        Value::Null => String::new(),
        Value::Array(_) | Value::Object(_) => value.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells(text: &str, skip: &[&str]) -> Vec<(String, String)> {
        Row::read(text.into(), skip).unwrap().scalars.iter().map(|(k, v)| (k.clone(), cell(v))).collect()
    }

    fn pairs(expected: &[(&str, &str)]) -> Vec<(String, String)> {
        expected.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
    }

    #[test]
    fn flattens_in_document_order_with_dotted_paths() {
        let text = r#"{ "z": 0.30000000000000004, "b": [1, {"c": "x\"y"}], "skip": [1, 2],
                       "n": null, "t": true, "e": {"deep": {"skip": 3, "k": -7}}, "a": [] }"#;
        let expected = [
            ("z", "0.30000000000000004"),
            ("b.0", "1"),
            ("b.1.c", "x\"y"),
            ("n", ""),
            ("t", "true"),
            ("e.deep.k", "-7"),
        ];
        assert_eq!(cells(text, &["skip"]), pairs(&expected));
        assert!(Row::read("{\"a\": }".into(), &[]).is_err() && Row::read("[1] x".into(), &[]).is_err());
    }

    #[test]
    fn cells_show_integers_as_written_floats_shortest_and_text_unescaped() {
        let text = r#"{"i": 18446744073709551615, "neg": -42, "f": 1.0, "tiny": 1e-5, "big": 1e20,
                      "dash": "arm\u2013vertical_stop", "raw": "arm–vertical_stop", "slash": "2-7/8"}"#;
        let expected = [
            ("i", "18446744073709551615"),
            ("neg", "-42"),
            ("f", "1"),
            ("tiny", "0.00001"),
            ("big", "100000000000000000000"),
            ("dash", "arm–vertical_stop"),
            ("raw", "arm–vertical_stop"),
            ("slash", "2-7/8"),
        ];
        assert_eq!(cells(text, &[]), pairs(&expected));
    }

    /// serde_json's default float parser reads this one ulp high (8.223091455434743e-8); the
    /// table needs the float written, which std's correctly rounded parser gives.
    #[test]
    fn a_float_the_fast_parser_misreads_comes_back_exactly() {
        let text = "8.223091455434742e-8";
        let row = Row::read(format!("{{\"x\": {text}}}"), &[]).unwrap();
        assert_eq!(
            row.get("x").and_then(Value::as_f64).map(f64::to_bits),
            Some(text.parse::<f64>().unwrap().to_bits())
        );
    }

    #[test]
    fn every_float_comes_back_bit_exact() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let f = f64::from_bits(x >> 2) * 1e-3;
            let row = Row::read(serde_json::to_string(&[f]).unwrap(), &[]).unwrap();
            assert_eq!(row.get("0").and_then(Value::as_f64).map(f64::to_bits), Some(f.to_bits()), "{}", row.text);
        }
    }
}
