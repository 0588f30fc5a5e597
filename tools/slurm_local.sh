#!/usr/bin/env bash
# A single-node Slurm on this machine, for the validation's Slurm executor
# (docs/validation.md) and its test; anyone can try the executor with it.
#   tools/slurm_local.sh start    install (tools/bootstrap.sh), configure and
#                                 start munged, slurmctld and slurmd, wait
#                                 until sinfo shows the node idle
#   tools/slurm_local.sh stop     cancel the jobs, stop the daemons; nothing
#                                 of this cluster keeps running
#   tools/slurm_local.sh status   exit 0 if the cluster answers, else 1
#   tools/slurm_local.sh env      print `export SLURM_CONF=...` for eval
# Environment:
#   SHAFTS_SLURM_DIR   state directory (default /tmp/shafts-slurm-UID): the
#                      munge key and socket, slurm.conf, spool, state, logs
#   SHAFTS_SLURM_PORT  slurmctld's port, slurmd's is the next (default 6817
#                      for the default directory; for another, a port from
#                      20000 to 29998 its path chooses, so that clusters of
#                      several build trees can run side by side)
# Both commands are idempotent: start on a running cluster and stop on a
# stopped one do nothing. Clients (sbatch, squeue, sinfo) find the cluster
# through SLURM_CONF: eval "$(tools/slurm_local.sh env)".
#
# Debian 12's slurm-wlm 22.05 and munge, started without systemd: the
# daemons fork into the background themselves and are stopped through
# their pid files. The node is what `slurmd -C` finds (CPUs, memory), its
# address 127.0.0.1. Process tracking is proctrack/linuxproc (the parent
# process ids) and task binding task/none: Slurm 22.05's cgroup plugins
# want cgroup v2 delegated by systemd or a cgroup v1 hierarchy it may
# write, and containers (this machine is one) have neither. Memory limits
# are enforced by polling (jobacct_gather/linux with OverMemoryKill), time
# limits by slurmctld as anywhere.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
dir=${SHAFTS_SLURM_DIR:-/tmp/shafts-slurm-$(id -u)}
if [ -n "${SHAFTS_SLURM_PORT:-}" ]; then
  port=$SHAFTS_SLURM_PORT
elif [ -z "${SHAFTS_SLURM_DIR:-}" ]; then
  port=6817
else
  port=$((20000 + 2 * ($(printf %s "$dir" | cksum | cut -d' ' -f1) % 5000)))
fi
conf=$dir/slurm.conf
export SLURM_CONF=$conf

say() { echo "slurm_local: $*" >&2; }
die() { say "$*"; exit 1; }
fail() { # a start that failed leaves nothing running
  stop_daemons
  die "$*"
}

