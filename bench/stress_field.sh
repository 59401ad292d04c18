#!/usr/bin/env bash
# Stress-field and partial-slip benchmark (issue 3): tribo against tamaas's volume operators.
#
# usage: bench/stress_field.sh [N ...]        (default: 128 256 512)
# environment:
#   SKIP_TAMAAS=1    run tribo only
#   PADDINGS="1 2"   tamaas window multipliers (tamaas is periodic: padding P puts the periodic
#                    images P times farther away; its memory grows like P^2, 7.8 GB at
#                    N = 512, P = 2)
#
# For each N: the full stress tensor on N x N x 20 points (z in [0, 1.5a]) under a circular
# Hertz pressure (tribo-bench-stress, frictionless and with q_x = 0.2 p; tamaas_stress.py),
# with the von Mises error in units of p0 against the closed form (Huber 1904 / Hamilton 1983)
# on the axis; then tribo's partial-slip solve (tribo-bench-slip, Q = 0.5 f P) at N = 256 and
# 512. Prints a markdown table and writes it to bench/results/stress-field-<date>.md.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
venv="$here/.venv"
skip_tamaas="${SKIP_TAMAAS:-0}"
paddings="${PADDINGS:-1 2}"
if [ "$#" -gt 0 ]; then sizes=("$@"); else sizes=(128 256 512); fi
for n in "${sizes[@]}"; do
    if ! [[ "$n" =~ ^[0-9]+$ ]] || [ "$n" -lt 4 ]; then
        echo "stress_field.sh: N must be an integer >= 4, got '$n'" >&2
        exit 2
    fi
done

if [ "$skip_tamaas" != 1 ]; then
    if [ ! -x "$venv/bin/python" ]; then
        python3 -m venv "$venv"
    fi
    if ! "$venv/bin/python" -c 'import tamaas, numpy' 2>/dev/null; then
        "$venv/bin/pip" install --quiet tamaas numpy
    fi
fi
(cd "$root" && cargo build --release --quiet -p tribo-bench)
bin="${CARGO_TARGET_DIR:-$root/target}/release"

load_start="$(cut -d' ' -f1-3 /proc/loadavg)"
out="$here/results/stress-field-$(date +%Y-%m-%d).md"
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
json_field() { python3 -c "import json,sys; d=json.loads(sys.argv[1]); print(d.get(sys.argv[2], ''))" "$1" "$2"; }
fmt() { python3 -c "import sys; v=sys.argv[1]; print(f'{float(v):.3g}' if v else '-')" "$1"; }
mib() { python3 -c "import sys; v=sys.argv[1]; print(f'{float(v)/2**20:.0f}' if v else '-')" "$1"; }

{
    echo "## Stress field, N x N x 20 points, circular Hertz pressure"
    echo
    echo "| N | code | traction | window | s | von Mises error on axis / p0 | peak MiB |"
    echo "|---:|---|---|---|---:|---:|---:|"
    for n in "${sizes[@]}"; do
        for f in 0 0.2; do
            r="$("$bin/tribo-bench-stress" --n "$n" --friction "$f")"
            echo "   $r" >&2
            if [ "$f" = 0 ]; then traction="p"; else traction="p, q_x = $f p"; fi
            echo "| $n | tribo | $traction | exact (non-periodic) | $(fmt "$(json_field "$r" seconds)") | $(fmt "$(json_field "$r" von_mises_error_axis)") | $(mib "$(json_field "$r" peak_rss_bytes)") |"
        done
        if [ "$skip_tamaas" != 1 ]; then
            for pad in $paddings; do
                r="$("$venv/bin/python" "$here/tamaas_stress.py" --n "$n" --padding "$pad" 2>/dev/null)" || r='{}'
                echo "   $r" >&2
                echo "| $n | tamaas $(json_field "$r" version) | p | periodic, padding $pad | $(fmt "$(json_field "$r" seconds)") | $(fmt "$(json_field "$r" von_mises_error_axis)") | $(mib "$(json_field "$r" peak_rss_bytes)") |"
            done
        fi
    done
    echo
    echo "## Partial slip (Cattaneo-Mindlin sphere, Q = 0.5 f P, tolerance 1e-10)"
    echo
    echo "| N | operator s | solve s | iterations | residual | stick radius / a | Cattaneo-Mindlin / a |"
    echo "|---:|---:|---:|---:|---:|---:|---:|"
    for n in 256 512; do
        r="$("$bin/tribo-bench-slip" --n "$n")"
        echo "   $r" >&2
        echo "| $n | $(fmt "$(json_field "$r" operator_seconds)") | $(fmt "$(json_field "$r" seconds)") | $(json_field "$r" iterations) | $(fmt "$(json_field "$r" residual)") | $(fmt "$(json_field "$r" stick_radius_over_a)") | $(fmt "$(json_field "$r" cattaneo_mindlin_over_a)") |"
    done
    echo
    echo "Machine: $(nproc) cores; load average at start $load_start, at end $(cut -d' ' -f1-3 /proc/loadavg)."
    echo "tribo: rayon on all cores; tamaas 2.9.0's PyPI wheel runs on one core."
} | tee "$tmp"
mkdir -p "$here/results"
mv "$tmp" "$out"
trap - EXIT
echo "wrote $out" >&2
