//! Flattens JSON text into `(dotted.path, scalar)` pairs, keeping each number's text, so a
//! table shows exactly the value written. (serde_json without its `float_roundtrip` feature,
//! which this crate's dependency tree does not enable, reads about one float in ten one ulp
//! off.)

/// A scalar of the document.
#[derive(Debug, Clone, PartialEq)]
pub enum Scalar {
    /// A number, as written.
    Number(String),
    /// A string, unescaped.
    Text(String),
    /// `true` or `false`.
    Bool(bool),
    /// `null` (how serde_json writes NaN and absent options).
    Null,
}

impl Scalar {
    /// The number's value (exact: std's parser rounds correctly).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Scalar::Number(text) => text.parse().ok(),
            _ => None,
        }
    }

    /// As a table cell: integers as written, floats with Rust's `{}` (shortest round trip),
    /// `null` empty.
    pub fn cell(&self) -> String {
        match self {
            Scalar::Number(text) if text.contains(['.', 'e', 'E']) => {
                self.as_f64().map_or(text.clone(), |f| f.to_string())
            }
            Scalar::Number(text) | Scalar::Text(text) => text.clone(),
            Scalar::Bool(b) => b.to_string(),
            Scalar::Null => String::new(),
        }
    }
}

/// Every scalar of the JSON `text` with its dotted path (array elements by index), in document
/// order, leaving out the values of the keys in `skip`. `None` if `text` is not JSON.
pub fn flatten(text: &str, skip: &[&str]) -> Option<Vec<(String, Scalar)>> {
    let mut scan = Scan { text, at: 0, skip, out: Vec::new() };
    scan.value("", true)?;
    scan.blank();
    (scan.at == text.len()).then_some(scan.out)
}

struct Scan<'a> {
    text: &'a str,
    at: usize,
    skip: &'a [&'a str],
    out: Vec<(String, Scalar)>,
}

impl Scan<'_> {
    fn blank(&mut self) {
        let rest = &self.text[self.at..];
        self.at += rest.len() - rest.trim_start().len();
    }

    fn eat(&mut self, c: char) -> bool {
        self.blank();
        let hit = self.text[self.at..].starts_with(c);
        self.at += usize::from(hit);
        hit
    }

    fn value(&mut self, path: &str, keep: bool) -> Option<()> {
        self.blank();
        match self.text[self.at..].chars().next()? {
            '{' => self.object(path, keep),
            '[' => self.array(path, keep),
            '"' => self.scalar(path, keep, |t| serde_json::from_str(t).ok().map(Scalar::Text)),
            _ => self.scalar(path, keep, |t| match t {
                "true" | "false" => Some(Scalar::Bool(t == "true")),
                "null" => Some(Scalar::Null),
                _ => t.parse::<f64>().is_ok().then(|| Scalar::Number(t.into())),
            }),
        }
    }

    fn object(&mut self, path: &str, keep: bool) -> Option<()> {
        self.at += 1;
        if self.eat('}') {
            return Some(());
        }
        loop {
            self.blank();
            let key: String = serde_json::from_str(self.string_token()?).ok()?;
            self.eat(':').then_some(())?;
            let keep = keep && !self.skip.contains(&key.as_str());
            self.value(&join(path, &key), keep)?;
            if !self.eat(',') {
                return self.eat('}').then_some(());
            }
        }
    }

    fn array(&mut self, path: &str, keep: bool) -> Option<()> {
        self.at += 1;
        if self.eat(']') {
            return Some(());
        }
        for i in 0.. {
            self.value(&join(path, &i.to_string()), keep)?;
            if !self.eat(',') {
                break;
            }
        }
        self.eat(']').then_some(())
    }

    fn scalar(&mut self, path: &str, keep: bool, read: impl Fn(&str) -> Option<Scalar>) -> Option<()> {
        let token = if self.text[self.at..].starts_with('"') { self.string_token()? } else { self.bare_token() };
        let scalar = read(token)?;
        if keep {
            self.out.push((path.to_string(), scalar));
        }
        Some(())
    }

    /// A quoted string with its quotes, escapes left in.
    fn string_token(&mut self) -> Option<&str> {
        let start = self.at;
        let mut escaped = false;
        for (i, c) in self.text[start + 1..].char_indices() {
            match (escaped, c) {
                (false, '"') => {
                    self.at = start + 1 + i + 1;
                    return Some(&self.text[start..self.at]);
                }
                (false, '\\') => escaped = true,
                _ => escaped = false,
            }
        }
        None
    }

    fn bare_token(&mut self) -> &str {
        let start = self.at;
        let rest = &self.text[start..];
        self.at += rest.find(|c: char| matches!(c, ',' | '}' | ']') || c.is_whitespace()).unwrap_or(rest.len());
        &self.text[start..self.at]
    }
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() { key.to_string() } else { format!("{path}.{key}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flattens_with_dotted_paths_and_exact_numbers() {
        let text = r#"{ "a": 0.30000000000000004, "b": [1, {"c": "x\"y"}], "skip": [1, 2], "n": null, "t": true }"#;
        let flat = flatten(text, &["skip"]).unwrap();
        let cells: Vec<(String, String)> = flat.iter().map(|(k, v)| (k.clone(), v.cell())).collect();
        let expected = [("a", "0.30000000000000004"), ("b.0", "1"), ("b.1.c", "x\"y"), ("n", ""), ("t", "true")];
        assert_eq!(cells, expected.map(|(k, v)| (k.to_string(), v.to_string())));
        assert_eq!(flatten("1e-5", &[]).unwrap()[0].1.cell(), "0.00001");
        assert!(flatten("{\"a\": }", &[]).is_none() && flatten("[1] x", &[]).is_none());
    }

    #[test]
    fn every_float_comes_back_bit_exact() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let f = f64::from_bits(x >> 2) * 1e-3;
            let text = serde_json::to_string(&[f]).unwrap();
            let back = flatten(&text, &[]).unwrap()[0].1.as_f64().unwrap();
            assert_eq!(back.to_bits(), f.to_bits(), "{text}");
        }
    }
}
