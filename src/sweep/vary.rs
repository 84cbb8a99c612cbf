//! `--vary` arguments: a dotted key and its values, listed (`key=v1,v2,...`, TOML values) or as
//! an inclusive numeric range (`key=a..b:step`).

use serde::{Deserialize, Serialize};

use super::SweepError;

/// Most values one range may expand to.
pub const MAX_RANGE_VALUES: usize = 100_000;

/// One varied key with its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Vary {
    /// Dotted path into the scenario's TOML document (a numeric segment indexes an array).
    pub key: String,
    /// The values, in the order given.
    pub values: Vec<toml::Value>,
}

impl std::str::FromStr for Vary {
    type Err = SweepError;

    fn from_str(arg: &str) -> Result<Self, SweepError> {
        let bad = |message: &str| SweepError::Vary { arg: arg.into(), message: message.into() };
        let (key, values) = arg.split_once('=').ok_or_else(|| bad("no `=` between the key and its values"))?;
        let key = key.trim();
        check_key(key).map_err(|m| bad(&m))?;
        let values = match range(values.trim()).map_err(|m| bad(&m))? {
            Some(values) => values,
            None => list(values).map_err(|m| bad(&m))?,
        };
        Ok(Vary { key: key.into(), values })
    }
}

/// Whether `key` is a path of names and indices as errors write it (`dampeners[0].gap_m`; the
/// dotted index `dampeners.0.gap_m` is read too), the form every scenario key on the command
/// line takes.
pub fn check_key(key: &str) -> Result<(), String> {
    let segment_ok = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    let brackets_ok = key.matches('[').count() == key.matches(']').count();
    if brackets_ok && crate::sweep::plan::key_segments(key).into_iter().all(segment_ok) {
        Ok(())
    } else {
        Err(format!("key `{key}` is not a path of names and indices such as dampeners[0].gap_m"))
    }
}

/// `a..b:step` → a, a + step, ... up to b (included within rounding); `None` if not a range.
fn range(text: &str) -> Result<Option<Vec<toml::Value>>, String> {
    let Some((a, rest)) = text.split_once("..") else { return Ok(None) };
    if a.trim().parse::<f64>().is_err() {
        return Ok(None); // a value such as ../robots/arm.urdf
    }
    let (b, step) = rest.split_once(':').ok_or("a range needs a step: A..B:STEP")?;
    let [a, b, step] = [a, b, step].map(str::trim);
    let number = |t: &str| t.parse::<f64>().map_err(|_| format!("`{t}` in the range is not a number"));
    let (lo, hi, h) = (number(a)?, number(b)?, number(step)?);
    if !(lo.is_finite() && hi.is_finite() && h.is_finite() && h > 0.0 && hi >= lo) {
        return Err("a range needs finite A <= B and STEP > 0".into());
    }
    let count = ((hi - lo) / h + 1e-9).floor() as usize + 1;
    if count > MAX_RANGE_VALUES {
        return Err(format!("the range has {count} values, more than {MAX_RANGE_VALUES}"));
    }
    let integers = [a, b, step].iter().all(|t| t.parse::<i64>().is_ok());
    let decimals = [a, b, step].iter().map(|t| decimals(t)).max().flatten();
    Ok(Some((0..count).map(|k| range_value(lo + k as f64 * h, integers, decimals)).collect()))
}

/// Digits after the point of a plain decimal (`None` with an exponent: no rounding then).
fn decimals(text: &str) -> Option<usize> {
    if text.contains(['e', 'E']) {
        return None;
    }
    Some(text.split_once('.').map_or(0, |(_, frac)| frac.len()))
}

/// A range value as an integer if every bound was one, else a float rounded to the bounds'
/// decimals (so 0.1..0.3:0.1 gives 0.1, 0.2, 0.3).
fn range_value(x: f64, integers: bool, decimals: Option<usize>) -> toml::Value {
    if integers {
        return toml::Value::Integer(x.round() as i64);
    }
    let rounded = decimals.map_or(x, |d| format!("{x:.d$}").parse().unwrap_or(x));
    toml::Value::Float(rounded)
}

/// `v1,v2,...`: each a TOML value, or bare text taken as a string.
fn list(text: &str) -> Result<Vec<toml::Value>, String> {
    split_top_level(text)
        .into_iter()
        .map(|item| {
            let item = item.trim();
            if item.is_empty() { Err("an empty value".to_string()) } else { value(item) }
        })
        .collect()
}

/// Splits at commas outside quotes, brackets and braces (so inline arrays and tables stay whole).
fn split_top_level(text: &str) -> Vec<&str> {
    let (mut items, mut start, mut depth, mut quote) = (Vec::new(), 0, 0_i32, None);
    for (i, c) in text.char_indices() {
        match (quote, c) {
            (Some(q), _) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                items.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&text[start..]);
    items
}

/// One value: TOML if it parses as one, else bare text (a string).
fn value(item: &str) -> Result<toml::Value, String> {
    match toml::from_str::<toml::Table>(&format!("v = {item}")) {
        Ok(mut table) => Ok(table.remove("v").expect("the key just parsed")),
        Err(_) if item.starts_with(['"', '\'', '[', '{']) => Err(format!("`{item}` is not a valid TOML value")),
        Err(_) => Ok(toml::Value::String(item.into())),
    }
}

/// A value as a table cell or label shows it: strings bare, numbers with `{}`.
pub fn show(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => f.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(arg: &str) -> Vec<String> {
        arg.parse::<Vary>().unwrap().values.iter().map(show).collect()
    }

    #[test]
    fn lists_take_toml_values_and_bare_text() {
        assert_eq!(parse("payload.size=2-7/8,\"4-1/2\""), ["2-7/8", "4-1/2"]);
        assert_eq!(parse("a=1, 2.5, true"), ["1", "2.5", "true"]);
        assert_eq!(parse("law={kind=\"linear\", stiffness_n_m=1e6},[1,2]").len(), 2);
        assert_eq!(parse("robot=../robots/arm.urdf"), ["../robots/arm.urdf"]);
    }

    #[test]
    fn ranges_include_their_end_within_rounding() {
        assert_eq!(parse("drive.duration_s=10..20:5"), ["10", "15", "20"]);
        assert_eq!(parse("x=0.1..0.3:0.1"), ["0.1", "0.2", "0.3"]);
        assert_eq!(parse("x=1..2:0.4"), ["1", "1.4", "1.8"]);
    }

    #[test]
    fn keys_take_the_errors_indices_and_the_dotted_ones() {
        for key in ["dampeners[0].gap_m", "dampeners.0.gap_m", "arm.damping_ratios[1]", "payload.grips[1].at_m"] {
            assert!(check_key(key).is_ok(), "{key}");
        }
        for key in ["dampeners[0.gap_m", "dampeners[].gap_m", "a..b", "a b"] {
            assert!(check_key(key).is_err(), "{key}");
        }
    }

    #[test]
    fn bad_forms_name_the_argument() {
        for arg in ["novalue", "a..b=1", "x=", "x=1,,2", "x=10..20", "x=20..10:5", "x=1..2:0", "x=\"open"] {
            let e = arg.parse::<Vary>().unwrap_err().to_string();
            assert!(e.contains(&format!("`{arg}`")) && e.contains("allowed forms"), "{e}");
        }
    }
}
