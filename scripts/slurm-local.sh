#!/bin/bash
# A single-node Slurm on this machine, for tests and trying `armour sweep --executor slurm`.
#
#   scripts/slurm-local.sh start    # munged, slurmctld and slurmd, localhost only
#   eval "$(scripts/slurm-local.sh env)"   # SLURM_CONF for sbatch, squeue, sinfo, armour sweep
#   scripts/slurm-local.sh status   # exit 0 when the controller answers and the node is up
#   scripts/slurm-local.sh stop     # stops the three daemons and removes the folder
#
# Everything (configuration, munge key and socket, state, logs, the job completion
# log jobcomp.txt) lives in $ARMOUR_SLURM_DIR (default /tmp/armour-slurm); nothing under
# /etc is touched. Needs Debian's slurmctld, slurmd, slurm-client and munge
# (scripts/debian-packages.txt) and root (slurmd starts jobs as their user).
# There is no slurmdbd here, so `sacct` has no accounting: the completion log
# jobcomp.txt has one line per finished job (each array task is one job).
set -euo pipefail

dir=${ARMOUR_SLURM_DIR:-/tmp/armour-slurm}
port=${ARMOUR_SLURM_PORT:-6817} # slurmctld; slurmd listens on port + 1
host=$(hostname -s)

die() { echo "slurm-local: $*" >&2; exit 1; }

need_tools() {
    local t
    for t in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
        command -v "$t" > /dev/null || [ -x "/usr/sbin/$t" ] ||
            die "$t not found: apt-get install slurm-wlm munge (see scripts/debian-packages.txt)"
    done
}

write_config() {
    local cpus mem_mb
    cpus=$(nproc)
    mem_mb=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
    cat > "$dir/slurm.conf" << CONF
# Written by scripts/slurm-local.sh: one node (this machine), localhost only.
ClusterName=armourlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/slurmd-%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MinJobAge=3600
MaxArraySize=10001
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

start() {
    need_tools
    [ "$(id -u)" = 0 ] || die "start needs root (slurmd runs jobs as their user)"
    if status > /dev/null 2>&1; then
        echo "slurm-local: already running ($dir)"
        return 0
    fi
    stop > /dev/null 2>&1 || true
    mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
    chmod 700 "$dir/munge"
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1 count=1024 status=none
    chmod 400 "$dir/munge/munge.key"
    /usr/sbin/munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
        --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
        --seed-file="$dir/munge/munged.seed"
    write_config
    export SLURM_CONF=$dir/slurm.conf
    /usr/sbin/slurmctld -f "$SLURM_CONF" -i
    /usr/sbin/slurmd -f "$SLURM_CONF"
    local i
    for i in $(seq 1 60); do
        if status > /dev/null 2>&1; then
            echo "slurm-local: running; eval \"\$($0 env)\" to use it"
            return 0
        fi
        sleep 0.5
    done
    tail -n 5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
    stop_daemons
    die "the node did not come up within 30 s (logs in $dir; a port in use? ARMOUR_SLURM_PORT picks others)"
}

status() {
    [ -f "$dir/slurm.conf" ] || { echo "slurm-local: not started ($dir)"; return 1; }
    export SLURM_CONF=$dir/slurm.conf
    scontrol ping | grep -q UP || { echo "slurm-local: controller down"; return 1; }
    local state
    state=$(sinfo -h -N -o %t 2> /dev/null | head -n 1)
    case $state in
    idle* | mix* | alloc*) echo "slurm-local: up, node $host $state, SLURM_CONF=$SLURM_CONF" ;;
    *) echo "slurm-local: node $host is '$state'"; return 1 ;;
    esac
}

stop_pid() {
    local file=$1 pid i
    [ -f "$file" ] || return 0
    pid=$(cat "$file")
    kill "$pid" 2> /dev/null || return 0
    for i in $(seq 1 50); do
        kill -0 "$pid" 2> /dev/null || return 0
        sleep 0.1
    done
    kill -9 "$pid" 2> /dev/null || true
}

stop_daemons() {
    stop_pid "$dir/slurmd.pid"
    stop_pid "$dir/slurmctld.pid"
    stop_pid "$dir/munge/munged.pid"
}

stop() {
    stop_daemons
    # Only a folder this script made (it holds our slurm.conf) is removed.
    if [ -f "$dir/slurm.conf" ] && grep -q "scripts/slurm-local.sh" "$dir/slurm.conf"; then
        rm -rf "$dir"
    fi
    echo "slurm-local: stopped"
}

case ${1:-} in
start) start ;;
stop) stop ;;
status) status ;;
env) echo "export SLURM_CONF=$dir/slurm.conf" ;;
*) echo "usage: $0 start|stop|status|env" >&2; exit 2 ;;
esac
