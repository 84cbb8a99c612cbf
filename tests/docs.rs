//! Every command the documentation shows runs here, as a user would type it: each `pipearm …`
//! line of a fenced shell block in README.md, robots/README.md and docs/**/*.md, and each line
//! of every command's `--help` "Examples:" section. Where a page shows a command's output, the
//! output is compared.
//!
//! How a page is run:
//! - Each page (and the help examples, as one more page) runs in a scratch copy of the project,
//!   its commands in order in one shell session (`cd` carries over), through `bash -c` with the
//!   built `pipearm` first on the PATH; `cargo run --release --` is read as `pipearm`.
//! - Lines that are not pipearm commands (`pip install`, `rerun`, `cargo test`, …) are not run.
//! - Placeholders map to shipped files ([`PLACEHOLDERS`]): `my.toml` is the default scenario,
//!   `/abs/proj` the project, `/tmp/` a folder of the scratch copy.
//! - A page may shrink a command too heavy for the suite with a marker in an HTML comment just
//!   before the block, visible in the page's source: `<!-- doc-test: --samples 1000 => --samples 16 -->`
//!   (several replacements separated by ` ;; `). The command still runs.
//!
//! How output is compared: the lines a page shows after a `$ command` (or in a plain block right
//! after a shell block, for its last command) must appear in the command's output (stdout and
//! stderr together) in that order; other lines may come between. Whitespace runs are one space;
//! `...` alone is any lines, a trailing `...` any rest of the line, `[..]` any text within it.
//! Numbers agree within 1 % or one unit of the last digit shown; timings (wall, real-time
//! ratios, write times) are not compared. A shown output with an `Error:` line expects the
//! command to fail, any other the command to succeed.
//!
//! `PIPEARM_DOCS_BLESS=1 cargo test --release --test docs` rewrites the shown lines whose text
//! matches but whose numbers moved, from the runs (the figures regenerate); lines whose text
//! changed must be edited by hand.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{LazyLock, Mutex};

use regex::Regex;

/// Placeholders the docs write, and the shipped file or folder each runs on (`{root}` is the
/// scratch copy of the project).
const PLACEHOLDERS: &[(&str, &str)] =
    &[("my.toml", "scenarios/default.toml"), ("/abs/proj", "{root}"), ("~/", "{root}/home/"), ("/tmp/", "{root}/tmp/")];

/// Help examples too heavy for the suite, and the smaller run each stands for here (the pages
/// say theirs in a `<!-- doc-test: ... -->` marker).
const HELP_SIZES: &[(&str, &str)] = &[
    ("pipearm bench --quick", "pipearm bench scenarios/lab.toml --quick --repeats 1"),
    (
        "pipearm bench scenarios/default.toml scenarios/lab.toml --out docs/accuracy",
        "pipearm bench scenarios/lab.toml --quick --repeats 1 --out docs/accuracy",
    ),
];

/// Files and folders of the project a scratch copy holds.
const PROJECT_PARTS: &[&str] = &["scenarios", "robots", "tests/baselines", "docs", "scripts", "measurements"];

#[derive(Debug, Clone)]
struct Shown {
    /// The page, relative to the project.
    page: String,
    /// 1-based line of the command in the page.
    line: usize,
    command: String,
    /// The output lines shown, with their 1-based lines in the page.
    output: Vec<(usize, String)>,
    /// Whether a `cd` in it carries over to the next command: a walkthrough's shell block does;
    /// a `$ command` and a help example start where the page is.
    keeps_folder: bool,
    /// An edit of a file the page shows as a diff, made instead of running a command.
    edit: Option<Edit>,
}

/// A ```diff block marked `<!-- doc-test: edit PATH -->`: each hunk (hunks are split at a ` ...`
/// line) replaces its context and `-` lines by its context and `+` lines, found once in PATH.
#[derive(Debug, Clone)]
struct Edit {
    path: String,
    hunks: Vec<(String, String)>,
}

