#!/usr/bin/env bash
# The README's test command: everything.
#  1. the Rust test suite (`cargo test --release --workspace`: every verification row);
#  2. the Python package as a newcomer installs it: a virtual environment under
#     target/py-venv (made here), `pip install .` (maturin builds the wheel from
#     crates/tribo-py into the workspace's target/), then pytest on tests/python (parity with
#     the `tribo` binary built in step 1, Hertz, arrays, errors, threads, the example script).
# Needs the Rust toolchain and CPython >= 3.9 with the venv module; pip fetches maturin, numpy
# and pytest from PyPI. `scripts/test.sh --python` runs step 2 alone (after a cargo build).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" != "--python" ]; then
  echo "== cargo test --release --workspace"
  cargo test --release --workspace
fi

# The binary the parity tests compare with (built by step 1; a no-op then).
cargo build --release -p tribo-cli --quiet

python=${PYTHON:-python3}
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
  echo "== python venv in $venv"
  "$python" -m venv "$venv"
fi
echo "== pip install . (the wheel: maturin, crates/tribo-py)"
start=$(date +%s)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check numpy pytest
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps .
echo "   installed in $(( $(date +%s) - start )) s"

echo "== pytest tests/python"
TRIBO_BIN="$PWD/target/release/tribo" "$venv/bin/python" -m pytest -q -p no:cacheprovider tests/python
