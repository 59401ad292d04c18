#!/usr/bin/env bash
# The README's test command: everything.
#  1. the Rust test suite (`cargo test --release --workspace`: every verification row);
#  2. the Python package as a newcomer installs it: a virtual environment under
#     target/py-venv (made here), `pip install .` (maturin builds the wheel from
#     crates/tribo-py into the workspace's target/), then pytest on tests/python (parity with
#     the `tribo` binary built in step 1, Hertz, arrays, errors, threads, the stress field,
#     damage, fatigue, the example script and notebook).
# Needs the Rust toolchain and CPython >= 3.9 with the venv module; pip fetches maturin, numpy,
# pytest and the optional pandas, xarray and scipy (the sweep table read back as NetCDF-3) and
# dask[distributed] (the Dask example's test; about 6 s more of pip into a venv that has
# pandas) from PyPI (TRIBO_PY_MINIMAL=1 leaves the optional ones out: the tests then take the
# dict paths and the Dask test is skipped). `scripts/test.sh --python` runs step 2 alone.
# The wheel reuses step 1's compiled dependencies (the feature pins in crates/tribo-py/
# Cargo.toml): only pyo3, numpy and tribo-py itself are compiled for it.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" != "--python" ]; then
  echo "== cargo test --release --workspace"
  cargo test --release --workspace
  # target/release/tribo, the binary the parity tests compare with, is built by step 1 (the
  # CLI's integration tests run it), with the features of the whole workspace: a separate
  # `cargo build -p tribo-cli` would build it again with fewer (no dev-dependencies).
else
  cargo build --release -p tribo-cli --quiet
fi

python=${PYTHON:-python3}
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
  echo "== python venv in $venv"
  "$python" -m venv "$venv"
fi
echo "== pip install . (the wheel: maturin, crates/tribo-py)"
start=$(date +%s)
extras="pandas xarray scipy dask[distributed]"
if [ "${TRIBO_PY_MINIMAL:-}" = "1" ]; then extras=""; fi
# shellcheck disable=SC2086
set -f  # no globbing: "dask[distributed]" is a word, not a pattern
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check numpy pytest $extras
set +f
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps .
echo "   installed in $(( $(date +%s) - start )) s"

echo "== pytest tests/python"
TRIBO_BIN="$PWD/target/release/tribo" "$venv/bin/python" -m pytest -q -p no:cacheprovider tests/python
