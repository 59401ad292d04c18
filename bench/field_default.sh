#!/usr/bin/env bash
# Default stress-field path benchmark (issue 11 item 4): `tribo run` on a steel sphere on a flat
# (R = 10 mm, 2000 N) in partial slip (f = 0.3, Q = 300 N), with a uniform [field] on the
# default method ("fft": FFT on the extended contact grid + cubic interpolation), for contact
# grids and field sizes given as N:NX:NZ (default 64:41:41 128:41:41 128:46:48, i.e. up to
# 1.0e5 points on 128 x 128). Prints, for each, the median of REPEAT (default 3) wall times of
# the whole run and of the field stage (summary timings), with the load average before and
# after: the machine is shared and noisy, so read the times with the load; and the median CPU
# time (user + system, all threads) of the run, which the load disturbs less.
#
# EDGE sets `[field] edge_refinement` (e.g. EDGE='"none"' for the bilinear element tractions,
# EDGE='"band"'; unset: the case's default, the band since session 11).
#
# usage: bench/field_default.sh [N:NX:NZ ...]    environment: REPEAT=3, METHOD=fft|direct, EDGE
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
repeat="${REPEAT:-3}"
method="${METHOD:-fft}"
edge="${EDGE:-}"
if [ "$#" -gt 0 ]; then cases=("$@"); else cases=(64:41:41 128:41:41 128:46:48); fi
if [ ! -x "${CARGO_TARGET_DIR:-$root/target}/release/tribo" ] || [ "${BUILD:-1}" = 1 ]; then (cd "$root" && cargo build --release --quiet -p tribo-cli); fi
bin="${CARGO_TARGET_DIR:-$root/target}/release/tribo"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); cores: $(nproc)"
echo "| grid | field points | method | edge_refinement | median run (s) | median field stage (s) | median CPU of the run (s) |"
echo "|---|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
    IFS=: read -r n nx nz <<<"$c"
    cat >"$tmp/case.toml" <<TOML
[body1]
E = 2.1e11
nu = 0.3
radii = [0.01, 0.01]
[body2]
E = 2.1e11
nu = 0.3
radii = ["inf", "inf"]
[contact]
load = 2000.0
friction = 0.3
tangential_load = 300.0
[grid]
n = $n
extent = 1.5
[field]
n = [$nx, $nx, $nz]
extent = 1.5
depth = 1.5
method = "$method"
TOML
    if [ -n "$edge" ]; then echo "edge_refinement = $edge" >>"$tmp/case.toml"; fi
    runs=()
    fields=()
    cpus=()
    for _ in $(seq "$repeat"); do
        start=$(date +%s.%N)
        /usr/bin/time -f "%U %S" -o "$tmp/time" "$bin" run "$tmp/case.toml" -o "$tmp/out" --quiet --json >"$tmp/summary.json"
        end=$(date +%s.%N)
        cpus+=("$(awk '{print $1 + $2}' "$tmp/time")")
        runs+=("$(python3 -c "print($end - $start)")")
        fields+=("$(python3 -c "import json; d = json.load(open('$tmp/summary.json')); print(d['stress']['time_s'])")")
    done
    med() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
    echo "| $n x $n | $((nx * nx * nz)) | $method | ${edge:-default} | $(med "${runs[@]}") | $(med "${fields[@]}") | $(med "${cpus[@]}") |"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
