#!/usr/bin/env bash
# The speed target of docs/performance.md: the default scene (20 s simulated) with its recording,
# on one core (the script pins itself to CPU 0 with taskset, and each run inherits it), N runs
# (default 31). Prints the medians and quartiles of
#   - the step loop        (`wall` that `pipearm run` prints),
#   - writing the recording (the `wrote` line),
#   - the in-process total  (`total`: scenario read -> last file written),
#   - the whole command     (process start and exit included, measured here with bash's
#                            EPOCHREALTIME: no process forked for the clock).
# Usage: scripts/target.sh [path/to/pipearm] [runs]
set -euo pipefail
if [ -z "${PIPEARM_PINNED:-}" ]; then
    PIPEARM_PINNED=1 exec taskset -c 0 bash "$0" "$@"
fi
cd "$(dirname "$0")/.."
B=${1:-${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}/release/pipearm}
N=${2:-31}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

for _ in $(seq "$N"); do
    start=$EPOCHREALTIME
    "$B" run --out "$OUT" > "$OUT/stdout"
    end=$EPOCHREALTIME
    loop=$(sed -n 's/.*wall \([0-9.]*\) s.*/\1/p' "$OUT/stdout")
    rec=$(sed -n 's/.*MB, \([0-9.]*\) s).*/\1/p' "$OUT/stdout")
    total=$(sed -n 's/^total *\([0-9.]*\) s.*/\1/p' "$OUT/stdout")
    echo "$loop $rec $total $(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.4f", b - a}')"
done > "$OUT/times"

stats() {
    sort -g | awk '{a[NR] = $1} END {printf "median %.4f s (quartiles %.4f-%.4f): %.0fx real time\n",
        a[int((NR + 1) / 2)], a[int((NR + 3) / 4)], a[int((3 * NR + 1) / 4)], 20 / a[int((NR + 1) / 2)]}'
}
echo "step loop          $(cut -d' ' -f1 "$OUT/times" | stats)"
echo "recording          $(cut -d' ' -f2 "$OUT/times" | stats)"
echo "in-process total   $(cut -d' ' -f3 "$OUT/times" | stats)"
echo "whole command      $(cut -d' ' -f4 "$OUT/times" | stats)"
