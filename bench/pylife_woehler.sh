#!/usr/bin/env bash
# Woehler fits: tribo against pyLife on the same data set, side by side.
#
# usage: bench/pylife_woehler.sh [DATA.csv]   (default: crates/tribo-cli/examples/data/woehler-steel.csv)
#
# pyLife (PyPI `pylife`, installed into bench/.venv) fits with Elementary (regression of the
# finite-zone fractures, limit at the run-out/fracture transition) and MaxLikeFull (maximum
# likelihood of all five parameters, default likelihood LikelihoodHighestMixedLevel); tribo
# runs `tribo fatigue fit --json` (E739 regression and maximum likelihood with the same
# likelihood). The pyLife numbers of the default data set are kept, with their provenance,
# in crates/tribo-case/tests/fixtures/pylife_woehler.json, which `cargo test` compares with.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
venv="$here/.venv"
data="${1:-$root/crates/tribo-cli/examples/data/woehler-steel.csv}"
if [ ! -f "$data" ]; then
    echo "pylife_woehler.sh: no data file '$data'" >&2
    exit 2
fi

if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c 'import pylife' 2>/dev/null; then
    "$venv/bin/pip" install --quiet pylife
fi
py="$venv/bin/python"

(cd "$root" && cargo build --release --quiet -p tribo-cli)
tribo="${CARGO_TARGET_DIR:-$root/target}/release/tribo"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$py" "$here/pylife_woehler.py" "$data" >"$work/pylife.json"
"$tribo" fatigue fit "$data" -o "$work/out" --json >"$work/tribo.json"

"$py" - "$work/pylife.json" "$work/tribo.json" <<'PY'
import json, sys
pl = json.load(open(sys.argv[1]))
tr = json.load(open(sys.argv[2]))
print(f"data: {pl['data']}")
print(f"pyLife {pl['pylife_version']} (numpy {pl['numpy_version']}, pandas {pl['pandas_version']}), {pl['date']}")
def row(name, a, b):
    rel = (b - a) / a if a else float("nan")
    print(f"  {name:<22} {a:>16.8g} {b:>16.8g} {rel:>+12.2e}")
print(f"  {'quantity':<22} {'pyLife':>16} {'tribo':>16} {'rel. diff':>12}")
print("Elementary (pyLife) vs E739 regression + transition limit (tribo)")
reg = tr["regression"]
if reg and reg["curve"]:
    c = reg["curve"]
    row("SD, Pa", pl["elementary"]["SD"], c["fatigue_limit"])
    row("k_1 = m", pl["elementary"]["k_1"], c["slope"])
    row("ND, cycles", pl["elementary"]["ND"], c["knee_cycles"])
print("MaxLikeFull (pyLife) vs maximum likelihood (tribo)")
ml = tr["max_likelihood"]
if ml:
    c = ml["curve"]
    p = pl["max_like_full"]
    row("SD, Pa", p["SD"], c["fatigue_limit"])
    row("k_1 = m", p["k_1"], c["slope"])
    row("ND, cycles", p["ND"], c["knee_cycles"])
    row("TN", p["TN"], ml["scatter_cycles"])
    row("TS", p["TS"], ml["scatter_load"])
    row("log-likelihood", p["log_likelihood"], ml["log_likelihood"])
if pl["warnings"]:
    print("pyLife warnings:", *pl["warnings"], sep="\n  ")
PY
