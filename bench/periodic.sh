#!/usr/bin/env bash
# Issue 16's periodic benchmark, side by side: periodic normal contact of a self-affine rough
# surface (Hurst 0.8, rms slope 1, wave numbers 4 to N/4, seed 16; E* = 1, unit window, mean
# pressure 0.1 E*) solved by tamaas 2.9.0's periodic PolonskyKeerRey and by tribo's periodic
# Polonsky-Keer solver on the same surface, one process per code and N.
#
# usage: bench/periodic.sh [N ...]         (default: 256 512 1024 2048 4096)
# environment:
#   TOLERANCE=1e-10     the tolerance given to both solvers (each on its own measure; the
#                       table shows both answers under both measures: bench/README.md)
#   TRIBO_TOLERANCE     tribo's tolerance where it should differ from TOLERANCE (e.g. 3e-11 to
#                       be at least as converged as tamaas under both measures)
#   TAMAAS_MAX_N=1024   tamaas runs for N up to this (above: tribo only; tamaas takes ~45 s at
#                       1024^2 and grows like N^2 log N x its iterations)
#   SKIP_TAMAAS=1       tribo only (the surface is still made by bench/tamaas_periodic.py)
#   REPEAT=1            tribo solves per N (median time)
#   KERNEL=spectral     tribo's periodic kernel: spectral (tamaas's, like with like) or element
#   TRIBO_ARGS=...      more arguments to tribo-bench-periodic (e.g. --no-coarse-start)
#   OMP_NUM_THREADS     passed to tamaas (default 2; the PyPI wheel runs on one core anyway)
#
# Prints the table and writes it to bench/results/periodic-<date>.md (never overwriting).
# Exit 0 when every run succeeded and the pressures agree; 1 otherwise (the table is written
# either way); 2 on bad arguments.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
venv="$here/.venv"
tolerance="${TOLERANCE:-1e-10}"
tribo_tolerance="${TRIBO_TOLERANCE:-$tolerance}"
tamaas_max_n="${TAMAAS_MAX_N:-1024}"
skip_tamaas="${SKIP_TAMAAS:-0}"
repeat="${REPEAT:-1}"
kernel="${KERNEL:-spectral}"
read -r -a tribo_args <<<"${TRIBO_ARGS:-}"
if [ "$#" -gt 0 ]; then sizes=("$@"); else sizes=(256 512 1024 2048 4096); fi
for n in "${sizes[@]}"; do
    if ! [[ "$n" =~ ^[0-9]+$ ]] || [ "$n" -lt 16 ] || [ $((n % 2)) -ne 0 ]; then
        echo "periodic.sh: N must be an even integer >= 16, got '$n'" >&2
        exit 2
    fi
done
if ! [[ "$tamaas_max_n" =~ ^[0-9]+$ ]] || ! [[ "$repeat" =~ ^[1-9][0-9]*$ ]]; then
    echo "periodic.sh: TAMAAS_MAX_N must be an integer and REPEAT an integer >= 1" >&2
    exit 2
fi
case "$kernel" in spectral | element) ;; *)
    echo "periodic.sh: KERNEL must be spectral or element, got '$kernel'" >&2
    exit 2
    ;;
esac

# Python side: a venv with tamaas and numpy (the wheel exists for CPython 3.11 on x86_64).
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import tamaas, numpy' 2>/dev/null; then
    "$venv/bin/pip" install --quiet tamaas numpy
fi
py="$venv/bin/python"

# Rust side.
(cd "$root" && cargo build --release --quiet -p tribo-bench --bin tribo-bench-periodic)
bench_bin="${CARGO_TARGET_DIR:-$root/target}/release/tribo-bench-periodic"

load_start="$(cut -d' ' -f1-3 /proc/loadavg)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
jsonl="$work/results.jsonl"
: >"$jsonl"
failed=0

# One JSON line per run into $jsonl, or an "error" line naming the exit code.
record() { # code n file rc
    if [ -s "$3" ]; then
        tail -n 1 "$3" >>"$jsonl"
    else
        printf '{"code": "%s", "n": %s, "error": "exit code %s (see stderr)"}\n' "$1" "$2" "$4" >>"$jsonl"
    fi
    if [ "$4" -ne 0 ]; then failed=1; fi
}