impl Shown {
    fn command(page: &str, line: usize, command: String, keeps_folder: bool) -> Self {
        Shown { page: page.into(), line, command, output: vec![], keeps_folder, edit: None }
    }
}

/// One page's commands in order, with the replacements its markers ask for.
#[derive(Debug, Default)]
struct Page {
    name: String,
    commands: Vec<Shown>,
}

fn fence(line: &str) -> Option<&str> {
    let t = line.trim_start();
    t.strip_prefix("```").or_else(|| t.strip_prefix("~~~")).map(str::trim)
}

/// A shell line that runs pipearm (or `cd`), after `cargo run --release --` is read as pipearm.
fn runs_pipearm(command: &str) -> bool {
    let re = Regex::new(r"(^|&&|;|\|)\s*(\w+=\S+\s+)*pipearm(\s|$)").unwrap();
    re.is_match(command) || command.starts_with("cd ")
}

fn markers(comment: &str) -> Vec<(String, String)> {
    comment
        .split(" ;; ")
        .filter_map(|pair| pair.split_once(" => ").map(|(a, b)| (a.trim().to_string(), b.trim().to_string())))
        .collect()
}

/// The shown commands of a Markdown page.
fn parse_page(name: &str, text: &str) -> Page {
    let lines: Vec<&str> = text.lines().collect();
    let mut page = Page { name: name.to_string(), commands: Vec::new() };
    let mut pending: Vec<(String, String)> = Vec::new();
    let mut edit_of: Option<String> = None;
    let mut last_shell_end: Option<usize> = None;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if let Some(rest) = line.trim().strip_prefix("<!-- doc-test:") {
            let rest = rest.trim_end_matches("-->").trim();
            match rest.strip_prefix("edit ") {
                Some(path) => edit_of = Some(path.trim().to_string()),
                None => pending = markers(rest),
            }
            i += 1;
            continue;
        }
        let Some(info) = fence(line) else {
            if !line.trim().is_empty() {
                last_shell_end = None;
            }
            i += 1;
            continue;
        };
        let start = i + 1;
        let mut end = start;
        while end < lines.len() && fence(lines[end]) != Some("") {
            end += 1;
        }
        let body: Vec<(usize, &str)> = (start..end.min(lines.len())).map(|k| (k + 1, lines[k])).collect();
        let replace = std::mem::take(&mut pending);
        let apply = |c: &str| replace.iter().fold(c.to_string(), |c, (a, b)| c.replace(a.as_str(), b.as_str()));
        let dollar = body.iter().any(|(_, l)| l.trim_start().starts_with("$ "));
        if let Some(path) = edit_of.take() {
            let mut edit = Shown::command(name, start + 1, format!("edit {path}"), true);
            edit.edit = Some(Edit { path, hunks: hunks(&body) });
            page.commands.push(edit);
            last_shell_end = None;
        } else if matches!(info, "sh" | "bash" | "shell") {
            let before = page.commands.len();
            for (line_no, command) in joined(&body) {
                let command = command.replace("cargo run --release --", "pipearm");
                if runs_pipearm(&command) {
                    page.commands.push(Shown::command(name, line_no, apply(&command), true));
                }
            }
            last_shell_end = (page.commands.len() > before).then_some(page.commands.len());
        } else if dollar {
            let mut current: Option<Shown> = None;
            for (line_no, l) in &body {
                if let Some(command) = l.trim_start().strip_prefix("$ ") {
                    page.commands.extend(current.take());
                    let command = command.replace("cargo run --release --", "pipearm");
                    current = runs_pipearm(&command).then(|| Shown::command(name, *line_no, apply(&command), false));
                } else if let Some(c) = current.as_mut() {
                    c.output.push((*line_no, l.to_string()));
                }
            }
            page.commands.extend(current);
            last_shell_end = None;
        } else if matches!(info, "" | "text" | "console")
            && let Some(n) = last_shell_end.take()
        {
            page.commands[n - 1].output = body.iter().map(|(k, l)| (*k, l.to_string())).collect();
        }
        i = end + 1;
    }
    page
}

