"""Shared fixtures of the Python tests: the `tribo` binary for the parity tests."""

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def tribo_bin() -> str:
    """The `tribo` command line: $TRIBO_BIN, else target/release/tribo (built by the README's
    test command before the Python tests), else `tribo` on PATH."""
    for candidate in (os.environ.get("TRIBO_BIN"), str(ROOT / "target" / "release" / "tribo")):
        if candidate and Path(candidate).is_file():
            return candidate
    found = shutil.which("tribo")
    if found is None:
        pytest.fail("no tribo binary: build it with `cargo build --release` or set TRIBO_BIN")
    return found
