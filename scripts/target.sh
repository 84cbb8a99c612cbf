#!/usr/bin/env bash
# The speed target of docs/performance.md: the default scene (20 s simulated) with its recording,
# on one core (taskset -c 0: rerun's threads share it), N runs (default 31). Prints the medians
# and quartiles of
#   - the step loop        (`wall` that `pipearm run` prints),
#   - writing the recording (the `wrote` line),
#   - the in-process total  (`total`: scenario read -> last file written),
#   - the whole command     (process start and exit included, measured here).
# Usage: scripts/target.sh [path/to/pipearm] [runs]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}/release/pipearm}
N=${2:-31}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

for _ in $(seq "$N"); do
    start=$(date +%s%N)
    taskset -c 0 "$B" run --out "$OUT" > "$OUT/stdout"
    end=$(date +%s%N)
    loop=$(sed -n 's/.*wall \([0-9.]*\) s.*/\1/p' "$OUT/stdout")
    rec=$(sed -n 's/.*MB, \([0-9.]*\) s).*/\1/p' "$OUT/stdout")
    total=$(sed -n 's/^total *\([0-9.]*\) s.*/\1/p' "$OUT/stdout")
    echo "$loop $rec $total $(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.4f", (b - a) / 1e9}')"
done > "$OUT/times"

stats() {
    sort -g | awk '{a[NR] = $1} END {printf "median %.4f s (quartiles %.4f-%.4f): %.0fx real time\n",
        a[int((NR + 1) / 2)], a[int((NR + 3) / 4)], a[int((3 * NR + 1) / 4)], 20 / a[int((NR + 1) / 2)]}'
}
echo "step loop          $(cut -d' ' -f1 "$OUT/times" | stats)"
echo "recording          $(cut -d' ' -f2 "$OUT/times" | stats)"
echo "in-process total   $(cut -d' ' -f3 "$OUT/times" | stats)"
echo "whole command      $(cut -d' ' -f4 "$OUT/times" | stats)"
