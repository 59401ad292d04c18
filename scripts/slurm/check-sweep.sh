#!/usr/bin/env bash
# Runs one study locally (`tribo sweep run`) and through the single-node SLURM
# (`tribo sweep slurm --submit`), gathers both and compares the results tables byte for byte.
# Exit 0 only if every gathered table (results.csv and the columnar file beside it) is
# bit-identical; 1 if they differ or a point failed; 2 on bad usage; 75 if the SLURM jobs
# never started within the wait limit (the machine's SLURM, not the study).
#
# Usage: scripts/slurm/check-sweep.sh STUDY [--jobs N] [--chunk K] [--keep]
#   STUDY   a study file, or the name of one in examples/studies/ (NAME or NAME.toml)
#   --jobs  local parallel points (default: nproc)
#   --chunk points per SLURM array task (default 2)
#   --keep  keep the work directory (printed) instead of removing it
# The tribo binary is $TRIBO (default target/release/tribo). A SLURM that answers `sinfo` is
# used as it is; otherwise setup-local.sh starts one and teardown-local.sh stops it at the end.
# Wait limit for the SLURM jobs: $TRIBO_SLURM_WAIT seconds (default 1800).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
TRIBO=${TRIBO:-$root/target/release/tribo}
JOBS=$(nproc)
CHUNK=2
KEEP=0
STUDY=""
while [ $# -gt 0 ]; do
    case "$1" in
        --jobs) JOBS=$2; shift 2 ;;
        --chunk) CHUNK=$2; shift 2 ;;
        --keep) KEEP=1; shift ;;
        -*) echo "check-sweep.sh: unknown option '$1'" >&2; exit 2 ;;
        *) STUDY=$1; shift ;;
    esac
done
if [ -z "$STUDY" ]; then
    echo "usage: check-sweep.sh STUDY [--jobs N] [--chunk K] [--keep]" >&2
    exit 2
fi
if [ ! -f "$STUDY" ]; then
    name=${STUDY%.toml}
    STUDY="$root/examples/studies/$name.toml"
    [ -f "$STUDY" ] || { echo "check-sweep.sh: no study file '$STUDY'" >&2; exit 2; }
fi
[ -x "$TRIBO" ] || { echo "check-sweep.sh: no tribo binary at $TRIBO (cargo build --release)" >&2; exit 2; }

t0=$(date +%s)
log() { echo "[check-sweep $(( $(date +%s) - t0 ))s] $*"; }
WORK=$(mktemp -d /tmp/tribo-check-sweep.XXXXXX)
started_slurm=0
cleanup() {
    if [ "$started_slurm" = 1 ]; then bash "$here/teardown-local.sh" || true; fi
    if [ "$KEEP" = 0 ]; then rm -rf "$WORK"; else echo "work directory kept: $WORK"; fi
}
trap cleanup EXIT

DIR_SLURM=${TRIBO_SLURM_DIR:-/tmp/tribo-slurm}
if [ -f "$DIR_SLURM/env.sh" ]; then
    # shellcheck disable=SC1091
    source "$DIR_SLURM/env.sh"
fi
if ! sinfo -h >/dev/null 2>&1; then
    log "no SLURM answering: starting the local one"
    bash "$here/setup-local.sh"
    started_slurm=1
    # shellcheck disable=SC1091
    source "$DIR_SLURM/env.sh"
fi

log "planning $STUDY into A (local) and B (SLURM)"
"$TRIBO" sweep plan "$STUDY" -o "$WORK/A"
"$TRIBO" sweep plan "$STUDY" -o "$WORK/B"
cmp "$WORK/A/points.csv" "$WORK/B/points.csv"

log "local run (--jobs $JOBS)"
ta=$(date +%s)
"$TRIBO" sweep run "$WORK/A" --jobs "$JOBS"
ta=$(( $(date +%s) - ta ))

log "SLURM run (--chunk $CHUNK)"
tb=$(date +%s)
partition=$(sinfo -h -o '%R' | head -n 1)
"$TRIBO" sweep slurm "$WORK/B" --submit --partition "$partition" --time 00:30:00 \
    --cpus-per-task 1 --chunk "$CHUNK" | tee "$WORK/submit.txt"
# The local SLURM runs only what this script submitted: wait until its queue is empty.
limit=${TRIBO_SLURM_WAIT:-1800}
ran=0
while [ -n "$(squeue -h 2>/dev/null)" ]; do
    if [ -n "$(squeue -h -t RUNNING 2>/dev/null)" ]; then ran=1; fi
    if [ $(( $(date +%s) - tb )) -gt "$limit" ]; then
        echo "check-sweep.sh: the SLURM jobs did not finish in $limit s" >&2
        squeue >&2 || true
        scancel --user="$(id -un)" >/dev/null 2>&1 || true
        # Never started (a node down, a partition that does not schedule): the machine's
        # SLURM, not the study; exit 75 (EX_TEMPFAIL) so that CI can tell it from a mismatch.
        if [ "$ran" = 0 ]; then exit 75; fi
        exit 1
    fi
    sleep 2
done
tb=$(( $(date +%s) - tb ))

log "status of the SLURM run"
"$TRIBO" sweep status "$WORK/B" | tee "$WORK/status.txt"
if ls "$WORK"/B/points/*.failed >/dev/null 2>&1; then
    echo "check-sweep.sh: failed points in the SLURM run:" >&2
    head -n 5 "$WORK"/B/points/*.failed >&2
    exit 1
fi

log "gathering both"
"$TRIBO" sweep gather "$WORK/A"
"$TRIBO" sweep gather "$WORK/B"
status=0
found=0
for a in "$WORK"/A/results.*; do
    [ -f "$a" ] || continue
    found=1
    b="$WORK/B/$(basename "$a")"
    if cmp "$a" "$b"; then
        log "$(basename "$a"): identical ($(wc -c < "$a") bytes)"
    else
        status=1
    fi
done
if [ "$found" = 0 ]; then
    echo "check-sweep.sh: no results.* table was gathered in $WORK/A" >&2
    exit 1
fi
points=$(( $(wc -l < "$WORK/A/points.csv") - 1 ))
log "$points points: local ${ta}s, SLURM ${tb}s (queue to done)"
if [ "$status" = 0 ]; then
    echo "check-sweep: PASS (local and SLURM tables bit-identical)"
else
    echo "check-sweep: FAIL (the tables differ)"
fi
exit $status
