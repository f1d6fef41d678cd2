#!/usr/bin/env bash
# A real single-node Slurm cluster on localhost, for testing `covga grid --slurm`.
#   scripts/slurm-local.sh install        install slurm-wlm + munge from Debian (needs root)
#   scripts/slurm-local.sh start ROOT     start munged, slurmctld, slurmd with state under ROOT;
#                                         prints the SLURM_CONF path to export
#   scripts/slurm-local.sh stop ROOT      stop exactly the daemons started under ROOT
# Ports 6817/6818 are fixed: one such cluster per host.
set -euo pipefail

cmd=${1:-}
root=${2:-}

install_slurm() {
  if command -v slurmctld >/dev/null && command -v munged >/dev/null && command -v sbatch >/dev/null; then
    return 0
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends slurm-wlm >/dev/null
}

wait_for() { # seconds, command...
  local limit=$1; shift
  local end=$((SECONDS + limit))
  until "$@"; do
    if [ "$SECONDS" -ge "$end" ]; then return 1; fi
    sleep 0.2
  done
}

node_idle() {
  local state
  state=$(timeout 5 sinfo -h -n "$(hostname -s)" -o %T 2>/dev/null || true)
  [ "$state" = "idle" ]
}

start() {
  [ -n "$root" ] || { echo "usage: $0 start ROOT" >&2; exit 2; }
  mkdir -p "$root"/{munge,state,spool,run,log}
  chmod 755 "$root" "$root/munge"
  root=$(cd "$root" && pwd)
  local node mem
  node=$(hostname -s)
  if [ ! -f "$root/munge/munge.key" ]; then
    mungekey -c -k "$root/munge/munge.key" >/dev/null 2>&1 || dd if=/dev/urandom of="$root/munge/munge.key" bs=1024 count=1 status=none
    chmod 400 "$root/munge/munge.key"
  fi
  munged --force --key-file="$root/munge/munge.key" --socket="$root/munge/munge.socket.2" \
    --pid-file="$root/munge/munged.pid" --log-file="$root/log/munged.log" --seed-file="$root/munge/munged.seed"
  mem=$(slurmd -C 2>/dev/null | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
  mem=$(( ${mem:-2000} * 9 / 10 ))
  cat > "$root/slurm.conf" <<CONF
ClusterName=localci
SlurmctldHost=${node}(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=${root}/munge/munge.socket.2
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=${root}/log/jobcomp.log
MpiDefault=none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
MaxArraySize=100001
StateSaveLocation=${root}/state
SlurmdSpoolDir=${root}/spool
SlurmctldPidFile=${root}/run/slurmctld.pid
SlurmdPidFile=${root}/run/slurmd.pid
SlurmctldLogFile=${root}/log/slurmctld.log
SlurmdLogFile=${root}/log/slurmd.log
NodeName=${node} NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=${mem} State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$root/slurm.conf"
  slurmctld -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF"
  if ! wait_for 30 node_idle; then
    echo "slurm-local: node did not become idle; logs in $root/log" >&2
    tail -n 20 "$root/log/slurmctld.log" "$root/log/slurmd.log" >&2 || true
    exit 1
  fi
  echo "$SLURM_CONF"
}

stop_pid() { # pidfile name
  local file=$1 name=$2 pid
  [ -f "$file" ] || return 0
  pid=$(cat "$file" 2>/dev/null || true)
  [ -n "$pid" ] || return 0
  alive() { [ -d "/proc/$pid" ] && [ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)" != "Z" ]; }
  if alive && grep -q "$name" "/proc/$pid/comm" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null || true
    wait_for 10 bash -c "! { [ -d /proc/$pid ] && [ \"\$(awk '{print \$3}' /proc/$pid/stat 2>/dev/null)\" != Z ]; }" || kill -KILL "$pid" 2>/dev/null || true
  fi
  rm -f "$file"
}

stop() {
  [ -n "$root" ] || { echo "usage: $0 stop ROOT" >&2; exit 2; }
  stop_pid "$root/run/slurmd.pid" slurmd
  stop_pid "$root/run/slurmctld.pid" slurmctld
  stop_pid "$root/munge/munged.pid" munged
}

case "$cmd" in
  install) install_slurm ;;
  start) start ;;
  stop) stop ;;
  *) echo "usage: $0 install | start ROOT | stop ROOT" >&2; exit 2 ;;
esac
