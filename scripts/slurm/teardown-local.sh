#!/usr/bin/env bash
# Stops the daemons that setup-local.sh started, by the PIDs it recorded (slurmd, slurmctld,
# munged, in that order), and removes their PID files. Leaves the packages installed and the
# logs in $TRIBO_SLURM_DIR (default /tmp/tribo-slurm); --purge removes that directory too.
set -uo pipefail
DIR=${TRIBO_SLURM_DIR:-/tmp/tribo-slurm}
status=0
for d in slurmd slurmctld munged; do
    f="$DIR/$d.pid"
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
        kill -TERM "$pid"
        for _ in $(seq 1 50); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.2
        done
        if kill -0 "$pid" 2>/dev/null; then
            echo "teardown-local.sh: $d ($pid) did not stop on TERM; sending KILL" >&2
            kill -KILL "$pid" 2>/dev/null || status=1
        fi
        echo "stopped $d ($pid)"
    fi
    rm -f "$f"
done
if [ "${1:-}" = --purge ]; then
    rm -rf "$DIR"
fi
exit $status
