#!/usr/bin/env bash
# The cost table of docs/drives.md: scenes run in interleaved rounds, each round started when no
# compiler, no pipearm of the shared target dir and no other run of PIPEARM runs; a round during
# which one started is marked dirty. Prints: round, scene, in-process `total` (s), the summary's simulation `wall` (s), the
# process's user+sys CPU (s, from a second run), clean|dirty.
#
# Usage: PIPEARM=BINARY scripts/drives_timing.sh ROUNDS SCENARIO...   (recordings go to $OUT,
# default /tmp/drives-timing). PIPEARM is a built binary, not cargo: a copy outside the target dir,
# which another build may relink mid-run.
set -u
P=${PIPEARM:?set PIPEARM to the pipearm binary}; R=$1; shift 1
OUT=${OUT:-/tmp/drives-timing}
mkdir -p "$OUT"
busy() {
  pgrep -x rustc >/dev/null || pgrep -x cargo >/dev/null || pgrep -f "pipearm-target/release" >/dev/null ||
    pgrep -f "^$P " >/dev/null
}
TIMEFORMAT='%U %S'
for r in $(seq 1 $R); do
  while busy; do sleep 1; done
  sleep 1
  lines=()
  for s in "$@"; do
    out=$("$P" run "$s" --out "$OUT" 2>&1)
    { time "$P" run "$s" --out "$OUT" >/dev/null 2>&1; } 2>"$OUT/cpu.txt"
    cpu=$(awk '{print $1+$2}' "$OUT/cpu.txt")
    total=$(grep '^total' <<<"$out" | awk '{print $2}')
    wall=$(grep '^simulated' <<<"$out" | sed 's/.*wall \([0-9.]*\) s.*/\1/')
    lines+=("$r $(basename $s .toml) $total $wall $cpu")
  done
  if busy; then tag=dirty; else tag=clean; fi
  for l in "${lines[@]}"; do echo "$l $tag"; done
done
