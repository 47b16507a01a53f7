#!/usr/bin/env bash
# A single-node SLURM on localhost for tests and demos: munge + slurmctld + slurmd, all state
# (keys, sockets, spool, logs, generated slurm.conf) under one directory, no system files
# touched. The node gets this machine's cores and ~90% of its memory; daemons talk over
# 127.0.0.1, so the host name need not resolve.
#   bash slurm/local_cluster.sh start [DIR]   # prints the line to source: export SLURM_CONF=...
#   bash slurm/local_cluster.sh stop  [DIR]
#   bash slurm/local_cluster.sh status [DIR]
# DIR defaults to $HPCPLAN_SLURM_DIR or /tmp/hpcplan-slurm. Needs root (slurmd runs jobs as
# their users) and the Debian packages slurm-wlm and munge.
set -euo pipefail
cmd=${1:-}
dir=${2:-${HPCPLAN_SLURM_DIR:-/tmp/hpcplan-slurm}}
die() { echo "local_cluster: $*" >&2; exit 1; }

conf=$dir/slurm.conf
host=$(hostname -s)

start() {
  [[ $(id -u) -eq 0 ]] || die "must run as root (slurmd starts jobs as their owners)"
  for b in munged slurmctld slurmd sbatch sinfo scontrol; do
    command -v "$b" >/dev/null || die "$b not found (apt-get install slurm-wlm munge)"
  done
  if [[ -f $dir/slurmctld.pid ]] && kill -0 "$(cat "$dir/slurmctld.pid")" 2>/dev/null; then
    echo "export SLURM_CONF=$conf"
    return 0
  fi
  mkdir -p "$dir"/{state,spool,munge}
  chmod 700 "$dir/munge"
  # munge: a private key and socket; the key must be 0400 and owned by the daemon's user.
  [[ -f $dir/munge/munge.key ]] || dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$dir/munge/munge.key"
  munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" || die "munged failed to start (see $dir/munge/munged.log)"
  local cpus mem_mb port
  cpus=$(nproc)
  mem_mb=$(awk '/MemTotal/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)
  # Ports from the directory's name hash, so two clusters in two directories do not collide;
  # below Linux's ephemeral range (32768 up), so no outgoing connection of another program
  # (an mpirun beside the test cluster) can hold one first.
  port=$((20000 + $(printf '%s' "$dir" | cksum | cut -d' ' -f1) % 6000 * 2))
  cat > "$conf" <<CONF
ClusterName=hpcplan
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
# Jobs may be requeued (a checkpointed job requeues itself on its warning signal: README.md);
# SLURM holds a requeued job about two minutes before it may start again (BeginTime).
JobRequeue=1
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=FORCE:4
CONF
  export SLURM_CONF=$conf
  slurmctld -f "$conf" || die "slurmctld failed (see $dir/slurmctld.log)"
  slurmd -f "$conf" || die "slurmd failed (see $dir/slurmd.log)"
  for _ in $(seq 1 60); do
    if sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
      echo "export SLURM_CONF=$conf"
      return 0
    fi
    sleep 0.5
  done
  die "the node did not come up within 30 s (see $dir/slurmctld.log and $dir/slurmd.log)"
}

stop() {
  [[ -f $conf ]] || return 0
  export SLURM_CONF=$conf
  scontrol shutdown >/dev/null 2>&1 || true
  for f in slurmctld slurmd munge/munged; do
    local pidf=$dir/$f.pid
    [[ -f $pidf ]] || continue
    local pid
    pid=$(cat "$pidf")
    for _ in $(seq 1 20); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 1 20); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
    rm -f "$pidf"
  done
}

case $cmd in
  start) start ;;
  stop) stop ;;
  status) SLURM_CONF=$conf sinfo ;;
  *) die "usage: local_cluster.sh start|stop|status [DIR]" ;;
esac
