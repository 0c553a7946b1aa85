#!/usr/bin/env bash
# A one-node Slurm cluster for the farm tests, started and stopped by CTest fixtures
# (tests/CMakeLists.txt: farm.slurm_start / farm.slurm_stop):
#   slurm_cluster.sh start DIR    munged, slurmctld and slurmd on this machine, with the
#                                 key, configuration, spool, state and logs in DIR; waits
#                                 (at most 60 s) until the node is idle; writes DIR/env
#                                 (SLURM_CONF=...) for the tests
#   slurm_cluster.sh stop DIR     stops them (scontrol shutdown, then the pids), even after
#                                 a failed start
# The node is localhost under this machine's short host name with all its CPUs,
# proctrack/pgid (no cgroups), no accounting database. Needs root (the daemons run as it)
# and Debian 12's slurm-wlm and munge (scripts/bootstrap.sh installs them).
set -euo pipefail
action="${1:?start or stop}"
dir="${2:?the folder of the cluster}"

stop() {
  export SLURM_CONF="$dir/slurm.conf"
  if [[ -f "$dir/slurm.conf" ]]; then
    timeout 10 scontrol shutdown >/dev/null 2>&1 || true
  fi
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [[ -f "$pidfile" ]] || continue
    pid=$(cat "$pidfile" 2>/dev/null || true)
    [[ -n "$pid" ]] || continue
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; kill "$pid" 2>/dev/null || true; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  # Tasks a failed test left behind (proctrack/pgid: their own process groups).
  pkill -f "slurmstepd.*$dir" 2>/dev/null || true
}

if [[ "$action" == stop ]]; then
  stop
  exit 0
fi

for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol sinfo python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "slurm_cluster: '$tool' not found: install Debian's slurm-wlm and munge (scripts/bootstrap.sh does)" >&2
    exit 1
  fi
done
if [[ "$(id -u)" -ne 0 ]]; then
  echo "slurm_cluster: the test cluster's daemons run as root; run the tests as root" >&2
  exit 1
fi
stop  # a cluster an earlier run left
rm -rf "$dir"
mkdir -p "$dir/state" "$dir/spool" "$dir/log"
trap 'echo "slurm_cluster: start failed; logs in $dir/log" >&2; stop' ERR

mungekey -c -f -k "$dir/munge.key"
chmod 600 "$dir/munge.key"
munged -f --key-file="$dir/munge.key" --socket="$dir/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/log/munged.log" --seed-file="$dir/munged.seed"

# Two free TCP ports, from the kernel.
read -r ctld_port d_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host=$(hostname -s)
cat > "$dir/slurm.conf" <<CONF
# Written by tests/farm/slurm_cluster.sh: a one-node cluster for the tests.
ClusterName=patina-tests
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmdTimeout=30
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=patina Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 120); do
  state=$(sinfo -h -o %t 2>/dev/null || true)
  [[ "$state" == idle ]] && break
  sleep 0.5
done
if [[ "$state" != idle ]]; then
  echo "slurm_cluster: the node is '$state', not idle, after 60 s; logs in $dir/log" >&2
  stop
  exit 1
fi
echo "SLURM_CONF=$SLURM_CONF" > "$dir/env"
echo "slurm_cluster: node $host idle (ports $ctld_port, $d_port); SLURM_CONF=$SLURM_CONF"
