//! One spelling per idea: a variant is chosen by `kind` in every table. The older spellings,
//! `[drive] profile`, `[integrator] method` and `[contact] method`, are still read: each is
//! rewritten to `kind` when the file is read, before anything edits it (`--vary`, `--spread`,
//! `--params`), and reported as a [`Deprecation`] for the command to print.

/// (table, old key, current key).
const RENAMED: [(&str, &str, &str); 3] =
    [("drive", "profile", "kind"), ("integrator", "method", "kind"), ("contact", "method", "kind")];

/// An old spelling read and rewritten.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Deprecation {
    /// The key as written, e.g. `drive.profile`.
    pub old: String,
    /// The key it was read as, e.g. `drive.kind`.
    pub new: String,
}

impl std::fmt::Display for Deprecation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "`{}` is the old spelling of `{}`; read as `{}`", self.old, self.new, self.new)
    }
}

/// Rewrites the old spellings in a scenario document to the current ones, returning what it
/// rewrote. A table holding both spellings keeps the current one's value.
pub fn modernize(document: &mut toml::Table) -> Vec<Deprecation> {
    let mut found = Vec::new();
    for (table, old, new) in RENAMED {
        let Some(toml::Value::Table(t)) = document.get_mut(table) else { continue };
        if let Some(value) = t.remove(old) {
            t.entry(new.to_string()).or_insert(value);
            found.push(Deprecation { old: format!("{table}.{old}"), new: format!("{table}.{new}") });
        }
    }
    found
}

/// A key as a command line gives it (`drive.profile`), in its current spelling (`drive.kind`).
pub fn modern_key(key: &str) -> String {
    RENAMED
        .iter()
        .find(|(table, old, _)| key == format!("{table}.{old}"))
        .map_or_else(|| key.to_string(), |(table, _, new)| format!("{table}.{new}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn old_spellings_are_read_as_kind_and_reported() {
        let mut doc: toml::Table = toml::from_str(
            "[drive]\nprofile = \"uniform\"\n[integrator]\nmethod = \"rk4\"\n[contact]\nkind = \"rapier\"\n",
        )
        .unwrap();
        let found = modernize(&mut doc);
        assert_eq!(doc["drive"]["kind"].as_str(), Some("uniform"));
        assert_eq!(doc["integrator"]["kind"].as_str(), Some("rk4"));
        assert!(doc["drive"].get("profile").is_none());
        assert_eq!(found.len(), 2, "{found:?}");
        assert_eq!(found[0].to_string(), "`drive.profile` is the old spelling of `drive.kind`; read as `drive.kind`");
        assert_eq!(modern_key("integrator.method"), "integrator.kind");
        assert_eq!(modern_key("drive.duration_s"), "drive.duration_s");
    }
}
