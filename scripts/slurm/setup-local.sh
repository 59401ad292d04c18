#!/usr/bin/env bash
# A single-node SLURM on this machine, for testing `tribo sweep slurm --submit` (not for
# production): installs Debian's slurm-wlm and munge (apt-get, as root), writes a one-node
# slurm.conf under $TRIBO_SLURM_DIR (default /tmp/tribo-slurm), starts munged, slurmctld and
# slurmd (their PIDs in $TRIBO_SLURM_DIR/*.pid; teardown-local.sh stops them by PID) and waits
# until `sinfo` shows the node idle. Clients then need `source $TRIBO_SLURM_DIR/env.sh`
# (SLURM_CONF). See docs/user/studies-slurm.md.
#
# Usage: scripts/slurm/setup-local.sh [--no-install] [--prove]
#   --no-install  skip apt-get (the packages are already there)
#   --prove       submit an array job of 3 tasks that each write a file, wait, check them
set -euo pipefail

DIR=${TRIBO_SLURM_DIR:-/tmp/tribo-slurm}
INSTALL=1
PROVE=0
for a in "$@"; do
    case "$a" in
        --no-install) INSTALL=0 ;;
        --prove) PROVE=1 ;;
        *) echo "setup-local.sh: unknown argument '$a'" >&2; exit 2 ;;
    esac
done
t0=$(date +%s)
log() { echo "[setup-local $(( $(date +%s) - t0 ))s] $*"; }

if [ "$(id -u)" != 0 ]; then
    echo "setup-local.sh: must run as root (apt-get, munge key, daemons)" >&2
    exit 2
fi

if [ "$INSTALL" = 1 ] && ! command -v slurmctld >/dev/null; then
    log "installing slurm-wlm and munge (apt-get)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # The packages' own services are not wanted (this script starts the daemons itself):
    # policy-rc.d refuses their start under invoke-rc.d, where there is one.
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi
for b in slurmctld slurmd munged sinfo sbatch squeue scontrol; do
    command -v "$b" >/dev/null || { echo "setup-local.sh: $b not found" >&2; exit 1; }
done

if [ -f "$DIR/slurmctld.pid" ] || [ -f "$DIR/slurmd.pid" ] || [ -f "$DIR/munged.pid" ]; then
    echo "setup-local.sh: $DIR holds PID files of a running setup; run teardown-local.sh first" >&2
    exit 1
fi
mkdir -p "$DIR"/{state,spool,munge}
HOST=$(hostname -s)
CPUS=$(nproc)
MEM_MB=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)

# munge: its own key and socket under $DIR, so that a system munged (if any) is left alone.
KEY="$DIR/munge/munge.key"
if [ ! -f "$KEY" ]; then
    dd if=/dev/urandom of="$KEY" bs=1 count=1024 status=none
    chmod 0400 "$KEY"
fi
SOCK="$DIR/munge/munge.socket"
log "starting munged"
munged --force --key-file="$KEY" --socket="$SOCK" --pid-file="$DIR/munged.pid" \
    --log-file="$DIR/munged.log" --seed-file="$DIR/munge/munged.seed"

cat > "$DIR/slurm.conf" <<CONF
# Written by scripts/slurm/setup-local.sh: one node, for testing.
ClusterName=tribo-local
SlurmctldHost=$HOST(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$SOCK
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
CONF
echo "export SLURM_CONF=$DIR/slurm.conf" > "$DIR/env.sh"
export SLURM_CONF="$DIR/slurm.conf"

log "starting slurmctld and slurmd"
slurmctld -f "$SLURM_CONF" -c   # -c: a clean start (no saved jobs)
slurmd -f "$SLURM_CONF"

# Wait for the node to be idle (60 s at most).
for _ in $(seq 1 60); do
    state=$(sinfo -h -N -n "$HOST" -o '%t' 2>/dev/null || true)
    case "$state" in
        idle) break ;;
    esac
    sleep 1
done
if [ "${state:-}" != idle ]; then
    echo "setup-local.sh: the node is '${state:-unknown}' after 60 s, not idle; logs in $DIR" >&2
    exit 1
fi
log "node $HOST idle ($CPUS CPUs, $MEM_MB MB): source $DIR/env.sh to use it"

if [ "$PROVE" = 1 ]; then
    OUTD="$DIR/prove"
    rm -rf "$OUTD"; mkdir -p "$OUTD"
    jid=$(sbatch --parsable --array=0-2 --output="$OUTD/slurm-%A_%a.out" \
        --wrap="echo task \$SLURM_ARRAY_TASK_ID on \$(hostname) > $OUTD/task-\$SLURM_ARRAY_TASK_ID.txt")
    log "submitted array job $jid (3 tasks)"
    for _ in $(seq 1 120); do
        [ -z "$(squeue -h -j "$jid" 2>/dev/null)" ] && break
        sleep 1
    done
    for i in 0 1 2; do
        if ! grep -q "^task $i on " "$OUTD/task-$i.txt" 2>/dev/null; then
            echo "setup-local.sh: array task $i wrote no file; see $OUTD and $DIR/*.log" >&2
            exit 1
        fi
    done
    log "array job $jid: 3 tasks wrote their files ($OUTD)"
fi
log "done"