alive() { # pid file: the process is running
  [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null
}

answers() { # the controller answers and knows the node
  [ -f "$conf" ] && alive "$dir/slurmctld.pid" && timeout 10 sinfo -h >/dev/null 2>&1
}

node_state() {
  timeout 10 sinfo -h -N -o %T 2>/dev/null | head -n1
}

show_log() { # the last lines of a daemon's log, for the reason of a failure
  [ -f "$1" ] && { say "the end of $1:"; tail -n 15 "$1" | sed 's/^/  /' >&2; }
  return 0
}

start() {
  if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
     ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
    say "installing Slurm and munge (tools/bootstrap.sh --slurm)"
    "$here/bootstrap.sh" --slurm || fail "cannot install slurmctld, slurmd, slurm-client and munge"
  fi
  mkdir -p "$dir"
  if answers && alive "$dir/slurmd.pid" && alive "$dir/munged.pid"; then
    say "already running ($conf)"
    return 0
  fi
  # A half-started cluster (a daemon died) is stopped and started afresh.
  stop_daemons
  mkdir -p "$dir/munge" "$dir/ctld" "$dir/spool" "$dir/log"
  chmod 700 "$dir/munge"

  # munge: a key of our own and a socket in the state directory.
  if [ ! -s "$dir/munge/munge.key" ]; then
    mungekey --create --keyfile="$dir/munge/munge.key" --force >/dev/null ||
      fail "mungekey cannot create $dir/munge/munge.key"
  fi
  chmod 600 "$dir/munge/munge.key"
  munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" 9>&- ||
    { show_log "$dir/log/munged.log"; fail "munged did not start"; }
  for _ in $(seq 50); do [ -S "$dir/munge/munge.socket" ] && break; sleep 0.1; done
  [ -S "$dir/munge/munge.socket" ] || fail "munged made no socket $dir/munge/munge.socket"

  # The node as slurmd sees it: CPUs, sockets, cores, threads, memory.
  hw=$(slurmd -C | head -n1) || fail "slurmd -C cannot read the node's hardware"
  host=$(hostname -s)
  hw=$(echo "$hw" | sed "s/^NodeName=[^ ]*//")
  user=$(id -un)
  cat >"$conf.tmp" <<EOF
# Written by tools/slurm_local.sh: a single-node cluster, state in $dir.
ClusterName=shafts
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=task=2
JobAcctGatherParams=OverMemoryKill
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MinJobAge=600
KillWait=5
InactiveLimit=0
# Start the next array tasks as soon as others end: a wave takes 1 s
# instead of 3 s with the defaults (measured with 6 tasks, 2 at a time).
SchedulerParameters=sched_min_interval=0,batch_sched_delay=0
NodeName=$host NodeAddr=127.0.0.1$hw State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  mv "$conf.tmp" "$conf"

  # The daemons must not inherit the lock (fd 9): it would be held for ever.
  # -c: a new cluster each time, no jobs carried over from the last one.
  slurmctld -c -f "$conf" 9>&- ||
    { show_log "$dir/log/slurmctld.log"; fail "slurmctld did not start"; }
  slurmd -f "$conf" -N "$host" 9>&- ||
    { show_log "$dir/log/slurmd.log"; fail "slurmd did not start"; }
  state=""
  for _ in $(seq 120); do
    state=$(node_state || true)
    case "$state" in
      idle) break ;;
      down*|drain*) scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true ;;
    esac
    alive "$dir/slurmctld.pid" || { show_log "$dir/log/slurmctld.log"; fail "slurmctld died"; }
    sleep 0.5
  done
  if [ "$state" != idle ]; then
    show_log "$dir/log/slurmctld.log"
    show_log "$dir/log/slurmd.log"
    fail "node $host is '${state:-unknown}', not idle, after 60 s"
  fi
  say "up: node $host idle ($(echo "$hw" | grep -o 'CPUs=[0-9]*') $(echo "$hw" | grep -o 'RealMemory=[0-9]*') MB); export SLURM_CONF=$conf"
}

stop_pid() { # pid file, name: TERM, then KILL after 10 s
  [ -s "$1" ] || return 0
  pid=$(cat "$1")
  if kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      say "$2 ($pid) ignored TERM: killing it"
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$1"
}

stop_daemons() {
  stop_pid "$dir/slurmd.pid" slurmd
  stop_pid "$dir/slurmctld.pid" slurmctld
  stop_pid "$dir/munged.pid" munged
}

stop() {
  [ -d "$dir" ] || return 0
  if answers; then
    # The jobs first, so that no step outlives its slurmd.
    scancel --full --quiet "--user=$(id -un)" >/dev/null 2>&1 || true
    for _ in $(seq 100); do
      [ -z "$(timeout 10 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  stop_daemons
  # Steps whose slurmd is gone: slurmstepd processes reading our spool.
  for p in /proc/[0-9]*; do
    [ "$(cat "$p/comm" 2>/dev/null)" = slurmstepd ] || continue
    if tr '\0' ' ' <"$p/cmdline" 2>/dev/null | grep -q "$dir" ||
       ls -l "$p/cwd" 2>/dev/null | grep -q "$dir"; then
      kill -KILL "${p#/proc/}" 2>/dev/null || true
    fi
  done
  say "stopped (state kept in $dir)"
}

case "${1:-}" in
  start) exec 9>"/tmp/shafts-slurm-$(id -u).lock"; flock 9; start ;;
  stop) exec 9>"/tmp/shafts-slurm-$(id -u).lock"; flock 9; stop ;;
  status) answers && [ "$(node_state)" != "" ] ;;
  env) echo "export SLURM_CONF=$conf" ;;
  -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//' ;;
  *) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
esac
