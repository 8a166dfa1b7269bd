#!/usr/bin/env bash
# A single-node Slurm cluster on localhost in one folder, for the farm test (no root-owned state is
# left outside it; needs root, munge and slurm-wlm; addresses are 127.0.0.1, so no name service is
# needed). usage:
#   slurm_cluster.sh start DIR    start munged, slurmctld and slurmd with everything under DIR; prints the
#                                 environment to source (SLURM_CONF) once the node is idle
#   slurm_cluster.sh stop DIR     cancel every job, stop the daemons, remove DIR
set -euo pipefail
cmd=$1; dir=$2

free_port() {  # a TCP port nobody listens on
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()'
}

# slurmd needs the cgroup hierarchies mounted under /sys/fs/cgroup, which a bare root (a chroot, a
# minimal container) lacks: mount them as the kernel has them (/proc/self/cgroup), remembered for stop.
mount_cgroups() {
  [ "$(stat -f -c %T /sys/fs/cgroup 2>/dev/null)" = sysfs ] || [ -z "$(ls -A /sys/fs/cgroup 2>/dev/null)" ] || return 0
  mount -t tmpfs -o mode=755 obscura-cgroups /sys/fs/cgroup || return 1
  echo /sys/fs/cgroup >"$dir/run/mounts"
  while IFS=: read -r _ controllers _; do
    local name=${controllers#name=} opts=$controllers type=cgroup
    if [ -z "$controllers" ]; then name=unified; opts=defaults; type=cgroup2; fi
    [ "$name" != "$controllers" ] && [ -n "$controllers" ] && opts="none,name=$name"
    mkdir -p "/sys/fs/cgroup/$name"
    mount -t "$type" -o "$opts" cgroup "/sys/fs/cgroup/$name" && echo "/sys/fs/cgroup/$name" >>"$dir/run/mounts"
  done < /proc/self/cgroup
}

start() {
  mkdir -p "$dir"/{munge,state,spool,log,run}
  mount_cgroups
  chmod 755 "$dir" "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key" >/dev/null 2>&1
  chmod 600 "$dir/munge/munge.key"
  munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" --force
  local host ctld_port d_port cpus
  host=$(hostname -s); ctld_port=$(free_port); d_port=$(free_port); cpus=$(nproc)
  cat >"$dir/slurm.conf" <<CONF
ClusterName=obscura-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
SchedulerParameters=sched_interval=2,bf_interval=1
MinJobAge=600
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=4000 State=UNKNOWN
PartitionName=obscura Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$dir/slurm.conf
  setsid slurmctld -D -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 < /dev/null &
  setsid slurmd -D -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 < /dev/null &
  for _ in $(seq 1 100); do
    if sinfo -h -o %T 2>/dev/null | grep -q idle; then echo "export SLURM_CONF=$SLURM_CONF"; return 0; fi
    sleep 0.2
  done
  echo "slurm_cluster: the node did not become idle; logs in $dir/log" >&2
  tail -n 20 "$dir"/log/*.log >&2 || true
  return 1
}

stop() {
  [ -d "$dir" ] || return 0
  export SLURM_CONF=$dir/slurm.conf
  scancel --full --quiet -u "$(id -un)" 2>/dev/null || true
  for pid in "$dir/run/slurmd.pid" "$dir/run/slurmctld.pid"; do
    [ -f "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
  done
  sleep 0.5
  pkill -f -- "-f $dir/slurm.conf" 2>/dev/null || true
  munged -s --socket="$dir/munge/munge.socket" >/dev/null 2>&1 || true
  [ -f "$dir/munge/munged.pid" ] && kill "$(cat "$dir/munge/munged.pid")" 2>/dev/null || true
  [ -f "$dir/run/mounts" ] && tac "$dir/run/mounts" | while read -r m; do umount "$m" 2>/dev/null || true; done
  rm -rf "$dir"
}

case $cmd in
start) start ;;
stop) stop ;;
*) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
esac