/// A shell block's lines, continuations (`\` at the end) joined, comments and blanks left out.
fn joined(body: &[(usize, &str)]) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut open = false;
    for (line_no, l) in body {
        let t = l.trim();
        if open {
            let last = out.last_mut().unwrap();
            last.1.push(' ');
            last.1.push_str(t.trim_end_matches('\\').trim());
        } else if !t.is_empty() && !t.starts_with('#') {
            out.push((*line_no, t.trim_end_matches('\\').trim().to_string()));
        }
        open = t.ends_with('\\');
    }
    out
}

/// A diff block's hunks as (old text, new text), split at its ` ...` lines.
fn hunks(body: &[(usize, &str)]) -> Vec<(String, String)> {
    let mut out = vec![(Vec::new(), Vec::new())];
    for (_, l) in body {
        let (mark, text) = l.split_at(l.chars().next().map_or(0, char::len_utf8));
        if text.trim() == "..." {
            out.push((Vec::new(), Vec::new()));
            continue;
        }
        let (old, new) = out.last_mut().unwrap();
        match mark {
            "-" => old.push(text),
            "+" => new.push(text),
            _ => {
                old.push(text);
                new.push(text);
            }
        }
    }
    out.into_iter().filter(|(o, n)| o != n).map(|(o, n)| (o.join("\n"), n.join("\n"))).collect()
}

/// Applies `edit` in `folder`; the error says which hunk was not found once.
fn apply_edit(edit: &Edit, folder: &Path) -> Result<(), String> {
    let path = folder.join(&edit.path);
    let mut text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    for (old, new) in &edit.hunks {
        match text.matches(old.as_str()).count() {
            1 => text = text.replacen(old.as_str(), new, 1),
            n => return Err(format!("{}: the lines\n{old}\nare found {n} times, not once", edit.path)),
        }
    }
    std::fs::write(&path, text).map_err(|e| e.to_string())
}