for n in "${sizes[@]}"; do
    echo "== N = $n" >&2
    surface="$work/surface$n"
    reference=()
    rc=0
    if [ "$skip_tamaas" != 1 ] && [ "$n" -le "$tamaas_max_n" ]; then
        OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}" "$py" "$here/tamaas_periodic.py" --n "$n" \
            --tolerance "$tolerance" --surface-out "$surface" --pressure-out "$work/tamaas$n.bin" \
            >"$work/tamaas$n.json" || rc=$?
        record tamaas-periodic "$n" "$work/tamaas$n.json" "$rc"
        echo "   tamaas (rc $rc): $(tail -n 1 "$work/tamaas$n.json" 2>/dev/null)" >&2
        if [ "$rc" -eq 0 ]; then reference=(--reference "$work/tamaas$n.bin"); fi
    fi
    if [ ! -s "$surface.bin" ]; then
        rc=0
        "$py" "$here/tamaas_periodic.py" --n "$n" --surface-only --surface-out "$surface" >/dev/null || rc=$?
        if [ "$rc" -ne 0 ]; then
            printf '{"code": "tribo-periodic", "n": %s, "error": "the surface could not be made (exit %s)"}\n' "$n" "$rc" >>"$jsonl"
            failed=1
            continue
        fi
    fi
    rm -f "$surface.npy"
    rc=0
    "$bench_bin" --surface "$surface.bin" --n "$n" --tolerance "$tribo_tolerance" --repeat "$repeat" \
        --kernel "$kernel" ${reference[@]+"${reference[@]}"} ${tribo_args[@]+"${tribo_args[@]}"} \
        >"$work/tribo$n.json" || rc=$?
    record tribo-periodic "$n" "$work/tribo$n.json" "$rc"
    echo "   tribo  (rc $rc): $(tail -n 1 "$work/tribo$n.json" 2>/dev/null)" >&2
    rm -f "$surface.bin" "$work/tamaas$n.bin"
done

# The same answer: the pressures agree to 1e-6 of the maximum where both codes ran (tamaas's
# and tribo's answers each within ~1e-8 of the exact discrete solution at tolerance 1e-10,
# crates/tribo/src/validation/tamaas.rs).
if ! "$py" - "$jsonl" <<'PY'; then failed=1; fi
import json, sys
bad = []
for line in open(sys.argv[1]):
    d = json.loads(line)
    ref = (d.get("reference") or {}) if d.get("code") == "tribo-periodic" else {}
    if ref and not ref.get("max_pressure_difference", 1.0) <= 1e-6:
        bad.append(f"N = {d['n']}: max |dp| / max p = {ref.get('max_pressure_difference')}")
for b in bad:
    print("periodic.sh: the pressures differ:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

mkdir -p "$here/results"
out="$here/results/periodic-$(date +%Y-%m-%d).md"
k=2
while [ -e "$out" ]; do # never overwrite an earlier run of the same day
    out="$here/results/periodic-$(date +%Y-%m-%d)-$k.md"
    k=$((k + 1))
done
cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//' || true)"
commit="$(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
tamaas_version="$("$py" -c 'import tamaas; print(tamaas.__version__)' 2>/dev/null || echo -)"
{
    echo "# Periodic rough contact benchmark: tribo vs tamaas, $(date '+%Y-%m-%d %H:%M %Z')"
    echo
    echo "Issue 16's case: a self-affine surface (Hurst 0.8, rms slope 1, wave numbers 4 to N/4 per window,"
    echo "seed 16; bench/tamaas_periodic.py), E* = 1, unit periodic window, mean pressure 0.1 E*, N x N points."
    echo "tribo commit $commit, kernel $kernel${TRIBO_ARGS:+, tribo-bench-periodic $TRIBO_ARGS}; tamaas $tamaas_version (periodic PolonskyKeerRey);"
    echo "tolerance: tamaas $tolerance, tribo $tribo_tolerance (own measures). Machine: $(nproc) cores, $cpu."
    echo "tribo: rayon on all cores, median of $repeat solve(s); tamaas: PyPI wheel, sequential backend (one core)."
    echo "Load average (1, 5, 15 min) at the start: $load_start; at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "(other work on the machine inflates wall times: quote CPU seconds, compare within one run)."
    echo "s: wall seconds of the iteration alone; CPU s: user + system, all threads; FFT pair s: one operator"
    echo "application of tribo (forward + inverse real FFT), the floor of an iteration; ratio = tribo s / tamaas s."
    echo "Residuals: each answer under both stopping measures, computed by tribo-bench-periodic with the same"
    echo "operator: min-map = max |min(p/p_max, g/u_max)| (tribo's), tamaas res. = sum p (g - min_contact g) /"
    echo "(sum p std h) (tamaas's). max|dp|/max p and contact mismatch: tribo's pressure against tamaas's."
    echo
    "$py" "$here/periodic_table.py" "$jsonl"
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
exit "$failed"
