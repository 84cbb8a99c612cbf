#!/usr/bin/env bash
# The chart of docs/drives.md: peak contact force against string weight for the ideal drive (pad
# 0.2 mm clear, as scenarios/default.toml; and pad at the stop, as the actuated scenes), the servo
# and the hydraulic drive, over every string of the pipe catalogue, drawn on one chart.
#
# Usage: [PIPEARM=BINARY] scripts/drives_chart.sh [OUT_DIR]
#   PIPEARM  the pipearm binary (default: `cargo run --release --`)
#   OUT_DIR  the sweeps' folders (default: recordings/drives-sweep)
set -euo pipefail
cd "$(dirname "$0")/.."
read -r -a pipearm <<<"${PIPEARM:-cargo run --release --}"
out=${1:-recordings/drives-sweep}
sizes='payload.size=2-3/8,2-7/8,3-1/2,4-1/2'

"${pipearm[@]}" sweep scenarios/default.toml --vary "$sizes" --out "$out/ideal-gap"
# The hydraulic scene with its actuator set to ideal: the same pad at the stop, step and settling.
"${pipearm[@]}" sweep scenarios/hydraulic.toml --vary "$sizes" --vary 'actuator={kind="ideal"}' --out "$out/ideal-at-stop"
"${pipearm[@]}" sweep scenarios/servo.toml --vary "$sizes" --out "$out/servo"
"${pipearm[@]}" sweep scenarios/hydraulic.toml --vary "$sizes" --out "$out/hydraulic"
"${pipearm[@]}" sweep chart "$out/ideal-gap" "$out/ideal-at-stop" "$out/servo" "$out/hydraulic" \
  --label 'ideal, pad 0.2 mm clear (default.toml)' --label 'ideal, pad at the stop' \
  --label 'servo (servo.toml)' --label 'hydraulic (hydraulic.toml)' \
  --title 'default lift, 0 → 90° in 15 s: peak pad force against string weight' \
  --out docs/drives-force-vs-weight.svg
