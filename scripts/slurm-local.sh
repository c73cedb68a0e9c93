#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for `fognav sweep --backend slurm` in the tests:
# munged, slurmctld and slurmd from Debian's slurm-wlm and munge, started without systemd, with
# this host as the only node with its real CPUs and memory (as `slurmd -C` finds them).
# Usage: scripts/slurm-local.sh start|stop [STATE_DIR]   (default /tmp/fognav-slurm; root)
# After start, the Slurm commands find the cluster with: export SLURM_CONF=STATE_DIR/slurm.conf
# Exit code 77 when slurm-wlm or munge is not installed (apt-get install slurm-wlm munge).
set -euo pipefail
action="${1:-}"
dir="${2:-/tmp/fognav-slurm}"
case "$action" in start|stop) ;; *) echo "usage: $0 start|stop [STATE_DIR]" >&2; exit 2;; esac

stop() {
  # each daemon by the id in its pid file; then wait for it to be gone
  for name in slurmd slurmctld munged; do
    pid_file="$dir/$name.pid"
    [ -f "$pid_file" ] || continue
    pid="$(cat "$pid_file")"
    if kill "$pid" 2> /dev/null; then
      for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    fi
    rm -f "$pid_file"
  done
}

if [ "$action" = stop ]; then
  stop
  echo "slurm-local: stopped ($dir)"
  exit 0
fi

for command in munged slurmctld slurmd sbatch squeue sacct; do
  if ! command -v "$command" > /dev/null; then
    echo "slurm-local: $command is not installed (apt-get install slurm-wlm munge)" >&2
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm-local: slurmd must run as root" >&2
  exit 2
fi
stop  # a cluster left from before
rm -rf "$dir/state" "$dir/spool"  # a fresh cluster: no jobs from before
mkdir -p "$dir/state" "$dir/spool"
chmod 0700 "$dir"

# munge: its own key and socket, so a system munged (if any) is left alone
[ -f "$dir/munge.key" ] || dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chmod 0600 "$dir/munge.key"
munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munged.seed"

# the node as slurmd sees it: NodeName=HOST CPUs=... RealMemory=...; reached at 127.0.0.1,
# so a container whose host name does not resolve works too
node="$(slurmd -C | head -n 1)"
host="$(echo "$node" | sed 's/^NodeName=\([^ ]*\).*/\1/')"
cpus="$(echo "$node" | sed 's/.* CPUs=\([0-9]*\).*/\1/')"
memory="$(echo "$node" | sed 's/.* RealMemory=\([0-9]*\).*/\1/')"
cat > "$dir/slurm.conf" << EOF
ClusterName=fognav
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
# a task starts as soon as a CPU is free (the defaults wait up to 3 s for more submissions)
SchedulerParameters=batch_sched_delay=0,sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MinJobAge=600
# a task takes a CPU and its share of the memory, so the node runs one task per CPU
DefMemPerCPU=$((memory / cpus))
KillWait=5
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"

# ready when the node takes jobs
for _ in $(seq 100); do
  if sinfo -h -N -o '%T' 2> /dev/null | grep -qE '^(idle|mixed|allocated)'; then
    echo "slurm-local: started on $host ($dir); export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "slurm-local: the node did not come up; see $dir/slurmctld.log and $dir/slurmd.log" >&2
stop
exit 1
