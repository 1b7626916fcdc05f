#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for tests and trying scripts/slurm-bake.sh:
# munged, slurmctld and slurmd started without systemd, every file (config, key, state,
# logs, PID files) under one directory. Needs Debian's slurm-wlm and munge
# (scripts/install-deps.sh) and root (slurmd starts jobs as their user).
#
# Usage: scripts/slurm-local.sh start|stop|status
#   start   writes slurm.conf for this host (CPUs from nproc), starts the three daemons,
#           waits until the node is idle, and prints the line to point Slurm's commands at
#           it: export SLURM_CONF=DIR/slurm.conf
#   stop    cancels every job, stops the daemons (by their PID files) and waits for them
#   status  says which daemons run and what sinfo reports
# Environment: SLURM_LOCAL_DIR (default: build/slurm-local in the repository),
#   SLURM_LOCAL_PORT (slurmctld's port, default 16817; slurmd uses the next one),
#   SLURM_LOCAL_TIMEOUT (seconds start waits for an idle node, default 60).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
dir=${SLURM_LOCAL_DIR:-$root/build/slurm-local}
port=${SLURM_LOCAL_PORT:-16817}
timeout_s=${SLURM_LOCAL_TIMEOUT:-60}
conf=$dir/slurm.conf
socket=$dir/munge-socket/munge.socket
export SLURM_CONF=$conf

say() { echo "slurm-local: $*" >&2; }

# The PID in a PID file when that process is alive, else nothing.
live_pid() {
  local file=$1 pid
  [[ -f $file ]] || return 0
  pid=$(cat "$file" 2>/dev/null || true)
  [[ $pid =~ ^[0-9]+$ ]] && kill -0 "$pid" 2>/dev/null && echo "$pid"
  return 0
}

# Stops the process of one PID file: TERM, up to 20 s, then KILL.
stop_daemon() {
  local name=$1 file=$2 pid
  pid=$(live_pid "$file")
  [[ -n $pid ]] || { rm -f "$file"; return 0; }
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 1 200); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    say "$name (pid $pid) did not stop in 20 s; killing it"
    kill -KILL "$pid" 2>/dev/null || true
  fi
  rm -f "$file"
  say "stopped $name (pid $pid)"
}

require() {
  local missing=()
  for c in munged munge unmunge slurmctld slurmd sinfo scontrol; do command -v "$c" >/dev/null || missing+=("$c"); done
  if ((${#missing[@]})); then
    say "missing ${missing[*]}: install Debian's slurm-wlm and munge (scripts/install-deps.sh)"
    exit 3
  fi
  [[ $(id -u) -eq 0 ]] || { say "must run as root (slurmd starts jobs as their users)"; exit 3; }
}

write_conf() {
  local host cpus
  host=$(hostname -s)
  cpus=$(nproc)
  cat > "$conf" <<CONF
# Written by scripts/slurm-local.sh: one node, this host, for tests. Not for production.
ClusterName=prtlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups, no accounting: nothing outside this directory is touched.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
JobRequeue=1
# Tests wait on the scheduler: start what became eligible at once.
SchedulerParameters=sched_min_interval=100000
MinJobAge=300
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
  require
  if [[ -n $(live_pid "$dir/slurmctld.pid") || -n $(live_pid "$dir/slurmd.pid") || -n $(live_pid "$dir/munge/munged.pid") ]]; then
    say "already running under $dir (stop it first: scripts/slurm-local.sh stop)"
    echo "export SLURM_CONF=$conf"
    return 0
  fi
  mkdir -p "$dir/munge" "$dir/munge-socket" "$dir/state" "$dir/spool" "$dir/log"
  # munged wants its key private and its socket's directory open to every user.
  chmod 700 "$dir/munge"
  chmod 755 "$dir/munge-socket"
  if [[ ! -s $dir/munge/munge.key ]]; then
    head -c 1024 /dev/urandom > "$dir/munge/munge.key"
    chmod 400 "$dir/munge/munge.key"
  fi
  munged --key-file="$dir/munge/munge.key" --socket="$socket" --pid-file="$dir/munge/munged.pid" \
         --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munged.seed"
  for _ in $(seq 1 100); do
    munge -n -S "$socket" 2>/dev/null | unmunge -S "$socket" >/dev/null 2>&1 && break
    sleep 0.1
  done
  munge -n -S "$socket" | unmunge -S "$socket" >/dev/null || { say "munged does not answer on $socket (log: $dir/log/munged.log)"; stop; exit 7; }
  write_conf
  # -c: a clean start, no jobs left from an earlier run.
  slurmctld -c -f "$conf"
  slurmd -f "$conf" -N "$(hostname -s)"
  local state=""
  for _ in $(seq 1 $((timeout_s * 5))); do
    state=$(sinfo -h -N -o %T 2>/dev/null | head -1 || true)
    [[ $state == idle ]] && break
    sleep 0.2
  done
  if [[ $state != idle ]]; then
    say "the node is '${state:-not reported}' after ${timeout_s} s, not idle; last log lines:"
    tail -n 5 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
    stop
    exit 7
  fi
  say "running under $dir: node $(hostname -s), $(nproc) CPUs, idle"
  echo "export SLURM_CONF=$conf"
}

stop() {
  if [[ -n $(live_pid "$dir/slurmctld.pid") ]]; then
    scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 1 100); do
      [[ -z $(squeue -h -o %i 2>/dev/null) ]] && break
      sleep 0.1
    done
  fi
  stop_daemon slurmd "$dir/slurmd.pid"
  stop_daemon slurmctld "$dir/slurmctld.pid"
  stop_daemon munged "$dir/munge/munged.pid"
}

status() {
  local code=0
  for d in slurmctld:$dir/slurmctld.pid slurmd:$dir/slurmd.pid munged:$dir/munge/munged.pid; do
    local pid
    pid=$(live_pid "${d#*:}")
    if [[ -n $pid ]]; then echo "${d%%:*}: running (pid $pid)"; else echo "${d%%:*}: not running"; code=1; fi
  done
  if ((code == 0)); then sinfo -N; fi
  return $code
}

case ${1:-} in
  start) start ;;
  stop) stop ;;
  status) status ;;
  *) echo "usage: scripts/slurm-local.sh start|stop|status" >&2; exit 2 ;;
esac
