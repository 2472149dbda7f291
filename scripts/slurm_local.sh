#!/usr/bin/env bash
# A one-node Slurm on this machine, for the cluster tests (tests/cluster/test_slurm.py)
# and for trying `floatfoam batch --submit` / `floatfoam validate --slurm` without a cluster:
#   scripts/slurm_local.sh start DIR   munged, slurmctld and slurmd with their configuration,
#                                      state, spool, logs and sockets under DIR, on two free
#                                      ports; prints `export SLURM_CONF=DIR/slurm.conf`
#   scripts/slurm_local.sh stop DIR    cancels DIR's jobs and stops the three daemons
# Debian's slurmctld, slurmd, slurm-client and munge (scripts/setup.sh installs them). Runs as
# root (SlurmUser=root); the node is this machine with its cores, processes tracked by their
# parents (no cgroups needed).
set -eu

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(realpath -m "$2")
conf=$dir/slurm.conf

# whether process $1 runs (a zombie, ended but not yet reaped by its parent, does not)
alive() {
  [ -r "/proc/$1/status" ] && ! grep -q '^State:[[:space:]]*Z' "/proc/$1/status" 2>/dev/null
}

stop() {
  if [ -f "$conf" ] && [ -S "$dir/munge/munge.socket" ] && [ -f "$dir/slurmctld.pid" ]; then
    # the jobs first, and wait (up to a minute) until Slurm has stopped them: none of their
    # processes outlives the daemons
    SLURM_CONF=$conf scancel --quiet --user=root 2>/dev/null || true
    for _ in $(seq 600); do
      SLURM_CONF=$conf squeue --noheader --format=%T 2>/dev/null | grep -q . || break
      sleep 0.1
    done
  fi
  pids=""
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -f "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    rm -f "$pidfile"
    name=$(basename "$pidfile" .pid)  # a pid file left by a crash may name another process now
    [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] || continue
    kill "$pid" 2>/dev/null && pids="$pids $pid"
  done
  for pid in $pids; do  # each given 5 s to end, then killed
    for _ in $(seq 50); do alive "$pid" || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
}

start() {
  for exe in munged slurmctld slurmd sbatch; do
    command -v "$exe" >/dev/null || { echo "slurm_local: no $exe (run scripts/setup.sh)" >&2; exit 1; }
  done
  [ -f /etc/munge/munge.key ] || { echo "slurm_local: no /etc/munge/munge.key (reinstall munge)" >&2; exit 1; }
  mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/munge"
  chmod 700 "$dir/munge"
  read -r ctld_port d_port < <(python3 -c '
import socket
ports = []
for _ in range(2):
    s = socket.socket(); s.bind(("127.0.0.1", 0)); ports.append(s)
print(*(s.getsockname()[1] for s in ports))')
  node=$(slurmd -C | sed -n 's/^NodeName=\([^ ]*\).*/\1/p' | head -n 1)
  cat > "$conf" <<CONF
ClusterName=floatfoam-local
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
KillWait=30
MinJobAge=600
$(slurmd -C | head -n 1) NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
  trap stop ERR  # a daemon that does not start: the others are stopped too
  munged --force --socket="$dir/munge/munge.socket" --key-file=/etc/munge/munge.key \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed"
  SLURM_CONF=$conf slurmctld
  SLURM_CONF=$conf slurmd -N "$node"
  for _ in $(seq 100); do
    if SLURM_CONF=$conf sinfo --noheader --format=%t 2>/dev/null | grep -qx idle; then
      echo "export SLURM_CONF=$conf"
      return 0
    fi
    sleep 0.2
  done
  echo "slurm_local: the node did not come up idle in 20 s (logs in $dir/log)" >&2
  stop
  exit 1
}

case $action in
  start) stop; start ;;
  stop) stop ;;
  *) usage ;;
esac