/// The help examples of every command, as one page.
fn help_page(pipearm: &Path) -> Page {
    let help = |args: &[&str]| {
        let out = Command::new(pipearm).args(args).output().expect("pipearm runs");
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let top = help(&["--help"]);
    let commands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(String::from)
        .collect();
    assert!(commands.len() >= 10, "pipearm --help lists its commands: {top}");
    let mut page = Page { name: "--help examples".into(), commands: Vec::new() };
    for command in &commands {
        let text = help(&[command, "--help"]);
        let Some((_, examples)) = text.split_once("Examples:") else {
            panic!("`pipearm {command} --help` has no Examples: section");
        };
        // An example is its text up to two spaces (its comment), continued after a `\\`.
        let lines: Vec<(usize, &str)> = examples.lines().map(|l| (0, l.trim())).collect();
        for (_, line) in joined(&lines).into_iter().filter(|(_, l)| l.starts_with("pipearm ")) {
            let shown = line.split("  ").next().unwrap().trim().to_string();
            let shown = HELP_SIZES.iter().fold(shown, |c, (from, to)| if c == *from { to.to_string() } else { c });
            page.commands.push(Shown::command(&format!("pipearm {command} --help"), 0, shown, false));
        }
    }
    page
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// A scratch copy of the project for one page.
fn scratch(tag: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("pipearm-docs-{}-{tag}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    for part in PROJECT_PARTS {
        if root.join(part).exists() {
            copy_dir(&root.join(part), &dir.join(part));
        }
    }
    for file in ["README.md", "Cargo.toml"] {
        std::fs::copy(root.join(file), dir.join(file)).unwrap();
    }
    std::fs::create_dir_all(dir.join("tmp")).unwrap();
    std::fs::create_dir_all(dir.join("home")).unwrap();
    dir
}

/// `command` with its placeholders mapped into `root`: a path placeholder where a word (or an
/// option's `=value`) starts with it, a file name where it is the whole word.
fn mapped(command: &str, root: &Path) -> String {
    let root = root.to_str().unwrap();
    let map_word = |word: &str| -> String {
        let (head, value) = word.split_once('=').map_or(("", word), |(h, v)| (h, v));
        let eq = if head.is_empty() { "" } else { "=" };
        for (from, to) in PLACEHOLDERS {
            let to = to.replace("{root}", root);
            let is_path = from.starts_with(['/', '~']);
            if is_path && let Some(rest) = value.strip_prefix(from) {
                return format!("{head}{eq}{to}{rest}");
            }
            if !is_path && value == *from {
                return format!("{head}{eq}{to}");
            }
        }
        word.to_string()
    };
    command.split(' ').map(map_word).collect::<Vec<_>>().join(" ")
}

struct Ran {
    success: bool,
    output: String,
}

/// Runs `command` in the shell session whose folder is `cwd`, updating `cwd`.
fn run(command: &str, root: &Path, cwd: &mut PathBuf, bin: &Path) -> Ran {
    let cwd_file = root.join(".doc-test-cwd");
    let script = format!("exec 2>&1; cd \"$1\" || exit 1; {}\nrc=$?; pwd > \"$2\"; exit $rc", mapped(command, root));
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let out = Command::new("bash")
        .args(["-c", &script, "doc-test"])
        .arg(&*cwd)
        .arg(&cwd_file)
        .env("PATH", path)
        .env("HOME", root.join("home"))
        .env_remove("RUST_LOG")
        .env_remove("RUST_BACKTRACE")
        .env_remove("RUST_LIB_BACKTRACE")
        .output()
        .expect("bash runs");
    if let Ok(dir) = std::fs::read_to_string(&cwd_file) {
        *cwd = PathBuf::from(dir.trim());
    }
    let root_text = root.to_str().unwrap();
    let output = String::from_utf8_lossy(&out.stdout)
        .replace(&format!("{root_text}/tmp/"), "/tmp/")
        .replace(&format!("{root_text}/home/"), "~/")
        .replace(&format!("{root_text}/"), "")
        .replace(root_text, ".");
    Ran { success: out.status.success(), output }
}

// ---- comparing shown output ----

const NUMBER: &str = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?";

/// Timings: compared as text, never as numbers.
fn redact_timings(line: &str) -> String {
    static TIMINGS: LazyLock<Vec<(Regex, &str)>> = LazyLock::new(|| {
        [
            (r"wall \S+ s", "wall [t] s"),
            (r"\(\S+x real time\)", "([t]x real time)"),
            (r"\S+ s from reading", "[t] s from reading"),
            (r"MB, \S+ s\)", "MB, [t] s)"),
            (r"MB, \S+ s$", "MB, [t] s"),
        ]
        .into_iter()
        .map(|(p, r)| (Regex::new(p).unwrap(), r))
        .collect()
    });
    TIMINGS.iter().fold(line.to_string(), |l, (p, r)| p.replace_all(&l, *r).into_owned())
}

fn normalise(line: &str) -> String {
    redact_timings(&line.split_whitespace().collect::<Vec<_>>().join(" "))
}

/// A shown line as a pattern: its numbers as captures, `[..]` and a trailing `...` as any text.
fn pattern(shown: &str) -> (Regex, Vec<String>) {
    let shown = normalise(shown);
    let (body, open_end) = match shown.strip_suffix("...").or_else(|| shown.strip_suffix('…')) {
        Some(b) => (b.trim_end().to_string(), true),
        None => (shown.clone(), false),
    };
    let numbers = Regex::new(NUMBER).unwrap();
    let mut re = String::from("^");
    let mut expected = Vec::new();
    for (k, piece) in body.split("[..]").enumerate() {
        if k > 0 {
            re.push_str(".*?");
        }
        let mut last = 0;
        for m in numbers.find_iter(piece) {
            re.push_str(&regex::escape(&piece[last..m.start()]));
            re.push_str(&format!("({NUMBER})"));
            expected.push(m.as_str().to_string());
            last = m.end();
        }
        re.push_str(&regex::escape(&piece[last..]));
    }
    re.push_str(if open_end { ".*$" } else { "$" });
    (Regex::new(&re).unwrap(), expected)
}

/// Whether `actual` agrees with `expected`: within 1 % or one unit of the last digit shown.
fn number_agrees(expected: &str, actual: &str) -> bool {
    let (Ok(e), Ok(a)) = (expected.parse::<f64>(), actual.parse::<f64>()) else { return expected == actual };
    let mantissa = expected.split(['e', 'E']).next().unwrap();
    let exponent: i32 = expected.split(['e', 'E']).nth(1).map_or(0, |x| x.parse().unwrap_or(0));
    // Integers (counts, mode numbers) agree within 1 % only: one unit of a count is a change.
    let Some((_, decimals)) = mantissa.split_once('.') else { return (a - e).abs() <= 0.01 * e.abs().max(a.abs()) };
    let unit = 10f64.powi(exponent - decimals.len() as i32);
    (a - e).abs() <= (0.01 * e.abs().max(a.abs())).max(unit * 1.000001)
}

#[derive(Debug)]
enum LineMatch {
    Same,
    /// The text matches but a number moved: the actual line.
    Moved(String),
}

/// How `actual` (its raw and normalised text) meets a shown line's pattern.
fn match_line((re, expected): &(Regex, Vec<String>), (raw, normalised): (&str, &str)) -> Option<LineMatch> {
    let caps = re.captures(normalised)?;
    let agree = expected.iter().enumerate().all(|(k, e)| number_agrees(e, &caps[k + 1]));
    Some(if agree { LineMatch::Same } else { LineMatch::Moved(raw.trim_end().to_string()) })
}

/// Compares the shown output with the actual, in order. Returns the failures and the lines a
/// bless would rewrite (page line, new text).
fn compare(shown: &[(usize, String)], actual: &str) -> (Vec<String>, Vec<(usize, String)>) {
    let actual: Vec<(&str, String)> = actual.lines().map(|l| (l, normalise(l))).collect();
    let (mut failures, mut moved) = (Vec::new(), Vec::new());
    let mut at = 0;
    for (line_no, s) in shown {
        let t = s.trim();
        if t.is_empty() || t == "..." || t == "…" {
            continue;
        }
        let shown_pattern = pattern(t);
        let found = actual[at..]
            .iter()
            .enumerate()
            .find_map(|(k, (raw, normalised))| match_line(&shown_pattern, (raw, normalised)).map(|m| (k, m)));
        match found {
            Some((k, m)) => {
                at += k + 1;
                if let LineMatch::Moved(new) = m {
                    failures.push(format!("line {line_no}: shown `{t}`\n    but ran `{new}`"));
                    let indent = &s[..s.len() - s.trim_start().len()];
                    moved.push((*line_no, format!("{indent}{}", new.trim_start())));
                }
            }
            None => failures.push(format!("line {line_no}: shown `{t}` is not in the output (in order)")),
        }
    }
    (failures, moved)
}

/// Runs a page's commands in a scratch copy; returns the failures and the blessable lines.
fn run_page(page: &Page, tag: &str, bin: &Path) -> (Vec<String>, Vec<(String, usize, String)>, usize) {
    let root = scratch(tag);
    let mut cwd = root.clone();
    let (mut failures, mut moved) = (Vec::new(), Vec::new());
    for shown in &page.commands {
        let where_ = if shown.line > 0 { format!("{}:{}", shown.page, shown.line) } else { shown.page.clone() };
        if let Some(edit) = &shown.edit {
            if let Err(e) = apply_edit(edit, &cwd) {
                failures.push(format!("{where_}: the page's edit does not apply: {e}"));
            }
            continue;
        }
        let mut folder = cwd.clone();
        let started = std::time::Instant::now();
        let ran = run(&shown.command, &root, &mut folder, bin);
        let seconds = started.elapsed().as_secs_f64();
        if seconds > 20.0 {
            println!("{where_}: `{}` took {seconds:.0} s", shown.command);
        }
        if shown.keeps_folder {
            cwd = folder;
        }
        let expects_error = shown.output.iter().any(|(_, l)| l.trim_start().starts_with("Error:"));
        if ran.success == expects_error {
            let what = if expects_error { "succeeded, the page shows it failing" } else { "failed" };
            failures.push(format!("{where_}: `{}` {what}:\n{}", shown.command, tail(&ran.output)));
            continue;
        }
        let (f, m) = compare(&shown.output, &ran.output);
        if !f.is_empty() {
            failures.push(format!(
                "{where_}: `{}`: its shown output differs:\n  {}\n  output was:\n{}",
                shown.command,
                f.join("\n  "),
                tail(&ran.output)
            ));
        }
        moved.extend(m.into_iter().map(|(line, text)| (shown.page.clone(), line, text)));
    }
    std::fs::remove_dir_all(&root).ok();
    (failures, moved, page.commands.len())
}

fn tail(output: &str) -> String {
    let lines: Vec<&str> = output.lines().collect();
    lines[lines.len().saturating_sub(25)..].iter().map(|l| format!("    | {l}")).collect::<Vec<_>>().join("\n")
}

fn doc_pages() -> Vec<Page> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md"), root.join("robots/README.md")];
    let mut stack = vec![root.join("docs")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
        .iter()
        .map(|f| {
            let name = f.strip_prefix(root).unwrap().to_str().unwrap().to_string();
            parse_page(&name, &std::fs::read_to_string(f).unwrap())
        })
        .filter(|p| !p.commands.is_empty())
        .collect()
}

fn bless(moved: &[(String, usize, String)]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut by_page: BTreeMap<&str, Vec<(usize, &str)>> = BTreeMap::new();
    for (page, line, text) in moved {
        by_page.entry(page.as_str()).or_default().push((*line, text.as_str()));
    }
    for (page, edits) in by_page {
        let path = root.join(page);
        let Ok(text) = std::fs::read_to_string(&path) else { continue };
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        for (line, new) in edits {
            lines[line - 1] = new.to_string();
        }
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        eprintln!("blessed {page}");
    }
}

#[test]
fn every_documented_command_runs_and_shows_its_output() {
    // PIPEARM_DOCS_BIN runs the docs against another build (an installed pipearm, say).
    let pipearm =
        std::env::var_os("PIPEARM_DOCS_BIN").map_or(PathBuf::from(env!("CARGO_BIN_EXE_pipearm")), PathBuf::from);
    let bin = pipearm.parent().unwrap().to_path_buf();
    let mut pages = doc_pages();
    pages.push(help_page(&pipearm));
    let total: usize = pages.iter().map(|p| p.commands.len()).sum();
    assert!(
        total >= 40,
        "the docs show {total} pipearm commands; expected the README's, the tutorial's, the reference's"
    );
    let queue = Mutex::new(pages.iter().enumerate().collect::<Vec<_>>());
    let results = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                while let Some((k, page)) = queue.lock().unwrap().pop() {
                    let result = run_page(page, &k.to_string(), &bin);
                    results.lock().unwrap().push((page.name.clone(), result));
                }
            });
        }
    });
    let mut results = results.into_inner().unwrap();
    results.sort_by(|a, b| a.0.cmp(&b.0));
    let (mut failures, mut moved, mut ran) = (Vec::new(), Vec::new(), 0);
    for (name, (f, m, n)) in results {
        println!("{name}: {n} commands run, {} failing", f.len());
        failures.extend(f);
        moved.extend(m);
        ran += n;
    }
    println!("{ran} documented commands run");
    if std::env::var_os("PIPEARM_DOCS_BLESS").is_some() {
        bless(&moved);
    }
    assert!(failures.is_empty(), "{} of {ran} documented commands fail:\n\n{}", failures.len(), failures.join("\n\n"));
}

