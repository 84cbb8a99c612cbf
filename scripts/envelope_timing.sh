#!/usr/bin/env bash
# Speed of a 1000-run envelope of the default scene (docs/envelope.md): wall time with --threads 1
# and --threads 2 (fresh folders, nothing skipped), and the whole-process time of single runs of
# the same scene (`pipearm run --no-record`) for reference, all in the same session.
# Prints t1, t2, the parallel efficiency t1/(2 t2), and t1 against SAMPLES single runs.
# Usage: envelope_timing.sh [PIPEARM] [SAMPLES] [SINGLE_RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
PIPEARM=${1:-pipearm}
SAMPLES=${2:-1000}
SINGLE=${3:-20}
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
single() { # SINGLE whole-process runs → mean wall seconds
  local w0=$EPOCHREALTIME
  for _ in $(seq "$SINGLE"); do "$PIPEARM" run scenarios/default.toml --no-record > /dev/null; done
  echo "($EPOCHREALTIME - $w0) / $SINGLE" | bc -l
}
S0=$(single)
T2=$(envelope 2)
T1=$(envelope 1)
S1=$(single)
S=$(echo "($S0 + $S1) / 2" | bc -l)
printf 'single run (whole process, mean of %d before and after): %.4f s\n' "$((2 * SINGLE))" "$S"
printf 'envelope of %d runs: 1 thread %.2f s (%.4f s a run, %.2f x a single run), 2 threads %.2f s\n' \
  "$SAMPLES" "$T1" "$(echo "$T1 / $SAMPLES" | bc -l)" "$(echo "$T1 / ($SAMPLES * $S)" | bc -l)" "$T2"
printf 'parallel efficiency t1/(2 t2) = %.1f %%; 2 threads against %d single runs / 2: %.3f (goal <= 1.2)\n' \
  "$(echo "100 * $T1 / (2 * $T2)" | bc -l)" "$SAMPLES" "$(echo "$T2 / ($SAMPLES * $S / 2)" | bc -l)"
