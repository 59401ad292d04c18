#!/usr/bin/env bash
# Linear dynamic BEM benchmark (issue 13 "Speed"): the cylindrical cavity (ring a = 1 m,
# R = 4 m, outer boundary clamped, sudden pressure on the wall; docs/theory/DYNAMICS.md 3.2)
# with BDF2 convolution quadrature, all M steps at once (M/2 + 1 complex assemblies and LU
# solves), against the number of boundary unknowns N and of steps M: wall time and peak
# memory (VmHWM, each (N, M) in a child process of its own) and the ratio of one frequency
# to the static solve of the same model (no external peer exists for a 2D CQ-BEM). Then the
# cost along the contour at the largest N (five single frequencies) and the contact history
# machinery (CQ weights + CqHistory marching for 100 contact unknowns, M = 1000), and the
# two-body impact of issue 13 (DynamicContact::march: 2000 boundary unknowns, 100 contact
# unknowns, M = 250, 500, 1000 steps; IMPACT_DOF, IMPACT_NC, IMPACT_STEPS override).
# CPU seconds are the process's user + system time (/proc/self/stat): on a shared machine
# they, not the wall time, measure the method.
#
# usage: bench/dynamics.sh [N,N,...] [M,M,...] [B] [R]
#        (default: 250,500,1000  250,500,1000  1  1: dt = B l/c2, l the element length;
#        R runs per size, the median reported)
# Prints markdown and writes it to bench/results/dynamics-<date>.md (a second run of the
# day adds -2, -3, ...). About 15 min on 2 free cores (the N = 1000, M = 1000 cavity and
# the M = 1000 impact dominate).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
sizes="${1:-250,500,1000}"
steps="${2:-250,500,1000}"
cfl="${3:-1}"
repeat="${4:-1}"
# Two-body impact: boundary unknowns, contact unknowns, and the step counts (growth in M).
impact_dof="${IMPACT_DOF:-2000}"
impact_nc="${IMPACT_NC:-100}"
impact_steps="${IMPACT_STEPS:-250 500 1000}"
# Synthetic contact histories (NC,M): growth in M and in NC.
history="${HISTORY:-100,500 100,1000 100,2000 200,1000}"
for v in "$sizes" "$steps"; do
    if ! [[ "$v" =~ ^[0-9]+(,[0-9]+)*$ ]]; then
        echo "dynamics.sh: sizes and steps must be comma-separated integers, got '$v'" >&2
        exit 2
    fi
done
(cd "$root" && cargo build --release --quiet -p tribo-bench --bin tribo-bench-dynamics)
bin="${CARGO_TARGET_DIR:-$root/target}/release/tribo-bench-dynamics"
largest="${sizes##*,}"

out="$here/results/dynamics-$(date +%Y-%m-%d).md"
k=2
while [ -e "$out" ]; do
    out="$here/results/dynamics-$(date +%Y-%m-%d)-$k.md"
    k=$((k + 1))
done
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
{
    echo "Load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo
    "$bin" --dof "$sizes" --steps "$steps" --cfl "$cfl" --repeat "$repeat"
    echo
    echo "## Cost along the BDF2 contour (N = $largest, M = 1000, dt = $cfl l/c2)"
    echo
    echo '```'
    "$bin" --cfl "$cfl" --frequencies "$largest,1000"
    echo '```'
    echo
    echo "## Two-body impact (DynamicContact::march, BDF2, dt = h/c1)"
    echo
    echo "| boundary unknowns | contact unknowns | steps M | weights wall s | weights CPU-s | march wall s | march CPU-s | total CPU-s | peak MiB | load at end |"
    echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    for m in $impact_steps; do
        "$bin" --impact "$impact_dof,$impact_nc,$m" | python3 -c '
import json, sys
r = json.loads(sys.stdin.read())
print("| %d | %d | %d | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %s |" % (r["dof"], r["contact_unknowns"], r["steps"], r["weights_seconds"], r["weights_cpu_seconds"], r["march_seconds"], r["march_cpu_seconds"], r["total_cpu_seconds"], r["peak_rss_bytes"] / 1048576, r["load"]))'
    done
    echo
    echo "## Contact history machinery (synthetic dense map, CqHistory marching O(NC^2 M^2))"
    echo
    for h in $history; do
        "$bin" --history "$h"
    done
    echo
    echo "Host: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); run $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo '?'); load average at end $(cut -d' ' -f1-3 /proc/loadavg)."
} | tee "$tmp"
mkdir -p "$here/results"
mv "$tmp" "$out"
trap - EXIT
echo "wrote $out" >&2