#[test]
fn shown_output_is_compared_by_text_with_numbers_in_tolerance() {
    let actual = "model  modal(3), rk4\ncontact peak 795.4 N at 14.976 s, 5 impacts\nsimulated 20 s, wall 0.011 s (1857x real time)\n";
    let shown = |lines: &[&str]| lines.iter().enumerate().map(|(k, l)| (k + 1, l.to_string())).collect::<Vec<_>>();
    // Numbers within 1 %, timings not compared, lines in order with others between.
    assert!(
        compare(&shown(&["model modal(3), rk4", "simulated 20 s, wall 0.5 s (9x real time)"]), actual).0.is_empty()
    );
    assert!(compare(&shown(&["contact peak 799.0 N at 14.9 s, 5 impacts"]), actual).0.is_empty());
    // A number out of tolerance, an integer that changed, a line missing or out of order fail.
    let (failures, moved) = compare(&shown(&["contact peak 820.0 N at 14.976 s, 5 impacts"]), actual);
    assert_eq!(failures.len(), 1);
    assert_eq!(moved[0].1, "contact peak 795.4 N at 14.976 s, 5 impacts");
    assert_eq!(compare(&shown(&["model modal(4), rk4"]), actual).0.len(), 1);
    assert_eq!(compare(&shown(&["contact peak 795.4 N at 14.976 s, 6 impacts"]), actual).0.len(), 1);
    assert_eq!(
        compare(&shown(&["simulated 20 s, wall 0.011 s (1857x real time)", "model modal(3), rk4"]), actual).0.len(),
        1
    );
    // `[..]` and a trailing `...` stand for any text.
    assert!(compare(&shown(&["contact peak [..] 5 impacts", "simulated ..."]), actual).0.is_empty());
    // One unit of the last digit shown: 0.000 % against 0.001 %.
    assert!(number_agrees("0.000", "0.001") && !number_agrees("0.000", "0.003"));
    assert!(!number_agrees("4", "3") && number_agrees("1000", "1009"));
}

