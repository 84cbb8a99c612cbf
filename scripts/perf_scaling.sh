#!/usr/bin/env bash
# Cost against work (docs/performance.md): wall time per simulated second of the default scene
# (no recording, one thread, median of 5 runs) as the modes, the FE elements, the pads and the
# string grow, under generalized-alpha at the scene's step (the shipped RK4 is stable for the
# three modes `auto` keeps, not for eight modes or the FE arm at that step).
# Usage: scripts/perf_scaling.sh [path/to/pipearm]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}/release/pipearm}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ROOT=$PWD
BASE="$TMP/base.toml"
sed "s#^robot = .*#robot = \"$ROOT/robots/pipe_arm.urdf\"#; s#^kind = \"rk4\"#kind = \"generalized-alpha\"\nrho_inf = 0.8#" \
    scenarios/default.toml > "$BASE"

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}'; }
# Wall seconds of the step loop per simulated second.
cost() {
    for _ in 1 2 3 4 5; do
        "$B" run --no-record "$@" | sed -n 's/.*simulated *\([0-9.]*\) s in .* wall \([0-9.]*\) s.*/\2 \1/p' |
            awk '{printf "%.6e\n", $1 / $2}'
    done | median
}
row() { printf '| %s | %s | %.2e | %.0f |\n' "$1" "$2" "$3" "$(awk -v c="$3" 'BEGIN {print 1 / c}')"; }
# Least-squares slope of log(cost) on log(work) over "work cost" lines.
slope() { awk '{x = log($1); y = log($2); n++; sx += x; sy += y; sxx += x * x; sxy += x * y}
               END {printf "%.2f", (n * sxy - sx * sy) / (n * sxx - sx * sx)}'; }

echo "| axis | value | cost (s per simulated s) | real time × |"
echo "|---|---|---|---|"
: > "$TMP/modes"
for n in 1 2 3 4 6 8; do
    c=$(cost --model "modal:$n" "$BASE")
    row modes "$n" "$c"
    echo "$n $c" >> "$TMP/modes"
done
: > "$TMP/elements"
for e in 6 12 24 48; do
    sed "s/elements=\"24\"/elements=\"$e\"/" robots/pipe_arm.urdf > "$TMP/arm_$e.urdf"
    sed "s#^robot = .*#robot = \"$TMP/arm_$e.urdf\"#" "$BASE" > "$TMP/fe_$e.toml"
    c=$(cost --model fe "$TMP/fe_$e.toml")
    row "fe elements" "$e" "$c"
    echo "$e $c" >> "$TMP/elements"
done
: > "$TMP/pads"
for p in 1 2 4 8; do
    cp "$BASE" "$TMP/pads_$p.toml"
    # Extra pads at the same stop, further along the arm (they are struck too).
    for k in $(seq 2 "$p"); do
        station=$(awk -v k="$k" 'BEGIN {printf "%.2f", 8.2 - 0.4 * (k - 1)}')
        cat >> "$TMP/pads_$p.toml" <<EOF
[[dampeners]]
name = "pad_$k"
angle_deg = 90.0
station_m = $station
face = "upper"
gap_m = 0.0002
thickness_m = 0.025
length_m = 0.075
width_m = 0.075
law = { kind = "hunt-crossley", stiffness = 7.5e6, exponent = 1.0, restitution = 0.6 }
EOF
    done
    c=$(cost "$TMP/pads_$p.toml")
    row pads "$p" "$c"
    echo "$p $c" >> "$TMP/pads"
done
for size in 2-3/8 2-7/8 3-1/2 4-1/2; do
    sed "s#size = \"2-7/8\"#size = \"$size\"#" "$BASE" > "$TMP/string.toml"
    row "string" "$size in" "$(cost "$TMP/string.toml")"
done
echo
echo "fitted growth, cost ∝ work^p: modes p = $(slope < "$TMP/modes"), fe elements p = $(slope < "$TMP/elements"), pads p = $(slope < "$TMP/pads")"
