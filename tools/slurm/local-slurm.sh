#!/usr/bin/env bash
# A throwaway one-node Slurm cluster in a folder, for trying tools/slurm/ on
# one machine and for the integration test (tests/slurm). Everything it
# writes (munge key and socket, slurm.conf, state, spool, logs, PIDs) stays in
# DIR; it uses two free TCP ports on 127.0.0.1 and touches no system service.
#
#   tools/slurm/local-slurm.sh up DIR     start munged, slurmctld and slurmd;
#                                         prints "export SLURM_CONF=DIR/slurm.conf"
#   tools/slurm/local-slurm.sh down DIR   cancel its jobs, stop its daemons
#
# Needs the Debian packages slurmctld, slurmd, slurm-client and munge
# (tools/slurm/install-slurm.sh) and, for slurmd to start jobs, root.
# The node is this machine as `slurmd -C` sees it (CPUs, memory), with
# proctrack/linuxproc and task/none: no cgroups needed.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
(($# == 2)) || usage
action=$1
dir=$2

stop_pid_file() {  # the daemon whose PID this script wrote, and only it
  local file=$1 pid
  [[ -f $file ]] || return 0
  pid=$(<"$file")
  if [[ $pid =~ ^[0-9]+$ ]] && kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  fi
  rm -f "$file"
}

down() {
  [[ -d $dir ]] || return 0
  if [[ -f $dir/slurm.conf && -f $dir/slurmctld.pid ]]; then
    SLURM_CONF=$dir/slurm.conf timeout 10 scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
  fi
  stop_pid_file "$dir/slurmd.pid"
  stop_pid_file "$dir/slurmctld.pid"
  stop_pid_file "$dir/munged.pid"
}

free_ports() {  # two ports nobody listens on now
  python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}

fail() {
  echo "local-slurm.sh: $*" >&2
  for log in munged.log munged.out slurmctld.log slurmctld.out slurmd.log slurmd.out; do
    [[ -s $dir/$log ]] && { echo "--- $dir/$log (end)" >&2; tail -n 15 "$dir/$log" >&2; }
  done
  down
  exit 1
}

up() {
  for tool in munged mungekey slurmctld slurmd sinfo; do
    command -v "$tool" >/dev/null || { echo "local-slurm.sh: $tool not found: run tools/slurm/install-slurm.sh" >&2; exit 3; }
  done
  if [[ -e $dir ]] && [[ -n $(ls -A "$dir") ]]; then
    echo "local-slurm.sh: $dir is not empty: give a new folder" >&2
    exit 2
  fi
  mkdir -p "$dir"
  dir=$(realpath "$dir")
  local above=$dir
  while above=$(dirname "$above"); [[ $above != / ]]; do
    [[ $(stat -c %A "$above") == ?????????[xt] ]] ||
      fail "munged refuses a socket below $above, which not everyone may enter: chmod o+x it, or choose another DIR"
  done
  # munged wants its socket's folder reachable by everyone and its key private.
  chmod 711 "$dir"
  mkdir -m 755 "$dir/munge"
  mkdir -p "$dir/state" "$dir/spool"
  mungekey --create --keyfile="$dir/munge.key" || fail "cannot create a munge key"

  local user host ports cpus memory
  user=$(id -un)
  host=$(hostname -s)
  read -r -a ports <<<"$(free_ports)"
  cpus=$(nproc)
  memory=$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)
  cat >"$dir/slurm.conf" <<CONF
# A one-node cluster made by tools/slurm/local-slurm.sh; everything in $dir.
ClusterName=rollsense-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.daemon.pid
SlurmdPidFile=$dir/slurmd.daemon.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

  # In the foreground of a background job each, so this script knows their
  # PIDs; every output to a file, so no caller waits on an inherited pipe.
  munged --foreground --socket="$dir/munge/socket" --key-file="$dir/munge.key" --log-file="$dir/munged.log" \
    --pid-file="$dir/munged.daemon.pid" --seed-file="$dir/munged.seed" </dev/null >"$dir/munged.out" 2>&1 &
  echo $! >"$dir/munged.pid"
  for _ in $(seq 50); do [[ -S $dir/munge/socket ]] && break; sleep 0.1; done
  [[ -S $dir/munge/socket ]] || fail "munged did not start"

  export SLURM_CONF=$dir/slurm.conf
  slurmctld -D -f "$dir/slurm.conf" </dev/null >"$dir/slurmctld.out" 2>&1 &
  echo $! >"$dir/slurmctld.pid"
  slurmd -D -f "$dir/slurm.conf" </dev/null >"$dir/slurmd.out" 2>&1 &
  echo $! >"$dir/slurmd.pid"
  local state=
  for _ in $(seq 120); do
    kill -0 "$(<"$dir/slurmctld.pid")" 2>/dev/null || fail "slurmctld exited"
    kill -0 "$(<"$dir/slurmd.pid")" 2>/dev/null || fail "slurmd exited"
    state=$(timeout 5 sinfo --noheader --nodes="$host" --format=%T 2>/dev/null || true)
    [[ $state == idle ]] && break
    sleep 0.5
  done
  [[ $state == idle ]] || fail "the node did not become idle within 60 s (state '${state:-no answer}')"
  echo "export SLURM_CONF=$dir/slurm.conf"
}

case $action in
  up) up ;;
  down) down ;;
  *) usage ;;
esac