#[test]
fn pages_are_parsed_into_commands_outputs_and_markers() {
    let page = parse_page(
        "p.md",
        "Run it:\n\n```sh\ncd my_arm\npipearm run \\\n  --csv   # tables\npip install x\n```\n\n```\nmodel modal(3)\n```\n\n\
         <!-- doc-test: --samples 1000 => --samples 8 -->\n```console\n$ pipearm envelope a.toml --samples 1000\n  all 1185\n$ rerun x.rrd\n```\n",
    );
    let commands: Vec<&str> = page.commands.iter().map(|c| c.command.as_str()).collect();
    assert_eq!(commands, ["cd my_arm", "pipearm run --csv   # tables", "pipearm envelope a.toml --samples 8"]);
    assert_eq!(page.commands[1].output, [(11, "model modal(3)".to_string())]);
    assert_eq!(page.commands[2].output, [(17, "  all 1185".to_string())]);
    assert_eq!(page.commands[1].line, 5);
}

#[test]
fn a_marked_diff_block_edits_its_file_or_says_why_not() {
    let page = parse_page(
        "p.md",
        "<!-- doc-test: edit a.toml -->\n```diff\n [x]\n-k = 1\n+k = 2\n ...\n-z = 3\n+z = 4\n```\n",
    );
    let edit = page.commands[0].edit.clone().expect("an edit");
    let dir = std::env::temp_dir().join(format!("pipearm-docs-edit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.toml"), "[x]\nk = 1\ny = 0\nz = 3\n").unwrap();
    apply_edit(&edit, &dir).unwrap();
    assert_eq!(std::fs::read_to_string(dir.join("a.toml")).unwrap(), "[x]\nk = 2\ny = 0\nz = 4\n");
    // Applied again, its lines are no longer there: the page and the file disagree.
    assert!(apply_edit(&edit, &dir).unwrap_err().contains("found 0 times"));
    std::fs::remove_dir_all(&dir).ok();
}
