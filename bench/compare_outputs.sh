#!/usr/bin/env bash
# Runs every embedded example (and the gmsh example, the fatigue commands, `tribo validate
# --json`) with a tribo binary and writes the outputs into a folder; with `check`, compares
# them byte for byte with a saved folder. summary.json files are compared with their timing
# keys removed (wall times differ from run to run); the PNG files are compared byte for byte
# too (the plots are deterministic).
#
#   bench/compare_outputs.sh save  /tmp/before   [BIN]   # BIN default target/release/tribo
#   bench/compare_outputs.sh check /tmp/before   [BIN]   # exit 1 on any difference
set -u
mode=${1:?usage: compare_outputs.sh save|check DIR [BIN]}
ref=${2:?usage: compare_outputs.sh save|check DIR [BIN]}
bin=${3:-target/release/tribo}
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
case $mode in
  save) dest=$ref ;;
  check) dest=$(mktemp -d /tmp/tribo-compare.XXXXXX) ;;
  *) echo "mode must be save or check" >&2; exit 2 ;;
esac
rm -rf "$dest" && mkdir -p "$dest"

run_case() { # NAME then a command writing into $dest/NAME; records stdout, stderr-less, rc
  local name=$1; shift
  mkdir -p "$dest/$name"
  ( cd "$dest/$name" && "$@" >stdout.txt 2>/dev/null; echo $? >rc.txt )
}

for ex in $("$bin" example | tail -n +2 | awk '{print $1}'); do
  "$bin" example "$ex" >"$dest/$ex.toml"
  if [ "$ex" = fatigue-diagram ]; then
    run_case "$ex" "$bin" fatigue diagram "$dest/$ex.toml" -o out
  else
    run_case "$ex" "$bin" run "$dest/$ex.toml" -o out -q --json
  fi
done
run_case gmsh-hertz-cylinder "$bin" run "$root/crates/tribo-cli/examples/gmsh/hertz-cylinder.toml" -o out -q --json
run_case fatigue-fit "$bin" fatigue fit "$root/crates/tribo-cli/examples/data/woehler-steel.csv" -o out
run_case validate "$bin" validate --json
run_case default-run "$bin" run -o out -q --json

# Timing keys out of every summary.json / stdout JSON (wall times of the stages), and the
# output folder out of the file names in them.
strip() { python3 - "$1" "$dest" <<'PY'
import json, sys
p, dest = sys.argv[1], sys.argv[2] + "/"
try:
    d = json.load(open(p))
except Exception:
    sys.exit(0)
def clean(o, path=()):
    if isinstance(o, dict):
        return {k: clean(v, path + (k,)) for k, v in o.items()
                if not (k in ("time_s", "timings", "solve_s", "setup_s", "steps_s", "fields_s",
                              "damage_s", "comparison_s", "total_s", "seconds")
                        or k.endswith("time_s") or "timing" in k)}
    if isinstance(o, list):
        return [clean(v, path) for v in o]
    if isinstance(o, str):
        return o.replace(dest, "")
    return o
json.dump(clean(d), open(p, "w"), indent=1, sort_keys=True)
PY
}
find "$dest" \( -name '*.json' -o -name stdout.txt \) -print0 | while IFS= read -r -d '' f; do strip "$f"; done

[ "$mode" = save ] && { echo "saved into $dest"; exit 0; }
if diff -r -q "$ref" "$dest"; then
  echo "identical: $(find "$dest" -type f | wc -l) files"
  rm -rf "$dest"
else
  echo "DIFFERENT (new outputs kept in $dest)"; exit 1
fi
