#!/usr/bin/env bash
# Writes measurements/rig.csv, the rig log the docs' `compare` and `fit` examples read: the default
# lift with a stiffer pad (stiffness 9.0e6 for the scenario's 7.5e6), run at 0.5 ms, sampled every
# 3 ms, the logger's clock 7 ms late, noisy by 0.01 mm and 5 N (seeded, so the file is the same on
# every machine with the same binary).
#   scripts/make_rig_csv.sh            # with `cargo run --release --`
#   PIPEARM=pipearm scripts/make_rig_csv.sh
set -euo pipefail
cd "$(dirname "$0")/.."
pipearm=${PIPEARM:-cargo run --release --}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/scenarios"
cp -r robots "$work/robots"
sed 's/stiffness = 7.5e6/stiffness = 9.0e6/' scenarios/default.toml > "$work/scenarios/rig.toml"
grep -q 'stiffness = 9.0e6' "$work/scenarios/rig.toml"
$pipearm run "$work/scenarios/rig.toml" --step 0.0005 --csv --no-record --out "$work" >/dev/null
python3 - "$work/default.steps.csv" measurements/rig.csv <<'PY'
import csv, random, sys
rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["t[s]"]) for r in rows]
tip = [float(r["tip_deflection.transverse[m]"]) for r in rows]
pad = [float(r["contact_force.arm-vertical_stop[N]"]) for r in rows]
def at(series, x):
    lo, hi = 0, len(t) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if t[mid] <= x else (lo, mid)
    w = (x - t[lo]) / (t[hi] - t[lo])
    return series[lo] + w * (series[hi] - series[lo])
random.seed(20221)
late_s, period_s = 0.007, 0.003
with open(sys.argv[2], "w", newline="") as out:
    out.write("t[s],tip_deflection.transverse[mm],contact_force.arm-vertical_stop[kN]\n")
    k = 0
    while (k * period_s) <= t[-1] - late_s:
        clock = late_s + k * period_s   # the logger stamps each sample 7 ms late
        true_t = k * period_s
        mm = 1e3 * at(tip, true_t) + random.gauss(0, 0.01)
        kn = 1e-3 * (at(pad, true_t) + random.gauss(0, 5.0))
        out.write(f"{clock:.6f},{mm:.4f},{kn:.4f}\n")
        k += 1
PY
echo "wrote measurements/rig.csv"
