#!/usr/bin/env bash
# A real Slurm job array on this one machine (docs/sweeps.md): installs Debian's slurm-wlm,
# configures controller and node on localhost, starts munged, slurmctld and slurmd, submits the
# 16-case sweep of scripts/slurm_sweep.sh as 3 array tasks, waits, merges, and compares the
# merged files byte for byte with one unsharded run. Needs root (apt, daemons); not run by CI.
set -euo pipefail
cd "$(dirname "$0")/.."
WORK=${WORK:-/tmp/pipearm-slurm-demo}
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$HOME/.cache/pipearm-target}

command -v slurmctld >/dev/null || { apt-get update -qq; apt-get install -y -qq slurm-wlm; }

# A private copy of the binary: the shared target dir may be relinked by other builds meanwhile.
rm -rf "$WORK" && mkdir -p "$WORK"
if [ -z "${PIPEARM:-}" ]; then
  cargo build --release --quiet
  install -m 755 "$CARGO_TARGET_DIR/release/pipearm" "$WORK/pipearm"
  PIPEARM=$WORK/pipearm
fi
export PIPEARM

# munge: a key, its run dir, the daemon (as the munge user).
install -d -o munge -g munge -m 0700 /etc/munge /var/lib/munge /var/log/munge
install -d -o munge -g munge -m 0755 /run/munge
[ -s /etc/munge/munge.key ] || { dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none; }
chown munge:munge /etc/munge/munge.key && chmod 0400 /etc/munge/munge.key
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged
munge -n | unmunge >/dev/null

# slurm.conf: one node, localhost, with this machine's CPUs and memory (from slurmd -C).
CPUS=$(nproc)
MEM=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
install -d /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=pipearm
SlurmctldHost=localhost
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
NodeName=localhost CPUs=$CPUS RealMemory=$MEM State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF

pgrep -x slurmctld >/dev/null || slurmctld
pgrep -x slurmd >/dev/null || slurmd -N localhost
for _ in $(seq 30); do sinfo -h -o %t | grep -qE '^(idle|mix|alloc)' && break; sleep 1; done
sinfo

# The array: 3 tasks, one shard each, into one folder.
export OUT=$WORK/sharded
JOB=$(sbatch --parsable --array=0-2 --output="$WORK/slurm-%A_%a.out" scripts/slurm_sweep.sh)
echo "submitted job array $JOB"
squeue -j "$JOB"
while [ -n "$(squeue -h -j "$JOB" 2>/dev/null)" ]; do sleep 1; done
scontrol -o show job "$JOB" | grep -o 'JobId=[^ ]* ArrayJobId=[^ ]* ArrayTaskId=[^ ]*\|JobState=[^ ]*\|ExitCode=[^ ]*\|RunTime=[^ ]*' | paste - - - -
for f in "$WORK"/slurm-*.out; do echo "== $f"; cat "$f"; done
"$PIPEARM" sweep merge "$OUT"

# The same sweep in one process, then byte-for-byte comparison.
"$PIPEARM" sweep scenarios/default.toml --vary drive.duration_s=10..25:5 \
  --vary 'payload.size=2-3/8,2-7/8,3-1/2,4-1/2' --out "$WORK/whole"
for f in results.csv results.json force_vs_weight.svg; do
  cmp "$WORK/sharded/$f" "$WORK/whole/$f" && echo "identical: $f"
done
