#!/usr/bin/env bash
# Writes docs/validation.md: every check of the test suite against an independent truth, from
# the tests' own output. Runs `cargo test --release -- --nocapture` (the whole suite), gathers
# the `validation|...` lines the tests print (tests/common/mod.rs, `validated*`), and writes one
# table per area. Fails, writing nothing, if a test fails or no check was printed.
#
# Usage: scripts/validation.sh                 run the suite and write docs/validation.md
#        scripts/validation.sh --from-log FILE  write it from the saved output of such a run
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}
PAGE=docs/validation.md
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

if [ "${1:-}" = "--from-log" ]; then
    cp "$2" "$WORK/log"
else
    LOG=$CARGO_TARGET_DIR/validation.log
    mkdir -p "$CARGO_TARGET_DIR"
    if ! cargo test --release -- --nocapture > "$LOG" 2>&1; then
        grep -E "^test .*FAILED|panicked|^error" "$LOG" | head -40 >&2 || true
        echo "validation.sh: cargo test --release failed (output in $LOG); $PAGE left as it was" >&2
        exit 1
    fi
    cp "$LOG" "$WORK/log"
fi

# A line may follow libtest's "test name ... " on the same line: take it from its marker.
grep -o 'validation|.*' "$WORK/log" > "$WORK/rows" || true
rows=$(wc -l < "$WORK/rows")
if [ "$rows" -eq 0 ]; then
    echo "validation.sh: no validation rows in the tests' output" >&2
    exit 1
fi
# Every row: the marker and 9 fields, a named test.
bad=$(awk -F'|' 'NF != 10 || $10 ~ /::\?$/' "$WORK/rows" | head -5)
if [ -n "$bad" ]; then
    printf 'validation.sh: malformed rows:\n%s\n' "$bad" >&2
    exit 1
fi

# By area, then by test; a test's rows in the order it printed them.
sort -t'|' -s -k2,2n -k10,10 "$WORK/rows" > "$WORK/sorted"

{
    cat <<'EOF'
<!-- Written by scripts/validation.sh from the tests' output: edit the tests, not this page. -->
# Validation: pipearm against independent truths

Each row below is an assertion of pipearm's test suite that holds a number pipearm computes to a
truth it does not compute itself: a closed form, a finer model (the full finite-element arm, a
finer time step, the unreduced beams) or a published number. The measured values are the ones the
tests computed on the run that wrote this page, and the tolerance is what the test asserts: a row
outside its tolerance fails `cargo test --release`.

To re-measure, run `scripts/validation.sh` from the project's root. It runs the whole suite
(`cargo test --release -- --nocapture`), gathers the rows the tests print, and rewrites this page;
if a test fails it stops and leaves the page as it was.

The columns:

- **check**: what is computed, on which model or scene;
- **truth (source)**: the value it is held to, and where that value comes from;
- **measured**: what the test computed;
- **error**: measured against truth, relative unless a unit is given (in per cent from 0.1 %, as
  a fraction below);
- **tolerance**: what the test asserts;
- **test**: the test, as `file::function` under `tests/`.

The areas:

EOF
    awk -F'|' '!seen[$2]++ {
        anchor = tolower($3); gsub(/[^a-z0-9 -]/, "", anchor); gsub(/ /, "-", anchor)
        printf "- [%s](#%s)\n", $3, anchor
    }' "$WORK/sorted"
    awk -F'|' '
        $2 != area {
            area = $2
            printf "\n## %s\n\n%s\n\n", $3, $4
            print "| check | truth (source) | measured | error | tolerance | test |"
            print "|---|---|---|---|---|---|"
        }
        { printf "| %s | %s | %s | %s | %s | `%s` |\n", $5, $6, $7, $8, $9, $10 }
    ' "$WORK/sorted"
} > "$WORK/page"
mv "$WORK/page" "$PAGE"
echo "wrote $PAGE: $rows checks in $(cut -d'|' -f2 "$WORK/sorted" | sort -u | wc -l) areas"
