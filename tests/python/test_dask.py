"""examples/python/dask_sweep.py: tribo.run mapped over cases on a dask.distributed
LocalCluster (processes, 2 workers) gives the numbers of a serial tribo.run bit for bit.
Skipped where dask.distributed or pandas is not installed (TRIBO_PY_MINIMAL=1)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

import tribo

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "python" / "dask_sweep.py"


def test_dask_sweep_equals_serial_runs(tmp_path):
    pytest.importorskip("dask.distributed")
    pytest.importorskip("pandas")
    # Run as a script, as a user runs it: the mapped function is __main__'s, which Dask's
    # cloudpickle sends to the workers by value.
    out = subprocess.run([sys.executable, str(EXAMPLE), "--json", str(tmp_path / "rows.json")],
                         capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    rows = json.loads((tmp_path / "rows.json").read_text())

    sys.path.insert(0, str(EXAMPLE.parent))
    try:
        import dask_sweep
    finally:
        sys.path.remove(str(EXAMPLE.parent))
    serial = [dask_sweep.summarize(c) for c in dask_sweep.cases()]
    assert len(rows) == len(serial) == 8
    # Equal dicts: every float the same double (json round-trips Python floats exactly).
    assert rows == serial
    # The loads: the force of the solved pressure (the sum of p dA, to round-off).
    assert [r["load_N"] for r in rows] == pytest.approx(dask_sweep.LOADS * 2, rel=1e-12)
    # The solutions are Hertz's to the grid's accuracy (48 x 48 over 1.5 contact diameters).
    for r in rows:
        assert r["max_pressure_Pa"] == pytest.approx(r["hertz_p0_Pa"], rel=0.05)
    assert "max_pressure_Pa" in out.stdout  # the DataFrame printed


def test_cases_cross_to_other_processes():
    # What the workers get: a pickled case is the same case (its text, source and folder).
    import pickle

    case = tribo.Case.from_dict({"body1": {"E": 2.1e11, "nu": 0.3, "radii": [0.01, 0.01]},
                                 "body2": {"E": 2.1e11, "nu": 0.3, "radii": ["inf", "inf"]},
                                 "contact": {"load": 10.0}, "grid": {"n": 16}})
    back = pickle.loads(pickle.dumps(case))
    assert back.toml == case.toml
    assert tribo.run(back).summary["contact"] == tribo.run(case).summary["contact"]
