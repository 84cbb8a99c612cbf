#!/usr/bin/env bash
# What the recording adds to the default run's whole command: N interleaved pairs (default 41)
# of `pipearm run` (recording and summary written) and `pipearm run --no-record` (nothing
# written), each pair timed back to back in alternating order, with bash's EPOCHREALTIME (no
# process forked for the clock). Prints the median of the paired ratios with its quartiles, and
# the median times. Machines differ from one session to the next; the ratio is what compares.
# Usage: scripts/recording_cost.sh [path/to/pipearm] [pairs]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}/release/pipearm}
N=${2:-41}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

timed() {
    local start=$EPOCHREALTIME
    "$B" run "$@" > /dev/null
    awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN {printf "%.5f", b - a}'
}
"$B" run --out "$OUT" > /dev/null # warm the file cache
for i in $(seq "$N"); do
    if (( i % 2 )); then
        with=$(timed --out "$OUT"); without=$(timed --no-record)
    else
        without=$(timed --no-record); with=$(timed --out "$OUT")
    fi
    echo "$with $without"
done > "$OUT/times"

median() {
    sort -g | awk '{a[NR] = $1} END {printf "%.4f (quartiles %.4f-%.4f)", a[int((NR + 1) / 2)], a[int((NR + 3) / 4)], a[int((3 * NR + 1) / 4)]}'
}
echo "with the recording      $(cut -d' ' -f1 "$OUT/times" | median) s"
echo "without (--no-record)   $(cut -d' ' -f2 "$OUT/times" | median) s"
echo "ratio, paired           $(awk '{printf "%.4f\n", $1 / $2}' "$OUT/times" | median)"
