#!/usr/bin/env bash
# Linear dynamic BEM benchmark (issue 13 "Speed"): the cylindrical cavity (ring a = 1 m,
# R = 4 m, outer boundary clamped, sudden pressure on the wall; docs/theory/DYNAMICS.md 3.2)
# with BDF2 convolution quadrature, all M steps at once (M/2 + 1 complex assemblies and LU
# solves), against the number of boundary unknowns N and of steps M: wall time and peak
# memory (VmHWM, each (N, M) in a child process of its own) and the ratio of one frequency
# to the static solve of the same model (no external peer exists for a 2D CQ-BEM). Then the
# cost along the contour at the largest N (five single frequencies) and the contact history
# machinery (CQ weights + CqHistory marching for 100 contact unknowns, M = 1000).
#
# usage: bench/dynamics.sh [N,N,...] [M,M,...] [B] [R]
#        (default: 250,500,1000  250,500,1000  1  1: dt = B l/c2, l the element length;
#        R runs per size, the median reported)
# Prints markdown and writes it to bench/results/dynamics-<date>.md. About 10 min on 2 cores
# (the N = 1000, M = 1000 run dominates).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
sizes="${1:-250,500,1000}"
steps="${2:-250,500,1000}"
cfl="${3:-1}"
repeat="${4:-1}"
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
    echo "## Contact history machinery"
    echo
    "$bin" --history 100,1000
    echo
    echo "Host: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); run $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo '?'); load average at end $(cut -d' ' -f1-3 /proc/loadavg)."
} | tee "$tmp"
mkdir -p "$here/results"
mv "$tmp" "$out"
trap - EXIT
echo "wrote $out" >&2
