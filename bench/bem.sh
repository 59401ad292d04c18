#!/usr/bin/env bash
# Dense 2D BEM scaling benchmark: assembly, the N x N LU, the contact condensation and a
# contact load step on the Hertz cylinder-on-block model at about 1000, 2000, 4000 and 8000
# boundary DOF (tribo-bench-bem; each size in a child process for its own peak memory).
#
# usage: bench/bem.sh [N,N,...]        (default: 1000,2000,4000,8000)
# Prints a markdown table and writes it to bench/results/bem-<date>.md. About 30 s on 2
# cores (the 8000-DOF size dominates: 2 GB peak, a 6-10 s LU).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
sizes="${1:-1000,2000,4000,8000}"
if ! [[ "$sizes" =~ ^[0-9]+(,[0-9]+)*$ ]]; then
    echo "bem.sh: sizes must be comma-separated integers, got '$sizes'" >&2
    exit 2
fi
(cd "$root" && cargo build --release --quiet -p tribo-bench --bin tribo-bench-bem)
bin="${CARGO_TARGET_DIR:-$root/target}/release"

out="$here/results/bem-$(date +%Y-%m-%d).md"
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
{
    "$bin/tribo-bench-bem" --dof "$sizes"
    echo
    echo "Host: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); run $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo '?')."
} | tee "$tmp"
mkdir -p "$here/results"
mv "$tmp" "$out"
trap - EXIT
echo "wrote $out" >&2
