#!/usr/bin/env bash
# Half-space contact benchmark: tribo against tamaas on the paper's case (docs/theory/HALFSPACE.md section 4),
# one process per code and N, side by side.
#
# usage: bench/halfspace.sh [N ...]        (default: 64 128 256 512 1024)
# environment:
#   TOLERANCE=1e-10   the tolerance given to both solvers (see bench/README.md for how they compare)
#   SKIP_TAMAAS=1     run tribo only
#   REPEAT=3          tribo solves per N (the median time is reported; default 3)
#   TRIBO_ARGS=...    more arguments to tribo-bench (e.g. --no-coarse-start)
#   OMP_NUM_THREADS   passed to tamaas (default 2); the PyPI wheel of tamaas 2.9.0 is built with
#                     its sequential "cpp" backend and statically linked FFTW, so it runs on one
#                     core whatever this says. tribo uses rayon on all cores (RAYON_NUM_THREADS).
#
# Prints the table and writes it to bench/results/halfspace-<date>.md.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
venv="$here/.venv"
tolerance="${TOLERANCE:-1e-10}"
skip_tamaas="${SKIP_TAMAAS:-0}"
repeat="${REPEAT:-3}"
read -r -a tribo_args <<<"${TRIBO_ARGS:-}"
if [ "$#" -gt 0 ]; then sizes=("$@"); else sizes=(64 128 256 512 1024); fi
for n in "${sizes[@]}"; do
    if ! [[ "$n" =~ ^[0-9]+$ ]] || [ "$n" -lt 4 ]; then
        echo "halfspace.sh: N must be an integer >= 4, got '$n'" >&2
        exit 2
    fi
done

# Python side: a venv with tamaas and numpy (the wheel exists for CPython 3.11 on x86_64).
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import tamaas, numpy' 2>/dev/null; then
    "$venv/bin/pip" install --quiet tamaas numpy
fi
py="$venv/bin/python"

# Rust side.
(cd "$root" && cargo build --release --quiet -p tribo-bench)
bench_bin="${CARGO_TARGET_DIR:-$root/target}/release/tribo-bench"

load_start="$(cut -d' ' -f1-3 /proc/loadavg)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
jsonl="$work/results.jsonl"
: >"$jsonl"

for n in "${sizes[@]}"; do
    echo "== N = $n" >&2
    rc=0
    "$bench_bin" --n "$n" --tolerance "$tolerance" --repeat "$repeat" ${tribo_args[@]+"${tribo_args[@]}"} --pressure-out "$work/p$n.bin" >"$work/tribo$n.json" || rc=$?
    if [ -s "$work/tribo$n.json" ]; then
        tail -n 1 "$work/tribo$n.json" >>"$jsonl"
    else
        printf '{"code": "tribo", "n": %s, "error": "exit code %s (crashed, see stderr)"}\n' "$n" "$rc" >>"$jsonl"
    fi
    echo "   tribo  (rc $rc): $(tail -n 1 "$work/tribo$n.json")" >&2
    if [ "$skip_tamaas" != 1 ]; then
        if [ "$rc" -eq 0 ]; then
            # tribo's pressure measured with tamaas's operator: an independent residual and eps_avg.
            "$py" "$here/tamaas_case.py" --n "$n" --evaluate "$work/p$n.bin" >>"$jsonl"
        fi
        rc=0
        OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}" "$py" "$here/tamaas_case.py" --n "$n" --tolerance "$tolerance" \
            >"$work/tamaas$n.json" || rc=$?
        if [ -s "$work/tamaas$n.json" ]; then
            tail -n 1 "$work/tamaas$n.json" >>"$jsonl"
        else
            printf '{"code": "tamaas", "n": %s, "error": "exit code %s"}\n' "$n" "$rc" >>"$jsonl"
        fi
        echo "   tamaas (rc $rc): $(tail -n 1 "$work/tamaas$n.json")" >&2
    fi
done

mkdir -p "$here/results"
out="$here/results/halfspace-$(date +%Y-%m-%d).md"
k=2
while [ -e "$out" ]; do  # never overwrite an earlier run of the same day
    out="$here/results/halfspace-$(date +%Y-%m-%d)-$k.md"
    k=$((k + 1))
done
cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//' || true)"
commit="$(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
tamaas_version="$("$py" -c 'import tamaas; print(tamaas.__version__)' 2>/dev/null || echo -)"
{
    echo "# Half-space benchmark: tribo vs tamaas, $(date '+%Y-%m-%d %H:%M %Z')"
    echo
    echo "Paper's case (docs/theory/HALFSPACE.md section 4): E* = 1.10440e11 Pa, h = 50 x^2 + 60 y^2, F_N = 2000 N,"
    echo "force control, window |x|,|y| <= 1.5a, N x N elements. tribo commit $commit, tamaas $tamaas_version;"
    echo "tolerance $tolerance for both (own definitions; see bench/README.md). Machine: $(nproc) cores, $cpu."
    echo "tribo: rayon on all cores; tamaas: PyPI wheel, sequential backend (one core), OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}."
    echo "Load average (1, 5, 15 min) at the start: $load_start; at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "(other work on the machine inflates the times: compare within one run)."
    echo "tribo: median of $repeat solves${TRIBO_ARGS:+, tribo-bench $TRIBO_ARGS}; cpu_seconds in the raw JSON (user + sys, all threads)."
    echo "Times: wall seconds of the solve alone (tribo's operator construction is apart, \"tribo operator s\"); ratio = tribo s / tamaas s."
    echo "Residuals, each code's answer under both stopping measures: min-map = max |min(p/p_max, g/u_max)|"
    echo "(tribo's); tamaas res. = sum p (g - min_contact g) / (sum p std h) (tamaas's), for tribo's pressure"
    echo "computed with tamaas's operator. eps_avg: paper's eq. 17 against exact Hertz (same p_H in both)."
    echo
    "$py" "$here/table.py" "$jsonl"
    echo
    echo "<details><summary>raw JSON</summary>"
    echo
    echo '```'
    cat "$jsonl"
    echo '```'
    echo
    echo "</details>"
} >"$out"
sed -n '/^| N /,/^$/p' "$out"
echo "written: ${out#"$root"/}"
