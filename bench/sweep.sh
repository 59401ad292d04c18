#!/usr/bin/env bash
# Study benchmark (issue 15): (1) the per-point overhead of `tribo sweep run` against the bare
# `tribo run` of the same case, both on one thread (a sweep point runs on one thread; the bare
# run with RAYON_NUM_THREADS=1), in CPU seconds (user + sys: the machine is shared, wall times
# are noisy); (2) an N-point study (default 1000) of the paper's 21 x 21 case
# (roller-shaft-normal) over the load, with --jobs J (default 2), wall and CPU time.
#
# usage: bench/sweep.sh            environment: N=1000, JOBS=2, REPEAT=3, BUILD=1, CUT=0, BIG=1
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
n="${N:-1000}"
jobs="${JOBS:-2}"
repeat="${REPEAT:-3}"
if [ "${BUILD:-1}" = 1 ]; then (cd "$root" && cargo build --release --quiet -p tribo-cli); fi
bin="${CARGO_TARGET_DIR:-$root/target}/release/tribo"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cpu() { # command... -> "wall_s cpu_s"
    /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$@" >/dev/null 2>&1
    awk '{printf "%.3f %.3f\n", $1, $2 + $3}' "$tmp/t"
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); cores: $(nproc)"

# (1) overhead: the Sec. 6 roller/shaft (41 x 41, sliding, the 39 x 39 x 20 field, damage,
# its loading study and load cycle: a few CPU seconds); CUT=1 drops the study and the cycle.
if [ "${CUT:-0}" = 1 ]; then
    "$bin" example roller-shaft-sec6 | sed '/^\[damage.study\]/,$d' >"$tmp/case.toml"
else
    "$bin" example roller-shaft-sec6 >"$tmp/case.toml"
fi
echo
echo "| run | outputs | wall (s) | CPU (s) per case |"
echo "|---|---|---:|---:|"
for k in $(seq "$repeat"); do
    read -r w c < <(RAYON_NUM_THREADS=1 cpu "$bin" run "$tmp/case.toml" -o "$tmp/bare$k" -q)
    echo "| bare tribo run (1 thread) | all files | $w | $c |"
done
for outputs in all summary; do
    cat >"$tmp/over-$outputs.toml" <<TOML
[study]
name = "overhead"
base = "case.toml"
outputs = "$outputs"
collect = ["damage.criteria[0].psi_max"]
[[grid]]
key = "contact.load"
values = [$(seq -s, "$repeat" | sed 's/[0-9]*/2000.0/g')]
TOML
    "$bin" sweep plan "$tmp/over-$outputs.toml" -o "$tmp/over-$outputs" >/dev/null
    read -r w c < <(cpu "$bin" sweep run "$tmp/over-$outputs" --jobs 1 -q)
    echo "| sweep run, $repeat points, --jobs 1 | $outputs | $w | $(awk -v c="$c" -v r="$repeat" 'BEGIN{printf "%.3f", c / r}') |"
done

# (2) the N-point study of the 21 x 21 case (BIG=0 skips it).
if [ "${BIG:-1}" = 0 ]; then exit 0; fi
cat >"$tmp/big.toml" <<TOML
[study]
name = "big"
example = "roller-shaft-normal"
collect = ["contact.max_pressure", "contact.contact_area", "contact.approach"]
[[grid]]
key = "contact.load"
from = 500.0
to = 3000.0
points = $n
TOML
echo
read -r w c < <(cpu "$bin" sweep plan "$tmp/big.toml" -o "$tmp/big")
echo "plan: $n points, $w s wall"
read -r w c < <(cpu "$bin" sweep run "$tmp/big" --jobs "$jobs" -q)
echo "run: $n points, --jobs $jobs: $w s wall, $c s CPU ($(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.4f", c / n}') CPU-s per point)"
read -r w c < <(cpu "$bin" sweep gather "$tmp/big")
echo "gather: $w s wall; $(du -k "$tmp/big/results.csv" | cut -f1) KiB csv, $(du -k "$tmp/big/results.nc" | cut -f1) KiB nc, $(du -sk "$tmp/big/points" | cut -f1) KiB of points"
read -r w c < <(RAYON_NUM_THREADS=1 cpu "$bin" run "$tmp/big/points/000500/case.toml" -o "$tmp/one" -q)
echo "one point as a bare tribo run (1 thread): $w s wall, $c s CPU"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
