#!/usr/bin/env bash
# The N-point study (default 1000) of the paper's 21 x 21 case (roller-shaft-normal over the
# load, as in bench/sweep.sh) run locally (`tribo sweep run --jobs J`) and through a SLURM
# (`tribo sweep slurm --submit`) with each chunk size in CHUNKS, wall times from the submission
# to the gathered table, and the gathered tables (results.csv, results.nc) compared byte for
# byte with the local run's. Needs a SLURM that answers `sinfo` (scripts/slurm/setup-local.sh
# starts a single-node one; source $TRIBO_SLURM_DIR/env.sh first).
#
# usage: bench/sweep_slurm.sh     environment: N=1000, JOBS=2, CHUNKS="1000 100 1",
#                                 CPUS=1 (--cpus-per-task), TRIBO=target/release/tribo
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
n="${N:-1000}"
jobs="${JOBS:-2}"
chunks="${CHUNKS:-1000 100 1}"
cpus="${CPUS:-1}"
bin="${TRIBO:-$root/target/release/tribo}"
sinfo -h >/dev/null || { echo "sweep_slurm.sh: no SLURM answers sinfo" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); cores: $(nproc); $(sinfo -h -N -o '%N %c CPUs %t')"
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

"$bin" sweep plan "$tmp/big.toml" -o "$tmp/local" >/dev/null
t0=$(now)
"$bin" sweep run "$tmp/local" --jobs "$jobs" -q >/dev/null
"$bin" sweep gather "$tmp/local" >/dev/null
t1=$(now)
echo "local: $n points, --jobs $jobs, run + gather: $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b - a}') s wall"

for k in $chunks; do
    d="$tmp/slurm-$k"
    "$bin" sweep plan "$tmp/big.toml" -o "$d" >/dev/null
    t0=$(now)
    answer=$("$bin" sweep slurm "$d" --submit --chunk "$k" --cpus-per-task "$cpus" --time 00:30:00)
    gid=$(echo "$answer" | sed -n 's/.*gather job \([0-9]*\).*/\1/p')
    # Wait for the gather job (it runs after the whole array) to leave the queue.
    while [ -n "$(squeue -h -j "$gid" 2>/dev/null)" ]; do sleep 0.5; done
    t1=$(now)
    tasks=$(( (n + k - 1) / k ))
    same=identical
    for f in results.csv results.nc; do
        cmp -s "$tmp/local/$f" "$d/$f" || same="DIFFERENT ($f)"
    done
    echo "slurm: chunk $k ($tasks array tasks, --cpus-per-task $cpus): submit to gathered table $(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", b - a}') s wall; tables $same"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
