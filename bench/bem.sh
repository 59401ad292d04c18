#!/usr/bin/env bash
# Dense 2D BEM scaling benchmark: assembly, the N x N LU, the contact condensation and a
# contact load step on the Hertz cylinder-on-block model at about 1000, 2000, 4000 and 8000
# boundary DOF (tribo-bench-bem; each size in a child process for its own peak memory).
#
# usage: bench/bem.sh [N,N,...]        (default: 1000,2000,4000,8000)
# Then the clamp-knife-base example (`tribo example clamp-knife-base`, paper Sec. 7) end to
# end at three contact element sizes (the example's recommended 0.4 mm among them): wall
# time and peak memory of `tribo run` (/usr/bin/time), with the summary's own timings.
# Prints markdown tables and writes them to bench/results/bem-<date>.md. About 60 s on 2
# cores (the 8000-DOF size dominates: 2 GB peak, a 6-10 s LU).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
sizes="${1:-1000,2000,4000,8000}"
if ! [[ "$sizes" =~ ^[0-9]+(,[0-9]+)*$ ]]; then
    echo "bem.sh: sizes must be comma-separated integers, got '$sizes'" >&2
    exit 2
fi
(cd "$root" && cargo build --release --quiet -p tribo-bench --bin tribo-bench-bem -p tribo-cli)
bin="${CARGO_TARGET_DIR:-$root/target}/release"

out="$here/results/bem-$(date +%Y-%m-%d).md"
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT
example_table() {
    local dir size
    dir="$(mktemp -d)"
    echo "## The clamp-knife-base example end to end (steel knife, cast-iron comparison, damage sweep)"
    echo
    echo "| contact element | BEM DOF | contact unknowns | wall s | setup s | steps s | fields s | comparison s | peak MiB |"
    echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    for size in 0.8 0.4 0.2; do
        "$bin/tribo" example clamp-knife-base \
            | sed "s/^contact_element_size = .*/contact_element_size = \"$size mm\"/" > "$dir/case.toml"
        /usr/bin/time -f "%e %M" -o "$dir/time" "$bin/tribo" run "$dir/case.toml" -o "$dir/out" --quiet > /dev/null
        python3 - "$dir/out/summary.json" "$dir/time" "$size" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
wall, kib = open(sys.argv[2]).read().split()
t = s["timings"]
print(f"| {sys.argv[3]} mm | {s['dof']} | {s['contact_unknowns']} | {float(wall):.2f} | "
      f"{t['setup_s']:.2f} | {t['steps_s']:.2f} | {t['fields_s']:.2f} | {t['compare_s']:.2f} | "
      f"{int(kib) / 1024:.0f} |")
PY
        rm -rf "$dir/out"
    done
    rm -rf "$dir"
}

{
    "$bin/tribo-bench-bem" --dof "$sizes"
    echo
    example_table
    echo
    echo "Host: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); run $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$root" && git rev-parse --short HEAD 2>/dev/null || echo '?')."
} | tee "$tmp"
mkdir -p "$here/results"
mv "$tmp" "$out"
trap - EXIT
echo "wrote $out" >&2
