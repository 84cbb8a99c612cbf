#!/usr/bin/env bash
# Speed of a 1000-run envelope of the default scene (docs/envelope.md): wall time with --threads 1
# and --threads 2 (fresh folders, nothing skipped), and for reference the in-process `total` that
# `pipearm run --no-record` prints for single runs of the same scene (reading the scenario to the
# end), ROUNDS rounds interleaved in one session. Prints each round, then the medians: the
# parallel efficiency t1/(2 t2), and t2 against SAMPLES single runs' totals / 2 (goal <= 1.2).
# Usage: envelope_timing.sh [PIPEARM] [SAMPLES] [ROUNDS] [SINGLE_RUNS_PER_ROUND]
set -euo pipefail
cd "$(dirname "$0")/.."
PIPEARM=${1:-pipearm}
SAMPLES=${2:-1000}
ROUNDS=${3:-5}
SINGLE=${4:-20}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
SPREADS=(--spread dampeners.0.gap_m=uniform:0.0001..0.0003
         --spread dampeners.0.law.stiffness=uniform:6e6..9e6
         --spread arm.damping_ratios.0=uniform:0.005..0.02
         --spread drive.duration_s=uniform:14..16)
envelope() { # threads → wall seconds
  rm -rf "$TMP/out"
  local w0=$EPOCHREALTIME
  "$PIPEARM" envelope scenarios/default.toml "${SPREADS[@]}" --samples "$SAMPLES" \
    --sensitivity regression --threads "$1" --out "$TMP/out" > /dev/null
  echo "$EPOCHREALTIME - $w0" | bc -l
}
single() { # SINGLE runs → mean in-process total, seconds
  for _ in $(seq "$SINGLE"); do
    "$PIPEARM" run scenarios/default.toml --no-record | awk '$1 == "total" {print $2}'
  done | awk '{s += $1} END {print s / NR}'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
: > "$TMP/rounds"
for round in $(seq "$ROUNDS"); do
  S=$(single); T2=$(envelope 2); T1=$(envelope 1)
  echo "$S $T1 $T2" >> "$TMP/rounds"
  printf 'round %d: single run total %.4f s, envelope 1 thread %.2f s, 2 threads %.2f s\n' "$round" "$S" "$T1" "$T2"
done
EFF=$(awk '{print $2 / (2 * $3)}' "$TMP/rounds" | median)
GOAL=$(awk -v n="$SAMPLES" '{print $3 / (n * $1 / 2)}' "$TMP/rounds" | median)
PER=$(awk -v n="$SAMPLES" '{print $2 / (n * $1)}' "$TMP/rounds" | median)
printf 'medians over %d rounds: parallel efficiency t1/(2 t2) = %.1f %%; 1 thread per run against a single run = %.2f;\n' \
  "$ROUNDS" "$(echo "100 * $EFF" | bc -l)" "$PER"
printf '2 threads against %d single runs / 2 = %.3f (goal <= 1.2)\n' "$SAMPLES" "$GOAL"
