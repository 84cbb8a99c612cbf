#!/usr/bin/env bash
# One shard of a pipearm sweep as a Slurm job array task (docs/sweeps.md):
#   sbatch --array=0-2 scripts/slurm_sweep.sh          # 3 tasks = 3 shards
#   pipearm sweep merge recordings/slurm-sweep         # once every task is done
# Each task runs the cases with index % SLURM_ARRAY_TASK_COUNT == SLURM_ARRAY_TASK_ID into the
# shared folder OUT; case files are written whole (temporary name, then rename), so tasks never
# see each other's half-written files. Submit from the repository root (the paths are relative).
#SBATCH --job-name=pipearm-sweep
#SBATCH --output=slurm-%A_%a.out
#SBATCH --cpus-per-task=1
#SBATCH --ntasks=1
set -euo pipefail
PIPEARM=${PIPEARM:-pipearm}
SCENARIO=${SCENARIO:-scenarios/default.toml}
OUT=${OUT:-recordings/slurm-sweep}
SHARDS=${SLURM_ARRAY_TASK_COUNT:?run as a job array: sbatch --array=0-N scripts/slurm_sweep.sh}
"$PIPEARM" sweep "$SCENARIO" \
  --vary drive.duration_s=10..25:5 \
  --vary 'payload.size=2-3/8,2-7/8,3-1/2,4-1/2' \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --shard-count "$SHARDS" --out "$OUT"
